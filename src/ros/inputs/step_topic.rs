//! `~/step` as a topic (`std_msgs/Int64`): the `~/step` service's advance, fire and forget; a
//! refused one is logged.

use super::{Input, InputContext};
use crate::ros::services::step_refusal;
use crate::ros::severity::Severity;
use crate::ros::tick::Command;
use muscle_actuator_recording::msgs::Int64;

/// The topic's input.
pub(crate) const STEP_TOPIC: Input<Int64> = Input {
    what: "step",
    received: |_| None,
    handle,
};

fn handle(cx: &InputContext<'_>, _k: usize, msg: Int64) {
    match step_refusal(cx.mode, msg.data) {
        Some(why) => cx
            .log
            .report("step", Severity::Warn, format!("step refused: {why}")),
        None => cx.shared.send(Command::Step {
            ticks: msg.data as u64,
            reply: None,
        }),
    }
}
