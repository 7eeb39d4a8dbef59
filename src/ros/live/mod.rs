//! The live view (docs/live-view.md): the node serves the Foxglove WebSocket protocol, so that
//! Foxglove or Lichtblick connects to `ws://localhost:8765` and plots the node's topics while
//! it runs, publishes activations and loads, sets parameters, and calls `~/reset` and `~/step`.
//!
//! Written on `tungstenite` rather than with the `foxglove` crate (foxglove-sdk 0.30), which
//! answers HTTP 400 to the specification's subprotocol name `foxglove.websocket.v1` that older
//! clients still ask for, answers a frame outside the protocol with a status message where this
//! node disconnects the client, does not expose what it drops per client, and brings an async
//! runtime of its own. The protocol itself is small (see [`protocol`]).
//!
//! Threads, none of them on the tick path:
//! - the acceptor ([`LiveView::start`]), bound to 127.0.0.1 unless discovery is `SUBNET`;
//! - one per client ([`client`]), with its own bounded queue ([`hub`]);
//! - the publisher thread hands messages to [`LiveTap`], which encodes each once and queues it
//!   to the clients subscribed to it;
//! - what clients ask of the node (inputs, parameters, services, log lines) reaches the
//!   executor through one bounded queue ([`Request`]); `ros::live_requests` answers there,
//!   with the same validation, recording and replies as the DDS side.

pub(crate) mod channels;
mod client;
mod error;
mod hub;
pub(crate) mod protocol;
mod queue;
mod request;
mod server;

pub(crate) use channels::Catalogue;
pub(crate) use hub::LiveTap;
pub(crate) use request::{Answer, Request};
pub(crate) use server::{LiveOptions, LiveStatus, LiveView};
