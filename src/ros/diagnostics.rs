//! The node's `/diagnostics`: the tick loop's, the inputs' and the recorder's figures, once a
//! second, published and recorded.

use super::clock::{ClockMode, NodeClock};
use super::endpoints::Endpoint;
use super::live::{LiveStatus, LiveTap};
use super::logging::Reporter;
use super::node_state::NodeState;
use super::params::NodeParams;
use super::record::{self, RecordTx};
use super::severity::Severity;
use super::tick::TickStats;
use muscle_actuator_core::sim::input::Rejection;
use muscle_actuator_recording::msgs::Time;
use muscle_actuator_recording::msgs::{DiagnosticArray, DiagnosticStatus, Header, KeyValue};
use muscle_actuator_recording::recording::{Recorder, RecorderState};
use ros2_client::Publisher;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Duration;

/// Counters of the inputs (written on the DDS side, read by diagnostics).
#[derive(Default)]
pub struct InputStats {
    pub activation_received: AtomicU64,
    pub activation_rejected: AtomicU64,
    pub load_received: AtomicU64,
    pub load_rejected: AtomicU64,
    /// Commands with at least one excitation clamped to [0, 1].
    pub clamped_commands: AtomicU64,
    /// Excitation values clamped.
    pub clamped_values: AtomicU64,
    pub rejected_unknown_name: AtomicU64,
    pub rejected_length_mismatch: AtomicU64,
    pub rejected_non_finite: AtomicU64,
    pub rejected_duplicate_name: AtomicU64,
    pub rejected_empty: AtomicU64,
    pub malformed: AtomicU64,
    /// Joint states (driven joints) refused.
    pub joint_states_rejected: AtomicU64,
    /// `/clock` messages received (following an external clock), and refused.
    pub clock_received: AtomicU64,
    pub clock_rejected: AtomicU64,
    pub last_problem: Mutex<String>,
}

impl InputStats {
    pub(crate) fn count_rejection(&self, r: &Rejection) {
        let c = match r {
            Rejection::UnknownName { .. } => &self.rejected_unknown_name,
            Rejection::LengthMismatch { .. } => &self.rejected_length_mismatch,
            Rejection::NonFinite { .. } => &self.rejected_non_finite,
            Rejection::DuplicateName(_) => &self.rejected_duplicate_name,
            Rejection::Empty => &self.rejected_empty,
        };
        c.fetch_add(1, Ordering::Relaxed);
    }
    pub(crate) fn total_rejected(&self) -> u64 {
        self.activation_rejected.load(Ordering::Relaxed)
            + self.load_rejected.load(Ordering::Relaxed)
            + self.joint_states_rejected.load(Ordering::Relaxed)
    }
}

pub(crate) fn kv(key: &str, value: impl ToString) -> KeyValue {
    KeyValue {
        key: key.into(),
        value: value.to_string(),
    }
}

/// Figures of the last diagnostics period, to report rates of change.
#[derive(Default)]
pub(crate) struct DiagPrev {
    overruns: u64,
    rejected: u64,
    step_failures: u64,
    ticks: u64,
    clock_jumps: u64,
}

/// The tick loop's figures of this period, beside the last period's.
struct Period {
    overruns: u64,
    step_failures: u64,
    clock_jumps: u64,
    new_overruns: u64,
    new_failures: u64,
    /// No tick since the last period.
    idle: bool,
    /// `/clock` jumped since the last period.
    jumped: bool,
    rate_hz: f64,
    driven_joints: u64,
    /// Ticks since a driven joint's motion last arrived (`u64::MAX`: none yet).
    motion_age: u64,
}

impl DiagPrev {
    /// This period's figures against the last's (kept for the next), and the inputs rejected
    /// since (`rejected` in all).
    fn advance(&mut self, stats: &TickStats, rejected: u64) -> (Period, u64) {
        let ld = |a: &AtomicU64| a.load(Ordering::Relaxed);
        let overruns = ld(&stats.overruns);
        let step_failures = ld(&stats.step_failures);
        let ticks = ld(&stats.ticks);
        let clock_jumps = ld(&stats.clock_jumps);
        let period = Period {
            overruns,
            step_failures,
            clock_jumps,
            new_overruns: overruns - self.overruns.min(overruns),
            new_failures: step_failures - self.step_failures.min(step_failures),
            idle: ticks == self.ticks,
            jumped: clock_jumps > self.clock_jumps,
            rate_hz: stats.rate_hz(),
            driven_joints: ld(&stats.driven_joints),
            motion_age: ld(&stats.joint_motion_age_ticks),
        };
        let new_rejected = rejected - self.rejected.min(rejected);
        *self = DiagPrev {
            overruns,
            rejected,
            step_failures,
            ticks,
            clock_jumps,
        };
        (period, new_rejected)
    }
}

