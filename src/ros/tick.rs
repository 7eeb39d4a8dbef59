//! The fixed-rate tick loop, on its own thread. It owns the actuator; everything else talks to
//! it through queues, so it never waits for DDS: commands queue in a bounded [`command_channel`]
//! and are applied at the next tick boundary, samples go out through a bounded channel (dropped
//! and counted when the publisher falls behind), events for the log through another (likewise).
//!
//! The command queue is a mutex-guarded ring that the loop only ever `try_lock`s: a sender that
//! holds it (and was preempted, e.g. by this very thread running under SCHED_FIFO on the same
//! core) makes the loop leave the commands for the next tick, never wait. `std::sync::mpsc`'s
//! `try_recv` does wait in that case (it spins until a sender that has claimed a slot finishes
//! writing it), which under a flood of commands stalled the loop for 30-350 ms at a time.

use super::clock::{ClockMode, NodeClock};
use crate::physics::model::ModelKind;
use crate::runs::TimeBase;
use crate::sim::{Actuator, StateSnapshot};
use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{SyncSender, TrySendError};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, TryLockError};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// A request for the tick loop, applied at the next tick boundary.
pub enum Command {
    /// New excitations: (muscle index, u in [0, 1]).
    Excitation(Vec<(usize, f64)>),
    /// New external torques: (joint index, N m).
    Load(Vec<(usize, f64)>),
    /// Back to the initial state; the reply carries the tick count before the reset.
    Reset(Option<futures::channel::oneshot::Sender<u64>>),
    /// A new actuator (model, rate or configuration changed): starts from its initial state,
    /// the inputs in force stay in force.
    Replace(Box<Actuator>),
    /// Publish every `n`th tick.
    PublishEvery(u64),
    /// Driven joints' motion: (joint index, angle rad, velocity rad/s), extrapolated linearly
    /// until the next one.
    JointMotion(Vec<(usize, f64, f64)>),
    /// `sim`: simulated seconds per wall-clock second (0 = as fast as possible).
    RealTimeFactor(f64),
    /// `sim`, `lockstep`: publish `/clock` every `n`th tick.
    ClockEvery(u64),
    /// An input (`Excitation`, `Load`) with its message's header stamp, ns: with a simulated
    /// clock, a stamp ahead of the node's time (by at most [`SCHEDULE_HORIZON_S`]) holds it until
    /// the first tick stamped at or after it; otherwise it applies at the next tick.
    Stamped(i64, Box<Command>),
    /// Following `/clock`: the external clock's time now, ns. The loop steps the whole ticks it
    /// covers; a time before the last one (or too far past it) resets.
    ClockTime(i64),
    /// `lockstep`: advance `ticks` ticks (after the steps queued before); the reply, if any,
    /// gets the state after the last of them.
    Step {
        ticks: u64,
        reply: Option<futures::channel::oneshot::Sender<Sample>>,
    },
}

/// What the tick loop hands to the publisher thread.
#[derive(Debug)]
pub enum Output {
    /// A state to publish on `~/state` and `joint_states`.
    State(Sample),
    /// A time to publish on `/clock`, ns (sim and lockstep).
    Clock(i64),
}

/// What the tick loop hands to the publisher after a tick.
#[derive(Debug, Clone)]
pub struct Sample {
    /// Tick count after the step (1 for the first tick after start or reset).
    pub tick: u64,
    /// The tick's stamp: the loop's tick origin + tick / rate, ns since the Unix epoch (the
    /// wall-clock deadline at which the tick was computed, unless a stall made the loop skip
    /// ticks: stamps then lag the wall clock by the time skipped).
    pub stamp_ns: i64,
    pub model: ModelKind,
    pub muscle_names: Arc<[String]>,
    pub joint_names: Arc<[String]>,
    /// The driven joints (indices, configuration order): their efforts go on `~/joint_efforts`.
    pub driven: Arc<[usize]>,
    /// Everything observable after the tick.
    pub state: StateSnapshot,
}

/// Inputs as the tick loop applied them, for the recorder: they take effect for the step from
/// `tick` to `tick + 1`. The values are moved from the command (nothing is allocated).
#[derive(Debug, Clone)]
pub struct Applied {
    /// The actuator's tick when they took effect.
    pub tick: u64,
    /// That tick's stamp (tick origin + tick / rate), ns since the Unix epoch.
    pub stamp_ns: i64,
    /// The muscle names (excitations) or joint names (torques, motion) the indices refer to.
    pub names: Arc<[String]>,
    pub input: AppliedInput,
}

/// Which input was applied, with its values by index into [`Applied::names`].
#[derive(Debug, Clone)]
pub enum AppliedInput {
    /// (muscle index, u).
    Excitation(Vec<(usize, f64)>),
    /// (joint index, N m).
    Load(Vec<(usize, f64)>),
    /// Driven joints: (joint index, angle rad, velocity rad/s).
    JointMotion(Vec<(usize, f64, f64)>),
}

/// Something the log should say (the loop itself never logs).
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// The step of `tick` failed (`reason`: the solver or a non-finite state): the actuator was
    /// reset to its initial state.
    StepFailed { tick: u64, reason: &'static str },
    /// A tick started more than one period late.
    Overrun { tick: u64, lateness_us: f64 },
    /// The loop fell so far behind that it dropped the backlog and restarted its schedule.
    Resync { skipped: u64 },
    /// The actuator was replaced (model/rate/config change).
    Replaced { model: ModelKind, rate_hz: f64 },
    /// A reset was done on request.
    Reset { at_tick: u64 },
    /// Following `/clock`: the first clock message anchored tick 0 at `origin_ns`.
    ClockAnchored { origin_ns: i64 },
    /// Following `/clock`: the clock went from `from_ns` back to `to_ns` (or forward by more
    /// than [`FOLLOW_MAX_AHEAD_S`]): the actuator was reset after `at_tick` ticks and tick 0
    /// re-anchored at `to_ns`.
    ClockJumped {
        from_ns: i64,
        to_ns: i64,
        at_tick: u64,
    },
}

/// With a simulated clock, inputs stamped further ahead of the node's time than this are taken
/// for another clock's (a wall-clock stamp) and apply at the next tick, s.
pub const SCHEDULE_HORIZON_S: f64 = 3600.0;

/// Most inputs waiting for their stamp at once; more are dropped and counted.
pub const SCHEDULE_CAPACITY: usize = 1024;

/// Following `/clock`, a clock that moves forward by more than this much simulated time at once
/// is a jump (reset and re-anchored), not ticks to catch up on, s.
pub const FOLLOW_MAX_AHEAD_S: f64 = 60.0;

/// The ticks a clock at `ns` covers on `clock`: the largest k whose stamp is at or before `ns`
/// (0 before the origin).
pub fn ticks_covered(clock: TimeBase, ns: i64, rate_hz: f64) -> u64 {
    let origin = clock.tick_origin_ns();
    if ns <= origin {
        return 0;
    }
    // The float estimate is within a tick of the answer; the stamps settle it exactly (a few
    // corrections at most: bounded, so that no time, however large, can keep the loop here).
    let mut k = ((ns - origin) as f64 * rate_hz / 1e9).floor() as u64;
    for _ in 0..4 {
        if k > 0 && clock.stamp_ns(k, rate_hz) > ns {
            k -= 1;
        }
    }
    for _ in 0..4 {
        if clock.stamp_ns(k + 1, rate_hz) <= ns {
            k += 1;
        }
    }
    k
}

