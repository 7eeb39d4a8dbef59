//! What the runs' commands report ([`RunError`]): `simulate --out`, `replay`, `compare`,
//! `export`, each error naming the file or the number at fault; and what `compare` and `export`
//! find wrong with runs they read ([`CompareError`], [`ExportError`]).

use super::channels::Channel;
use super::limits::LimitError;
use super::load::LoadError;
use super::metadata::{BuildError, MetadataError};
use crate::recording::schema::SchemaError;
use crate::recording::{CdrError, RecordingError};
use muscle_actuator_core::config::StepperError;
use muscle_actuator_core::csv::CsvWriteError;
use muscle_actuator_core::files::OverwritesInput;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::{RecordMismatch, ScenarioError, ScenarioRunError, StepError};
use muscle_actuator_core::text::excerpt;
use std::io;
use std::path::PathBuf;

/// Why two runs cannot be compared.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CompareError {
    /// The runs have different muscles (in any order).
    #[error(
        "the runs cannot be compared: different muscles ({} vs {})",
        excerpt(&.a.join(", ")),
        excerpt(&.b.join(", "))
    )]
    DifferentMuscles {
        /// Run A's muscles.
        a: Vec<String>,
        /// Run B's muscles.
        b: Vec<String>,
    },
    /// The runs have different joints (in any order).
    #[error(
        "the runs cannot be compared: different joints ([{}] vs [{}])",
        excerpt(&.a.join(", ")),
        excerpt(&.b.join(", "))
    )]
    DifferentJoints {
        /// Run A's joints.
        a: Vec<String>,
        /// Run B's joints.
        b: Vec<String>,
    },
    /// A run has no state to compare.
    #[error("the runs cannot be compared: a run holds no actuator state")]
    NoStates,
    /// The runs' spans of time do not overlap.
    #[error(
        "the runs cannot be compared: no overlap in time (A {}..{} s, B {}..{} s)",
        .a.0, .a.1, .b.0, .b.1
    )]
    NoOverlap {
        /// Run A's first and last state times, s.
        a: (f64, f64),
        /// Run B's first and last state times, s.
        b: (f64, f64),
    },
    /// A figure of the comparison is not finite.
    #[error(
        "the runs cannot be compared: {} has no finite {figure} ({value}): values too large to \
         difference, or no sample inside the common span",
        excerpt(.signal)
    )]
    NotFinite {
        /// The signal (`muscle.force`, ...).
        signal: String,
        /// The figure (`rms diff`, `peak A`, ...).
        figure: &'static str,
        /// Its value.
        value: f64,
    },
}

/// Why a recorded run's states do not make a table (the file is named by [`RunError::Export`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// The recording holds no `~/state` message.
    #[error("the recording holds no actuator state")]
    NoStates,
    /// A state does not fit the run's table (muscle, joint or stiffness counts).
    #[error("tick {tick}: {reason}")]
    Record {
        /// The state's tick.
        tick: u64,
        /// Why ([`Run::push_parts`](muscle_actuator_core::sim::Run::push_parts)).
        #[source]
        reason: RecordMismatch,
    },
}

/// Why a run could not be simulated, recorded, loaded, replayed, compared or exported.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The recorder could not create or start writing the output.
    #[error(transparent)]
    Recording(#[from] RecordingError),
    /// A run file could not be loaded (missing, unreadable, damaged, not a fit run).
    #[error(transparent)]
    Load(#[from] LoadError),
    /// A recording without any `~/state` message, where states are needed.
    #[error("{}: the recording holds no actuator state", path.display())]
    NoStates {
        /// The recording.
        path: PathBuf,
    },
    /// A recording whose states do not make a table.
    #[error("{}: {source}", path.display())]
    Export {
        /// The recording.
        path: PathBuf,
        /// Why.
        #[source]
        source: ExportError,
    },
    /// `replay` of a force-driven run, whose tendon-force input is not recorded.
    #[error(
        "{}: a force-driven run (its tendon-force input is not a recorded topic) cannot be \
         replayed",
        path.display()
    )]
    ForceDriven {
        /// The recording.
        path: PathBuf,
    },
    /// Two runs that cannot be compared.
    #[error(transparent)]
    Compare(#[from] CompareError),
    /// The comparison's plot could not be drawn (the figures' own text).
    #[error("{0}")]
    Plot(String),
    /// An output named is one of the command's inputs.
    #[error(transparent)]
    OutputIsInput(#[from] OverwritesInput),
    /// The CSV table could not be written.
    #[error(transparent)]
    Csv(#[from] CsvWriteError),
    /// The scenario could not be resolved (an unknown name, a missing or bad file).
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// The scenario could not be set up or run.
    #[error(transparent)]
    ScenarioRun(#[from] ScenarioRunError),
    /// A tick of the scenario failed.
    #[error(transparent)]
    ScenarioStep(StepError),
    /// A state of the scenario did not fit its table.
    #[error(transparent)]
    Record(#[from] RecordMismatch),
    /// The simulation of the recorded run could not be built.
    #[error(transparent)]
    Build(#[from] BuildError),
    /// The configuration's `[stepper]` table with fixed sub-steps (`--substeps`, or a model
    /// that steps only so).
    #[error(transparent)]
    Stepper(#[from] StepperError),
    /// A rate or sub-steps out of their limits.
    #[error(transparent)]
    Limit(#[from] LimitError),
    /// The run's metadata could not be written or read back.
    #[error(transparent)]
    Metadata(#[from] MetadataError),
    /// A channel's schema could not be assembled.
    #[error(transparent)]
    Schema(#[from] SchemaError),
    /// A message could not be serialized.
    #[error(transparent)]
    Cdr(#[from] CdrError),
    /// A tick of the replay failed.
    #[error("replay with {model} failed at tick {tick}: {source}")]
    Step {
        /// The model replayed with.
        model: ModelKind,
        /// The tick that failed.
        tick: u64,
        /// Why.
        #[source]
        source: StepError,
    },
    /// The output (or its directory) could not be created or renamed into place.
    #[error("recording {}: {source}", path.display())]
    Output {
        /// The output.
        path: PathBuf,
        /// The reason, with its [`io::ErrorKind`].
        #[source]
        source: io::Error,
    },
    /// The recorder stopped on an error (its report, naming the output).
    #[error("{0}")]
    RecorderFailed(String),
    /// The recorder stopped without an error while the run was being written.
    #[error("the recording stopped")]
    RecorderStopped,
    /// The run writer has no channel for what it was asked to write (a bug).
    #[error("internal error: no {0:?} channel in this recording")]
    NoChannel(Channel),
}

impl RunError {
    /// Whether a file read (a recording) does not exist.
    pub fn is_not_found(&self) -> bool {
        matches!(self, Self::Load(e) if e.is_not_found())
    }

    /// Whether a recording was read but refused: damaged, not MCAP, not a run of this program,
    /// not fit for replay or compare, or without states.
    pub fn is_invalid_recording(&self) -> bool {
        match self {
            Self::Load(e) => e.is_invalid_recording(),
            Self::NoStates { .. } | Self::Export { .. } => true,
            _ => false,
        }
    }

    /// The [`io::ErrorKind`] of a file that could not be read or created.
    pub fn io_kind(&self) -> Option<io::ErrorKind> {
        match self {
            Self::Recording(e) | Self::Load(LoadError::Recording(e)) => e.io_kind(),
            Self::Output { source, .. } => Some(source.kind()),
            _ => None,
        }
    }
}
