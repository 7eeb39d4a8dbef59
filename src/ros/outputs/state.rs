//! `~/state` (`muscle_actuator_msgs/ActuatorState`): every muscle's and joint's state after a
//! published tick.

use super::{Producer, TickOutput};
use crate::ros::sample_messages::sample_to_msgs;
use muscle_actuator_recording::msgs::muscle_actuator_msgs::ActuatorState;

/// The topic's producer.
pub(crate) const STATE: Producer<ActuatorState> = Producer {
    make: |o| match o {
        TickOutput::State(s) => Some(sample_to_msgs(s).0),
        TickOutput::Clock(_) => None,
    },
};
