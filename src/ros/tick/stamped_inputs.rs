//! Inputs stamped ahead (docs/time.md): with a simulated clock, an input whose header stamp
//! lies ahead of the node's time, by at most [`SCHEDULE_HORIZON_S`], waits for the first tick
//! stamped at or after it (ros2_control's trajectory controller reads `header.stamp` so), in
//! stamp order whatever the order of arrival; inputs stamped alike keep their order of arrival.
//! At most [`SCHEDULE_CAPACITY`] wait at once; the room is allocated before the loop starts.

use super::super::clock::ClockMode;
use super::messages::Command;
use std::collections::VecDeque;

/// With a simulated clock, inputs stamped further ahead of the node's time than this are taken
/// for another clock's (a wall-clock stamp) and apply at the next tick, s.
pub const SCHEDULE_HORIZON_S: f64 = 3600.0;

/// Most inputs waiting for their stamp at once; more are dropped and counted.
pub const SCHEDULE_CAPACITY: usize = 1024;

/// The inputs waiting for their stamp, in stamp order: (stamp ns, input).
pub(super) struct Schedule {
    waiting: VecDeque<(i64, Command)>,
}

impl Schedule {
    pub(super) fn new() -> Self {
        Self {
            waiting: VecDeque::with_capacity(SCHEDULE_CAPACITY),
        }
    }

    /// Whether an input stamped `at` waits, on `mode`'s clock at `now_ns`.
    pub(super) fn holds(mode: ClockMode, at: i64, now_ns: i64) -> bool {
        mode.is_simulated() && at > now_ns && (at - now_ns) as f64 <= SCHEDULE_HORIZON_S * 1e9
    }

    /// Lays `input` out for its stamp `at`, after those stamped at or before it; `false` (the
    /// input dropped) when [`SCHEDULE_CAPACITY`] wait already.
    pub(super) fn insert(&mut self, at: i64, input: Command) -> bool {
        if self.waiting.len() >= SCHEDULE_CAPACITY {
            return false;
        }
        let k = self.waiting.partition_point(|(t, _)| *t <= at);
        self.waiting.insert(k, (at, input));
        true
    }

    /// The next input whose stamp has come at `now_ns`.
    pub(super) fn pop_due(&mut self, now_ns: i64) -> Option<Command> {
        self.waiting
            .pop_front_if(|(at, _)| *at <= now_ns)
            .map(|(_, c)| c)
    }

    pub(super) fn len(&self) -> usize {
        self.waiting.len()
    }

    /// Drops every input waiting (a reset, a failed step, a `/clock` jump).
    pub(super) fn clear(&mut self) {
        self.waiting.clear();
    }
}
