//! The commands applied at a tick boundary ([`TickLoop::apply`]), and the three resets: on
//! request, after a failed step, and on a `/clock` jump, each back to the initial state with
//! every input cleared and tick 0 re-anchored (docs/time.md).
//!
//! Following `/clock`: the first clock time anchors tick 0 there; each later one lets the loop
//! step the whole ticks it covers ([`ticks_covered`]); a clock that goes back, or forward by more
//! than [`FOLLOW_MAX_AHEAD_S`] at once, is a jump.

use super::super::clock::{ticks_covered, ClockMode};
use super::messages::{AppliedInput, Command, Event};
use super::pacing::wall_ns;
use super::tick_loop::{Names, TickLoop};
use muscle_actuator_core::sim::Actuator;
use muscle_actuator_core::time::TimeBase;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

/// Following `/clock`, a clock that moves forward by more than this much simulated time at once
/// is a jump (reset and re-anchored), not ticks to catch up on, s.
pub const FOLLOW_MAX_AHEAD_S: f64 = 60.0;

impl TickLoop {
    /// Applies `command` (taken from the queue or the schedule) before the next step.
    pub(super) fn apply(&mut self, command: Command) {
        match command {
            Command::Excitation(v) => self.set_excitations(v),
            Command::Load(v) => self.set_loads(v),
            Command::Reset(reply) => {
                let before = self.actuator.tick();
                self.reanchor(before);
                self.back_to_rest();
                self.io.stats.resets.fetch_add(1, Ordering::Relaxed);
                self.event(Event::Reset { at_tick: before });
                if let Some(r) = reply {
                    let _ = r.send(before);
                }
            }
            Command::Replace(new) => self.replace(*new),
            Command::PublishEvery(k) => self.publish_every = k.max(1),
            Command::JointMotion(mut v) => {
                v.retain(|&(j, angle, velocity)| {
                    self.actuator.set_joint_motion(j, angle, velocity)
                });
                self.motion_age = 0;
                self.hand_applied(&self.names.joints, AppliedInput::JointMotion(v));
            }
            Command::RealTimeFactor(f) => {
                self.real_time_factor = f;
                // Only a simulated clock is paced by it: the wall schedule stays as it is.
                if self.mode == ClockMode::Sim {
                    self.deadlines.restart(Instant::now());
                }
            }
            Command::ClockEvery(k) => self.clock_every = k.max(1),
            Command::ClockTime(ns) if self.mode == ClockMode::Follow => self.follow(ns),
            Command::ClockTime(_) => {}
            // Unwrapped when taken.
            Command::Stamped(_, _) => {}
            Command::Step { ticks, reply } => {
                if ticks > 0 {
                    self.steps.push_back((ticks, reply));
                }
            }
        }
    }

    /// New excitations, (muscle index, u), in force until the next.
    fn set_excitations(&mut self, v: Vec<(usize, f64)>) {
        for &(i, u) in &v {
            if let Some(slot) = self.excitation.get_mut(i) {
                *slot = u;
            }
            self.actuator.set_excitation(i, u);
        }
        self.hand_applied(&self.names.muscles, AppliedInput::Excitation(v));
    }

    /// New external torques, (joint index, N m), in force until the next.
    fn set_loads(&mut self, v: Vec<(usize, f64)>) {
        for &(i, t) in &v {
            if let Some(slot) = self.load.get_mut(i) {
                *slot = t;
            }
            self.actuator.set_external_torque(i, t);
        }
        self.hand_applied(&self.names.joints, AppliedInput::Load(v));
    }

    /// A new actuator from its initial state, with the inputs in force; a new rate starts a new
    /// schedule.
    fn replace(&mut self, new: Actuator) {
        self.reanchor(self.actuator.tick());
        self.actuator = new;
        self.names = Names::of(&self.actuator);
        self.motion_age = u64::MAX;
        self.io
            .stats
            .driven_joints
            .store(self.names.driven.len() as u64, Ordering::Relaxed);
        self.excitation.resize(self.names.muscles.len(), 0.0);
        self.load.resize(self.names.joints.len(), 0.0);
        for (i, u) in self.excitation.iter().enumerate() {
            self.actuator.set_excitation(i, *u);
        }
        for (i, t) in self.load.iter().enumerate() {
            self.actuator.set_external_torque(i, *t);
        }
        let new_period = Duration::from_secs_f64(1.0 / self.actuator.rate_hz());
        if new_period != self.period {
            self.period = new_period;
            self.deadlines.restart(Instant::now());
        }
        if self.mode == ClockMode::Wall {
            self.reanchor(0);
        }
        self.io
            .stats
            .rate_hz_bits
            .store(self.actuator.rate_hz().to_bits(), Ordering::Relaxed);
        self.event(Event::Replaced {
            model: self.actuator.model(),
            rate_hz: self.actuator.rate_hz(),
        });
    }

    /// Following `/clock`: the external clock's time `ns` now.
    fn follow(&mut self, ns: i64) {
        let rate = self.actuator.rate_hz();
        match self.follow_until {
            None => {
                // The first clock message: the tick reached (0) is at its time.
                self.clock = TimeBase::WallOrigin {
                    tick_origin_ns: ns
                        - muscle_actuator_core::time::tick_ns(self.actuator.tick(), rate) as i64,
                };
                self.event(Event::ClockAnchored {
                    origin_ns: self.clock.tick_origin_ns(),
                });
            }
            Some(last)
                if ns < last
                    || ticks_covered(self.clock, ns, rate).saturating_sub(self.actuator.tick())
                        as f64
                        > FOLLOW_MAX_AHEAD_S * rate =>
            {
                let before = self.actuator.tick();
                self.back_to_rest();
                self.clock = TimeBase::WallOrigin { tick_origin_ns: ns };
                self.io.stats.clock_jumps.fetch_add(1, Ordering::Relaxed);
                self.event(Event::ClockJumped {
                    from_ns: last,
                    to_ns: ns,
                    at_tick: before,
                });
            }
            Some(_) => {}
        }
        self.follow_until = Some(ns);
        self.io
            .pacing
            .clock
            .advance_to(self.clock.stamp_ns(self.actuator.tick(), rate));
    }

    /// Tick 0 re-anchored after a reset or a rebuild from `tick`: one period before now (wall),
    /// or at the simulated time `tick` reached (simulated clocks, whose time never goes back).
    pub(super) fn reanchor(&mut self, tick: u64) {
        self.clock = TimeBase::WallOrigin {
            tick_origin_ns: match self.mode {
                ClockMode::Wall => wall_ns() - self.period.as_nanos() as i64,
                _ => self.clock.stamp_ns(tick, self.actuator.rate_hz()),
            },
        };
    }

    /// The actuator back to its initial state with every input cleared: those in force and
    /// those stamped ahead (a reset on request, a failed step, a `/clock` jump).
    pub(super) fn back_to_rest(&mut self) {
        self.actuator.reset();
        self.excitation.fill(0.0);
        self.load.fill(0.0);
        self.schedule.clear();
    }
}
