//! Why a scenario cannot be read ([`ScenarioError`]: an unknown name, a file missing, unreadable
//! or not a scenario, a scenario breaking its rules) or run ([`ScenarioRunError`]: its size, the
//! names its inputs give, its driven joints, the simulation's set-up, a failed tick).

use crate::sim::records::RecordMismatch;
use crate::sim::scenario_kinds::{SetupKind, Signal};
use crate::sim::schedule::ScheduleError;
use crate::sim::setup_error::SetupError;
use crate::sim::simulation::StepError;
use crate::text::excerpt;
use std::path::PathBuf;

/// Why a scenario cannot be had by name or read from its file.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// Neither a built-in scenario nor a file.
    #[error(
        "unknown scenario {name:?}: expected one of {} or a scenario file (.toml)",
        .built_in.join(", ")
    )]
    Unknown {
        /// The name given.
        name: String,
        /// The built-in scenarios' names.
        built_in: &'static [&'static str],
    },
    /// A scenario file (a `.toml` path) that does not exist.
    #[error("scenario file {} does not exist", .path.display())]
    FileMissing {
        /// The path.
        path: PathBuf,
    },
    /// The file cannot be read (not a regular file, too large, an I/O error).
    #[error("cannot read scenario file {}: {source}", .path.display())]
    Read {
        /// The path.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not UTF-8 text.
    #[error("cannot read scenario file {}: {source}", .path.display())]
    NotUtf8 {
        /// The path.
        path: PathBuf,
        /// Where the text breaks.
        source: std::string::FromUtf8Error,
    },
    /// The file is not a scenario in TOML.
    #[error("scenario file {}: {message}", .path.display())]
    Parse {
        /// The path.
        path: PathBuf,
        /// The parser's message, with its line and column.
        message: String,
    },
    /// The scenario breaks a rule.
    #[error("scenario file {}: {error}", .path.display())]
    Invalid {
        /// The path.
        path: PathBuf,
        /// The rule broken.
        error: BadScenario,
    },
}

impl ScenarioError {
    /// Whether the scenario file does not exist.
    pub fn is_not_found(&self) -> bool {
        match self {
            ScenarioError::FileMissing { .. } => true,
            ScenarioError::Read { source, .. } => source.kind() == std::io::ErrorKind::NotFound,
            _ => false,
        }
    }

    /// Whether the name is no built-in scenario (and no file).
    pub fn is_unknown_name(&self) -> bool {
        matches!(self, ScenarioError::Unknown { .. })
    }
}

/// A rule a scenario breaks.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BadScenario {
    /// A name longer than `crate::sim::scenario::MAX_NAME_CHARS`.
    #[error("name {:?} is longer than {max_chars} characters", excerpt(.name))]
    NameTooLong {
        /// The name.
        name: String,
        /// The most characters allowed.
        max_chars: usize,
    },
    /// A duration outside (0, 3600] s.
    #[error("duration = {0} must be in (0, 3600] s")]
    Duration(
        /// The duration, s.
        f64,
    ),
    /// A clamped length that is not a finite number > 0.
    #[error("length = {0} must be a finite number > 0")]
    Length(
        /// The length, m.
        f64,
    ),
    /// An initial force that is not a finite number ≥ 0.
    #[error("initial_force = {0} must be a finite number >= 0")]
    InitialForce(
        /// The force, N.
        f64,
    ),
    /// An input's schedule breaks its rules.
    #[error("input[{index}]: {error}")]
    Schedule {
        /// The input's index.
        index: usize,
        /// The rule broken.
        error: ScheduleError,
    },
    /// An input whose signal the attachment does not have.
    #[error("input[{index}]: signal {signal:?} does not apply to attachment {attachment:?}")]
    SignalNotForAttachment {
        /// The input's index.
        index: usize,
        /// Its signal.
        signal: Signal,
        /// The scenario's attachment.
        attachment: SetupKind,
    },
}

