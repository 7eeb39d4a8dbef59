//! Runs as recordings: the channels ([`channels`]) and the `muscle_actuator` metadata record of
//! a run file, `simulate --out` ([`simulate_to_mcap`]), [`replay`], [`compare`] and [`export`].
//!
//! One time base per recording, named in the metadata ([`TimeBase`]): every log time and header
//! stamp of an offline run is simulated time from zero; every one of a node run is wall-clock
//! time (ns since the Unix epoch). Inputs are recorded stamped with the tick at which they take
//! effect: stamp = tick origin + tick / rate, so tick = round((stamp − origin) · rate), with origin
//! 0 offline and the node's tick origin (the wall-clock time of its tick 0) in a node run. Offline
//! runs carry them on the input topics themselves; the node records inputs as received on the
//! input topics and, as applied by the tick loop, on `<node>/applied/activation` and
//! `<node>/applied/external_load`.

pub mod channels;
pub mod checks;
pub mod compare;
pub mod export;
pub mod limits;

use crate::config::ActuatorConfig;
use crate::msgs::muscle_actuator_msgs::{ActivationCommand, ActuatorState, ExternalLoad};
use crate::msgs::{definition, state_messages, type_hash, Header, JointState};
use crate::physics::model::ModelKind;
use crate::physics::plant::{Inputs, Plant};
use crate::physics::topology::Topology;
use crate::recording::{
    self, qos_yaml, reader::read_run_file, schema::ros2msg_schema, ChannelSpec, Recorder,
    RecorderOptions, RecorderState, Recording,
};
use crate::sim::scenario::{Record, Run, Scenario, SetupKind};
use crate::sim::simulation::{default_stepping, Simulation, Stepping};
use crate::sim::snapshot::StateSnapshot;
use crate::text::excerpt;
pub use channels::{
    Channel, Layout, ACTIVATION_TOPIC, ACTIVATION_TYPE, APPLIED_ACTIVATION_SUFFIX,
    APPLIED_JOINT_MOTION_SUFFIX, APPLIED_JOINT_MOTION_TOPIC, APPLIED_LOAD_SUFFIX,
    DIAGNOSTICS_TOPIC, DIAGNOSTICS_TYPE, FLOAT64_ARRAY_TYPE, FLOAT64_TYPE, JOINT_STATES_TOPIC,
    JOINT_STATE_TYPE, LOAD_TOPIC, LOAD_TYPE, LOG_TYPE, ROSOUT_TOPIC, STATE_TOPIC, STATE_TYPE,
};
use ros2_client::builtin_interfaces::Time;
use std::collections::BTreeMap;
use std::path::Path;

/// Name of our metadata record.
pub const METADATA_NAME: &str = "muscle_actuator";

/// The channel of `topic` with type `type_name` (reliable, volatile, depth 10, as the node).
pub fn channel(topic: &str, type_name: &str) -> Result<ChannelSpec, String> {
    Ok(ChannelSpec {
        topic: topic.into(),
        type_name: type_name.into(),
        schema: ros2msg_schema(type_name, &definition)?,
        qos_yaml: qos_yaml(true, false, 10),
        type_hash: type_hash(type_name).map(String::from),
    })
}

/// How the muscles were attached in a run.
#[derive(Debug, Clone, PartialEq)]
pub enum AttachmentMeta {
    Joint,
    Clamped {
        length: f64,
    },
    Force {
        initial_force: f64,
    },
    /// The configuration's limb with driven joints (those marked in `config`), their motion
    /// from a scenario's schedules (recorded as applied, on `~/applied/joint_motion`).
    Driven,
}

/// What the `muscle_actuator` metadata record holds: everything needed to rebuild the run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunMeta {
    /// What made the run (`simulate pulse`, `node /muscle_actuator`, `replay ...`).
    pub source: String,
    pub model: ModelKind,
    pub rate_hz: f64,
    pub stepping: Stepping,
    pub attachment: AttachmentMeta,
    pub config: ActuatorConfig,
    /// The node's parameters (JSON), for node runs.
    pub parameters_json: Option<String>,
    /// Wall-clock start, ns since the Unix epoch.
    pub start_time_ns: i64,
    /// What the log times and header stamps count.
    pub time_base: TimeBase,
    /// The driven joints' motion the run started from, (angle rad, velocity rad/s) per driven
    /// joint in configuration order; empty: their initial angles, at rest (as the node starts).
    pub initial_joint_motion: Vec<(f64, f64)>,
    pub muscles: Vec<String>,
    pub joints: Vec<String>,
}