/// Counters and timing figures shared with the diagnostics (written by the tick loop).
#[derive(Debug, Default)]
pub struct TickStats {
    /// Whether the tick thread runs under real-time (SCHED_FIFO) scheduling.
    pub realtime: AtomicBool,
    /// Ticks done since start (across resets).
    pub ticks: AtomicU64,
    /// The actuator's current tick.
    pub current_tick: AtomicU64,
    /// Ticks that started more than one period after their deadline.
    pub overruns: AtomicU64,
    /// Ticks dropped by a schedule restart after a long stall.
    pub skipped: AtomicU64,
    /// States dropped because the publisher was behind.
    pub samples_dropped: AtomicU64,
    /// Applied inputs the recorder channel had no room for.
    pub applied_dropped: AtomicU64,
    /// Commands the command queue had no room for (dropped on the sending side; a copy of the
    /// queue's own count, updated every tick).
    pub commands_dropped: AtomicU64,
    /// Ticks at which the command queue was busy (a sender held it): its commands were left for
    /// the next tick rather than waited for.
    pub commands_deferred: AtomicU64,
    /// Events (for the log) the event channel had no room for.
    pub events_dropped: AtomicU64,
    /// Resets after a failed step.
    pub step_failures: AtomicU64,
    /// Resets on request.
    pub resets: AtomicU64,
    /// Lateness over the last second, ns (p50, p99, max): f64 bits.
    pub window_p50_ns: AtomicU64,
    pub window_p99_ns: AtomicU64,
    pub window_max_ns: AtomicU64,
    /// Whole-run maximum lateness, ns.
    pub max_lateness_ns: AtomicU64,
    /// Current tick rate, Hz (f64 bits).
    pub rate_hz_bits: AtomicU64,
    /// Mean step cost over the last second, ns (f64 bits).
    pub window_step_ns: AtomicU64,
    /// Driven joints in the actuator.
    pub driven_joints: AtomicU64,
    /// Ticks since a driven joint's motion last arrived (u64::MAX: none yet).
    pub joint_motion_age_ticks: AtomicU64,
    /// Following `/clock`: jumps back (or too far forward) that reset the actuator.
    pub clock_jumps: AtomicU64,
    /// Inputs stamped ahead, waiting for their tick; and those dropped for want of room.
    pub scheduled_pending: AtomicU64,
    pub scheduled_dropped: AtomicU64,
}

impl TickStats {
    pub fn rate_hz(&self) -> f64 {
        f64::from_bits(self.rate_hz_bits.load(Ordering::Relaxed))
    }
    pub fn window(&self) -> (f64, f64, f64) {
        (
            f64::from_bits(self.window_p50_ns.load(Ordering::Relaxed)),
            f64::from_bits(self.window_p99_ns.load(Ordering::Relaxed)),
            f64::from_bits(self.window_max_ns.load(Ordering::Relaxed)),
        )
    }
}

/// A lateness histogram with 1 µs buckets up to 20 ms (beyond: the last bucket).
#[derive(Clone)]
pub struct Histogram {
    buckets: Vec<u64>,
    count: u64,
    max_ns: u64,
}

impl Default for Histogram {
    fn default() -> Self {
        Self::new()
    }
}

impl Histogram {
    const BUCKETS: usize = 20_000;
    pub fn new() -> Self {
        Self {
            buckets: vec![0; Self::BUCKETS],
            count: 0,
            max_ns: 0,
        }
    }
    pub fn record(&mut self, ns: u64) {
        let b = ((ns / 1000) as usize).min(Self::BUCKETS - 1);
        self.buckets[b] += 1;
        self.count += 1;
        self.max_ns = self.max_ns.max(ns);
    }
    pub fn count(&self) -> u64 {
        self.count
    }
    pub fn max_ns(&self) -> u64 {
        self.max_ns
    }
    /// The `q` quantile (0..1), ns, at bucket resolution (upper edge of the bucket, capped by
    /// the maximum).
    pub fn quantile_ns(&self, q: f64) -> u64 {
        if self.count == 0 {
            return 0;
        }
        let target = ((q * self.count as f64).ceil() as u64).clamp(1, self.count);
        let mut seen = 0;
        for (i, n) in self.buckets.iter().enumerate() {
            seen += n;
            if seen >= target {
                if i == Self::BUCKETS - 1 {
                    return self.max_ns;
                }
                return (((i as u64) + 1) * 1000).min(self.max_ns);
            }
        }
        self.max_ns
    }
    pub fn clear(&mut self) {
        self.buckets.iter_mut().for_each(|b| *b = 0);
        self.count = 0;
        self.max_ns = 0;
    }
}

/// Whole-run timing summary, returned when the loop ends.
#[derive(Debug, Clone, Default)]
pub struct RunSummary {
    pub ticks: u64,
    pub overruns: u64,
    pub skipped: u64,
    pub p50_us: f64,
    pub p99_us: f64,
    pub max_us: f64,
    pub mean_step_us: f64,
}

/// How a loop paces and stamps its ticks.
#[derive(Debug, Clone)]
pub struct Pacing {
    /// Shared with the node: the loop advances it in `sim` and `lockstep`.
    pub clock: Arc<NodeClock>,
    /// `sim`: simulated seconds per wall-clock second (0 = as fast as possible).
    pub real_time_factor: f64,
    /// Publish `/clock` every `n`th tick (simulated clocks).
    pub clock_every: u64,
}

impl Pacing {
    /// Ticks paced by the wall clock, stamped with it.
    pub fn wall() -> Self {
        Self {
            clock: Arc::new(NodeClock::new(ClockMode::Wall)),
            real_time_factor: 0.0,
            clock_every: 1,
        }
    }
}

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

/// Longest a lockstep loop sleeps between looks at its stop flag when no step is asked for.
const LOCKSTEP_IDLE: Duration = Duration::from_millis(20);

/// After this many periods behind, the loop stops catching up and restarts its schedule.
const RESYNC_PERIODS: u32 = 100;

/// Lowers this thread's timer slack so that sleeps end close to their deadline (Linux).
fn tighten_timer_slack() {
    #[cfg(target_os = "linux")]
    // SAFETY: prctl(PR_SET_TIMERSLACK) takes an integer argument and affects only this thread.
    unsafe {
        libc::prctl(libc::PR_SET_TIMERSLACK, 1 as libc::c_ulong, 0, 0, 0);
    }
}

/// Priority of the tick thread under SCHED_FIFO, when the process may use it (root or
/// CAP_SYS_NICE / an rtprio limit): the loop then preempts the DDS and publisher threads and other
/// processes' ordinary threads, which is what holds the period on a loaded machine.
const REALTIME_PRIORITY: libc::c_int = 40;

/// Asks for real-time (SCHED_FIFO) scheduling for this thread; returns whether it was granted.
/// Without the privilege the loop runs at normal priority, which is only slower to wake.
fn request_realtime_priority() -> bool {
    #[cfg(target_os = "linux")]
    {
        let param = libc::sched_param {
            sched_priority: REALTIME_PRIORITY,
        };
        // SAFETY: pid 0 is the calling thread; `param` is a valid sched_param for the call.
        unsafe { libc::sched_setscheduler(0, libc::SCHED_FIFO, &param) == 0 }
    }
    #[cfg(not(target_os = "linux"))]
    false
}

