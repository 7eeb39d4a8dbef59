//! The `muscle_actuator` command line: one module per subcommand, each its arguments
//! (`clap::Args`) and its `run`, and this dispatcher. Model names, the default model (one for
//! every command: `ModelKind::DEFAULT`, the node's) and the default sub-stepping in the help
//! come from [`MODELS`](muscle_actuator_core::physics::models::MODELS).
//!
//! A new command is a module here, a variant of [`Command`] and an arm of [`run`].

mod calibrate;
mod common;
mod compare;
mod error;
mod export;
mod models;
mod predict;
mod prediction_run;
mod recover;
mod replay;
mod simulate;
mod staged;
mod steady;
mod subject;

pub use error::{CliError, SteadyError, SubjectError};
pub use models::models_listing;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "muscle_actuator",
    version,
    about = "Muscle actuators driving any limb: Hill and Huxley (Distribution-Moment) models, as a ROS 2 node and offline"
)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// Run a scenario offline (no DDS); record it to MCAP (--out) and/or CSV (--csv).
    Simulate(simulate::Args),
    /// Feed the recorded inputs of a run through a model, tick by tick, and record the result.
    Replay(replay::Args),
    /// Compare two recorded runs: RMS and max differences, peak timing, rise times.
    Compare(compare::Args),
    /// Rewrite a recording cut by a crash (no summary) as a complete, indexed MCAP file holding
    /// everything readable in it.
    Recover(recover::Args),
    /// Write a recording's states as CSV: the columns of `simulate --csv`, one row per recorded
    /// state per muscle.
    Export(export::Args),
    /// Run the ROS 2 node; everything after `node` goes to it (`--ros-args ...`, see `node --help`).
    #[command(disable_help_flag = true)]
    Node {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Reproduce the paper's Figs. 4-6 and the force-velocity comparison as PNG and SVG.
    Figures {
        /// Output directory.
        #[arg(long, default_value = "figures")]
        out: PathBuf,
    },
    /// List the contractile models: name and what it is, one a line.
    Models,
    /// A subject's muscle-tendon units (CEINMS's subject XML, or the project's TOML) written as
    /// the project's TOML subject file (docs/emg.md).
    Subject(subject::Args),
    /// Drive a subject's units through a measured trial (EMG, muscle-tendon lengths, moment
    /// arms) and rate the predicted joint moments against the measured ones: R2, r2, RMSE.
    Predict(predict::Args),
    /// Calibrate a subject's units on trials: bounded parameters fitted by CMA-ES so that the
    /// predicted moments of the degrees of freedom match the measured ones (docs/emg.md).
    Calibrate(calibrate::Args),
    /// One muscle's steady states at full activation and optimal length, shortening velocities
    /// from -vmax to vmax: force, ATP rate, chemical power, heat, work, efficiency, from the
    /// cross-bridges (Huxley models) and each phenomenological energy model.
    Steady(steady::Args),
}

/// Runs one parsed command.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Simulate(a) => simulate::run(a),
        Command::Replay(a) => replay::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Recover(a) => recover::run(a),
        Command::Export(a) => export::run(a),
        Command::Node { args } => Ok(crate::ros::run_node(args)?),
        Command::Figures { out } => Ok(crate::figures::write_all(&out)?),
        Command::Models => {
            print!("{}", models_listing());
            Ok(())
        }
        Command::Subject(a) => Ok(subject::run(a)?),
        Command::Predict(a) => predict::run(a),
        Command::Calibrate(a) => calibrate::run(a),
        Command::Steady(a) => steady::run(a),
    }
}

/// Parses the command line, runs the command, reports an error as one line.
pub fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
