//! The DDS side's set-up: the participant (discovery kept on this host unless asked otherwise)
//! and the node's endpoints ([`super::endpoints::ENDPOINTS`]) under the remap rules, each made
//! from its row: the executor serves the inputs (with their handlers), the services and
//! `/diagnostics`; the publisher thread writes the outputs (with their producers).

use super::args;
use super::args::DEFAULT_NODE_NAME;
use super::clock::ClockMode;
use super::endpoints::{spec_of, Direction, Endpoint, Endpoint as E, Names, Qos, When, ENDPOINTS};
use super::inputs::{InputHandler, Subscribed};
use super::logging::Logger;
use super::outputs::{Emitter, OutputProducer};
use super::roles::{role, Role};
use super::setup::Setup;
use muscle_actuator_core::sim::input;
use muscle_actuator_recording::msgs::{
    DiagnosticArray, StepRequest, StepResponse, TriggerRequest, TriggerResponse,
};
use ros2_client::qos::{Durability, History, Reliability, WhenFull};
use ros2_client::service::Server;
use ros2_client::{
    Context, MessageTypeName, Name, Node, Publisher, QosProfile, ServiceMapping, ServiceTypeName,
};
use rustdds::DomainParticipantBuilder;
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
    /// What the publisher thread writes the tick loop's states and times to, in the table's
    /// order.
    pub(crate) published: Vec<Box<dyn Emitter>>,
    pub(crate) names: Names,
}

/// What the executor serves: the inputs, the services and `/diagnostics`.
pub(crate) struct Served {
    /// Every input topic's subscription, in the table's order.
    pub(crate) inputs: Vec<Box<dyn Subscribed>>,
    /// The muscle of each `~/<muscle>/...` instance, in order.
    pub(crate) muscle_topics: Vec<String>,
    pub(crate) diagnostics: Publisher<DiagnosticArray>,
    pub(crate) reset: Server<TriggerRequest, TriggerResponse>,
    pub(crate) step: Server<StepRequest, StepResponse>,
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

    /// The subscription of the `k`-th instance of input `e`, named `relative`.
    fn subscribe(
        &mut self,
        handler: &'static dyn InputHandler,
        e: Endpoint,
        k: usize,
        relative: &str,
    ) -> Result<Box<dyn Subscribed>, DdsError> {
        let (t, resolved, qos) = self.topic(e, k, relative)?;
        handler
            .subscribe(self.node, &t, qos, e, k)
            .map_err(|reason| DdsError::Subscribe {
                topic: resolved,
                reason,
            })
    }

    /// The publisher of output `e`.
    fn publish(
        &mut self,
        producer: &'static dyn OutputProducer,
        e: Endpoint,
    ) -> Result<Box<dyn Emitter>, DdsError> {
        let (t, resolved, qos) = self.topic(e, 0, spec_of(e).name)?;
        producer
            .publisher(self.node, &t, qos, e)
            .map_err(|reason| DdsError::Publish {
                topic: resolved,
                reason,
            })
    }

    /// A publisher of `e`, whose messages its own code makes.
    fn publish_own<M: Serialize>(&mut self, e: Endpoint) -> Result<Publisher<M>, DdsError> {
        let (t, resolved, qos) = self.topic(e, 0, spec_of(e).name)?;
        self.node
            .create_publisher::<M>(&t, Some(qos))
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

    /// The subscriptions of input `e`: one, or one per muscle whose name makes a valid topic
    /// name when its name holds `<muscle>` (the others are warned about).
    fn subscribe_all(
        &mut self,
        handler: &'static dyn InputHandler,
        e: Endpoint,
        muscles: &[String],
        logger: &Logger,
        served: &mut Served,
    ) -> Result<(), DdsError> {
        let template = spec_of(e).name;
        if !template.contains(MUSCLE) {
            served.inputs.push(self.subscribe(handler, e, 0, template)?);
            return Ok(());
        }
        let mut k = 0;
        for muscle in muscles {
            let rel = template.replace(MUSCLE, muscle);
            if let Err(why) = args::check_name(&rel) {
                logger.warn(&format!(
                    "no {template} topic for muscle {}: not a valid name ({why})",
                    input::quote(muscle)
                ));
                continue;
            }
            served.inputs.push(self.subscribe(handler, e, k, &rel)?);
            if served.muscle_topics.len() == k {
                served.muscle_topics.push(muscle.clone());
            }
            k += 1;
        }
        Ok(())
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

/// What a per-muscle endpoint's name holds in place of each muscle's name.
const MUSCLE: &str = "<muscle>";

impl Endpoints {
    /// Every endpoint of [`ENDPOINTS`] this node has: inputs subscribed with their handlers,
    /// outputs published with their producers, then `/diagnostics` and the services.
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
        let mut inputs = Served {
            inputs: Vec::new(),
            muscle_topics: Vec::new(),
            diagnostics: m.publish_own(E::Diagnostics)?,
            reset: m.serve(E::Reset)?,
            step: m.serve(E::Step)?,
        };
        let mut published = Vec::new();
        for s in ENDPOINTS {
            if !m.has(s.when) {
                continue;
            }
            match role(s.endpoint) {
                Role::Input(h) => m.subscribe_all(h, s.endpoint, muscles, logger, &mut inputs)?,
                Role::Output(p) => published.push(m.publish(p, s.endpoint)?),
                Role::Own => {}
            }
        }
        m.note_unmade();
        Ok(Self {
            served: inputs,
            published,
            names: m.names,
        })
    }
}