/// One `/diagnostics` message: the tick loop's status, the inputs' and the recorder's.
fn diagnostics(
    src: &DiagSources<'_>,
    prev: &mut DiagPrev,
    recorder_status: DiagnosticStatus,
) -> DiagnosticArray {
    let (fqn, stats, inputs) = (src.fqn, src.ticks, src.inputs);
    let params = &src.shared.params();
    let publish_errors = src.publish_errors.load(Ordering::Relaxed);
    let clock = src.clock.mode();
    let rejected = inputs.total_rejected();
    let (period, new_rejected) = prev.advance(stats, rejected);
    let (level, message) = tick_level(stats, params, clock, &period);
    let tick_status = DiagnosticStatus {
        level,
        name: format!("{fqn}: tick loop"),
        message,
        hardware_id: fqn.into(),
        values: tick_values(stats, params, clock, &period, publish_errors),
    };
    DiagnosticArray {
        header: Header {
            stamp: Time::from_nanos(muscle_actuator_core::time::now_ns()),
            frame_id: String::new(),
        },
        status: vec![
            tick_status,
            input_status(fqn, inputs, rejected, new_rejected),
            recorder_status,
            live_status(fqn, &src.live),
            services_status(fqn, src.participant.held_reply_counts()),
        ],
    }
}

/// The tick loop's level and message, the first that holds of: `/clock` jumped; a driven loop
/// (lockstep, following `/clock`) waiting, which is no stall; a stall (no tick in the period);
/// driven joints without a recent joint state; a failed step; overruns; all well.
fn tick_level(
    stats: &TickStats,
    params: &NodeParams,
    clock: ClockMode,
    p: &Period,
) -> (u8, String) {
    let ld = |a: &AtomicU64| a.load(Ordering::Relaxed);
    let stalled = p.idle && !clock.is_driven();
    let motion_age = p.motion_age;
    let stale = p.driven_joints > 0 && motion_age > params.joint_state_timeout_ticks.max(1) as u64;
    let tick = || ld(&stats.current_tick);
    if p.jumped {
        (
            DiagnosticStatus::WARN,
            format!(
                "/clock jumped ({} so far): the actuator was reset and tick 0 re-anchored at the \
                 new time (at tick {})",
                p.clock_jumps,
                tick()
            ),
        )
    } else if p.idle && !stalled {
        let message = if clock == ClockMode::Follow {
            format!(
                "following /clock: waiting for it to move (at tick {})",
                tick()
            )
        } else {
            format!("lockstep: waiting for ~/step (at tick {})", tick())
        };
        (DiagnosticStatus::OK, message)
    } else if stalled {
        (
            DiagnosticStatus::ERROR,
            format!(
                "tick loop stalled: no tick in the last period (at tick {})",
                tick()
            ),
        )
    } else if stale {
        let message = if motion_age == u64::MAX {
            format!(
                "driven joints: no JointState on ~/joint_states_in yet (at tick {})",
                tick()
            )
        } else {
            format!(
                "driven joints: no JointState for {motion_age} ticks (their motion is extrapolated)"
            )
        };
        (DiagnosticStatus::WARN, message)
    } else if p.new_failures > 0 {
        (
            DiagnosticStatus::ERROR,
            format!(
                "a step failed: actuator reset ({} in the last period)",
                p.new_failures
            ),
        )
    } else if p.new_overruns > 0 {
        (
            DiagnosticStatus::WARN,
            format!(
                "{} ticks later than one period in the last period",
                p.new_overruns
            ),
        )
    } else {
        (DiagnosticStatus::OK, format!("holding {} Hz", p.rate_hz))
    }
}

