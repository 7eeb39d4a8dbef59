//! The DDS side's set-up: the participant (discovery kept on this host unless asked otherwise)
//! and the node's endpoints ([`super::endpoints::ENDPOINTS`]) under the remap rules: those the
//! executor serves (input topics, services, `/diagnostics`) and those the publisher thread
//! writes the tick loop's states to.

use super::args;
use super::args::DEFAULT_NODE_NAME;
use super::clock::ClockMode;
use super::endpoints::{spec_of, Direction, Endpoint, Endpoint as E, Names, Qos, When, ENDPOINTS};
use super::logging::Logger;
use super::setup::Setup;
use muscle_actuator_core::sim::input;
use muscle_actuator_recording::msgs::muscle_actuator_msgs::{
    ActivationCommand, ActuatorState, ExternalLoad,
};
use muscle_actuator_recording::msgs::{
    Clock, DiagnosticArray, Float64, Float64MultiArray, Int64, JointState, StepRequest,
    StepResponse, TriggerRequest, TriggerResponse,
};
use ros2_client::qos::{Durability, History, Reliability, WhenFull};
use ros2_client::service::Server;
use ros2_client::{
    Context, MessageTypeName, Name, Node, Publisher, QosProfile, ServiceMapping, ServiceTypeName,
    Subscription,
};
use rustdds::DomainParticipantBuilder;
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::net::{IpAddr, Ipv4Addr};

/// Highest valid `ROS_DOMAIN_ID` (as rmw implementations accept with default ports).
const MAX_DOMAIN_ID: u16 = 232;

/// Why the node cannot join DDS. A DDS library's own error is quoted as it prints itself
/// (`{:?}`), as the `reason` of the step that failed.
#[derive(Debug, thiserror::Error)]
pub enum DdsError {
    /// `ROS_DOMAIN_ID` is not an integer from 0 to `max`.
    #[error("ROS_DOMAIN_ID={value:?} is invalid: expected an integer from 0 to {max}")]
    DomainId {
        /// The variable's value.
        value: String,
        /// The highest valid domain.
        max: u16,
    },
    /// The DDS participant cannot be created.
    #[error("cannot create the DDS participant (domain {domain}): {reason}")]
    Participant {
        /// The domain.
        domain: u16,
        /// The library's error.
        reason: String,
    },
    /// The ROS 2 context cannot be created on the participant.
    #[error("cannot create the ROS 2 context: {reason}")]
    Context {
        /// The library's error.
        reason: String,
    },
    /// A resolved topic or service name the library refuses.
    #[error("invalid name {name:?}: {reason}")]
    InvalidName {
        /// The resolved name.
        name: String,
        /// The library's error.
        reason: String,
    },
    /// A topic cannot be created.
    #[error("cannot create topic {name}: {reason}")]
    Topic {
        /// The resolved name.
        name: String,
        /// The library's error.
        reason: String,
    },
    /// A subscription cannot be created.
    #[error("cannot subscribe to {topic}: {reason}")]
    Subscribe {
        /// The resolved topic.
        topic: String,
        /// The library's error.
        reason: String,
    },
    /// A publisher cannot be created.
    #[error("cannot publish {topic}: {reason}")]
    Publish {
        /// The resolved topic.
        topic: String,
        /// The library's error.
        reason: String,
    },
    /// A service server cannot be created.
    #[error("cannot create service {name}: {reason}")]
    Service {
        /// The resolved name.
        name: String,
        /// The library's error.
        reason: String,
    },
    /// An endpoint the node always has was not made (a bug of the endpoints' table).
    #[error("internal error: endpoint {endpoint} was not made")]
    NotMade {
        /// The endpoint, as `{:?}` prints it.
        endpoint: String,
    },
    /// The node's namespace and name the library refuses.
    #[error("invalid node name {fqn}: {reason}")]
    NodeName {
        /// The fully qualified name.
        fqn: String,
        /// The library's error.
        reason: String,
    },
    /// The node cannot be created.
    #[error("cannot create node {fqn}: {reason}")]
    Node {
        /// The fully qualified name.
        fqn: String,
        /// The library's error.
        reason: String,
    },
    /// The node's spinner cannot start.
    #[error("cannot start the node's spinner: {reason}")]
    Spinner {
        /// The library's error.
        reason: String,
    },
}

