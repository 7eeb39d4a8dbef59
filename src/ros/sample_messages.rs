//! A tick's sample as the messages the node publishes (`~/state`, `joint_states`,
//! `~/joint_efforts`), for the publisher thread, the `~/step` answers and the live view.

use super::tick::Sample;
use muscle_actuator_recording::msgs::muscle_actuator_msgs::ActuatorState;
use muscle_actuator_recording::msgs::{
    state_messages, Float64MultiArray, JointState, MultiArrayLayout,
};

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

/// `~/joint_efforts`: the muscles' net torque on each driven joint, N m, in configuration
/// order (ros2_control's `forward_command_controller` convention).
pub(crate) fn efforts_msg(s: &Sample) -> Float64MultiArray {
    Float64MultiArray {
        layout: MultiArrayLayout::default(),
        data: s.driven.iter().map(|&j| s.state.joints[j].torque).collect(),
    }
}
