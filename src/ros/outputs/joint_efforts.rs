//! `~/joint_efforts` (`std_msgs/Float64MultiArray`): with driven joints, the muscles' net torque
//! on each, N m, in configuration order (ros2_control's `forward_command_controller`
//! convention).

use super::{Producer, TickOutput};
use muscle_actuator_recording::msgs::{Float64MultiArray, MultiArrayLayout};

/// The topic's producer.
pub(crate) const JOINT_EFFORTS: Producer<Float64MultiArray> = Producer {
    make: |o| match o {
        TickOutput::State(s) if !s.driven.is_empty() => Some(Float64MultiArray {
            layout: MultiArrayLayout::default(),
            data: s.driven.iter().map(|&j| s.state.joints[j].torque).collect(),
        }),
        _ => None,
    },
};