/// The clock of a recording's log times and header stamps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeBase {
    /// Simulated time from zero: tick k at k / rate (offline runs).
    Simulated,
    /// Wall-clock time, ns since the Unix epoch; tick k of the run is stamped
    /// `tick_origin_ns + k / rate` (node runs).
    Wall { tick_origin_ns: i64 },
    /// The time of an external `/clock` the node followed (`use_sim_time`), ns; tick k is
    /// stamped `tick_origin_ns + k / rate`, the origin being the first `/clock` time received
    /// (`None` until one arrived: the run has no tick yet).
    RosClock { tick_origin_ns: Option<i64> },
}

impl TimeBase {
    /// The stamp of tick 0, ns.
    pub fn tick_origin_ns(self) -> i64 {
        match self {
            TimeBase::Simulated
            | TimeBase::RosClock {
                tick_origin_ns: None,
            } => 0,
            TimeBase::Wall { tick_origin_ns }
            | TimeBase::RosClock {
                tick_origin_ns: Some(tick_origin_ns),
            } => tick_origin_ns,
        }
    }

    /// The stamp of `tick` at `rate_hz`, ns.
    pub fn stamp_ns(self, tick: u64, rate_hz: f64) -> i64 {
        self.tick_origin_ns()
            .saturating_add(i64::try_from(tick_ns(tick, rate_hz)).unwrap_or(i64::MAX))
    }

    /// The tick stamped `ns` at `rate_hz` (refused before the origin: it names no tick).
    pub fn tick_of(self, ns: i64, rate_hz: f64) -> Result<u64, String> {
        if self
            == (TimeBase::RosClock {
                tick_origin_ns: None,
            })
        {
            return Err(format!(
                "stamp {ns} ns names no tick: the node received no /clock message, so the run \
                 has no tick origin"
            ));
        }
        let origin = self.tick_origin_ns();
        let since = ns.checked_sub(origin).filter(|d| *d >= 0).ok_or_else(|| {
            format!("stamp {ns} ns is before the run's tick origin ({origin} ns)")
        })?;
        Ok(ns_tick(since as u64, rate_hz))
    }
}

fn stepping_text(s: Stepping) -> String {
    match s {
        Stepping::Adaptive {
            tolerance,
            max_substeps,
        } => format!("adaptive {tolerance:e} {max_substeps}"),
        Stepping::Fixed(n) => format!("fixed {n}"),
    }
}

fn parse_stepping(s: &str) -> Option<Stepping> {
    let parts: Vec<&str> = s.split_whitespace().collect();
    match parts.as_slice() {
        ["adaptive", t, m] => Some(Stepping::Adaptive {
            tolerance: t.parse().ok()?,
            max_substeps: m.parse().ok()?,
        }),
        ["fixed", n] => Some(Stepping::Fixed(n.parse().ok()?)),
        _ => None,
    }
}

/// Now, ns since the Unix epoch.
pub fn now_ns() -> i64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos() as i64)
        .unwrap_or(0)
}

/// `YYYY-MM-DDTHH:MM:SS.mmmZ` of ns since the epoch (UTC).
pub fn iso8601(ns: i64) -> String {
    let secs = ns.div_euclid(1_000_000_000);
    let ms = ns.rem_euclid(1_000_000_000) / 1_000_000;
    let days = secs.div_euclid(86_400);
    let sod = secs.rem_euclid(86_400);
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}.{ms:03}Z",
        sod / 3600,
        sod / 60 % 60,
        sod % 60
    )
}

impl RunMeta {
    /// The metadata record's map.
    pub fn to_map(&self) -> Result<BTreeMap<String, String>, String> {
        let mut m = BTreeMap::new();
        let mut put = |k: &str, v: String| {
            m.insert(k.to_string(), v);
        };
        put("source", self.source.clone());
        put("model", self.model.name().into());
        put("rate_hz", format!("{:?}", self.rate_hz));
        put("stepping", stepping_text(self.stepping));
        match &self.attachment {
            AttachmentMeta::Joint => put("attachment", "joint".into()),
            AttachmentMeta::Driven => put("attachment", "driven".into()),
            AttachmentMeta::Clamped { length } => {
                put("attachment", "clamped".into());
                put("length", format!("{length:?}"));
            }
            AttachmentMeta::Force { initial_force } => {
                put("attachment", "force".into());
                put("initial_force", format!("{initial_force:?}"));
            }
        }
        put(
            "config_toml",
            toml::to_string(&self.config).map_err(|e| format!("configuration as TOML: {e}"))?,
        );
        if let Some(p) = &self.parameters_json {
            put("parameters_json", p.clone());
        }
        put("start_time_ns", self.start_time_ns.to_string());
        put("start_time", iso8601(self.start_time_ns));
        match self.time_base {
            TimeBase::Simulated => put("time_base", "simulated".into()),
            TimeBase::Wall { tick_origin_ns } => {
                put("time_base", "wall".into());
                put("tick_origin_ns", tick_origin_ns.to_string());
            }
            TimeBase::RosClock { tick_origin_ns } => {
                put("time_base", "ros_clock".into());
                if let Some(t) = tick_origin_ns {
                    put("tick_origin_ns", t.to_string());
                }
            }
        }
        if !self.initial_joint_motion.is_empty() {
            // `{:?}` prints the shortest text that parses back to the same f64.
            let v: Vec<String> = (self.initial_joint_motion.iter())
                .map(|(a, w)| format!("{a:?} {w:?}"))
                .collect();
            put("initial_joint_motion", v.join(" "));
        }
        put("muscles", self.muscles.join(","));
        put("joints", self.joints.join(","));
        put("program_version", env!("CARGO_PKG_VERSION").into());
        put("program", "muscle_actuator".into());
        Ok(m)
    }

