//! An actuator stepped over per-tick inputs with chosen outputs written after each tick into
//! flat buffers: what the Python package's `Actuator.rollout` and each instance of its batched
//! `rollout` run (docs/python.md), here so that the allocation count of its loop is tested with
//! the node's (tests/no_allocation.rs).
//!
//! The outputs are named by the one field list (`physics::observables`): a `MuscleState` field
//! (`force`: one value per muscle), `joint.` and a joint field (`joint.position`: one per
//! joint), or `stiffness_matrix` (joints × joints, row-major).

use crate::sim::actuator::Actuator;
use crate::sim::records::Record;
use crate::sim::simulation::StepError;
use crate::sim::snapshot::{JointSnapshot, MuscleSnapshot};

/// Where an output's values come from: a field index of [`MuscleSnapshot::FIELDS`] or of
/// [`JointSnapshot::FIELDS`], or the joints' stiffness matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Source {
    /// A field of every muscle: its index in [`MuscleSnapshot::FIELDS`].
    Muscle(usize),
    /// A field of every joint: its index in [`JointSnapshot::FIELDS`].
    Joint(usize),
    /// The joints' stiffness matrix (joints × joints, row-major), N m/rad.
    StiffnessMatrix,
}

/// A chosen list of outputs, by name.
#[derive(Debug, Clone, PartialEq)]
pub struct Outputs {
    /// Each output's name and source, in the order they are written.
    pub keys: Vec<(String, Source)>,
}

/// The prefix of a joint field's output name.
pub(crate) const JOINT_PREFIX: &str = "joint.";

/// Why a list of outputs is refused ([`Outputs::named`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum OutputsError {
    /// A name that is no output (quoted as a short excerpt, with the list of names).
    #[error("unknown output {:?}: expected one of {}", crate::text::excerpt(.0), output_names())]
    Unknown(
        /// The name.
        String,
    ),
    /// A name given twice.
    #[error("output {0:?} named twice")]
    Repeated(
        /// The name.
        String,
    ),
}

/// Every output's name, comma-separated.
fn output_names() -> String {
    Outputs::all()
        .keys
        .iter()
        .map(|(k, _)| k.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

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

    /// The outputs named, in that order (None: all); an unknown name (quoted as a short
    /// excerpt, with the list of names) or a name given twice is refused.
    pub fn named(names: Option<Vec<String>>) -> Result<Self, OutputsError> {
        let all = Self::all();
        let Some(names) = names else { return Ok(all) };
        let mut keys = Vec::with_capacity(names.len());
        for n in names {
            let Some(k) = all.keys.iter().find(|(k, _)| *k == n) else {
                return Err(OutputsError::Unknown(n));
            };
            if keys.iter().any(|(k, _): &(String, Source)| *k == n) {
                return Err(OutputsError::Repeated(n));
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

/// Steps `a` one tick per row of `u` (ticks × muscles: excitations) and `tau` (ticks × joints:
/// external torques, N m), writing the outputs after each tick into `bufs` (one per output,
/// ticks × width). The same ticks as `set_excitation`, `set_external_torque` and `step` called
/// one by one. Stops at the first tick that fails, with its error; the ticks before it are
/// written.
///
/// # Panics
/// If `u` is shorter than `ticks × muscles`, `tau` than `ticks × joints`, or a buffer than
/// `ticks ×` its width (the Python package checks the arrays' shapes before it calls this).
pub fn rollout(
    a: &mut Actuator,
    outputs: &Outputs,
    u: &[f64],
    tau: Option<&[f64]>,
    ticks: usize,
    bufs: &mut [impl AsMut<[f64]>],
) -> Result<(), StepError> {
    let (m, j) = (a.muscle_names().len(), a.joint_names().len());
    let widths = outputs.widths(m, j);
    let mut slices: Vec<&mut [f64]> = bufs.iter_mut().map(|b| b.as_mut()).collect();
    assert!(
        u.len() >= ticks * m,
        "rollout: excitations for fewer than {ticks} ticks"
    );
    assert!(
        tau.is_none_or(|tau| tau.len() >= ticks * j),
        "rollout: torques for fewer than {ticks} ticks"
    );
    assert!(
        slices.len() == widths.len()
            && slices
                .iter()
                .zip(&widths)
                .all(|(s, w)| s.len() >= ticks * w),
        "rollout: output buffers for fewer than {ticks} ticks"
    );
    for t in 0..ticks {
        for (i, &x) in u[t * m..(t + 1) * m].iter().enumerate() {
            a.set_excitation(i, x);
        }
        if let Some(tau) = tau {
            for (k, &x) in tau[t * j..(t + 1) * j].iter().enumerate() {
                a.set_external_torque(k, x);
            }
        }
        a.step()?;
        // The record's time is not among the outputs.
        write_tick(
            outputs,
            &widths,
            &Record::of(0.0, a.state()),
            t,
            &mut slices,
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An unknown output and a repeated one are told apart, with the same text.
    #[test]
    fn unknown_and_repeated_outputs_are_refused() {
        let e = Outputs::named(Some(vec!["pull".into()])).unwrap_err();
        assert_eq!(e, OutputsError::Unknown("pull".into()));
        assert!(e
            .to_string()
            .starts_with("unknown output \"pull\": expected one of "));
        assert!(e.to_string().ends_with(", stiffness_matrix"), "{e}");
        let e = Outputs::named(Some(vec!["force".into(), "force".into()])).unwrap_err();
        assert_eq!(e, OutputsError::Repeated("force".into()));
        assert_eq!(e.to_string(), "output \"force\" named twice");
    }
}