/// Why a scenario cannot be run (or stopped running).
#[derive(Debug, thiserror::Error)]
pub enum ScenarioRunError {
    /// The configuration, the plant or the simulation cannot be set up.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The run's records would take more than `scenario::MAX_RUN_BYTES`.
    #[error(
        "a run of {duration} s at {rate_hz} Hz is {ticks} ticks, whose records ({muscles} \
         muscles, {joints} joints) take about {:.0} MiB, more than the {} MiB a run may \
         hold: shorten the duration or lower the rate",
        .bytes / (1u64 << 20) as f64,
        .max_bytes / (1u64 << 20) as f64
    )]
    TooLarge {
        /// The scenario's duration, s.
        duration: f64,
        /// The tick rate, Hz.
        rate_hz: f64,
        /// Ticks of the run.
        ticks: f64,
        /// Muscles of the limb.
        muscles: usize,
        /// Joints of the limb.
        joints: usize,
        /// Bytes the records would take.
        bytes: f64,
        /// The most bytes a run's records may take.
        max_bytes: f64,
    },
    /// An input names a muscle or joint the scenario's limb does not have.
    #[error(
        "input[{index}]: unknown {what} {:?} (this scenario has {})",
        excerpt(.name),
        names_or_none(.names)
    )]
    UnknownName {
        /// The input's index.
        index: usize,
        /// `muscle` or `joint`.
        what: &'static str,
        /// The name given.
        name: String,
        /// The names the limb has.
        names: Vec<String>,
    },
    /// A torque or angle input in a scenario without joints.
    #[error("input[{index}]: this scenario has no joint")]
    NoJoint {
        /// The input's index.
        index: usize,
    },
    /// A driven joint without a `joint_angle` schedule.
    #[error(
        "joint {:?} is driven: the scenario needs attachment = \"driven\" and a \
         joint_angle input for it",
        excerpt(.joint)
    )]
    DrivenWithoutSchedule {
        /// The joint's name.
        joint: String,
    },
    /// An external torque on a driven joint.
    #[error("joint {:?} is driven: an external torque on it has no effect", excerpt(.joint))]
    DrivenWithTorque {
        /// The joint's name.
        joint: String,
    },
    /// A tick failed.
    #[error(transparent)]
    Step(#[from] StepError),
    /// A record does not fit the run.
    #[error(transparent)]
    Record(#[from] RecordMismatch),
}

impl ScenarioRunError {
    /// Whether an input names a muscle or joint the limb does not have.
    pub fn is_unknown_name(&self) -> bool {
        matches!(self, ScenarioRunError::UnknownName { .. })
    }
}

/// The names on one line, or `none`.
fn names_or_none(names: &[String]) -> String {
    if names.is_empty() {
        "none".to_string()
    } else {
        crate::text::one_line(&names.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::ActuatorConfig;
    use crate::physics::limb_params::MuscleParams;
    use crate::physics::models::ModelKind;
    use crate::sim::scenario::Scenario;
    use crate::sim::simulation::default_stepping;
    use std::path::Path;

    /// An unknown name, a missing file and an unreadable one are told apart, with the same text.
    #[test]
    fn names_and_files_are_told_apart() {
        let p = MuscleParams::default();
        let e = Scenario::resolve("sprint", &p).unwrap_err();
        assert!(e.is_unknown_name() && !e.is_not_found(), "{e}");
        assert_eq!(
            e.to_string(),
            "unknown scenario \"sprint\": expected one of pulse, energy-10hz, energy-100hz or a \
             scenario file (.toml)"
        );
        let e = Scenario::resolve("/nonexistent/s.toml", &p).unwrap_err();
        assert!(e.is_not_found() && !e.is_unknown_name(), "{e}");
        assert_eq!(
            e.to_string(),
            "scenario file /nonexistent/s.toml does not exist"
        );
        let e = Scenario::from_file(Path::new("/nonexistent/s.toml")).unwrap_err();
        assert!(e.is_not_found(), "{e}");
        let e = Scenario::from_file(Path::new("/")).unwrap_err();
        assert!(matches!(e, ScenarioError::Read { .. }) && !e.is_not_found());
        assert!(
            e.to_string().starts_with("cannot read scenario file /: "),
            "{e}"
        );
    }

    /// An input naming a muscle the limb does not have is an unknown name.
    #[test]
    fn an_unknown_input_name_is_told_apart() {
        let mut sc = Scenario::built_in("pulse", &MuscleParams::default()).unwrap();
        sc.inputs[0].muscle = Some("biceps".into());
        let cfg = ActuatorConfig::default();
        let hill = ModelKind::HILL;
        let e = sc
            .run(&cfg, hill, 1000.0, default_stepping(hill))
            .unwrap_err();
        assert!(e.is_unknown_name(), "{e}");
        assert_eq!(
            e.to_string(),
            "input[0]: unknown muscle \"biceps\" (this scenario has flexor)"
        );
        sc.inputs[0].muscle = None;
        let e = sc
            .run(&cfg, hill, -1.0, default_stepping(hill))
            .unwrap_err();
        assert!(
            matches!(e, ScenarioRunError::Setup(SetupError::Rate(_))) && !e.is_unknown_name(),
            "{e}"
        );
    }
}
