//! `~/activation_array` (`std_msgs/Float64MultiArray`): every muscle's excitation, in the
//! configuration's order (ros2_control's `forward_command_controller` convention).

use super::{Input, InputContext};
use muscle_actuator_core::sim::input::Rejection;
use muscle_actuator_recording::msgs::Float64MultiArray;

/// The topic's input.
pub(crate) const ACTIVATION_ARRAY: Input<Float64MultiArray> = Input {
    what: "activation_array",
    received: |s| Some(&s.activation_received),
    handle,
};

fn handle(cx: &InputContext<'_>, _k: usize, msg: Float64MultiArray) {
    let known = cx.shared.muscles();
    if msg.data.len() != known.len() {
        let rej = Rejection::LengthMismatch {
            names: known.len(),
            values: msg.data.len(),
        };
        let m = format!(
            "activation_array rejected: {} values for {} muscles (in order: {})",
            msg.data.len(),
            known.len(),
            muscle_actuator_core::text::excerpt(&known.join(", "))
        );
        cx.rejected(&cx.stats.activation_rejected, &rej, m);
        return;
    }
    // All of them, in order: the names are the configuration's own.
    cx.excite(&known, &msg.data, &known, None);
}