fn wall_ns() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_nanos() as i64)
        .unwrap_or(0)
}

/// Passes applied inputs to the recorder, if any (never waits).
fn hand_applied(
    io: &LoopIo,
    actuator: &Actuator,
    clock: TimeBase,
    names: &Arc<[String]>,
    input: AppliedInput,
) {
    if let Some(tx) = &io.applied {
        if let Err(TrySendError::Full(_)) = tx.try_send(Applied {
            tick: actuator.tick(),
            stamp_ns: clock.stamp_ns(actuator.tick(), actuator.rate_hz()),
            names: names.clone(),
            input,
        }) {
            io.stats.applied_dropped.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// The actuator back to its initial state with every input cleared: those in force and those
/// stamped ahead (a reset on request, a failed step, a `/clock` jump).
fn back_to_rest(
    actuator: &mut Actuator,
    excitation: &mut [f64],
    load: &mut [f64],
    scheduled: &mut VecDeque<(i64, Command)>,
) {
    actuator.reset();
    excitation.fill(0.0);
    load.fill(0.0);
    scheduled.clear();
}

/// Runs the loop until `io.stop` is set (or the command channel closes). Ticks at the actuator's
/// rate against absolute deadlines; a tick that starts more than one period late is an overrun.
pub fn run(mut actuator: Actuator, mut publish_every: u64, io: LoopIo) -> RunSummary {
    tighten_timer_slack();
    let mode = io.pacing.clock.mode();
    // Only a loop with deadlines to meet asks to preempt others: a simulated clock running flat
    // out under SCHED_FIFO would starve the node's other threads.
    if mode == ClockMode::Wall {
        io.stats
            .realtime
            .store(request_realtime_priority(), Ordering::Relaxed);
    }
    if mode.is_driven() {
        io.commands.wake_me();
    }
    // Following /clock: the latest clock time received, ns.
    let mut follow_until: Option<i64> = None;
    let mut real_time_factor = io.pacing.real_time_factor;
    let mut clock_every = io.pacing.clock_every.max(1);
    // Lockstep: the steps asked for, in order (ticks left, reply).
    let mut steps: VecDeque<(u64, Option<futures::channel::oneshot::Sender<Sample>>)> =
        VecDeque::with_capacity(CONTROL_RESERVE);
    let mut muscle_names: Arc<[String]> = actuator.muscle_names().into();
    let mut joint_names: Arc<[String]> = actuator.joint_names().into();
    let mut driven: Arc<[usize]> = actuator.driven_joints().into();
    let mut motion_age: u64 = u64::MAX;
    io.stats
        .driven_joints
        .store(driven.len() as u64, Ordering::Relaxed);
    let mut excitation = vec![0.0; muscle_names.len()];
    let mut load = vec![0.0; joint_names.len()];

    let mut period = Duration::from_secs_f64(1.0 / actuator.rate_hz());
    io.stats
        .rate_hz_bits
        .store(actuator.rate_hz().to_bits(), Ordering::Relaxed);
    let mut window = Histogram::new();
    let mut whole = Histogram::new();
    let mut window_start = Instant::now();
    let mut window_step_ns: u64 = 0;
    let mut window_steps: u64 = 0;
    let mut total_step_ns: u128 = 0;
    let mut summary = RunSummary::default();

    let mut origin = Instant::now();
    let mut n: u64 = 0; // ticks since `origin`
                        // Stamps: tick k is stamped `tick_origin_ns + k / rate`.
    let mut clock = TimeBase::Wall {
        tick_origin_ns: io.tick_origin_ns,
    };
    // After a reset or a rebuild: tick 0 one period before now (wall), or at the simulated
    // time reached (simulated clocks, whose time never goes back).
    let reanchored = |period: Duration, clock: TimeBase, tick: u64, rate_hz: f64| TimeBase::Wall {
        tick_origin_ns: match mode {
            ClockMode::Wall => wall_ns() - period.as_nanos() as i64,
            _ => clock.stamp_ns(tick, rate_hz),
        },
    };
    let send_event = |e: Event| {
        if let Err(TrySendError::Full(_)) = io.events.try_send(e) {
            io.stats.events_dropped.fetch_add(1, Ordering::Relaxed);
        }
    };
    let mut commands = io.commands.buffer();
    let mut ready = io.commands.buffer();
    // Inputs stamped ahead (simulated clocks), in stamp order: (stamp ns, input).
    let mut scheduled: VecDeque<(i64, Command)> = VecDeque::with_capacity(SCHEDULE_CAPACITY);

    while !io.stop.load(Ordering::Relaxed) {
        // 1. Inputs that arrived since the last tick take effect now (never waiting for the
        //    queue: when a sender holds it, they take effect at the next tick).
        match io.commands.try_drain(&mut commands) {
            Drain::Taken => {}
            Drain::Busy => {
                io.stats.commands_deferred.fetch_add(1, Ordering::Relaxed);
            }
            Drain::Disconnected => io.stop.store(true, Ordering::Relaxed),
        }
        io.stats
            .commands_dropped
            .store(io.commands.dropped(), Ordering::Relaxed);
        // Inputs whose stamp has come first (in stamp order), then those that arrived; inputs
        // stamped ahead wait.
        let now_ns = clock.stamp_ns(actuator.tick(), actuator.rate_hz());
        while let Some((_, c)) = scheduled.pop_front_if(|(at, _)| *at <= now_ns) {
            ready.push(c);
        }
        for command in commands.drain(..) {
            match command {
                Command::Stamped(at, input)
                    if mode.is_simulated()
                        && at > now_ns
                        && (at - now_ns) as f64 <= SCHEDULE_HORIZON_S * 1e9 =>
                {
                    if scheduled.len() < SCHEDULE_CAPACITY {
                        let k = scheduled.partition_point(|(t, _)| *t <= at);
                        scheduled.insert(k, (at, *input));
                    } else {
                        io.stats.scheduled_dropped.fetch_add(1, Ordering::Relaxed);
                    }
                }
                Command::Stamped(_, input) => ready.push(*input),
                other => ready.push(other),
            }
        }
        io.stats
            .scheduled_pending
            .store(scheduled.len() as u64, Ordering::Relaxed);
        for command in ready.drain(..) {
            match command {
                Command::Excitation(v) => {
                    for &(i, u) in &v {
                        if let Some(slot) = excitation.get_mut(i) {
                            *slot = u;
                        }
                        actuator.set_excitation(i, u);
                    }
                    hand_applied(
                        &io,
                        &actuator,
                        clock,
                        &muscle_names,
                        AppliedInput::Excitation(v),
                    );
                }
                Command::Load(v) => {
                    for &(i, t) in &v {
                        if let Some(slot) = load.get_mut(i) {
                            *slot = t;
                        }
                        actuator.set_external_torque(i, t);
                    }
                    hand_applied(&io, &actuator, clock, &joint_names, AppliedInput::Load(v));
                }
                Command::Reset(reply) => {
                    let before = actuator.tick();
                    clock = reanchored(period, clock, before, actuator.rate_hz());
                    back_to_rest(&mut actuator, &mut excitation, &mut load, &mut scheduled);
                    io.stats.resets.fetch_add(1, Ordering::Relaxed);
                    send_event(Event::Reset { at_tick: before });
                    if let Some(r) = reply {
                        let _ = r.send(before);
                    }
                }
                Command::Replace(new) => {
                    clock = reanchored(period, clock, actuator.tick(), actuator.rate_hz());
                    actuator = *new;
                    muscle_names = actuator.muscle_names().into();
                    joint_names = actuator.joint_names().into();
                    driven = actuator.driven_joints().into();
                    motion_age = u64::MAX;
                    io.stats
                        .driven_joints
                        .store(driven.len() as u64, Ordering::Relaxed);
                    excitation.resize(muscle_names.len(), 0.0);
                    load.resize(joint_names.len(), 0.0);
                    for (i, u) in excitation.iter().enumerate() {
                        actuator.set_excitation(i, *u);
                    }
                    for (i, t) in load.iter().enumerate() {
                        actuator.set_external_torque(i, *t);
                    }
                    let new_period = Duration::from_secs_f64(1.0 / actuator.rate_hz());
                    if new_period != period {
                        period = new_period;
                        origin = Instant::now();
                        n = 0;
                    }
                    if mode == ClockMode::Wall {
                        clock = reanchored(period, clock, 0, actuator.rate_hz());
                    }
                    io.stats
                        .rate_hz_bits
                        .store(actuator.rate_hz().to_bits(), Ordering::Relaxed);
                    send_event(Event::Replaced {
                        model: actuator.model(),
                        rate_hz: actuator.rate_hz(),
                    });
                }
                Command::PublishEvery(k) => publish_every = k.max(1),
                Command::JointMotion(mut v) => {
                    v.retain(|&(j, angle, velocity)| actuator.set_joint_motion(j, angle, velocity));
                    motion_age = 0;
                    hand_applied(
                        &io,
                        &actuator,
                        clock,
                        &joint_names,
                        AppliedInput::JointMotion(v),
                    );
                }
                Command::RealTimeFactor(f) => {
                    real_time_factor = f;
                    // Only a simulated clock is paced by it: the wall schedule stays as it is.
                    if mode == ClockMode::Sim {
                        origin = Instant::now();
                        n = 0;
                    }
                }
                Command::ClockEvery(k) => clock_every = k.max(1),
                Command::ClockTime(ns) if mode == ClockMode::Follow => {
                    let rate = actuator.rate_hz();
                    match follow_until {
                        None => {
                            // The first clock message: the tick reached (0) is at its time.
                            clock = TimeBase::Wall {
                                tick_origin_ns: ns
                                    - crate::runs::tick_ns(actuator.tick(), rate) as i64,
                            };
                            send_event(Event::ClockAnchored {
                                origin_ns: clock.tick_origin_ns(),
                            });
                        }
                        Some(last)
                            if ns < last
                                || ticks_covered(clock, ns, rate).saturating_sub(actuator.tick())
                                    as f64
                                    > FOLLOW_MAX_AHEAD_S * rate =>
                        {
                            let before = actuator.tick();
                            back_to_rest(&mut actuator, &mut excitation, &mut load, &mut scheduled);
                            clock = TimeBase::Wall { tick_origin_ns: ns };
                            io.stats.clock_jumps.fetch_add(1, Ordering::Relaxed);
                            send_event(Event::ClockJumped {
                                from_ns: last,
                                to_ns: ns,
                                at_tick: before,
                            });
                        }
                        Some(_) => {}
                    }
                    follow_until = Some(ns);
                    io.pacing
                        .clock
                        .advance_to(clock.stamp_ns(actuator.tick(), rate));
                }
                Command::ClockTime(_) => {}
                // Unwrapped above.
                Command::Stamped(_, _) => {}
                Command::Step { ticks, reply } => {
                    if ticks > 0 {
                        steps.push_back((ticks, reply));
                    }
                }
            }
        }
        // Lockstep: nothing to do until a step is asked for; following /clock, until the
        // clock covers the next tick (a sender wakes the loop).
        let waiting = match mode {
            ClockMode::Lockstep => steps.is_empty(),
            ClockMode::Follow => follow_until
                .is_none_or(|ns| ticks_covered(clock, ns, actuator.rate_hz()) <= actuator.tick()),
            _ => false,
        };
        if waiting {
            std::thread::park_timeout(LOCKSTEP_IDLE);
            continue;
        }

        // 2. One step.
        let t0 = Instant::now();
        if let Err(e) = actuator.step() {
            // Back to the initial state with the inputs cleared (whatever drove the state out
            // of range is not applied again); the next valid command applies as usual.
            let tick = e.tick;
            clock = reanchored(period, clock, tick, actuator.rate_hz());
            back_to_rest(&mut actuator, &mut excitation, &mut load, &mut scheduled);
            io.stats.step_failures.fetch_add(1, Ordering::Relaxed);
            send_event(Event::StepFailed {
                tick,
                reason: e.reason,
            });
        }
        let step_ns = t0.elapsed().as_nanos() as u64;
        window_step_ns += step_ns;
        window_steps += 1;
        total_step_ns += step_ns as u128;
        io.stats.ticks.fetch_add(1, Ordering::Relaxed);
        io.stats
            .current_tick
            .store(actuator.tick(), Ordering::Relaxed);
        summary.ticks += 1;

        // 3. Hand the state (and the time) over, never waiting.
        let stamp_ns = clock.stamp_ns(actuator.tick(), actuator.rate_hz());
        let sample = || Sample {
            tick: actuator.tick(),
            stamp_ns,
            model: actuator.model(),
            muscle_names: muscle_names.clone(),
            joint_names: joint_names.clone(),
            driven: driven.clone(),
            state: actuator.state().clone(),
        };
        motion_age = motion_age.saturating_add(1);
        io.stats
            .joint_motion_age_ticks
            .store(motion_age, Ordering::Relaxed);
        let hand = |o: Output| match io.samples.try_send(o) {
            Ok(()) => {}
            Err(TrySendError::Full(_)) => {
                io.stats.samples_dropped.fetch_add(1, Ordering::Relaxed);
            }
            Err(TrySendError::Disconnected(_)) => {}
        };
        if mode.is_simulated() {
            io.pacing.clock.advance_to(stamp_ns);
        }
        if mode.publishes_clock() && actuator.tick().is_multiple_of(clock_every) {
            hand(Output::Clock(stamp_ns));
        }
        if actuator.tick().is_multiple_of(publish_every) || publish_every == 1 {
            // Never waiting, in every mode: a simulated clock that waited for the publisher
            // ran at 2.5x real time with a state every tick (the DDS write is the bottleneck);
            // what the publisher cannot take is counted (`samples_dropped`).
            hand(Output::State(sample()));
        }
        if let Some(front) = steps.front_mut() {
            front.0 -= 1;
            if front.0 == 0 {
                if let Some((_, Some(reply))) = steps.pop_front() {
                    let _ = reply.send(sample());
                }
            }
        }
        // Lockstep, and sim as fast as possible, have no deadline: the next tick at once.
        let paced = mode == ClockMode::Wall || (mode == ClockMode::Sim && real_time_factor > 0.0);

        if paced {
            // 4. Wait for the next deadline (wall: one period; sim: a period / real_time_factor).
            let pace = if mode == ClockMode::Sim {
                period.div_f64(real_time_factor)
            } else {
                period
            };
            n += 1;
            let deadline =
                origin + Duration::from_nanos((pace.as_nanos() as u64).saturating_mul(n));
            let now = Instant::now();
            if deadline > now {
                std::thread::sleep(deadline - now);
            }
            let woke = Instant::now();
            let late = woke.saturating_duration_since(deadline);
            let late_ns = late.as_nanos() as u64;
            window.record(late_ns);
            whole.record(late_ns);
            if late > pace {
                io.stats.overruns.fetch_add(1, Ordering::Relaxed);
                summary.overruns += 1;
                send_event(Event::Overrun {
                    tick: actuator.tick(),
                    lateness_us: late_ns as f64 / 1e3,
                });
            }
            if late > pace * RESYNC_PERIODS {
                let skipped = (late.as_nanos() / pace.as_nanos().max(1)) as u64;
                io.stats.skipped.fetch_add(skipped, Ordering::Relaxed);
                summary.skipped += skipped;
                send_event(Event::Resync { skipped });
                origin = woke;
                n = 0;
            }
            io.stats
                .max_lateness_ns
                .fetch_max(late_ns, Ordering::Relaxed);
        }

        // 5. Once a second: the window's figures.
        let woke = Instant::now();
        if woke.duration_since(window_start) >= Duration::from_secs(1) {
            let st = &io.stats;
            st.window_p50_ns.store(
                (window.quantile_ns(0.5) as f64).to_bits(),
                Ordering::Relaxed,
            );
            st.window_p99_ns.store(
                (window.quantile_ns(0.99) as f64).to_bits(),
                Ordering::Relaxed,
            );
            st.window_max_ns
                .store((window.max_ns() as f64).to_bits(), Ordering::Relaxed);
            st.window_step_ns.store(
                (window_step_ns as f64 / window_steps.max(1) as f64).to_bits(),
                Ordering::Relaxed,
            );
            window.clear();
            window_step_ns = 0;
            window_steps = 0;
            window_start = woke;
        }
    }
    summary.p50_us = whole.quantile_ns(0.5) as f64 / 1e3;
    summary.p99_us = whole.quantile_ns(0.99) as f64 / 1e3;
    summary.max_us = whole.max_ns() as f64 / 1e3;
    summary.mean_step_us = total_step_ns as f64 / summary.ticks.max(1) as f64 / 1e3;
    summary
}

/// Starts the loop on its own thread.
pub fn spawn(
    actuator: Actuator,
    publish_every: u64,
    io: LoopIo,
) -> std::io::Result<std::thread::JoinHandle<RunSummary>> {
    std::thread::Builder::new()
        .name("tick".into())
        .spawn(move || run(actuator, publish_every, io))
}

/// Inputs (excitations, loads) the command queue holds before it drops new ones: a second of
/// commands at 1 kHz, far more than arrive between two ticks unless the loop is stopped.
pub const COMMAND_CAPACITY: usize = 1024;

/// Extra room for control commands (reset, actuator replacement, publish rate), so that a
/// flood of inputs never crowds them out; beyond it they are dropped (and counted) too.
pub const CONTROL_RESERVE: usize = 64;

/// The command queue shared by the senders and the loop.
struct CommandQueue {
    items: Mutex<VecDeque<Command>>,
    /// The loop's thread, when it sleeps until a command arrives (lockstep).
    waiter: OnceLock<std::thread::Thread>,
    /// Live senders; none left (and the queue empty) = disconnected.
    senders: AtomicUsize,
    dropped: AtomicU64,
    inputs_capacity: usize,
    capacity: usize,
}

impl CommandQueue {
    fn lock(&self) -> MutexGuard<'_, VecDeque<Command>> {
        // A panic while the lock was held cannot leave the deque inconsistent: use it.
        self.items.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The sending side of the command queue (the DDS side, any thread). Never waits for a tick:
/// only, briefly, for another sender's push or the loop's drain (a copy of the queued commands);
/// a full queue drops the command and counts it.
pub struct CommandSender {
    queue: Arc<CommandQueue>,
}

impl CommandSender {
    /// Queues `c` for the next tick; gives it back when the queue is full (it is then counted
    /// as dropped).
    pub fn send(&self, c: Command) -> Result<(), Command> {
        let q = &self.queue;
        let limit = match c {
            Command::Excitation(_) | Command::Load(_) => q.inputs_capacity,
            _ => q.capacity,
        };
        let mut items = q.lock();
        if items.len() >= limit {
            drop(items);
            q.dropped.fetch_add(1, Ordering::Relaxed);
            return Err(c);
        }
        items.push_back(c);
        drop(items);
        if let Some(t) = q.waiter.get() {
            t.unpark();
        }
        Ok(())
    }

    /// Commands dropped so far because the queue was full.
    pub fn dropped(&self) -> u64 {
        self.queue.dropped.load(Ordering::Relaxed)
    }
}

impl Clone for CommandSender {
    fn clone(&self) -> Self {
        self.queue.senders.fetch_add(1, Ordering::AcqRel);
        Self {
            queue: self.queue.clone(),
        }
    }
}

impl Drop for CommandSender {
    fn drop(&mut self) {
        self.queue.senders.fetch_sub(1, Ordering::AcqRel);
    }
}

/// What [`CommandReceiver::try_drain`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Drain {
    /// The queued commands (maybe none) were moved to the buffer.
    Taken,
    /// A sender held the queue: nothing taken, try again at the next tick.
    Busy,
    /// Every sender is gone and nothing is left.
    Disconnected,
}

/// The loop's side of the command queue.
pub struct CommandReceiver {
    queue: Arc<CommandQueue>,
}

impl CommandReceiver {
    /// A buffer for [`Self::try_drain`] that never has to grow (allocated once, before the
    /// loop starts).
    pub fn buffer(&self) -> Vec<Command> {
        Vec::with_capacity(self.queue.capacity)
    }

    /// Moves every queued command to `out`, in order, if the queue is free; never waits (a
    /// `try_lock`, never a blocking lock or a spin).
    pub fn try_drain(&self, out: &mut Vec<Command>) -> Drain {
        let mut items = match self.queue.items.try_lock() {
            Ok(g) => g,
            Err(TryLockError::Poisoned(e)) => e.into_inner(),
            Err(TryLockError::WouldBlock) => return Drain::Busy,
        };
        if items.is_empty() && self.queue.senders.load(Ordering::Acquire) == 0 {
            return Drain::Disconnected;
        }
        out.extend(items.drain(..));
        Drain::Taken
    }

    /// Commands dropped so far because the queue was full.
    pub fn dropped(&self) -> u64 {
        self.queue.dropped.load(Ordering::Relaxed)
    }

    /// From now on every command sent unparks the calling thread.
    pub fn wake_me(&self) {
        let _ = self.queue.waiter.set(std::thread::current());
    }
}

/// The command queue, bounded: [`COMMAND_CAPACITY`] inputs plus [`CONTROL_RESERVE`] for control
/// commands.
pub fn command_channel() -> (CommandSender, CommandReceiver) {
    command_channel_with(COMMAND_CAPACITY, CONTROL_RESERVE)
}

/// The command queue with room for `inputs` inputs and `reserve` more control commands.
pub fn command_channel_with(inputs: usize, reserve: usize) -> (CommandSender, CommandReceiver) {
    let capacity = inputs + reserve;
    let queue = Arc::new(CommandQueue {
        items: Mutex::new(VecDeque::with_capacity(capacity)),
        waiter: OnceLock::new(),
        senders: AtomicUsize::new(1),
        dropped: AtomicU64::new(0),
        inputs_capacity: inputs,
        capacity,
    });
    (
        CommandSender {
            queue: queue.clone(),
        },
        CommandReceiver { queue },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn histogram_quantiles() {
        let mut h = Histogram::new();
        for us in 1..=100u64 {
            h.record(us * 1000 - 500);
        }
        assert_eq!(h.count(), 100);
        assert_eq!(h.quantile_ns(0.5), 50_000);
        assert_eq!(h.quantile_ns(0.99), 99_000);
        assert_eq!(h.max_ns(), 99_500);
        h.record(1_000_000_000);
        assert_eq!(h.quantile_ns(1.0), 1_000_000_000);
        h.clear();
        assert_eq!(h.quantile_ns(0.5), 0);
    }

    fn excitation(u: f64) -> Command {
        Command::Excitation(vec![(0, u)])
    }

    #[test]
    fn command_queue_is_bounded_and_counts_drops() {
        let (tx, rx) = command_channel_with(4, 2);
        for k in 0..4 {
            assert!(tx.send(excitation(k as f64 / 10.0)).is_ok());
        }
        // Inputs beyond their capacity are dropped and counted...
        assert!(matches!(
            tx.send(excitation(0.9)),
            Err(Command::Excitation(_))
        ));
        assert!(tx.send(Command::Load(vec![(0, 1.0)])).is_err());
        assert_eq!(tx.dropped(), 2);
        // ...control commands still have their reserve, then are dropped too.
        assert!(tx.send(Command::Reset(None)).is_ok());
        assert!(tx.send(Command::PublishEvery(2)).is_ok());
        assert!(tx.send(Command::Reset(None)).is_err());
        assert_eq!(rx.dropped(), 3);
        let mut buf = rx.buffer();
        assert_eq!(rx.try_drain(&mut buf), Drain::Taken);
        assert_eq!(buf.len(), 6);
        let us: Vec<f64> = buf
            .iter()
            .filter_map(|c| match c {
                Command::Excitation(v) => Some(v[0].1),
                _ => None,
            })
            .collect();
        assert_eq!(
            us,
            vec![0.0, 0.1, 0.2, 0.3],
            "in order, the first ones kept"
        );
        assert!(matches!(buf[4], Command::Reset(None)));
        assert!(matches!(buf[5], Command::PublishEvery(2)));
        // Room again once drained; the buffer never grew.
        let cap = buf.capacity();
        buf.clear();
        assert!(tx.send(excitation(0.5)).is_ok());
        assert_eq!(rx.try_drain(&mut buf), Drain::Taken);
        assert_eq!((buf.len(), buf.capacity()), (1, cap));
        assert_eq!(cap, 6);
    }

    #[test]
    fn draining_never_waits_for_a_sender_holding_the_queue() {
        let (tx, rx) = command_channel();
        tx.send(excitation(0.5)).ok();
        let mut buf = rx.buffer();
        {
            // A sender inside `send` (e.g. preempted there) holds the lock.
            let _held = rx.queue.items.lock().unwrap();
            assert_eq!(rx.try_drain(&mut buf), Drain::Busy);
            assert!(buf.is_empty());
        }
        assert_eq!(rx.try_drain(&mut buf), Drain::Taken);
        assert_eq!(buf.len(), 1);
    }

    #[test]
    fn command_queue_disconnects_once_senders_are_gone_and_it_is_empty() {
        let (tx, rx) = command_channel();
        let tx2 = tx.clone();
        drop(tx);
        tx2.send(excitation(0.1)).ok();
        drop(tx2);
        let mut buf = rx.buffer();
        assert_eq!(rx.try_drain(&mut buf), Drain::Taken);
        assert_eq!(buf.len(), 1);
        assert_eq!(rx.try_drain(&mut buf), Drain::Disconnected);
    }

    /// The loop keeps ticking while a sender holds the command queue (the commands then take
    /// effect at a later tick). No timing figure is asserted: with a loop that waited for the
    /// queue the tick count would not move at all while it is held.
    #[test]
    fn loop_keeps_ticking_while_a_sender_holds_the_queue() {
        let actuator = crate::ros::params::NodeParams::default().build().unwrap();
        let (tx, rx) = command_channel();
        let (sample_tx, _sample_rx) = std::sync::mpsc::sync_channel(4);
        let (event_tx, _event_rx) = std::sync::mpsc::sync_channel(4);
        let stats = Arc::new(TickStats::default());
        let stop = Arc::new(AtomicBool::new(false));
        let queue = rx.queue.clone();
        let handle = spawn(
            actuator,
            1,
            LoopIo {
                commands: rx,
                samples: sample_tx,
                events: event_tx,
                stats: stats.clone(),
                stop: stop.clone(),
                applied: None,
                tick_origin_ns: 0,
                pacing: Pacing::wall(),
            },
        )
        .unwrap();
        let wait_for = |what: &str, cond: &mut dyn FnMut() -> bool| {
            let end = Instant::now() + Duration::from_secs(30);
            while !cond() {
                assert!(Instant::now() < end, "timed out waiting for {what}");
                std::thread::sleep(Duration::from_millis(1));
            }
        };
        wait_for("the first tick", &mut || {
            stats.ticks.load(Ordering::Relaxed) > 0
        });
        let (reply_tx, mut reply_rx) = futures::channel::oneshot::channel();
        {
            let _held = queue.items.lock().unwrap();
            let t0 = stats.ticks.load(Ordering::Relaxed);
            wait_for("ticks while the queue is held", &mut || {
                stats.ticks.load(Ordering::Relaxed) >= t0 + 5
                    && stats.commands_deferred.load(Ordering::Relaxed) >= 1
            });
        }
        // The queue is free again: a command goes through.
        tx.send(Command::Reset(Some(reply_tx))).ok();
        wait_for("the reset's reply", &mut || {
            matches!(reply_rx.try_recv(), Ok(Some(_)))
        });
        assert_eq!(stats.resets.load(Ordering::Relaxed), 1);
        assert_eq!(stats.commands_dropped.load(Ordering::Relaxed), 0);
        stop.store(true, Ordering::Relaxed);
        let summary = handle.join().unwrap();
        assert!(summary.ticks >= 6);
    }

    /// States and applied inputs carry one clock: tick k is stamped origin + k / rate, which
    /// maps back to k (what replay does with a node recording); a reset re-anchors tick 0 at
    /// the wall clock.
    #[test]
    fn states_and_applied_inputs_share_the_tick_clock() {
        let actuator = crate::ros::params::NodeParams::default().build().unwrap();
        let rate = actuator.rate_hz();
        let origin: i64 = 1_700_000_000_123_456_789;
        let (tx, rx) = command_channel();
        let (sample_tx, sample_rx) = std::sync::mpsc::sync_channel(64);
        let (event_tx, _event_rx) = std::sync::mpsc::sync_channel(64);
        let (applied_tx, applied_rx) = std::sync::mpsc::sync_channel(64);
        let stop = Arc::new(AtomicBool::new(false));
        let handle = spawn(
            actuator,
            1,
            LoopIo {
                commands: rx,
                samples: sample_tx,
                events: event_tx,
                stats: Arc::new(TickStats::default()),
                stop: stop.clone(),
                applied: Some(applied_tx),
                tick_origin_ns: origin,
                pacing: Pacing::wall(),
            },
        )
        .unwrap();
        let clock = TimeBase::Wall {
            tick_origin_ns: origin,
        };
        let next_state = || loop {
            if let Output::State(s) = sample_rx.recv_timeout(Duration::from_secs(30)).unwrap() {
                return s;
            }
        };
        let first = next_state();
        assert_eq!(first.stamp_ns, clock.stamp_ns(first.tick, rate));
        tx.send(Command::Excitation(vec![(0, 0.5)])).ok();
        let a = applied_rx.recv_timeout(Duration::from_secs(30)).unwrap();
        assert!(a.tick >= first.tick);
        assert_eq!(a.stamp_ns, clock.stamp_ns(a.tick, rate));
        assert_eq!(clock.tick_of(a.stamp_ns, rate), Ok(a.tick));
        // The state after the tick the input took effect at carries the next stamp.
        let after = std::iter::from_fn(|| Some(next_state()))
            .find(|s| s.tick == a.tick + 1)
            .unwrap();
        assert_eq!(after.stamp_ns - a.stamp_ns, tick_ns_i64(1, rate));
        // After a reset tick 0 is re-anchored near now (not at the old origin).
        let (reply_tx, _reply_rx) = futures::channel::oneshot::channel();
        tx.send(Command::Reset(Some(reply_tx))).ok();
        let now = wall_ns();
        let s = std::iter::from_fn(|| Some(next_state()))
            .find(|s| s.tick == 1)
            .unwrap();
        assert!(
            (s.stamp_ns - now).abs() < 5_000_000_000,
            "{} vs {now}",
            s.stamp_ns
        );
        stop.store(true, Ordering::Relaxed);
        drop(sample_rx);
        handle.join().unwrap();
    }

    fn tick_ns_i64(ticks: u64, rate: f64) -> i64 {
        crate::runs::tick_ns(ticks, rate) as i64
    }

    /// Lockstep: no tick until a step is asked for; steps run in order and each reply carries
    /// the state after its last tick; the simulated clock advances with the ticks and `/clock`
    /// goes out every `clock_every` ticks, stamped tick / rate.
    #[test]
    fn lockstep_ticks_only_when_stepped() {
        let l = TestLoop::start(ClockMode::Lockstep, 4);
        let (tx, stats, clock, rate) = (&l.tx, &l.stats, &l.clock, 1000.0);
        std::thread::sleep(Duration::from_millis(100));
        assert_eq!(
            stats.ticks.load(Ordering::Relaxed),
            0,
            "no tick before a step"
        );
        let (a_tx, a_rx) = futures::channel::oneshot::channel();
        let (b_tx, b_rx) = futures::channel::oneshot::channel();
        tx.send(Command::Step {
            ticks: 10,
            reply: Some(a_tx),
        })
        .ok();
        tx.send(Command::Step {
            ticks: 0,
            reply: None,
        })
        .ok();
        tx.send(Command::Step {
            ticks: 7,
            reply: Some(b_tx),
        })
        .ok();
        let wait = |mut rx: futures::channel::oneshot::Receiver<Sample>| {
            let end = Instant::now() + Duration::from_secs(30);
            loop {
                if let Ok(Some(s)) = rx.try_recv() {
                    return s;
                }
                assert!(Instant::now() < end, "no reply");
                std::thread::sleep(Duration::from_millis(1));
            }
        };
        let a = wait(a_rx);
        let b = wait(b_rx);
        assert_eq!((a.tick, b.tick), (10, 17));
        assert_eq!(b.stamp_ns, crate::runs::tick_ns(17, rate) as i64);
        assert_eq!(clock.now_ns(), b.stamp_ns);
        std::thread::sleep(Duration::from_millis(100));
        assert_eq!(
            stats.ticks.load(Ordering::Relaxed),
            17,
            "no tick after the steps"
        );
        let (out, _, _) = l.finish();
        let clocks: Vec<i64> = out
            .into_iter()
            .filter_map(|o| match o {
                Output::Clock(ns) => Some(ns),
                Output::State(_) => None,
            })
            .collect();
        let expected: Vec<i64> = [4, 8, 12, 16]
            .iter()
            .map(|&k| crate::runs::tick_ns(k, rate) as i64)
            .collect();
        assert_eq!(clocks, expected);
    }

    /// The ticks a clock time covers: exactly those stamped at or before it, at rates whose
    /// period is not a whole number of ns too.
    #[test]
    fn ticks_covered_are_those_stamped_at_or_before() {
        for rate in [1000.0, 333.0, 2500.0, 7.0] {
            for origin in [0, 5_000_000_000_123, 7] {
                let clock = TimeBase::Wall {
                    tick_origin_ns: origin,
                };
                assert_eq!(ticks_covered(clock, origin - 1, rate), 0);
                // Up to the largest time a builtin_interfaces/Time holds (i32 seconds), and
                // beyond: an answer, never a hang.
                let top = clock
                    .tick_of(i32::MAX as i64 * 1_000_000_000, rate)
                    .unwrap()
                    - 1;
                assert!(ticks_covered(clock, i64::MAX, rate) > top);
                for k in [0u64, 1, 2, 999, 1000, 123_457, top] {
                    let at = clock.stamp_ns(k, rate);
                    assert_eq!(ticks_covered(clock, at, rate), k, "{rate} {origin} {k}");
                    assert_eq!(ticks_covered(clock, at + 1, rate), k);
                    if k > 0 {
                        assert_eq!(ticks_covered(clock, at - 1, rate), k - 1);
                    }
                }
            }
        }
    }

    /// Following /clock: nothing before the first clock time, which anchors tick 0; each time
    /// steps the ticks it covers, stamped with it; a paused clock pauses the loop; a jump back
    /// resets and re-anchors, and so does a jump forward of more than a minute; `/clock` is not
    /// published.
    #[test]
    fn follow_steps_the_ticks_each_clock_time_covers() {
        let l = TestLoop::start(ClockMode::Follow, 1);
        std::thread::sleep(Duration::from_millis(50));
        assert_eq!(l.stats.ticks.load(Ordering::Relaxed), 0);
        let t0: i64 = 5_000_000_000_000;
        l.tx.send(Command::ClockTime(t0)).ok();
        l.tx.send(Command::ClockTime(t0 + 10_500_000)).ok();
        assert_eq!(l.settle(10), 10, "10.5 ms covers 10 ticks");
        assert_eq!(l.clock.now_ns(), t0 + 10_000_000);
        std::thread::sleep(Duration::from_millis(100));
        assert_eq!(l.stats.ticks.load(Ordering::Relaxed), 10, "paused");
        // Back to 1 s: reset, tick 0 there; then 3 ticks from it.
        l.tx.send(Command::ClockTime(1_000_000_000)).ok();
        l.tx.send(Command::ClockTime(1_003_000_000)).ok();
        assert_eq!(l.settle(13), 13);
        assert_eq!(l.stats.clock_jumps.load(Ordering::Relaxed), 1);
        // Two minutes on at once: a jump too (not 120 000 ticks to catch up on).
        l.tx.send(Command::ClockTime(121_003_000_000)).ok();
        l.tx.send(Command::ClockTime(121_005_000_000)).ok();
        assert_eq!(l.settle(15), 15);
        assert_eq!(l.stats.clock_jumps.load(Ordering::Relaxed), 2);
        let (out, events, _) = l.finish();
        let states: Vec<(u64, i64)> = out
            .into_iter()
            .map(|o| match o {
                Output::State(s) => (s.tick, s.stamp_ns),
                Output::Clock(_) => panic!("a follower publishes no /clock"),
            })
            .collect();
        let ms = |t: i64, k: u64| (k, t + k as i64 * 1_000_000);
        let mut expected: Vec<(u64, i64)> = (1..=10).map(|k| ms(t0, k)).collect();
        expected.extend((1..=3).map(|k| ms(1_000_000_000, k)));
        expected.extend((1..=2).map(|k| ms(121_003_000_000, k)));
        assert_eq!(states, expected);
        assert_eq!(
            events,
            vec![
                Event::ClockAnchored { origin_ns: t0 },
                Event::ClockJumped {
                    from_ns: t0 + 10_500_000,
                    to_ns: 1_000_000_000,
                    at_tick: 10
                },
                Event::ClockJumped {
                    from_ns: 1_003_000_000,
                    to_ns: 121_003_000_000,
                    at_tick: 3
                },
            ]
        );
    }

    /// With a simulated clock an input stamped ahead waits for the first tick stamped at or
    /// after it (in stamp order, whatever the order of arrival); one stamped in the past, with
    /// zero, or beyond the horizon (a wall-clock stamp) applies at the next tick; a reset drops
    /// those waiting.
    #[test]
    fn inputs_stamped_ahead_wait_for_their_tick() {
        let l = TestLoop::start(ClockMode::Lockstep, 1);
        let at = |tick: u64| crate::runs::tick_ns(tick, 1000.0) as i64;
        let excite = |u: f64| Box::new(Command::Excitation(vec![(0, u)]));
        // Sent out of order: tick 7's before tick 4's (and one between two ticks: tick 9).
        l.tx.send(Command::Stamped(at(7), excite(0.7))).ok();
        l.tx.send(Command::Stamped(at(4), excite(0.4))).ok();
        l.tx.send(Command::Stamped(at(8) + 1, excite(0.9))).ok();
        let wall_stamp = 1_763_800_000_000_000_000;
        let load = Box::new(Command::Load(vec![(0, 0.25)]));
        l.tx.send(Command::Stamped(wall_stamp, load)).ok();
        let step = |ticks| Command::Step { ticks, reply: None };
        l.tx.send(step(12)).ok();
        l.settle(12);
        // One stamped ahead, then a reset: it never applies.
        l.tx.send(Command::Stamped(at(20), excite(1.0))).ok();
        l.tx.send(Command::Reset(None)).ok();
        l.tx.send(step(30)).ok();
        l.settle(42);
        assert_eq!(l.stats.scheduled_pending.load(Ordering::Relaxed), 0);
        let (out, _, applied) = l.finish();
        let applied: Vec<(u64, bool)> = applied
            .iter()
            .map(|a| (a.tick, matches!(a.input, AppliedInput::Excitation(_))))
            .collect();
        // The wall-stamped load at once (tick 0), then the excitations at 4, 7 and 9.
        assert_eq!(applied, vec![(0, false), (4, true), (7, true), (9, true)]);
        let u: Vec<(u64, f64)> = out
            .into_iter()
            .filter_map(|o| match o {
                Output::State(s) => Some((s.tick, s.state.muscles[0].excitation)),
                Output::Clock(_) => None,
            })
            .collect();
        let want = |k: u64| match k {
            1..=4 => 0.0,
            5..=7 => 0.4,
            8..=9 => 0.7,
            _ => 0.9,
        };
        assert_eq!(
            &u[..12],
            &(1..=12).map(|k| (k, want(k))).collect::<Vec<_>>()[..]
        );
        // After the reset: nothing applied, excitation 0 to the end.
        assert!(u[12..].iter().all(|(_, x)| *x == 0.0), "{:?}", &u[12..]);
    }

    /// A loop under test on `mode`'s clock, from the default actuator at tick origin 0: its
    /// command sender, outputs, events, applied inputs, counters, stop flag and thread.
    struct TestLoop {
        tx: CommandSender,
        out: std::sync::mpsc::Receiver<Output>,
        events: std::sync::mpsc::Receiver<Event>,
        applied: std::sync::mpsc::Receiver<Applied>,
        stats: Arc<TickStats>,
        clock: Arc<NodeClock>,
        stop: Arc<AtomicBool>,
        handle: std::thread::JoinHandle<RunSummary>,
    }

    impl TestLoop {
        fn start(mode: ClockMode, clock_every: u64) -> Self {
            let actuator = crate::ros::params::NodeParams::default().build().unwrap();
            let (tx, rx) = command_channel();
            let (out_tx, out) = std::sync::mpsc::sync_channel(65_536);
            let (event_tx, events) = std::sync::mpsc::sync_channel(64);
            let (applied_tx, applied) = std::sync::mpsc::sync_channel(64);
            let stats = Arc::new(TickStats::default());
            let stop = Arc::new(AtomicBool::new(false));
            let clock = Arc::new(NodeClock::new(mode));
            let handle = spawn(
                actuator,
                1,
                LoopIo {
                    commands: rx,
                    samples: out_tx,
                    events: event_tx,
                    stats: stats.clone(),
                    stop: stop.clone(),
                    applied: Some(applied_tx),
                    tick_origin_ns: 0,
                    pacing: Pacing {
                        clock: clock.clone(),
                        real_time_factor: 0.0,
                        clock_every,
                    },
                },
            )
            .unwrap();
            Self {
                tx,
                out,
                events,
                applied,
                stats,
                clock,
                stop,
                handle,
            }
        }

        /// Waits until `ticks` ticks are done (and a little more, to see that no more come).
        fn settle(&self, ticks: u64) -> u64 {
            let end = Instant::now() + Duration::from_secs(30);
            while self.stats.ticks.load(Ordering::Relaxed) < ticks {
                assert!(Instant::now() < end, "stuck before {ticks} ticks");
                std::thread::sleep(Duration::from_millis(1));
            }
            std::thread::sleep(Duration::from_millis(50));
            self.stats.ticks.load(Ordering::Relaxed)
        }

        /// Stops the loop; what it handed over.
        fn finish(self) -> (Vec<Output>, Vec<Event>, Vec<Applied>) {
            self.stop.store(true, Ordering::Relaxed);
            self.handle.join().unwrap();
            (
                self.out.try_iter().collect(),
                self.events.try_iter().collect(),
                self.applied.try_iter().collect(),
            )
        }
    }
}
