//! Why the live view cannot start: its catalogue of schemas, or its socket and thread. The node
//! runs on without it, warning with the message.

use std::net::SocketAddr;

/// Why the live view cannot start.
#[derive(Debug, thiserror::Error)]
pub enum LiveError {
    /// A channel's or service's schema cannot be assembled (a type without a definition).
    #[error(transparent)]
    Schema(#[from] muscle_actuator_recording::recording::schema::SchemaError),
    /// The port cannot be bound or set non-blocking.
    #[error("cannot listen on {addr}: {source}")]
    Listen {
        /// The address asked for.
        addr: SocketAddr,
        /// Why.
        source: std::io::Error,
    },
    /// The bound socket has no local address.
    #[error(transparent)]
    LocalAddr(std::io::Error),
    /// The thread that accepts connections cannot start.
    #[error("cannot start the live view's thread: {0}")]
    Thread(#[source] std::io::Error),
}
