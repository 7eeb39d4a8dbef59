//! The loop itself: a [`TickLoop`] holds the actuator and everything the loop keeps from one
//! tick to the next; [`TickLoop::run`] turns it, each turn in this order (the order the node's
//! stamps, applied inputs and replays depend on, docs/recordings.md and docs/time.md):
//! 1. take the commands that arrived, and the inputs whose stamp has come
//!    ([`TickLoop::take_commands`]);
//! 2. apply them, in that order ([`TickLoop::apply`], in `apply.rs`);
//! 3. a driven loop with nothing to do parks until a command arrives ([`TickLoop::waiting`]);
//! 4. step the actuator once ([`TickLoop::step`]);
//! 5. hand the state and the time over, never waiting ([`TickLoop::hand_over`]);
//! 6. a paced loop waits for the next deadline ([`TickLoop::pace`]);
//! 7. once a second, the window's timing figures to [`TickStats`].
//!
//! Nothing on this path allocates (docs/model.md §10): the command buffers, the schedule, the
//! lockstep steps and the histograms are sized before the first tick; samples share the names by
//! reference count.

use super::super::clock::{ticks_covered, ClockMode};
use super::messages::{Applied, AppliedInput, Command, Event, Output, Sample};
use super::pacing::{self, Deadlines, Pacing, LOCKSTEP_IDLE};
use super::queue::{CommandReceiver, Drain, CONTROL_RESERVE};
use super::realtime;
use super::stamped_inputs::Schedule;
use super::stats::{RunSummary, TickStats, Timing};
use muscle_actuator_core::sim::Actuator;
use muscle_actuator_core::time::TimeBase;
use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{SyncSender, TrySendError};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The channels and flags of a running loop.
pub struct LoopIo {
    pub commands: CommandReceiver,
    pub samples: SyncSender<Output>,
    pub events: SyncSender<Event>,
    pub stats: Arc<TickStats>,
    pub stop: Arc<AtomicBool>,
    /// Where applied inputs go for the recording (never waited on: dropped when full).
    pub applied: Option<SyncSender<Applied>>,
    /// The stamp of tick 0, ns since the Unix epoch (the recording's tick origin). After a reset
    /// or a rebuild, tick 0 is re-anchored one period before the wall-clock time of the next
    /// step (simulated clocks: at the simulated time reached, so that time never goes back).
    pub tick_origin_ns: i64,
    pub pacing: Pacing,
}

/// A lockstep step asked for: the ticks left, and who wants the state after the last of them.
pub(super) type StepRequest = (u64, Option<futures::channel::oneshot::Sender<Sample>>);

/// The actuator's names, shared with every sample (a clone is a reference count).
pub(super) struct Names {
    pub(super) muscles: Arc<[String]>,
    pub(super) joints: Arc<[String]>,
    /// The driven joints (indices, configuration order).
    pub(super) driven: Arc<[usize]>,
}

impl Names {
    pub(super) fn of(actuator: &Actuator) -> Self {
        Self {
            muscles: actuator.muscle_names().into(),
            joints: actuator.joint_names().into(),
            driven: actuator.driven_joints().into(),
        }
    }
}

/// The loop's state between ticks.
pub(super) struct TickLoop {
    pub(super) actuator: Actuator,
    pub(super) io: LoopIo,
    pub(super) mode: ClockMode,
    /// Publish a state every `publish_every`th tick.
    pub(super) publish_every: u64,
    /// `sim`: simulated seconds per wall-clock second (0 = as fast as possible).
    pub(super) real_time_factor: f64,
    /// Simulated clocks: publish `/clock` every `clock_every`th tick.
    pub(super) clock_every: u64,
    /// Stamps: tick k is stamped `tick_origin_ns + k / rate`.
    pub(super) clock: TimeBase,
    /// Following `/clock`: the latest clock time received, ns.
    pub(super) follow_until: Option<i64>,
    /// Lockstep: the steps asked for, in order.
    pub(super) steps: VecDeque<StepRequest>,
    pub(super) names: Names,
    /// Ticks since a driven joint's motion last arrived (`u64::MAX`: none yet).
    pub(super) motion_age: u64,
    /// The inputs in force: excitation by muscle, external torque by joint (N m).
    pub(super) excitation: Vec<f64>,
    pub(super) load: Vec<f64>,
    /// One tick of simulated time.
    pub(super) period: Duration,
    pub(super) deadlines: Deadlines,
    pub(super) timing: Timing,
    /// The commands taken from the queue this tick, and those to apply (sized once).
    pub(super) commands: Vec<Command>,
    pub(super) ready: Vec<Command>,
    /// Inputs stamped ahead, waiting for their tick.
    pub(super) schedule: Schedule,
}

