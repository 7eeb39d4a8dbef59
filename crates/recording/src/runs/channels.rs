//! The channels of a recording: the topics offline runs share with the node (name and type,
//! spelt here once), the message types, and the id the recorder gave each channel. A writer asks
//! a [`Layout`] for the id of a channel's key instead of counting positions.

use crate::msgs::{definition, type_hash};
use crate::recording::schema::{ros2msg_schema, SchemaError};
use crate::recording::{qos_yaml, ChannelSpec};

/// The channel of `topic` with type `type_name` (reliable, volatile, depth 10, as the node).
pub fn channel(topic: &str, type_name: &str) -> Result<ChannelSpec, SchemaError> {
    Ok(ChannelSpec {
        topic: topic.into(),
        type_name: type_name.into(),
        schema: ros2msg_schema(type_name, &definition)?,
        qos_yaml: qos_yaml(true, false, 10).map_err(|e| SchemaError::QosYaml {
            topic: topic.into(),
            reason: e.to_string(),
        })?,
        type_hash: type_hash(type_name).map(String::from),
    })
}

/// A topic that offline runs write as the node does: its name under the node (`~/` stands for
/// the node's namespace and name, as in docs/ros-interface.md) and its type. The node's table of
/// endpoints names these from here, so each is spelt once.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeTopic {
    /// As the node declares it, before namespace and remapping.
    pub name: &'static str,
    /// `pkg/msg/Type`.
    pub type_name: &'static str,
}

/// The node's default fully qualified name, under which offline runs name their topics.
pub const OFFLINE_NODE: &str = "/muscle_actuator";

impl NodeTopic {
    /// The topic as an offline run names it: the node's, under [`OFFLINE_NODE`] at the root.
    pub fn offline(&self) -> String {
        match self.name.strip_prefix("~/") {
            Some(rest) => format!("{OFFLINE_NODE}/{rest}"),
            None if self.name.starts_with('/') => self.name.to_string(),
            None => format!("/{}", self.name),
        }
    }

    /// What the name ends with under any node name (`/applied/activation` for
    /// `~/applied/activation`): how a reader finds the channel in a node's recording.
    pub fn suffix(&self) -> &'static str {
        self.name.trim_start_matches('~')
    }
}

/// `~/state`: each tick's state.
pub const STATE: NodeTopic = NodeTopic {
    name: "~/state",
    type_name: STATE_TYPE,
};
/// `joint_states`: the joints' angle, velocity and torque.
pub const JOINT_STATES: NodeTopic = NodeTopic {
    name: "joint_states",
    type_name: JOINT_STATE_TYPE,
};
/// `~/activation`: excitations by muscle name (offline: the inputs as applied).
pub const ACTIVATION: NodeTopic = NodeTopic {
    name: "~/activation",
    type_name: ACTIVATION_TYPE,
};
/// `~/external_load`: torques by joint name (offline: the inputs as applied).
pub const LOAD: NodeTopic = NodeTopic {
    name: "~/external_load",
    type_name: LOAD_TYPE,
};
/// `~/applied/activation`: excitations as the node's tick loop applied them.
pub const APPLIED_ACTIVATION: NodeTopic = NodeTopic {
    name: "~/applied/activation",
    type_name: ACTIVATION_TYPE,
};
/// `~/applied/external_load`: loads as the node's tick loop applied them.
pub const APPLIED_LOAD: NodeTopic = NodeTopic {
    name: "~/applied/external_load",
    type_name: LOAD_TYPE,
};
/// `~/applied/joint_motion`: the driven joints' angle and velocity as applied (node and offline
/// runs alike).
pub const APPLIED_JOINT_MOTION: NodeTopic = NodeTopic {
    name: "~/applied/joint_motion",
    type_name: JOINT_STATE_TYPE,
};

