//! The outputs a trajectory carries, by the names of the one field list
//! (`physics::observables`): a `MuscleState` field (`force`: one value per muscle), `joint.` and a
//! joint field (`joint.position`: one per joint), or `stiffness_matrix` (joints × joints).

use muscle_actuator::sim::run::Record;
use muscle_actuator::sim::snapshot::{JointSnapshot, MuscleSnapshot};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Where an output's values come from.
#[derive(Debug, Clone, Copy)]
pub enum Source {
    Muscle(usize),
    Joint(usize),
    StiffnessMatrix,
}

/// A chosen list of outputs.
#[derive(Debug, Clone)]
pub struct Outputs {
    pub keys: Vec<(String, Source)>,
}

pub const JOINT_PREFIX: &str = "joint.";

impl Outputs {
    /// Every output: the muscle fields, the joint fields, the stiffness matrix.
    pub fn all() -> Self {
        let mut keys: Vec<(String, Source)> = MuscleSnapshot::FIELDS
            .iter()
            .enumerate()
            .map(|(k, f)| (f.to_string(), Source::Muscle(k)))
            .collect();
        keys.extend(
            (JointSnapshot::FIELDS.iter().enumerate())
                .map(|(k, f)| (format!("{JOINT_PREFIX}{f}"), Source::Joint(k))),
        );
        keys.push(("stiffness_matrix".into(), Source::StiffnessMatrix));
        Self { keys }
    }

    /// The outputs named (None: all); an unknown name is refused with the list of names.
    pub fn named(names: Option<Vec<String>>) -> PyResult<Self> {
        let all = Self::all();
        let Some(names) = names else { return Ok(all) };
        let mut keys = Vec::with_capacity(names.len());
        for n in names {
            let Some(k) = all.keys.iter().find(|(k, _)| *k == n) else {
                return Err(PyValueError::new_err(format!(
                    "unknown output {:?}: expected one of {}",
                    muscle_actuator::text::excerpt(&n),
                    all.keys
                        .iter()
                        .map(|(k, _)| k.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )));
            };
            if keys.iter().any(|(k, _): &(String, Source)| *k == n) {
                return Err(PyValueError::new_err(format!("output {n:?} named twice")));
            }
            keys.push(k.clone());
        }
        Ok(Self { keys })
    }

    /// Values per tick of each output for `m` muscles and `j` joints.
    pub fn widths(&self, m: usize, j: usize) -> Vec<usize> {
        self.keys
            .iter()
            .map(|(_, s)| match s {
                Source::Muscle(_) => m,
                Source::Joint(_) => j,
                Source::StiffnessMatrix => j * j,
            })
            .collect()
    }

    /// The trailing shape of each output for `m` muscles and `j` joints.
    pub fn shapes(&self, m: usize, j: usize) -> Vec<Vec<usize>> {
        self.keys
            .iter()
            .map(|(_, s)| match s {
                Source::Muscle(_) => vec![m],
                Source::Joint(_) => vec![j],
                Source::StiffnessMatrix => vec![j, j],
            })
            .collect()
    }
}

/// Writes tick `t`'s values of every output of `state` into `bufs` (one per output, each
/// `ticks × width` long, `widths` as [`Outputs::widths`]).
pub fn write_tick(
    outputs: &Outputs,
    widths: &[usize],
    state: &Record<'_>,
    t: usize,
    bufs: &mut [&mut [f64]],
) {
    for (i, m) in state.muscles.iter().enumerate() {
        let v = m.values();
        for ((_, s), (buf, w)) in outputs.keys.iter().zip(bufs.iter_mut().zip(widths)) {
            if let Source::Muscle(f) = s {
                buf[t * w + i] = v[*f];
            }
        }
    }
    for (j, joint) in state.joints.iter().enumerate() {
        let v = joint.values();
        for ((_, s), (buf, w)) in outputs.keys.iter().zip(bufs.iter_mut().zip(widths)) {
            if let Source::Joint(f) = s {
                buf[t * w + j] = v[*f];
            }
        }
    }
    for ((_, s), (buf, w)) in outputs.keys.iter().zip(bufs.iter_mut().zip(widths)) {
        if let Source::StiffnessMatrix = s {
            buf[t * w..(t + 1) * w].copy_from_slice(state.stiffness_matrix);
        }
    }
}

/// One buffer per output for `lead` leading entries (instances × ticks) of their widths.
pub fn buffers(outputs: &Outputs, lead: usize, m: usize, j: usize) -> Vec<Vec<f64>> {
    outputs
        .widths(m, j)
        .iter()
        .map(|w| vec![0.0; lead * w])
        .collect()
}

/// The buffers as a dict of numpy arrays of shape `lead ++ trailing shape` (no copy).
pub fn into_dict<'py>(
    py: Python<'py>,
    outputs: &Outputs,
    buffers: Vec<Vec<f64>>,
    lead: &[usize],
    m: usize,
    j: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (((key, _), buf), tail) in outputs.keys.iter().zip(buffers).zip(outputs.shapes(m, j)) {
        let shape: Vec<usize> = lead.iter().chain(&tail).copied().collect();
        let a = PyArray1::from_vec(py, buf).reshape(shape)?;
        d.set_item(key, a)?;
    }
    Ok(d)
}
