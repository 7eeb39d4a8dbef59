//! The live view's clients and the fan-out to them: the publisher thread hands each message
//! over once ([`LiveTap::put`]); it is encoded only when a client subscribed to its channel, and
//! each subscribed client gets it through its own bounded queue. A full queue drops the message
//! for that client and counts it: nothing here ever waits for a client.

use super::channels::{Catalogue, Outlet, OUTLETS};
use super::protocol;
use super::queue::{Client, Frame, LiveStats};
use super::request::Request;
use crate::ros::endpoints::Endpoint;
use muscle_actuator_recording::recording::encode_cdr;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::SyncSender;
use std::sync::{Arc, Mutex};

/// The clients, the catalogue they are served, and the way to the executor.
pub(crate) struct Hub {
    pub(crate) catalogue: Catalogue,
    /// `serverInfo`, as sent to each client.
    pub(crate) server_info: String,
    clients: Mutex<Vec<Arc<Client>>>,
    /// Subscriptions per outlet, over all clients: a message nobody subscribed to is not
    /// encoded.
    subscribers: [AtomicUsize; OUTLETS],
    pub(crate) stats: Arc<LiveStats>,
    requests: smol::channel::Sender<Request>,
    /// Set at the node's stop: client threads end.
    pub(crate) stopping: AtomicBool,
}

impl Hub {
    pub(crate) fn new(
        catalogue: Catalogue,
        server_info: String,
        requests: smol::channel::Sender<Request>,
    ) -> Self {
        Self {
            catalogue,
            server_info,
            clients: Mutex::new(Vec::new()),
            subscribers: Default::default(),
            stats: Arc::new(LiveStats::default()),
            requests,
            stopping: AtomicBool::new(false),
        }
    }

    pub(crate) fn add(&self, queue: SyncSender<Frame>) -> Arc<Client> {
        let c = Arc::new(Client {
            queue,
            subscriptions: Mutex::new(Vec::new()),
            dropped: AtomicU64::new(0),
        });
        if let Ok(mut all) = self.clients.lock() {
            all.push(c.clone());
        }
        self.stats.clients.fetch_add(1, Ordering::Relaxed);
        self.stats.connections.fetch_add(1, Ordering::Relaxed);
        c
    }

    pub(crate) fn remove(&self, c: &Arc<Client>) {
        if let Ok(mut subs) = c.subscriptions.lock() {
            for (_, o) in subs.drain(..) {
                self.subscribers[o.index()].fetch_sub(1, Ordering::Relaxed);
            }
        }
        if let Ok(mut all) = self.clients.lock() {
            all.retain(|x| !Arc::ptr_eq(x, c));
        }
        self.stats.clients.fetch_sub(1, Ordering::Relaxed);
    }

    /// Subscribes `c` to `outlet` under its id `sub`; false when the id is taken.
    pub(crate) fn subscribe(&self, c: &Client, sub: u32, outlet: Outlet) -> bool {
        let Ok(mut subs) = c.subscriptions.lock() else {
            return false;
        };
        if subs.iter().any(|(s, _)| *s == sub) {
            return false;
        }
        subs.push((sub, outlet));
        self.subscribers[outlet.index()].fetch_add(1, Ordering::Relaxed);
        true
    }

    pub(crate) fn unsubscribe(&self, c: &Client, sub: u32) {
        if let Ok(mut subs) = c.subscriptions.lock() {
            subs.retain(|(s, o)| {
                let keep = *s != sub;
                if !keep {
                    self.subscribers[o.index()].fetch_sub(1, Ordering::Relaxed);
                }
                keep
            });
        }
    }

    /// Hands a request to the executor; a full queue drops it (counted) and says so.
    pub(crate) fn request(&self, r: Request) -> bool {
        let ok = self.requests.try_send(r).is_ok();
        if !ok {
            self.stats.requests_dropped.fetch_add(1, Ordering::Relaxed);
        }
        ok
    }
}

/// The publisher thread's handle on the live view: cheap to clone, never blocks.
#[derive(Clone)]
pub(crate) struct LiveTap(pub(crate) Arc<Hub>);

impl LiveTap {
    /// `msg` of `endpoint`, stamped `stamp_ns`, to every client subscribed to its channel:
    /// encoded once (the recordings' CDR bytes), queued to each. Nothing for an endpoint the
    /// live view does not serve as a channel.
    pub(crate) fn put<T: serde::Serialize>(&self, endpoint: Endpoint, stamp_ns: i64, msg: &T) {
        let Some(outlet) = Outlet::of(endpoint) else {
            return;
        };
        let hub = &self.0;
        if hub.subscribers[outlet.index()].load(Ordering::Relaxed) == 0 {
            return;
        }
        let Ok(bytes) = encode_cdr(msg) else {
            return;
        };
        let payload: Arc<[u8]> = bytes.into();
        let Ok(clients) = hub.clients.lock() else {
            return;
        };
        for c in clients.iter() {
            let subs: Vec<u32> = match c.subscriptions.lock() {
                Ok(s) => s
                    .iter()
                    .filter(|(_, o)| *o == outlet)
                    .map(|(s, _)| *s)
                    .collect(),
                Err(_) => continue,
            };
            for subscription in subs {
                c.send(
                    Frame::Data {
                        subscription,
                        receive_ns: stamp_ns.max(0) as u64,
                        payload: payload.clone(),
                    },
                    &hub.stats,
                );
            }
        }
    }

    /// The simulated clock's time to every client (the `time` capability).
    pub(crate) fn time(&self, ns: i64) {
        let hub = &self.0;
        let Ok(clients) = hub.clients.lock() else {
            return;
        };
        for c in clients.iter() {
            c.send(Frame::Binary(protocol::time(ns.max(0) as u64)), &hub.stats);
        }
    }
}
