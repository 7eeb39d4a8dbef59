//! The node's main: set-up, the DDS endpoints, the recording, the threads, the tasks on the
//! executor (the inputs, the services, `/diagnostics`, the live view's requests, the tick loop's
//! events), and the stop. Each piece lives in its own module; this one only wires them.

use super::clock::{ClockMode, NodeClock};
use super::dds::{Dds, DdsError, Endpoints, Served};
use super::diagnostics::{self, DiagSources, InputStats};
use super::endpoints::{Endpoint, Names};
use super::error::NodeError;
use super::events;
use super::inputs::{self, InputContext};
use super::live::{Catalogue, LiveOptions, LiveStatus, LiveView, Request};
use super::live_requests;
use super::logging::{Logger, Reporter};
use super::node_state::NodeState;
use super::param_callbacks;
use super::record::{self, NodeRecorder, RecordTx};
use super::services;
use super::setup::{setup, Setup};
use super::severity::Severity;
use super::signals::StopSignals;
use super::threads::{self, ThreadInputs, Threads};
use super::tick::{self, Event, Pacing};
use futures::FutureExt;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_recording::recording::RecorderState;
use ros2_client::{NodeName, NodeOptions, ParameterValue, Spinner};
use std::sync::atomic::Ordering;
use std::sync::mpsc::Receiver;
use std::sync::{Arc, OnceLock};

/// Runs the node (see [`super::run_node`]): the set-up, the DDS endpoints, the recording, the
/// threads, the executor until a stop signal, and the stop.
pub fn run(argv: &[String]) -> Result<(), NodeError> {
    let Some(setup) = setup(argv)? else {
        return Ok(());
    };
    let actuator = setup.params.build()?;
    let signals = StopSignals::install()?;
    let dds = Dds::start()?;
    let (cmd_tx, cmd_rx) = tick::command_channel();
    let shared = Arc::new(NodeState::new(&setup.params, &actuator, cmd_tx));
    let mut node = create_node(&setup, &dds, &shared)?;
    let clock = Arc::new(NodeClock::new(
        setup.params.clock.with_sim_time(setup.use_sim_time),
    ));
    let logger = logger(&setup, &node, &clock);
    log_notes(&setup, &logger);
    let endpoints = Endpoints::create(
        &mut node,
        &setup,
        actuator.muscle_names(),
        clock.mode(),
        !actuator.driven_joints().is_empty(),
        &logger,
    )?;
    let (live, live_error) = start_live(&setup, &dds, &endpoints.names, clock.mode(), &logger);
    let spinner = node.spinner().map_err(|e| DdsError::Spinner {
        reason: format!("{e:?}"),
    })?;

    // Tick 0's stamp, the recording's tick origin: the loop starts right after.
    let tick_origin_ns = clock.start_origin_ns();
    let (recorder, recorder_error) = start_recording(
        &setup,
        &endpoints.names,
        &actuator,
        &clock,
        tick_origin_ns,
        &logger,
    );
    let rec = recording_tx(recorder.as_ref(), &signals, &logger);
    let (model, rate) = (actuator.model(), actuator.rate_hz());
    let (threads, events) = Threads::start(ThreadInputs {
        actuator,
        publish_every: setup.params.publish_every(),
        commands: cmd_rx,
        published: endpoints.published,
        rec: rec.clone(),
        live: live.as_ref().map(LiveView::tap),
        tick_origin_ns,
        pacing: Pacing {
            clock: clock.clone(),
            real_time_factor: setup.params.real_time_factor,
            clock_every: setup.params.clock_every(),
        },
    })?;
    shared.arm(&logger);
    log_up(
        &setup,
        &dds,
        &endpoints.names,
        clock.mode(),
        &logger,
        model,
        rate,
    );
    serve(
        Executor {
            setup: &setup,
            served: &endpoints.served,
            shared: &shared,
            threads: &threads,
            events: &events,
            recorder: recorder.as_ref(),
            recorder_error: &recorder_error,
            clock: &clock,
            logger: &logger,
            rec: rec.clone(),
            signals: &signals,
            node: &node,
            live: live.as_ref(),
            live_error: &live_error,
            participant: dds.context.domain_participant(),
        },
        spinner,
    );
    if let Some(l) = live {
        l.stop();
    }
    stop(threads, recorder, rec, &signals, &logger)
}

