//! `predict --out`: a subject's units driven through a measured trial
//! ([`PreparedTrial::run_observed`]) recorded as an ordinary run: the units on their driven
//! length coordinates ([`PreparedTrial::config`], [`AttachmentMeta::Driven`]), the tick rate the
//! EMG's, every tick's excitations and driven joints' motion on the input topics and its state,
//! so that `replay`, `compare`, `export` and Foxglove read it as a `simulate --out` run.
//!
//! Tick 0 of the recording is the trial's first EMG sample ([`PreparedTrial::start_s`], named in
//! the metadata's `source`). As every offline run, the state at tick 0 shows the inputs of
//! tick 0 (the first excitations and the first tick's motion) applied to the run at rest.
//!
//! The drive shows each tick's applied inputs beside the simulation after it, and those are what
//! is recorded, so that `replay` gives every state back bit for bit
//! (`tests/subject_recording.rs`).

use super::error::RunError;
use super::limits;
use super::metadata::{AttachmentMeta, BuildError, RunMeta};
use super::writer::RunWriter;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::params::MuscleParams;
use muscle_actuator_core::physics::plant::Inputs;
use muscle_actuator_core::sim::simulation::{Simulation, Stepping};
use muscle_actuator_core::subject::{DriveError, Prediction, PreparedTrial};
use muscle_actuator_core::time::{now_ns, TimeBase};
use std::path::Path;

/// Why a prediction could not be recorded.
#[derive(Debug, thiserror::Error)]
pub enum PredictionRunError {
    /// The trial could not be driven.
    #[error(transparent)]
    Drive(#[from] DriveError),
    /// The run could not be recorded.
    #[error(transparent)]
    Run(#[from] RunError),
}

/// A recorded prediction not yet under its name: [`PredictionRecording::commit`] finishes the
/// file and renames it into place; dropped instead, it leaves nothing behind (so that a command
/// may still fail after the drive, on its other outputs, without leaving the recording).
#[must_use = "the recording is written under its name only by commit"]
pub struct PredictionRecording {
    writer: RunWriter,
}

impl PredictionRecording {
    /// Finishes the recording and renames it into place.
    pub fn commit(self) -> Result<(), RunError> {
        self.writer.finish()
    }
}

/// The metadata of the prediction of `prepared` with `params` under `model` and `stepping`: a
/// driven run of the units' length coordinates, at rest at their first lengths.
pub fn prediction_meta(
    prepared: &PreparedTrial,
    params: &[MuscleParams],
    model: ModelKind,
    stepping: Stepping,
) -> RunMeta {
    let config = prepared.config(params);
    let topology = config.topology();
    RunMeta {
        source: format!(
            "predict {}, tick 0 at t = {} s of the trial",
            prepared.name, prepared.start_s
        ),
        model,
        rate_hz: prepared.rate_hz,
        stepping,
        attachment: AttachmentMeta::Driven,
        initial_joint_motion: (config.joints.iter())
            .map(|j| (j.initial_angle, 0.0))
            .collect(),
        config,
        parameters_json: None,
        start_time_ns: now_ns(),
        time_base: TimeBase::Simulated,
        muscles: topology.muscle_names(),
        joints: topology.joint_names(),
    }
}

/// Drives the units of `prepared` with `params` (one per unit, in order) under `model` through
/// the trial ([`PreparedTrial::run_observed`]) and records every tick to `out`, written under a
/// temporary name until [`PredictionRecording::commit`]. A drive that fails leaves nothing.
pub fn record_prediction(
    prepared: &PreparedTrial,
    params: &[MuscleParams],
    model: ModelKind,
    stepping: Stepping,
    out: &Path,
) -> Result<(Prediction, PredictionRecording), PredictionRunError> {
    limits::check_rate_hz("the EMG's rate", prepared.rate_hz).map_err(RunError::from)?;
    limits::check_stepping("the stepping", stepping).map_err(RunError::from)?;
    let meta = prediction_meta(prepared, params, model, stepping);
    let writer = RunWriter::start(out, &meta)?;
    let mut ticks = TickWriter {
        writer,
        meta,
        observed: 0,
        error: None,
    };
    let prediction = prepared.run_observed(params, model, stepping, |sim, applied| {
        ticks.observe(sim, applied)
    })?;
    if let Some(e) = ticks.error {
        return Err(e.into());
    }
    Ok((
        prediction,
        PredictionRecording {
            writer: ticks.writer,
        },
    ))
}

/// Writes the drive tick by tick as [`PreparedTrial::run_observed`] shows it the simulation: at
/// rest, then after each tick.
struct TickWriter {
    writer: RunWriter,
    meta: RunMeta,
    /// Simulations observed so far (the first at rest).
    observed: u64,
    /// The first error: the drive runs on, nothing more is written.
    error: Option<RunError>,
}

impl TickWriter {
    fn observe(&mut self, sim: &Simulation, applied: &Inputs) {
        if self.error.is_none() {
            if let Err(e) = self.write(sim, applied) {
                self.error = Some(e);
            }
        }
        self.observed += 1;
    }

    /// After tick k (the observation k + 1): the inputs of tick k, the state after it; after
    /// tick 0 first the state at tick 0 (the run at rest with tick 0's inputs).
    fn write(&mut self, sim: &Simulation, applied: &Inputs) -> Result<(), RunError> {
        let Some(k) = self.observed.checked_sub(1) else {
            return Ok(());
        };
        if k == 0 {
            let state0 = self.state_zero(applied)?;
            self.writer.state(0, &state0.snapshot())?;
        }
        self.writer.inputs(k, applied)?;
        self.writer.state(k + 1, &sim.snapshot())
    }

    /// The run at rest as `replay` rebuilds it from the metadata, with tick 0's inputs.
    fn state_zero(&self, applied: &Inputs) -> Result<Simulation, BuildError> {
        let mut sim = self.meta.build(self.meta.model, self.meta.stepping)?;
        sim.inputs_mut().clone_from(applied);
        Ok(sim)
    }
}
