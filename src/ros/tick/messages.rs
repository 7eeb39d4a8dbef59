//! What the tick loop and the node's other threads pass each other: [`Command`]s in (applied at
//! the next tick boundary), [`Output`]s and [`Event`]s out (states and times to publish, lines
//! to log), and the [`Applied`] inputs for the recording (docs/ros-interface.md).

use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::{Actuator, StateSnapshot};
use std::sync::Arc;

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
    ///
    /// [`SCHEDULE_HORIZON_S`]: super::SCHEDULE_HORIZON_S
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
    /// The actuator's tick when they took effect (the recording keeps the stamp; the tests
    /// read the tick).
    #[cfg_attr(not(test), expect(dead_code, reason = "read by the tick loop's tests"))]
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
    ///
    /// [`FOLLOW_MAX_AHEAD_S`]: super::FOLLOW_MAX_AHEAD_S
    ClockJumped {
        from_ns: i64,
        to_ns: i64,
        at_tick: u64,
    },
}
