//! The DDS side of the node: participant, topics, the reset service, parameters, diagnostics,
//! logging and signals. The simulation runs on the tick thread ([`super::tick`]); this side only
//! validates and forwards inputs, and publishes what the tick thread hands over.

use super::args::{self, RosArgs, Severity};
use super::diagnostics::{diagnostics, DiagPrev, InputStats};
use super::input::{self, Rejection};
use super::logging::{LateTicks, Logger, RateLimit, LATE_WARN_PERIODS};
use super::msgs::muscle_actuator_msgs::{ActivationCommand, ActuatorState, ExternalLoad};
use super::msgs::{
    state_messages, DiagnosticArray, DiagnosticStatus, Float64, Float64MultiArray, JointState,
    TriggerRequest, TriggerResponse,
};
use super::params::{self, NodeParams};
use super::record;
use super::tick::{self, Applied, Command, Event, LoopIo, RunSummary, Sample, TickStats};
use super::DEFAULT_NODE_NAME;
use crate::recording::{RecordSender, RecorderState};
use crate::runs;
use futures::{FutureExt, StreamExt};
use ros2_client::qos::{Durability, History, WhenFull};
use ros2_client::{
    Context, MessageTypeName, Name, NodeName, NodeOptions, Publisher, QosProfile, ServiceMapping,
    ServiceTypeName,
};
use rustdds::DomainParticipantBuilder;
use std::net::{IpAddr, Ipv4Addr};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver};
use std::sync::{Arc, Mutex, OnceLock, RwLock};
use std::time::{Duration, Instant};

/// Highest valid `ROS_DOMAIN_ID` (as rmw implementations accept with default ports).
const MAX_DOMAIN_ID: u16 = 232;

/// The DDS domain from `ROS_DOMAIN_ID` (default 0).
pub fn domain_id_from_env() -> Result<u16, String> {
    match std::env::var("ROS_DOMAIN_ID") {
        Err(_) => Ok(0),
        Ok(s) if s.trim().is_empty() => Ok(0),
        Ok(s) => match s.trim().parse::<u16>() {
            Ok(d) if d <= MAX_DOMAIN_ID => Ok(d),
            _ => Err(format!(
                "ROS_DOMAIN_ID={s:?} is invalid: expected an integer from 0 to {MAX_DOMAIN_ID}"
            )),
        },
    }
}

/// Whether discovery must stay on this host: yes unless `ROS_AUTOMATIC_DISCOVERY_RANGE=SUBNET`
/// (`LOCALHOST`, `OFF`, unset, and `ROS_LOCALHOST_ONLY=1` all keep it local).
pub fn discovery_is_local() -> bool {
    !matches!(
        std::env::var("ROS_AUTOMATIC_DISCOVERY_RANGE")
            .map(|s| s.trim().to_ascii_uppercase())
            .as_deref(),
        Ok("SUBNET")
    )
}

/// Names that commands are checked against (they change with the `config` parameter).
#[derive(Clone, Default)]
struct Names {
    muscles: Vec<String>,
    joints: Vec<String>,
}

/// State shared between the parameter callbacks (on the spinner) and the rest.
struct Shared {
    params: Mutex<NodeParams>,
    names: RwLock<Names>,
    commands: tick::CommandSender,
    /// Parameter changes act only once the node is up (the store also runs the action for the
    /// initial values).
    armed: AtomicBool,
    logger: OnceLock<Logger>,
}

impl Shared {
    fn log(&self) -> Option<&Logger> {
        self.logger.get()
    }
    fn send(&self, c: Command) {
        // Never waits for the tick loop; a full queue drops (and counts) the command.
        let _ = self.commands.send(c);
    }
}

/// A second SIGINT/SIGTERM sooner than this after the first is part of the same stop request.
const SIGNAL_INSIST_AFTER: Duration = Duration::from_secs(2);

/// Longest a parameter change may take to build its actuator (configuration file read and
/// calibration) before it is refused.
const BUILD_TIMEOUT: Duration = Duration::from_secs(5);

/// Builds the actuator `params` describe on a thread of its own: the parameter callbacks run on
/// the node's executor, which must not wait on a slow file system for longer than
/// [`BUILD_TIMEOUT`] (a configuration is read only from a regular file of at most 1 MiB, but that
/// file may sit on a stalled network mount).
fn build_off_executor(params: &NodeParams) -> Result<crate::sim::Actuator, String> {
    let (tx, rx) = mpsc::sync_channel(1);
    let p = params.clone();
    std::thread::Builder::new()
        .name("build".into())
        .spawn(move || {
            let _ = tx.send(p.build());
        })
        .map_err(|e| format!("cannot start a thread to build the actuator: {e}"))?;
    rx.recv_timeout(BUILD_TIMEOUT).map_err(|_| {
        format!(
            "building the actuator took longer than {} s (is the configuration file on a \
             stalled file system?)",
            BUILD_TIMEOUT.as_secs()
        )
    })?
}

