//! Why a command failed. `main` prints it as one line after `error: `.

use super::steady::SteadyError;
use crate::figures::FigureError;
use crate::ros::NodeError;
use muscle_actuator_core::config::ConfigError;
use muscle_actuator_core::csv::CsvWriteError;
use muscle_actuator_core::files::OverwritesInput;
use muscle_actuator_core::physics::energetics::params::UnknownEnergyModel;
use muscle_actuator_core::physics::models::UnknownModel;
use muscle_actuator_recording::recording::RecordingError;
use muscle_actuator_recording::runs::RunError;

/// Why a command failed.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// `--model` names no model.
    #[error(transparent)]
    Model(#[from] UnknownModel),
    /// `--energy-model` names no energy model.
    #[error(transparent)]
    EnergyModel(#[from] UnknownEnergyModel),
    /// `--config` cannot be used.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// An output that would overwrite one of the command's inputs.
    #[error(transparent)]
    OutputIsInput(#[from] OverwritesInput),
    /// `--points` out of its rules.
    #[error(transparent)]
    Points(#[from] muscle_actuator_core::sim::steady::SteadyError),
    /// The CSV cannot be written.
    #[error(transparent)]
    Csv(#[from] CsvWriteError),
    /// A recording that cannot be recovered.
    #[error(transparent)]
    Recording(#[from] RecordingError),
    /// A run that cannot be simulated, recorded, exported, replayed or compared.
    #[error(transparent)]
    Run(#[from] RunError),
    /// `simulate` ran no tick.
    #[error("the scenario produced no ticks")]
    NoTicks,
    /// `replay` did not reproduce every recorded state (the counts are printed before).
    #[error("the replay did not reproduce the recorded states")]
    ReplayDiffers,
    /// `compare --json` cannot write its JSON.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
    /// `figures` failed.
    #[error(transparent)]
    Figures(#[from] FigureError),
    /// `steady` failed.
    #[error(transparent)]
    Steady(#[from] SteadyError),
    /// `subject`, `predict` or `calibrate` failed.
    #[error(transparent)]
    Subject(#[from] super::subject::SubjectError),
    /// `node` failed.
    #[error(transparent)]
    Node(#[from] NodeError),
}