    /// Back from the record (fails with the missing or bad key).
    pub fn from_map(m: &BTreeMap<String, String>) -> Result<Self, String> {
        let get = |k: &str| {
            m.get(k)
                .ok_or_else(|| format!("metadata record {METADATA_NAME:?} has no {k:?}"))
        };
        let bad = |k: &str, v: &str| {
            format!("metadata {METADATA_NAME}.{k} = {:?} is invalid", excerpt(v))
        };
        let f64_of = |k: &str| -> Result<f64, String> {
            let v = get(k)?;
            v.parse::<f64>().map_err(|_| bad(k, v))
        };
        let model: ModelKind = get("model")?
            .parse()
            .map_err(|_| bad("model", &m["model"]))?;
        let stepping =
            parse_stepping(get("stepping")?).ok_or_else(|| bad("stepping", &m["stepping"]))?;
        let attachment = match get("attachment")?.as_str() {
            "joint" => AttachmentMeta::Joint,
            "driven" => AttachmentMeta::Driven,
            "clamped" => AttachmentMeta::Clamped {
                length: f64_of("length")?,
            },
            "force" => AttachmentMeta::Force {
                initial_force: f64_of("initial_force")?,
            },
            other => return Err(bad("attachment", other)),
        };
        let config = ActuatorConfig::from_toml_str(get("config_toml")?).map_err(|e| {
            format!(
                "metadata {METADATA_NAME}.config_toml: {}",
                e.to_string().replace('\n', "; ")
            )
        })?;
        let list = |k: &str| -> Vec<String> {
            m.get(k)
                .map(|s| {
                    s.split(',')
                        .filter(|x| !x.is_empty())
                        .map(String::from)
                        .collect()
                })
                .unwrap_or_default()
        };
        // Recordings older than the key stamped inputs from zero, as offline runs do.
        let time_base = match m.get("time_base").map(String::as_str) {
            None | Some("simulated") => TimeBase::Simulated,
            Some("wall") => {
                let v = get("tick_origin_ns")?;
                TimeBase::Wall {
                    tick_origin_ns: v.parse().map_err(|_| bad("tick_origin_ns", v))?,
                }
            }
            Some("ros_clock") => TimeBase::RosClock {
                tick_origin_ns: match m.get("tick_origin_ns") {
                    Some(v) => Some(v.parse().map_err(|_| bad("tick_origin_ns", v))?),
                    None => None,
                },
            },
            Some(other) => return Err(bad("time_base", other)),
        };
        let meta = RunMeta {
            source: m.get("source").cloned().unwrap_or_default(),
            model,
            rate_hz: f64_of("rate_hz")?,
            stepping,
            attachment,
            config,
            parameters_json: m.get("parameters_json").cloned(),
            start_time_ns: m
                .get("start_time_ns")
                .and_then(|s| s.parse().ok())
                .unwrap_or(0),
            time_base,
            initial_joint_motion: match m.get("initial_joint_motion") {
                None => vec![],
                Some(v) => {
                    let x: Vec<f64> = (v.split_whitespace())
                        .map(str::parse)
                        .collect::<Result<_, _>>()
                        .map_err(|_| bad("initial_joint_motion", v))?;
                    if !x.len().is_multiple_of(2) || x.iter().any(|x| !x.is_finite()) {
                        return Err(bad("initial_joint_motion", v));
                    }
                    x.chunks(2).map(|p| (p[0], p[1])).collect()
                }
            },
            muscles: list("muscles"),
            joints: list("joints"),
        };
        meta.check()?;
        Ok(meta)
    }

