//! How well a predicted series p matches a measured one m, sample by sample (same length, same
//! times): the figures EMG-driven models are judged by when their joint moments are set against
//! those of inverse dynamics (Lloyd & Besier 2003, J Biomech 36(6): 765–776; Sartori et al.
//! 2012, PLoS ONE 7(12): e52618; the CEINMS toolbox, Pizzolato et al. 2015, J Biomech 48(14):
//! 3929–3936), which report an R² and a root-mean-square error in N m.
//!
//! With n samples, m̄ and p̄ the means, `SS_tot = Σ(m − m̄)²` and `SS_res = Σ(m − p)²`:
//!
//! - [`Rating::r_squared`], the coefficient of determination, `1 − SS_res / SS_tot`:
//!   dimensionless, at most 1, unbounded below.
//! - [`Rating::pearson_r_squared`], Pearson's squared correlation,
//!   `(Σ(m − m̄)(p − p̄))² / (SS_tot Σ(p − p̄)²)`: dimensionless, in [0, 1].
//! - [`Rating::rmse`], the root-mean-square error `√(SS_res / n)`: in the unit of m (N m for
//!   moments).
//! - [`Rating::rmse_over_peak`], the RMSE over the peak `max |m|`: dimensionless.
//!
//! The two R² differ and papers call both "R²". The coefficient of determination is 1 only for
//! p = m, falls with any offset, gain or sign error, and is negative when p is further from m
//! than the constant m̄ is (p = −m with m̄ = 0 gives −3). Pearson's r² sees the shape alone:
//! p = a m + b scores 1 for every a ≠ 0 and every b, p = −m included; it is the coefficient of
//! determination p would score after the offset and gain that fit it best to m by least
//! squares, so the two agree only when that fit leaves p as it is. **Quote the coefficient of
//! determination** ([`Rating::r_squared`]) with the RMSE in N m: it is the one that says how far
//! the predicted moment is from the measured one, and the one CEINMS calibrates on. CEINMS's
//! objective per trial and degree of freedom, `SS_res / (n s²)` with `s² = SS_tot/(n − 1)`, is
//! `(n − 1)/n · (1 − R²)` (`computeVariance` and `evalFp` in the toolbox's
//! `lib/Calibration/ObjectiveFunctions/SumMinObjectiveFunction_singleF.cpp`). The RMSE over the
//! peak |m| compares degrees of freedom whose moments differ in size.
//!
//! Refused: series of different lengths or empty, values that are not finite, a measured
//! series without spread (`SS_tot = 0`: R² is 0/0 for p = m and −∞ otherwise, r is 0/0), and
//! for Pearson's r a predicted series without spread. "Without spread" is all values equal, or
//! a spread so small beside the series' peak that the figures would leave the doubles:
//! `Σ(x − x̄)²` below `MIN_SPREAD` times the square of the larger series' peak (rounded up to
//! a power of two), an RMS deviation under about 1e-100 of it. The series are first divided by
//! that power of two (exact: the figures are those of the raw values), so no square overflows;
//! R², r² and the RMSE over the peak are then always finite, and the RMSE is unless |m − p|
//! nears the largest double.
//!
//! Sums of squares and products about the means are taken in two passes, corrected by the
//! rounding left in the means, `Σ dx dy − (Σ dx)(Σ dy)/n` with `dx = x − x̄` (Chan, Golub &
//! LeVeque 1983, Am Stat 37(3): 242–247; CEINMS's `computeVariance` does the same for the
//! variance).

/// Least `Σ(x − x̄)²` of a series, over the square of the larger series' peak, for it to count
/// as spread (a relative RMS deviation of about 1e-100).
pub(crate) const MIN_SPREAD: f64 = 1e-200;

/// The four figures of a predicted series against a measured one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rating {
    /// The coefficient of determination `1 − Σ(m − p)² / Σ(m − m̄)²`, dimensionless, at most 1,
    /// negative when p is further from m than m̄ is: the one to quote.
    pub r_squared: f64,
    /// Pearson's squared correlation `(Σ(m − m̄)(p − p̄))² / (Σ(m − m̄)² Σ(p − p̄)²)`,
    /// dimensionless, in [0, 1]: blind to offset, gain and sign.
    pub pearson_r_squared: f64,
    /// The root-mean-square error `√(Σ(m − p)²/n)`, in the unit of m (N m for moments).
    pub rmse: f64,
    /// The RMSE over the peak `max |m|`, dimensionless.
    pub rmse_over_peak: f64,
}

