//! `replay`: a recorded run's inputs fed back, at their ticks, through a model (the recorded one
//! by default, which gives every recorded state back bit for bit), and recorded again.

use super::error::RunError;
use super::load::{load_run, InputsAt, JointMotionAt, LoadedRun};
use super::metadata::{AttachmentMeta, RunMeta};
use super::writer::RunWriter;
use crate::msgs::muscle_actuator_msgs::ActuatorState;
use crate::msgs::state_messages;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::Stepping;
use muscle_actuator_core::sim::{Simulation, StateSnapshot};
use muscle_actuator_core::text::excerpt;
use muscle_actuator_core::time::{now_ns, TimeBase};
use std::collections::BTreeMap;
use std::path::Path;

/// What a replay did.
#[derive(Debug, Clone, PartialEq)]
pub struct ReplaySummary {
    /// The model the inputs were fed through.
    pub model: ModelKind,
    /// Ticks simulated.
    pub ticks: u64,
    /// Recorded states compared with the replay (same model only).
    pub compared: u64,
    /// Of those, identical in every field bit for bit (header stamps aside).
    pub identical: u64,
    /// The first tick that differed.
    pub first_difference: Option<u64>,
    /// The input was cut by a crash and read up to the cut: what was read.
    pub warning: Option<String>,
}

/// The bits of a state's simulated fields (everything but the header), iterating the field
/// lists.
fn state_bits(s: &ActuatorState) -> Vec<u64> {
    let mut v = vec![s.tick];
    for j in &s.joints {
        v.extend(j.values().iter().map(|x| x.to_bits()));
    }
    v.extend(s.stiffness_matrix.iter().map(|x| x.to_bits()));
    for m in &s.muscles {
        v.extend(m.state.values().iter().map(|x| x.to_bits()));
    }
    v
}

/// A run's recorded inputs, handed to a simulation tick by tick as the run applied them.
struct RecordedInputs<'a> {
    activations: std::iter::Peekable<std::slice::Iter<'a, InputsAt>>,
    loads: std::iter::Peekable<std::slice::Iter<'a, InputsAt>>,
    motions: std::iter::Peekable<std::slice::Iter<'a, JointMotionAt>>,
    /// Per joint of the simulation, whether it is driven.
    driven: Vec<bool>,
}

impl<'a> RecordedInputs<'a> {
    fn new(run: &'a LoadedRun, sim: &Simulation) -> Self {
        Self {
            activations: run.activations.iter().peekable(),
            loads: run.loads.iter().peekable(),
            motions: run.joint_motions.iter().peekable(),
            driven: sim.plant().joints.iter().map(|j| j.driven).collect(),
        }
    }

    /// Applies the inputs recorded for ticks up to `tick` not applied yet: excitations and
    /// torques are held; a driven joint's motion carries on from where the last tick's
    /// extrapolation ended until the next one recorded. Names the run does not have, values
    /// that are not finite and motion for joints that are not driven are passed over, as the
    /// run passed them over.
    fn apply(&mut self, tick: u64, meta: &RunMeta, sim: &mut Simulation) {
        let driven = &self.driven;
        let inputs = sim.inputs_mut();
        let muscle = |n: &String| meta.muscles.iter().position(|m| m == n);
        let joint = |n: &String| meta.joints.iter().position(|m| m == n);
        while let Some((_, names, values)) = self.activations.next_if(|a| a.0 <= tick) {
            for (n, u) in names.iter().zip(values) {
                if let Some(slot) = muscle(n).and_then(|i| inputs.excitation.get_mut(i)) {
                    if u.is_finite() {
                        *slot = u.clamp(0.0, 1.0);
                    }
                }
            }
        }
        while let Some((_, names, values)) = self.loads.next_if(|l| l.0 <= tick) {
            for (n, t) in names.iter().zip(values) {
                if let Some(slot) = joint(n).and_then(|j| inputs.external_torque.get_mut(j)) {
                    if t.is_finite() {
                        *slot = *t;
                    }
                }
            }
        }
        while let Some((_, names, angles, velocities)) = self.motions.next_if(|m| m.0 <= tick) {
            for ((n, a), w) in names.iter().zip(angles).zip(velocities) {
                if let Some(j) = joint(n).filter(|&j| driven.get(j) == Some(&true)) {
                    if a.is_finite() && w.is_finite() {
                        inputs.joint_angle[j] = *a;
                        inputs.joint_velocity[j] = *w;
                    }
                }
            }
        }
    }
}