/// The DDS domain from `ROS_DOMAIN_ID` (default 0).
pub fn domain_id_from_env() -> Result<u16, DdsError> {
    match std::env::var("ROS_DOMAIN_ID") {
        Err(_) => Ok(0),
        Ok(s) if s.trim().is_empty() => Ok(0),
        Ok(s) => match s.trim().parse::<u16>() {
            Ok(d) if d <= MAX_DOMAIN_ID => Ok(d),
            _ => Err(DdsError::DomainId {
                value: s,
                max: MAX_DOMAIN_ID,
            }),
        },
    }
}

/// Whether discovery must stay on this host: yes unless `ROS_AUTOMATIC_DISCOVERY_RANGE=SUBNET`
/// (`LOCALHOST`, `OFF`, unset, and `ROS_LOCALHOST_ONLY=1` all keep it local).
pub fn discovery_is_local() -> bool {
    !matches!(
        std::env::var("ROS_AUTOMATIC_DISCOVERY_RANGE")
            .map(|s| s.trim().to_ascii_uppercase())
            .as_deref(),
        Ok("SUBNET")
    )
}

/// The ROS 2 context on a participant of domain `ROS_DOMAIN_ID`.
pub(crate) struct Dds {
    pub(crate) context: Context,
    pub(crate) domain: u16,
    /// Discovery kept on this host.
    pub(crate) local: bool,
}

impl Dds {
    /// Unless SUBNET, discovery stays on this host: only 127.0.0.1 is announced and every UDP
    /// socket is bound to it (rustdds binds 0.0.0.0 otherwise, open to any host), so there is no
    /// multicast listener and discovery is unicast on loopback.
    pub(crate) fn start() -> Result<Self, DdsError> {
        let domain = domain_id_from_env()?;
        let local = discovery_is_local();
        let mut builder = DomainParticipantBuilder::new(domain);
        if local {
            builder = builder
                .with_only_networks([IpAddr::V4(Ipv4Addr::LOCALHOST)])
                .with_bind_address(Ipv4Addr::LOCALHOST);
        }
        let participant = builder.build().map_err(|e| DdsError::Participant {
            domain,
            reason: format!("{e:?}"),
        })?;
        let context =
            Context::from_domain_participant(participant).map_err(|e| DdsError::Context {
                reason: format!("{e:?}"),
            })?;
        Ok(Self {
            context,
            domain,
            local,
        })
    }
}

/// Reliable, volatile, keep last `depth`: every endpoint of the node.
pub(crate) fn qos_reliable(depth: usize) -> QosProfile {
    QosProfile::publisher_default()
        .reliability_reliable(WhenFull::DEFAULT)
        .durability(Durability::Volatile)
        .history(History::KeepLast { depth })
}

/// The QoS profile of `qos` (docs/ros-interface.md): best effort as rclpy's time source
/// subscribes to `/clock` (a best-effort reader takes reliable and best-effort writers alike).
fn profile(qos: Qos) -> QosProfile {
    match qos {
        Qos::Reliable => qos_reliable(10),
        Qos::BestEffort { depth } => QosProfile::publisher_default()
            .reliability(Reliability::BestEffort)
            .durability(Durability::Volatile)
            .history(History::KeepLast { depth }),
    }
}

fn dds_name(resolved: &str) -> Result<Name, DdsError> {
    Name::parse(resolved).map_err(|e| DdsError::InvalidName {
        name: resolved.to_string(),
        reason: format!("{e:?}"),
    })
}

/// The node's topics and services.
pub(crate) struct Endpoints {
    pub(crate) served: Served,
    pub(crate) published: Published,
    pub(crate) names: Names,
}