/// Which of the two series a value belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Series {
    /// The measured one, m.
    Measured,
    /// The predicted one, p.
    Predicted,
}

impl std::fmt::Display for Series {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Series::Measured => "measured",
            Series::Predicted => "predicted",
        })
    }
}

/// Why two series cannot be rated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RatingError {
    /// No samples.
    #[error("no samples to rate")]
    Empty,
    /// The two series have different lengths.
    #[error(
        "{measured} measured samples but {predicted} predicted: they must be sample for sample"
    )]
    LengthMismatch {
        /// The measured series' length.
        measured: usize,
        /// The predicted series' length.
        predicted: usize,
    },
    /// A value that is infinite or not a number.
    #[error("{series} sample {index} is {value}, not a finite number")]
    NotFinite {
        /// The series.
        series: Series,
        /// Its index, from 0.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A series without spread (all its values equal, or its spread below `MIN_SPREAD` of
    /// the peak): R² and r divide by the measured one's, r by the predicted one's.
    #[error(
        "the {series} series has no spread (its first value {first}): Pearson's r divides by \
         Σ(m − m̄)² Σ(p − p̄)², and R² = 1 − Σ(m − p)²/Σ(m − m̄)² by the measured one's"
    )]
    NoSpread {
        /// The series.
        series: Series,
        /// Its first value.
        first: f64,
    },
}

/// The four figures of `predicted` against `measured` (same length, same times).
pub fn rate(measured: &[f64], predicted: &[f64]) -> Result<Rating, RatingError> {
    let pair = Pair::new(measured, predicted)?;
    let ss_tot = pair.spread(Series::Measured)?;
    let ss_pred = pair.spread(Series::Predicted)?;
    let ss_res = pair.residual_sum_of_squares();
    let rmse_scaled = root_mean_square(ss_res, pair.len());
    Ok(Rating {
        r_squared: determination(ss_res, ss_tot),
        pearson_r_squared: pearson_squared(pair.co_spread(), ss_tot, ss_pred),
        rmse: rmse_scaled * pair.scale,
        rmse_over_peak: rmse_scaled / peak(&pair.m),
    })
}

/// The coefficient of determination `1 − Σ(m − p)² / Σ(m − m̄)²` of `predicted` against
/// `measured` alone; a predicted series without spread is accepted.
pub fn coefficient_of_determination(
    measured: &[f64],
    predicted: &[f64],
) -> Result<f64, RatingError> {
    let pair = Pair::new(measured, predicted)?;
    let ss_tot = pair.spread(Series::Measured)?;
    Ok(determination(pair.residual_sum_of_squares(), ss_tot))
}

/// Pearson's correlation `Σ(m − m̄)(p − p̄) / √(Σ(m − m̄)² Σ(p − p̄)²)`, in [−1, 1]: signed,
/// which its square [`Rating::pearson_r_squared`] is not.
pub fn pearson_r(measured: &[f64], predicted: &[f64]) -> Result<f64, RatingError> {
    let pair = Pair::new(measured, predicted)?;
    let ss_tot = pair.spread(Series::Measured)?;
    let ss_pred = pair.spread(Series::Predicted)?;
    Ok(correlation(pair.co_spread(), ss_tot, ss_pred))
}

/// The root-mean-square error `√(Σ(m − p)²/n)` alone, in the unit of the series; series without
/// spread are accepted.
pub fn rmse(measured: &[f64], predicted: &[f64]) -> Result<f64, RatingError> {
    let pair = Pair::new(measured, predicted)?;
    Ok(root_mean_square(pair.residual_sum_of_squares(), pair.len()) * pair.scale)
}

/// `1 − ss_res / ss_tot`; `ss_tot > 0`.
fn determination(ss_res: f64, ss_tot: f64) -> f64 {
    1.0 - ss_res / ss_tot
}

/// `s_mp / √(s_mm s_pp)` as the square root of [`pearson_squared`] with the sign of `s_mp`
/// (the product `s_mm s_pp` may underflow; ±1 stays exact); `s_mm, s_pp > 0`.
fn correlation(s_mp: f64, s_mm: f64, s_pp: f64) -> f64 {
    pearson_squared(s_mp, s_mm, s_pp).sqrt().copysign(s_mp)
}

