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
