//! The time base of a run: what its log times and header stamps count, and ticks ↔ stamps.
//!
//! One time base per recording, named in its metadata ([`TimeBase`]): every log time and header
//! stamp of an offline run is simulated time from zero; every one of a node run counts from a
//! wall-clock origin (ns since the Unix epoch), or from the time of the external `/clock` it
//! followed. Inputs are recorded stamped with the tick at which they take effect:
//! stamp = tick origin + tick / rate,
//! so tick = round((stamp − origin) · rate), with origin 0 offline and the node's tick origin
//! (the time of its tick 0) in a node run.

/// The clock of a recording's log times and header stamps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeBase {
    /// Simulated time from zero: tick k at k / rate (offline runs).
    Simulated,
    /// Stamps counted from a wall-clock origin (node runs): tick k is stamped
    /// `tick_origin_ns + k / rate`, the origin being the wall-clock time of the node's tick 0
    /// (ns since the Unix epoch). Under `clock:=wall` the stamps keep to the wall clock; under
    /// `sim` and `lockstep` they are simulated time from that origin. Named `wall` in a
    /// recording's metadata.
    WallOrigin {
        /// The wall-clock time of tick 0, ns since the Unix epoch.
        tick_origin_ns: i64,
    },
    /// The time of an external `/clock` the node followed (`use_sim_time`), ns; tick k is
    /// stamped `tick_origin_ns + k / rate`, the origin being the first `/clock` time received
    /// (`None` until one arrived: the run has no tick yet).
    RosClock {
        /// The first `/clock` time received, ns (`None` until one arrived).
        tick_origin_ns: Option<i64>,
    },
}

impl TimeBase {
    /// The stamp of tick 0, ns.
    pub fn tick_origin_ns(self) -> i64 {
        match self {
            TimeBase::Simulated
            | TimeBase::RosClock {
                tick_origin_ns: None,
            } => 0,
            TimeBase::WallOrigin { tick_origin_ns }
            | TimeBase::RosClock {
                tick_origin_ns: Some(tick_origin_ns),
            } => tick_origin_ns,
        }
    }

    /// The stamp of `tick` at `rate_hz`, ns.
    pub fn stamp_ns(self, tick: u64, rate_hz: f64) -> i64 {
        self.tick_origin_ns()
            .saturating_add(i64::try_from(tick_ns(tick, rate_hz)).unwrap_or(i64::MAX))
    }

    /// The tick stamped `ns` at `rate_hz` (refused before the origin: it names no tick).
    pub fn tick_of(self, ns: i64, rate_hz: f64) -> Result<u64, StampError> {
        if self
            == (TimeBase::RosClock {
                tick_origin_ns: None,
            })
        {
            return Err(StampError::NoOrigin { ns });
        }
        let origin = self.tick_origin_ns();
        let since = (ns.checked_sub(origin).filter(|d| *d >= 0))
            .ok_or(StampError::BeforeOrigin { ns, origin })?;
        Ok(ns_tick(since as u64, rate_hz))
    }
}

/// A stamp that names no tick ([`TimeBase::tick_of`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum StampError {
    /// Following `/clock`, before any clock message gave the run its tick origin.
    #[error(
        "stamp {ns} ns names no tick: the node received no /clock message, so the run has no \
         tick origin"
    )]
    NoOrigin {
        /// The stamp, ns.
        ns: i64,
    },
    /// A stamp before the run's tick origin.
    #[error("stamp {ns} ns is before the run's tick origin ({origin} ns)")]
    BeforeOrigin {
        /// The stamp, ns.
        ns: i64,
        /// The tick origin, ns.
        origin: i64,
    },
}

/// Simulated time of `tick` at `rate_hz`, ns.
pub fn tick_ns(tick: u64, rate_hz: f64) -> u64 {
    (tick as f64 * 1e9 / rate_hz).round() as u64
}

/// The tick whose simulated time is `ns`.
pub(crate) fn ns_tick(ns: u64, rate_hz: f64) -> u64 {
    (ns as f64 * rate_hz / 1e9).round() as u64
}

/// Now, ns since the Unix epoch.
pub fn now_ns() -> i64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos() as i64)
        .unwrap_or(0)
}

/// `YYYY-MM-DDTHH:MM:SS.mmmZ` of ns since the epoch (UTC).
pub fn iso8601(ns: i64) -> String {
    let secs = ns.div_euclid(1_000_000_000);
    let ms = ns.rem_euclid(1_000_000_000) / 1_000_000;
    let days = secs.div_euclid(86_400);
    let sod = secs.rem_euclid(86_400);
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}.{ms:03}Z",
        sod / 3600,
        sod / 60 % 60,
        sod % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Stamps and ticks map both ways on either clock; a stamp before the origin names no tick;
    /// following /clock, no stamp names a tick before the first clock message, then ticks count
    /// from the origin it gave.
    #[test]
    fn time_base_maps_stamps_to_ticks() {
        let wall = TimeBase::WallOrigin {
            tick_origin_ns: 1_763_800_000_000_000_123,
        };
        for rate in [1000.0, 333.0, 2500.0] {
            for tick in [0, 1, 7, 123_456, 86_400_000] {
                for tb in [TimeBase::Simulated, wall] {
                    assert_eq!(tb.tick_of(tb.stamp_ns(tick, rate), rate), Ok(tick));
                }
            }
        }
        assert_eq!(wall.stamp_ns(2, 1000.0), 1_763_800_000_002_000_123);
        assert!(wall
            .tick_of(1_763_800_000_000_000_000, 1000.0)
            .unwrap_err()
            .to_string()
            .contains("before the run's tick origin"));
        assert!(TimeBase::Simulated.tick_of(-1, 1000.0).is_err());
        let rc = TimeBase::RosClock {
            tick_origin_ns: Some(5_000_000_000_000),
        };
        assert_eq!(rc.tick_of(rc.stamp_ns(42, 1000.0), 1000.0), Ok(42));
        let none = TimeBase::RosClock {
            tick_origin_ns: None,
        };
        assert!(matches!(
            none.tick_of(0, 1000.0),
            Err(StampError::NoOrigin { ns: 0 })
        ));
        assert!(none
            .tick_of(0, 1000.0)
            .unwrap_err()
            .to_string()
            .contains("no /clock"));
    }
}
