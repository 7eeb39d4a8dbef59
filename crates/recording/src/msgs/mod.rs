//! The ROS 2 message types the node uses, as serde structs in wire (field) order, and the
//! conversion of a tick's state into the published messages (a leaf module: the node and the
//! offline runs both use it).
//!
//! `muscle_actuator_msgs` mirrors `msg/*.msg` field for field (`tests/msg_definitions.rs` checks
//! it); the standard types mirror their kilted definitions.

/// With the `ros2` feature (the node's), the type is a `ros2_client` message: the node
/// publishes, subscribes and serves it over DDS. Without it this crate has no DDS in it.
macro_rules! ros2_message {
    ($t:ty) => {
        #[cfg(feature = "ros2")]
        impl ros2_client::Message for $t {}
    };
}

mod header;
mod time;
pub(crate) mod type_hash;

pub use header::Header;
pub use time::Time;

use muscle_actuator_core::sim::StateSnapshot;
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// Types of the interface package `muscle_actuator_msgs` (`msg/`).
pub mod muscle_actuator_msgs;

/// The two messages published after a tick: `ActuatorState` and `sensor_msgs/JointState`
/// (effort = the net muscle torque), stamped `stamp_ns`.
pub fn state_messages(
    stamp_ns: i64,
    model: &str,
    tick: u64,
    muscle_names: &[String],
    joint_names: &[String],
    state: &StateSnapshot,
) -> (muscle_actuator_msgs::ActuatorState, JointState) {
    let header = Header {
        stamp: Time::from_nanos(stamp_ns),
        frame_id: String::new(),
    };
    let muscles = state
        .muscles
        .iter()
        .zip(muscle_names)
        .map(|(m, name)| muscle_actuator_msgs::MuscleState {
            name: name.clone(),
            state: *m,
        })
        .collect();
    let js = JointState {
        header: header.clone(),
        name: joint_names.to_vec(),
        position: state.joints.iter().map(|j| j.position).collect(),
        velocity: state.joints.iter().map(|j| j.velocity).collect(),
        effort: state.joints.iter().map(|j| j.torque).collect(),
    };
    let msg = muscle_actuator_msgs::ActuatorState {
        header,
        model: model.into(),
        tick,
        joint: joint_names.to_vec(),
        joints: state.joints.clone(),
        stiffness_matrix: state.stiffness_matrix.clone(),
        muscles,
    };
    (msg, js)
}

/// `sensor_msgs/msg/JointState`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct JointState {
    /// Stamp: when the tick was due (published), or the time of the robot simulator's state
    /// (driven joints).
    pub header: Header,
    /// Joint names.
    pub name: Vec<String>,
    /// Joint angles, rad.
    pub position: Vec<f64>,
    /// Joint angular velocities, rad/s.
    pub velocity: Vec<f64>,
    /// Net muscle torque on each joint, N m.
    pub effort: Vec<f64>,
}
ros2_message!(JointState);

/// `std_msgs/msg/Float64`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Float64 {
    /// The value.
    pub data: f64,
}
ros2_message!(Float64);

/// `std_msgs/msg/Int64`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Int64 {
    /// The value.
    pub data: i64,
}
ros2_message!(Int64);

/// `rosgraph_msgs/msg/Clock`: the time of a graph that runs on simulated time.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Clock {
    /// The graph's current time, ns.
    pub clock: Time,
}
ros2_message!(Clock);

/// `muscle_actuator_msgs/srv/Step` request (`msg/srv/Step.srv`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct StepRequest {
    /// Ticks to advance, >= 1.
    pub ticks: i64,
}
ros2_message!(StepRequest);

/// `muscle_actuator_msgs/srv/Step` response.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StepResponse {
    /// Whether the ticks were run.
    pub success: bool,
    /// Why not, when `success` is false.
    pub message: String,
    /// The tick reached.
    pub tick: u64,
    /// The state after the last tick.
    pub state: muscle_actuator_msgs::ActuatorState,
}
ros2_message!(StepResponse);

/// `std_msgs/msg/MultiArrayDimension`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct MultiArrayDimension {
    /// The dimension's name.
    pub label: String,
    /// Its number of elements.
    pub size: u32,
    pub(crate) stride: u32,
}

/// `std_msgs/msg/MultiArrayLayout`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct MultiArrayLayout {
    /// The dimensions, outermost first.
    pub dim: Vec<MultiArrayDimension>,
    /// Elements of `data` before the first one of the array.
    pub data_offset: u32,
}