    /// The numbers within their limits (a rate the node would accept, sub-steps the simulation
    /// would), the attachment's numbers finite, the muscle and joint lists those of the
    /// configuration's topology.
    fn check(&self) -> Result<(), String> {
        let key = |k: &str| format!("metadata {METADATA_NAME}.{k}");
        limits::check_rate_hz(&key("rate_hz"), self.rate_hz)?;
        limits::check_stepping(&key("stepping"), self.stepping)?;
        match self.attachment {
            AttachmentMeta::Clamped { length } if !(length.is_finite() && length > 0.0) => {
                return Err(format!(
                    "{} = {length} is invalid: must be a finite number > 0",
                    key("length")
                ));
            }
            AttachmentMeta::Force { initial_force }
                if !(initial_force.is_finite() && initial_force >= 0.0) =>
            {
                return Err(format!(
                    "{} = {initial_force} is invalid: must be a finite number >= 0",
                    key("initial_force")
                ));
            }
            _ => {}
        }
        let driven = self.config.joints.iter().filter(|j| j.driven).count();
        if !self.initial_joint_motion.is_empty() && self.initial_joint_motion.len() != driven {
            return Err(format!(
                "{} has {} (angle, velocity) pairs for {driven} driven joints",
                key("initial_joint_motion"),
                self.initial_joint_motion.len()
            ));
        }
        let topology = self.topology();
        for (k, listed, actual) in [
            ("muscles", &self.muscles, topology.muscle_names()),
            ("joints", &self.joints, topology.joint_names()),
        ] {
            if *listed != actual {
                return Err(format!(
                    "{} = {:?} does not match its configuration ({})",
                    key(k),
                    excerpt(&listed.join(",")),
                    excerpt(&actual.join(","))
                ));
            }
        }
        Ok(())
    }

    /// The topology of the run.
    pub fn topology(&self) -> Topology {
        let first = &self.config.muscles[0];
        match &self.attachment {
            AttachmentMeta::Joint | AttachmentMeta::Driven => self.config.topology(),
            AttachmentMeta::Clamped { length } => {
                Topology::clamped(&first.name, first.params.clone(), *length)
            }
            AttachmentMeta::Force { .. } => {
                Topology::force_driven(&first.name, first.params.clone())
            }
        }
    }

    /// The simulation this run describes, in its initial state (with model `model`).
    pub fn build(&self, model: ModelKind, stepping: Stepping) -> Result<Simulation, String> {
        self.config.validate().map_err(|e| e.to_string())?;
        let plant = Plant::new(&self.topology(), model)?;
        let mut initial = Inputs::zeros(plant.muscle_count(), plant.joint_count());
        if let AttachmentMeta::Force { initial_force } = self.attachment {
            initial.tendon_force.fill(initial_force);
        }
        let driven = (plant.joints.iter().enumerate()).filter(|(_, j)| j.driven);
        for (n, (j, p)) in driven.enumerate() {
            let (angle, velocity) =
                (self.initial_joint_motion.get(n).copied()).unwrap_or((p.initial_angle, 0.0));
            initial.joint_angle[j] = angle;
            initial.joint_velocity[j] = velocity;
        }
        Simulation::new(plant, self.rate_hz, stepping, initial)
    }
}

/// The driven joints' motion that `sim` holds for its next tick: (angle rad, velocity rad/s) per
/// driven joint, in configuration order ([`RunMeta::initial_joint_motion`] at tick 0).
pub fn driven_motion(sim: &Simulation) -> Vec<(f64, f64)> {
    let inputs = sim.inputs();
    (sim.plant().joints.iter().enumerate())
        .filter(|(_, j)| j.driven)
        .map(|(j, _)| (inputs.joint_angle[j], inputs.joint_velocity[j]))
        .collect()
}

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

/// Simulated time of `tick` at `rate_hz`, ns.
pub fn tick_ns(tick: u64, rate_hz: f64) -> u64 {
    (tick as f64 * 1e9 / rate_hz).round() as u64
}

/// The tick whose simulated time is `ns`.
pub fn ns_tick(ns: u64, rate_hz: f64) -> u64 {
    (ns as f64 * rate_hz / 1e9).round() as u64
}

fn stamp(ns: u64) -> Header {
    Header {
        stamp: Time::from_nanos(ns as i64),
        frame_id: String::new(),
    }
}

/// Writes a run to MCAP tick by tick: states, joint states (with a joint) and inputs (when they
/// change), log time = simulated time.
struct RunWriter {
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
}