/// Type of the state ([`STATE`]).
pub const STATE_TYPE: &str = "muscle_actuator_msgs/msg/ActuatorState";
/// Type of joint states ([`JOINT_STATES`], the driven joints' motion).
pub const JOINT_STATE_TYPE: &str = "sensor_msgs/msg/JointState";
/// Type of excitation commands.
pub const ACTIVATION_TYPE: &str = "muscle_actuator_msgs/msg/ActivationCommand";
/// Type of load commands.
pub const LOAD_TYPE: &str = "muscle_actuator_msgs/msg/ExternalLoad";
/// Type of one number (the node's per-muscle commands).
pub const FLOAT64_TYPE: &str = "std_msgs/msg/Float64";
/// Type of arrays of numbers (the node's activation arrays and joint efforts).
pub const FLOAT64_ARRAY_TYPE: &str = "std_msgs/msg/Float64MultiArray";
/// Type of the node's diagnostics.
pub const DIAGNOSTICS_TYPE: &str = "diagnostic_msgs/msg/DiagnosticArray";
/// Type of the node's log lines.
pub const LOG_TYPE: &str = "rcl_interfaces/msg/Log";

/// What a channel of an offline run carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Channel {
    /// [`STATE`].
    State,
    /// [`JOINT_STATES`].
    JointStates,
    /// [`ACTIVATION`]: the inputs as applied.
    Activation,
    /// [`LOAD`]: the inputs as applied.
    Load,
    /// [`APPLIED_JOINT_MOTION`]: the driven joints' motion as the scenario's schedules gave it.
    AppliedJointMotion,
}

/// The channels of one recording with their ids (the recorder numbers them in order), each
/// known by a key `K`: a [`Channel`] for offline runs, the node's own key for its recordings.
#[derive(Debug)]
pub struct Layout<K = Channel> {
    specs: Vec<ChannelSpec>,
    kinds: Vec<K>,
}

impl<K> Default for Layout<K> {
    fn default() -> Self {
        Self {
            specs: Vec::new(),
            kinds: Vec::new(),
        }
    }
}

impl<K: PartialEq> Layout<K> {
    /// No channels yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `kind` on `topic` with type `type_name` (reliable, volatile, depth 10).
    pub fn add(&mut self, kind: K, topic: &str, type_name: &str) -> Result<(), SchemaError> {
        self.specs.push(channel(topic, type_name)?);
        self.kinds.push(kind);
        Ok(())
    }

    /// The id of `kind`, if this recording has it.
    pub fn id(&self, kind: K) -> Option<usize> {
        self.kinds.iter().position(|k| *k == kind)
    }

    /// The specifications, in id order (for [`crate::recording::Recorder::start`]).
    pub fn specs(&self) -> Vec<ChannelSpec> {
        self.specs.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_follow_the_order_of_addition() {
        let mut l = Layout::new();
        l.add(Channel::State, &STATE.offline(), STATE_TYPE).unwrap();
        l.add(Channel::Activation, &ACTIVATION.offline(), ACTIVATION_TYPE)
            .unwrap();
        l.add(Channel::Load, "/m/external_load", LOAD_TYPE).unwrap();
        assert_eq!(l.id(Channel::State), Some(0));
        assert_eq!(l.id(Channel::Activation), Some(1));
        assert_eq!(l.id(Channel::Load), Some(2));
        assert_eq!(l.id(Channel::JointStates), None);
        assert_eq!(l.specs().len(), 3);
        assert_eq!(l.specs()[2].topic, "/m/external_load");
    }

    /// Offline runs name their topics as the node does under its default name.
    #[test]
    fn offline_names_are_the_default_nodes() {
        assert_eq!(STATE.offline(), "/muscle_actuator/state");
        assert_eq!(JOINT_STATES.offline(), "/joint_states");
        assert_eq!(ACTIVATION.offline(), "/muscle_actuator/activation");
        assert_eq!(LOAD.offline(), "/muscle_actuator/external_load");
        assert_eq!(
            APPLIED_JOINT_MOTION.offline(),
            "/muscle_actuator/applied/joint_motion"
        );
        assert_eq!(APPLIED_LOAD.suffix(), "/applied/external_load");
    }
}
