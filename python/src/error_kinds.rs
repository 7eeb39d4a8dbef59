//! Which Python exception each of the crates' errors raises (docs/python.md#errors), read from
//! the error's variant; the message is the error's text as the command line prints it.
//!
//! - a file that does not exist: `FileNotFound` (also `FileNotFoundError`); one that exists but
//!   cannot be read or written: `OSError`;
//! - an unknown model, muscle, joint, output or scenario name: `UnknownNameError`;
//! - a configuration, scenario, rate or stepping that breaks its rules: `ConfigError`;
//! - an output that would overwrite an input, bad saved-state bytes, a repeated output:
//!   `InputError`;
//! - a recording that reads but is damaged or not a run of this program: `RecordingError`;
//! - a failed tick: `StepError`, with its `tick` and `reason`.
//! - subjects, trials and EMG (docs/python.md "Subjects, EMG and calibration"): a subject or
//!   excitation-map file that is not one, a unit's parameters, the EMG filters' and the
//!   activation's parameters: `ConfigError`; a trial's tables, a trial that cannot be driven
//!   (uneven EMG, kinematics outside it, a negative excitation, a length beyond a unit's
//!   reach), a signal (non-finite, too short, no peak), a rating: `InputError`; a degree of
//!   freedom or unit the subject, the map or the trial does not have: `UnknownNameError`; a
//!   unit's failed tick: `StepError`.

use crate::errors::{with_step_attributes, ErrorKind};
use muscle_actuator_core::config::{ConfigError, StepperError};
use muscle_actuator_core::emg::EmgError;
use muscle_actuator_core::files::OverwritesInput;
use muscle_actuator_core::physics::models::UnknownModel;
use muscle_actuator_core::physics::UnknownEnergyModel;
use muscle_actuator_core::sim::{
    OutputsError, SavedStateError, ScenarioError, ScenarioRunError, SetupError, StepError,
};
use muscle_actuator_core::text::one_line;
use muscle_actuator_measured::measured::rating::RatingError;
use muscle_actuator_measured::measured::MeasuredError;
use muscle_actuator_measured::subject::calibrate::CalibrateError;
use muscle_actuator_measured::subject::{DriveError, SubjectFileError};
use muscle_actuator_recording::recording::RecordingError;
use muscle_actuator_recording::runs::limits::LimitError;
use muscle_actuator_recording::runs::load::LoadError;
use muscle_actuator_recording::runs::RunError;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;

/// An error of the crates as the Python exception it raises.
pub trait ToPyErr: std::fmt::Display {
    /// The exception.
    fn to_py(&self, py: Python<'_>) -> PyErr;
}

/// `e` as its Python exception (for `map_err`).
pub fn py_err<E: ToPyErr>(e: E) -> PyErr {
    Python::attach(|py| e.to_py(py))
}

/// The exception of a file error: `FileNotFound` for a missing file, `OSError` for any other.
fn io_error(kind: std::io::ErrorKind, msg: String) -> PyErr {
    if kind == std::io::ErrorKind::NotFound {
        ErrorKind::FileNotFound.err(msg)
    } else {
        PyOSError::new_err(msg)
    }
}

/// A failed tick with the crate's message `msg`, and its `tick` and `reason`.
fn failed_tick(py: Python<'_>, e: &StepError, msg: String) -> PyErr {
    with_step_attributes(py, ErrorKind::Step.err(msg), e.tick, e.reason, None)
}

impl ToPyErr for ConfigError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        match self {
            // Bytes that are not UTF-8 are the file's content, not its access.
            ConfigError::Io { kind, .. } if *kind != std::io::ErrorKind::InvalidData => {
                io_error(*kind, self.to_string())
            }
            _ if self.is_unknown_name() => ErrorKind::UnknownName.err(self.to_string()),
            _ => ErrorKind::Config.err(self.to_string()),
        }
    }
}

impl ToPyErr for StepperError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        ErrorKind::Config.err(self.to_string())
    }
}

impl ToPyErr for ScenarioError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        match self {
            _ if self.is_not_found() => ErrorKind::FileNotFound.err(self.to_string()),
            ScenarioError::Read { source, .. } => io_error(source.kind(), self.to_string()),
            _ if self.is_unknown_name() => ErrorKind::UnknownName.err(self.to_string()),
            _ => ErrorKind::Config.err(self.to_string()),
        }
    }
}

impl ToPyErr for ScenarioRunError {
    fn to_py(&self, py: Python<'_>) -> PyErr {
        match self {
            ScenarioRunError::Step(e) => failed_tick(py, e, self.to_string()),
            ScenarioRunError::Setup(e) => e.to_py(py),
            _ if self.is_unknown_name() => ErrorKind::UnknownName.err(self.to_string()),
            _ => ErrorKind::Config.err(self.to_string()),
        }
    }
}

impl ToPyErr for SetupError {
    fn to_py(&self, py: Python<'_>) -> PyErr {
        match self {
            SetupError::Config(e) => e.to_py(py),
            _ => ErrorKind::Config.err(self.to_string()),
        }
    }
}

impl ToPyErr for UnknownModel {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        ErrorKind::UnknownName.err(self.to_string())
    }
}

impl ToPyErr for UnknownEnergyModel {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        ErrorKind::UnknownName.err(self.to_string())
    }
}

impl ToPyErr for LimitError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        ErrorKind::Config.err(self.to_string())
    }
}

