//! Reading a run back: a run file's metadata record, states and inputs, decoded and checked
//! ([`super::checks`]); what replay, compare and export start from.

use super::channels::{
    NodeTopic, ACTIVATION_TYPE, APPLIED_ACTIVATION, APPLIED_JOINT_MOTION, APPLIED_LOAD,
    JOINT_STATE_TYPE, LOAD_TYPE, STATE_TYPE,
};
use super::checks::{self, CheckError};
use super::metadata::{MetadataError, RunMeta, METADATA_NAME};
use crate::msgs::muscle_actuator_msgs::{ActivationCommand, ActuatorState, ExternalLoad};
use crate::msgs::JointState;
use crate::recording::RecordingError;
use crate::recording::{self, reader::read_run_file, CdrError, RawMessage, Recording};
use muscle_actuator_core::text::excerpt;
use muscle_actuator_core::time::StampError;
use std::path::{Path, PathBuf};

/// Why a run file could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read as a recording (missing, unreadable, damaged).
    #[error(transparent)]
    Recording(#[from] RecordingError),
    /// The recording reads fine but is not a run of this program, or not a fit one.
    #[error("{}: {source}", path.display())]
    Invalid {
        /// The recording.
        path: PathBuf,
        /// What is wrong with it.
        #[source]
        source: InvalidRun,
    },
}

impl LoadError {
    /// Whether the file does not exist.
    pub fn is_not_found(&self) -> bool {
        matches!(self, Self::Recording(e) if e.is_not_found())
    }

    /// Whether the file was read but refused: damaged, not MCAP, not a run of this program, or
    /// not fit for replay, compare or export.
    pub fn is_invalid_recording(&self) -> bool {
        match self {
            Self::Recording(e) => e.is_damaged(),
            Self::Invalid { .. } => true,
        }
    }
}

/// What makes a recording that reads fine not a run of this program to load (the file is named
/// by [`LoadError::Invalid`]).
#[derive(Debug, thiserror::Error)]
pub enum InvalidRun {
    /// The recording has no `muscle_actuator` metadata record: another program made it.
    #[error("no {METADATA_NAME:?} metadata record: not a muscle_actuator recording")]
    NotOurs,
    /// The metadata record is incomplete or invalid.
    #[error(transparent)]
    Metadata(#[from] MetadataError),
    /// The run recorded is not fit for replay, compare or export.
    #[error(transparent)]
    Check(#[from] CheckError),
    /// A message of ours recorded in another encoding.
    #[error(
        "message on {}: encoding {:?} with a {:?} schema, where {type_name} is recorded as \
         \"cdr\" with a \"ros2msg\" schema",
        excerpt(.topic),
        excerpt(.encoding),
        excerpt(.schema_encoding)
    )]
    Encoding {
        /// The message's topic.
        topic: String,
        /// Its channel's message encoding.
        encoding: String,
        /// Its schema's encoding.
        schema_encoding: String,
        /// Its type.
        type_name: String,
    },
    /// A message of ours that does not decode.
    #[error("message on {}: {source}", excerpt(.topic))]
    Cdr {
        /// The message's topic.
        topic: String,
        /// Why it does not decode.
        #[source]
        source: CdrError,
    },
    /// Driven joints' motion without one position and one velocity per name.
    #[error(
        "message on {}: {names} names with {positions} positions and {velocities} velocities",
        excerpt(.topic)
    )]
    MotionLengths {
        /// The message's topic.
        topic: String,
        /// Names given.
        names: usize,
        /// Positions given.
        positions: usize,
        /// Velocities given.
        velocities: usize,
    },
    /// A message's stamp that is no tick of the run's time base.
    #[error("message on {}: {reason}", excerpt(.topic))]
    Stamp {
        /// The message's topic.
        topic: String,
        /// Why it is no tick ([`muscle_actuator_core::time::TimeBase::tick_of`]).
        #[source]
        reason: StampError,
    },
}

