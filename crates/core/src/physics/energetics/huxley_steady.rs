//! Steady isovelocity energetics of the full Huxley (1957) model in closed form
//! (docs/model.md §11.3), with g3 = 0 as in `contractile::huxley_exact`.
//!
//! At constant shortening rate u (h/s; negative when lengthening) and attachment factor r, with
//! `N = f1/(f1 + g1)` and `φ = (f1 + g1)/(2|u|)`, the steady bound fraction is
//!
//! ```text
//! shortening:  n = r N (1 - e^{-φ(1-ξ²)}) on [0, 1],  n(0) e^{g2 ξ/u} for ξ < 0,  0 beyond 1
//! lengthening: n = r N (1 - e^{-φ ξ²}) on [0, 1],      n(1) e^{-g1 (ξ²-1)/(2|u|)} beyond 1
//! ```
//!
//! and the fluxes of `energetics::bridge_flux` follow by integration. In a steady state
//! attachment balances detachment, `A_0 = D_0`, and the strain balance of eq. (12) for Q2 reads
//! `A_2 - D_2 = 2 u Q1`.

use crate::physics::contractile::crossbridge::Rates;
use crate::physics::energetics::bridge_flux::EnergyFluxes;

/// `N = f1/(f1 + g1)`.
fn plateau(rates: &Rates) -> f64 {
    rates.f1 / (rates.f1 + rates.g1)
}

/// `φ = (f1 + g1)/(2|u|)` (infinite when isometric).
fn phi(rates: &Rates, u: f64) -> f64 {
    (rates.f1 + rates.g1) / (2.0 * u.abs())
}

/// `∫_0^1 e^{-φ s} ds = (1 - e^{-φ})/φ` (1 at φ = 0, 0 at φ = ∞).
fn mean_exp(phi: f64) -> f64 {
    if phi.is_infinite() {
        0.0
    } else if phi == 0.0 {
        1.0
    } else {
        -(-phi).exp_m1() / phi
    }
}

/// `∫_0^1 s e^{-φ s} ds = (1 - (1 + φ) e^{-φ})/φ²`, by its series below φ = 0.01 (error
/// below 1e-13, where the closed form loses digits).
fn first_moment_exp(phi: f64) -> f64 {
    if phi.is_infinite() {
        0.0
    } else if phi < 0.01 {
        0.5 - phi / 3.0 + phi * phi / 8.0 - phi.powi(3) / 30.0 + phi.powi(4) / 144.0
    } else {
        (-(-phi).exp_m1() - phi * (-phi).exp()) / (phi * phi)
    }
}

/// `∫_0^1 ξ³ e^{-φ(1-ξ²)} dξ` when shortening, `∫_0^1 ξ³ e^{-φ ξ²} dξ` when lengthening.
fn cubic_exp(phi: f64, shortening: bool) -> f64 {
    if shortening {
        0.5 * (mean_exp(phi) - first_moment_exp(phi))
    } else {
        0.5 * first_moment_exp(phi)
    }
}

/// The steady bound fraction n(ξ) at shortening rate u (h/s) and attachment factor r.
#[cfg(test)]
pub(crate) fn steady_bonds(rates: &Rates, r: f64, u: f64, xi: f64) -> f64 {
    let n = r * plateau(rates);
    let s = rates.f1 + rates.g1;
    if u == 0.0 {
        return if (0.0..=1.0).contains(&xi) { n } else { 0.0 };
    }
    if u > 0.0 {
        let edge = n * -(-s / (2.0 * u)).exp_m1();
        match xi {
            x if x < 0.0 => edge * (rates.g2 * x / u).exp(),
            x if x <= 1.0 => n * -(-s * (1.0 - x * x) / (2.0 * u)).exp_m1(),
            _ => 0.0,
        }
    } else {
        let w = -u;
        let edge = n * -(-s / (2.0 * w)).exp_m1();
        match xi {
            x if x < 0.0 => 0.0,
            x if x <= 1.0 => n * -(-s * x * x / (2.0 * w)).exp_m1(),
            x => edge * (-rates.g1 * (x * x - 1.0) / (2.0 * w)).exp(),
        }
    }
}

/// Steady ATP flux `D_0 = A_0 = r (f1/2) [(1 - N) + N (1 - e^{-φ})/φ]`, 1/s (moment units).
/// The same in both directions: Huxley's (1957) energy rate rises on lengthening too.
pub(crate) fn steady_atp_flux(rates: &Rates, r: f64, u: f64) -> f64 {
    let n = plateau(rates);
    r * 0.5 * rates.f1 * ((1.0 - n) + n * mean_exp(phi(rates, u)))
}

/// Huxley's (1957) energy rate over its isometric value,
/// `Ė/Ė0 = 1 + (f1/g1) (1 - e^{-φ})/φ` (φ = (f1 + g1)/(2|u|)).
pub fn energy_rate_ratio(rates: &Rates, u: f64) -> f64 {
    1.0 + rates.f1 / rates.g1 * mean_exp(phi(rates, u))
}

/// Steady strain flux in at attachment, `A_2 = r f1 [(1 - N)/4 + N ∫_0^1 ξ³ e^{…} dξ]`.
pub(crate) fn steady_attachment_strain_flux(rates: &Rates, r: f64, u: f64) -> f64 {
    let n = plateau(rates);
    r * rates.f1 * ((1.0 - n) / 4.0 + n * cubic_exp(phi(rates, u), u > 0.0))
}

/// Steady strain flux out at detachment, `D_2 = ∫ ξ² g n dξ`: on [0, 1]
/// `r g1 N [1/4 - ∫_0^1 ξ³ e^{…} dξ]`, plus the tail: `2 n(0) u³/g2²` below 0 when shortening,
/// `g1 n(1) (1/β + 1/β²)/2` with `β = g1/(2|u|)` beyond 1 when lengthening.
pub(crate) fn steady_detachment_strain_flux(rates: &Rates, r: f64, u: f64) -> f64 {
    let n = r * plateau(rates);
    let ph = phi(rates, u);
    let inner = rates.g1 * n * (0.25 - cubic_exp(ph, u > 0.0));
    // n(0) when shortening, n(1) when lengthening: r N (1 - e^{-φ}).
    let edge = n * -(-ph).exp_m1();
    let tail = if u > 0.0 {
        2.0 * edge * u.powi(3) / (rates.g2 * rates.g2)
    } else if u < 0.0 {
        let beta = rates.g1 / (2.0 * -u);
        0.5 * rates.g1 * edge * (1.0 / beta + 1.0 / (beta * beta))
    } else {
        0.0
    };
    inner + tail
}

/// The four energy fluxes of the steady state (`A_0 = D_0`).
pub(crate) fn steady_energy_fluxes(rates: &Rates, r: f64, u: f64) -> EnergyFluxes {
    let atp = steady_atp_flux(rates, r, u);
    EnergyFluxes {
        attachment: atp,
        detachment: atp,
        strain_in: steady_attachment_strain_flux(rates, r, u),
        strain_out: steady_detachment_strain_flux(rates, r, u),
    }
}