impl ToPyErr for OutputsError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        match self {
            OutputsError::Unknown(_) => ErrorKind::UnknownName.err(self.to_string()),
            OutputsError::Repeated(_) => ErrorKind::Input.err(self.to_string()),
        }
    }
}

impl ToPyErr for OverwritesInput {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        ErrorKind::Input.err(self.to_string())
    }
}

impl ToPyErr for SavedStateError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        ErrorKind::Input.err(self.to_string())
    }
}

impl ToPyErr for RecordingError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        match self.io_kind() {
            Some(kind) => io_error(kind, self.to_string()),
            None => ErrorKind::Recording.err(self.to_string()),
        }
    }
}

impl ToPyErr for LoadError {
    fn to_py(&self, py: Python<'_>) -> PyErr {
        match self {
            LoadError::Recording(e) => e.to_py(py),
            LoadError::Invalid { .. } => ErrorKind::Recording.err(self.to_string()),
        }
    }
}

impl ToPyErr for RunError {
    fn to_py(&self, py: Python<'_>) -> PyErr {
        let msg = || self.to_string();
        match self {
            RunError::Recording(e) => e.to_py(py),
            RunError::Load(e) => e.to_py(py),
            RunError::Scenario(e) => e.to_py(py),
            RunError::ScenarioRun(e) => e.to_py(py),
            RunError::ScenarioStep(e) | RunError::Step { source: e, .. } => {
                failed_tick(py, e, msg())
            }
            RunError::Limit(e) => e.to_py(py),
            RunError::Stepper(e) => e.to_py(py),
            RunError::OutputIsInput(e) => e.to_py(py),
            RunError::Output { source, .. } => io_error(source.kind(), msg()),
            RunError::Csv(e) => io_error(e.io_kind(), msg()),
            RunError::RecorderFailed(_) | RunError::RecorderStopped => PyOSError::new_err(msg()),
            _ => ErrorKind::Recording.err(msg()),
        }
    }
}

/// A subject file that failed to read: `FileNotFound` when it does not exist, else
/// `ConfigError`.
pub fn subject_file_error(e: &SubjectFileError) -> PyErr {
    if e.is_not_found() {
        ErrorKind::FileNotFound.err(e.to_string())
    } else {
        ErrorKind::Config.err(e.to_string())
    }
}

impl ToPyErr for MeasuredError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        match self {
            MeasuredError::Io { kind, .. } => io_error(*kind, self.to_string()),
            MeasuredError::Subject { .. } | MeasuredError::ExcitationMap { .. } => {
                ErrorKind::Config.err(self.to_string())
            }
            MeasuredError::Table { .. } | MeasuredError::Trial { .. } => {
                ErrorKind::Input.err(self.to_string())
            }
        }
    }
}

impl ToPyErr for DriveError {
    fn to_py(&self, py: Python<'_>) -> PyErr {
        drive_error(py, self, self.to_string())
    }
}

/// `e` of the trial in the folder `path`, the folder before its message (as the command line
/// says it).
pub fn drive_error_in(py: Python<'_>, path: &str, e: &DriveError) -> PyErr {
    drive_error(py, e, format!("{path}: {}", one_line(&e.to_string())))
}

/// The exception of `e`'s variant, with the message `msg`.
fn drive_error(py: Python<'_>, e: &DriveError, msg: String) -> PyErr {
    let kind = match e {
        DriveError::Step { error, .. } => return failed_tick(py, error, msg),
        DriveError::DofNotInSubject { .. }
        | DriveError::DofNotInTrial { .. }
        | DriveError::UnitNotInSubject(_)
        | DriveError::UnitNotInMap(_)
        | DriveError::UnitNotInTrial { .. } => ErrorKind::UnknownName,
        DriveError::NoDof
        | DriveError::UnevenEmg { .. }
        | DriveError::KinematicsOutsideEmg { .. }
        | DriveError::NegativeExcitation { .. }
        | DriveError::OutOfReach { .. }
        | DriveError::Map { .. }
        | DriveError::Resample { .. } => ErrorKind::Input,
        DriveError::Params(_) | DriveError::Plant(_) | DriveError::Setup(_) => ErrorKind::Config,
    };
    kind.err(msg)
}

impl ToPyErr for CalibrateError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        match self {
            CalibrateError::Threads(_) => PyOSError::new_err(self.to_string()),
            CalibrateError::Options(_) => ErrorKind::Config.err(self.to_string()),
            CalibrateError::NothingDrives(_) => ErrorKind::Input.err(self.to_string()),
            CalibrateError::Stopped { .. } => {
                pyo3::exceptions::PyKeyboardInterrupt::new_err(self.to_string())
            }
        }
    }
}

impl ToPyErr for EmgError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        match self {
            EmgError::NonFiniteSample { .. }
            | EmgError::TooShort { .. }
            | EmgError::ZeroPeak { .. } => ErrorKind::Input.err(self.to_string()),
            EmgError::SampleRate { .. }
            | EmgError::SamplePeriod { .. }
            | EmgError::Order { .. }
            | EmgError::CutOff { .. }
            | EmgError::BandOrder { .. }
            | EmgError::Normaliser { .. }
            | EmgError::Coefficient { .. }
            | EmgError::NoOtherPeriod { .. }
            | EmgError::Delay { .. }
            | EmgError::DelaySamples { .. }
            | EmgError::ShapeFactor { .. } => ErrorKind::Config.err(self.to_string()),
        }
    }
}

impl ToPyErr for RatingError {
    fn to_py(&self, _py: Python<'_>) -> PyErr {
        ErrorKind::Input.err(self.to_string())
    }
}