/// The live view the parameters ask for, or why it could not start (a warning: the node runs
/// on without it).
fn start_live(
    setup: &Setup,
    dds: &Dds,
    n: &Names,
    mode: ClockMode,
    logger: &Logger,
) -> (Option<LiveView>, String) {
    let port = setup.params.foxglove_port;
    if port == 0 {
        return (None, String::new());
    }
    let started = Catalogue::new(n).and_then(|catalogue| {
        LiveView::start(LiveOptions {
            port,
            local: dds.local,
            catalogue,
            name: &setup.fqn,
            sim_time: mode.publishes_clock(),
        })
    });
    match started {
        Ok(v) => {
            let _ = logger.live.set(v.tap());
            logger.info(&format!(
                "live view: ws://{} (in Foxglove or Lichtblick: Open connection, Foxglove \
                 WebSocket)",
                v.addr
            ));
            (Some(v), String::new())
        }
        Err(e) => {
            logger.warn(&format!(
                "live view (foxglove) not started: {e}; the node runs on without it \
                 (-p foxglove_port:=N for another port, 0 for none)"
            ));
            (None, e.to_string())
        }
    }
}

/// The node on DDS, its parameter services started (`use_sim_time` declared when given).
fn create_node(
    setup: &Setup,
    dds: &Dds,
    shared: &Arc<NodeState>,
) -> Result<ros2_client::Node, DdsError> {
    let mut options = NodeOptions::new()
        .enable_rosout(!setup.ros_args.disable_rosout)
        .start_parameter_services(true);
    if setup.use_sim_time {
        // Reported by the parameter services as given (the store's default is false).
        options = options.declare_parameter("use_sim_time", ParameterValue::Boolean(true));
    }
    let node_name =
        NodeName::new(&setup.namespace, &setup.name).map_err(|e| DdsError::NodeName {
            fqn: setup.fqn.clone(),
            reason: format!("{e:?}"),
        })?;
    dds.context
        .new_node(
            node_name,
            param_callbacks::attach(shared, options, &setup.params),
        )
        .map_err(|e| DdsError::Node {
            fqn: setup.fqn.clone(),
            reason: format!("{e:?}"),
        })
}

/// What the set-up noted before the logger existed, and `use_sim_time` where the node is the
/// clock itself.
fn log_notes(setup: &Setup, logger: &Logger) {
    for note in &setup.ignored {
        logger.debug(note);
    }
    if setup.use_sim_time && setup.params.clock.publishes_clock() {
        logger.info(&format!(
            "use_sim_time is true, but clock:={} makes this node the graph's clock: it \
             publishes /clock and does not follow one",
            setup.params.clock.name()
        ));
    }
}

/// The line that says the node is up: model, rate, clock, DDS domain, topics and services.
fn log_up(
    setup: &Setup,
    dds: &Dds,
    n: &Names,
    mode: ClockMode,
    logger: &Logger,
    model: ModelKind,
    rate: f64,
) {
    logger.info(&format!(
        "{} up: model {model}, {rate} Hz, clock {}, domain {}, discovery {}; topics {}, {} -> {}, \
         {}, /diagnostics; services {}, {}",
        setup.fqn,
        mode.name(),
        dds.domain,
        if dds.local { "localhost" } else { "subnet" },
        n.name(Endpoint::Activation),
        n.name(Endpoint::Load),
        n.name(Endpoint::State),
        n.name(Endpoint::JointStates),
        n.name(Endpoint::Reset),
        n.name(Endpoint::Step)
    ));
}

/// What the executor runs on.
struct Executor<'a> {
    setup: &'a Setup,
    served: &'a Served,
    shared: &'a NodeState,
    threads: &'a Threads,
    events: &'a Receiver<Event>,
    recorder: Option<&'a NodeRecorder>,
    recorder_error: &'a str,
    clock: &'a NodeClock,
    logger: &'a Logger,
    rec: Option<RecordTx>,
    signals: &'a StopSignals,
    node: &'a ros2_client::Node,
    live: Option<&'a LiveView>,
    live_error: &'a str,
    /// For its counts of service replies held (`/diagnostics`).
    participant: rustdds::DomainParticipant,
}