/// Checks one parameter change against the current set (and builds the actuator it would give
/// when it affects the simulation), without applying it.
fn validate_param(
    shared: &Shared,
    name: &str,
    value: &ros2_client::ParameterValue,
) -> Result<(), String> {
    let mut candidate = shared
        .params
        .lock()
        .map_err(|_| "internal error: parameter lock poisoned".to_string())?
        .clone();
    candidate.set(name, value, false)?;
    if matches!(name, params::MODEL | params::RATE_HZ | params::CONFIG) {
        build_off_executor(&candidate)?;
    }
    Ok(())
}

/// Applies an accepted parameter change.
fn apply_param(
    shared: &Shared,
    name: &str,
    value: &ros2_client::ParameterValue,
) -> Result<(), String> {
    if !shared.armed.load(Ordering::SeqCst) {
        return Ok(());
    }
    let mut p = shared
        .params
        .lock()
        .map_err(|_| "internal error: parameter lock poisoned".to_string())?;
    let mut candidate = p.clone();
    candidate.set(name, value, false)?;
    match name {
        params::MODEL | params::RATE_HZ | params::CONFIG => {
            let act = build_off_executor(&candidate)?;
            if let Ok(mut n) = shared.names.write() {
                *n = Names {
                    muscles: act.muscle_names().to_vec(),
                    joints: act.joint_names().to_vec(),
                };
            }
            shared.send(Command::Replace(Box::new(act)));
            shared.send(Command::PublishEvery(candidate.publish_every()));
        }
        params::PUBLISH_RATE_HZ => shared.send(Command::PublishEvery(candidate.publish_every())),
        _ => {}
    }
    *p = candidate;
    drop(p);
    if let Some(l) = shared.log() {
        let shown = match value {
            ros2_client::ParameterValue::String(s) => format!("{:?}", crate::config::excerpt(s)),
            other => crate::config::excerpt(&format!("{other:?}")),
        };
        l.info(&format!("parameter {name} set to {shown}"));
    }
    Ok(())
}

fn qos_reliable(depth: usize) -> QosProfile {
    QosProfile::publisher_default()
        .reliability_reliable(WhenFull::DEFAULT)
        .durability(Durability::Volatile)
        .history(History::KeepLast { depth })
}

fn dds_name(resolved: &str) -> Result<Name, String> {
    Name::parse(resolved).map_err(|e| format!("invalid name {resolved:?}: {e:?}"))
}

/// Converts a sample into the two published messages.
pub fn sample_to_msgs(s: &Sample) -> (ActuatorState, JointState) {
    state_messages(
        s.stamp_ns,
        s.model.name(),
        s.tick,
        &s.muscle_names,
        &s.joint_names,
        &s.state,
    )
}

