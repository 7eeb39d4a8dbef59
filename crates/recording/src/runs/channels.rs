//! The channels of a recording, in one place: what each one carries (topic, type) and the id the
//! recorder gave it. Offline runs record a few of them, the node all; a writer asks a
//! [`Layout`] for the id of a [`Channel`] instead of counting positions.

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

// Topics of an offline run (`simulate --out`, `replay --out`): the node's names under its
// default name.

/// The state topic of an offline run (the node's `~/state`).
pub const STATE_TOPIC: &str = "/muscle_actuator/state";
/// The joint states topic of an offline run (the node's `joint_states`).
pub const JOINT_STATES_TOPIC: &str = "/joint_states";
/// The excitation commands of an offline run (the node's `~/activation`).
pub const ACTIVATION_TOPIC: &str = "/muscle_actuator/activation";
/// The load commands of an offline run (the node's `~/external_load`).
pub const LOAD_TOPIC: &str = "/muscle_actuator/external_load";
/// Suffix (after the node's name) of the node's applied excitations.
pub const APPLIED_ACTIVATION_SUFFIX: &str = "/applied/activation";
/// Suffix (after the node's name) of the node's applied loads.
pub const APPLIED_LOAD_SUFFIX: &str = "/applied/external_load";
/// Suffix of the driven joints' motion as applied (node and offline runs alike).
pub const APPLIED_JOINT_MOTION_SUFFIX: &str = "/applied/joint_motion";
/// The driven joints' motion of an offline run, as applied: the node's name for it.
pub const APPLIED_JOINT_MOTION_TOPIC: &str = "/muscle_actuator/applied/joint_motion";
/// The node's diagnostics topic.
pub const DIAGNOSTICS_TOPIC: &str = "/diagnostics";
/// The node's log topic.
pub const ROSOUT_TOPIC: &str = "/rosout";

/// Type of the state ([`Channel::State`]).
pub const STATE_TYPE: &str = "muscle_actuator_msgs/msg/ActuatorState";
/// Type of joint states ([`Channel::JointStates`], the driven joints' motion).
pub const JOINT_STATE_TYPE: &str = "sensor_msgs/msg/JointState";
/// Type of excitation commands.
pub const ACTIVATION_TYPE: &str = "muscle_actuator_msgs/msg/ActivationCommand";
/// Type of load commands.
pub const LOAD_TYPE: &str = "muscle_actuator_msgs/msg/ExternalLoad";
/// Type of one muscle's excitation ([`Channel::MuscleCommand`]).
pub const FLOAT64_TYPE: &str = "std_msgs/msg/Float64";
/// Type of arrays of values ([`Channel::ActivationArray`], [`Channel::JointEfforts`]).
pub const FLOAT64_ARRAY_TYPE: &str = "std_msgs/msg/Float64MultiArray";
/// Type of diagnostics ([`Channel::Diagnostics`]).
pub const DIAGNOSTICS_TYPE: &str = "diagnostic_msgs/msg/DiagnosticArray";
/// Type of log lines ([`Channel::Rosout`]).
pub const LOG_TYPE: &str = "rcl_interfaces/msg/Log";

/// What a channel carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Channel {
    /// `~/state` (`ActuatorState`).
    State,
    /// `joint_states` (`sensor_msgs/JointState`).
    JointStates,
    /// `~/activation` as received (offline: the inputs as applied).
    Activation,
    /// `~/external_load` as received (offline: the inputs as applied).
    Load,
    /// The node's `~/applied/activation`: excitations as the tick loop applied them.
    AppliedActivation,
    /// The node's `~/applied/external_load`.
    AppliedLoad,
    /// `~/applied/joint_motion` (`sensor_msgs/JointState`): the driven joints' angle and
    /// velocity as the tick loop applied them (offline: as the scenario's schedules gave them).
    AppliedJointMotion,
    /// The node's `/diagnostics` arrays.
    Diagnostics,
    /// The node's own `/rosout` lines.
    Rosout,
    /// `~/activation_array` as received.
    ActivationArray,
    /// `~/<muscle>/cmd_activation` as received: the k-th muscle topic the node opened.
    MuscleCommand(usize),
    /// `~/joint_states_in` as received: the driven joints' motion.
    JointStatesIn,
    /// `~/joint_efforts` as published: the muscles' net torque on each driven joint.
    JointEfforts,
}

/// The channels of one recording with their ids (the recorder numbers them in order).
#[derive(Debug, Default)]
pub struct Layout {
    specs: Vec<ChannelSpec>,
    kinds: Vec<Channel>,
}

impl Layout {
    /// No channels yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `kind` on `topic` with type `type_name` (reliable, volatile, depth 10).
    pub fn add(&mut self, kind: Channel, topic: &str, type_name: &str) -> Result<(), SchemaError> {
        self.specs.push(channel(topic, type_name)?);
        self.kinds.push(kind);
        Ok(())
    }

    /// The id of `kind`, if this recording has it.
    pub fn id(&self, kind: Channel) -> Option<usize> {
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
        l.add(Channel::State, STATE_TOPIC, STATE_TYPE).unwrap();
        l.add(Channel::Activation, ACTIVATION_TOPIC, ACTIVATION_TYPE)
            .unwrap();
        l.add(
            Channel::MuscleCommand(1),
            "/m/b/cmd_activation",
            FLOAT64_TYPE,
        )
        .unwrap();
        assert_eq!(l.id(Channel::State), Some(0));
        assert_eq!(l.id(Channel::Activation), Some(1));
        assert_eq!(l.id(Channel::MuscleCommand(1)), Some(2));
        assert_eq!(l.id(Channel::MuscleCommand(0)), None);
        assert_eq!(l.id(Channel::JointStates), None);
        assert_eq!(l.specs().len(), 3);
        assert_eq!(l.specs()[2].topic, "/m/b/cmd_activation");
    }
}
