//! The node's input topics. Each one is a row of the endpoints' table
//! ([`super::endpoints::ENDPOINTS`]) that names its [`Input`]: the message type and one handler
//! function, in a file of its own here. Everything else is done once, for every input, from the
//! row: the DDS subscription (`dds.rs`), counting what arrives, the recording of each message as
//! received (on the row's channel), the live view's clients publishing on it (CDR or JSON,
//! [`decode`]) and the logging of unreadable messages.
//!
//! Adding an input: a file here with its [`Input`] constant and handler, and its row in the
//! table, which names it (`src/tests_topic.rs` proves that this is all it takes).

mod activation_array;
mod activation_command;
mod clock_in;
mod context;
mod decode;
mod external_load;
mod joint_states_in;
mod message;
mod muscle_command;
mod step_topic;
#[cfg(feature = "test-topic")]
pub(crate) mod test_excitation;

pub(crate) use activation_array::ACTIVATION_ARRAY;
pub(crate) use activation_command::ACTIVATION;
pub(crate) use clock_in::CLOCK_IN;
pub(crate) use context::InputContext;
pub(crate) use external_load::LOAD;
pub(crate) use joint_states_in::JOINT_STATES_IN;
pub(crate) use message::InputMessage;
pub(crate) use muscle_command::MUSCLE_COMMAND;
pub(crate) use step_topic::STEP_TOPIC;

use super::diagnostics::InputStats;
use super::endpoints::{spec_of, Endpoint};
use futures::future::LocalBoxFuture;
use futures::{FutureExt, StreamExt};
use muscle_actuator_core::time;
use ros2_client::{Node, QosProfile, Subscription};
use std::sync::atomic::{AtomicU64, Ordering};

/// An input topic: its message type `M` and what a message does.
pub(crate) struct Input<M> {
    /// How log lines name the topic's messages ("unreadable {what} message").
    pub(crate) what: &'static str,
    /// The counter of messages received that `/diagnostics` reports, if any.
    pub(crate) received: fn(&InputStats) -> Option<&AtomicU64>,
    /// One message, from DDS or the live view, after it was counted and recorded; `k` is the
    /// instance (the k-th `~/<muscle>/...` topic, 0 for the others).
    pub(crate) handle: fn(&InputContext<'_>, usize, M),
}

/// An [`Input`] whatever its message type, as the table holds it.
pub(crate) trait InputHandler: Sync {
    /// Subscribes to `topic`, the `k`-th instance of `endpoint`; the library's error as text.
    fn subscribe(
        &'static self,
        node: &mut Node,
        topic: &rustdds::Topic,
        qos: QosProfile,
        endpoint: Endpoint,
        k: usize,
    ) -> Result<Box<dyn Subscribed>, String>;

    /// A live-view client's message on the `k`-th instance of `endpoint` (CDR, or JSON when
    /// `json`): taken as a DDS message is, or logged as unreadable.
    fn on_payload(
        &self,
        cx: &InputContext<'_>,
        endpoint: Endpoint,
        k: usize,
        json: bool,
        payload: &[u8],
    );
}

/// A subscription the executor serves.
pub(crate) trait Subscribed {
    /// Every message, for as long as the subscription lasts.
    fn serve<'a>(&'a self, cx: &'a InputContext<'a>) -> LocalBoxFuture<'a, ()>;
}

impl<M: InputMessage> Input<M> {
    /// A readable message: counted, recorded as received (at its header's stamp, or now), then
    /// handled.
    fn take(&self, cx: &InputContext<'_>, endpoint: Endpoint, k: usize, msg: M) {
        self.count(cx);
        if spec_of(endpoint).record {
            let stamp = msg.header_stamp_ns().unwrap_or_else(time::now_ns);
            cx.record((endpoint, k), stamp, &msg);
        }
        (self.handle)(cx, k, msg)
    }

    fn count(&self, cx: &InputContext<'_>) {
        if let Some(c) = (self.received)(cx.stats) {
            c.fetch_add(1, Ordering::Relaxed);
        }
    }
}

impl<M: InputMessage> InputHandler for Input<M> {
    fn subscribe(
        &'static self,
        node: &mut Node,
        topic: &rustdds::Topic,
        qos: QosProfile,
        endpoint: Endpoint,
        k: usize,
    ) -> Result<Box<dyn Subscribed>, String> {
        let sub = node
            .create_subscription::<M>(topic, Some(qos))
            .map_err(|e| format!("{e:?}"))?;
        Ok(Box::new(Subscribing {
            sub,
            input: self,
            endpoint,
            k,
        }))
    }

    fn on_payload(
        &self,
        cx: &InputContext<'_>,
        endpoint: Endpoint,
        k: usize,
        json: bool,
        payload: &[u8],
    ) {
        match decode::decode::<M>(json, payload) {
            Ok(msg) => self.take(cx, endpoint, k, msg),
            Err(e) => cx.unreadable(self.what, e.to_string()),
        }
    }
}

/// One DDS subscription of an input.
struct Subscribing<M: InputMessage> {
    sub: Subscription<M>,
    input: &'static Input<M>,
    endpoint: Endpoint,
    k: usize,
}

impl<M: InputMessage> Subscribed for Subscribing<M> {
    fn serve<'a>(&'a self, cx: &'a InputContext<'a>) -> LocalBoxFuture<'a, ()> {
        async move {
            let mut stream = std::pin::pin!(self.sub.async_stream());
            while let Some(r) = stream.next().await {
                match r {
                    Ok((msg, _info)) => self.input.take(cx, self.endpoint, self.k, msg),
                    Err(e) => {
                        self.input.count(cx);
                        cx.unreadable(self.input.what, format!("{e:?}"));
                    }
                }
            }
        }
        .boxed_local()
    }
}

/// Every subscription, served together until one ends (none does while the node runs); with
/// none at all, nothing, for ever. Polled in the table's order.
pub(crate) async fn serve(subscribed: &[Box<dyn Subscribed>], cx: &InputContext<'_>) {
    if subscribed.is_empty() {
        return futures::future::pending().await;
    }
    futures::future::select_all(subscribed.iter().map(|s| s.serve(cx))).await;
}