/// The tick loop's figures, as `/diagnostics` key-values.
fn tick_values(
    stats: &TickStats,
    params: &NodeParams,
    clock: ClockMode,
    p: &Period,
    publish_errors: u64,
) -> Vec<KeyValue> {
    let ld = |a: &AtomicU64| a.load(Ordering::Relaxed);
    let (p50, p99, max) = stats.window();
    vec![
        kv("model", params.model.name()),
        kv("rate_hz", p.rate_hz),
        kv("clock", clock.name()),
        kv("driven_joints", p.driven_joints),
        kv(
            "joint_state_age_ticks",
            if p.motion_age == u64::MAX {
                "none yet".to_string()
            } else {
                p.motion_age.to_string()
            },
        ),
        kv(
            "realtime_priority",
            stats.realtime.load(Ordering::Relaxed).to_string(),
        ),
        kv("tick", ld(&stats.current_tick)),
        kv("ticks_total", ld(&stats.ticks)),
        kv("overruns", p.overruns),
        kv("skipped_ticks", ld(&stats.skipped)),
        kv("lateness_p50_us", format!("{:.1}", p50 / 1e3)),
        kv("lateness_p99_us", format!("{:.1}", p99 / 1e3)),
        kv("lateness_max_us", format!("{:.1}", max / 1e3)),
        kv(
            "lateness_max_total_us",
            format!("{:.1}", ld(&stats.max_lateness_ns) as f64 / 1e3),
        ),
        kv(
            "step_mean_us",
            format!(
                "{:.2}",
                f64::from_bits(stats.window_step_ns.load(Ordering::Relaxed)) / 1e3
            ),
        ),
        kv("states_dropped", ld(&stats.samples_dropped)),
        kv("applied_inputs_dropped", ld(&stats.applied_dropped)),
        kv("commands_dropped", ld(&stats.commands_dropped)),
        kv("commands_deferred", ld(&stats.commands_deferred)),
        kv("events_dropped", ld(&stats.events_dropped)),
        kv("publish_errors", publish_errors),
        kv("step_failures", p.step_failures),
        kv("resets", ld(&stats.resets)),
        kv("clock_jumps", p.clock_jumps),
        kv("scheduled_inputs", ld(&stats.scheduled_pending)),
        kv("scheduled_dropped", ld(&stats.scheduled_dropped)),
    ]
}

/// The inputs' status: a warning while commands are rejected (`new_rejected` in the period).
fn input_status(
    fqn: &str,
    inputs: &InputStats,
    rejected: u64,
    new_rejected: u64,
) -> DiagnosticStatus {
    let ld = |a: &AtomicU64| a.load(Ordering::Relaxed);
    let last = inputs
        .last_problem
        .lock()
        .map(|s| s.clone())
        .unwrap_or_default();
    DiagnosticStatus {
        level: if new_rejected > 0 {
            DiagnosticStatus::WARN
        } else {
            DiagnosticStatus::OK
        },
        name: format!("{fqn}: inputs"),
        message: if new_rejected > 0 {
            format!("{new_rejected} commands rejected in the last period")
        } else {
            "ok".into()
        },
        hardware_id: fqn.into(),
        values: vec![
            kv("activation_received", ld(&inputs.activation_received)),
            kv("activation_rejected", ld(&inputs.activation_rejected)),
            kv("load_received", ld(&inputs.load_received)),
            kv("load_rejected", ld(&inputs.load_rejected)),
            kv("rejected_total", rejected),
            kv("rejected_unknown_name", ld(&inputs.rejected_unknown_name)),
            kv(
                "rejected_length_mismatch",
                ld(&inputs.rejected_length_mismatch),
            ),
            kv("rejected_non_finite", ld(&inputs.rejected_non_finite)),
            kv(
                "rejected_duplicate_name",
                ld(&inputs.rejected_duplicate_name),
            ),
            kv("rejected_empty", ld(&inputs.rejected_empty)),
            kv("clamped_commands", ld(&inputs.clamped_commands)),
            kv("clamped_values", ld(&inputs.clamped_values)),
            kv("malformed", ld(&inputs.malformed)),
            kv("joint_states_rejected", ld(&inputs.joint_states_rejected)),
            kv("last_problem", last),
        ],
    }
}

/// What the `/diagnostics` task reads.
pub(crate) struct DiagSources<'a> {
    pub(crate) fqn: &'a str,
    pub(crate) ticks: &'a TickStats,
    pub(crate) inputs: &'a InputStats,
    pub(crate) shared: &'a NodeState,
    pub(crate) publish_errors: &'a AtomicU64,
    /// The recording as configured at start-up, and how its start went.
    pub(crate) startup_params: &'a NodeParams,
    pub(crate) recorder: Option<&'a Recorder>,
    pub(crate) recorder_error: &'a str,
    /// Stamps, and what a tick-less second means.
    pub(crate) clock: &'a NodeClock,
    pub(crate) live: LiveStatus<'a>,
    /// The DDS participant: its counts of service replies held for a client not yet matched.
    pub(crate) participant: &'a rustdds::DomainParticipant,
}

