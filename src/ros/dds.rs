//! The DDS side's set-up: the participant (discovery kept on this host unless asked otherwise)
//! and the node's endpoints under the remap rules: those the executor serves (input topics,
//! services, `/diagnostics`) and those the publisher thread writes the tick loop's states to.

use super::args;
use super::args::DEFAULT_NODE_NAME;
use super::clock::ClockMode;
use super::logging::Logger;
use super::setup::Setup;
use crate::msgs::muscle_actuator_msgs::{ActivationCommand, ActuatorState, ExternalLoad};
use crate::msgs::{
    Clock, DiagnosticArray, Float64, Float64MultiArray, Int64, JointState, StepRequest,
    StepResponse, TriggerRequest, TriggerResponse,
};
use crate::sim::input;
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

/// The DDS domain from `ROS_DOMAIN_ID` (default 0).
pub fn domain_id_from_env() -> Result<u16, String> {
    match std::env::var("ROS_DOMAIN_ID") {
        Err(_) => Ok(0),
        Ok(s) if s.trim().is_empty() => Ok(0),
        Ok(s) => match s.trim().parse::<u16>() {
            Ok(d) if d <= MAX_DOMAIN_ID => Ok(d),
            _ => Err(format!(
                "ROS_DOMAIN_ID={s:?} is invalid: expected an integer from 0 to {MAX_DOMAIN_ID}"
            )),
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
    pub(crate) fn start() -> Result<Self, String> {
        let domain = domain_id_from_env()?;
        let local = discovery_is_local();
        let mut builder = DomainParticipantBuilder::new(domain);
        if local {
            builder = builder
                .with_only_networks([IpAddr::V4(Ipv4Addr::LOCALHOST)])
                .with_bind_address(Ipv4Addr::LOCALHOST);
        }
        let participant = builder
            .build()
            .map_err(|e| format!("cannot create the DDS participant (domain {domain}): {e:?}"))?;
        let context = Context::from_domain_participant(participant)
            .map_err(|e| format!("cannot create the ROS 2 context: {e:?}"))?;
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

/// `/clock` as rclpy's time source subscribes to it: best effort, keep last `depth` (1 to
/// publish; more to follow, so that a jump back between two looks is still seen). A best-effort
/// reader takes reliable and best-effort writers alike.
fn qos_clock(depth: usize) -> QosProfile {
    QosProfile::publisher_default()
        .reliability(Reliability::BestEffort)
        .durability(Durability::Volatile)
        .history(History::KeepLast { depth })
}

fn dds_name(resolved: &str) -> Result<Name, String> {
    Name::parse(resolved).map_err(|e| format!("invalid name {resolved:?}: {e:?}"))
}

/// The resolved names of the node's endpoints.
#[derive(Debug, Clone, Default)]
pub(crate) struct EndpointNames {
    pub(crate) activation: String,
    pub(crate) activation_array: String,
    /// One per muscle topic opened, in order.
    pub(crate) muscle_commands: Vec<String>,
    pub(crate) load: String,
    pub(crate) state: String,
    pub(crate) joint_states: String,
    pub(crate) reset: String,
    pub(crate) step: String,
    /// `~/joint_states_in` and `~/joint_efforts`, with driven joints.
    pub(crate) driven: Option<(String, String)>,
}

/// The node's topics and services.
pub(crate) struct Endpoints {
    pub(crate) served: Served,
    pub(crate) published: Published,
    pub(crate) names: EndpointNames,
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

/// Creates endpoints on one node under the set-up's namespace, name and remap rules.
struct Maker<'a> {
    node: &'a mut Node,
    setup: &'a Setup,
    qos: QosProfile,
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

    fn topic(&self, name: &str, ty: (&str, &str)) -> Result<(rustdds::Topic, String), String> {
        let resolved = self.resolve(name);
        let t = self
            .node
            .create_topic(
                &dds_name(&resolved)?,
                MessageTypeName::new(ty.0, ty.1),
                &self.qos,
            )
            .map_err(|e| format!("cannot create topic {resolved}: {e:?}"))?;
        Ok((t, resolved))
    }

    fn subscribe<M: 'static + DeserializeOwned>(
        &mut self,
        name: &str,
        ty: (&str, &str),
    ) -> Result<(Subscription<M>, String), String> {
        self.subscribe_with(name, ty, self.qos.clone())
    }

    fn subscribe_with<M: 'static + DeserializeOwned>(
        &mut self,
        name: &str,
        ty: (&str, &str),
        qos: QosProfile,
    ) -> Result<(Subscription<M>, String), String> {
        let (t, resolved) = self.topic(name, ty)?;
        let sub = self
            .node
            .create_subscription::<M>(&t, Some(qos))
            .map_err(|e| format!("cannot subscribe to {resolved}: {e:?}"))?;
        Ok((sub, resolved))
    }

    fn publish<M: Serialize>(
        &mut self,
        name: &str,
        ty: (&str, &str),
    ) -> Result<(Publisher<M>, String), String> {
        self.publish_with(name, ty, self.qos.clone())
    }

    fn publish_with<M: Serialize>(
        &mut self,
        name: &str,
        ty: (&str, &str),
        qos: QosProfile,
    ) -> Result<(Publisher<M>, String), String> {
        let (t, resolved) = self.topic(name, ty)?;
        let p = self
            .node
            .create_publisher::<M>(&t, Some(qos))
            .map_err(|e| format!("cannot publish {resolved}: {e:?}"))?;
        Ok((p, resolved))
    }

    fn serve<Req, Resp>(
        &mut self,
        name: &str,
        ty: (&str, &str),
    ) -> Result<(Server<Req, Resp>, String), String>
    where
        Req: 'static + ros2_client::Message + Clone,
        Resp: 'static + ros2_client::Message,
    {
        let resolved = self.resolve(name);
        let server = self
            .node
            .create_server::<Req, Resp>(
                ServiceMapping::Enhanced,
                &dds_name(&resolved)?,
                &ServiceTypeName::new(ty.0, ty.1),
                self.qos.clone(),
                self.qos.clone(),
            )
            .map_err(|e| format!("cannot create service {resolved}: {e:?}"))?;
        Ok((server, resolved))
    }
}

impl Endpoints {
    /// Every endpoint; one `~/<muscle>/cmd_activation` per muscle of `muscles` whose name makes
    /// a valid topic name (the others are warned about).
    pub(crate) fn create(
        node: &mut Node,
        setup: &Setup,
        muscles: &[String],
        clock_mode: ClockMode,
        driven_joints: bool,
        logger: &Logger,
    ) -> Result<Self, String> {
        let mut m = Maker {
            node,
            setup,
            qos: qos_reliable(10),
        };
        const OURS: &str = "muscle_actuator_msgs";
        let (activation, activation_name) =
            m.subscribe("~/activation", (OURS, "ActivationCommand"))?;
        let (activation_array, activation_array_name) =
            m.subscribe("~/activation_array", ("std_msgs", "Float64MultiArray"))?;
        let mut muscle_commands = Vec::new();
        let mut muscle_command_names = Vec::new();
        for muscle in muscles {
            let rel = format!("~/{muscle}/cmd_activation");
            if let Err(e) = args::check_name(&rel) {
                logger.warn(&format!(
                    "no ~/<muscle>/cmd_activation topic for muscle {}: not a valid name ({e})",
                    input::quote(muscle)
                ));
                continue;
            }
            let (sub, name) = m.subscribe(&rel, ("std_msgs", "Float64"))?;
            muscle_commands.push((muscle.clone(), sub));
            muscle_command_names.push(name);
        }
        let (load, load_name) = m.subscribe("~/external_load", (OURS, "ExternalLoad"))?;
        let (state, state_name) = m.publish("~/state", (OURS, "ActuatorState"))?;
        let (joint_states, joint_states_name) =
            m.publish("joint_states", ("sensor_msgs", "JointState"))?;
        let (diagnostics, _) = m.publish("/diagnostics", ("diagnostic_msgs", "DiagnosticArray"))?;
        let (reset, reset_name) = m.serve("~/reset", ("std_srvs", "Trigger"))?;
        let (step, step_name) = m.serve("~/step", (OURS, "Step"))?;
        let (step_topic, _) = m.subscribe("~/step", ("std_msgs", "Int64"))?;
        let (joint_states_in, joint_efforts, driven_names) = if driven_joints {
            let (sub, sub_name) =
                m.subscribe("~/joint_states_in", ("sensor_msgs", "JointState"))?;
            let (publ, pub_name) =
                m.publish("~/joint_efforts", ("std_msgs", "Float64MultiArray"))?;
            (Some(sub), Some(publ), Some((sub_name, pub_name)))
        } else {
            (None, None, None)
        };
        let clock = if clock_mode.publishes_clock() {
            Some(
                m.publish_with("/clock", ("rosgraph_msgs", "Clock"), qos_clock(1))?
                    .0,
            )
        } else {
            None
        };
        let clock_in = if clock_mode == ClockMode::Follow {
            Some(
                m.subscribe_with("/clock", ("rosgraph_msgs", "Clock"), qos_clock(10))?
                    .0,
            )
        } else {
            None
        };
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
            names: EndpointNames {
                activation: activation_name,
                activation_array: activation_array_name,
                muscle_commands: muscle_command_names,
                load: load_name,
                state: state_name,
                joint_states: joint_states_name,
                reset: reset_name,
                step: step_name,
                driven: driven_names,
            },
        })
    }
}
