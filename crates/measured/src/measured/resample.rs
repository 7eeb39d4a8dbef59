//! Measured series at other times: linear interpolation of a [`Table`] column, or of any series
//! of (times, values), onto given times, and the time derivative of a series; for a [`Trial`],
//! the inverse-dynamics moments at the kinematics' times and a muscle–tendon unit's length and
//! lengthening rate at any time within them.
//!
//! **Interpolation.** Between the samples `(tᵢ, vᵢ)` and `(tᵢ₊₁, vᵢ₊₁)` the value at t is
//! `(1 − f) vᵢ + f vᵢ₊₁` with `f = (t − tᵢ)/(tᵢ₊₁ − tᵢ)`; at a sample's own time it is that
//! sample's value, bit for bit. A time before the first sample or after the last is refused
//! (no extrapolation), except within `TIME_TOLERANCE_S` of an end, which is taken as that end
//! (the tolerance by which a trial's tables share their times, `Trial::check`). The error of
//! linear interpolation is at most `h² max|v''| / 8` on a step h.
//!
//! **Derivative.** At the samples, by the derivative of the parabola through three neighbours
//! (Fornberg 1988, Math Comp 51(184): 699–706; numpy.gradient with `edge_order=2` computes the
//! same): inside, the central difference, with `s₋`, `s₊` the slopes of the steps `h₋`, `h₊`
//! either side, `(h₊ s₋ + h₋ s₊)/(h₋ + h₊)`, which is `(vᵢ₊₁ − vᵢ₋₁)/(2h)` on a uniform step
//! and errs by `h₋ h₊ v'''/6`; at the two ends, one-sided over the first (last) three samples,
//! `(−3v₀ + 4v₁ − v₂)/(2h)` on a uniform step, erring by `−h² v'''/3`. Both are second order
//! (exact for a parabola); the ends are one-sided of second order rather than the two-point
//! slope `(v₁ − v₀)/h`, whose first-order error `h v''/2` would set the whole series' error. Two
//! samples give their one slope. Between samples the derivatives at the samples are
//! interpolated linearly, adding at most `h² max|v'''| / 8`: the rate is continuous in time and
//! its error O(h²) everywhere. Noise of standard deviation σ on the samples reaches the central
//! difference as `0.71 σ / h` and the one-sided one as `2.55 σ / h`; `lmt.txt` holds
//! smooth lengths from OpenSim's muscle analysis at h = 4 ms. (CEINMS differentiates the
//! fibre length instead, by a cubic spline through its trace: `updateFibreVelocity` in the
//! toolbox's `lib/NMSmodel/MTU.cpp`, the spline in `lib/Curve/Curve.h`.)
//!
//! **A trial.** The toolbox's `<dof>Torque.txt` share `lmt.txt`'s times: `Trial::check` holds
//! them within `TIME_TOLERANCE_S`, and in `data/ceinms` they are the same text, so the same
//! doubles. [`moments_at_kinematics`] interpolates each moment at `lmt.txt`'s times all the
//! same, which returns the moment's column unchanged there, and values on `lmt.txt`'s times for
//! a trial whose times differ within the tolerance.
//!
//! **Why not a crate.** `interp` (after numpy.interp) returns values, never an error: outside
//! the range it extrapolates or holds an end (its `InterpMode`), it does not check that the
//! times increase, and it reads slices of unequal length, or empty ones, as best it can (the
//! shorter length; zeros). `ndarray-interp` refuses extrapolation by default, but takes
//! `ndarray` arrays, which this crate does not use (it has `nalgebra`), and has errors of its
//! own. What is needed here, checked inputs, this module's errors and the derivative of sampled
//! data, takes a few short functions, written out below.

use crate::measured::table::Table;
use crate::measured::trial::{Trial, TIME_TOLERANCE_S};
use muscle_actuator_core::text::excerpt;
use std::collections::BTreeMap;

/// A value of a series or of a request, as errors name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// A sample's time, s.
    SampleTime,
    /// A sample's value.
    SampleValue,
    /// A time asked for, s.
    RequestedTime,
    /// A derivative at a sample (infinite when the samples are too steep for the doubles).
    Derivative,
}

impl std::fmt::Display for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Quantity::SampleTime => "sample time",
            Quantity::SampleValue => "sample value",
            Quantity::RequestedTime => "requested time",
            Quantity::Derivative => "the derivative at sample",
        })
    }
}

