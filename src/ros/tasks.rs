//! The node's tasks on the DDS executor, one function each: the input topics (the three
//! activation topics, the load, the driven joints' motion: validated, recorded as received,
//! forwarded to the tick loop; `/clock` when following it), the reset service, the `~/step`
//! service and topic, and the tick loop's events turned into log lines. None of them waits on the
//! tick loop.

use super::clock::ClockMode;
use super::diagnostics::InputStats;
use super::logging::{LateTicks, Reporter, LATE_WARN_PERIODS};
use super::node_state::NodeState;
use super::record::RecordTx;
use super::sample_messages::sample_to_msgs;
use super::severity::Severity;
use super::tick::{Command, Event, Sample, TickStats};
use futures::{FutureExt, StreamExt};
use muscle_actuator_core::sim::input::{self, Rejection};
use muscle_actuator_core::time;
use muscle_actuator_recording::msgs::muscle_actuator_msgs::{
    ActivationCommand, ActuatorState, ExternalLoad,
};
use muscle_actuator_recording::msgs::{
    Clock, Float64, Float64MultiArray, Int64, JointState, StepRequest, StepResponse,
    TriggerRequest, TriggerResponse,
};
use muscle_actuator_recording::runs::Channel;
use ros2_client::{RmwRequestId, Server, Subscription};
use serde::de::DeserializeOwned;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::Receiver;
use std::time::Duration;

/// What the input tasks share: the commands' destination and names, the counters, the log and
/// the recording.
pub(crate) struct InputContext<'a> {
    pub(crate) shared: &'a NodeState,
    pub(crate) stats: &'a InputStats,
    pub(crate) log: &'a Reporter,
    pub(crate) rec: Option<RecordTx>,
}

impl InputContext<'_> {
    /// An input problem: kept as the last one for `/diagnostics`, and logged (rate-limited).
    pub(crate) fn problem(&self, key: &str, msg: String) {
        if let Ok(mut l) = self.stats.last_problem.lock() {
            *l = msg.clone();
        }
        self.log.report(key, Severity::Warn, msg);
    }

    fn rejected(&self, counter: &AtomicU64, rej: &Rejection, msg: String) {
        counter.fetch_add(1, Ordering::Relaxed);
        self.stats.count_rejection(rej);
        self.problem(rej.kind(), msg);
    }

    fn record<T: serde::Serialize>(&self, ch: Channel, publish_ns: i64, msg: &T) {
        if let Some(r) = &self.rec {
            r.put(ch, publish_ns, msg);
        }
    }

    /// Excitations by name, from any of the three activation topics: validated the same way
    /// and applied at the next tick boundary (with a header `stamp_ns`, see [`stamped`]).
    fn excite(&self, names: &[String], values: &[f64], known: &[String], stamp_ns: Option<i64>) {
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

    /// Every message of `sub`, counted in `received`; an unreadable one is counted and logged.
    async fn each<M: 'static + DeserializeOwned>(
        &self,
        sub: &Subscription<M>,
        what: &str,
        received: &AtomicU64,
        mut handle: impl FnMut(M),
    ) {
        let mut stream = std::pin::pin!(sub.async_stream());
        while let Some(r) = stream.next().await {
            received.fetch_add(1, Ordering::Relaxed);
            match r {
                Ok((msg, _info)) => handle(msg),
                Err(e) => self.unreadable(what, format!("{e:?}")),
            }
        }
    }

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
fn stamped(stamp_ns: Option<i64>, input: Command) -> Command {
    match stamp_ns {
        Some(ns) if ns != 0 => Command::Stamped(ns, Box::new(input)),
        _ => input,
    }
}

/// `~/activation`: excitations by muscle name.
pub(crate) async fn activation(sub: &Subscription<ActivationCommand>, cx: &InputContext<'_>) {
    cx.each(sub, "activation", &cx.stats.activation_received, |msg| {
        on_activation(cx, msg)
    })
    .await
}

/// One `~/activation` message (from DDS or the live view): recorded, validated, applied.
pub(crate) fn on_activation(cx: &InputContext<'_>, msg: ActivationCommand) {
    cx.record(Channel::Activation, msg.header.stamp.to_nanos(), &msg);
    let stamp = msg.header.stamp.to_nanos();
    cx.excite(
        &msg.muscle,
        &msg.excitation,
        &cx.shared.muscles(),
        Some(stamp),
    );
}