impl RunWriter {
    fn start(path: &Path, meta: &RunMeta) -> Result<Self, String> {
        let has_joint = !meta.joints.is_empty();
        let mut layout = Layout::new();
        layout.add(Channel::State, STATE_TOPIC, STATE_TYPE)?;
        layout.add(Channel::Activation, ACTIVATION_TOPIC, ACTIVATION_TYPE)?;
        if has_joint {
            layout.add(Channel::JointStates, JOINT_STATES_TOPIC, JOINT_STATE_TYPE)?;
            layout.add(Channel::Load, LOAD_TOPIC, LOAD_TYPE)?;
        }
        let driven: Vec<usize> = (meta.config.joints.iter().enumerate())
            .filter(|(_, j)| j.driven && has_joint)
            .map(|(k, _)| k)
            .collect();
        if !driven.is_empty() {
            layout.add(
                Channel::AppliedJointMotion,
                APPLIED_JOINT_MOTION_TOPIC,
                JOINT_STATE_TYPE,
            )?;
        }
        let rec = Recorder::start(
            path,
            layout.specs(),
            vec![(METADATA_NAME.into(), meta.to_map()?)],
            RecorderOptions::default(),
        )?;
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
        })
    }

    fn put<T: serde::Serialize>(&self, ch: Channel, ns: u64, msg: &T) -> Result<(), String> {
        let id = self
            .layout
            .id(ch)
            .ok_or_else(|| format!("internal error: no {ch:?} channel in this recording"))?;
        let data = recording::encode_cdr(msg)?;
        if self.rec.record_blocking(id, ns, ns, data) {
            Ok(())
        } else {
            Err(match self.rec.stats().state() {
                RecorderState::Failed(e) => e,
                _ => "the recording stopped".into(),
            })
        }
    }

    /// Inputs that take effect at `tick` (written when they change).
    fn inputs(&mut self, tick: u64, inputs: &Inputs) -> Result<(), String> {
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

    fn state(&self, tick: u64, state: &StateSnapshot) -> Result<(), String> {
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

    fn finish(self) -> Result<(), String> {
        match self.rec.finish() {
            RecorderState::Failed(e) => Err(e),
            _ => Ok(()),
        }
    }
}

/// Runs a scenario (as [`Scenario::run`]) and records it to `out`.
pub fn simulate_to_mcap(
    sc: &Scenario,
    cfg: &ActuatorConfig,
    model: ModelKind,
    rate_hz: f64,
    stepping: Stepping,
    out: &Path,
) -> Result<Run, String> {
    let mut runner = sc.runner(cfg, model, rate_hz, stepping)?;
    let first = &cfg.muscles[0];
    let attachment = match sc.attachment {
        SetupKind::Joint => AttachmentMeta::Joint,
        SetupKind::Driven => AttachmentMeta::Driven,
        SetupKind::Clamped => AttachmentMeta::Clamped {
            length: sc.length.unwrap_or(first.params.l_opt + first.params.l_ts),
        },
        SetupKind::Force => AttachmentMeta::Force {
            initial_force: sc.initial_force,
        },
    };
    let meta = RunMeta {
        source: format!("simulate {}", sc.name),
        model,
        rate_hz,
        stepping,
        attachment,
        config: sc.limb_config(cfg),
        parameters_json: None,
        start_time_ns: now_ns(),
        time_base: TimeBase::Simulated,
        initial_joint_motion: driven_motion(runner.simulation()),
        muscles: runner.muscle_names().to_vec(),
        joints: runner.joint_names().to_vec(),
    };
    let mut w = RunWriter::start(out, &meta)?;
    let ticks = (sc.duration * rate_hz).round() as u64;
    let mut records: Vec<Record> = Vec::with_capacity(ticks as usize + 1);
    let state = |r: &Record| StateSnapshot {
        muscles: r.muscles.clone(),
        joints: r.joints.clone(),
        stiffness_matrix: r.stiffness_matrix.clone(),
    };
    let r0 = runner.record();
    w.state(0, &state(&r0))?;
    records.push(r0);
    for k in 0..ticks {
        // The inputs `step` applies: the schedules at the tick's start.
        let inputs = runner.inputs_at(runner.simulation().time());
        w.inputs(k, &inputs)?;
        runner.step()?;
        let r = runner.record();
        w.state(k + 1, &state(&r))?;
        records.push(r);
    }
    w.finish()?;
    Ok(Run {
        scenario: sc.name.clone(),
        model,
        rate_hz,
        muscle_names: meta.muscles.clone(),
        joint_names: meta.joints.clone(),
        muscle_joints: runner.muscle_joints(),
        records,
    })
}

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

fn load_from(rec: &Recording) -> Result<LoadedRun, String> {
    let meta_map = rec.metadata.get(METADATA_NAME).ok_or_else(|| {
        format!("no {METADATA_NAME:?} metadata record: not a muscle_actuator recording")
    })?;
    let meta = RunMeta::from_map(meta_map)?;
    let ours = [STATE_TYPE, JOINT_STATE_TYPE, ACTIVATION_TYPE, LOAD_TYPE];
    let mut states = Vec::new();
    let mut activations = Vec::new();
    let mut loads = Vec::new();
    let mut joint_motions = Vec::new();
    let applied = |ty: &str, suffix: &str| {
        rec.messages
            .iter()
            .any(|m| m.type_name == ty && m.topic.ends_with(suffix))
    };
    let applied_act = applied(ACTIVATION_TYPE, APPLIED_ACTIVATION_SUFFIX);
    let applied_load = applied(LOAD_TYPE, APPLIED_LOAD_SUFFIX);
    for m in rec
        .messages
        .iter()
        .filter(|m| ours.contains(&m.type_name.as_str()))
    {
        let on = |e: String| format!("message on {}: {e}", excerpt(&m.topic));
        if m.encoding != "cdr" || m.schema_encoding != "ros2msg" {
            return Err(on(format!(
                "encoding {:?} with a {:?} schema, where {} is recorded as \"cdr\" with a \
                 \"ros2msg\" schema",
                excerpt(&m.encoding),
                excerpt(&m.schema_encoding),
                m.type_name
            )));
        }
        match m.type_name.as_str() {
            STATE_TYPE => states.push(recording::decode_cdr::<ActuatorState>(&m.data).map_err(on)?),
            // Only the driven joints' motion as applied is used, but a recording whose
            // messages do not decode is not accepted.
            JOINT_STATE_TYPE => {
                let js: JointState = recording::decode_cdr(&m.data).map_err(on)?;
                if m.topic.ends_with(APPLIED_JOINT_MOTION_SUFFIX) {
                    let n = js.name.len();
                    if js.position.len() != n || js.velocity.len() != n {
                        return Err(on(format!(
                            "{n} names with {} positions and {} velocities",
                            js.position.len(),
                            js.velocity.len()
                        )));
                    }
                    let tick = meta
                        .time_base
                        .tick_of(js.header.stamp.to_nanos(), meta.rate_hz)
                        .map_err(on)?;
                    joint_motions.push((tick, js.name, js.position, js.velocity));
                }
            }
            ACTIVATION_TYPE => {
                let a: ActivationCommand = recording::decode_cdr(&m.data).map_err(on)?;
                if !applied_act || m.topic.ends_with(APPLIED_ACTIVATION_SUFFIX) {
                    let tick = meta
                        .time_base
                        .tick_of(a.header.stamp.to_nanos(), meta.rate_hz)
                        .map_err(on)?;
                    activations.push((tick, a.muscle, a.excitation));
                }
            }
            _ => {
                let l: ExternalLoad = recording::decode_cdr(&m.data).map_err(on)?;
                if !applied_load || m.topic.ends_with(APPLIED_LOAD_SUFFIX) {
                    let tick = meta
                        .time_base
                        .tick_of(l.header.stamp.to_nanos(), meta.rate_hz)
                        .map_err(on)?;
                    loads.push((tick, l.joint, l.torque));
                }
            }
        }
    }
    let run = LoadedRun {
        meta,
        states,
        activations,
        loads,
        joint_motions,
        warning: None,
    };
    checks::check_run(&run, recorded_span_s(rec))?;
    Ok(run)
}

/// The time from the first message's log time to the last's, s.
fn recorded_span_s(rec: &Recording) -> f64 {
    let times = rec.messages.iter().map(|m| m.log_time);
    match (times.clone().min(), times.max()) {
        (Some(a), Some(b)) => (b - a) as f64 * 1e-9,
        _ => 0.0,
    }
}

/// What a replay did.
#[derive(Debug, Clone, PartialEq)]
pub struct ReplaySummary {
    pub model: ModelKind,
    /// Ticks simulated.
    pub ticks: u64,
    /// Recorded states compared with the replay (same model only).
    pub compared: u64,
    /// Of those, identical in every field bit for bit (header stamps aside).
    pub identical: u64,
    /// The first tick that differed.
    pub first_difference: Option<u64>,
    /// The input was cut by a crash and read up to the cut: what was read.
    pub warning: Option<String>,
}

/// The bits of a state's simulated fields (everything but the header), iterating the field
/// lists.
fn state_bits(s: &ActuatorState) -> Vec<u64> {
    let mut v = vec![s.tick];
    for j in &s.joints {
        v.extend(j.values().iter().map(|x| x.to_bits()));
    }
    v.extend(s.stiffness_matrix.iter().map(|x| x.to_bits()));
    for m in &s.muscles {
        v.extend(m.state.values().iter().map(|x| x.to_bits()));
    }
    v
}

/// A run's recorded inputs, handed to a simulation tick by tick as the run applied them.
struct RecordedInputs<'a> {
    activations: std::iter::Peekable<std::slice::Iter<'a, InputsAt>>,
    loads: std::iter::Peekable<std::slice::Iter<'a, InputsAt>>,
    motions: std::iter::Peekable<std::slice::Iter<'a, JointMotionAt>>,
    /// Per joint of the simulation, whether it is driven.
    driven: Vec<bool>,
}

