//! `/clock` (`rosgraph_msgs/Clock`): the node's simulated time, when it is the graph's clock
//! (`clock` sim or lockstep).

use super::{Producer, TickOutput};
use muscle_actuator_recording::msgs::{Clock, Time};

/// The topic's producer.
pub(crate) const CLOCK: Producer<Clock> = Producer {
    make: |o| match o {
        TickOutput::Clock(ns) => Some(Clock {
            clock: Time::from_nanos(*ns),
        }),
        TickOutput::State(_) => None,
    },
};