/// Why a series cannot be resampled or differentiated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ResampleError {
    /// Fewer samples than the operation needs (one to interpolate, two to differentiate).
    #[error("{found} samples, at least {needed} needed")]
    TooFewSamples {
        /// The samples given.
        found: usize,
        /// The least needed.
        needed: usize,
    },
    /// Another count of times than of values.
    #[error("{times} sample times but {values} values")]
    LengthMismatch {
        /// The times given.
        times: usize,
        /// The values given.
        values: usize,
    },
    /// A time or value that is infinite or not a number.
    #[error("{quantity} {index} is {value}, not a finite number")]
    NotFinite {
        /// What it is.
        quantity: Quantity,
        /// Its index, from 0.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A sample's time not after the previous one's.
    #[error("sample time {index} ({time_s} s) is not after the previous one ({previous_s} s)")]
    TimeNotIncreasing {
        /// The sample's index, from 0.
        index: usize,
        /// Its time, s.
        time_s: f64,
        /// The previous sample's time, s.
        previous_s: f64,
    },
    /// A time asked for outside the samples' range.
    #[error(
        "requested time {index} ({time_s} s) is outside the samples' {start_s} s to {end_s} s \
         (no extrapolation)"
    )]
    OutOfRange {
        /// Its index among the times asked for, from 0.
        index: usize,
        /// The time, s.
        time_s: f64,
        /// The first sample's time, s.
        start_s: f64,
        /// The last sample's time, s.
        end_s: f64,
    },
    /// A table without the column asked for.
    #[error("the table has no column {:?}", excerpt(.column))]
    NoColumn {
        /// The column asked for.
        column: String,
    },
}

/// The series (`times`, s, strictly increasing; `values`) at the times `at`, s, linearly
/// interpolated (see the module's documentation); one value per time asked for.
pub(crate) fn interpolate(
    times: &[f64],
    values: &[f64],
    at: &[f64],
) -> Result<Vec<f64>, ResampleError> {
    let series = Series::new(times, values, 1)?;
    let at = series.clamped(at)?;
    Ok(at.into_iter().map(|t| series.value_at(t)).collect())
}

/// The time derivative of the series (`times`, s, strictly increasing; `values`) at its own
/// samples, in the values' unit per second: central differences inside, one-sided at the ends,
/// both of second order (see the module's documentation). At least two samples.
pub fn derivative_at_samples(times: &[f64], values: &[f64]) -> Result<Vec<f64>, ResampleError> {
    Series::new(times, values, 2)?.derivatives()
}

/// The time derivative of the series (`times`, s, strictly increasing; `values`) at the times
/// `at`, s: [`derivative_at_samples`] linearly interpolated. At least two samples.
pub fn derivative_at(times: &[f64], values: &[f64], at: &[f64]) -> Result<Vec<f64>, ResampleError> {
    let series = Series::new(times, values, 2)?;
    let at = series.clamped(at)?;
    let derivatives = series.derivatives()?;
    let rates = Series {
        times,
        values: &derivatives,
    };
    Ok(at.into_iter().map(|t| rates.value_at(t)).collect())
}

/// The column `column` of `table` at the times `at`, s, linearly interpolated.
pub(crate) fn column_at(
    table: &Table,
    column: &str,
    at: &[f64],
) -> Result<Vec<f64>, ResampleError> {
    interpolate(table.times(), named(table, column)?, at)
}

/// Per degree of freedom of `trial`, its inverse-dynamics moment, N m, at the times of
/// `lmt.txt` (its own values there: see the module's documentation).
pub fn moments_at_kinematics(trial: &Trial) -> Result<BTreeMap<String, Vec<f64>>, ResampleError> {
    let at = trial.lmt.times();
    trial
        .moments
        .iter()
        .map(|(dof, table)| Ok((dof.clone(), column_at(table, dof, at)?)))
        .collect()
}

/// The length, m, of the muscle–tendon unit `unit` of `trial` at the times `at`, s, within the
/// times of `lmt.txt`.
pub(crate) fn unit_length(
    trial: &Trial,
    unit: &str,
    at: &[f64],
) -> Result<Vec<f64>, ResampleError> {
    column_at(&trial.lmt, unit, at)
}

/// The lengthening rate, m/s (positive lengthening), of the muscle–tendon unit `unit` of
/// `trial` at the times `at`, s, within the times of `lmt.txt`: [`derivative_at`] of its length.
pub fn unit_lengthening_rate(
    trial: &Trial,
    unit: &str,
    at: &[f64],
) -> Result<Vec<f64>, ResampleError> {
    derivative_at(trial.lmt.times(), named(&trial.lmt, unit)?, at)
}

/// The column `column` of `table`.
fn named<'a>(table: &'a Table, column: &str) -> Result<&'a [f64], ResampleError> {
    table
        .column_named(column)
        .ok_or_else(|| ResampleError::NoColumn {
            column: column.to_string(),
        })
}

/// A checked series: times finite and strictly increasing, values finite, of one length.
struct Series<'a> {
    /// The samples' times, s.
    times: &'a [f64],
    /// The samples' values.
    values: &'a [f64],
}

impl<'a> Series<'a> {
    /// `times` and `values` checked, at least `needed` samples.
    fn new(times: &'a [f64], values: &'a [f64], needed: usize) -> Result<Self, ResampleError> {
        if times.len() != values.len() {
            return Err(ResampleError::LengthMismatch {
                times: times.len(),
                values: values.len(),
            });
        }
        if times.len() < needed {
            return Err(ResampleError::TooFewSamples {
                found: times.len(),
                needed,
            });
        }
        finite(times, Quantity::SampleTime)?;
        finite(values, Quantity::SampleValue)?;
        increasing(times)?;
        Ok(Series { times, values })
    }

