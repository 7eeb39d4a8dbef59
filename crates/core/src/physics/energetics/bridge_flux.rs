//! Attachment and detachment fluxes of the bond distribution (docs/model.md §11.1).
//!
//! With `n(ξ, t)` the bound fraction and `r = a λ` the attachment factor, eq. (9)'s right-hand
//! side splits into attachment `f (r - n)` and detachment `g n`. Their ξ^k-weighted integrals,
//!
//! ```text
//! A_k = ∫ ξ^k f(ξ) (r - n) dξ = r β_k - ∫ ξ^k f n dξ,     D_k = ∫ ξ^k g(ξ) n dξ,
//! ```
//!
//! give the rate of new bonds (A_0), of broken bonds (D_0: one ATP each, Huxley 1957) and the
//! strain they carry in and out (A_2, D_2, in units of the bridge energy at ξ = 1). Together
//! `∫ ξ^k f n + D_k = φ_k`, the closure of eq. (12), so `dQ_k/dt = A_k - D_k - k u Q_{k-1}`.
//! Units are those of the moments per second: per unit density of bridges in ξ.

use crate::physics::contractile::closure_limits::ClosureLimits;
use crate::physics::contractile::crossbridge::Rates;
use crate::physics::contractile::distribution_moment::{
    full_moments, normal_cdf_pdf, partial_moments_of, MEAN_BOUND, Q_VARIANCE_FLOOR, VARIANCE_BOUND,
};
use crate::physics::contractile::huxley_grid::CrossBridgeGrid;

/// The ξ^k-weighted fluxes, k = 0, 1, 2, 1/s.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct BridgeFluxes {
    /// Attachment `A_k = ∫ ξ^k f (r - n) dξ`.
    pub attachment: [f64; 3],
    /// Detachment `D_k = ∫ ξ^k g n dξ`; D_0 is the ATP flux.
    pub detachment: [f64; 3],
}

impl BridgeFluxes {
    /// The four fluxes the energetics needs.
    pub(crate) fn energy(&self) -> EnergyFluxes {
        EnergyFluxes {
            attachment: self.attachment[0],
            detachment: self.detachment[0],
            strain_in: self.attachment[2],
            strain_out: self.detachment[2],
        }
    }
}

/// The fluxes that carry energy, 1/s (moment units).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct EnergyFluxes {
    /// Bonds formed, A_0.
    pub attachment: f64,
    /// Bonds broken, D_0: the ATP flux.
    pub detachment: f64,
    /// Strain brought in by new bonds, A_2 (units of the strain at ξ = 1).
    pub(crate) strain_in: f64,
    /// Strain taken out by broken bonds, D_2.
    pub(crate) strain_out: f64,
}

/// The rates with attachment only (`f1`; every `g` zero).
fn attachment_only(rates: &Rates) -> Rates {
    Rates {
        f1: rates.f1,
        g1: 0.0,
        g2: 0.0,
        g3: 0.0,
    }
}

/// The rates with detachment only (`f1 = 0`).
fn detachment_only(rates: &Rates) -> Rates {
    Rates { f1: 0.0, ..*rates }
}

/// `A_k = r β_k - ∫ ξ^k f n dξ`, from the bound part of the attachment integral.
pub(crate) fn attachment(rates: &Rates, r: f64, bound_attachment: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| r * rates.beta(k) - bound_attachment[k])
}

/// The Gaussian the DM closure takes for moments `q`, as `distribution_moment::closure` clamps
/// it: `(Q0, p, q)` with `p = Q1/Q0` in [-10, 10] and `q² = Q2/Q0 - p²` in [1e-10, 100]
/// (docs/model.md §6, Guards), with `1/q`; `None` when Q0 ≤ 0 (no Gaussian part). One division
/// for the two ratios and one for `1/q`: a tick's end evaluates this for every muscle, and a
/// division's latency is what its time is made of.
fn closure_gaussian(q: &[f64; 3]) -> Option<(f64, f64, f64, f64)> {
    if q[0] <= 0.0 {
        return None;
    }
    let inv_q0 = 1.0 / q[0];
    let p = (q[1] * inv_q0).clamp(-MEAN_BOUND, MEAN_BOUND);
    let var = (q[2] * inv_q0 - p * p).clamp(Q_VARIANCE_FLOOR, VARIANCE_BOUND);
    let sd = var.sqrt();
    Some((q[0], p, sd, 1.0 / sd))
}

