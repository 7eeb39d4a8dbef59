//! A tick's sample as the messages the node publishes (`~/state`, `joint_states`), for the
//! publisher thread's outputs and the `~/step` answers.

use super::tick::Sample;
use muscle_actuator_recording::msgs::muscle_actuator_msgs::ActuatorState;
use muscle_actuator_recording::msgs::{state_messages, JointState};

/// Converts a sample into the two published messages.
pub(crate) fn sample_to_msgs(s: &Sample) -> (ActuatorState, JointState) {
    state_messages(
        s.stamp_ns,
        s.model.name(),
        s.tick,
        &s.muscle_names,
        &s.joint_names,
        &s.state,
    )
}
