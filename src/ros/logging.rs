//! The node's log: lines to stderr and `/rosout` above a level, each at most 1000 characters,
//! and into the recording as published on `/rosout`; repeats held back (at most one a second
//! per kind); late ticks summarised once a minute when they are more than a few.

use super::clock::NodeClock;
use super::endpoints::Endpoint;
use super::live::LiveTap;
use super::record::RecordTx;
use super::severity::Severity;
use muscle_actuator_recording::msgs::Log;
use muscle_actuator_recording::msgs::Time;
use ros2_client::log::LogLevel;
use ros2_client::{NodeLoggingHandle, RosoutRaw};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant};

/// Logging to stderr and `/rosout`, with a level threshold.
#[derive(Clone)]
pub struct Logger {
    pub(crate) rosout: Option<Arc<NodeLoggingHandle>>,
    pub(crate) level: Severity,
    pub(crate) stdout: bool,
    pub(crate) name: String,
    /// The recording, once it has started: the `/rosout` lines go into it too.
    pub(crate) recording: Arc<OnceLock<RecordTx>>,
    /// The live view, once it has started: the `/rosout` lines go to its clients too.
    pub(crate) live: Arc<OnceLock<LiveTap>>,
    /// Stamps of the `/rosout` lines.
    pub(crate) clock: Arc<NodeClock>,
}

/// Longest log line, characters: what a user sends is quoted as an excerpt already; this is
/// the last guard (a line goes to stderr and `/rosout`).
const MAX_LOG_CHARS: usize = 1000;

impl Logger {
    pub(crate) fn log(&self, sev: Severity, msg: &str) {
        if sev < self.level {
            return;
        }
        let cut;
        let msg = match msg.char_indices().nth(MAX_LOG_CHARS) {
            Some((at, _)) => {
                cut = format!("{}... ({} bytes)", &msg[..at], msg.len());
                cut.as_str()
            }
            None => msg,
        };
        if self.stdout {
            let t = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map(|d| d.as_secs_f64())
                .unwrap_or(0.0);
            eprintln!("[{}] [{t:.6}] [{}]: {msg}", sev.label(), self.name);
        }
        if let Some(h) = &self.rosout {
            let level = match sev {
                Severity::Debug => LogLevel::Debug,
                Severity::Info => LogLevel::Info,
                Severity::Warn => LogLevel::Warn,
                Severity::Error => LogLevel::Error,
                Severity::Fatal => LogLevel::Fatal,
            };
            let stamp = Time::from_nanos(self.clock.now_ns());
            h.rosout_raw(stamp.into(), level, &self.name, msg, file!(), "", line!());
            let (rec, live) = (self.recording.get(), self.live.get());
            if rec.is_some() || live.is_some() {
                let line = Log {
                    stamp,
                    level: level as u8,
                    name: self.name.clone(),
                    msg: msg.to_string(),
                    file: file!().into(),
                    function: String::new(),
                    line: line!(),
                };
                if let Some(r) = rec {
                    r.put((Endpoint::Rosout, 0), stamp.to_nanos(), &line);
                }
                if let Some(l) = live {
                    l.put(Endpoint::Rosout, stamp.to_nanos(), &line);
                }
            }
        }
    }
    pub fn info(&self, msg: &str) {
        self.log(Severity::Info, msg)
    }
    pub fn warn(&self, msg: &str) {
        self.log(Severity::Warn, msg)
    }
    pub fn error(&self, msg: &str) {
        self.log(Severity::Error, msg)
    }
    pub fn debug(&self, msg: &str) {
        self.log(Severity::Debug, msg)
    }
}

/// The log with repeats held back ([`RateLimit`]), shared by the node's tasks.
pub(crate) struct Reporter {
    pub(crate) logger: Logger,
    limits: Mutex<RateLimit>,
}

impl Reporter {
    pub(crate) fn new(logger: Logger) -> Self {
        Self {
            logger,
            limits: Mutex::new(RateLimit::default()),
        }
    }
    /// Logs `msg` unless one of kind `key` went out less than a second ago; the next one says
    /// how many were held back.
    pub(crate) fn report(&self, key: &str, sev: Severity, msg: String) {
        let allowed = self.limits.lock().ok().and_then(|mut l| l.allow(key));
        match allowed {
            Some(0) => self.logger.log(sev, &msg),
            Some(held) => self
                .logger
                .log(sev, &format!("{msg} ({held} more like this held back)")),
            None => {}
        }
    }
}

/// Says a repeated thing at most once a second per key, with the count of what it held back.
#[derive(Default)]
pub(crate) struct RateLimit {
    last: HashMap<String, (Instant, u64)>,
}

