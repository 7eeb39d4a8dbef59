//! Input schedules of scenario files: functions of time sampled at each tick's start.

use serde::{Deserialize, Serialize};

/// One scheduled signal.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum Schedule {
    /// A constant value.
    Constant {
        /// The value.
        value: f64,
    },
    /// `from` before `at`, `to` from `at` on.
    Step {
        /// Switch time, s.
        at: f64,
        /// Value before, default 0.
        #[serde(default)]
        from: f64,
        /// Value after.
        to: f64,
    },
    /// `value` on [start, end), `base` elsewhere.
    Pulse {
        /// Start, s.
        start: f64,
        /// End, s.
        end: f64,
        /// Value inside.
        value: f64,
        /// Value outside, default 0.
        #[serde(default)]
        base: f64,
    },
    /// Linear from `from` at `start` to `to` at `end`, held outside.
    Ramp {
        /// Start, s.
        start: f64,
        /// End, s.
        end: f64,
        /// Value at and before start.
        from: f64,
        /// Value at and after end.
        to: f64,
    },
    /// `offset + amplitude sin(2π frequency t + phase)`.
    Sine {
        /// Mean value.
        #[serde(default)]
        offset: f64,
        /// Amplitude.
        amplitude: f64,
        /// Frequency, Hz.
        frequency: f64,
        /// Phase, rad.
        #[serde(default)]
        phase: f64,
    },
    /// Linear interpolation through `points` = [[t, value], ...] (ascending t), held outside.
    Piecewise {
        /// The corner points.
        points: Vec<[f64; 2]>,
    },
}

/// A schedule whose numbers break its rules (`Schedule::check`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScheduleError {
    /// A value that is not a finite number.
    #[error("{name} = {value} must be a finite number")]
    NotFinite {
        /// The value's name (`start`, `point time`, ...).
        name: &'static str,
        /// The value.
        value: f64,
    },
    /// An interval that ends at or before its start.
    #[error("end = {end} must be > start = {start}")]
    EndNotAfterStart {
        /// Its start, s.
        start: f64,
        /// Its end, s.
        end: f64,
    },
    /// A piecewise schedule without points.
    #[error("points must not be empty")]
    NoPoints,
    /// A piecewise schedule whose times do not rise.
    #[error("point times must be strictly ascending")]
    PointsNotAscending,
}

impl Schedule {
    /// The value at time t.
    pub fn value(&self, t: f64) -> f64 {
        match self {
            Schedule::Constant { value } => *value,
            Schedule::Step { at, from, to } => {
                if t >= *at {
                    *to
                } else {
                    *from
                }
            }
            Schedule::Pulse {
                start,
                end,
                value,
                base,
            } => {
                if t >= *start && t < *end {
                    *value
                } else {
                    *base
                }
            }
            Schedule::Ramp {
                start,
                end,
                from,
                to,
            } => {
                if t <= *start {
                    *from
                } else if t >= *end {
                    *to
                } else {
                    from + (to - from) * (t - start) / (end - start)
                }
            }
            Schedule::Sine {
                offset,
                amplitude,
                frequency,
                phase,
            } => offset + amplitude * (2.0 * std::f64::consts::PI * frequency * t + phase).sin(),
            Schedule::Piecewise { points } => {
                let Some(first) = points.first() else {
                    return 0.0;
                };
                if t <= first[0] {
                    return first[1];
                }
                for w in points.windows(2) {
                    let (a, b) = (w[0], w[1]);
                    if t <= b[0] {
                        return a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]);
                    }
                }
                points[points.len() - 1][1]
            }
        }
    }

    /// The value's rate of change at time t, per s: the analytic derivative, from the right
    /// where the schedule has a corner (the slope of the piece that starts at t); zero across
    /// the jumps of `step` and `pulse` (a jump is a jump, not a velocity).
    pub fn slope(&self, t: f64) -> f64 {
        match self {
            Schedule::Constant { .. } | Schedule::Step { .. } | Schedule::Pulse { .. } => 0.0,
            Schedule::Ramp {
                start,
                end,
                from,
                to,
            } => {
                if t >= *start && t < *end {
                    (to - from) / (end - start)
                } else {
                    0.0
                }
            }
            Schedule::Sine {
                amplitude,
                frequency,
                phase,
                ..
            } => {
                let w = 2.0 * std::f64::consts::PI * frequency;
                amplitude * w * (w * t + phase).cos()
            }
            Schedule::Piecewise { points } => points
                .windows(2)
                .find(|w| t >= w[0][0] && t < w[1][0])
                .map_or(0.0, |w| (w[1][1] - w[0][1]) / (w[1][0] - w[0][0])),
        }
    }

    /// The first problem with the schedule's numbers, if any.
    pub(crate) fn check(&self) -> Result<(), ScheduleError> {
        let finite = |name: &'static str, value: f64| {
            if value.is_finite() {
                Ok(())
            } else {
                Err(ScheduleError::NotFinite { name, value })
            }
        };
        match self {
            Schedule::Constant { value } => finite("value", *value),
            Schedule::Step { at, from, to } => {
                finite("at", *at)?;
                finite("from", *from)?;
                finite("to", *to)
            }
            Schedule::Pulse {
                start,
                end,
                value,
                base,
            } => {
                finite("start", *start)?;
                finite("end", *end)?;
                finite("value", *value)?;
                finite("base", *base)?;
                if end <= start {
                    return Err(ScheduleError::EndNotAfterStart {
                        start: *start,
                        end: *end,
                    });
                }
                Ok(())
            }
            Schedule::Ramp {
                start,
                end,
                from,
                to,
            } => {
                finite("start", *start)?;
                finite("end", *end)?;
                finite("from", *from)?;
                finite("to", *to)?;
                if end <= start {
                    return Err(ScheduleError::EndNotAfterStart {
                        start: *start,
                        end: *end,
                    });
                }
                Ok(())
            }
            Schedule::Sine {
                offset,
                amplitude,
                frequency,
                phase,
            } => {
                finite("offset", *offset)?;
                finite("amplitude", *amplitude)?;
                finite("frequency", *frequency)?;
                finite("phase", *phase)
            }
            Schedule::Piecewise { points } => {
                if points.is_empty() {
                    return Err(ScheduleError::NoPoints);
                }
                for p in points {
                    finite("point time", p[0])?;
                    finite("point value", p[1])?;
                }
                if points.windows(2).any(|w| w[1][0] <= w[0][0]) {
                    return Err(ScheduleError::PointsNotAscending);
                }
                Ok(())
            }
        }
    }
}