/// The metadata of the replay of `input` (recorded as `meta`) with `model` and `stepping`: an
/// offline run, started now, on simulated time.
fn replay_meta(input: &Path, meta: &RunMeta, model: ModelKind, stepping: Stepping) -> RunMeta {
    let mut out = meta.clone();
    out.model = model;
    out.stepping = stepping;
    out.source = format!("replay of {} ({})", input.display(), excerpt(&meta.source));
    out.start_time_ns = now_ns();
    out.time_base = TimeBase::Simulated;
    out.parameters_json = None;
    out
}

/// Feeds the recorded inputs of `input` at their ticks through `model` (default: the recorded
/// one) and records the result to `out`. With the recorded model (and its recorded stepping)
/// every recorded state comes back bit for bit (the summary says how many were compared and
/// matched); another model steps as the recorded configuration's `[stepper]` table says.
pub fn replay(
    input: &Path,
    model: Option<ModelKind>,
    out: &Path,
) -> Result<ReplaySummary, RunError> {
    muscle_actuator_core::files::check_not_an_input(out, &[input])?;
    let run = load_run(input)?;
    let meta = &run.meta;
    if let AttachmentMeta::Force { .. } = meta.attachment {
        return Err(RunError::ForceDriven {
            path: input.to_path_buf(),
        });
    }
    let last_tick = (run.states.last().map(|s| s.tick)).ok_or_else(|| RunError::NoStates {
        path: input.to_path_buf(),
    })?;
    let model = model.unwrap_or(meta.model);
    let stepping = if model == meta.model {
        meta.stepping
    } else {
        meta.config.stepping(model, None)?
    };
    let mut sim = meta.build(model, stepping)?;
    let mut w = RunWriter::start(out, &replay_meta(input, meta, model, stepping))?;
    let mut by_tick: BTreeMap<u64, &ActuatorState> = BTreeMap::new();
    for s in &run.states {
        by_tick.insert(s.tick, s);
    }
    let mut summary = ReplaySummary {
        model,
        ticks: last_tick,
        compared: 0,
        identical: 0,
        first_difference: None,
        warning: run.warning.clone(),
    };
    let mut check = |tick: u64, state: &StateSnapshot| {
        if model != meta.model {
            return;
        }
        if let Some(rec) = by_tick.get(&tick) {
            let (mine, _) = state_messages(0, model.name(), tick, &meta.muscles, &rec.joint, state);
            summary.compared += 1;
            if state_bits(&mine) == state_bits(rec) {
                summary.identical += 1;
            } else if summary.first_difference.is_none() {
                summary.first_difference = Some(tick);
            }
        }
    };
    let mut inputs = RecordedInputs::new(&run, &sim);
    // The inputs of tick 0 first: an offline run's state at tick 0 shows them.
    inputs.apply(0, meta, &mut sim);
    let mut state = StateSnapshot::default();
    sim.fill_snapshot(&mut state);
    if by_tick.contains_key(&0) {
        w.state(0, &state)?;
        check(0, &state);
    }
    for k in 0..last_tick {
        inputs.apply(k, meta, &mut sim);
        w.inputs(k, sim.inputs())?;
        sim.step().map_err(|source| RunError::Step {
            model,
            tick: k,
            source,
        })?;
        sim.fill_snapshot(&mut state);
        w.state(k + 1, &state)?;
        check(k + 1, &state);
    }
    w.finish()?;
    Ok(summary)
}