/// `~/activation_array`: every muscle's excitation, in the configuration's order.
pub(crate) async fn activation_array(sub: &Subscription<Float64MultiArray>, cx: &InputContext<'_>) {
    cx.each(
        sub,
        "activation_array",
        &cx.stats.activation_received,
        |msg| on_activation_array(cx, msg),
    )
    .await
}

/// One `~/activation_array` message (from DDS or the live view).
pub(crate) fn on_activation_array(cx: &InputContext<'_>, msg: Float64MultiArray) {
    cx.record(Channel::ActivationArray, time::now_ns(), &msg);
    let known = cx.shared.muscles();
    if msg.data.len() != known.len() {
        let rej = Rejection::LengthMismatch {
            names: known.len(),
            values: msg.data.len(),
        };
        let m = format!(
            "activation_array rejected: {} values for {} muscles (in order: {})",
            msg.data.len(),
            known.len(),
            muscle_actuator_core::text::excerpt(&known.join(", "))
        );
        cx.rejected(&cx.stats.activation_rejected, &rej, m);
        return;
    }
    // All of them, in order: the names are the configuration's own.
    cx.excite(&known, &msg.data, &known, None);
}

/// `~/<muscle>/cmd_activation`: one muscle's excitation, on one topic per muscle.
pub(crate) async fn muscle_commands(
    subs: &[(String, Subscription<Float64>)],
    cx: &InputContext<'_>,
) {
    let streams = subs
        .iter()
        .enumerate()
        .map(|(k, (name, sub))| sub.async_stream().map(move |r| (k, name, r)));
    let mut all = futures::stream::select_all(streams.map(Box::pin));
    while let Some((k, name, r)) = all.next().await {
        cx.stats.activation_received.fetch_add(1, Ordering::Relaxed);
        match r {
            Ok((msg, _info)) => on_muscle_command(cx, k, name, msg),
            Err(e) => cx.unreadable("cmd_activation", format!("{e:?}")),
        }
    }
    // No muscle topic at all (no muscle name is a valid topic name): nothing to do, but the
    // node goes on (it stops when any of its tasks ends).
    futures::future::pending::<()>().await;
}

/// One `~/<muscle>/cmd_activation` message, the k-th muscle topic's (from DDS or the live
/// view).
pub(crate) fn on_muscle_command(cx: &InputContext<'_>, k: usize, muscle: &str, msg: Float64) {
    cx.record(Channel::MuscleCommand(k), time::now_ns(), &msg);
    cx.excite(
        &[muscle.to_string()],
        &[msg.data],
        &cx.shared.muscles(),
        None,
    );
}

/// `~/external_load`: torques by joint name.
pub(crate) async fn load(sub: &Subscription<ExternalLoad>, cx: &InputContext<'_>) {
    cx.each(sub, "external load", &cx.stats.load_received, |msg| {
        on_load(cx, msg)
    })
    .await
}

/// One `~/external_load` message (from DDS or the live view).
pub(crate) fn on_load(cx: &InputContext<'_>, msg: ExternalLoad) {
    cx.record(Channel::Load, msg.header.stamp.to_nanos(), &msg);
    match input::validate_load(&msg.joint, &msg.torque, &cx.shared.joints()) {
        Ok(acc) => cx.shared.send(stamped(
            Some(msg.header.stamp.to_nanos()),
            Command::Load(acc.values),
        )),
        Err(rej) => cx.rejected(
            &cx.stats.load_rejected,
            &rej,
            format!("external load rejected: {rej}"),
        ),
    }
}