impl TickLoop {
    /// The loop for `actuator`, set up on the calling thread (the tick thread): its timer slack,
    /// SCHED_FIFO for the wall clock, a wake-up on every command for a driven loop.
    pub(super) fn start(actuator: Actuator, publish_every: u64, io: LoopIo) -> Self {
        realtime::tighten_timer_slack();
        let mode = io.pacing.clock.mode();
        if mode == ClockMode::Wall {
            io.stats
                .realtime
                .store(realtime::request_realtime_priority(), Ordering::Relaxed);
        }
        if mode.is_driven() {
            io.commands.wake_me();
        }
        let names = Names::of(&actuator);
        io.stats
            .driven_joints
            .store(names.driven.len() as u64, Ordering::Relaxed);
        let excitation = vec![0.0; names.muscles.len()];
        let load = vec![0.0; names.joints.len()];
        let period = Duration::from_secs_f64(1.0 / actuator.rate_hz());
        io.stats
            .rate_hz_bits
            .store(actuator.rate_hz().to_bits(), Ordering::Relaxed);
        let timing = Timing::new();
        let deadlines = Deadlines::start();
        let clock = TimeBase::WallOrigin {
            tick_origin_ns: io.tick_origin_ns,
        };
        Self {
            mode,
            publish_every,
            real_time_factor: io.pacing.real_time_factor,
            clock_every: io.pacing.clock_every.max(1),
            clock,
            follow_until: None,
            steps: VecDeque::with_capacity(CONTROL_RESERVE),
            names,
            motion_age: u64::MAX,
            excitation,
            load,
            period,
            deadlines,
            timing,
            commands: io.commands.buffer(),
            ready: io.commands.buffer(),
            schedule: Schedule::new(),
            actuator,
            io,
        }
    }

    /// Runs the loop until `io.stop` is set (or the command channel closes). Ticks at the
    /// actuator's rate against absolute deadlines; a tick that starts more than one period late
    /// is an overrun.
    pub(super) fn run(mut self) -> RunSummary {
        while !self.io.stop.load(Ordering::Relaxed) {
            self.take_commands();
            self.apply_ready();
            if self.waiting() {
                std::thread::park_timeout(LOCKSTEP_IDLE);
                continue;
            }
            self.step();
            self.hand_over();
            if self.paced() {
                self.pace();
            }
            self.timing.report(Instant::now(), &self.io.stats);
        }
        self.timing.summary()
    }

    /// The stamp of the actuator's current tick, ns.
    pub(super) fn stamp_ns(&self) -> i64 {
        self.clock
            .stamp_ns(self.actuator.tick(), self.actuator.rate_hz())
    }

    /// The commands that arrived since the last tick, never waiting for the queue (when a sender
    /// holds it, they take effect at the next tick), into `ready` after the inputs whose stamp
    /// has come (in stamp order); inputs stamped ahead wait in the schedule.
    fn take_commands(&mut self) {
        let stats = &self.io.stats;
        match self.io.commands.try_drain(&mut self.commands) {
            Drain::Taken => {}
            Drain::Busy => {
                stats.commands_deferred.fetch_add(1, Ordering::Relaxed);
            }
            Drain::Disconnected => self.io.stop.store(true, Ordering::Relaxed),
        }
        stats
            .commands_dropped
            .store(self.io.commands.dropped(), Ordering::Relaxed);
        let now_ns = self.stamp_ns();
        while let Some(c) = self.schedule.pop_due(now_ns) {
            self.ready.push(c);
        }
        for command in self.commands.drain(..) {
            match command {
                Command::Stamped(at, input) if Schedule::holds(self.mode, at, now_ns) => {
                    if !self.schedule.insert(at, *input) {
                        stats.scheduled_dropped.fetch_add(1, Ordering::Relaxed);
                    }
                }
                Command::Stamped(_, input) => self.ready.push(*input),
                other => self.ready.push(other),
            }
        }
        stats
            .scheduled_pending
            .store(self.schedule.len() as u64, Ordering::Relaxed);
    }

    /// Applies the commands taken, in order (the buffer keeps its room for the next tick).
    fn apply_ready(&mut self) {
        let mut ready = std::mem::take(&mut self.ready);
        for command in ready.drain(..) {
            self.apply(command);
        }
        self.ready = ready;
    }

    /// Lockstep: nothing to do until a step is asked for; following `/clock`, until the clock
    /// covers the next tick (a sender wakes the loop).
    fn waiting(&self) -> bool {
        match self.mode {
            ClockMode::Lockstep => self.steps.is_empty(),
            ClockMode::Follow => self.follow_until.is_none_or(|ns| {
                ticks_covered(self.clock, ns, self.actuator.rate_hz()) <= self.actuator.tick()
            }),
            _ => false,
        }
    }