/// `std_msgs/msg/Float64MultiArray`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Float64MultiArray {
    /// The shape of `data`.
    pub layout: MultiArrayLayout,
    /// The values, row-major.
    pub data: Vec<f64>,
}
ros2_message!(Float64MultiArray);

/// `diagnostic_msgs/msg/KeyValue`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct KeyValue {
    /// The value's name.
    pub key: String,
    /// The value, as text.
    pub value: String,
}
ros2_message!(KeyValue);

/// `diagnostic_msgs/msg/DiagnosticStatus`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct DiagnosticStatus {
    /// OK = 0, WARN = 1, ERROR = 2, STALE = 3.
    pub level: u8,
    /// The name of what is reported on.
    pub name: String,
    /// The status in one line.
    pub message: String,
    /// The hardware reported on (the node puts its fully qualified name).
    pub hardware_id: String,
    /// The figures behind the status, by name.
    pub values: Vec<KeyValue>,
}
ros2_message!(DiagnosticStatus);

impl DiagnosticStatus {
    /// [`level`](Self::level): all is well.
    pub const OK: u8 = 0;
    /// [`level`](Self::level): a warning.
    pub const WARN: u8 = 1;
    /// [`level`](Self::level): an error.
    pub const ERROR: u8 = 2;
}

/// `diagnostic_msgs/msg/DiagnosticArray`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct DiagnosticArray {
    /// Stamp: when the statuses were gathered.
    pub header: Header,
    /// One status per thing reported on.
    pub status: Vec<DiagnosticStatus>,
}
ros2_message!(DiagnosticArray);

/// `rcl_interfaces/msg/Log`: a `/rosout` line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Log {
    /// When the line was logged.
    pub stamp: Time,
    /// DEBUG = 10, INFO = 20, WARN = 30, ERROR = 40, FATAL = 50.
    pub level: u8,
    /// The logger's name.
    pub name: String,
    /// The line's text.
    pub msg: String,
    /// The source file that logged it.
    pub file: String,
    /// The function that logged it.
    pub function: String,
    /// The line in `file`.
    pub line: u32,
}
ros2_message!(Log);

/// `std_srvs/srv/Trigger` request: an empty structure, which the ROS 2 IDL carries as one
/// placeholder byte.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TriggerRequest {
    /// The placeholder byte, 0.
    pub structure_needs_at_least_one_member: u8,
}
ros2_message!(TriggerRequest);

/// `std_srvs/srv/Trigger` response.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TriggerResponse {
    /// Whether the service did what it was asked.
    pub success: bool,
    /// Informational text (why not, when `success` is false).
    pub message: String,
}
ros2_message!(TriggerResponse);

/// The `.msg` definitions of the recorded types (`pkg/msg/Type` → text), for the `ros2msg`
/// schemas of recordings: ours from `crates/recording/msg/` (copies of the interface package's
/// `msg/msg/`, kept equal by tests/msg_copies.rs), the standard ones as in ROS 2 kilted (fields
/// only).
pub(crate) const DEFINITIONS: &[(&str, &str)] = &[
    (
        "muscle_actuator_msgs/msg/ActivationCommand",
        include_str!("../../msg/ActivationCommand.msg"),
    ),
    (
        "muscle_actuator_msgs/msg/ExternalLoad",
        include_str!("../../msg/ExternalLoad.msg"),
    ),
    (
        "muscle_actuator_msgs/msg/MuscleState",
        include_str!("../../msg/MuscleState.msg"),
    ),
    (
        "muscle_actuator_msgs/msg/ActuatorState",
        include_str!("../../msg/ActuatorState.msg"),
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
    ("std_msgs/msg/Float64", "float64 data\n"),
    (
        "std_msgs/msg/Float64MultiArray",
        "MultiArrayLayout layout\nfloat64[] data\n",
    ),
    (
        "std_msgs/msg/MultiArrayLayout",
        "MultiArrayDimension[] dim\nuint32 data_offset\n",
    ),
    (
        "std_msgs/msg/MultiArrayDimension",
        "string label\nuint32 size\nuint32 stride\n",
    ),
    (
        "rosgraph_msgs/msg/Clock",
        "builtin_interfaces/Time clock\n",
    ),
    (
        "diagnostic_msgs/msg/DiagnosticArray",
        "std_msgs/Header header\nDiagnosticStatus[] status\n",
    ),
    (
        "diagnostic_msgs/msg/DiagnosticStatus",
        "byte OK=0\nbyte WARN=1\nbyte ERROR=2\nbyte STALE=3\n\nbyte level\nstring name\n\
         string message\nstring hardware_id\nKeyValue[] values\n",
    ),
    (
        "diagnostic_msgs/msg/KeyValue",
        "string key\nstring value\n",
    ),
    (
        "rcl_interfaces/msg/Log",
        "uint8 DEBUG=10\nuint8 INFO=20\nuint8 WARN=30\nuint8 ERROR=40\nuint8 FATAL=50\n\n\
         builtin_interfaces/Time stamp\nuint8 level\nstring name\nstring msg\nstring file\n\
         string function\nuint32 line\n",
    ),
];

/// The `.msg` text of `pkg/msg/Type`, if it is one of `DEFINITIONS`.
pub fn definition(type_name: &str) -> Option<&'static str> {
    DEFINITIONS
        .iter()
        .find(|(n, _)| *n == type_name)
        .map(|(_, t)| *t)
}

