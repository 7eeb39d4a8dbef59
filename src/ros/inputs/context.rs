//! What the input handlers share: the commands' destination and names, the counters, the log
//! and the recording.

use crate::ros::clock::ClockMode;
use crate::ros::diagnostics::InputStats;
use crate::ros::endpoints::Endpoint;
use crate::ros::logging::Reporter;
use crate::ros::node_state::NodeState;
use crate::ros::record::RecordTx;
use crate::ros::severity::Severity;
use crate::ros::tick::Command;
use muscle_actuator_core::sim::input::{self, Rejection};
use std::sync::atomic::{AtomicU64, Ordering};

/// What the input handlers share.
pub(crate) struct InputContext<'a> {
    pub(crate) shared: &'a NodeState,
    pub(crate) stats: &'a InputStats,
    pub(crate) log: &'a Reporter,
    pub(crate) rec: Option<RecordTx>,
    /// The node's clock mode (`~/step` needs lockstep).
    pub(crate) mode: ClockMode,
    /// The muscle of each `~/<muscle>/...` instance, in order.
    pub(crate) muscle_topics: &'a [String],
}

impl InputContext<'_> {
    /// An input problem: kept as the last one for `/diagnostics`, and logged (rate-limited).
    pub(crate) fn problem(&self, key: &str, msg: String) {
        if let Ok(mut l) = self.stats.last_problem.lock() {
            *l = msg.clone();
        }
        self.log.report(key, Severity::Warn, msg);
    }

    /// A message refused: counted in `counter` and by kind, and reported.
    pub(crate) fn rejected(&self, counter: &AtomicU64, rej: &Rejection, msg: String) {
        counter.fetch_add(1, Ordering::Relaxed);
        self.stats.count_rejection(rej);
        self.problem(rej.kind(), msg);
    }

    /// `msg` into the recording, on the channel of the `k`-th instance of an endpoint.
    pub(crate) fn record<T: serde::Serialize>(&self, at: (Endpoint, usize), ns: i64, msg: &T) {
        if let Some(r) = &self.rec {
            r.put(at, ns, msg);
        }
    }

    /// Excitations by name, from any of the activation topics: validated the same way and
    /// applied at the next tick boundary (with a header `stamp_ns`, see [`stamped`]).
    pub(crate) fn excite(
        &self,
        names: &[String],
        values: &[f64],
        known: &[String],
        stamp_ns: Option<i64>,
    ) {
        match input::validate_activation(names, values, known) {
            Ok(acc) => {
                if !acc.clamped.is_empty() {
                    self.stats.clamped_commands.fetch_add(1, Ordering::Relaxed);
                    self.stats
                        .clamped_values
                        .fetch_add(acc.clamped.len() as u64, Ordering::Relaxed);
                    let what: Vec<String> = acc
                        .clamped
                        .iter()
                        .map(|(n, u)| format!("{n}={u}"))
                        .collect();
                    self.problem(
                        "clamped",
                        format!(
                            "activation: excitation outside [0, 1] clamped: {}",
                            what.join(", ")
                        ),
                    );
                }
                self.shared
                    .send(stamped(stamp_ns, Command::Excitation(acc.values)));
            }
            Err(rej) => self.rejected(
                &self.stats.activation_rejected,
                &rej,
                format!("activation command rejected: {rej}"),
            ),
        }
    }

    /// A message that could not be read: counted and logged.
    pub(crate) fn unreadable(&self, what: &str, e: String) {
        self.stats.malformed.fetch_add(1, Ordering::Relaxed);
        self.log.report(
            "malformed",
            Severity::Warn,
            format!("unreadable {what} message: {e}"),
        );
    }
}

/// An input with its message's header stamp (not zero): the tick loop holds one stamped ahead
/// of a simulated clock until its time ([`Command::Stamped`]). A zero stamp means "now".
pub(crate) fn stamped(stamp_ns: Option<i64>, input: Command) -> Command {
    match stamp_ns {
        Some(ns) if ns != 0 => Command::Stamped(ns, Box::new(input)),
        _ => input,
    }
}
