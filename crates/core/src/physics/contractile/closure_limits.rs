//! Φ and ϕ at the DM closure's two integration limits, kept from one evaluation to the next
//! (docs/model.md §11.1, Cost).
//!
//! The closure and the bridges' fluxes integrate the Gaussian between the same limits,
//! τ0 = -p/q and τ1 = (1-p)/q, and their cost is the error function and the exponential there
//! (`distribution_moment::normal_cdf_pdf`). A run asks for the fluxes once per tick, at the
//! tick's end state, and the stepper's last closure evaluation was at its last Newton iterate,
//! a correction below the Newton tolerance away. There the fluxes take Φ and ϕ from the kept
//! values by the Taylor series to third order,
//!
//! ```text
//! Φ(τ+Δ) = Φ + ϕ (Δ - τ Δ²/2 + (τ² - 1) Δ³/6),   ϕ(τ+Δ) = ϕ (1 - τ Δ + (τ² - 1) Δ²/2 - (τ³ - 3τ) Δ³/6)
//! ```
//!
//! (Φ' = ϕ, ϕ' = -τ ϕ). The fourth derivatives are ϕ times `-(τ³ - 3τ)` and `τ⁴ - 6τ² + 3`,
//! both at most `3 (1 + |τ|)⁴` in size, so the remainder is below `ϕ ((1 + |τ|) |Δ|)⁴ / 8`:
//! for `(1 + |τ|) |Δ| ≤ 1e-4`, below 1.3e-17 of ϕ — a tenth of a rounding of both values, also
//! in the lower tail where Φ is itself about ϕ / |τ|. Farther away the caller evaluates them.
//! (The stepper's last correction moves τ by about 1e-9 to 8e-5 in the elbow's ticks.)
//!
//! The kept values are not state: each tick's stepper writes them before the fluxes read them,
//! so a run, its replay and a restored snapshot compute the same fluxes to the bit.

use std::sync::atomic::{AtomicU64, Ordering};

/// Largest `(1 + |τ|) |Δ|` the Taylor series is used for.
pub(crate) const TAYLOR_REACH: f64 = 1e-4;

/// Φ(τ) and ϕ(τ) at the two limits of the last closure evaluation, as f64 bits: the model is
/// shared read-only between the stepper's calls (`&self`), and one run steps it from one thread
/// at a time, so relaxed atomics are plain loads and stores here.
#[derive(Debug)]
pub(crate) struct ClosureLimits {
    /// Per limit: τ, Φ(τ), ϕ(τ).
    kept: [[AtomicU64; 3]; 2],
}

/// Nothing kept: τ is NaN, within no reach of any τ.
impl Default for ClosureLimits {
    fn default() -> Self {
        let none = || {
            [
                AtomicU64::new(f64::NAN.to_bits()),
                AtomicU64::new(0),
                AtomicU64::new(0),
            ]
        };
        Self {
            kept: [none(), none()],
        }
    }
}

impl Clone for ClosureLimits {
    fn clone(&self) -> Self {
        let out = Self::default();
        for (o, k) in out.kept.iter().zip(&self.kept) {
            for (a, b) in o.iter().zip(k) {
                a.store(b.load(Ordering::Relaxed), Ordering::Relaxed);
            }
        }
        out
    }
}

impl ClosureLimits {
    /// Keeps (Φ, ϕ) = `values` at limit `i` (0: τ0, 1: τ1), τ = `tau`.
    pub(crate) fn keep(&self, i: usize, tau: f64, values: (f64, f64)) {
        let k = &self.kept[i];
        k[0].store(tau.to_bits(), Ordering::Relaxed);
        k[1].store(values.0.to_bits(), Ordering::Relaxed);
        k[2].store(values.1.to_bits(), Ordering::Relaxed);
    }

    /// (Φ, ϕ) at τ for limit i from the kept values, where τ is within [`TAYLOR_REACH`] of
    /// theirs; `None` farther away (or with nothing kept).
    pub(crate) fn near(&self, i: usize, tau: f64) -> Option<(f64, f64)> {
        let k = &self.kept[i];
        let t0 = f64::from_bits(k[0].load(Ordering::Relaxed));
        let d = tau - t0;
        #[allow(
            clippy::neg_cmp_op_on_partial_ord,
            reason = "a NaN distance is not near: the negated comparison gives None for it"
        )]
        if !((1.0 + t0.abs()) * d.abs() <= TAYLOR_REACH) {
            return None;
        }
        let cdf = f64::from_bits(k[1].load(Ordering::Relaxed));
        let pdf = f64::from_bits(k[2].load(Ordering::Relaxed));
        Some(taylor(t0, cdf, pdf, d))
    }
}

/// 1/6, the third-order terms' factor (a product rather than a division by 6).
const SIXTH: f64 = 1.0 / 6.0;

/// Φ and ϕ at τ + Δ from their values at τ, the series of the module's comment.
pub(crate) fn taylor(tau: f64, cdf: f64, pdf: f64, d: f64) -> (f64, f64) {
    let t2 = tau * tau - 1.0;
    let d2 = d * d;
    let d3_6 = d2 * d * SIXTH;
    let cdf_step = d - 0.5 * tau * d2 + t2 * d3_6;
    let pdf_factor = 1.0 - tau * d + 0.5 * t2 * d2 - (tau * tau * tau - 3.0 * tau) * d3_6;
    (cdf + pdf * cdf_step, pdf * pdf_factor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::contractile::distribution_moment::normal_cdf_pdf;

    fn relative(a: f64, b: f64) -> f64 {
        if a == b {
            0.0
        } else {
            (a - b).abs() / a.abs().max(b.abs())
        }
    }

    /// Within the reach the series agrees with a fresh evaluation to rounding (that evaluation's
    /// own, which grows as τ² in the tails), from the far lower tail (Φ ~ 1e-98) to the upper
    /// one; beyond it nothing is given.
    #[test]
    fn the_series_is_the_evaluation_to_rounding_within_its_reach() {
        let limits = ClosureLimits::default();
        for tau in [-21.0, -8.5, -3.0, -1.3, -0.4, 0.0, 0.2, 1.0, 2.7, 6.0, 12.0] {
            limits.keep(0, tau, normal_cdf_pdf(tau));
            let reach = TAYLOR_REACH / (1.0 + f64::abs(tau));
            for frac in [-0.999, -0.37, -1e-3, 0.0, 1e-6, 0.5, 0.999] {
                let t = tau + frac * reach;
                let (c, p) = limits.near(0, t).unwrap();
                let (ce, pe) = normal_cdf_pdf(t);
                // normal_cdf_pdf itself is within about τ² · 1e-16 of Φ in the tails.
                let tol = 1e-15 * (1.0 + tau * tau);
                assert!(relative(c, ce) < tol, "Φ at {t}: {c:e} vs {ce:e}");
                assert!(relative(p, pe) < tol, "ϕ at {t}: {p:e} vs {pe:e}");
            }
            // Beyond the reach: left to a fresh evaluation.
            assert_eq!(limits.near(0, tau + 3.0 * reach), None);
            assert_eq!(limits.near(0, tau - 3.0 * reach), None);
        }
        // Nothing kept: nothing given, also at τ = 0; a clone keeps what its original kept.
        let fresh = ClosureLimits::default();
        assert_eq!(fresh.near(1, 0.0), None);
        assert_eq!(limits.clone().near(0, 12.0), limits.near(0, 12.0));
    }
}