impl RateLimit {
    /// `Some(suppressed_since_last)` when the message may go out now.
    pub(crate) fn allow(&mut self, key: &str) -> Option<u64> {
        let now = Instant::now();
        match self.last.get_mut(key) {
            Some((t, held)) if now.duration_since(*t) < Duration::from_secs(1) => {
                *held += 1;
                None
            }
            Some((t, held)) => {
                let n = *held;
                *t = now;
                *held = 0;
                Some(n)
            }
            None => {
                self.last.insert(key.into(), (now, 0));
                Some(0)
            }
        }
    }
}

/// A tick later than this many periods is warned about on its own (rate-limited); later than
/// one period, it is counted in the summary logged every [`LATENESS_SUMMARY_PERIOD`].
pub(crate) const LATE_WARN_PERIODS: f64 = 5.0;
const LATENESS_SUMMARY_PERIOD: Duration = Duration::from_secs(60);
/// The share of a summary period's ticks that must start late for the summary to be logged: a
/// shared or busy machine starts a few ticks late now and then, which changes no tick's step,
/// only when its outputs appear; `/diagnostics` counts every one.
const LATE_SHARE_LOGGED: f64 = 0.01;

/// Ticks that started more than one period late since the last summary.
pub(crate) struct LateTicks {
    count: u64,
    worst_us: f64,
    since: Instant,
    /// Ticks done (`TickStats::ticks`) when the period began.
    ticks_at_start: u64,
}

impl LateTicks {
    /// A summary period that begins now, after `ticks` ticks.
    pub(crate) fn new(ticks: u64) -> Self {
        Self {
            count: 0,
            worst_us: 0.0,
            since: Instant::now(),
            ticks_at_start: ticks,
        }
    }
    /// Counts a late tick; true if it deserves a warning of its own.
    pub(crate) fn add(&mut self, lateness_us: f64, period_us: f64) -> bool {
        self.count += 1;
        self.worst_us = self.worst_us.max(lateness_us);
        lateness_us > LATE_WARN_PERIODS * period_us
    }
    /// The summary line, once a period is over (`ticks` done by now) and more than
    /// [`LATE_SHARE_LOGGED`] of its ticks started late.
    pub(crate) fn summary_due(&mut self, ticks: u64) -> Option<String> {
        if self.since.elapsed() < LATENESS_SUMMARY_PERIOD {
            return None;
        }
        let done = ticks
            .saturating_sub(self.ticks_at_start)
            .max(self.count)
            .max(1);
        let share = self.count as f64 / done as f64;
        let line = (share > LATE_SHARE_LOGGED).then(|| {
            format!(
                "{} of {done} ticks ({:.1} %) started more than one period late in the last {} s \
                 (worst {:.0} us): the machine is busy; the ticks step as always, their outputs come late",
                self.count,
                100.0 * share,
                LATENESS_SUMMARY_PERIOD.as_secs(),
                self.worst_us
            )
        });
        *self = Self::new(ticks);
        line
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Late ticks are counted for the minute's summary, said only when more than 1 % of the
    /// minute's ticks were late; only those later than five periods are warned about on their
    /// own.
    #[test]
    fn late_ticks_are_summarised_when_more_than_a_few() {
        let mut late = LateTicks::new(1000);
        assert!(!late.add(1500.0, 1000.0));
        assert!(late.add(6000.0, 1000.0));
        assert_eq!(late.summary_due(1100), None, "not before a minute");
        late.since = Instant::now() - Duration::from_secs(61);
        let line = late.summary_due(1100).unwrap();
        assert!(
            line.starts_with("2 of 100 ticks (2.0 %) started") && line.contains("(worst 6000 us)"),
            "{line}"
        );
        // 2 late of 60,000 (a minute at 1 kHz): normal on a busy machine, nothing said.
        late.add(1500.0, 1000.0);
        late.add(1500.0, 1000.0);
        late.since = Instant::now() - Duration::from_secs(61);
        assert_eq!(late.summary_due(61_100), None, "a few late: nothing said");
        late.since = Instant::now() - Duration::from_secs(61);
        assert_eq!(
            late.summary_due(121_100),
            None,
            "nothing late: nothing said"
        );
    }

    #[test]
    fn rate_limit_holds_back_repeats() {
        let mut r = RateLimit::default();
        assert_eq!(r.allow("a"), Some(0));
        assert_eq!(r.allow("a"), None);
        assert_eq!(r.allow("a"), None);
        assert_eq!(r.allow("b"), Some(0));
    }
}
