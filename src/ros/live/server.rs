//! The live view's server: the listening socket and the thread that accepts connections,
//! each served on a thread of its own ([`super::client`]).

use super::channels::Catalogue;
use super::client;
use super::error::LiveError;
use super::hub::{Hub, LiveTap};
use super::queue::LiveStats;
use super::request::Request;
use serde_json::json;
use std::net::{Ipv4Addr, SocketAddr, TcpListener};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

/// Most clients served at once; more are refused (counted).
pub(crate) const MAX_CLIENTS: usize = 16;
/// Requests from clients waiting for the executor, at most.
const REQUEST_QUEUE: usize = 256;
/// How often the acceptor looks for a new connection (and for the stop).
const ACCEPT_POLL: Duration = Duration::from_millis(20);

/// How the live view runs, for `/diagnostics`.
pub(crate) enum LiveStatus<'a> {
    /// `foxglove_port` 0.
    Off,
    /// It could not start (the port taken, say): why.
    Failed(&'a str),
    Serving(&'a LiveStats, std::net::SocketAddr),
}

/// What the live view is started with.
pub(crate) struct LiveOptions<'a> {
    pub(crate) port: u16,
    /// Bind to 127.0.0.1 (discovery kept on this host), else to every interface.
    pub(crate) local: bool,
    pub(crate) catalogue: Catalogue,
    /// The node's fully qualified name, the server's name.
    pub(crate) name: &'a str,
    /// The node runs a simulated clock: the `time` capability.
    pub(crate) sim_time: bool,
}

/// The running live view.
pub(crate) struct LiveView {
    hub: Arc<Hub>,
    acceptor: JoinHandle<()>,
    pub(crate) addr: SocketAddr,
    pub(crate) requests: smol::channel::Receiver<Request>,
}

impl LiveView {
    /// Binds the port and starts accepting; an error (the port taken, say) is one line.
    pub(crate) fn start(o: LiveOptions<'_>) -> Result<Self, LiveError> {
        let ip = if o.local {
            Ipv4Addr::LOCALHOST
        } else {
            Ipv4Addr::UNSPECIFIED
        };
        let asked = SocketAddr::from((ip, o.port));
        let listener = TcpListener::bind(asked).map_err(|source| LiveError::Listen {
            addr: asked,
            source,
        })?;
        let addr = listener.local_addr().map_err(LiveError::LocalAddr)?;
        listener
            .set_nonblocking(true)
            .map_err(|source| LiveError::Listen { addr, source })?;
        let (tx, requests) = smol::channel::bounded(REQUEST_QUEUE);
        let mut capabilities = vec!["clientPublish", "parameters", "services"];
        if o.sim_time {
            capabilities.push("time");
        }
        let server_info = json!({
            "op": "serverInfo",
            "name": o.name,
            "capabilities": capabilities,
            "supportedEncodings": ["cdr", "json"],
            "metadata": {"ROS_DISTRO": "kilted"},
            "sessionId": muscle_actuator_core::time::now_ns().to_string(),
        })
        .to_string();
        let hub = Arc::new(Hub::new(o.catalogue, server_info, tx));
        let h = hub.clone();
        let acceptor = std::thread::Builder::new()
            .name("live-accept".into())
            .spawn(move || accept_loop(listener, h))
            .map_err(LiveError::Thread)?;
        Ok(Self {
            hub,
            acceptor,
            addr,
            requests,
        })
    }

    /// The live view's counters.
    pub(crate) fn stats(&self) -> &LiveStats {
        &self.hub.stats
    }

    /// The publisher thread's handle.
    pub(crate) fn tap(&self) -> LiveTap {
        LiveTap(self.hub.clone())
    }

    /// Stops accepting; the client threads end within a poll.
    pub(crate) fn stop(self) {
        self.hub.stopping.store(true, Ordering::SeqCst);
        let _ = self.acceptor.join();
    }
}

/// Accepts connections until the stop, each served on its own thread; at most [`MAX_CLIENTS`]
/// threads (handshakes included) at once.
fn accept_loop(listener: TcpListener, hub: Arc<Hub>) {
    let active = Arc::new(AtomicUsize::new(0));
    while !hub.stopping.load(Ordering::Relaxed) {
        match listener.accept() {
            Ok((stream, _)) => {
                if active.load(Ordering::SeqCst) >= MAX_CLIENTS {
                    hub.stats.refused.fetch_add(1, Ordering::Relaxed);
                    continue;
                }
                // The listener is non-blocking; the handshake is not.
                if stream.set_nonblocking(false).is_err() {
                    continue;
                }
                let h = hub.clone();
                let a = active.clone();
                a.fetch_add(1, Ordering::SeqCst);
                let spawned = std::thread::Builder::new()
                    .name("live-client".into())
                    .spawn(move || {
                        client::serve(stream, h);
                        a.fetch_sub(1, Ordering::SeqCst);
                    });
                if spawned.is_err() {
                    active.fetch_sub(1, Ordering::SeqCst);
                    hub.stats.refused.fetch_add(1, Ordering::Relaxed);
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => std::thread::sleep(ACCEPT_POLL),
            // A connection that failed before it was accepted, or no descriptors left: wait.
            Err(_) => std::thread::sleep(ACCEPT_POLL),
        }
    }
}
