//! What a client asks of the node, on its way to the executor, and where the answer goes.

use super::protocol::ParameterIn;
use super::queue::{Client, Frame, LiveStats};
use crate::ros::endpoints::{Endpoint, Service};
use std::sync::Arc;

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
    /// A message a client published on the `k`-th instance of an input topic, as sent (CDR, or
    /// JSON when `json`): the input's handler decodes it on the executor.
    Input {
        endpoint: Endpoint,
        k: usize,
        json: bool,
        payload: Vec<u8>,
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
