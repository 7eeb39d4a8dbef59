//! How the loop paces its ticks ([`Pacing`], docs/time.md). A paced loop (`wall`, and `sim`
//! with a `real_time_factor`) ticks against absolute [`Deadlines`]: tick n of a schedule is due
//! at its origin + n × pace, so that a late tick does not delay the ones after it. A tick that
//! wakes more than one pace after its deadline is an overrun; more than [`RESYNC_PERIODS`] paces
//! after it, the loop drops the backlog and starts a new schedule from the wake. A driven loop
//! (`lockstep`, following `/clock`) has no deadline: it parks for at most [`LOCKSTEP_IDLE`]
//! until a command arrives.

use super::super::clock::NodeClock;
use std::sync::Arc;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

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

/// Longest a lockstep loop sleeps between looks at its stop flag when no step is asked for.
pub(super) const LOCKSTEP_IDLE: Duration = Duration::from_millis(20);

/// After this many periods behind, the loop stops catching up and restarts its schedule.
pub(super) const RESYNC_PERIODS: u32 = 100;

/// The wall clock now, ns since the Unix epoch.
pub(super) fn wall_ns() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_nanos() as i64)
        .unwrap_or(0)
}

/// A paced loop's schedule: the `n`th tick after `origin` is due at `origin + n × pace`.
pub(super) struct Deadlines {
    origin: Instant,
    /// Ticks since `origin`.
    n: u64,
}

/// How a paced tick woke: when, and how long after its deadline.
pub(super) struct Wake {
    pub(super) at: Instant,
    pub(super) late: Duration,
}

impl Deadlines {
    /// A schedule starting now.
    pub(super) fn start() -> Self {
        Self {
            origin: Instant::now(),
            n: 0,
        }
    }

    /// A new schedule from `at`: the next tick is due one pace after it.
    pub(super) fn restart(&mut self, at: Instant) {
        self.origin = at;
        self.n = 0;
    }

    /// Sleeps until the next tick's deadline (at once when it has passed).
    pub(super) fn sleep_until_next(&mut self, pace: Duration) -> Wake {
        self.n += 1;
        let deadline =
            self.origin + Duration::from_nanos((pace.as_nanos() as u64).saturating_mul(self.n));
        let now = Instant::now();
        if deadline > now {
            std::thread::sleep(deadline - now);
        }
        let at = Instant::now();
        Wake {
            at,
            late: at.saturating_duration_since(deadline),
        }
    }
}

/// The ticks a wake `late` after its deadline drops when it restarts the schedule: `None` while
/// it is at most [`RESYNC_PERIODS`] paces late.
pub(super) fn skipped_ticks(late: Duration, pace: Duration) -> Option<u64> {
    (late > pace * RESYNC_PERIODS).then(|| (late.as_nanos() / pace.as_nanos().max(1)) as u64)
}
