//! A run's records: the initial state and one record per tick, each the muscles', the joints'
//! and the joint stiffness matrix's values after it, stored tick after tick in flat arrays of
//! fixed widths (the muscles, the joints, the matrix's n × n entries). Reserved once for the
//! whole run, so that keeping a tick's record copies it and allocates nothing; read back as
//! borrowed [`Record`]s.

use crate::physics::models::ModelKind;
use crate::sim::snapshot::{JointSnapshot, MuscleSnapshot, StateSnapshot};

/// One recorded tick, borrowed from its [`Run`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Record<'a> {
    /// Time at the end of the tick, s (0 for the initial state).
    pub time: f64,
    /// The muscles' states.
    pub muscles: &'a [MuscleSnapshot],
    /// The joints' states (none for a clamped or force-driven muscle).
    pub joints: &'a [JointSnapshot],
    /// The joint stiffness matrix, row-major, N m/rad.
    pub stiffness_matrix: &'a [f64],
}

impl<'a> Record<'a> {
    /// `state` at `time`, as a record.
    pub fn of(time: f64, state: &'a StateSnapshot) -> Self {
        Self {
            time,
            muscles: &state.muscles,
            joints: &state.joints,
            stiffness_matrix: &state.stiffness_matrix,
        }
    }
}

/// A record whose muscles, joints or stiffness matrix do not match the run's names
/// (`Run::push`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "a state of {muscles} muscles, {joints} joints and {stiffness_entries} stiffness entries in \
     a run of {run_muscles} muscles and {run_joints} joints"
)]
pub struct RecordMismatch {
    /// Muscles of the record.
    pub muscles: usize,
    /// Joints of the record.
    pub joints: usize,
    /// Entries of the record's stiffness matrix.
    pub(crate) stiffness_entries: usize,
    /// Muscles of the run.
    pub(crate) run_muscles: usize,
    /// Joints of the run.
    pub(crate) run_joints: usize,
}

/// The result of running a scenario (or of reading a recording back): its names and rate, and
/// its records.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// Scenario name.
    pub scenario: String,
    /// Model used.
    pub model: ModelKind,
    /// Tick rate, Hz.
    pub rate_hz: f64,
    /// Muscle names.
    pub muscle_names: Vec<String>,
    /// Joint names.
    pub joint_names: Vec<String>,
    /// Per muscle, the indices of the joints it spans.
    pub muscle_joints: Vec<Vec<usize>>,
    /// Per record, its time, s.
    times: Vec<f64>,
    /// Per record, `muscle_names.len()` muscle states.
    muscles: Vec<MuscleSnapshot>,
    /// Per record, `joint_names.len()` joint states.
    joints: Vec<JointSnapshot>,
    /// Per record, the `joint_names.len()`² entries of the stiffness matrix.
    stiffness: Vec<f64>,
}

impl Run {
    /// A run without records, with room reserved for `capacity` of them.
    pub fn new(
        scenario: String,
        model: ModelKind,
        rate_hz: f64,
        muscle_names: Vec<String>,
        joint_names: Vec<String>,
        muscle_joints: Vec<Vec<usize>>,
        capacity: usize,
    ) -> Self {
        let (m, n) = (muscle_names.len(), joint_names.len());
        Self {
            scenario,
            model,
            rate_hz,
            muscle_names,
            joint_names,
            muscle_joints,
            times: Vec::with_capacity(capacity),
            muscles: Vec::with_capacity(capacity * m),
            joints: Vec::with_capacity(capacity * n),
            stiffness: Vec::with_capacity(capacity * n * n),
        }
    }

    /// Appends the record of `state` at `time`; a state whose muscles, joints or matrix do not
    /// match the run's names is refused (and nothing is appended).
    pub(crate) fn push(&mut self, time: f64, state: &StateSnapshot) -> Result<(), RecordMismatch> {
        self.push_parts(time, &state.muscles, &state.joints, &state.stiffness_matrix)
    }

    /// `Run::push` from the record's parts.
    pub fn push_parts(
        &mut self,
        time: f64,
        muscles: &[MuscleSnapshot],
        joints: &[JointSnapshot],
        stiffness_matrix: &[f64],
    ) -> Result<(), RecordMismatch> {
        let (m, n) = (self.muscle_names.len(), self.joint_names.len());
        if muscles.len() != m || joints.len() != n || stiffness_matrix.len() != n * n {
            return Err(RecordMismatch {
                muscles: muscles.len(),
                joints: joints.len(),
                stiffness_entries: stiffness_matrix.len(),
                run_muscles: m,
                run_joints: n,
            });
        }
        self.times.push(time);
        self.muscles.extend_from_slice(muscles);
        self.joints.extend_from_slice(joints);
        self.stiffness.extend_from_slice(stiffness_matrix);
        Ok(())
    }

    /// Number of records (the initial state and one per tick).
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether it holds no record.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Record `k`, or None past the last.
    pub(crate) fn get(&self, k: usize) -> Option<Record<'_>> {
        let (m, n) = (self.muscle_names.len(), self.joint_names.len());
        Some(Record {
            time: *self.times.get(k)?,
            muscles: &self.muscles[k * m..(k + 1) * m],
            joints: &self.joints[k * n..(k + 1) * n],
            stiffness_matrix: &self.stiffness[k * n * n..(k + 1) * n * n],
        })
    }

    /// Record `k`. Panics past the last, as indexing does.
    pub fn record(&self, k: usize) -> Record<'_> {
        self.get(k)
            .unwrap_or_else(|| panic!("record {k} of a run of {}", self.len()))
    }

    /// The last record, None for a run without any.
    pub fn last(&self) -> Option<Record<'_>> {
        self.len().checked_sub(1).and_then(|k| self.get(k))
    }

    /// The records in order.
    pub fn records(&self) -> impl DoubleEndedIterator<Item = Record<'_>> + ExactSizeIterator {
        (0..self.len()).map(|k| self.record(k))
    }

    /// Bytes one record takes: its time, its muscles' and joints' states and its matrix.
    pub(crate) fn record_bytes(muscles: usize, joints: usize) -> f64 {
        (std::mem::size_of::<f64>()
            + muscles * std::mem::size_of::<MuscleSnapshot>()
            + joints * std::mem::size_of::<JointSnapshot>()) as f64
            + (joints as f64).powi(2) * 8.0
    }
}
