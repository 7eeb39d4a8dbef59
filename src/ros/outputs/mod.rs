//! The node's output topics made by the publisher thread. Each one is a row of the endpoints'
//! table ([`super::endpoints::ENDPOINTS`]) that names its [`Producer`]: the message type and one
//! function from what the tick loop hands over ([`TickOutput`]) to the message, in a file of its
//! own here. Everything else is done once, for every output, from the row: the DDS publisher
//! (`dds.rs`), the recording's channel, the live view's channel and the count of failed
//! publications.
//!
//! Adding an output: a file here with its [`Producer`] constant, and its row in the table.

mod clock_out;
mod joint_efforts;
mod joint_states;
mod state;

pub(crate) use clock_out::CLOCK;
pub(crate) use joint_efforts::JOINT_EFFORTS;
pub(crate) use joint_states::JOINT_STATES;
pub(crate) use state::STATE;

use super::endpoints::{spec_of, Endpoint};
use super::live::LiveTap;
use super::record::RecordTx;
use super::tick::Output as TickOutput;
use ros2_client::{Node, Publisher, QosProfile};
use serde::Serialize;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::Receiver;
use std::sync::Arc;

/// An output topic: its message type `M` and how a tick's output makes one.
pub(crate) struct Producer<M> {
    /// The message of this output, if the tick loop's output makes one.
    pub(crate) make: fn(&TickOutput) -> Option<M>,
}

/// A [`Producer`] whatever its message type, as the table holds it.
pub(crate) trait OutputProducer: Sync {
    /// A publisher on `topic` for `endpoint`; the library's error as text.
    fn publisher(
        &'static self,
        node: &mut Node,
        topic: &rustdds::Topic,
        qos: QosProfile,
        endpoint: Endpoint,
    ) -> Result<Box<dyn Emitter>, String>;
}

/// An output the publisher thread writes.
pub(crate) trait Emitter: Send {
    /// The message of `o`, if any, to the recording, the live view and DDS.
    fn emit(&self, o: &TickOutput, sinks: &Sinks);
}

impl<M: 'static + Serialize + Send> OutputProducer for Producer<M> {
    fn publisher(
        &'static self,
        node: &mut Node,
        topic: &rustdds::Topic,
        qos: QosProfile,
        endpoint: Endpoint,
    ) -> Result<Box<dyn Emitter>, String> {
        let publisher = node
            .create_publisher::<M>(topic, Some(qos))
            .map_err(|e| format!("{e:?}"))?;
        Ok(Box::new(Publishing {
            publisher,
            producer: self,
            endpoint,
        }))
    }
}

/// One DDS publisher of an output.
struct Publishing<M: 'static + Serialize> {
    publisher: Publisher<M>,
    producer: &'static Producer<M>,
    endpoint: Endpoint,
}

impl<M: 'static + Serialize + Send> Emitter for Publishing<M> {
    fn emit(&self, o: &TickOutput, sinks: &Sinks) {
        let Some(msg) = (self.producer.make)(o) else {
            return;
        };
        let stamp_ns = stamp_ns(o);
        if let (Some(r), true) = (&sinks.rec, spec_of(self.endpoint).record) {
            r.put_tick((self.endpoint, 0), stamp_ns, &msg);
        }
        if let Some(l) = &sinks.live {
            l.put(self.endpoint, stamp_ns, &msg);
        }
        if self.publisher.publish(msg).is_err() {
            sinks.errors.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// The stamp of a tick's output: its tick's, or the clock's time.
fn stamp_ns(o: &TickOutput) -> i64 {
    match o {
        TickOutput::State(s) => s.stamp_ns,
        TickOutput::Clock(ns) => *ns,
    }
}

/// Where the outputs go beside DDS.
pub(crate) struct Sinks {
    /// Failed publications.
    pub(crate) errors: Arc<AtomicU64>,
    pub(crate) rec: Option<RecordTx>,
    /// The live view's clients.
    pub(crate) live: Option<LiveTap>,
}

/// The publisher thread: takes states and times from the tick thread and hands each to every
/// output the node has, in the table's order; the live view's time follows the clock.
pub(crate) fn publish_loop(
    rx: Receiver<TickOutput>,
    emitters: Vec<Box<dyn Emitter>>,
    sinks: Sinks,
) {
    while let Ok(o) = rx.recv() {
        for e in &emitters {
            e.emit(&o, &sinks);
        }
        if let (TickOutput::Clock(ns), Some(l)) = (&o, &sinks.live) {
            l.time(*ns);
        }
    }
}