impl<'a> RecordedInputs<'a> {
    fn new(run: &'a LoadedRun, sim: &Simulation) -> Self {
        Self {
            activations: run.activations.iter().peekable(),
            loads: run.loads.iter().peekable(),
            motions: run.joint_motions.iter().peekable(),
            driven: sim.plant().joints.iter().map(|j| j.driven).collect(),
        }
    }

    /// Applies the inputs recorded for ticks up to `tick` not applied yet: excitations and
    /// torques are held; a driven joint's motion carries on from where the last tick's
    /// extrapolation ended until the next one recorded. Names the run does not have, values
    /// that are not finite and motion for joints that are not driven are passed over, as the
    /// run passed them over.
    fn apply(&mut self, tick: u64, meta: &RunMeta, sim: &mut Simulation) {
        let driven = &self.driven;
        let inputs = sim.inputs_mut();
        let muscle = |n: &String| meta.muscles.iter().position(|m| m == n);
        let joint = |n: &String| meta.joints.iter().position(|m| m == n);
        while let Some((_, names, values)) = self.activations.next_if(|a| a.0 <= tick) {
            for (n, u) in names.iter().zip(values) {
                if let Some(slot) = muscle(n).and_then(|i| inputs.excitation.get_mut(i)) {
                    if u.is_finite() {
                        *slot = u.clamp(0.0, 1.0);
                    }
                }
            }
        }
        while let Some((_, names, values)) = self.loads.next_if(|l| l.0 <= tick) {
            for (n, t) in names.iter().zip(values) {
                if let Some(slot) = joint(n).and_then(|j| inputs.external_torque.get_mut(j)) {
                    if t.is_finite() {
                        *slot = *t;
                    }
                }
            }
        }
        while let Some((_, names, angles, velocities)) = self.motions.next_if(|m| m.0 <= tick) {
            for ((n, a), w) in names.iter().zip(angles).zip(velocities) {
                if let Some(j) = joint(n).filter(|&j| driven.get(j) == Some(&true)) {
                    if a.is_finite() && w.is_finite() {
                        inputs.joint_angle[j] = *a;
                        inputs.joint_velocity[j] = *w;
                    }
                }
            }
        }
    }
}

