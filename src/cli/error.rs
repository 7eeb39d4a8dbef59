//! Why a command failed. `main` prints it as one line after `error: `. The commands' own
//! errors are here too, so that every command module reads this one and none reads another.

use crate::figures::FigureError;
use crate::ros::NodeError;
use muscle_actuator_core::config::ConfigError;
use muscle_actuator_core::csv::CsvWriteError;
use muscle_actuator_core::files::OverwritesInput;
use muscle_actuator_core::physics::models::UnknownModel;
use muscle_actuator_core::physics::UnknownEnergyModel;
use muscle_actuator_core::text::one_line;
use muscle_actuator_measured::measured::rating::RatingError;
use muscle_actuator_measured::measured::MeasuredError;
use muscle_actuator_measured::subject::calibrate::CalibrateError;
use muscle_actuator_measured::subject::{DriveError, SubjectFileError};
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
    Subject(#[from] SubjectError),
    /// `node` failed.
    #[error(transparent)]
    Node(#[from] NodeError),
}

/// Why `steady` failed.
#[derive(Debug, thiserror::Error)]
pub enum SteadyError {
    /// The configuration has no muscle to take by default.
    #[error("the configuration has no muscle")]
    NoMuscle,
    /// `--muscle` names no muscle of the configuration.
    #[error("{}", one_line(&format!("unknown muscle {name:?}: the configuration has {known}")))]
    UnknownMuscle {
        /// The name given, as an excerpt.
        name: String,
        /// The configuration's muscles, as excerpts, joined.
        known: String,
    },
    /// The steady states cannot be computed.
    #[error("muscle {muscle}: {reason}")]
    Table {
        /// The muscle, as an excerpt.
        muscle: String,
        /// Why.
        #[source]
        reason: muscle_actuator_core::sim::steady::SteadyError,
    },
    /// The CSV cannot be written.
    #[error(transparent)]
    Csv(#[from] muscle_actuator_core::csv::CsvWriteError),
}

/// Why a subject command failed.
#[derive(Debug, thiserror::Error)]
pub enum SubjectError {
    /// The subject file.
    #[error(transparent)]
    Subject(#[from] SubjectFileError),
    /// The excitation map or a trial.
    #[error(transparent)]
    Measured(#[from] MeasuredError),
    /// A trial that cannot be driven.
    #[error("{path}: {}", one_line(&.error.to_string()))]
    Drive {
        /// The trial's folder.
        path: String,
        /// What is wrong.
        error: Box<DriveError>,
    },
    /// The calibration cannot run.
    #[error(transparent)]
    Calibrate(#[from] CalibrateError),
    /// A rating that cannot be computed (a constant measured moment).
    #[error("{dof}: {error}")]
    Rating {
        /// The degree of freedom.
        dof: String,
        /// Why.
        error: RatingError,
    },
    /// `--dofs` empty or repeated.
    #[error("--dofs: {0}")]
    Dofs(String),
    /// An output that would overwrite an input.
    #[error(transparent)]
    OutputIsInput(#[from] OverwritesInput),
    /// An output that cannot be written.
    #[error("cannot write {path}: {reason}")]
    Write {
        /// The output.
        path: String,
        /// Why.
        reason: String,
    },
    /// `--threads` or `--evaluations` out of range.
    #[error("{0}")]
    Setting(String),
    /// The calibration was stopped (Ctrl-C); the best found so far was written.
    #[error(
        "calibration stopped after {evaluations} of {of} evaluations; the best so far is in {out}, marked stopped"
    )]
    Stopped {
        /// Evaluations made.
        evaluations: usize,
        /// Evaluations asked.
        of: usize,
        /// The calibrated subject's file, as shown.
        out: String,
    },
}
