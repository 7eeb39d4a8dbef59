//! What several commands share: the help texts built from the model registry, the model and
//! configuration options parsed, and the rule that no output overwrites an input.

use super::CliError;
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::{join, ModelKind};
use muscle_actuator_core::physics::{EnergyModel, Stepping};
use std::path::{Path, PathBuf};

/// The default `--model` of every command: the registry's default, the node's (the
/// Distribution-Moment model, the paper's subject).
pub(super) fn default_model() -> &'static str {
    ModelKind::DEFAULT.name()
}

/// Help of every `--model`.
pub(super) fn model_help() -> String {
    format!(
        "Contractile model: {}",
        ModelKind::names_joined(", ", " or ")
    )
}

/// Help of `simulate --substeps`: each model's default stepping.
pub(super) fn substeps_help() -> String {
    let adaptive = ModelKind::all().filter(|m| m.spec().stepping.is_adaptive());
    let mut defaults = vec![format!(
        "adaptive for {}",
        join(adaptive.map(|m| m.name()), ", ", " and ")
    )];
    for m in ModelKind::all() {
        if let Stepping::Fixed(n) = m.spec().stepping {
            defaults.push(format!("{n} for {m}"));
        }
    }
    format!(
        "Fixed number of implicit (TR-BDF2) sub-steps per tick (default: {}; a configuration's \
         [stepper] table sets the adaptive ones' tolerance, and is refused with --substeps)",
        defaults.join(", ")
    )
}

/// The help of `--energy-model`, from the list of energy models.
pub(super) fn energy_model_help() -> String {
    format!(
        "Phenomenological energy model of every muscle: {} (default: each muscle's \
         energetics.energy_model in the configuration, umberger unless set)",
        EnergyModel::names()
    )
}

/// A `--model` by name.
pub(super) fn parse_model(name: &str) -> Result<ModelKind, CliError> {
    Ok(name.parse()?)
}

/// A `--config` (a built-in name or a file; the default limb when absent), its warnings on
/// standard error.
pub(super) fn load_config(path: &Option<PathBuf>) -> Result<ActuatorConfig, CliError> {
    let cfg = match path {
        Some(p) => ActuatorConfig::resolve(&p.to_string_lossy())?,
        None => ActuatorConfig::default(),
    };
    for w in cfg.warnings() {
        eprintln!("warning: {w}");
    }
    Ok(cfg)
}

/// `cfg` with every muscle's energy model set to `name`, if one is given.
pub(super) fn with_energy_model(
    cfg: ActuatorConfig,
    name: Option<&str>,
) -> Result<ActuatorConfig, CliError> {
    match name {
        Some(n) => Ok(cfg.with_energy_model(n.parse()?)),
        None => Ok(cfg),
    }
}

/// Refuses an output that would overwrite one of `inputs` ([`muscle_actuator_core::files::check_not_an_input`]).
pub(super) fn check_not_an_input(out: &Path, inputs: &[&Path]) -> Result<(), CliError> {
    muscle_actuator_core::files::check_not_an_input(out, inputs).map_err(CliError::from)
}

/// The files among `paths` that exist (a scenario or configuration named by path rather than
/// as a built-in), which no output may overwrite.
pub(super) fn read_files<'a>(paths: &[Option<&'a Path>]) -> Vec<&'a Path> {
    paths
        .iter()
        .flatten()
        .copied()
        .filter(|p| p.is_file())
        .collect()
}
