//! Closed-form steady states of the full Huxley (1957) model (docs/model.md §7), with g3 = 0.
//! They calibrate the full model and serve as the oracle the numerical solutions are tested on.

use crate::physics::contractile::crossbridge::Rates;

/// Bond fraction of the isometric steady state on [0, 1]: `r f1/(f1 + g1)`.
fn plateau(rates: &Rates, r: f64) -> f64 {
    r * rates.f1 / (rates.f1 + rates.g1)
}

/// Isometric steady moments (Q0, Q1, Q2) = n∞ (1, 1/2, 1/3).
pub(crate) fn isometric_moments(rates: &Rates, r: f64) -> [f64; 3] {
    let n = plateau(rates, r);
    [n, n / 2.0, n / 3.0]
}

/// Steady Q1 at constant shortening rate u (h/s; negative: lengthening).
///
/// Shortening, `φ = (f1+g1)/(2u)`: `Q1 = n∞ [½ - (1 - e^{-φ})/(2φ) - (1 - e^{-φ}) u²/g2²]`,
/// i.e. `F/F0 = 1 - (1 - e^{-φ}) [1/φ + (f1+g1)²/(2 g2² φ²)]`.
/// Lengthening, w = -u, `α = (f1+g1)/(2w)`, `β = g1/(2w)`:
/// `Q1 = n∞ [½ - (1 - e^{-α})/(2α) + (1 - e^{-α})/(2β)]` (bonds carried past ξ = 1 decay at g1 ξ).
pub fn steady_q1(rates: &Rates, r: f64, u: f64) -> f64 {
    let n = plateau(rates, r);
    if u == 0.0 {
        return n / 2.0;
    }
    let s = rates.f1 + rates.g1;
    if u > 0.0 {
        let phi = s / (2.0 * u);
        let e = -(-phi).exp_m1();
        n * (0.5 - e / (2.0 * phi) - e * u * u / (rates.g2 * rates.g2))
    } else {
        let w = -u;
        let alpha = s / (2.0 * w);
        let beta = rates.g1 / (2.0 * w);
        let e = -(-alpha).exp_m1();
        n * (0.5 - e / (2.0 * alpha) + e / (2.0 * beta))
    }
}

/// Q1 during the isometric rise from n = 0 at constant r: with `b = (f1+g1) t`,
/// `Q1 = n∞ [½ - (1 - (1+b) e^{-b}) / b²]`. The oracle of the grid's isometric rise (the
/// tests').
#[cfg(test)]
pub(crate) fn isometric_rise_q1(rates: &Rates, r: f64, t: f64) -> f64 {
    let n = plateau(rates, r);
    let b = (rates.f1 + rates.g1) * t;
    if b < 1e-4 {
        // Series of the bracket: b/3 - b²/8 + ...
        return n * (b / 3.0 - b * b / 8.0);
    }
    n * (0.5 - (1.0 - (1.0 + b) * (-b).exp()) / (b * b))
}

/// Unloaded shortening rate (h/s): the root of `steady_q1(u) = 0`, by bisection.
pub(crate) fn unloaded_shortening_rate(rates: &Rates) -> f64 {
    let (mut lo, mut hi) = (0.0, rates.f1 + rates.g1);
    while steady_q1(rates, 1.0, hi) > 0.0 {
        lo = hi;
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if steady_q1(rates, 1.0, mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
