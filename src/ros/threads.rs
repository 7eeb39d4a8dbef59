//! The node's threads beside the DDS executor: the tick loop, the publisher
//! ([`outputs::publish_loop`]), and (when recording) the thread that turns applied inputs into
//! messages. Started together; stopped in
//! order, the tick loop first, each ending when its input channel closes.

use super::live::LiveTap;
use super::logging::Logger;
use super::outputs::{self, Emitter, Sinks};
use super::record::{self, RecordTx};
use super::tick::{
    self, Applied, CommandReceiver, Event, LoopIo, Output, Pacing, RunSummary, TickStats,
};
use muscle_actuator_core::sim::Actuator;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Capacity of the channels from the tick loop: states to publish, events to log, applied
/// inputs to record. Each is bounded and counts what it drops ([`TickStats`]).
const SAMPLE_QUEUE: usize = 256;
const EVENT_QUEUE: usize = 1024;
const APPLIED_QUEUE: usize = 1024;

/// How long a stop waits for the tick loop to return from its step.
const TICK_STOP_GRACE: Duration = Duration::from_millis(500);

/// What the threads are given.
pub(crate) struct ThreadInputs {
    pub(crate) actuator: Actuator,
    pub(crate) publish_every: u64,
    pub(crate) commands: CommandReceiver,
    /// The outputs the node publishes ([`outputs`]).
    pub(crate) published: Vec<Box<dyn Emitter>>,
    pub(crate) rec: Option<RecordTx>,
    pub(crate) live: Option<LiveTap>,
    /// The stamp of tick 0, ns (since the Unix epoch for the wall clock).
    pub(crate) tick_origin_ns: i64,
    pub(crate) pacing: Pacing,
}

/// Why the node's threads cannot start, or did not stop cleanly.
#[derive(Debug, thiserror::Error)]
pub enum ThreadsError {
    /// A thread cannot be started.
    #[error("cannot start the {thread} thread: {source}")]
    Spawn {
        /// Which: "recorder's input", "publisher", "tick".
        thread: &'static str,
        /// Why.
        source: std::io::Error,
    },
    /// The tick loop outlived its grace at the stop.
    #[error(
        "the tick loop did not stop within {grace_s} s (a step at tick {tick} never returned); \
         exiting without it"
    )]
    StopTimeout {
        /// The grace, s.
        grace_s: f64,
        /// The tick it was stepping.
        tick: u64,
    },
    /// The tick thread panicked.
    #[error("the tick thread panicked")]
    TickPanicked,
}

/// The error of starting `thread`.
fn spawn_error(thread: &'static str) -> impl FnOnce(std::io::Error) -> ThreadsError {
    move |source| ThreadsError::Spawn { thread, source }
}

/// The running threads.
pub(crate) struct Threads {
    stop: Arc<AtomicBool>,
    tick: JoinHandle<RunSummary>,
    publisher: JoinHandle<()>,
    applied: Option<JoinHandle<()>>,
    pub(crate) stats: Arc<TickStats>,
    pub(crate) publish_errors: Arc<AtomicU64>,
}

impl Threads {
    /// Starts them; returns the receiver of the tick loop's events too.
    pub(crate) fn start(t: ThreadInputs) -> Result<(Self, Receiver<Event>), ThreadsError> {
        let (applied_tx, applied) = match &t.rec {
            Some(tx) => {
                let (atx, arx) = mpsc::sync_channel::<Applied>(APPLIED_QUEUE);
                let tx = tx.clone();
                let h = std::thread::Builder::new()
                    .name("record-inputs".into())
                    .spawn(move || record::applied_loop(arx, tx))
                    .map_err(spawn_error("recorder's input"))?;
                (Some(atx), Some(h))
            }
            None => (None, None),
        };
        let stats = Arc::new(TickStats::default());
        let stop = Arc::new(AtomicBool::new(false));
        let (sample_tx, sample_rx) = mpsc::sync_channel::<Output>(SAMPLE_QUEUE);
        let (event_tx, event_rx) = mpsc::sync_channel::<Event>(EVENT_QUEUE);
        let publish_errors = Arc::new(AtomicU64::new(0));
        let sinks = Sinks {
            errors: publish_errors.clone(),
            rec: t.rec.clone(),
            live: t.live,
        };
        let published = t.published;
        let publisher = std::thread::Builder::new()
            .name("publish".into())
            .spawn(move || outputs::publish_loop(sample_rx, published, sinks))
            .map_err(spawn_error("publisher"))?;
        let tick = tick::spawn(
            t.actuator,
            t.publish_every,
            LoopIo {
                commands: t.commands,
                samples: sample_tx,
                events: event_tx,
                stats: stats.clone(),
                stop: stop.clone(),
                applied: applied_tx,
                tick_origin_ns: t.tick_origin_ns,
                pacing: t.pacing,
            },
        )
        .map_err(spawn_error("tick"))?;
        Ok((
            Self {
                stop,
                tick,
                publisher,
                applied,
                stats,
                publish_errors,
            },
            event_rx,
        ))
    }

    /// Stops the tick loop, then the publisher and the input recorder, which end once the
    /// loop's channels close. A step that never returns must not hold the process: the loop
    /// gets [`TICK_STOP_GRACE`], then the stop goes on without it (an error).
    pub(crate) fn stop(self, logger: &Logger) -> Result<RunSummary, ThreadsError> {
        self.stop.store(true, Ordering::SeqCst);
        let deadline = Instant::now() + TICK_STOP_GRACE;
        while !self.tick.is_finished() && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(1));
        }
        if !self.tick.is_finished() {
            let tick = self.stats.current_tick.load(Ordering::Relaxed);
            let e = ThreadsError::StopTimeout {
                grace_s: TICK_STOP_GRACE.as_secs_f64(),
                tick,
            };
            logger.error(&e.to_string());
            return Err(e);
        }
        let summary = self.tick.join().map_err(|_| ThreadsError::TickPanicked)?;
        let _ = self.publisher.join();
        if let Some(t) = self.applied {
            let _ = t.join();
        }
        Ok(summary)
    }
}

/// The whole run's timing, logged (and printed as JSON when `MUSCLE_ACTUATOR_TICK_SUMMARY` is
/// set, for the benchmarks).
pub(crate) fn log_summary(logger: &Logger, s: &RunSummary) {
    logger.info(&format!(
        "stopped after {} ticks: lateness p50 {:.1} us, p99 {:.1} us, max {:.1} us; {} overruns, \
         {} skipped; mean step {:.2} us",
        s.ticks, s.p50_us, s.p99_us, s.max_us, s.overruns, s.skipped, s.mean_step_us
    ));
    if std::env::var_os("MUSCLE_ACTUATOR_TICK_SUMMARY").is_some() {
        eprintln!(
            "tick-summary: {{\"ticks\": {}, \"overruns\": {}, \"skipped\": {}, \"p50_us\": {:.3}, \
             \"p99_us\": {:.3}, \"max_us\": {:.3}, \"mean_step_us\": {:.3}}}",
            s.ticks, s.overruns, s.skipped, s.p50_us, s.p99_us, s.max_us, s.mean_step_us
        );
    }
}
