//! `~/joint_states_in` (`sensor_msgs/JointState`): the driven joints' angle and velocity, by
//! name, from the simulator that owns them; they take effect at the next tick and are
//! extrapolated linearly until the next message.

use super::{Input, InputContext};
use crate::ros::tick::Command;
use muscle_actuator_core::sim::input;
use muscle_actuator_recording::msgs::JointState;

/// The topic's input.
pub(crate) const JOINT_STATES_IN: Input<JointState> = Input {
    what: "joint state",
    received: |_| None,
    handle,
};

fn handle(cx: &InputContext<'_>, _k: usize, msg: JointState) {
    let driven = cx.shared.driven();
    match input::validate_joint_motion(&msg.name, &msg.position, &msg.velocity, &driven) {
        Ok(motion) if motion.is_empty() => cx.problem(
            "joint_state_unmatched",
            format!(
                "joint state ignored: it names none of the driven joints ({})",
                muscle_actuator_core::text::excerpt(
                    &driven
                        .iter()
                        .map(|(_, n)| n.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            ),
        ),
        Ok(motion) => cx.shared.send(Command::JointMotion(motion)),
        Err(rej) => cx.rejected(
            &cx.stats.joint_states_rejected,
            &rej,
            format!("joint state rejected: {rej}"),
        ),
    }
}
