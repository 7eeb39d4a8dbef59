//! `simulate`: a built-in experiment or a scenario file run offline, recorded to MCAP and/or
//! written as CSV.

use super::common::{
    check_not_an_input, default_model, energy_model_help, load_config, model_help, parse_model,
    read_files, substeps_help, with_energy_model,
};
use super::CliError;
use std::path::{Path, PathBuf};

/// What `simulate` is asked.
#[derive(clap::Args)]
pub struct Args {
    /// A built-in scenario (pulse, energy-10hz, energy-100hz) or a scenario file (.toml).
    scenario: String,
    #[arg(long, default_value = default_model(), help = model_help())]
    model: String,
    /// Limb configuration: a built-in name (elbow, arm) or a file (TOML); default: elbow.
    #[arg(long)]
    config: Option<PathBuf>,
    #[arg(long, help = energy_model_help())]
    energy_model: Option<String>,
    /// Tick rate, Hz.
    #[arg(long, default_value_t = 1000.0, allow_negative_numbers = true)]
    rate_hz: f64,
    #[arg(long, help = substeps_help(), allow_negative_numbers = true)]
    substeps: Option<usize>,
    /// CSV output file ('-' for standard output).
    #[arg(long)]
    csv: Option<PathBuf>,
    /// MCAP recording (rosbag2-compatible) of the run.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Runs `simulate`: no output may overwrite an input or another output.
pub(super) fn run(a: Args) -> Result<(), CliError> {
    let mut inputs = read_files(&[Some(Path::new(&a.scenario)), a.config.as_deref()]);
    for o in [&a.csv, &a.out].into_iter().flatten() {
        check_not_an_input(o, &inputs)?;
        inputs.push(o);
    }
    let model = parse_model(&a.model)?;
    let cfg = with_energy_model(load_config(&a.config)?, a.energy_model.as_deref())?;
    let run = muscle_actuator_recording::runs::run_scenario(
        &a.scenario,
        &cfg,
        model,
        a.rate_hz,
        a.substeps,
        a.out.as_deref(),
    )?;
    if let Some(path) = &a.csv {
        muscle_actuator_core::csv::write_csv_to(&run, path)?;
    }
    let last = run.last().ok_or(CliError::NoTicks)?;
    eprintln!(
        "{}: {} ticks of {} at {} Hz; final tendon force {:.3} N, fibre length {:.6} m",
        run.scenario,
        run.len() - 1,
        run.model,
        run.rate_hz,
        last.muscles[0].force,
        last.muscles[0].fiber_length
    );
    Ok(())
}