/// `~/joint_states_in` (`sensor_msgs/JointState`): the driven joints' angle and velocity, by
/// name, from the simulator that owns them; they take effect at the next tick and are
/// extrapolated linearly until the next message.
pub(crate) async fn joint_states_in(sub: &Subscription<JointState>, cx: &InputContext<'_>) {
    let received = AtomicU64::new(0);
    cx.each(sub, "joint state", &received, |msg| {
        cx.record(Channel::JointStatesIn, msg.header.stamp.to_nanos(), &msg);
        let driven = cx.shared.driven();
        match input::validate_joint_motion(&msg.name, &msg.position, &msg.velocity, &driven) {
            Ok(motion) if motion.is_empty() => cx.problem(
                "joint_state_unmatched",
                format!(
                    "joint state ignored: it names none of the driven joints ({})",
                    muscle_actuator_core::text::excerpt(
                        &driven
                            .iter()
                            .map(|(_, n)| n.as_str())
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                ),
            ),
            Ok(motion) => cx.shared.send(Command::JointMotion(motion)),
            Err(rej) => cx.rejected(
                &cx.stats.joint_states_rejected,
                &rej,
                format!("joint state rejected: {rej}"),
            ),
        }
    })
    .await
}

/// `/clock` to follow (`use_sim_time` with `clock` wall): each time goes to the tick loop, which
/// steps the whole ticks it covers (after the inputs received before it). A time before zero is
/// refused.
pub(crate) async fn clock_in(sub: &Subscription<Clock>, cx: &InputContext<'_>) {
    cx.each(sub, "clock", &cx.stats.clock_received, |msg| {
        let ns = msg.clock.to_nanos();
        if ns < 0 {
            cx.stats.clock_rejected.fetch_add(1, Ordering::Relaxed);
            cx.problem(
                "clock_negative",
                format!("/clock message refused: its time ({ns} ns) is before zero"),
            );
        } else {
            cx.shared.send(Command::ClockTime(ns));
        }
    })
    .await
}

/// Longest the reset service waits for the tick loop's answer.
const RESET_ANSWER_TIMEOUT: Duration = Duration::from_secs(2);

/// `~/reset` (`std_srvs/Trigger`): back to the initial state, answered with the ticks run.
pub(crate) async fn reset(
    server: &Server<TriggerRequest, TriggerResponse>,
    shared: &NodeState,
    log: &Reporter,
) {
    let mut stream = server.receive_request_stream();
    while let Some(r) = stream.next().await {
        let Ok((id, _req)) = r else {
            continue;
        };
        let resp = reset_answer(shared).await;
        if let Err(e) = server.async_send_response(id, resp).await {
            log.logger
                .warn(&format!("reset: cannot send the response: {e:?}"));
        }
    }
}

/// Resets the actuator and answers as `~/reset` does (from DDS or the live view).
pub(crate) async fn reset_answer(shared: &NodeState) -> TriggerResponse {
    let (tx, rx) = futures::channel::oneshot::channel();
    shared.send(Command::Reset(Some(tx)));
    let timeout = smol::Timer::after(RESET_ANSWER_TIMEOUT);
    futures::select! {
        r = rx.fuse() => match r {
            Ok(before) => TriggerResponse {
                success: true,
                message: format!("reset to the initial state after {before} ticks"),
            },
            Err(_) => TriggerResponse {
                success: false,
                message: "the tick loop is not running".into(),
            },
        },
        _ = FutureExt::fuse(timeout) => TriggerResponse {
            success: false,
            message: format!(
                "the tick loop did not answer within {} s",
                RESET_ANSWER_TIMEOUT.as_secs()
            ),
        },
    }
}

/// How often the tick loop's events are read.
const EVENT_POLL: Duration = Duration::from_millis(50);

/// The tick loop's events as log lines (the loop itself never logs); late ticks summarised.
pub(crate) async fn events(
    rx: &Receiver<Event>,
    stats: &TickStats,
    log: &Reporter,
    rec: Option<&RecordTx>,
) {
    let ticks = || stats.ticks.load(std::sync::atomic::Ordering::Relaxed);
    let mut late = LateTicks::new(ticks());
    loop {
        smol::Timer::after(EVENT_POLL).await;
        if let Some(summary) = late.summary_due(ticks()) {
            log.logger.info(&summary);
        }
        while let Ok(e) = rx.try_recv() {
            match e {
                Event::StepFailed { tick, reason } => log.report(
                    "step_failed",
                    Severity::Error,
                    format!(
                        "tick {tick} failed ({reason}): actuator reset to its initial state, \
                         inputs cleared until the next command"
                    ),
                ),
                Event::Overrun { tick, lateness_us } => {
                    let period_us = 1e6 / stats.rate_hz();
                    if late.add(lateness_us, period_us) {
                        log.report(
                            "overrun",
                            Severity::Warn,
                            format!(
                                "tick {tick} started {lateness_us:.0} us late (more than \
                                 {LATE_WARN_PERIODS} periods)"
                            ),
                        );
                    }
                }
                Event::Resync { skipped } => log.logger.warn(&format!(
                    "the tick loop stalled: {skipped} ticks skipped, schedule restarted"
                )),
                Event::Replaced { model, rate_hz } => log.logger.info(&format!(
                    "actuator rebuilt: model {model}, {rate_hz} Hz (from the initial state)"
                )),
                Event::Reset { at_tick } => log
                    .logger
                    .info(&format!("reset to the initial state after {at_tick} ticks")),
                Event::ClockAnchored { origin_ns } => {
                    if let Some(r) = rec {
                        r.anchored(origin_ns);
                    }
                    log.logger.info(&format!(
                        "following /clock: tick 0 at {:.6} s",
                        origin_ns as f64 * 1e-9
                    ));
                }
                Event::ClockJumped {
                    from_ns,
                    to_ns,
                    at_tick,
                } => log.logger.warn(&format!(
                    "/clock jumped {} from {:.6} s to {:.6} s: reset to the initial state after \
                     {at_tick} ticks, tick 0 now at {:.6} s",
                    if to_ns < from_ns { "back" } else { "forward" },
                    from_ns as f64 * 1e-9,
                    to_ns as f64 * 1e-9,
                    to_ns as f64 * 1e-9
                )),
            }
        }
    }
}

/// Most ticks one step may ask for (about 2.8 h of simulated time at 1 kHz); more is refused.
pub(crate) const MAX_STEP_TICKS: i64 = 10_000_000;

/// Why a step of `ticks` cannot be done in `mode`, if it cannot.
pub(crate) fn step_refusal(mode: ClockMode, ticks: i64) -> Option<String> {
    if mode != ClockMode::Lockstep {
        return Some(format!(
            "~/step needs clock:=lockstep; this node runs clock:={}",
            mode.name()
        ));
    }
    if !(1..=MAX_STEP_TICKS).contains(&ticks) {
        return Some(format!(
            "ticks = {ticks} is invalid: must be from 1 to {MAX_STEP_TICKS}"
        ));
    }
    None
}

pub(crate) fn step_failed(message: String) -> StepResponse {
    StepResponse {
        success: false,
        message,
        tick: 0,
        state: ActuatorState::default(),
    }
}

/// `~/step` (`muscle_actuator_msgs/Step`): advances a lockstep node and answers with the state
/// after the last tick. One step at a time: a request while one is running is refused at once.
pub(crate) async fn step(
    server: &Server<StepRequest, StepResponse>,
    shared: &NodeState,
    mode: ClockMode,
    log: &Reporter,
) {
    let mut requests = server.receive_request_stream().fuse();
    // The step running: its request id, its ticks, and the loop's answer to come.
    let mut running: Option<(
        RmwRequestId,
        i64,
        futures::channel::oneshot::Receiver<Sample>,
    )> = None;
    loop {
        let request = match running.take() {
            None => requests.next().await,
            Some((id, ticks, mut done)) => futures::select! {
                r = done => {
                    let resp = match r {
                        Ok(s) => StepResponse {
                            success: true,
                            message: String::new(),
                            tick: s.tick,
                            state: sample_to_msgs(&s).0,
                        },
                        Err(_) => step_failed(
                            "the tick loop stopped before the step was done".into(),
                        ),
                    };
                    if let Err(e) = server.async_send_response(id, resp).await {
                        log.logger.warn(&format!("step: cannot send the response: {e:?}"));
                    }
                    continue;
                },
                r = requests.next() => {
                    running = Some((id, ticks, done));
                    r
                },
            },
        };
        let Some(request) = request else {
            return;
        };
        let Ok((id, req)) = request else {
            continue;
        };
        let refusal = match &running {
            Some((_, ticks, _)) => Some(format!(
                "a step of {ticks} ticks is running; ask again once it has answered"
            )),
            None => step_refusal(mode, req.ticks),
        };
        if let Some(why) = refusal {
            if let Err(e) = server.async_send_response(id, step_failed(why)).await {
                log.logger
                    .warn(&format!("step: cannot send the response: {e:?}"));
            }
            continue;
        }
        let (tx, rx) = futures::channel::oneshot::channel();
        shared.send(Command::Step {
            ticks: req.ticks as u64,
            reply: Some(tx),
        });
        running = Some((id, req.ticks, rx));
    }
}

/// `~/step` as a topic (`std_msgs/Int64`): the same advance, fire and forget; a refused one is
/// logged.
pub(crate) async fn step_topic(sub: &Subscription<Int64>, cx: &InputContext<'_>, mode: ClockMode) {
    let received = AtomicU64::new(0);
    cx.each(sub, "step", &received, |msg| {
        match step_refusal(mode, msg.data) {
            Some(why) => cx
                .log
                .report("step", Severity::Warn, format!("step refused: {why}")),
            None => cx.shared.send(Command::Step {
                ticks: msg.data as u64,
                reply: None,
            }),
        }
    })
    .await
}
