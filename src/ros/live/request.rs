//! What a client asks of the node, on its way to the executor, and where the answer goes.

use super::channels::Service;
use super::protocol::ParameterIn;
use super::queue::{Client, Frame, LiveStats};
use muscle_actuator_recording::msgs::muscle_actuator_msgs::{ActivationCommand, ExternalLoad};
use muscle_actuator_recording::msgs::{Float64, Float64MultiArray};
use std::sync::Arc;

/// A message a client published on an input topic, decoded.
#[derive(Debug)]
pub(crate) enum Input {
    Activation(ActivationCommand),
    ActivationArray(Float64MultiArray),
    /// The k-th muscle topic.
    MuscleCommand(usize, Float64),
    Load(ExternalLoad),
}

/// Where an answer goes: the client that asked.
pub(crate) struct Answer {
    pub(crate) client: Arc<Client>,
    pub(crate) stats: Arc<LiveStats>,
}

impl Answer {
    pub(crate) fn text(&self, t: String) {
        self.client.send(Frame::Text(t), &self.stats);
    }
    pub(crate) fn binary(&self, b: Vec<u8>) {
        self.client.send(Frame::Binary(b), &self.stats);
    }
}

/// What a client asks of the node, for the executor.
pub(crate) enum Request {
    Input(Input),
    /// A message on an input topic that could not be decoded.
    Unreadable {
        what: &'static str,
        error: String,
    },
    GetParameters {
        names: Vec<String>,
        id: Option<String>,
        answer: Answer,
    },
    SetParameters {
        parameters: Vec<ParameterIn>,
        id: Option<String>,
        answer: Answer,
    },
    Call {
        service: Service,
        call_id: u32,
        payload: Vec<u8>,
        answer: Answer,
    },
    /// A line for the node's log (rate-limited per key).
    Log {
        key: &'static str,
        warn: bool,
        line: String,
    },
}
