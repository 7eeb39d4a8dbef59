//! Reading a run back: a run file's metadata record, states and inputs, decoded and checked
//! ([`super::checks`]); what replay, compare and export start from.

use super::channels::{
    ACTIVATION_TYPE, APPLIED_ACTIVATION_SUFFIX, APPLIED_JOINT_MOTION_SUFFIX, APPLIED_LOAD_SUFFIX,
    JOINT_STATE_TYPE, LOAD_TYPE, STATE_TYPE,
};
use super::checks;
use super::metadata::{RunMeta, METADATA_NAME};
use crate::msgs::muscle_actuator_msgs::{ActivationCommand, ActuatorState, ExternalLoad};
use crate::msgs::JointState;
use crate::recording::{self, reader::read_run_file, RawMessage, Recording};
use muscle_actuator_core::text::excerpt;
use std::path::Path;

/// A driven joints' motion as applied: (tick, joint names, angles rad, velocities rad/s).
pub type JointMotionAt = (u64, Vec<String>, Vec<f64>, Vec<f64>);
/// Inputs as applied: (tick, names, values).
pub type InputsAt = (u64, Vec<String>, Vec<f64>);

/// A recorded run, decoded: metadata, states by tick, inputs by the tick they take effect.
pub struct LoadedRun {
    pub meta: RunMeta,
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
/// cut, with a warning ([`crate::recording::reader::read_run_file`]).
pub fn load_run(path: &Path) -> Result<LoadedRun, String> {
    let rec = read_run_file(path)?;
    let mut run = load_from(&rec).map_err(|e| format!("{}: {e}", path.display()))?;
    run.warning = rec.truncation_warning(path);
    Ok(run)
}

/// Which inputs a run's replay takes: those as the tick loop applied them where the recording
/// has them (a node run), else those on the input topics (an offline run).
struct AppliedTopics {
    activation: bool,
    load: bool,
}

fn load_from(rec: &Recording) -> Result<LoadedRun, String> {
    let meta_map = rec.metadata.get(METADATA_NAME).ok_or_else(|| {
        format!("no {METADATA_NAME:?} metadata record: not a muscle_actuator recording")
    })?;
    let meta = RunMeta::from_map(meta_map)?;
    checks::check_state_schema(rec)?;
    let ours = [STATE_TYPE, JOINT_STATE_TYPE, ACTIVATION_TYPE, LOAD_TYPE];
    let applied = |ty: &str, suffix: &str| {
        rec.messages
            .iter()
            .any(|m| m.type_name == ty && m.topic.ends_with(suffix))
    };
    let applied = AppliedTopics {
        activation: applied(ACTIVATION_TYPE, APPLIED_ACTIVATION_SUFFIX),
        load: applied(LOAD_TYPE, APPLIED_LOAD_SUFFIX),
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
        let on = |e: String| format!("message on {}: {e}", excerpt(&m.topic));
        run.take(m, &applied).map_err(on)?;
    }
    run.check(recorded_span_s(rec))?;
    Ok(run)
}

impl LoadedRun {
    /// Every check of [`checks`], on a decoded run whose messages span `recorded_span_s` seconds
    /// of log time.
    fn check(&self, recorded_span_s: f64) -> Result<(), String> {
        checks::check_states(&self.meta, &self.states)?;
        checks::check_inputs("activation", &self.activations)?;
        checks::check_inputs("external load", &self.loads)?;
        checks::check_length(&self.meta, &self.states, recorded_span_s)
    }

    /// Decodes one message of ours and keeps what replay uses of it.
    fn take(&mut self, m: &RawMessage, applied: &AppliedTopics) -> Result<(), String> {
        if m.encoding != "cdr" || m.schema_encoding != "ros2msg" {
            return Err(format!(
                "encoding {:?} with a {:?} schema, where {} is recorded as \"cdr\" with a \
                 \"ros2msg\" schema",
                excerpt(&m.encoding),
                excerpt(&m.schema_encoding),
                m.type_name
            ));
        }
        let (time_base, rate_hz) = (self.meta.time_base, self.meta.rate_hz);
        match m.type_name.as_str() {
            STATE_TYPE => self
                .states
                .push(recording::decode_cdr::<ActuatorState>(&m.data)?),
            // Only the driven joints' motion as applied is used, but a recording whose
            // messages do not decode is not accepted.
            JOINT_STATE_TYPE => {
                let js: JointState = recording::decode_cdr(&m.data)?;
                if m.topic.ends_with(APPLIED_JOINT_MOTION_SUFFIX) {
                    let n = js.name.len();
                    if js.position.len() != n || js.velocity.len() != n {
                        return Err(format!(
                            "{n} names with {} positions and {} velocities",
                            js.position.len(),
                            js.velocity.len()
                        ));
                    }
                    let tick = time_base.tick_of(js.header.stamp.to_nanos(), rate_hz)?;
                    self.joint_motions
                        .push((tick, js.name, js.position, js.velocity));
                }
            }
            ACTIVATION_TYPE => {
                let a: ActivationCommand = recording::decode_cdr(&m.data)?;
                if !applied.activation || m.topic.ends_with(APPLIED_ACTIVATION_SUFFIX) {
                    let tick = time_base.tick_of(a.header.stamp.to_nanos(), rate_hz)?;
                    self.activations.push((tick, a.muscle, a.excitation));
                }
            }
            _ => {
                let l: ExternalLoad = recording::decode_cdr(&m.data)?;
                if !applied.load || m.topic.ends_with(APPLIED_LOAD_SUFFIX) {
                    let tick = time_base.tick_of(l.header.stamp.to_nanos(), rate_hz)?;
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