/// A driven joints' motion as applied: (tick, joint names, angles rad, velocities rad/s).
pub type JointMotionAt = (u64, Vec<String>, Vec<f64>, Vec<f64>);
/// Inputs as applied: (tick, names, values).
pub type InputsAt = (u64, Vec<String>, Vec<f64>);

/// A recorded run, decoded: metadata, states by tick, inputs by the tick they take effect.
pub struct LoadedRun {
    /// The run's metadata record.
    pub meta: RunMeta,
    /// The recorded states, by tick.
    pub states: Vec<ActuatorState>,
    /// (tick, muscle names, excitations), in order.
    pub activations: Vec<InputsAt>,
    /// (tick, joint names, torques), in order.
    pub loads: Vec<InputsAt>,
    /// Driven joints' motion as applied, in order.
    pub joint_motions: Vec<JointMotionAt>,
    /// For a file cut by a crash (read up to the cut): the warning naming what was read.
    pub warning: Option<String>,
}

/// Reads a run file: a complete one strictly (damage is an error), one cut by a crash up to the
/// cut, with a warning (`recording::reader::read_run_file`).
pub fn load_run(path: &Path) -> Result<LoadedRun, LoadError> {
    let rec = read_run_file(path)?;
    let mut run = load_from(&rec).map_err(|source| LoadError::Invalid {
        path: path.to_path_buf(),
        source,
    })?;
    run.warning = rec.truncation_warning(path);
    Ok(run)
}

/// Which inputs a run's replay takes: those as the tick loop applied them where the recording
/// has them (a node run), else those on the input topics (an offline run).
struct AppliedTopics {
    activation: bool,
    load: bool,
}

fn load_from(rec: &Recording) -> Result<LoadedRun, InvalidRun> {
    let meta_map = rec.metadata.get(METADATA_NAME).ok_or(InvalidRun::NotOurs)?;
    let meta = RunMeta::from_map(meta_map)?;
    checks::check_state_schema(rec)?;
    let ours = [STATE_TYPE, JOINT_STATE_TYPE, ACTIVATION_TYPE, LOAD_TYPE];
    let applied = |t: NodeTopic| {
        rec.messages
            .iter()
            .any(|m| m.type_name == t.type_name && m.topic.ends_with(t.suffix()))
    };
    let applied = AppliedTopics {
        activation: applied(APPLIED_ACTIVATION),
        load: applied(APPLIED_LOAD),
    };
    let mut run = LoadedRun {
        meta,
        states: Vec::new(),
        activations: Vec::new(),
        loads: Vec::new(),
        joint_motions: Vec::new(),
        warning: None,
    };
    for m in rec
        .messages
        .iter()
        .filter(|m| ours.contains(&m.type_name.as_str()))
    {
        run.take(m, &applied)?;
    }
    run.check(recorded_span_s(rec))?;
    Ok(run)
}

impl LoadedRun {
    /// Every check of [`checks`], on a decoded run whose messages span `recorded_span_s` seconds
    /// of log time.
    fn check(&self, recorded_span_s: f64) -> Result<(), CheckError> {
        checks::check_states(&self.meta, &self.states)?;
        checks::check_inputs("activation", &self.activations)?;
        checks::check_inputs("external load", &self.loads)?;
        checks::check_length(&self.meta, &self.states, recorded_span_s)
    }