/// The executor: spinner, inputs, services, diagnostics and events, until a stop signal.
fn serve(x: Executor<'_>, spinner: Spinner) {
    let e = x.served;
    let log = Reporter::new(x.logger.clone());
    let inputs = InputStats::default();
    let mode = x.clock.mode();
    let cx = InputContext {
        shared: x.shared,
        stats: &inputs,
        log: &log,
        rec: x.rec.clone(),
        mode,
        muscle_topics: &e.muscle_topics,
    };
    let diag = DiagSources {
        fqn: &x.setup.fqn,
        ticks: &x.threads.stats,
        inputs: &inputs,
        shared: x.shared,
        publish_errors: &x.threads.publish_errors,
        startup_params: &x.setup.params,
        recorder: x.recorder.map(|r| &r.recorder),
        recorder_error: x.recorder_error,
        clock: x.clock,
        live: match x.live {
            Some(l) => LiveStatus::Serving(l.stats(), l.addr),
            None if !x.live_error.is_empty() => LiveStatus::Failed(x.live_error),
            None => LiveStatus::Off,
        },
        participant: &x.participant,
    };
    let lcx = live_requests::Context {
        inputs: &cx,
        node: x.node,
    };
    // Biased: each wake polls the inputs before the step service, so that inputs received
    // before a step request take effect at its first tick.
    smol::block_on(async {
        futures::select_biased! {
            _ = x.signals.requested.recv().fuse() => {},
            _ = inputs::serve(&e.inputs, &cx).fuse() => {},
            _ = services::step(&e.step, x.shared, mode, &log).fuse() => {},
            _ = services::reset(&e.reset, x.shared, &log).fuse() => {},
            res = spinner.spin().fuse() => {
                if let Err(e) = res {
                    x.logger.error(&format!("the node's spinner failed: {e:?}"));
                }
            },
            _ = diagnostics::publish_task(
                diag, &e.diagnostics, &log, x.rec.clone(), x.live.map(LiveView::tap)
            ).fuse() => {},
            _ = live_in(x.live.map(|l| &l.requests), &lcx).fuse() => {},
            _ = events::log_events(x.events, &x.threads.stats, &log, x.rec.as_ref()).fuse() => {},
        }
    });
}

/// The stop: the threads, then the recording (the summary line still goes into it).
fn stop(
    threads: Threads,
    recorder: Option<NodeRecorder>,
    rec: Option<RecordTx>,
    signals: &StopSignals,
    logger: &Logger,
) -> Result<(), NodeError> {
    let summary = threads.stop(logger)?;
    threads::log_summary(logger, &summary);
    drop(rec);
    if let Some(r) = recorder {
        finish_recording(r, logger);
    }
    signals.close();
    Ok(())
}

/// The live view's requests when it runs; otherwise nothing, for ever.
async fn live_in(rx: Option<&smol::channel::Receiver<Request>>, cx: &live_requests::Context<'_>) {
    match rx {
        Some(rx) => live_requests::serve(rx, cx).await,
        None => futures::future::pending().await,
    }
}

/// The node's logger: stderr and `/rosout` as the ROS arguments say.
fn logger(setup: &Setup, node: &ros2_client::Node, clock: &Arc<NodeClock>) -> Logger {
    let a = &setup.ros_args;
    Logger {
        rosout: (!a.disable_rosout).then(|| Arc::new(node.logging_handle())),
        level: a.log_level.unwrap_or(Severity::Info),
        stdout: !a.disable_stdout,
        name: setup.fqn.trim_start_matches('/').replace('/', "."),
        recording: Arc::new(OnceLock::new()),
        live: Arc::new(OnceLock::new()),
        clock: clock.clone(),
    }
}

/// The recording the parameters ask for, or why it could not start (reported, never fatal).
fn start_recording(
    setup: &Setup,
    names: &Names,
    actuator: &muscle_actuator_core::sim::Actuator,
    clock: &Arc<NodeClock>,
    tick_origin_ns: i64,
    logger: &Logger,
) -> (Option<NodeRecorder>, String) {
    if !record::enabled(&setup.params) {
        return (None, String::new());
    }
    match record::start(
        &setup.params,
        &setup.fqn,
        names,
        actuator,
        clock,
        tick_origin_ns,
    ) {
        Ok(r) => {
            logger.info(&format!(
                "recording to {}",
                r.recorder.stats().path.display()
            ));
            (Some(r), String::new())
        }
        Err(e) => {
            logger.error(&format!("not recording: {e}"));
            (None, e.to_string())
        }
    }
}

/// The recording's sender, for the threads and tasks; an insisted stop (a second signal)
/// finishes the recording through it, and the logger records its lines through it.
fn recording_tx(
    recorder: Option<&NodeRecorder>,
    signals: &StopSignals,
    logger: &Logger,
) -> Option<RecordTx> {
    let rec = recorder.map(NodeRecorder::tx);
    signals.guard_recording(rec.as_ref().map(|r| r.sender.clone()));
    if let Some(r) = &rec {
        let _ = logger.recording.set(r.clone());
    }
    rec
}

/// Writes the recording's summary and says how it ended.
fn finish_recording(r: NodeRecorder, logger: &Logger) {
    let st = r.recorder.stats().clone();
    let path = st.path.clone();
    match r.recorder.finish() {
        RecorderState::Failed(e) => logger.error(&e),
        _ => logger.info(&format!(
            "recording {} finished: {} messages, {} dropped",
            path.display(),
            st.written.load(Ordering::Relaxed),
            st.dropped.load(Ordering::Relaxed)
        )),
    }
}