/// The publisher thread: takes samples from the tick thread and publishes them.
fn publish_loop(
    rx: Receiver<Sample>,
    state_pub: Publisher<ActuatorState>,
    joint_pub: Publisher<JointState>,
    errors: Arc<AtomicU64>,
    rec: Option<RecordSender>,
) {
    while let Ok(s) = rx.recv() {
        let (state, js) = sample_to_msgs(&s);
        if let Some(r) = &rec {
            record::put(r, record::CH_STATE, s.stamp_ns, &state);
            record::put(r, record::CH_JOINT_STATES, s.stamp_ns, &js);
        }
        if state_pub.publish(state).is_err() {
            errors.fetch_add(1, Ordering::Relaxed);
        }
        if joint_pub.publish(js).is_err() {
            errors.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// Everything the node needs, resolved from the command line before DDS starts.
#[derive(Debug)]
struct Setup {
    namespace: String,
    name: String,
    fqn: String,
    params: NodeParams,
    ros_args: RosArgs,
    /// Notes on the undeclared parameters ignored, logged at debug level once the logger
    /// exists.
    ignored: Vec<String>,
}

fn setup(argv: &[String]) -> Result<Option<Setup>, String> {
    let ros_args = RosArgs::parse(argv)?;
    if ros_args.help {
        println!("{}", args::USAGE);
        return Ok(None);
    }
    let namespace = ros_args.namespace.clone().unwrap_or_else(|| "/".into());
    let name = ros_args
        .node_name
        .clone()
        .unwrap_or_else(|| DEFAULT_NODE_NAME.into());
    let fqn = args::expand("~", &namespace, &name);
    let mut p = NodeParams::default();
    let mut ignored = Vec::new();
    for a in ros_args.resolved_params(&fqn)? {
        // As rclcpp and rclpy do (without `allow_undeclared_parameters`), a parameter this
        // node does not declare is ignored: a shared file holds other nodes' parameters.
        if a.name != "use_sim_time" && !params::ALL.contains(&a.name.as_str()) {
            ignored.push(format!(
                "ignoring undeclared parameter {:?} (from {})",
                crate::config::excerpt(&a.name),
                a.source
            ));
            continue;
        }
        if a.name == "use_sim_time" {
            if !matches!(a.value, ros2_client::ParameterValue::Boolean(_)) {
                return Err(format!("{}: use_sim_time must be a bool", a.source));
            }
            continue;
        }
        p.set(&a.name, &a.value, true)
            .map_err(|e| format!("{}: {e}", a.source))?;
    }
    Ok(Some(Setup {
        namespace,
        name,
        fqn,
        params: p,
        ros_args,
        ignored,
    }))
}

/// Runs the node (see [`super::run_node`]).
pub fn run(argv: &[String]) -> Result<(), String> {
    let Some(setup) = setup(argv)? else {
        return Ok(());
    };
    let actuator = setup.params.build()?;
    let level = setup.ros_args.log_level.unwrap_or(Severity::Info);

    // Signals first, so that an early Ctrl-C is not lost.
    let (stop_tx, stop_rx) = smol::channel::bounded::<()>(1);
    let mut signals = signal_hook::iterator::Signals::new([
        signal_hook::consts::SIGINT,
        signal_hook::consts::SIGTERM,
    ])
    .map_err(|e| format!("cannot install signal handlers: {e}"))?;
    let signals_handle = signals.handle();
    let emergency_recording: Arc<Mutex<Option<RecordSender>>> = Arc::new(Mutex::new(None));
    let er = emergency_recording.clone();
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            let mut first: Option<Instant> = None;
            for _ in signals.forever() {
                match first {
                    None => {
                        first = Some(Instant::now());
                        let _ = stop_tx.try_send(());
                    }
                    // A terminal's Ctrl-C through a wrapper, or `timeout`, delivers the signal
                    // to the process group too: a second one in the same instant is the same
                    // request. Only one well after the first, while the shutdown is stuck, cuts
                    // it short, and even then the recording is finished first.
                    Some(t) if t.elapsed() >= SIGNAL_INSIST_AFTER => {
                        if let Some(tx) = er.lock().ok().and_then(|g| g.clone()) {
                            tx.finish_now(Duration::from_secs(2));
                        }
                        std::process::exit(130);
                    }
                    Some(_) => {}
                }
            }
        })
        .map_err(|e| format!("cannot start the signal thread: {e}"))?;

    // DDS participant: ROS_DOMAIN_ID. Unless SUBNET, discovery stays on this host: only 127.0.0.1
    // is announced and every UDP socket is bound to it (rustdds binds 0.0.0.0 otherwise, open to
    // any host), so there is no multicast listener and discovery is unicast on loopback.
    let domain = domain_id_from_env()?;
    let local = discovery_is_local();
    let mut builder = DomainParticipantBuilder::new(domain);
    if local {
        builder = builder
            .with_only_networks([IpAddr::V4(Ipv4Addr::LOCALHOST)])
            .with_bind_address(Ipv4Addr::LOCALHOST);
    }
    let participant = builder
        .build()
        .map_err(|e| format!("cannot create the DDS participant (domain {domain}): {e:?}"))?;
    let context = Context::from_domain_participant(participant)
        .map_err(|e| format!("cannot create the ROS 2 context: {e:?}"))?;

    // Parameters, shared with the spinner's callbacks.
    let (cmd_tx, cmd_rx) = tick::command_channel();
    let shared = Arc::new(Shared {
        params: Mutex::new(setup.params.clone()),
        names: RwLock::new(Names {
            muscles: actuator.muscle_names().to_vec(),
            joints: actuator.joint_names().to_vec(),
        }),
        commands: cmd_tx.clone(),
        armed: AtomicBool::new(false),
        logger: OnceLock::new(),
    });
    let mut options = NodeOptions::new()
        .enable_rosout(!setup.ros_args.disable_rosout)
        .start_parameter_services(true);
    for (n, v) in setup.params.values() {
        options = options.declare_parameter(n, v);
    }
    let sv = shared.clone();
    let sa = shared.clone();
    options = options
        .parameter_validator(Box::new(move |n, v| validate_param(&sv, n, v)))
        .parameter_set_action(Box::new(move |n, v| apply_param(&sa, n, v)));
    let node_name = NodeName::new(&setup.namespace, &setup.name)
        .map_err(|e| format!("invalid node name {}: {e:?}", setup.fqn))?;
    let mut node = context
        .new_node(node_name, options)
        .map_err(|e| format!("cannot create node {}: {e:?}", setup.fqn))?;

    let logger = Logger {
        rosout: if setup.ros_args.disable_rosout {
            None
        } else {
            Some(Arc::new(node.logging_handle()))
        },
        level,
        stdout: !setup.ros_args.disable_stdout,
        name: setup.fqn.trim_start_matches('/').replace('/', "."),
    };
    let _ = shared.logger.set(logger.clone());
    for note in &setup.ignored {
        logger.debug(note);
    }

    // Topics and the service, with the remap rules.
    let resolve = |n: &str| {
        args::resolve(
            n,
            &setup.namespace,
            &setup.name,
            DEFAULT_NODE_NAME,
            &setup.ros_args.remaps,
        )
    };
    let qos = qos_reliable(10);
    let mk_topic = |node: &ros2_client::Node, name: &str, ty: (&str, &str)| {
        let resolved = resolve(name);
        let n = dds_name(&resolved)?;
        node.create_topic(&n, MessageTypeName::new(ty.0, ty.1), &qos)
            .map(|t| (t, resolved.clone()))
            .map_err(|e| format!("cannot create topic {resolved}: {e:?}"))
    };
    let (activation_topic, activation_name) = mk_topic(
        &node,
        "~/activation",
        ("muscle_actuator_msgs", "ActivationCommand"),
    )?;
    let (load_topic, load_name) = mk_topic(
        &node,
        "~/external_load",
        ("muscle_actuator_msgs", "ExternalLoad"),
    )?;
    let (state_topic, state_name) =
        mk_topic(&node, "~/state", ("muscle_actuator_msgs", "ActuatorState"))?;
    let (js_topic, js_name) = mk_topic(&node, "joint_states", ("sensor_msgs", "JointState"))?;
    let (diag_topic, _) = mk_topic(
        &node,
        "/diagnostics",
        ("diagnostic_msgs", "DiagnosticArray"),
    )?;
    let activation_sub = node
        .create_subscription::<ActivationCommand>(&activation_topic, Some(qos.clone()))
        .map_err(|e| format!("cannot subscribe to {activation_name}: {e:?}"))?;
    let (activation_array_topic, activation_array_name) = mk_topic(
        &node,
        "~/activation_array",
        ("std_msgs", "Float64MultiArray"),
    )?;
    let activation_array_sub = node
        .create_subscription::<Float64MultiArray>(&activation_array_topic, Some(qos.clone()))
        .map_err(|e| format!("cannot subscribe to {activation_array_name}: {e:?}"))?;
    // One `~/<muscle>/cmd_activation` per muscle of the start-up configuration whose name makes
    // a valid topic name.
    let mut muscle_command_subs = Vec::new();
    let mut muscle_command_names = Vec::new();
    for m in actuator.muscle_names() {
        let rel = format!("~/{m}/cmd_activation");
        if let Err(e) = args::check_name(&rel) {
            logger.warn(&format!(
                "no ~/<muscle>/cmd_activation topic for muscle {}: not a valid name ({e})",
                input::quote(m)
            ));
            continue;
        }
        let (t, n) = mk_topic(&node, &rel, ("std_msgs", "Float64"))?;
        let sub = node
            .create_subscription::<Float64>(&t, Some(qos.clone()))
            .map_err(|e| format!("cannot subscribe to {n}: {e:?}"))?;
        muscle_command_subs.push((m.clone(), sub));
        muscle_command_names.push(n);
    }
    let load_sub = node
        .create_subscription::<ExternalLoad>(&load_topic, Some(qos.clone()))
        .map_err(|e| format!("cannot subscribe to {load_name}: {e:?}"))?;
    let state_pub = node
        .create_publisher::<ActuatorState>(&state_topic, Some(qos.clone()))
        .map_err(|e| format!("cannot publish {state_name}: {e:?}"))?;
    let js_pub = node
        .create_publisher::<JointState>(&js_topic, Some(qos.clone()))
        .map_err(|e| format!("cannot publish {js_name}: {e:?}"))?;
    let diag_pub = node
        .create_publisher::<DiagnosticArray>(&diag_topic, Some(qos.clone()))
        .map_err(|e| format!("cannot publish /diagnostics: {e:?}"))?;
    let reset_name = resolve("~/reset");
    let reset_server = node
        .create_server::<TriggerRequest, TriggerResponse>(
            ServiceMapping::Enhanced,
            &dds_name(&reset_name)?,
            &ServiceTypeName::new("std_srvs", "Trigger"),
            qos.clone(),
            qos.clone(),
        )
        .map_err(|e| format!("cannot create service {reset_name}: {e:?}"))?;
    let spinner = node
        .spinner()
        .map_err(|e| format!("cannot start the node's spinner: {e:?}"))?;

    // The recording (a failure to start is reported, never fatal).
    let mut recorder = None;
    let mut recorder_error = String::new();
    if record::enabled(&setup.params) {
        match record::start(
            &setup.params,
            &setup.fqn,
            &record::Topics {
                state: &state_name,
                joint_states: &js_name,
                activation: &activation_name,
                load: &load_name,
                activation_array: &activation_array_name,
                muscle_commands: &muscle_command_names,
            },
            &actuator,
        ) {
            Ok(r) => recorder = Some(r),
            Err(e) => recorder_error = e,
        }
    }
    let rec_tx = recorder.as_ref().map(|r| r.sender());
    if let Ok(mut g) = emergency_recording.lock() {
        g.clone_from(&rec_tx);
    }
    let (applied_tx, applied_thread) = match &rec_tx {
        Some(tx) => {
            let (atx, arx) = mpsc::sync_channel::<Applied>(1024);
            let tx = tx.clone();
            let t = std::thread::Builder::new()
                .name("record-inputs".into())
                .spawn(move || record::applied_loop(arx, tx))
                .map_err(|e| format!("cannot start the recorder's input thread: {e}"))?;
            (Some(atx), Some(t))
        }
        None => (None, None),
    };

    // The tick thread and the publisher thread.
    let stats = Arc::new(TickStats::default());
    let inputs = Arc::new(InputStats::default());
    let stop = Arc::new(AtomicBool::new(false));
    let (sample_tx, sample_rx) = mpsc::sync_channel::<Sample>(256);
    let (event_tx, event_rx) = mpsc::sync_channel::<Event>(1024);
    let publish_errors = Arc::new(AtomicU64::new(0));
    let pe = publish_errors.clone();
    let pub_rec = rec_tx.clone();
    let publisher_thread = std::thread::Builder::new()
        .name("publish".into())
        .spawn(move || publish_loop(sample_rx, state_pub, js_pub, pe, pub_rec))
        .map_err(|e| format!("cannot start the publisher thread: {e}"))?;
    let model = actuator.model();
    let rate = actuator.rate_hz();
    let tick_thread = tick::spawn(
        actuator,
        setup.params.publish_every(),
        LoopIo {
            commands: cmd_rx,
            samples: sample_tx,
            events: event_tx,
            stats: stats.clone(),
            stop: stop.clone(),
            applied: applied_tx,
        },
    )
    .map_err(|e| format!("cannot start the tick thread: {e}"))?;
    shared.armed.store(true, Ordering::SeqCst);
    logger.info(&format!(
        "{} up: model {model}, {rate} Hz, domain {domain}, discovery {}; topics {activation_name}, \
         {load_name} -> {state_name}, {js_name}, /diagnostics; service {reset_name}",
        setup.fqn,
        if local { "localhost" } else { "subnet" },
    ));

    let limits = Mutex::new(RateLimit::default());
    let report = |key: &str, sev: Severity, msg: String| {
        let allowed = limits.lock().ok().and_then(|mut l| l.allow(key));
        if let Some(held) = allowed {
            if held > 0 {
                logger.log(sev, &format!("{msg} ({held} more like this held back)"));
            } else {
                logger.log(sev, &msg);
            }
        }
    };
    // An input problem: kept as the last one for /diagnostics, and logged (rate-limited).
    let input_problem = |key: &str, msg: String| {
        if let Ok(mut l) = inputs.last_problem.lock() {
            *l = msg.clone();
        }
        report(key, Severity::Warn, msg);
    };

    let muscle_names = || {
        shared
            .names
            .read()
            .map(|n| n.muscles.clone())
            .unwrap_or_default()
    };
    // Excitations by name, from any of the three activation topics: validated the same way and
    // applied at the next tick boundary.
    let excite =
        |names: &[String], values: &[f64], known: &[String]| match input::validate_activation(
            names, values, known,
        ) {
            Ok(acc) => {
                if !acc.clamped.is_empty() {
                    inputs.clamped_commands.fetch_add(1, Ordering::Relaxed);
                    inputs
                        .clamped_values
                        .fetch_add(acc.clamped.len() as u64, Ordering::Relaxed);
                    let what: Vec<String> = acc
                        .clamped
                        .iter()
                        .map(|(n, u)| format!("{n}={u}"))
                        .collect();
                    let m = format!(
                        "activation: excitation outside [0, 1] clamped: {}",
                        what.join(", ")
                    );
                    input_problem("clamped", m);
                }
                shared.send(Command::Excitation(acc.values));
            }
            Err(rej) => {
                inputs.activation_rejected.fetch_add(1, Ordering::Relaxed);
                inputs.count_rejection(&rej);
                let m = format!("activation command rejected: {rej}");
                input_problem(rej.kind(), m);
            }
        };
    let unreadable = |what: &str, e: String| {
        inputs.malformed.fetch_add(1, Ordering::Relaxed);
        report(
            "malformed",
            Severity::Warn,
            format!("unreadable {what} message: {e}"),
        );
    };
    let activation_task = async {
        let mut stream = std::pin::pin!(activation_sub.async_stream());
        while let Some(r) = stream.next().await {
            inputs.activation_received.fetch_add(1, Ordering::Relaxed);
            match r {
                Ok((msg, _info)) => {
                    if let Some(tx) = &rec_tx {
                        record::put(tx, record::CH_ACTIVATION, msg.header.stamp.to_nanos(), &msg);
                    }
                    excite(&msg.muscle, &msg.excitation, &muscle_names());
                }
                Err(e) => unreadable("activation", format!("{e:?}")),
            }
        }
    };
    // `~/activation_array`: every muscle's excitation, in the configuration's order.
    let activation_array_task = async {
        let mut stream = std::pin::pin!(activation_array_sub.async_stream());
        while let Some(r) = stream.next().await {
            inputs.activation_received.fetch_add(1, Ordering::Relaxed);
            match r {
                Ok((msg, _info)) => {
                    if let Some(tx) = &rec_tx {
                        record::put(tx, record::CH_ACTIVATION_ARRAY, runs::now_ns(), &msg);
                    }
                    let known = muscle_names();
                    // All of them, in order: the names are the configuration's own.
                    let names: Vec<String> = known.iter().take(msg.data.len()).cloned().collect();
                    if msg.data.len() != known.len() {
                        let rej = Rejection::LengthMismatch {
                            names: known.len(),
                            values: msg.data.len(),
                        };
                        inputs.activation_rejected.fetch_add(1, Ordering::Relaxed);
                        inputs.count_rejection(&rej);
                        let m = format!(
                            "activation_array rejected: {} values for {} muscles (in order: {})",
                            msg.data.len(),
                            known.len(),
                            crate::config::excerpt(&known.join(", "))
                        );
                        input_problem(rej.kind(), m);
                        continue;
                    }
                    excite(&names, &msg.data, &known);
                }
                Err(e) => unreadable("activation_array", format!("{e:?}")),
            }
        }
    };
    // `~/<muscle>/cmd_activation`: one muscle's excitation.
    let muscle_command_task = async {
        let streams = muscle_command_subs
            .iter()
            .enumerate()
            .map(|(k, (name, sub))| sub.async_stream().map(move |r| (k, name.clone(), r)));
        let mut all = futures::stream::select_all(streams.map(Box::pin));
        while let Some((k, name, r)) = all.next().await {
            inputs.activation_received.fetch_add(1, Ordering::Relaxed);
            match r {
                Ok((msg, _info)) => {
                    if let Some(tx) = &rec_tx {
                        record::put(tx, record::CH_MUSCLE_COMMANDS + k, runs::now_ns(), &msg);
                    }
                    excite(&[name], &[msg.data], &muscle_names());
                }
                Err(e) => unreadable("cmd_activation", format!("{e:?}")),
            }
        }
        // No muscle topic at all (no muscle name is a valid topic name): nothing to do, but the
        // node goes on (the main loop ends when any of its tasks does).
        futures::future::pending::<()>().await;
    };
    let load_task = async {
        let mut stream = std::pin::pin!(load_sub.async_stream());
        while let Some(r) = stream.next().await {
            inputs.load_received.fetch_add(1, Ordering::Relaxed);
            match r {
                Ok((msg, _info)) => {
                    if let Some(tx) = &rec_tx {
                        record::put(tx, record::CH_LOAD, msg.header.stamp.to_nanos(), &msg);
                    }
                    let known = shared
                        .names
                        .read()
                        .map(|n| n.joints.clone())
                        .unwrap_or_default();
                    match input::validate_load(&msg.joint, &msg.torque, &known) {
                        Ok(acc) => shared.send(Command::Load(acc.values)),
                        Err(rej) => {
                            inputs.load_rejected.fetch_add(1, Ordering::Relaxed);
                            inputs.count_rejection(&rej);
                            let m = format!("external load rejected: {rej}");
                            input_problem(rej.kind(), m);
                        }
                    }
                }
                Err(e) => {
                    inputs.malformed.fetch_add(1, Ordering::Relaxed);
                    report(
                        "malformed",
                        Severity::Warn,
                        format!("unreadable external load message: {e:?}"),
                    );
                }
            }
        }
    };
    let reset_task = async {
        let mut stream = reset_server.receive_request_stream();
        while let Some(r) = stream.next().await {
            let Ok((id, _req)) = r else {
                continue;
            };
            let (tx, rx) = futures::channel::oneshot::channel();
            shared.send(Command::Reset(Some(tx)));
            let timeout = smol::Timer::after(Duration::from_secs(2));
            let resp = futures::select! {
                r = rx.fuse() => match r {
                    Ok(before) => TriggerResponse {
                        success: true,
                        message: format!("reset to the initial state after {before} ticks"),
                    },
                    Err(_) => TriggerResponse {
                        success: false,
                        message: "the tick loop is not running".into(),
                    },
                },
                _ = FutureExt::fuse(timeout) => TriggerResponse {
                    success: false,
                    message: "the tick loop did not answer within 2 s".into(),
                },
            };
            if let Err(e) = reset_server.async_send_response(id, resp).await {
                logger.warn(&format!("reset: cannot send the response: {e:?}"));
            }
        }
    };
    let diag_task = async {
        let mut prev = DiagPrev::default();
        let mut failure_reported = false;
        if !recorder_error.is_empty() {
            logger.error(&format!("not recording: {recorder_error}"));
        } else if let Some(r) = &recorder {
            logger.info(&format!("recording to {}", r.stats().path.display()));
        }
        loop {
            smol::Timer::after(Duration::from_secs(1)).await;
            let p = shared.params.lock().map(|p| p.clone()).unwrap_or_default();
            let rec_status = match &recorder {
                Some(r) => {
                    if let RecorderState::Failed(e) = r.stats().state() {
                        if !failure_reported {
                            failure_reported = true;
                            logger.error(&format!("{e}; the simulation goes on without it"));
                        }
                    }
                    record::Status::Running(r)
                }
                None if !recorder_error.is_empty() => record::Status::StartFailed(&recorder_error),
                None => record::Status::Disabled,
            };
            let msg = diagnostics(
                &setup.fqn,
                &stats,
                &inputs,
                &p,
                publish_errors.load(Ordering::Relaxed),
                &mut prev,
                record::diagnostic(&setup.fqn, &setup.params, &rec_status),
            );
            if let Some(st) = msg.status.first() {
                if st.level == DiagnosticStatus::ERROR
                    && st.message.starts_with("tick loop stalled")
                {
                    report("stalled", Severity::Error, st.message.clone());
                }
            }
            if let Err(e) = diag_pub.async_publish(msg).await {
                logger.debug(&format!("diagnostics: publish failed: {e:?}"));
            }
        }
    };
    let events_task = async {
        let mut late = LateTicks::new();
        loop {
            smol::Timer::after(Duration::from_millis(50)).await;
            if let Some(summary) = late.summary_due() {
                logger.info(&summary);
            }
            while let Ok(e) = event_rx.try_recv() {
                match e {
                    Event::StepFailed { tick, reason } => report(
                        "step_failed",
                        Severity::Error,
                        format!(
                            "tick {tick} failed ({reason}): actuator reset to its initial state, \
                             inputs cleared until the next command"
                        ),
                    ),
                    Event::Overrun { tick, lateness_us } => {
                        let period_us = 1e6 / stats.rate_hz();
                        if late.add(lateness_us, period_us) {
                            report(
                                "overrun",
                                Severity::Warn,
                                format!(
                                    "tick {tick} started {lateness_us:.0} us late (more than \
                                     {LATE_WARN_PERIODS} periods)"
                                ),
                            );
                        }
                    }
                    Event::Resync { skipped } => logger.warn(&format!(
                        "the tick loop stalled: {skipped} ticks skipped, schedule restarted"
                    )),
                    Event::Replaced { model, rate_hz } => logger.info(&format!(
                        "actuator rebuilt: model {model}, {rate_hz} Hz (from the initial state)"
                    )),
                    Event::Reset { at_tick } => {
                        logger.info(&format!("reset to the initial state after {at_tick} ticks"))
                    }
                }
            }
        }
    };

    smol::block_on(async {
        let spin = spinner.spin().fuse();
        let stop_fut = stop_rx.recv().fuse();
        let a = activation_task.fuse();
        let aa = activation_array_task.fuse();
        let mc = muscle_command_task.fuse();
        let l = load_task.fuse();
        let r = reset_task.fuse();
        let d = diag_task.fuse();
        let e = events_task.fuse();
        futures::pin_mut!(spin, stop_fut, a, aa, mc, l, r, d, e);
        futures::select! {
            _ = stop_fut => {},
            res = spin => {
                if let Err(e) = res {
                    logger.error(&format!("the node's spinner failed: {e:?}"));
                }
            },
            _ = a => {}, _ = l => {}, _ = r => {}, _ = d => {}, _ = e => {},
            _ = aa => {},
            _ = mc => {},
        }
    });

    // Clean stop: end the loop, then the publisher; the DDS entities go with the node. A step
    // that never returns must not hold the process: give the loop half a second.
    stop.store(true, Ordering::SeqCst);
    let deadline = Instant::now() + Duration::from_millis(500);
    while !tick_thread.is_finished() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(1));
    }
    if !tick_thread.is_finished() {
        let tick = stats.current_tick.load(Ordering::Relaxed);
        let msg = format!(
            "the tick loop did not stop within 0.5 s (a step at tick {tick} never returned); \
             exiting without it"
        );
        logger.error(&msg);
        return Err(msg);
    }
    let summary: RunSummary = tick_thread
        .join()
        .map_err(|_| "the tick thread panicked".to_string())?;
    drop(cmd_tx);
    drop(shared);
    let _ = publisher_thread.join();
    if let Some(t) = applied_thread {
        let _ = t.join();
    }
    drop(rec_tx);
    if let Some(r) = recorder {
        let path = r.stats().path.clone();
        let (written, dropped) = (
            r.stats().written.load(Ordering::Relaxed),
            r.stats().dropped.load(Ordering::Relaxed),
        );
        match r.finish() {
            RecorderState::Failed(e) => logger.error(&e),
            _ => logger.info(&format!(
                "recording {} finished: {written} messages, {dropped} dropped",
                path.display()
            )),
        }
    }
    logger.info(&format!(
        "stopped after {} ticks: lateness p50 {:.1} us, p99 {:.1} us, max {:.1} us; {} overruns, \
         {} skipped; mean step {:.2} us",
        summary.ticks,
        summary.p50_us,
        summary.p99_us,
        summary.max_us,
        summary.overruns,
        summary.skipped,
        summary.mean_step_us
    ));
    if std::env::var_os("MUSCLE_ACTUATOR_TICK_SUMMARY").is_some() {
        eprintln!(
            "tick-summary: {{\"ticks\": {}, \"overruns\": {}, \"skipped\": {}, \"p50_us\": {:.3}, \
             \"p99_us\": {:.3}, \"max_us\": {:.3}, \"mean_step_us\": {:.3}}}",
            summary.ticks,
            summary.overruns,
            summary.skipped,
            summary.p50_us,
            summary.p99_us,
            summary.max_us,
            summary.mean_step_us
        );
    }
    signals_handle.close();
    drop(reset_server);
    drop(activation_sub);
    drop(activation_array_sub);
    drop(muscle_command_subs);
    drop(load_sub);
    drop(diag_pub);
    drop(node);
    drop(context);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn setup_applies_arguments_in_order() {
        let argv: Vec<String> =
            "--ros-args -r __ns:=/lab -p model:=hill -p rate_hz:=250 -p model:=huxley"
                .split_whitespace()
                .map(String::from)
                .collect();
        let s = setup(&argv).unwrap().unwrap();
        assert_eq!(s.fqn, "/lab/muscle_actuator");
        assert_eq!(s.params.model.name(), "huxley");
        assert_eq!(s.params.rate_hz, 250.0);
        let bad: Vec<String> = "--ros-args -p rate_hz:=-1"
            .split_whitespace()
            .map(String::from)
            .collect();
        assert!(setup(&bad).unwrap_err().contains("rate_hz"));
        // An undeclared parameter is ignored with a note; a declared one keeps its checks.
        let unknown: Vec<String> = "--ros-args -p colour:=red -p model:=hill"
            .split_whitespace()
            .map(String::from)
            .collect();
        let s = setup(&unknown).unwrap().unwrap();
        assert_eq!(s.params.model.name(), "hill");
        assert_eq!(s.ignored.len(), 1);
        assert!(s.ignored[0].contains("colour"), "{:?}", s.ignored);
        let bad: Vec<String> = "--ros-args -p colour:=red -p record:=maybe"
            .split_whitespace()
            .map(String::from)
            .collect();
        assert!(setup(&bad).unwrap_err().contains("record"));
    }
}