    /// Decodes one message of ours and keeps what replay uses of it.
    fn take(&mut self, m: &RawMessage, applied: &AppliedTopics) -> Result<(), InvalidRun> {
        let topic = || m.topic.clone();
        if m.encoding != "cdr" || m.schema_encoding != "ros2msg" {
            return Err(InvalidRun::Encoding {
                topic: topic(),
                encoding: m.encoding.clone(),
                schema_encoding: m.schema_encoding.clone(),
                type_name: m.type_name.clone(),
            });
        }
        let cdr = |source| InvalidRun::Cdr {
            topic: topic(),
            source,
        };
        let stamp = |reason| InvalidRun::Stamp {
            topic: topic(),
            reason,
        };
        let (time_base, rate_hz) = (self.meta.time_base, self.meta.rate_hz);
        match m.type_name.as_str() {
            STATE_TYPE => self
                .states
                .push(recording::decode_cdr::<ActuatorState>(&m.data).map_err(cdr)?),
            // Only the driven joints' motion as applied is used, but a recording whose
            // messages do not decode is not accepted.
            JOINT_STATE_TYPE => {
                let js: JointState = recording::decode_cdr(&m.data).map_err(cdr)?;
                if m.topic.ends_with(APPLIED_JOINT_MOTION.suffix()) {
                    let n = js.name.len();
                    if js.position.len() != n || js.velocity.len() != n {
                        return Err(InvalidRun::MotionLengths {
                            topic: topic(),
                            names: n,
                            positions: js.position.len(),
                            velocities: js.velocity.len(),
                        });
                    }
                    let tick =
                        (time_base.tick_of(js.header.stamp.to_nanos(), rate_hz)).map_err(stamp)?;
                    self.joint_motions
                        .push((tick, js.name, js.position, js.velocity));
                }
            }
            ACTIVATION_TYPE => {
                let a: ActivationCommand = recording::decode_cdr(&m.data).map_err(cdr)?;
                if !applied.activation || m.topic.ends_with(APPLIED_ACTIVATION.suffix()) {
                    let tick =
                        (time_base.tick_of(a.header.stamp.to_nanos(), rate_hz)).map_err(stamp)?;
                    self.activations.push((tick, a.muscle, a.excitation));
                }
            }
            _ => {
                let l: ExternalLoad = recording::decode_cdr(&m.data).map_err(cdr)?;
                if !applied.load || m.topic.ends_with(APPLIED_LOAD.suffix()) {
                    let tick =
                        (time_base.tick_of(l.header.stamp.to_nanos(), rate_hz)).map_err(stamp)?;
                    self.loads.push((tick, l.joint, l.torque));
                }
            }
        }
        Ok(())
    }
}

/// The time from the first message's log time to the last's, s.
fn recorded_span_s(rec: &Recording) -> f64 {
    let times = rec.messages.iter().map(|m| m.log_time);
    match (times.clone().min(), times.max()) {
        (Some(a), Some(b)) => (b - a) as f64 * 1e-9,
        _ => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recording::{Recorder, RecorderOptions, RecorderState};

    /// A missing file, a file that is not MCAP and a recording of another program are each
    /// their own error, with the same texts as ever.
    #[test]
    fn missing_damaged_and_foreign_files_are_told_apart() {
        let dir = std::env::temp_dir().join(format!("load-errors-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();

        let e = load_run(&dir.join("missing.mcap")).err().unwrap();
        assert!(e.is_not_found() && !e.is_invalid_recording(), "{e}");
        assert!(e.to_string().starts_with("cannot read "), "{e}");

        let junk = dir.join("junk.mcap");
        std::fs::write(&junk, b"not mcap").unwrap();
        let e = load_run(&junk).err().unwrap();
        assert!(!e.is_not_found() && e.is_invalid_recording(), "{e}");
        assert!(
            matches!(
                &e,
                LoadError::Recording(RecordingError::NothingReadable { .. })
            ),
            "{e}"
        );

        let foreign = dir.join("foreign.mcap");
        let rec = Recorder::start(&foreign, vec![], vec![], RecorderOptions::default()).unwrap();
        assert_eq!(rec.finish(), RecorderState::Finished);
        let e = load_run(&foreign).err().unwrap();
        assert!(
            matches!(
                &e,
                LoadError::Invalid {
                    source: InvalidRun::NotOurs,
                    ..
                }
            ),
            "{e}"
        );
        assert_eq!(
            e.to_string(),
            format!(
                "{}: no \"muscle_actuator\" metadata record: not a muscle_actuator recording",
                foreign.display()
            )
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
