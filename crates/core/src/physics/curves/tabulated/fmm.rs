//! The cubic spline of Forsythe, Malcolm & Moler (1977), Computer Methods for Mathematical
//! Computations, Prentice-Hall, the `SPLINE` routine (pp. 77–78 as CEINMS cites them; CEINMS's
//! lib/Curve/Curve.cpp, `computeCoefficients(Int2Type<CurveMode::Cubic>)`, is a transcription).
//!
//! With σ_i = s''(x_i)/6, h_i = x_{i+1} − x_i and Δ_i = (y_{i+1} − y_i)/h_i, continuity of the
//! slope at each inner point gives `h_{i−1} σ_{i−1} + 2 (h_{i−1} + h_i) σ_i + h_i σ_{i+1} =
//! Δ_i − Δ_{i−1}`. The two end rows set the third derivative at each end to that of the cubic
//! through the four points nearest it, `s'''(x_0) = 6 f[x_0, x_1, x_2, x_3]` (and likewise at
//! the last point); with three points the third derivative is zero at both ends, so the spline is
//! the parabola through them; with two it is the line. The system is solved by elimination
//! without pivoting, as FMM do: its pivots are never zero (the first is −h_0, each inner one
//! exceeds the next interval's width, the last is below −h_{n−2}).

/// The cubic that starts at one point: `y + b·dx + c·dx² + d·dx³` with dx from the point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Cubic {
    /// dy/dx at the point.
    pub b: f64,
    /// Half the second derivative at the point.
    pub c: f64,
    /// A sixth of the third derivative on the interval that starts at the point.
    pub d: f64,
}

/// The cubic at every point of (x, y): at least two points, x strictly increasing (the caller
/// checks). The last point's cubic is FMM's: the end slope and second derivative, and the last
/// interval's third derivative.
pub(super) fn cubics(x: &[f64], y: &[f64]) -> Vec<Cubic> {
    let n = x.len();
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let delta: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    if n == 2 {
        let line = Cubic {
            b: delta[0],
            c: 0.0,
            d: 0.0,
        };
        return vec![line; 2];
    }
    let sigma = second_derivatives_over_six(x, &h, &delta);
    (0..n).map(|i| cubic_at(i, &h, &delta, &sigma)).collect()
}

/// σ_i = s''(x_i)/6 at every point (three or more), by FMM's tridiagonal system.
fn second_derivatives_over_six(x: &[f64], h: &[f64], delta: &[f64]) -> Vec<f64> {
    let n = x.len();
    let mut diagonal = vec![0.0; n];
    let mut rhs = vec![0.0; n];
    for i in 1..n - 1 {
        diagonal[i] = 2.0 * (h[i - 1] + h[i]);
        rhs[i] = delta[i] - delta[i - 1];
    }
    diagonal[0] = -h[0];
    diagonal[n - 1] = -h[n - 2];
    if n > 3 {
        rhs[0] = h[0] * h[0] * third_divided_difference(&x[..4], &rhs[1..3]);
        rhs[n - 1] =
            -h[n - 2] * h[n - 2] * third_divided_difference(&x[n - 4..], &rhs[n - 3..n - 1]);
    }
    // Forward elimination; the off-diagonal between rows i and i + 1 is h_i.
    for i in 1..n {
        let t = h[i - 1] / diagonal[i - 1];
        diagonal[i] -= t * h[i - 1];
        rhs[i] -= t * rhs[i - 1];
    }
    let mut sigma = rhs;
    sigma[n - 1] /= diagonal[n - 1];
    for i in (0..n - 1).rev() {
        sigma[i] = (sigma[i] - h[i] * sigma[i + 1]) / diagonal[i];
    }
    sigma
}

/// f[x_0, x_1, x_2, x_3] from the differences of slopes at the two inner points,
/// `jumps = [Δ_1 − Δ_0, Δ_2 − Δ_1]`: each over its span is a second divided difference.
fn third_divided_difference(x: &[f64], jumps: &[f64]) -> f64 {
    (jumps[1] / (x[3] - x[1]) - jumps[0] / (x[2] - x[0])) / (x[3] - x[0])
}

/// The cubic at point i from the σ: on [x_i, x_{i+1}], `b = Δ_i − h_i (σ_{i+1} + 2σ_i)`,
/// `c = 3σ_i`, `d = (σ_{i+1} − σ_i)/h_i`; at the last point the slope the last interval ends
/// with, `Δ + h (σ_{n−2} + 2σ_{n−1})`, and that interval's d.
fn cubic_at(i: usize, h: &[f64], delta: &[f64], sigma: &[f64]) -> Cubic {
    let last = h.len();
    if i < last {
        Cubic {
            b: delta[i] - h[i] * (sigma[i + 1] + 2.0 * sigma[i]),
            c: 3.0 * sigma[i],
            d: (sigma[i + 1] - sigma[i]) / h[i],
        }
    } else {
        let j = last - 1;
        Cubic {
            b: delta[j] + h[j] * (sigma[j] + 2.0 * sigma[i]),
            c: 3.0 * sigma[i],
            d: (sigma[i] - sigma[j]) / h[j],
        }
    }
}