    /// The first time, s.
    fn start(&self) -> f64 {
        self.times.first().copied().unwrap_or(f64::NAN)
    }

    /// The last time, s.
    fn end(&self) -> f64 {
        self.times.last().copied().unwrap_or(f64::NAN)
    }

    /// The times `at` checked (finite, within the samples' range give or take
    /// [`TIME_TOLERANCE_S`]) and brought within the range.
    fn clamped(&self, at: &[f64]) -> Result<Vec<f64>, ResampleError> {
        finite(at, Quantity::RequestedTime)?;
        let (start, end) = (self.start(), self.end());
        at.iter()
            .enumerate()
            .map(|(index, &t)| {
                if t < start - TIME_TOLERANCE_S || t > end + TIME_TOLERANCE_S {
                    Err(ResampleError::OutOfRange {
                        index,
                        time_s: t,
                        start_s: start,
                        end_s: end,
                    })
                } else {
                    Ok(t.clamp(start, end))
                }
            })
            .collect()
    }

    /// The value at `t`, within the samples' range: a sample's own at its time, else the
    /// interpolation between the two samples around `t`.
    fn value_at(&self, t: f64) -> f64 {
        let (times, values) = (self.times, self.values);
        let lo = times.partition_point(|&x| x <= t).saturating_sub(1);
        match (times.get(lo), times.get(lo + 1)) {
            (Some(&t0), Some(&t1)) if t0 != t => {
                lerp(values[lo], values[lo + 1], (t - t0) / (t1 - t0))
            }
            _ => values[lo],
        }
    }

    /// The derivative at every sample (at least two): [`derivative_at_samples`]; refused where
    /// it is not finite.
    fn derivatives(&self) -> Result<Vec<f64>, ResampleError> {
        let (h, s) = self.steps_and_slopes();
        let n = self.times.len();
        let d = if n == 2 {
            vec![s[0]; 2]
        } else {
            let mut d = Vec::with_capacity(n);
            d.push(one_sided(s[0], s[1], h[0], h[1]));
            d.extend((1..n - 1).map(|i| central(s[i - 1], s[i], h[i - 1], h[i])));
            d.push(one_sided(s[n - 2], s[n - 3], h[n - 2], h[n - 3]));
            d
        };
        finite(&d, Quantity::Derivative)?;
        Ok(d)
    }

    /// The steps `hᵢ = tᵢ₊₁ − tᵢ`, s, and the slopes `(vᵢ₊₁ − vᵢ)/hᵢ` between samples.
    fn steps_and_slopes(&self) -> (Vec<f64>, Vec<f64>) {
        let h: Vec<f64> = self.times.windows(2).map(|w| w[1] - w[0]).collect();
        let s = self
            .values
            .windows(2)
            .zip(&h)
            .map(|(v, h)| (v[1] - v[0]) / h)
            .collect();
        (h, s)
    }
}

/// `(1 − f) a + f b`, `f` in [0, 1]: `a` at 0 and `b` at 1 exactly, never beyond them.
fn lerp(a: f64, b: f64, f: f64) -> f64 {
    (1.0 - f) * a + f * b
}

/// The central difference at a sample between a step `h_before` of slope `s_before` and a step
/// `h_after` of slope `s_after`: `(h₊ s₋ + h₋ s₊)/(h₋ + h₊)`, the parabola's derivative.
fn central(s_before: f64, s_after: f64, h_before: f64, h_after: f64) -> f64 {
    (h_after * s_before + h_before * s_after) / (h_before + h_after)
}

/// The one-sided difference at an end sample, its adjacent step `h_near` of slope `s_near`,
/// the next step `h_far` of slope `s_far`: `s_near + h_near (s_near − s_far)/(h_near + h_far)`,
/// the parabola's derivative (`(−3v₀ + 4v₁ − v₂)/(2h)` at the start on a uniform step).
fn one_sided(s_near: f64, s_far: f64, h_near: f64, h_far: f64) -> f64 {
    s_near + h_near * (s_near - s_far) / (h_near + h_far)
}

/// The first value of `x` that is not finite, refused as a `quantity`.
fn finite(x: &[f64], quantity: Quantity) -> Result<(), ResampleError> {
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(ResampleError::NotFinite {
            quantity,
            index,
            value: x[index],
        }),
        None => Ok(()),
    }
}

/// The first time of `times` not after the previous one, refused.
fn increasing(times: &[f64]) -> Result<(), ResampleError> {
    match times.windows(2).position(|w| w[1] <= w[0]) {
        Some(i) => Err(ResampleError::TimeNotIncreasing {
            index: i + 1,
            time_s: times[i + 1],
            previous_s: times[i],
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests;
