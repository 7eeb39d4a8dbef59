//! `~/test_excitation` (`std_msgs/Float64`), an input only the tests know (feature
//! `test-topic`, `src/tests_topic.rs`): one excitation for every muscle at once. This file and its
//! row in the endpoints' table are all there is of it.

use super::{Input, InputContext};
use muscle_actuator_recording::msgs::Float64;

/// The topic's input.
pub(crate) const TEST_EXCITATION: Input<Float64> = Input {
    what: "test_excitation",
    received: |s| Some(&s.activation_received),
    handle,
};

fn handle(cx: &InputContext<'_>, _k: usize, msg: Float64) {
    let known = cx.shared.muscles();
    let values = vec![msg.data; known.len()];
    cx.excite(&known, &values, &known, None);
}
