//! The tick loop's figures: [`TickStats`], the counters it shares with `/diagnostics` (written
//! by the loop, read by the node; every access `Relaxed`: each counter stands alone), the
//! lateness [`Histogram`], the [`Timing`] the loop keeps for itself, and the [`RunSummary`] it
//! returns when it ends.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

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
    #[cfg(test)]
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

/// The loop's own timing figures: the lateness of the last second and of the whole run, and the
/// step costs. [`Self::report`] publishes the window's to [`TickStats`] once a second.
pub(super) struct Timing {
    window: Histogram,
    whole: Histogram,
    window_start: Instant,
    window_step_ns: u64,
    window_steps: u64,
    total_step_ns: u128,
    summary: RunSummary,
}

impl Timing {
    /// Allocates the histograms (before the loop starts); the first window starts now.
    pub(super) fn new() -> Self {
        Self {
            window: Histogram::new(),
            whole: Histogram::new(),
            window_start: Instant::now(),
            window_step_ns: 0,
            window_steps: 0,
            total_step_ns: 0,
            summary: RunSummary::default(),
        }
    }

    /// A tick's step took `step_ns`.
    pub(super) fn stepped(&mut self, step_ns: u64) {
        self.window_step_ns += step_ns;
        self.window_steps += 1;
        self.total_step_ns += step_ns as u128;
        self.summary.ticks += 1;
    }

    /// A paced tick woke `late_ns` after its deadline.
    pub(super) fn lateness(&mut self, late_ns: u64) {
        self.window.record(late_ns);
        self.whole.record(late_ns);
    }

    /// A tick started more than one period late.
    pub(super) fn overrun(&mut self) {
        self.summary.overruns += 1;
    }

    /// A schedule restart dropped `ticks` ticks.
    pub(super) fn skipped(&mut self, ticks: u64) {
        self.summary.skipped += ticks;
    }

    /// Once the window has lasted a second (at `now`): its figures to `stats`, and a new window.
    pub(super) fn report(&mut self, now: Instant, stats: &TickStats) {
        if now.duration_since(self.window_start) < Duration::from_secs(1) {
            return;
        }
        let window = &self.window;
        stats.window_p50_ns.store(
            (window.quantile_ns(0.5) as f64).to_bits(),
            Ordering::Relaxed,
        );
        stats.window_p99_ns.store(
            (window.quantile_ns(0.99) as f64).to_bits(),
            Ordering::Relaxed,
        );
        stats
            .window_max_ns
            .store((window.max_ns() as f64).to_bits(), Ordering::Relaxed);
        stats.window_step_ns.store(
            (self.window_step_ns as f64 / self.window_steps.max(1) as f64).to_bits(),
            Ordering::Relaxed,
        );
        self.window.clear();
        self.window_step_ns = 0;
        self.window_steps = 0;
        self.window_start = now;
    }

    /// The whole run's figures.
    pub(super) fn summary(self) -> RunSummary {
        let mut summary = self.summary;
        summary.p50_us = self.whole.quantile_ns(0.5) as f64 / 1e3;
        summary.p99_us = self.whole.quantile_ns(0.99) as f64 / 1e3;
        summary.max_us = self.whole.max_ns() as f64 / 1e3;
        summary.mean_step_us = self.total_step_ns as f64 / summary.ticks.max(1) as f64 / 1e3;
        summary
    }
}
