use super::super::clock::{ClockMode, NodeClock};
use super::queue::{command_channel_with, Drain};
use super::stats::Histogram;
use super::*;
use muscle_actuator_core::time::TimeBase;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

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
    let l = TestLoop::start(ClockMode::Wall, 1);
    let stats = &l.stats;
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
        let _held = l.queue.items.lock().unwrap();
        let t0 = stats.ticks.load(Ordering::Relaxed);
        wait_for("ticks while the queue is held", &mut || {
            stats.ticks.load(Ordering::Relaxed) >= t0 + 5
                && stats.commands_deferred.load(Ordering::Relaxed) >= 1
        });
    }
    // The queue is free again: a command goes through.
    l.tx.send(Command::Reset(Some(reply_tx))).ok();
    wait_for("the reset's reply", &mut || {
        matches!(reply_rx.try_recv(), Ok(Some(_)))
    });
    assert_eq!(stats.resets.load(Ordering::Relaxed), 1);
    assert_eq!(stats.commands_dropped.load(Ordering::Relaxed), 0);
    let summary = l.finish().summary;
    assert!(summary.ticks >= 6);
}

/// States and applied inputs carry one clock: tick k is stamped origin + k / rate, which
/// maps back to k (what replay does with a node recording); a reset re-anchors tick 0 at
/// the wall clock.
#[test]
fn states_and_applied_inputs_share_the_tick_clock() {
    let origin: i64 = 1_700_000_000_123_456_789;
    let l = TestLoop::start_at(ClockMode::Wall, 1, origin);
    let (tx, rate) = (&l.tx, l.rate_hz);
    let clock = TimeBase::WallOrigin {
        tick_origin_ns: origin,
    };
    let next_state = || loop {
        if let Output::State(s) = l.out.recv_timeout(Duration::from_secs(30)).unwrap() {
            return s;
        }
    };
    let first = next_state();
    assert_eq!(first.stamp_ns, clock.stamp_ns(first.tick, rate));
    tx.send(Command::Excitation(vec![(0, 0.5)])).ok();
    let a = l.applied.recv_timeout(Duration::from_secs(30)).unwrap();
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
    let now = pacing::wall_ns();
    let s = std::iter::from_fn(|| Some(next_state()))
        .find(|s| s.tick == 1)
        .unwrap();
    assert!(
        (s.stamp_ns - now).abs() < 5_000_000_000,
        "{} vs {now}",
        s.stamp_ns
    );
    l.finish();
}

fn tick_ns_i64(ticks: u64, rate: f64) -> i64 {
    muscle_actuator_core::time::tick_ns(ticks, rate) as i64
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
    assert_eq!(
        b.stamp_ns,
        muscle_actuator_core::time::tick_ns(17, rate) as i64
    );
    assert_eq!(clock.now_ns(), b.stamp_ns);
    std::thread::sleep(Duration::from_millis(100));
    assert_eq!(
        stats.ticks.load(Ordering::Relaxed),
        17,
        "no tick after the steps"
    );
    let out = l.finish().out;
    let clocks: Vec<i64> = out
        .into_iter()
        .filter_map(|o| match o {
            Output::Clock(ns) => Some(ns),
            Output::State(_) => None,
        })
        .collect();
    let expected: Vec<i64> = [4, 8, 12, 16]
        .iter()
        .map(|&k| muscle_actuator_core::time::tick_ns(k, rate) as i64)
        .collect();
    assert_eq!(clocks, expected);
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
    let Handed { out, events, .. } = l.finish();
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
    let at = |tick: u64| muscle_actuator_core::time::tick_ns(tick, 1000.0) as i64;
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
    let Handed { out, applied, .. } = l.finish();
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

/// A loop under test on `mode`'s clock, from the default actuator: its command sender and
/// queue, outputs, events, applied inputs, counters, clock, stop flag and thread.
struct TestLoop {
    tx: CommandSender,
    /// The queue the loop drains, to hold it as a preempted sender would.
    queue: Arc<queue::CommandQueue>,
    rate_hz: f64,
    out: std::sync::mpsc::Receiver<Output>,
    events: std::sync::mpsc::Receiver<Event>,
    applied: std::sync::mpsc::Receiver<Applied>,
    stats: Arc<TickStats>,
    clock: Arc<NodeClock>,
    stop: Arc<AtomicBool>,
    handle: std::thread::JoinHandle<RunSummary>,
}

/// What a stopped [`TestLoop`] handed over, and its summary.
struct Handed {
    out: Vec<Output>,
    events: Vec<Event>,
    applied: Vec<Applied>,
    summary: RunSummary,
}

impl TestLoop {
    /// At tick origin 0.
    fn start(mode: ClockMode, clock_every: u64) -> Self {
        Self::start_at(mode, clock_every, 0)
    }

    fn start_at(mode: ClockMode, clock_every: u64, tick_origin_ns: i64) -> Self {
        let actuator = crate::ros::params::NodeParams::default().build().unwrap();
        let rate_hz = actuator.rate_hz();
        let (tx, rx) = command_channel();
        let queue = rx.queue.clone();
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
                tick_origin_ns,
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
            queue,
            rate_hz,
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
    fn finish(self) -> Handed {
        self.stop.store(true, Ordering::Relaxed);
        let summary = self.handle.join().unwrap();
        Handed {
            out: self.out.try_iter().collect(),
            events: self.events.try_iter().collect(),
            applied: self.applied.try_iter().collect(),
            summary,
        }
    }
}
