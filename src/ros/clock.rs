//! The node's clock (parameter `clock`, docs/time.md): `wall`, ticks paced by the wall clock
//! and stamped with it; `sim`, the node is the graph's clock, stepping as fast as it can or at
//! `real_time_factor` × real time and publishing `/clock`; `lockstep`, the node is the clock and
//! advances only when asked (`~/step`). With `use_sim_time` and `clock` wall, the node follows
//! an external `/clock` instead ([`ClockMode::Follow`]): each clock message advances it by the
//! whole ticks it covers ([`ticks_covered`]). Every stamp the node writes (states,
//! `/diagnostics`, `/rosout`, the recording's log times) reads [`NodeClock::now_ns`].

use muscle_actuator_core::time::{self, TimeBase};
use std::sync::atomic::{AtomicI64, Ordering};

/// How ticks are paced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClockMode {
    Wall,
    Sim,
    Lockstep,
    /// `clock` wall with `use_sim_time`: ticks follow an external `/clock`.
    Follow,
}

impl ClockMode {
    pub const NAMES: [&'static str; 3] = ["wall", "sim", "lockstep"];

    pub fn name(self) -> &'static str {
        match self {
            ClockMode::Wall => "wall",
            ClockMode::Sim => "sim",
            ClockMode::Lockstep => "lockstep",
            ClockMode::Follow => "wall with use_sim_time (following /clock)",
        }
    }

    /// The mode of parameter `clock` with `use_sim_time`: `wall` follows `/clock` when it is
    /// true; `sim` and `lockstep` are the graph's clock themselves and do not.
    pub fn with_sim_time(self, use_sim_time: bool) -> Self {
        match self {
            ClockMode::Wall if use_sim_time => ClockMode::Follow,
            other => other,
        }
    }

    /// Whether the node is the graph's clock (publishes `/clock`).
    pub fn publishes_clock(self) -> bool {
        matches!(self, ClockMode::Sim | ClockMode::Lockstep)
    }

    /// Whether ticks are stamped with simulated time (the node's own, or a followed `/clock`)
    /// rather than the wall clock.
    pub fn is_simulated(self) -> bool {
        self != ClockMode::Wall
    }

    /// Whether ticks wait for someone else (a `~/step`, a `/clock`) rather than a schedule.
    pub fn is_driven(self) -> bool {
        matches!(self, ClockMode::Lockstep | ClockMode::Follow)
    }
}

/// A `clock` value that names no clock mode.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("clock {name:?} is not one of {}", ClockMode::NAMES.join(", "))]
pub struct UnknownClock {
    /// The value given, as an excerpt.
    pub name: String,
}

impl std::str::FromStr for ClockMode {
    type Err = UnknownClock;
    fn from_str(s: &str) -> Result<Self, UnknownClock> {
        match s {
            "wall" => Ok(ClockMode::Wall),
            "sim" => Ok(ClockMode::Sim),
            "lockstep" => Ok(ClockMode::Lockstep),
            other => Err(UnknownClock {
                name: muscle_actuator_core::text::excerpt(other),
            }),
        }
    }
}

/// The node's time now, shared by its threads: the wall clock, or the simulated time the tick
/// loop has reached.
#[derive(Debug)]
pub struct NodeClock {
    mode: ClockMode,
    /// Simulated time of the last tick, ns (sim and lockstep).
    sim_ns: AtomicI64,
}

impl NodeClock {
    pub fn new(mode: ClockMode) -> Self {
        Self {
            mode,
            sim_ns: AtomicI64::new(0),
        }
    }

    pub fn mode(&self) -> ClockMode {
        self.mode
    }

    /// Now, ns: since the Unix epoch (wall), since the simulation's start (sim, lockstep), or
    /// the followed `/clock`'s time at the last tick (0 before the first one).
    pub fn now_ns(&self) -> i64 {
        match self.mode {
            ClockMode::Wall => time::now_ns(),
            _ => self.sim_ns.load(Ordering::Acquire),
        }
    }

    /// Set by the tick loop after each tick (simulated clocks only).
    pub fn advance_to(&self, ns: i64) {
        if self.mode.is_simulated() {
            self.sim_ns.store(ns, Ordering::Release);
        }
    }

    /// The stamp of tick 0 at start: the wall clock's now, or simulated time zero (following
    /// `/clock`: not known until the first message, which re-anchors it).
    pub fn start_origin_ns(&self) -> i64 {
        match self.mode {
            ClockMode::Wall => time::now_ns(),
            _ => 0,
        }
    }

    /// The recording's time base for a run whose tick 0 is stamped `tick_origin_ns` (following
    /// `/clock`: no origin until the first message).
    pub fn time_base(&self, tick_origin_ns: i64) -> TimeBase {
        match self.mode {
            ClockMode::Wall => TimeBase::WallOrigin { tick_origin_ns },
            ClockMode::Follow => TimeBase::RosClock {
                tick_origin_ns: None,
            },
            _ => TimeBase::Simulated,
        }
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    /// The ticks a clock time covers: exactly those stamped at or before it, at rates whose
    /// period is not a whole number of ns too.
    #[test]
    fn ticks_covered_are_those_stamped_at_or_before() {
        for rate in [1000.0, 333.0, 2500.0, 7.0] {
            for origin in [0, 5_000_000_000_123, 7] {
                let clock = TimeBase::WallOrigin {
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
}