/// The REP-2016 type hash (`RIHS01_...`) of `pkg/msg/Type`, computed from `DEFINITIONS`
/// (once per process), if it is one of them: the `topic_type_hash` of recordings.
/// `tests/python/test_recording.py` checks it against the hash `rosbags` computes from the
/// schemas embedded in a recording.
pub(crate) fn type_hash(type_name: &str) -> Option<&'static str> {
    static HASHES: OnceLock<Vec<(&'static str, Option<String>)>> = OnceLock::new();
    HASHES
        .get_or_init(|| {
            DEFINITIONS
                .iter()
                .map(|(n, _)| (*n, type_hash::rihs01(n, definition).ok()))
                .collect()
        })
        .iter()
        .find(|(n, _)| *n == type_name)
        .and_then(|(_, h)| h.as_deref())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hashes `rosbags` (`Typestore.hash_rihs01`) gives the recorded types, and ROS 2 kilted
    /// for the standard ones.
    #[test]
    fn type_hashes_are_those_of_ros() {
        for (name, hash) in [
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
                "RIHS01_18ca2781f4598ed2c13314d95bb40066122c9b0bc819394fddfcbf88701f9714",
            ),
            (
                "sensor_msgs/msg/JointState",
                "RIHS01_a13ee3a330e346c9d87b5aa18d24e11690752bd33a0350f11c5882bc9179260e",
            ),
            (
                "std_msgs/msg/Float64",
                "RIHS01_705ba9c3d1a09df43737eb67095534de36fd426c0587779bda2bc51fe790182a",
            ),
            (
                "std_msgs/msg/Float64MultiArray",
                "RIHS01_1025ddc6b9552d191f89ef1a8d2f60f3d373e28b283d8891ddcc974e8c55397f",
            ),
            (
                "diagnostic_msgs/msg/DiagnosticArray",
                "RIHS01_5a8a36efb05fb25070fa0fb3810290c0e6cd4862b54a8fb975a1ee8dc55a333e",
            ),
            (
                "rcl_interfaces/msg/Log",
                "RIHS01_e28ce254ca8abc06abf92773b74602cdbf116ed34fbaf294fb9f81da9f318eac",
            ),
        ] {
            assert_eq!(type_hash(name), Some(hash), "{name}");
        }
        assert_eq!(type_hash("std_msgs/msg/Nothing"), None);
    }

    /// The description of a type with every kind of field, written as rosidl writes it.
    #[test]
    fn type_description_json_layout() {
        let defs = |n: &str| match n {
            "p/msg/A" => Some("# c\nint8 K=1\nstring<=4 s # x\nB[2] b\nfloat64[<=3] f\nbyte[] o\n"),
            "p/msg/B" => Some(""),
            _ => None,
        };
        let field = |name: &str, id: u8, cap: u64, scap: u64, nested: &str| {
            format!(
                "{{\"name\": \"{name}\", \"type\": {{\"type_id\": {id}, \"capacity\": {cap}, \
                 \"string_capacity\": {scap}, \"nested_type_name\": \"{nested}\"}}}}"
            )
        };
        let want = format!(
            "{{\"type_description\": {{\"type_name\": \"p/msg/A\", \"fields\": [{}, {}, {}, {}]}}, \
             \"referenced_type_descriptions\": [{{\"type_name\": \"p/msg/B\", \"fields\": [{}]}}]}}",
            field("s", 21, 0, 4, ""),
            field("b", 49, 2, 0, "p/msg/B"),
            field("f", 107, 3, 0, ""),
            field("o", 160, 0, 0, ""),
            field("structure_needs_at_least_one_member", 3, 0, 0, ""),
        );
        assert_eq!(type_hash::type_description_json("p/msg/A", defs), Ok(want));
        assert!(type_hash::type_description_json("p/msg/C", defs).is_err());
    }
}
