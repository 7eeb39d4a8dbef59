//! What is observable after a tick: every muscle's and joint's fields (the one field list,
//! [`crate::physics::observables`]) and the joint stiffness matrix.

pub(crate) use crate::physics::observables::{
    JointSnapshot, MuscleSnapshot, JOINT_FIELD_COUNT, MUSCLE_FIELD_COUNT,
};

/// Everything observable after a tick: the muscles, the joints and the joint stiffness matrix.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StateSnapshot {
    /// One per muscle, in configuration order.
    pub muscles: Vec<MuscleSnapshot>,
    /// One per joint, in configuration order.
    pub joints: Vec<JointSnapshot>,
    /// The joint stiffness matrix K, row-major n × n (n joints), N m/rad.
    pub stiffness_matrix: Vec<f64>,
}
