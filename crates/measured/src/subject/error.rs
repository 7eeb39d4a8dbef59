//! Why a trial cannot be driven: each message names the trial, then the unit, time or file.

use crate::measured::resample::ResampleError;
use crate::measured::ExcitationMapError;
use crate::subject::limits::MAX_FIBRE_LOPT;
use muscle_actuator_core::physics::models::ModelBuildError;
use muscle_actuator_core::physics::{ParamError, PlantError};
use muscle_actuator_core::sim::{SetupError, StepError};

/// Why a trial cannot be driven.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DriveError {
    /// No degree of freedom was asked for.
    #[error("no degree of freedom given")]
    NoDof,
    /// A degree of freedom the subject does not have.
    #[error("the subject has no degree of freedom {dof:?}; it has {known}")]
    DofNotInSubject {
        /// The degree of freedom asked for.
        dof: String,
        /// The subject's, joined.
        known: String,
    },
    /// A degree of freedom the trial has no moment or moment arms for.
    #[error(
        "trial {trial}: no moment and moment arms of {dof:?} (no {dof}Torque.txt, {dof}Ma.txt); it has {known}"
    )]
    DofNotInTrial {
        /// The trial.
        trial: String,
        /// The degree of freedom.
        dof: String,
        /// The trial's, joined.
        known: String,
    },
    /// A unit the subject's degree of freedom names but the subject does not describe.
    #[error("the subject has no unit {0:?}")]
    UnitNotInSubject(String),
    /// A unit the excitation map does not drive.
    #[error("the excitation map has no unit {0:?}")]
    UnitNotInMap(String),
    /// A unit the trial gives no length (or, for a degree of freedom, no moment arm) of.
    #[error("trial {trial}: {file} has no column {unit:?}")]
    UnitNotInTrial {
        /// The trial.
        trial: String,
        /// The file that lacks it.
        file: String,
        /// The unit.
        unit: String,
    },
    /// The EMG's samples are not evenly spaced.
    #[error("trial {trial}: emg.txt is not evenly sampled (row {row} is {step_s} s after the one before, the mean step {mean_s} s)")]
    UnevenEmg {
        /// The trial.
        trial: String,
        /// The row (1-based, after the header).
        row: usize,
        /// Its step, s.
        step_s: f64,
        /// The mean step, s.
        mean_s: f64,
    },
    /// The kinematics start before the EMG or end after it.
    #[error("trial {trial}: the kinematics ({lmt_start} to {lmt_end} s) are not within the EMG ({emg_start} to {emg_end} s)")]
    KinematicsOutsideEmg {
        /// The trial.
        trial: String,
        /// First kinematic time, s.
        lmt_start: f64,
        /// Last kinematic time, s.
        lmt_end: f64,
        /// First EMG time, s.
        emg_start: f64,
        /// Last EMG time, s.
        emg_end: f64,
    },
    /// A negative excitation.
    #[error("trial {trial}: the excitation of {unit:?} is negative ({value}) at {time_s} s")]
    NegativeExcitation {
        /// The trial.
        trial: String,
        /// The unit.
        unit: String,
        /// The time, s.
        time_s: f64,
        /// The value.
        value: f64,
    },
    /// The map cannot be applied to the trial's EMG.
    #[error("trial {trial}: {error}")]
    Map {
        /// The trial.
        trial: String,
        /// What is wrong.
        error: ExcitationMapError,
    },
    /// A trial's series cannot be resampled.
    #[error("trial {trial}: {error}")]
    Resample {
        /// The trial.
        trial: String,
        /// What is wrong.
        error: ResampleError,
    },
    /// A unit's parameters break a rule.
    #[error("{}", .0.iter().map(ToString::to_string).collect::<Vec<_>>().join("; "))]
    Params(Vec<ParamError>),
    /// The units cannot be built as a plant.
    #[error("{0}")]
    Plant(String),
    /// The simulation cannot be set up.
    #[error("{0}")]
    Setup(String),
    /// A unit's length leaves its fibre longer than `MAX_FIBRE_LOPT` optimal lengths even with
    /// its tendon at slack: a length no fibre of the unit can take.
    #[error("trial {trial}: unit {unit:?} is {length_m} m long at {time_s} s, which leaves its fibre {fibre_lopt:.2} optimal lengths long even with its tendon at slack (at most {MAX_FIBRE_LOPT}); check the lengths, or the unit's l_ts and l_opt")]
    OutOfReach {
        /// The trial.
        trial: String,
        /// The unit.
        unit: String,
        /// The time, s.
        time_s: f64,
        /// Its length, m.
        length_m: f64,
        /// `(l_mt − l_ts) / l_opt`.
        fibre_lopt: f64,
    },
    /// A tick failed: a unit's length or velocity is one its fibre and tendon cannot follow.
    #[error("trial {trial}, unit {unit:?}, at {time_s} s (length {length_m} m): {error}")]
    Step {
        /// The trial.
        trial: String,
        /// The first unit that fails alone, if one does.
        unit: Option<String>,
        /// The tick's start, s.
        time_s: f64,
        /// The unit's length at the tick's start, m (NaN when no unit fails alone).
        length_m: f64,
        /// What failed.
        error: StepError,
    },
}

impl From<PlantError> for DriveError {
    fn from(e: PlantError) -> Self {
        DriveError::Plant(e.to_string())
    }
}

impl From<SetupError> for DriveError {
    fn from(e: SetupError) -> Self {
        DriveError::Setup(e.to_string())
    }
}

impl From<ModelBuildError> for DriveError {
    fn from(e: ModelBuildError) -> Self {
        DriveError::Plant(e.to_string())
    }
}
