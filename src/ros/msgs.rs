//! The ROS 2 message types the node uses, as serde structs in wire (field) order.
//!
//! `muscle_actuator_msgs` mirrors `msg/*.msg` field for field (`tests/msg_definitions.rs` checks
//! it); the standard types mirror their kilted definitions.

use ros2_client::builtin_interfaces::Time;
use ros2_client::Message;
use serde::{Deserialize, Serialize};

/// `std_msgs/msg/Header`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header {
    pub stamp: Time,
    pub frame_id: String,
}
impl Message for Header {}

impl Default for Header {
    fn default() -> Self {
        Self {
            stamp: Time::ZERO,
            frame_id: String::new(),
        }
    }
}

/// Types of the interface package `muscle_actuator_msgs` (`msg/`).
pub mod muscle_actuator_msgs {
    use super::*;

    /// `muscle_actuator_msgs/msg/ActivationCommand`.
    #[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
    pub struct ActivationCommand {
        pub header: Header,
        pub muscle: Vec<String>,
        pub excitation: Vec<f64>,
    }
    impl Message for ActivationCommand {}

    /// `muscle_actuator_msgs/msg/ExternalLoad`.
    #[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
    pub struct ExternalLoad {
        pub header: Header,
        pub joint: Vec<String>,
        pub torque: Vec<f64>,
    }
    impl Message for ExternalLoad {}

    /// `muscle_actuator_msgs/msg/MuscleState`.
    #[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
    pub struct MuscleState {
        pub name: String,
        pub excitation: f64,
        pub activation: f64,
        pub force: f64,
        pub ce_force: f64,
        pub pe_force: f64,
        pub fiber_length: f64,
        pub fiber_velocity: f64,
        pub tendon_length: f64,
        pub stiffness: f64,
        pub mtu_stiffness: f64,
        pub q0: f64,
        pub q1: f64,
        pub q2: f64,
        pub tendon_energy: f64,
        pub fiber_energy: f64,
        pub crossbridge_energy: f64,
    }
    impl Message for MuscleState {}

    /// `muscle_actuator_msgs/msg/ActuatorState`.
    #[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
    pub struct ActuatorState {
        pub header: Header,
        pub model: String,
        pub tick: u64,
        pub joint: Vec<String>,
        pub position: Vec<f64>,
        pub velocity: Vec<f64>,
        pub torque: Vec<f64>,
        pub external_torque: Vec<f64>,
        pub stiffness: Vec<f64>,
        pub muscles: Vec<MuscleState>,
    }
    impl Message for ActuatorState {}
}

/// `sensor_msgs/msg/JointState`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct JointState {
    pub header: Header,
    pub name: Vec<String>,
    pub position: Vec<f64>,
    pub velocity: Vec<f64>,
    pub effort: Vec<f64>,
}
impl Message for JointState {}

/// `diagnostic_msgs/msg/KeyValue`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct KeyValue {
    pub key: String,
    pub value: String,
}
impl Message for KeyValue {}

/// `diagnostic_msgs/msg/DiagnosticStatus`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct DiagnosticStatus {
    /// OK = 0, WARN = 1, ERROR = 2, STALE = 3.
    pub level: u8,
    pub name: String,
    pub message: String,
    pub hardware_id: String,
    pub values: Vec<KeyValue>,
}
impl Message for DiagnosticStatus {}

impl DiagnosticStatus {
    pub const OK: u8 = 0;
    pub const WARN: u8 = 1;
    pub const ERROR: u8 = 2;
}

/// `diagnostic_msgs/msg/DiagnosticArray`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct DiagnosticArray {
    pub header: Header,
    pub status: Vec<DiagnosticStatus>,
}
impl Message for DiagnosticArray {}

/// `std_srvs/srv/Trigger` request: an empty structure, which the ROS 2 IDL carries as one
/// placeholder byte.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TriggerRequest {
    pub structure_needs_at_least_one_member: u8,
}
impl Message for TriggerRequest {}

/// `std_srvs/srv/Trigger` response.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TriggerResponse {
    pub success: bool,
    pub message: String,
}
impl Message for TriggerResponse {}

/// The `.msg` definitions of the recorded types (`pkg/msg/Type` → text), for the `ros2msg`
/// schemas of recordings: ours from `msg/msg/`, the standard ones as in ROS 2 kilted (fields
/// only).
pub const DEFINITIONS: &[(&str, &str)] = &[
    (
        "muscle_actuator_msgs/msg/ActivationCommand",
        include_str!("../../msg/msg/ActivationCommand.msg"),
    ),
    (
        "muscle_actuator_msgs/msg/ExternalLoad",
        include_str!("../../msg/msg/ExternalLoad.msg"),
    ),
    (
        "muscle_actuator_msgs/msg/MuscleState",
        include_str!("../../msg/msg/MuscleState.msg"),
    ),
    (
        "muscle_actuator_msgs/msg/ActuatorState",
        include_str!("../../msg/msg/ActuatorState.msg"),
    ),
    (
        "std_msgs/msg/Header",
        "builtin_interfaces/Time stamp\nstring frame_id\n",
    ),
    (
        "builtin_interfaces/msg/Time",
        "int32 sec\nuint32 nanosec\n",
    ),
    (
        "sensor_msgs/msg/JointState",
        "std_msgs/Header header\n\nstring[] name\nfloat64[] position\nfloat64[] velocity\nfloat64[] effort\n",
    ),
];

/// The `.msg` text of `pkg/msg/Type`, if it is one of [`DEFINITIONS`].
pub fn definition(type_name: &str) -> Option<&'static str> {
    DEFINITIONS
        .iter()
        .find(|(n, _)| *n == type_name)
        .map(|(_, t)| *t)
}

/// REP-2016 type hashes (`RIHS01_...`) of the recorded types, for `topic_type_hash` in
/// recordings. They follow from the definitions above; `tests/python/test_recording.py` checks
/// them against the hash `rosbags` computes from the schemas embedded in a recording (update
/// them from its failure message when a `.msg` file changes).
pub const TYPE_HASHES: &[(&str, &str)] = &[
    (
        "muscle_actuator_msgs/msg/ActivationCommand",
        "RIHS01_ce7fb9cd9d358cb8c05032e923e09d976928fe6ef1b58367d2e8d7cd4053ab73",
    ),
    (
        "muscle_actuator_msgs/msg/ExternalLoad",
        "RIHS01_47f5dd3d3840d4448236aa191a63b0fc7c5098b0e170b47e0473684948ddb16f",
    ),
    (
        "muscle_actuator_msgs/msg/ActuatorState",
        "RIHS01_01dfcdb343cd8f8b5ad7a5c078b71e04d48d874374ef737c5d730dae05b1a202",
    ),
    (
        "sensor_msgs/msg/JointState",
        "RIHS01_a13ee3a330e346c9d87b5aa18d24e11690752bd33a0350f11c5882bc9179260e",
    ),
];

/// The type hash of `pkg/msg/Type`, if known.
pub fn type_hash(type_name: &str) -> Option<&'static str> {
    TYPE_HASHES
        .iter()
        .find(|(n, _)| *n == type_name)
        .map(|(_, h)| *h)
}
