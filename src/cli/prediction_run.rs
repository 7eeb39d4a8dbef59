//! `predict --out`: a subject's units driven through a measured trial
//! ([`PreparedTrial::run_observed`]) recorded as an ordinary run ([`ObservedRun`]): the units on
//! their driven length coordinates ([`PreparedTrial::config`], [`AttachmentMeta::Driven`]), the
//! tick rate the EMG's, every tick's excitations and driven joints' motion on the input topics
//! and its state (`tests/subject_recording.rs` replays it bit for bit).
//!
//! Tick 0 of the recording is the trial's first EMG sample ([`PreparedTrial::start_s`], named in
//! the metadata's `source`).

use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{MuscleParams, Stepping};
use muscle_actuator_core::time::{now_ns, TimeBase};
use muscle_actuator_measured::subject::{DriveError, Prediction, PreparedTrial};
use muscle_actuator_recording::runs::{AttachmentMeta, ObservedRun, RunError, RunMeta};
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
/// temporary name until [`ObservedRun::commit`]. A drive that fails leaves nothing.
pub fn record_prediction(
    prepared: &PreparedTrial,
    params: &[MuscleParams],
    model: ModelKind,
    stepping: Stepping,
    out: &Path,
) -> Result<(Prediction, ObservedRun), PredictionRunError> {
    let meta = prediction_meta(prepared, params, model, stepping);
    let mut run = ObservedRun::start(out, meta, "the EMG's rate")?;
    let prediction = prepared.run_observed(params, model, stepping, |sim, applied| {
        run.observe(sim, applied)
    })?;
    if let Some(e) = run.take_error() {
        return Err(e.into());
    }
    Ok((prediction, run))
}
