//! `~/<muscle>/cmd_activation` (`std_msgs/Float64`): one muscle's excitation, on one topic per
//! muscle whose name makes a valid topic name (the HBP muscle interface's convention).

use super::{Input, InputContext};
use muscle_actuator_recording::msgs::Float64;

/// The topics' input; the instance `k` is the k-th muscle topic the node opened.
pub(crate) const MUSCLE_COMMAND: Input<Float64> = Input {
    what: "cmd_activation",
    received: |s| Some(&s.activation_received),
    handle,
};

fn handle(cx: &InputContext<'_>, k: usize, msg: Float64) {
    let Some(muscle) = cx.muscle_topics.get(k) else {
        return;
    };
    cx.excite(
        std::slice::from_ref(muscle),
        &[msg.data],
        &cx.shared.muscles(),
        None,
    );
}
