//! The node's recording (parameters `record`, `record_dir`): every input as received, every
//! state as published, the inputs as the tick loop applied them (stamped with the tick they took
//! effect at: stamp = tick origin + tick / rate), which is what `replay` feeds back, and the
//! node's `/diagnostics` and `/rosout` lines. One time base, the node's clock
//! ([`super::clock`]): wall-clock time, simulated time with `clock` sim or lockstep, or the
//! followed `/clock`'s time (docs/time.md, "Time in recordings").

use super::clock::{ClockMode, NodeClock};
use super::endpoints::{Endpoint, Names};
use super::params::NodeParams;
use super::tick::{Applied, AppliedInput};
use muscle_actuator_core::sim::Actuator;
use muscle_actuator_core::time::{self, TimeBase};
use muscle_actuator_recording::msgs::muscle_actuator_msgs::{ActivationCommand, ExternalLoad};
use muscle_actuator_recording::msgs::Time;
use muscle_actuator_recording::msgs::{DiagnosticStatus, Header, KeyValue};
use muscle_actuator_recording::recording::{
    encode_cdr, RecordSender, Recorder, RecorderOptions, RecorderState,
};
use muscle_actuator_recording::runs::{self, AttachmentMeta, Layout, RunMeta};
use ros2_client::ParameterValue;
use std::path::PathBuf;
use std::sync::atomic::Ordering;
use std::sync::mpsc::Receiver;
use std::sync::Arc;

/// A channel of the node's recording: the `k`-th instance of an endpoint.
pub(crate) type ChannelKey = (Endpoint, usize);

/// Where the node's threads hand messages for the recording: the recorder's sender and the
/// channel layout (cheap to clone).
#[derive(Clone)]
pub struct RecordTx {
    pub sender: RecordSender,
    layout: Arc<Layout<ChannelKey>>,
    clock: Arc<NodeClock>,
    /// The run's metadata as first written.
    meta: Arc<RunMeta>,
}

impl RecordTx {
    /// Serializes `msg` and hands it to the recorder on channel `ch` (log time: the node's
    /// clock now), for what the node received or logged.
    pub(crate) fn put<T: serde::Serialize>(&self, ch: ChannelKey, publish_ns: i64, msg: &T) {
        self.put_logged(ch, self.clock.now_ns(), publish_ns, msg);
    }

    /// As [`RecordTx::put`] for what the tick loop made (states, joint states, efforts, inputs
    /// as applied): log time = the tick's stamp, so that the same ticks give the same records
    /// whenever the recorder's thread got to them.
    pub(crate) fn put_tick<T: serde::Serialize>(&self, ch: ChannelKey, stamp_ns: i64, msg: &T) {
        self.put_logged(ch, stamp_ns, stamp_ns, msg);
    }

    fn put_logged<T: serde::Serialize>(
        &self,
        ch: ChannelKey,
        log_ns: i64,
        publish_ns: i64,
        msg: &T,
    ) {
        let Some(id) = self.layout.id(ch) else {
            return;
        };
        match encode_cdr(msg) {
            Ok(data) => {
                let log = log_ns.max(0) as u64;
                self.sender.record(id, log, publish_ns.max(0) as u64, data);
            }
            Err(_) => {
                self.sender.stats().dropped.fetch_add(1, Ordering::Relaxed);
            }
        }
    }

    /// Following `/clock`: the first clock message put tick 0 at `tick_origin_ns`. The run's
    /// metadata record is written again with it (a reader keeps the last record of a name).
    pub fn anchored(&self, tick_origin_ns: i64) {
        let mut meta = (*self.meta).clone();
        meta.time_base = TimeBase::RosClock {
            tick_origin_ns: Some(tick_origin_ns),
        };
        if let Ok(map) = meta.to_map() {
            self.sender.metadata(runs::METADATA_NAME, map);
        }
    }
}

