//! A client's queue of frames and the live view's counters: what the fan-out and the
//! executor's answers hand to one client never waits; a full queue drops and counts.

use super::channels::Outlet;
use super::protocol;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{SyncSender, TrySendError};
use std::sync::{Arc, Mutex};

/// Frames waiting for one client, most [`CLIENT_QUEUE`].
pub(crate) const CLIENT_QUEUE: usize = 1024;

/// What a client's thread sends next.
pub(crate) enum Frame {
    Text(String),
    Binary(Vec<u8>),
    /// A channel's message for one of the client's subscriptions (the payload shared by all).
    Data {
        subscription: u32,
        receive_ns: u64,
        payload: Arc<[u8]>,
    },
}

impl Frame {
    pub(crate) fn into_message(self) -> tungstenite::Message {
        match self {
            Frame::Text(t) => tungstenite::Message::text(t),
            Frame::Binary(b) => tungstenite::Message::binary(b),
            Frame::Data {
                subscription,
                receive_ns,
                payload,
            } => tungstenite::Message::binary(protocol::message_data(
                subscription,
                receive_ns,
                &payload,
            )),
        }
    }
}

/// One connected client, as the fan-out and the executor's answers see it.
pub(crate) struct Client {
    pub(crate) queue: SyncSender<Frame>,
    /// (subscription id, outlet) pairs.
    pub(crate) subscriptions: Mutex<Vec<(u32, Outlet)>>,
    pub(crate) dropped: AtomicU64,
}

impl Client {
    /// Queues a frame for the client; a full queue drops it (counted here and in `stats`).
    pub(crate) fn send(&self, f: Frame, stats: &LiveStats) -> bool {
        match self.queue.try_send(f) {
            Ok(()) => true,
            Err(TrySendError::Full(_)) => {
                self.dropped.fetch_add(1, Ordering::Relaxed);
                stats.dropped.fetch_add(1, Ordering::Relaxed);
                false
            }
            Err(TrySendError::Disconnected(_)) => false,
        }
    }
}

/// The live view's counters, for `/diagnostics`.
#[derive(Debug, Default)]
pub(crate) struct LiveStats {
    /// Clients connected now.
    pub(crate) clients: AtomicUsize,
    /// Connections accepted since start.
    pub(crate) connections: AtomicU64,
    /// Messages a client's full queue could not take.
    pub(crate) dropped: AtomicU64,
    /// Clients disconnected for what they sent (garbage, an oversized frame, an unknown op).
    pub(crate) kicked: AtomicU64,
    /// Connections refused: too many clients, or a failed handshake.
    pub(crate) refused: AtomicU64,
    /// Client requests the executor's full queue could not take.
    pub(crate) requests_dropped: AtomicU64,
}
