//! `/clock` followed (`use_sim_time` with `clock` wall): each time goes to the tick loop, which
//! steps the whole ticks it covers (after the inputs received before it). A time before zero is
//! refused.

use super::{Input, InputContext};
use crate::ros::tick::Command;
use muscle_actuator_recording::msgs::Clock;
use std::sync::atomic::Ordering;

/// The topic's input.
pub(crate) const CLOCK_IN: Input<Clock> = Input {
    what: "clock",
    received: |s| Some(&s.clock_received),
    handle,
};

fn handle(cx: &InputContext<'_>, _k: usize, msg: Clock) {
    let ns = msg.clock.to_nanos();
    if ns < 0 {
        cx.stats.clock_rejected.fetch_add(1, Ordering::Relaxed);
        cx.problem(
            "clock_negative",
            format!("/clock message refused: its time ({ns} ns) is before zero"),
        );
    } else {
        cx.shared.send(Command::ClockTime(ns));
    }
}