/// What the executor serves: the inputs, the services and `/diagnostics`.
pub(crate) struct Served {
    pub(crate) activation: Subscription<ActivationCommand>,
    pub(crate) activation_array: Subscription<Float64MultiArray>,
    /// `~/<muscle>/cmd_activation`: (muscle, subscription).
    pub(crate) muscle_commands: Vec<(String, Subscription<Float64>)>,
    pub(crate) load: Subscription<ExternalLoad>,
    pub(crate) diagnostics: Publisher<DiagnosticArray>,
    pub(crate) reset: Server<TriggerRequest, TriggerResponse>,
    /// `~/step`, the service and the fire-and-forget topic (answered in every clock mode).
    pub(crate) step: Server<StepRequest, StepResponse>,
    pub(crate) step_topic: Subscription<Int64>,
    /// `/clock` to follow (`use_sim_time` with `clock` wall).
    pub(crate) clock_in: Option<Subscription<Clock>>,
    /// With driven joints: their motion in.
    pub(crate) joint_states_in: Option<Subscription<JointState>>,
}

/// What the publisher thread writes the tick loop's states and times to.
pub(crate) struct Published {
    pub(crate) state: Publisher<ActuatorState>,
    pub(crate) joint_states: Publisher<JointState>,
    /// `/clock`, with a simulated clock.
    pub(crate) clock: Option<Publisher<Clock>>,
    /// With driven joints: the muscles' torque on them.
    pub(crate) joint_efforts: Option<Publisher<Float64MultiArray>>,
}

/// Creates the table's endpoints ([`ENDPOINTS`]) on one node under the set-up's namespace, name
/// and remap rules, noting each name made.
struct Maker<'a> {
    node: &'a mut Node,
    setup: &'a Setup,
    clock_mode: ClockMode,
    driven_joints: bool,
    names: Names,
}

impl Maker<'_> {
    fn resolve(&self, name: &str) -> String {
        let s = self.setup;
        args::resolve(
            name,
            &s.namespace,
            &s.name,
            DEFAULT_NODE_NAME,
            &s.ros_args.remaps,
        )
    }

    /// Whether this node has `when`'s endpoints.
    fn has(&self, when: When) -> bool {
        match when {
            When::Always | When::Library => true,
            When::DrivenJoints => self.driven_joints,
            When::PublishesClock => self.clock_mode.publishes_clock(),
            When::FollowsClock => self.clock_mode == ClockMode::Follow,
        }
    }

    /// The topic of `e` (its `k`-th instance, named `relative`), resolved and noted.
    fn topic(
        &mut self,
        e: Endpoint,
        k: usize,
        relative: &str,
    ) -> Result<(rustdds::Topic, String, QosProfile), DdsError> {
        let spec = spec_of(e);
        let resolved = self.resolve(relative);
        let (pkg, ty) = spec.package_and_type();
        let qos = profile(spec.qos);
        let t = self
            .node
            .create_topic(&dds_name(&resolved)?, MessageTypeName::new(pkg, ty), &qos)
            .map_err(|e| DdsError::Topic {
                name: resolved.clone(),
                reason: format!("{e:?}"),
            })?;
        self.names.add(e, k, resolved.clone());
        Ok((t, resolved, qos))
    }

    /// A subscription to `e`, if this node has it.
    fn subscribe<M: 'static + DeserializeOwned>(
        &mut self,
        e: Endpoint,
    ) -> Result<Option<Subscription<M>>, DdsError> {
        if !self.has(spec_of(e).when) {
            return Ok(None);
        }
        self.subscribe_as(e, 0, spec_of(e).name).map(Some)
    }

    fn subscribe_as<M: 'static + DeserializeOwned>(
        &mut self,
        e: Endpoint,
        k: usize,
        relative: &str,
    ) -> Result<Subscription<M>, DdsError> {
        let (t, resolved, qos) = self.topic(e, k, relative)?;
        self.node
            .create_subscription::<M>(&t, Some(qos))
            .map_err(|e| DdsError::Subscribe {
                topic: resolved,
                reason: format!("{e:?}"),
            })
    }

    /// A publisher of `e`, if this node has it.
    fn publish<M: Serialize>(&mut self, e: Endpoint) -> Result<Option<Publisher<M>>, DdsError> {
        if !self.has(spec_of(e).when) {
            return Ok(None);
        }
        let (t, resolved, qos) = self.topic(e, 0, spec_of(e).name)?;
        self.node
            .create_publisher::<M>(&t, Some(qos))
            .map(Some)
            .map_err(|e| DdsError::Publish {
                topic: resolved,
                reason: format!("{e:?}"),
            })
    }

    /// The server of `e`.
    fn serve<Req, Resp>(&mut self, e: Endpoint) -> Result<Server<Req, Resp>, DdsError>
    where
        Req: 'static + ros2_client::Message + Clone,
        Resp: 'static + ros2_client::Message,
    {
        let spec = spec_of(e);
        let resolved = self.resolve(spec.name);
        let (pkg, ty) = spec.package_and_type();
        let qos = profile(spec.qos);
        let server = self
            .node
            .create_server::<Req, Resp>(
                ServiceMapping::Enhanced,
                &dds_name(&resolved)?,
                &ServiceTypeName::new(pkg, ty),
                qos.clone(),
                qos,
            )
            .map_err(|e| DdsError::Service {
                name: resolved.clone(),
                reason: format!("{e:?}"),
            })?;
        self.names.add(e, 0, resolved);
        Ok(server)
    }

    /// Notes the endpoints made elsewhere: by the client library (`/rosout`) and the
    /// recording's own (`~/applied/...`, named under the node, never remapped).
    fn note_unmade(&mut self) {
        for s in ENDPOINTS {
            if !self.has(s.when) {
                continue;
            }
            if s.direction == Direction::Recorded {
                let name = args::expand(s.name, &self.setup.namespace, &self.setup.name);
                self.names.add(s.endpoint, 0, name);
            } else if s.when == When::Library {
                self.names.add(s.endpoint, 0, s.name.to_string());
            }
        }
    }
}

