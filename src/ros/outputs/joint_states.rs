//! `joint_states` (`sensor_msgs/JointState`): the joints' angle, velocity and torque after a
//! published tick, for robot_state_publisher and the simulators.

use super::{Producer, TickOutput};
use crate::ros::sample_messages::sample_to_msgs;
use muscle_actuator_recording::msgs::JointState;

/// The topic's producer.
pub(crate) const JOINT_STATES: Producer<JointState> = Producer {
    make: |o| match o {
        TickOutput::State(s) => Some(sample_to_msgs(s).1),
        TickOutput::Clock(_) => None,
    },
};
