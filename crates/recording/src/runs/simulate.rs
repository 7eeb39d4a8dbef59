//! `simulate --out`: a scenario run recorded as it is simulated.

use super::error::RunError;
use super::limits;
use super::metadata::{driven_motion, AttachmentMeta, RunMeta};
use super::writer::RunWriter;
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::Stepping;
use muscle_actuator_core::sim::{Run, Scenario, SetupKind};
use muscle_actuator_core::time::{now_ns, TimeBase};
use std::path::Path;

/// `simulate`'s run: the scenario (a built-in name or a file) with `model` at `rate_hz`, fixed
/// `substeps` per tick or the stepping of the configuration's `[stepper]` table (by default the
/// model's; [`ActuatorConfig::stepping`]: a `[stepper]` value with fixed sub-steps is refused),
/// recorded to `out` if given. The command line and the Python package both run this, so their
/// numbers are the same.
pub fn run_scenario(
    scenario: &str,
    cfg: &ActuatorConfig,
    model: ModelKind,
    rate_hz: f64,
    substeps: Option<usize>,
    out: Option<&Path>,
) -> Result<Run, RunError> {
    limits::check_rate_hz("--rate-hz", rate_hz)?;
    if let Some(n) = substeps {
        limits::check_substeps("--substeps", n)?;
    }
    let sc = Scenario::resolve(scenario, &cfg.muscles[0].params)?;
    let stepping = cfg.stepping(model, substeps)?;
    match out {
        Some(path) => simulate_to_mcap(&sc, cfg, model, rate_hz, stepping, path),
        None => Ok(sc.run(cfg, model, rate_hz, stepping)?),
    }
}

/// Runs a scenario (as [`Scenario::run`]) and records it to `out`.
pub fn simulate_to_mcap(
    sc: &Scenario,
    cfg: &ActuatorConfig,
    model: ModelKind,
    rate_hz: f64,
    stepping: Stepping,
    out: &Path,
) -> Result<Run, RunError> {
    let mut runner = sc.runner(cfg, model, rate_hz, stepping)?;
    let first = &cfg.muscles[0];
    let attachment = match sc.attachment {
        SetupKind::Joint => AttachmentMeta::Joint,
        SetupKind::Driven => AttachmentMeta::Driven,
        SetupKind::Clamped => AttachmentMeta::Clamped {
            length: sc.length.unwrap_or(first.params.l_opt + first.params.l_ts),
        },
        SetupKind::Force => AttachmentMeta::Force {
            initial_force: sc.initial_force,
        },
    };
    let meta = RunMeta {
        source: format!("simulate {}", sc.name),
        model,
        rate_hz,
        stepping,
        attachment,
        config: sc.limb_config(cfg),
        parameters_json: None,
        start_time_ns: now_ns(),
        time_base: TimeBase::Simulated,
        initial_joint_motion: driven_motion(runner.simulation()),
        muscles: runner.muscle_names().to_vec(),
        joints: runner.joint_names().to_vec(),
    };
    let mut w = RunWriter::start(out, &meta)?;
    let ticks = (sc.duration * rate_hz).round() as u64;
    let mut run = runner.empty_run(ticks as usize + 1);
    runner.keep_record(&mut run)?;
    w.state(0, runner.snapshot())?;
    for k in 0..ticks {
        // The inputs `step` applies: the schedules at the tick's start.
        let inputs = runner.inputs_at(runner.simulation().time());
        w.inputs(k, &inputs)?;
        runner.step().map_err(RunError::ScenarioStep)?;
        runner.keep_record(&mut run)?;
        w.state(k + 1, runner.snapshot())?;
    }
    w.finish()?;
    Ok(run)
}