/// The services' status (`~/reset`, `~/step`, the parameter services): replies held because the
/// client's reply reader was not matched yet when the answer was written, sent when it matched,
/// or dropped after the hold time (vendor/rustdds/PATCHED.md). A warning once any was dropped.
fn services_status(fqn: &str, c: rustdds::HeldReplyCounts) -> DiagnosticStatus {
    DiagnosticStatus {
        level: if c.dropped > 0 {
            DiagnosticStatus::WARN
        } else {
            DiagnosticStatus::OK
        },
        name: format!("{fqn}: services"),
        message: if c.dropped > 0 {
            format!("{} replies dropped: their client never matched", c.dropped)
        } else {
            "ok".into()
        },
        hardware_id: fqn.into(),
        values: vec![
            kv("replies_held", c.held),
            kv("replies_held_sent", c.delivered),
            kv("replies_dropped", c.dropped),
        ],
    }
}

/// The live view's `/diagnostics` status: clients, what was dropped for slow clients, who was
/// disconnected for what they sent.
fn live_status(fqn: &str, s: &LiveStatus<'_>) -> muscle_actuator_recording::msgs::DiagnosticStatus {
    let (level, message, values) = match s {
        LiveStatus::Off => (
            DiagnosticStatus::OK,
            "off (foxglove_port 0)".to_string(),
            vec![],
        ),
        LiveStatus::Failed(why) => (
            DiagnosticStatus::WARN,
            format!("not serving: {why}"),
            vec![],
        ),
        LiveStatus::Serving(st, addr) => {
            let ld = |a: &AtomicU64| a.load(Ordering::Relaxed);
            let dropped = ld(&st.dropped);
            (
                if dropped > 0 {
                    DiagnosticStatus::WARN
                } else {
                    DiagnosticStatus::OK
                },
                format!("serving ws://{addr}"),
                vec![
                    kv("clients", st.clients.load(Ordering::Relaxed)),
                    kv("connections", ld(&st.connections)),
                    kv("dropped", dropped),
                    kv("disconnected_for_bad_frames", ld(&st.kicked)),
                    kv("refused", ld(&st.refused)),
                    kv("requests_dropped", ld(&st.requests_dropped)),
                ],
            )
        }
    };
    DiagnosticStatus {
        level,
        name: format!("{fqn}: live view (foxglove)"),
        message,
        hardware_id: fqn.into(),
        values,
    }
}

/// How often `/diagnostics` is published.
const DIAGNOSTICS_PERIOD: Duration = Duration::from_secs(1);

/// Publishes (and records) `/diagnostics` once a second; a failed recording and a stalled tick
/// loop are also logged.
pub(crate) async fn publish_task(
    src: DiagSources<'_>,
    publisher: &Publisher<DiagnosticArray>,
    log: &Reporter,
    rec: Option<RecordTx>,
    live: Option<LiveTap>,
) {
    let mut prev = DiagPrev::default();
    let mut failure_reported = false;
    loop {
        smol::Timer::after(DIAGNOSTICS_PERIOD).await;
        let rec_status = match src.recorder {
            Some(r) => {
                if let RecorderState::Failed(e) = r.stats().state() {
                    if !failure_reported {
                        failure_reported = true;
                        log.logger
                            .error(&format!("{e}; the simulation goes on without it"));
                    }
                }
                record::Status::Running(r)
            }
            None if !src.recorder_error.is_empty() => {
                record::Status::StartFailed(src.recorder_error)
            }
            None => record::Status::Disabled,
        };
        let mut msg = diagnostics(
            &src,
            &mut prev,
            record::diagnostic(src.fqn, src.startup_params, &rec_status),
        );
        msg.header.stamp = Time::from_nanos(src.clock.now_ns());
        if let Some(st) = msg.status.first() {
            if st.level == DiagnosticStatus::ERROR && st.message.starts_with("tick loop stalled") {
                log.report("stalled", Severity::Error, st.message.clone());
            }
        }
        if let Some(r) = &rec {
            r.put(
                (Endpoint::Diagnostics, 0),
                msg.header.stamp.to_nanos(),
                &msg,
            );
        }
        if let Some(l) = &live {
            l.put(Endpoint::Diagnostics, msg.header.stamp.to_nanos(), &msg);
        }
        if let Err(e) = publisher.async_publish(msg).await {
            log.logger
                .debug(&format!("diagnostics: publish failed: {e:?}"));
        }
    }
}