/// Why the node's recording cannot start.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// A channel of the layout is refused (a name or type).
    #[error(transparent)]
    Layout(#[from] muscle_actuator_recording::recording::schema::SchemaError),
    /// The run's metadata cannot be written as a record.
    #[error(transparent)]
    Metadata(#[from] muscle_actuator_recording::runs::metadata::MetadataError),
    /// The file cannot be created or written.
    #[error(transparent)]
    Start(#[from] muscle_actuator_recording::recording::RecordingError),
}

/// A running recording.
pub struct NodeRecorder {
    pub recorder: Recorder,
    layout: Arc<Layout<ChannelKey>>,
    clock: Arc<NodeClock>,
    meta: Arc<RunMeta>,
}

impl NodeRecorder {
    pub fn tx(&self) -> RecordTx {
        RecordTx {
            sender: self.recorder.sender(),
            layout: self.layout.clone(),
            clock: self.clock.clone(),
            meta: self.meta.clone(),
        }
    }
}

/// Whether these parameters ask for a recording.
pub fn enabled(p: &NodeParams) -> bool {
    p.record && !p.record_dir.trim().is_empty()
}

/// The file for a run of node `fqn` started at `start_ns`: `DIR/<name>_<UTC time>.mcap`.
pub fn file_path(p: &NodeParams, fqn: &str, start_ns: i64) -> PathBuf {
    let t = time::iso8601(start_ns)
        .replace([':', '-'], "")
        .replace('.', "-");
    let name = fqn.trim_start_matches('/').replace('/', "_");
    PathBuf::from(&p.record_dir).join(format!("{name}_{t}.mcap"))
}

/// The recording's channels: every endpoint the node has that the table records
/// ([`super::endpoints::ENDPOINTS`]), in the table's order, under its resolved name.
pub(crate) fn layout(names: &Names) -> Result<Layout<ChannelKey>, RecordError> {
    let mut layout = Layout::new();
    for r in names.in_table_order() {
        if let Some(ch) = r.channel() {
            layout
                .add(ch, &r.name, r.spec().type_name)
                .map_err(RecordError::Layout)?;
        }
    }
    Ok(layout)
}

/// The node's parameters as the recording's metadata holds them: every one of the parameter
/// table with its value, and `use_sim_time` (whether the node follows `/clock`).
fn parameters_json(p: &NodeParams, mode: ClockMode) -> String {
    let mut m = serde_json::Map::new();
    for (name, value) in p.values() {
        let v = match value {
            ParameterValue::Boolean(b) => b.into(),
            ParameterValue::Integer(i) => i.into(),
            ParameterValue::Double(d) => d.into(),
            ParameterValue::String(s) => s.into(),
            other => format!("{other:?}").into(),
        };
        m.insert(name.into(), v);
    }
    m.insert("use_sim_time".into(), (mode == ClockMode::Follow).into());
    serde_json::Value::Object(m).to_string()
}

/// Starts the recording of a node run whose tick 0 is stamped `tick_origin_ns` on `clock`.
pub(crate) fn start(
    p: &NodeParams,
    fqn: &str,
    names: &Names,
    actuator: &Actuator,
    clock: &Arc<NodeClock>,
    tick_origin_ns: i64,
) -> Result<NodeRecorder, RecordError> {
    let start_ns = time::now_ns();
    let params_json = parameters_json(p, clock.mode());
    let meta = RunMeta {
        source: format!("node {fqn}"),
        model: actuator.model(),
        rate_hz: actuator.rate_hz(),
        stepping: actuator.simulation().stepping(),
        attachment: AttachmentMeta::Joint,
        config: actuator.config().clone(),
        parameters_json: Some(params_json),
        start_time_ns: start_ns,
        time_base: clock.time_base(tick_origin_ns),
        initial_joint_motion: runs::driven_motion(actuator.simulation()),
        muscles: actuator.muscle_names().to_vec(),
        joints: actuator.joint_names().to_vec(),
    };
    let layout = layout(names)?;
    let metadata = meta.to_map().map_err(RecordError::Metadata)?;
    let recorder = Recorder::start(
        &file_path(p, fqn, start_ns),
        layout.specs(),
        vec![(runs::METADATA_NAME.into(), metadata)],
        RecorderOptions::default(),
    )
    .map_err(RecordError::Start)?;
    Ok(NodeRecorder {
        recorder,
        layout: Arc::new(layout),
        clock: clock.clone(),
        meta: Arc::new(meta),
    })
}

/// The thread that turns applied inputs into messages for the recorder.
pub fn applied_loop(rx: Receiver<Applied>, tx: RecordTx) {
    while let Ok(a) = rx.recv() {
        let header = Header {
            stamp: Time::from_nanos(a.stamp_ns),
            frame_id: String::new(),
        };
        let name = |i: usize| a.names.get(i).cloned().unwrap_or_default();
        match a.input {
            AppliedInput::Excitation(v) => {
                let m = ActivationCommand {
                    header,
                    muscle: v.iter().map(|(i, _)| name(*i)).collect(),
                    excitation: v.iter().map(|(_, u)| *u).collect(),
                };
                tx.put_tick((Endpoint::AppliedActivation, 0), a.stamp_ns, &m);
            }
            AppliedInput::Load(v) => {
                let m = ExternalLoad {
                    header,
                    joint: v.iter().map(|(j, _)| name(*j)).collect(),
                    torque: v.iter().map(|(_, t)| *t).collect(),
                };
                tx.put_tick((Endpoint::AppliedLoad, 0), a.stamp_ns, &m);
            }
            AppliedInput::JointMotion(v) => {
                let m = runs::joint_motion_msg(
                    header,
                    v.iter()
                        .map(|&(j, angle, velocity)| (name(j), angle, velocity)),
                );
                tx.put_tick((Endpoint::AppliedJointMotion, 0), a.stamp_ns, &m);
            }
        }
    }
}

fn kv(key: &str, value: impl ToString) -> KeyValue {
    KeyValue {
        key: key.into(),
        value: value.to_string(),
    }
}

/// What the recorder looks like now, for /diagnostics.
pub enum Status<'a> {
    Disabled,
    /// Could not start.
    StartFailed(&'a str),
    Running(&'a Recorder),
}

/// The recorder's diagnostic status.
pub fn diagnostic(fqn: &str, params: &NodeParams, status: &Status) -> DiagnosticStatus {
    let mut values = vec![
        kv("record", params.record),
        kv("record_dir", &params.record_dir),
    ];
    let (level, message, state) = match status {
        Status::Disabled => (
            DiagnosticStatus::OK,
            "not recording (record is false or record_dir is empty)".to_string(),
            "inactive",
        ),
        Status::StartFailed(e) => (
            DiagnosticStatus::ERROR,
            format!("not recording: {e}"),
            "failed",
        ),
        Status::Running(r) => {
            let st = r.stats();
            values.push(kv("file", st.path.display()));
            values.push(kv("messages_written", st.written.load(Ordering::Relaxed)));
            values.push(kv("messages_dropped", st.dropped.load(Ordering::Relaxed)));
            values.push(kv("bytes", st.message_bytes.load(Ordering::Relaxed)));
            match st.state() {
                RecorderState::Recording => {
                    let dropped = st.dropped.load(Ordering::Relaxed);
                    (
                        if dropped > 0 {
                            DiagnosticStatus::WARN
                        } else {
                            DiagnosticStatus::OK
                        },
                        format!("recording to {}", st.path.display()),
                        "recording",
                    )
                }
                RecorderState::Finished => (
                    DiagnosticStatus::OK,
                    "recording finished".to_string(),
                    "finished",
                ),
                RecorderState::Failed(e) => (DiagnosticStatus::ERROR, e, "failed"),
            }
        }
    };
    values.push(kv("state", state));
    DiagnosticStatus {
        level,
        name: format!("{fqn}: recorder"),
        message,
        hardware_id: fqn.into(),
        values,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ros::args::expand;
    use crate::ros::clock::ClockMode;
    use crate::ros::endpoints::ENDPOINTS;

    /// Every endpoint the table records is a channel of the file the node's recorder writes,
    /// under its name and with its type (here every endpoint made, as with driven joints).
    #[test]
    fn every_recorded_endpoint_is_in_the_file() {
        let dir = std::env::temp_dir().join(format!("node_record_{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let p = NodeParams {
            record_dir: dir.display().to_string(),
            ..NodeParams::default()
        };
        let fqn = "/lab/muscle_actuator";
        let mut names = Names::default();
        for s in ENDPOINTS {
            names.add(s.endpoint, 0, expand(s.name, "/lab", "muscle_actuator"));
        }
        names.add(
            Endpoint::MuscleCommand,
            1,
            "/lab/muscle_actuator/b/cmd_activation".into(),
        );
        let actuator = p.build().unwrap();
        let clock = Arc::new(NodeClock::new(ClockMode::Sim));
        let r = start(&p, fqn, &names, &actuator, &clock, 0).unwrap();
        let path = r.recorder.stats().path.clone();
        r.recorder.finish();
        let file = muscle_actuator_recording::recording::read_recording(&path, false).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        let channels: Vec<(String, String)> = file
            .channels
            .values()
            .map(|c| {
                let ty = c
                    .schema
                    .as_ref()
                    .map(|s| s.name.clone())
                    .unwrap_or_default();
                (c.topic.clone(), ty)
            })
            .collect();
        let mut recorded = 0;
        for s in ENDPOINTS.iter().filter(|s| s.record) {
            let name = expand(s.name, "/lab", "muscle_actuator");
            assert!(
                channels.contains(&(name.clone(), s.type_name.to_string())),
                "{name} ({}) is not in the recording: {channels:?}",
                s.type_name
            );
            recorded += 1;
        }
        assert!(channels.contains(&(
            "/lab/muscle_actuator/b/cmd_activation".into(),
            "std_msgs/msg/Float64".into()
        )));
        assert_eq!(channels.len(), recorded + 1);
    }
}