/// Every `Some` of a table entry the node always has.
fn always<T>(e: Endpoint, made: Option<T>) -> Result<T, DdsError> {
    made.ok_or_else(|| DdsError::NotMade {
        endpoint: format!("{e:?}"),
    })
}

impl Endpoints {
    /// Every endpoint of [`ENDPOINTS`] this node has; one `~/<muscle>/cmd_activation` per
    /// muscle of `muscles` whose name makes a valid topic name (the others are warned about).
    pub(crate) fn create(
        node: &mut Node,
        setup: &Setup,
        muscles: &[String],
        clock_mode: ClockMode,
        driven_joints: bool,
        logger: &Logger,
    ) -> Result<Self, DdsError> {
        let mut m = Maker {
            node,
            setup,
            clock_mode,
            driven_joints,
            names: Names::default(),
        };
        let activation = always(E::Activation, m.subscribe(E::Activation)?)?;
        let activation_array = always(E::ActivationArray, m.subscribe(E::ActivationArray)?)?;
        let mut muscle_commands = Vec::new();
        let template = spec_of(E::MuscleCommand).name;
        for muscle in muscles {
            let rel = template.replace("<muscle>", muscle);
            if let Err(e) = args::check_name(&rel) {
                logger.warn(&format!(
                    "no {template} topic for muscle {}: not a valid name ({e})",
                    input::quote(muscle)
                ));
                continue;
            }
            let sub = m.subscribe_as(E::MuscleCommand, muscle_commands.len(), &rel)?;
            muscle_commands.push((muscle.clone(), sub));
        }
        let load = always(E::Load, m.subscribe(E::Load)?)?;
        let state = always(E::State, m.publish(E::State)?)?;
        let joint_states = always(E::JointStates, m.publish(E::JointStates)?)?;
        let diagnostics = always(E::Diagnostics, m.publish(E::Diagnostics)?)?;
        let reset = m.serve(E::Reset)?;
        let step = m.serve(E::Step)?;
        let step_topic = always(E::StepTopic, m.subscribe(E::StepTopic)?)?;
        let joint_states_in = m.subscribe(E::JointStatesIn)?;
        let joint_efforts = m.publish(E::JointEfforts)?;
        let clock = m.publish(E::ClockOut)?;
        let clock_in = m.subscribe(E::ClockIn)?;
        m.note_unmade();
        Ok(Self {
            served: Served {
                activation,
                activation_array,
                muscle_commands,
                load,
                diagnostics,
                reset,
                step,
                step_topic,
                clock_in,
                joint_states_in,
            },
            published: Published {
                state,
                joint_states,
                clock,
                joint_efforts,
            },
            names: m.names,
        })
    }
}
