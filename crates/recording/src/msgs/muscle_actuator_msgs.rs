//! Types of the interface package `muscle_actuator_msgs` (`msg/`), field for field.

use super::header::Header;
use muscle_actuator_core::sim::{
    JointSnapshot, MuscleSnapshot, JOINT_FIELD_COUNT, MUSCLE_FIELD_COUNT,
};
use serde::de::{self, SeqAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// `muscle_actuator_msgs/msg/ActivationCommand`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct ActivationCommand {
    /// The command's header (its stamp: when it takes effect, docs/time.md).
    pub header: Header,
    /// Muscle names from the configuration.
    pub muscle: Vec<String>,
    /// Neural excitation u of each named muscle, dimensionless, in [0, 1].
    pub excitation: Vec<f64>,
}
ros2_message!(ActivationCommand);

/// `muscle_actuator_msgs/msg/ExternalLoad`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct ExternalLoad {
    /// The command's header (its stamp: when it takes effect, docs/time.md).
    pub header: Header,
    /// Joint names from the configuration.
    pub joint: Vec<String>,
    /// Load torque on each named joint about its axis, N m, positive as the angle.
    pub torque: Vec<f64>,
}
ros2_message!(ExternalLoad);

/// `muscle_actuator_msgs/msg/MuscleState`: the muscle's name, then the fields of
/// [`MuscleSnapshot`] in their order (the one field list; the serde impls iterate it).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MuscleState {
    /// The muscle's name in the configuration.
    pub name: String,
    /// Its state after the tick (the rest of the message's fields, SI units).
    pub state: MuscleSnapshot,
}
ros2_message!(MuscleState);

impl Serialize for MuscleState {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("MuscleState", 1 + MUSCLE_FIELD_COUNT)?;
        st.serialize_field("name", &self.name)?;
        for (field, value) in MuscleSnapshot::FIELDS.iter().zip(self.state.values()) {
            st.serialize_field(field, &value)?;
        }
        st.end()
    }
}

impl<'de> Deserialize<'de> for MuscleState {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = MuscleState;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a MuscleState")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<MuscleState, A::Error> {
                let name: String = next(&mut seq, 0)?;
                let mut values = [0.0; MUSCLE_FIELD_COUNT];
                for (k, v) in values.iter_mut().enumerate() {
                    *v = next(&mut seq, k + 1)?;
                }
                Ok(MuscleState {
                    name,
                    state: MuscleSnapshot::from_values(values),
                })
            }
        }
        d.deserialize_struct("MuscleState", &MUSCLE_STATE_FIELDS, V)
    }
}

/// `muscle_actuator_msgs/msg/ActuatorState`. On the wire the joints are the per-joint arrays
/// of `ActuatorState.msg` (one per [`JointSnapshot`] field, in order), followed by the
/// row-major joint stiffness matrix.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ActuatorState {
    /// Stamp: when the tick that computed this state was due, on the node's clock
    /// (docs/time.md).
    pub header: Header,
    /// The contractile-element model: `hill`, `huxley` or `huxley-pde`.
    pub model: String,
    /// Ticks since the start (or the last reset).
    pub tick: u64,
    /// Joint names, in the configuration's order.
    pub joint: Vec<String>,
    /// One per joint name.
    pub joints: Vec<JointSnapshot>,
    /// Row-major n × n, n = the number of joints, N m/rad.
    pub stiffness_matrix: Vec<f64>,
    /// Every muscle, in the configuration's order.
    pub muscles: Vec<MuscleState>,
}
ros2_message!(ActuatorState);

impl ActuatorState {
    /// Field `k` of every joint (the k-th per-joint array).
    pub fn column(&self, k: usize) -> Vec<f64> {
        self.joints.iter().map(|j| j.values()[k]).collect()
    }
}

/// Field `k` of every joint, serialized as a sequence.
struct Column<'a>(&'a [JointSnapshot], usize);
impl Serialize for Column<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.iter().map(|j| j.values()[self.1]))
    }
}