/// `s_mp² / (s_mm s_pp)`, at most 1 against rounding; `s_mm, s_pp > 0`.
fn pearson_squared(s_mp: f64, s_mm: f64, s_pp: f64) -> f64 {
    ((s_mp / s_mm) * (s_mp / s_pp)).min(1.0)
}

/// `√(sum / n)`.
fn root_mean_square(sum: f64, n: usize) -> f64 {
    (sum / n as f64).sqrt()
}

/// `max |x|` (0 for no values).
fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |a, v| v.abs().max(a))
}

/// Two checked series of one length, both divided by [`Pair::scale`].
struct Pair {
    /// m / scale.
    m: Vec<f64>,
    /// p / scale.
    p: Vec<f64>,
    /// The least power of two at or above the larger peak |value| of the two series (within
    /// [2^−1022, 2^1023]): every scaled value lies in [−2, 2].
    scale: f64,
}

impl Pair {
    /// The series checked (same length, not empty, finite) and scaled.
    fn new(measured: &[f64], predicted: &[f64]) -> Result<Pair, RatingError> {
        if measured.len() != predicted.len() {
            return Err(RatingError::LengthMismatch {
                measured: measured.len(),
                predicted: predicted.len(),
            });
        }
        if measured.is_empty() {
            return Err(RatingError::Empty);
        }
        finite(measured, Series::Measured)?;
        finite(predicted, Series::Predicted)?;
        let scale = power_of_two_at_or_above(peak(measured).max(peak(predicted)));
        Ok(Pair {
            m: measured.iter().map(|x| x / scale).collect(),
            p: predicted.iter().map(|x| x / scale).collect(),
            scale,
        })
    }

    /// The number of samples.
    fn len(&self) -> usize {
        self.m.len()
    }

    /// `Σ(x − x̄)²` of the series `which`, scaled; refused below [`MIN_SPREAD`] or when all its
    /// values are equal.
    fn spread(&self, which: Series) -> Result<f64, RatingError> {
        let x = match which {
            Series::Measured => &self.m,
            Series::Predicted => &self.p,
        };
        let ss = co_spread(x, x);
        if ss < MIN_SPREAD || x.iter().all(|&v| v == x[0]) {
            return Err(RatingError::NoSpread {
                series: which,
                first: x[0] * self.scale,
            });
        }
        Ok(ss)
    }

    /// `Σ(m − m̄)(p − p̄)`, scaled.
    fn co_spread(&self) -> f64 {
        co_spread(&self.m, &self.p)
    }

    /// `Σ(m − p)²`, scaled.
    fn residual_sum_of_squares(&self) -> f64 {
        self.m
            .iter()
            .zip(&self.p)
            .map(|(m, p)| (m - p) * (m - p))
            .sum()
    }
}

/// The first non-finite value of `x`, refused.
fn finite(x: &[f64], series: Series) -> Result<(), RatingError> {
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(RatingError::NotFinite {
            series,
            index,
            value: x[index],
        }),
        None => Ok(()),
    }
}

/// The least power of two at or above `peak` (≥ 0, finite), within [2^−1022, 2^1023].
fn power_of_two_at_or_above(peak: f64) -> f64 {
    let exponent = if peak > 0.0 {
        peak.log2().ceil().clamp(-1022.0, 1023.0) as i32
    } else {
        0
    };
    2f64.powi(exponent)
}

/// The mean of `x` (not empty).
fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

/// `Σ(x − x̄)(y − ȳ)` (`x`, `y` of one length, not empty) by the corrected two-pass sum
/// `Σ dx dy − (Σ dx)(Σ dy)/n`, `dx = x − x̄` (Chan, Golub & LeVeque 1983).
fn co_spread(x: &[f64], y: &[f64]) -> f64 {
    let (x_mean, y_mean) = (mean(x), mean(y));
    let (mut sum_dx, mut sum_dy, mut sum_dxdy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        let (dx, dy) = (a - x_mean, b - y_mean);
        sum_dx += dx;
        sum_dy += dy;
        sum_dxdy += dx * dy;
    }
    sum_dxdy - sum_dx * sum_dy / x.len() as f64
}

#[cfg(test)]
mod tests;
