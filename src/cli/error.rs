//! Why a command failed. `main` prints it as one line after `error: `.

use super::steady::SteadyError;
use crate::config::ConfigError;
use crate::figures::FigureError;
use crate::physics::energetics::params::UnknownEnergyModel;
use crate::physics::models::UnknownModel;
use crate::ros::NodeError;

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
    /// The core crate's message: an output that would overwrite an input, `--points` out of
    /// its rules, a CSV that cannot be written.
    #[error("{0}")]
    Core(String),
    /// The recording crate's message: a scenario run, a recording read, written, recovered,
    /// exported, replayed or compared.
    #[error("{0}")]
    Recording(String),
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
    /// `node` failed.
    #[error(transparent)]
    Node(#[from] NodeError),
}