    /// One step. A failed one puts the actuator back to its initial state with the inputs
    /// cleared (whatever drove the state out of range is not applied again); the next valid
    /// command applies as usual.
    fn step(&mut self) {
        let t0 = Instant::now();
        if let Err(e) = self.actuator.step() {
            let tick = e.tick;
            self.reanchor(tick);
            self.back_to_rest();
            self.io.stats.step_failures.fetch_add(1, Ordering::Relaxed);
            self.event(Event::StepFailed {
                tick,
                reason: e.reason,
            });
        }
        self.timing.stepped(t0.elapsed().as_nanos() as u64);
        self.io.stats.ticks.fetch_add(1, Ordering::Relaxed);
        self.io
            .stats
            .current_tick
            .store(self.actuator.tick(), Ordering::Relaxed);
    }

    /// The state (and the time) to the publisher, and to the lockstep step that asked for it,
    /// never waiting, in every mode: the loop's pace is never the publisher's; what the publisher
    /// cannot take is counted (`samples_dropped`).
    fn hand_over(&mut self) {
        let stamp_ns = self.stamp_ns();
        self.motion_age = self.motion_age.saturating_add(1);
        self.io
            .stats
            .joint_motion_age_ticks
            .store(self.motion_age, Ordering::Relaxed);
        if self.mode.is_simulated() {
            self.io.pacing.clock.advance_to(stamp_ns);
        }
        let tick = self.actuator.tick();
        if self.mode.publishes_clock() && tick.is_multiple_of(self.clock_every) {
            self.hand(Output::Clock(stamp_ns));
        }
        if tick.is_multiple_of(self.publish_every) || self.publish_every == 1 {
            self.hand(Output::State(self.sample(stamp_ns)));
        }
        if let Some(front) = self.steps.front_mut() {
            front.0 -= 1;
            if front.0 == 0 {
                if let Some((_, Some(reply))) = self.steps.pop_front() {
                    let _ = reply.send(self.sample(stamp_ns));
                }
            }
        }
    }

    /// The state after the tick stamped `stamp_ns`.
    fn sample(&self, stamp_ns: i64) -> Sample {
        Sample {
            tick: self.actuator.tick(),
            stamp_ns,
            model: self.actuator.model(),
            muscle_names: self.names.muscles.clone(),
            joint_names: self.names.joints.clone(),
            driven: self.names.driven.clone(),
            state: self.actuator.state().clone(),
        }
    }

    /// Passes `o` to the publisher, never waiting (counted when it has no room).
    fn hand(&self, o: Output) {
        match self.io.samples.try_send(o) {
            Ok(()) => {}
            Err(TrySendError::Full(_)) => {
                self.io
                    .stats
                    .samples_dropped
                    .fetch_add(1, Ordering::Relaxed);
            }
            Err(TrySendError::Disconnected(_)) => {}
        }
    }

    /// Passes `e` to the log, never waiting (counted when it has no room).
    pub(super) fn event(&self, e: Event) {
        if let Err(TrySendError::Full(_)) = self.io.events.try_send(e) {
            self.io.stats.events_dropped.fetch_add(1, Ordering::Relaxed);
        }
    }

    /// Passes applied inputs to the recorder, if any (never waits).
    pub(super) fn hand_applied(&self, names: &Arc<[String]>, input: AppliedInput) {
        if let Some(tx) = &self.io.applied {
            if let Err(TrySendError::Full(_)) = tx.try_send(Applied {
                tick: self.actuator.tick(),
                stamp_ns: self.stamp_ns(),
                names: names.clone(),
                input,
            }) {
                self.io
                    .stats
                    .applied_dropped
                    .fetch_add(1, Ordering::Relaxed);
            }
        }
    }

    /// Whether the loop waits for deadlines: `wall`, and `sim` with a real-time factor
    /// (lockstep, and sim as fast as possible, have none: the next tick at once).
    fn paced(&self) -> bool {
        self.mode == ClockMode::Wall || (self.mode == ClockMode::Sim && self.real_time_factor > 0.0)
    }

    /// Waits for the next deadline (wall: one period; sim: a period / `real_time_factor`) and
    /// accounts for the lateness: an overrun beyond one pace, a new schedule beyond
    /// [`pacing::RESYNC_PERIODS`].
    fn pace(&mut self) {
        let pace = if self.mode == ClockMode::Sim {
            self.period.div_f64(self.real_time_factor)
        } else {
            self.period
        };
        let wake = self.deadlines.sleep_until_next(pace);
        let late_ns = wake.late.as_nanos() as u64;
        self.timing.lateness(late_ns);
        let stats = &self.io.stats;
        if wake.late > pace {
            stats.overruns.fetch_add(1, Ordering::Relaxed);
            self.timing.overrun();
            self.event(Event::Overrun {
                tick: self.actuator.tick(),
                lateness_us: late_ns as f64 / 1e3,
            });
        }
        if let Some(skipped) = pacing::skipped_ticks(wake.late, pace) {
            stats.skipped.fetch_add(skipped, Ordering::Relaxed);
            self.timing.skipped(skipped);
            self.event(Event::Resync { skipped });
            self.deadlines.restart(wake.at);
        }
        stats.max_lateness_ns.fetch_max(late_ns, Ordering::Relaxed);
    }
}
