//! The tick loop's events as log lines, on the DDS executor (the loop itself never logs); late
//! ticks summarised.

use super::logging::{LateTicks, Reporter, LATE_WARN_PERIODS};
use super::record::RecordTx;
use super::severity::Severity;
use super::tick::{Event, TickStats};
use std::sync::mpsc::Receiver;
use std::time::Duration;

/// How often the tick loop's events are read.
const EVENT_POLL: Duration = Duration::from_millis(50);

/// The tick loop's events as log lines (the loop itself never logs); late ticks summarised.
pub(crate) async fn log_events(
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