/// Feeds the recorded inputs of `input` at their ticks through `model` (default: the recorded
/// one) and records the result to `out`. With the recorded model every recorded state comes back
/// bit for bit (the summary says how many were compared and matched).
pub fn replay(input: &Path, model: Option<ModelKind>, out: &Path) -> Result<ReplaySummary, String> {
    let run = load_run(input)?;
    let meta = &run.meta;
    if let AttachmentMeta::Force { .. } = meta.attachment {
        return Err(format!(
            "{}: a force-driven run (its tendon-force input is not a recorded topic) cannot be replayed",
            input.display()
        ));
    }
    let last_tick = run
        .states
        .last()
        .map(|s| s.tick)
        .ok_or_else(|| format!("{}: the recording holds no actuator state", input.display()))?;
    let model = model.unwrap_or(meta.model);
    let stepping = if model == meta.model {
        meta.stepping
    } else {
        default_stepping(model)
    };
    let mut sim = meta.build(model, stepping)?;
    let mut out_meta = meta.clone();
    out_meta.model = model;
    out_meta.stepping = stepping;
    out_meta.source = format!("replay of {} ({})", input.display(), excerpt(&meta.source));
    out_meta.start_time_ns = now_ns();
    out_meta.time_base = TimeBase::Simulated;
    out_meta.parameters_json = None;
    let mut w = RunWriter::start(out, &out_meta)?;
    let mut by_tick: BTreeMap<u64, &ActuatorState> = BTreeMap::new();
    for s in &run.states {
        by_tick.insert(s.tick, s);
    }
    let mut summary = ReplaySummary {
        model,
        ticks: last_tick,
        compared: 0,
        identical: 0,
        first_difference: None,
        warning: run.warning.clone(),
    };
    let mut check = |tick: u64, state: &StateSnapshot| {
        if model != meta.model {
            return;
        }
        if let Some(rec) = by_tick.get(&tick) {
            let (mine, _) = state_messages(0, model.name(), tick, &meta.muscles, &rec.joint, state);
            summary.compared += 1;
            if state_bits(&mine) == state_bits(rec) {
                summary.identical += 1;
            } else if summary.first_difference.is_none() {
                summary.first_difference = Some(tick);
            }
        }
    };
    let mut inputs = RecordedInputs::new(&run, &sim);
    // The inputs of tick 0 first: an offline run's state at tick 0 shows them.
    inputs.apply(0, meta, &mut sim);
    let mut state = StateSnapshot::default();
    sim.fill_snapshot(&mut state);
    if by_tick.contains_key(&0) {
        w.state(0, &state)?;
        check(0, &state);
    }
    for k in 0..last_tick {
        inputs.apply(k, meta, &mut sim);
        w.inputs(k, sim.inputs())?;
        sim.step()
            .map_err(|e| format!("replay with {model} failed at tick {k}: {e}"))?;
        sim.fill_snapshot(&mut state);
        w.state(k + 1, &state)?;
        check(k + 1, &state);
    }
    w.finish()?;
    Ok(summary)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Stamps and ticks map both ways on either clock; a stamp before the origin names no tick;
    /// the time base survives the metadata record, and a record without one (older files) is
    /// simulated time.
    #[test]
    fn time_base_maps_stamps_to_ticks_and_round_trips() {
        let wall = TimeBase::Wall {
            tick_origin_ns: 1_763_800_000_000_000_123,
        };
        for rate in [1000.0, 333.0, 2500.0] {
            for tick in [0, 1, 7, 123_456, 86_400_000] {
                for tb in [TimeBase::Simulated, wall] {
                    assert_eq!(tb.tick_of(tb.stamp_ns(tick, rate), rate), Ok(tick));
                }
            }
        }
        assert_eq!(wall.stamp_ns(2, 1000.0), 1_763_800_000_002_000_123);
        assert!(wall
            .tick_of(1_763_800_000_000_000_000, 1000.0)
            .unwrap_err()
            .contains("before the run's tick origin"));
        assert!(TimeBase::Simulated.tick_of(-1, 1000.0).is_err());

        let cfg = ActuatorConfig::default();
        let mut meta = RunMeta {
            source: "test".into(),
            model: "hill".parse().unwrap(),
            rate_hz: 1000.0,
            stepping: default_stepping("hill".parse().unwrap()),
            attachment: AttachmentMeta::Joint,
            config: cfg.clone(),
            parameters_json: None,
            start_time_ns: 5,
            time_base: wall,
            initial_joint_motion: vec![],
            muscles: cfg.topology().muscle_names(),
            joints: cfg.topology().joint_names(),
        };
        let mut map = meta.to_map().unwrap();
        assert_eq!(map["time_base"], "wall");
        assert_eq!(RunMeta::from_map(&map).unwrap(), meta);
        map.remove("time_base");
        map.remove("tick_origin_ns");
        meta.time_base = TimeBase::Simulated;
        assert_eq!(RunMeta::from_map(&map).unwrap(), meta);
        map.insert("time_base".into(), "sundial".into());
        assert!(RunMeta::from_map(&map).unwrap_err().contains("time_base"));
        map.insert("time_base".into(), "wall".into());
        assert!(RunMeta::from_map(&map)
            .unwrap_err()
            .contains("tick_origin_ns"));
        // Following /clock: no origin until the first clock message, then the one it gave.
        for origin in [None, Some(5_000_000_000_000)] {
            meta.time_base = TimeBase::RosClock {
                tick_origin_ns: origin,
            };
            assert_eq!(RunMeta::from_map(&meta.to_map().unwrap()).unwrap(), meta);
        }
        let rc = meta.time_base;
        assert_eq!(rc.tick_of(rc.stamp_ns(42, 1000.0), 1000.0), Ok(42));
        let none = TimeBase::RosClock {
            tick_origin_ns: None,
        };
        assert!(none.tick_of(0, 1000.0).unwrap_err().contains("no /clock"));
        // The driven joints' initial motion round-trips exactly, and must fit them.
        let mut cfg = ActuatorConfig::default();
        cfg.joints[0].driven = true;
        meta.config = cfg;
        meta.initial_joint_motion = vec![(0.1 + 0.2, std::f64::consts::PI / 3.0)];
        assert_eq!(RunMeta::from_map(&meta.to_map().unwrap()).unwrap(), meta);
        meta.initial_joint_motion.push((0.0, 0.0));
        assert!(RunMeta::from_map(&meta.to_map().unwrap())
            .unwrap_err()
            .contains("initial_joint_motion"));
    }
}
