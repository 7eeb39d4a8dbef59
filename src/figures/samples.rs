//! The runs the figures read and the samples they take: a built-in scenario at 1 kHz, the first
//! muscle's signal as a time series or at one time.

use super::error::FigureError;
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::{default_stepping, MuscleSnapshot, Run, Scenario};

/// The built-in scenario `name` with `model` on `cfg`, at 1 kHz with the model's stepping.
pub fn run(name: &str, model: ModelKind, cfg: &ActuatorConfig) -> Result<Run, FigureError> {
    let sc = Scenario::built_in(name, &cfg.muscles[0].params)?;
    sc.run(cfg, model, 1000.0, default_stepping(model))
        .map_err(FigureError::from)
}

/// The first muscle's signal `f` over the run, (time s, value).
pub fn series(run: &Run, f: impl Fn(&MuscleSnapshot) -> f64) -> Vec<(f64, f64)> {
    run.records().map(|r| (r.time, f(&r.muscles[0]))).collect()
}

/// Value of the first muscle's signal at time t (nearest tick).
pub fn at(run: &Run, t: f64, f: impl Fn(&MuscleSnapshot) -> f64) -> f64 {
    let i = ((t * run.rate_hz).round() as usize).min(run.len() - 1);
    f(&run.record(i).muscles[0])
}