/// DM detachment moments `D_k = ∫ ξ^k g n dξ` for the Gaussian n with moments `q`:
///
/// ```text
/// D_k = Q0 { g2 J_k(τ0) + g1 [M_{k+1} - J_{k+1}(τ0)] + g3 [M_{k+1} - J_{k+1}(τ1) - M_k + J_k(τ1)] }
/// ```
///
/// (τ0 = -p/q, τ1 = (1-p)/q; J, M of docs/model.md §6). For k = 0 this is
/// `Q0 [g2 Φ(-p/q) + g1 (p Φ(p/q) + q ϕ(p/q)) + g3 (...)]`. The part of the moments the guard's
/// Gaussian does not carry (zero for physical moments), which the closure relaxes at
/// `(f1 + g1)/2`, counts as detachment, so that `gaussian_bound_attachment + this = φ` exactly.
#[cfg(test)]
pub(crate) fn gaussian_detachment(rates: &Rates, q: &[f64; 3]) -> [f64; 3] {
    gaussian_parts(rates, q, None).1
}

/// DM bound part of the attachment integral, `∫ ξ^k f n dξ = Q0 f1 [J_{k+1}(τ1) - J_{k+1}(τ0)]`
/// (zero without a Gaussian part).
#[cfg(test)]
pub(crate) fn gaussian_bound_attachment(rates: &Rates, q: &[f64; 3]) -> [f64; 3] {
    gaussian_parts(rates, q, None).0
}

/// Both DM integrals, (bound attachment, detachment), from one evaluation of the Gaussian's
/// partial moments (the error functions and exponentials are the cost).
/// Φ and ϕ at the limits are taken from `limits` where it keeps them near enough
/// ([`ClosureLimits::near`]), else evaluated.
fn gaussian_parts(
    rates: &Rates,
    q: &[f64; 3],
    limits: Option<&ClosureLimits>,
) -> ([f64; 3], [f64; 3]) {
    let relax = 0.5 * (rates.f1 + rates.g1);
    let Some((q0, p, sd, inv_sd)) = closure_gaussian(q) else {
        return ([0.0; 3], q.map(|x| relax * x));
    };
    let at = |i: usize, tau: f64| {
        let values = limits
            .and_then(|l| l.near(i, tau))
            .unwrap_or_else(|| normal_cdf_pdf(tau));
        partial_moments_of(p, sd, tau, values)
    };
    let j0 = at(0, -p * inv_sd);
    let j1 = at(1, (1.0 - p) * inv_sd);
    let m = full_moments(p, sd);
    let bound = [0, 1, 2].map(|k| q0 * rates.f1 * (j1[k + 1] - j0[k + 1]));
    let mut d = [0.0; 3];
    for (k, out) in d.iter_mut().enumerate() {
        let body = rates.g2 * j0[k]
            + rates.g1 * (m[k + 1] - j0[k + 1])
            + rates.g3 * (m[k + 1] - j1[k + 1] - m[k] + j1[k]);
        *out = q0 * body;
    }
    d[1] += relax * (q[1] - q0 * m[1]);
    d[2] += relax * (q[2] - q0 * m[2]);
    (bound, d)
}

/// Both fluxes of the DM model at moments `q` and attachment factor `r`.
pub(crate) fn gaussian_fluxes(rates: &Rates, r: f64, q: &[f64; 3]) -> BridgeFluxes {
    gaussian_fluxes_near(rates, r, q, None)
}

/// [`gaussian_fluxes`] with Φ and ϕ at the limits from the last closure evaluation's where they
/// are near enough (docs/model.md §11.1, Cost): equal to a fresh evaluation to rounding.
pub(crate) fn gaussian_fluxes_near(
    rates: &Rates,
    r: f64,
    q: &[f64; 3],
    limits: Option<&ClosureLimits>,
) -> BridgeFluxes {
    let (bound, detachment) = gaussian_parts(rates, q, limits);
    BridgeFluxes {
        attachment: attachment(rates, r, bound),
        detachment,
    }
}

/// Grid detachment moments `D_k`: the grid's own quadrature of `∫ ξ^k g n dξ` (its closure with
/// the attachment rate set to zero, so cells that straddle ξ = 0 or 1 are split as in φ).
pub(crate) fn grid_detachment(grid: &CrossBridgeGrid, rates: &Rates) -> [f64; 3] {
    grid.closure(&detachment_only(rates))
}

/// Grid bound part of the attachment integral, `∫ ξ^k f n dξ` (its closure with every
/// detachment rate set to zero).
pub(crate) fn grid_bound_attachment(grid: &CrossBridgeGrid, rates: &Rates) -> [f64; 3] {
    grid.closure(&attachment_only(rates))
}

/// Both fluxes of the full model's grid at attachment factor `r`.
pub(crate) fn grid_fluxes(grid: &CrossBridgeGrid, rates: &Rates, r: f64) -> BridgeFluxes {
    BridgeFluxes {
        attachment: attachment(rates, r, grid_bound_attachment(grid, rates)),
        detachment: grid_detachment(grid, rates),
    }
}