/// Names of the wire fields of `MuscleState`, in order: `name`, then the field list.
pub(crate) const MUSCLE_STATE_FIELDS: [&str; 1 + MUSCLE_FIELD_COUNT] = {
    let mut out = [""; 1 + MUSCLE_FIELD_COUNT];
    out[0] = "name";
    let mut k = 0;
    while k < MUSCLE_FIELD_COUNT {
        out[k + 1] = MuscleSnapshot::FIELDS[k];
        k += 1;
    }
    out
};

/// Names of the wire fields of `ActuatorState`, in order: the per-joint arrays are the
/// joint field list.
pub(crate) const ACTUATOR_STATE_FIELDS: [&str; 6 + JOINT_FIELD_COUNT] = {
    let mut out = [""; 6 + JOINT_FIELD_COUNT];
    out[0] = "header";
    out[1] = "model";
    out[2] = "tick";
    out[3] = "joint";
    let mut k = 0;
    while k < JOINT_FIELD_COUNT {
        out[4 + k] = JointSnapshot::FIELDS[k];
        k += 1;
    }
    out[4 + JOINT_FIELD_COUNT] = "stiffness_matrix";
    out[5 + JOINT_FIELD_COUNT] = "muscles";
    out
};

impl Serialize for ActuatorState {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("ActuatorState", ACTUATOR_STATE_FIELDS.len())?;
        st.serialize_field("header", &self.header)?;
        st.serialize_field("model", &self.model)?;
        st.serialize_field("tick", &self.tick)?;
        st.serialize_field("joint", &self.joint)?;
        for (k, field) in JointSnapshot::FIELDS.iter().enumerate() {
            st.serialize_field(field, &Column(&self.joints, k))?;
        }
        st.serialize_field("stiffness_matrix", &self.stiffness_matrix)?;
        st.serialize_field("muscles", &self.muscles)?;
        st.end()
    }
}

impl<'de> Deserialize<'de> for ActuatorState {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = ActuatorState;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an ActuatorState")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<ActuatorState, A::Error> {
                let header: Header = next(&mut seq, 0)?;
                let model: String = next(&mut seq, 1)?;
                let tick: u64 = next(&mut seq, 2)?;
                let joint: Vec<String> = next(&mut seq, 3)?;
                let mut joints = vec![JointSnapshot::default(); joint.len()];
                for k in 0..JOINT_FIELD_COUNT {
                    let column: Vec<f64> = next(&mut seq, 4 + k)?;
                    if column.len() != joint.len() {
                        return Err(de::Error::custom(format!(
                            "ActuatorState.{} has {} values for {} joints",
                            JointSnapshot::FIELDS[k],
                            column.len(),
                            joint.len()
                        )));
                    }
                    for (j, v) in joints.iter_mut().zip(column) {
                        let mut values = j.values();
                        values[k] = v;
                        *j = JointSnapshot::from_values(values);
                    }
                }
                let stiffness_matrix: Vec<f64> = next(&mut seq, 4 + JOINT_FIELD_COUNT)?;
                if stiffness_matrix.len() != joint.len() * joint.len() {
                    return Err(de::Error::custom(format!(
                        "ActuatorState.stiffness_matrix has {} values for {} joints",
                        stiffness_matrix.len(),
                        joint.len()
                    )));
                }
                let muscles: Vec<MuscleState> = next(&mut seq, 5 + JOINT_FIELD_COUNT)?;
                Ok(ActuatorState {
                    header,
                    model,
                    tick,
                    joint,
                    joints,
                    stiffness_matrix,
                    muscles,
                })
            }
        }
        d.deserialize_struct("ActuatorState", &ACTUATOR_STATE_FIELDS, V)
    }
}

/// The next element of a struct read as a sequence, or an error naming its position.
fn next<'de, T: Deserialize<'de>, A: SeqAccess<'de>>(
    seq: &mut A,
    index: usize,
) -> Result<T, A::Error> {
    seq.next_element()?
        .ok_or_else(|| de::Error::invalid_length(index, &"all fields of the message"))
}
