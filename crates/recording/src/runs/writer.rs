//! The offline run writer: a run to MCAP tick by tick, log time = simulated time (the writer of
//! `simulate --out` and `replay --out`); and the message of driven joints' motion as applied,
//! which the node records too.

use super::channels::{
    Channel, Layout, NodeTopic, ACTIVATION, APPLIED_JOINT_MOTION, JOINT_STATES, LOAD, STATE,
};
use super::error::RunError;
use super::metadata::{RunMeta, METADATA_NAME};
use crate::msgs::muscle_actuator_msgs::{ActivationCommand, ExternalLoad};
use crate::msgs::Time;
use crate::msgs::{state_messages, Header, JointState};
use crate::recording::{self, Recorder, RecorderOptions, RecorderState};
use muscle_actuator_core::files::AtomicFile;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::Inputs;
use muscle_actuator_core::sim::StateSnapshot;
use muscle_actuator_core::time::tick_ns;
use std::path::Path;

/// The `sensor_msgs/JointState` of driven joints' motion as applied: (name, angle rad,
/// velocity rad/s) each; no effort.
pub fn joint_motion_msg(
    header: Header,
    motion: impl Iterator<Item = (String, f64, f64)>,
) -> JointState {
    let mut m = JointState {
        header,
        name: vec![],
        position: vec![],
        velocity: vec![],
        effort: vec![],
    };
    for (name, angle, velocity) in motion {
        m.name.push(name);
        m.position.push(angle);
        m.velocity.push(velocity);
    }
    m
}

fn stamp(ns: u64) -> Header {
    Header {
        stamp: Time::from_nanos(ns as i64),
        frame_id: String::new(),
    }
}

/// Writes a run to MCAP tick by tick: states, joint states (with a joint) and inputs (when they
/// change), log time = simulated time. The recorder writes a temporary beside the output
/// ([`AtomicFile`]), renamed into place by [`RunWriter::finish`]: a run that fails or is killed
/// leaves no partial recording under the output's name. (The node's own recordings are written
/// in place, readable up to a crash: `recover` is for those.)
pub(super) struct RunWriter {
    /// Declared before `out`: dropped first, so the recorder has closed the temporary before an
    /// unfinished run's is removed.
    rec: Recorder,
    layout: Layout,
    has_joint: bool,
    rate_hz: f64,
    model: ModelKind,
    muscles: Vec<String>,
    joints: Vec<String>,
    /// The driven joints (indices): their motion is written every tick.
    driven: Vec<usize>,
    last: Option<Inputs>,
    out: AtomicFile,
}

impl RunWriter {
    pub(super) fn start(path: &Path, meta: &RunMeta) -> Result<Self, RunError> {
        let has_joint = !meta.joints.is_empty();
        let mut layout = Layout::new();
        let mut add = |ch, t: NodeTopic| layout.add(ch, &t.offline(), t.type_name);
        add(Channel::State, STATE)?;
        add(Channel::Activation, ACTIVATION)?;
        if has_joint {
            add(Channel::JointStates, JOINT_STATES)?;
            add(Channel::Load, LOAD)?;
        }
        let driven: Vec<usize> = (meta.config.joints.iter().enumerate())
            .filter(|(_, j)| j.driven && has_joint)
            .map(|(k, _)| k)
            .collect();
        if !driven.is_empty() {
            layout.add(
                Channel::AppliedJointMotion,
                &APPLIED_JOINT_MOTION.offline(),
                APPLIED_JOINT_MOTION.type_name,
            )?;
        }
        let what = |source| RunError::Output {
            path: path.to_path_buf(),
            source,
        };
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(what)?;
        }
        let out = AtomicFile::create(path).map_err(what)?;
        let rec = Recorder::start(
            out.path(),
            layout.specs(),
            vec![(METADATA_NAME.into(), meta.to_map()?)],
            RecorderOptions::default(),
        )
        .map_err(|e| e.renamed(out.path(), out.target()))?;
        Ok(Self {
            rec,
            layout,
            has_joint,
            rate_hz: meta.rate_hz,
            model: meta.model,
            muscles: meta.muscles.clone(),
            joints: if has_joint {
                meta.joints.clone()
            } else {
                vec![]
            },
            driven,
            last: None,
            out,
        })
    }

    fn put<T: serde::Serialize>(&self, ch: Channel, ns: u64, msg: &T) -> Result<(), RunError> {
        let id = self.layout.id(ch).ok_or(RunError::NoChannel(ch))?;
        let data = recording::encode_cdr(msg)?;
        if self.rec.record_blocking(id, ns, ns, data) {
            Ok(())
        } else {
            Err(match self.rec.stats().state() {
                RecorderState::Failed(e) => RunError::RecorderFailed(named(&self.out, e)),
                _ => RunError::RecorderStopped,
            })
        }
    }

    /// Inputs that take effect at `tick` (written when they change).
    pub(super) fn inputs(&mut self, tick: u64, inputs: &Inputs) -> Result<(), RunError> {
        let ns = tick_ns(tick, self.rate_hz);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let prev = self.last.take();
        let changed =
            |now: &[f64], before: Option<&Vec<f64>>| before.is_none_or(|b| bits(b) != bits(now));
        if changed(&inputs.excitation, prev.as_ref().map(|p| &p.excitation)) {
            self.put(
                Channel::Activation,
                ns,
                &ActivationCommand {
                    header: stamp(ns),
                    muscle: self.muscles.clone(),
                    excitation: inputs.excitation.clone(),
                },
            )?;
        }
        if self.has_joint
            && changed(
                &inputs.external_torque,
                prev.as_ref().map(|p| &p.external_torque),
            )
        {
            self.put(
                Channel::Load,
                ns,
                &ExternalLoad {
                    header: stamp(ns),
                    joint: self.joints.clone(),
                    torque: inputs.external_torque.clone(),
                },
            )?;
        }
        if !self.driven.is_empty() {
            // Every tick: between schedule samples the motion is the carried-on extrapolation,
            // so "unchanged from the last message" would not say what the tick applied.
            let motion = (self.driven.iter()).map(|&j| {
                (
                    self.joints[j].clone(),
                    inputs.joint_angle[j],
                    inputs.joint_velocity[j],
                )
            });
            self.put(
                Channel::AppliedJointMotion,
                ns,
                &joint_motion_msg(stamp(ns), motion),
            )?;
        }
        self.last = Some(inputs.clone());
        Ok(())
    }

    /// The state after `tick` ticks (and the joint states, with a joint).
    pub(super) fn state(&self, tick: u64, state: &StateSnapshot) -> Result<(), RunError> {
        let ns = tick_ns(tick, self.rate_hz);
        let (msg, js) = state_messages(
            ns as i64,
            self.model.name(),
            tick,
            &self.muscles,
            &self.joints,
            state,
        );
        self.put(Channel::State, ns, &msg)?;
        if self.has_joint {
            self.put(Channel::JointStates, ns, &js)?;
        }
        Ok(())
    }

    /// Finishes the recording and renames it into place.
    pub(super) fn finish(self) -> Result<(), RunError> {
        if let RecorderState::Failed(e) = self.rec.finish() {
            return Err(RunError::RecorderFailed(named(&self.out, e)));
        }
        let path = self.out.target().to_path_buf();
        (self.out.commit()).map_err(|source| RunError::Output { path, source })
    }
}

/// The recorder's report `e` about the temporary, naming the output instead.
fn named(out: &AtomicFile, e: String) -> String {
    e.replace(
        &out.path().display().to_string(),
        &out.target().display().to_string(),
    )
}
