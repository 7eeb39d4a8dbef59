//! Zahalak's Distribution-Moment (DM) approximation of the Huxley model (docs/model.md §6,
//! paper eqs. 9–12): the bond distribution is taken Gaussian with the moments Q0, Q1, Q2.

use crate::physics::contractile::closure_limits::ClosureLimits;
use crate::physics::contractile::crossbridge::Rates;
use nalgebra::{Matrix3, Vector3};

/// Smallest variance q² (in ξ² units) the closure accepts.
pub(crate) const Q_VARIANCE_FLOOR: f64 = 1e-10;
/// Largest |mean| of the bond distribution (in h) the closure takes as Gaussian: bonds form on
/// [0, 1] and detach fast outside it, so a physical distribution stays well inside.
pub(crate) const MEAN_BOUND: f64 = 10.0;
/// Largest variance (in h²) the closure takes as Gaussian, for the same reason.
pub(crate) const VARIANCE_BOUND: f64 = 100.0;

const INV_SQRT_2: f64 = std::f64::consts::FRAC_1_SQRT_2;
const INV_SQRT_2PI: f64 = 0.398_942_280_401_432_7;

/// Standard normal CDF Φ(x) = erfc(-x/√2)/2.
#[cfg(test)]
pub(crate) fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x * INV_SQRT_2)
}

/// Standard normal density ϕ(x).
#[cfg(test)]
pub(crate) fn normal_pdf(x: f64) -> f64 {
    INV_SQRT_2PI * (-0.5 * x * x).exp()
}

/// Φ(τ) and ϕ(τ) together, sharing one evaluation of `exp(-τ²/2)`.
///
/// Φ(τ) = erfc(x)/2 with x = -τ/√2. For |x| < 1.25, `libm::erfc` uses rational approximations
/// with no exponential; beyond, erfc(|x|) = exp(-x²) · exp(R(1/x²) - 0.5625) / |x| (FreeBSD's
/// s_erf.c, which `libm::erfc` ports), whose first factor is ϕ(τ)·√(2π): this takes it from ϕ
/// instead of computing it again (libm splits x to evaluate it in two exponentials), which
/// leaves one exponential of a small argument. Relative difference from
/// `normal_cdf`: within a few ulps of exp(-x²), i.e. about x² · 1e-16.
pub(crate) fn normal_cdf_pdf(tau: f64) -> (f64, f64) {
    let e = (-0.5 * tau * tau).exp();
    let pdf = INV_SQRT_2PI * e;
    let x = -tau * INV_SQRT_2;
    let ax = x.abs();
    if !(1.25..28.0).contains(&ax) {
        // Rational approximations near 0, limits far out (and NaN), as libm::erfc.
        return (0.5 * libm::erfc(x), pdf);
    }
    let tail = 0.5 * e * (erfc_tail_exponent(ax) - 0.5625).exp() / ax;
    (if x > 0.0 { tail } else { 1.0 - tail }, pdf)
}

/// `R(1/x²)` of erfc(x) = exp(-x² - 0.5625 + R) / x for 1.25 ≤ x < 28: FreeBSD s_erf.c's
/// rational approximations ra/sa (x < 1/0.35) and rb/sb, their coefficients copied from it
/// (through the `libm` crate 0.2.16, src/math/erf.rs). Written out here because `libm` does not
/// expose this part alone.
///
/// ====================================================
/// Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved.
///
/// Developed at SunPro, a Sun Microsystems, Inc. business.
/// Permission to use, copy, modify, and distribute this
/// software is freely granted, provided that this notice
/// is preserved.
/// ====================================================
#[allow(clippy::excessive_precision)]
fn erfc_tail_exponent(x: f64) -> f64 {
    let s = 1.0 / (x * x);
    // The same split point as s_erf.c: the high word of x below that of 1/0.35.
    if (x.to_bits() >> 32) < 0x4006db6d {
        const RA: [f64; 8] = [
            -9.86494403484714822705e-03,
            -6.93858572707181764372e-01,
            -1.05586262253232909814e+01,
            -6.23753324503260060396e+01,
            -1.62396669462573470355e+02,
            -1.84605092906711035994e+02,
            -8.12874355063065934246e+01,
            -9.81432934416914548592e+00,
        ];
        const SA: [f64; 9] = [
            1.0,
            1.96512716674392571292e+01,
            1.37657754143519042600e+02,
            4.34565877475229228821e+02,
            6.45387271733267880336e+02,
            4.29008140027567833386e+02,
            1.08635005541779435134e+02,
            6.57024977031928170135e+00,
            -6.04244152148580987438e-02,
        ];
        horner(&RA, s) / horner(&SA, s)
    } else {
        const RB: [f64; 7] = [
            -9.86494292470009928597e-03,
            -7.99283237680523006574e-01,
            -1.77579549177547519889e+01,
            -1.60636384855821916062e+02,
            -6.37566443368389627722e+02,
            -1.02509513161107724954e+03,
            -4.83519191608651397019e+02,
        ];
        const SB: [f64; 8] = [
            1.0,
            3.03380607434824582924e+01,
            3.25792512996573918826e+02,
            1.53672958608443695994e+03,
            3.19985821950859553908e+03,
            2.55305040643316442583e+03,
            4.74528541206955367215e+02,
            -2.24409524465858183362e+01,
        ];
        horner(&RB, s) / horner(&SB, s)
    }
}

/// The polynomial with coefficients `c` (constant first) at s.
fn horner(c: &[f64], s: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &k| acc * s + k)
}

/// Partial moments `J_k(τ) = ∫_{-∞}^{p+qτ} ξ^k N(ξ; p, q²) dξ`, k = 0..3 (docs/model.md §6),
/// from (Φ(τ), ϕ(τ)) given.
pub(crate) fn partial_moments_of(p: f64, q: f64, tau: f64, (cdf, pdf): (f64, f64)) -> [f64; 4] {
    let q2 = q * q;
    [
        cdf,
        p * cdf - q * pdf,
        (p * p + q2) * cdf - q * (2.0 * p + q * tau) * pdf,
        (p * p * p + 3.0 * p * q2) * cdf
            - q * pdf * (3.0 * p * p + 3.0 * p * q * tau + q2 * (2.0 + tau * tau)),
    ]
}

/// Full moments of N(p, q²): `(1, p, p² + q², p³ + 3 p q²)`.
pub(crate) fn full_moments(p: f64, q: f64) -> [f64; 4] {
    let q2 = q * q;
    [1.0, p, p * p + q2, p * p * p + 3.0 * p * q2]
}

/// The DM closure `φ_k = ∫ ξ^k (f + g) n dξ` for the Gaussian n with moments `q`, k = 0, 1, 2.
///
/// Moments no Gaussian has (Q0 ≤ 0, or a mean or variance outside the physical bounds: numerical
/// noise once the bonds are nearly all gone) are split into the nearest Gaussian part and a
/// remainder that relaxes linearly at the mean rate `(f1 + g1)/2` (docs/model.md §6). The split is
/// continuous in `q`, so the implicit solver's Newton iteration sees no jump as Q0 crosses zero.
#[cfg(test)]
pub(crate) fn closure(rates: &Rates, q: &[f64; 3]) -> [f64; 3] {
    closure_keeping(rates, q, None)
}

/// [`closure`], keeping Φ and ϕ at its two limits in `limits` when given (for the fluxes at the
/// tick's end, [`crate::physics::contractile::closure_limits`]).
pub(crate) fn closure_keeping(
    rates: &Rates,
    q: &[f64; 3],
    limits: Option<&ClosureLimits>,
) -> [f64; 3] {
    let k = 0.5 * (rates.f1 + rates.g1);
    let q0 = q[0];
    if q0 <= 0.0 {
        return [k * q[0], k * q[1], k * q[2]];
    }
    let p = (q[1] / q0).clamp(-MEAN_BOUND, MEAN_BOUND);
    let var = (q[2] / q0 - p * p).clamp(Q_VARIANCE_FLOOR, VARIANCE_BOUND);
    let sd = var.sqrt();
    let tau0 = -p / sd;
    let tau1 = (1.0 - p) / sd;
    let (l0, l1) = (normal_cdf_pdf(tau0), normal_cdf_pdf(tau1));
    if let Some(kept) = limits {
        kept.keep(0, tau0, l0);
        kept.keep(1, tau1, l1);
    }
    let j0 = partial_moments_of(p, sd, tau0, l0);
    let j1 = partial_moments_of(p, sd, tau1, l1);
    let m = full_moments(p, sd);
    let mut phi = [0.0; 3];
    for (k, out) in phi.iter_mut().enumerate() {
        let body = rates.g2 * j0[k]
            + (rates.f1 + rates.g1) * (j1[k + 1] - j0[k + 1])
            + rates.g1 * (m[k + 1] - j1[k + 1])
            + rates.g3 * (m[k + 1] - j1[k + 1] - m[k] + j1[k]);
        *out = q0 * body;
    }
    // The part of Q1, Q2 the Gaussian (p, sd) does not carry: zero for physical moments.
    phi[1] += k * (q[1] - q0 * m[1]);
    phi[2] += k * (q[2] - q0 * m[2]);
    phi
}

/// Moment equations (12): `dQ_k/dt = r β_k - φ_k - k u Q_{k-1}`; `u` is the shortening rate in
/// h/s (u > 0 shortening), `r` the attachment factor a·λ(l_m).
pub(crate) fn moment_rates(rates: &Rates, q: &[f64; 3], r: f64, u: f64) -> [f64; 3] {
    moment_rates_keeping(rates, q, r, u, None)
}

/// [`moment_rates`], its closure keeping its limits' values in `limits` when given.
pub(crate) fn moment_rates_keeping(
    rates: &Rates,
    q: &[f64; 3],
    r: f64,
    u: f64,
    limits: Option<&ClosureLimits>,
) -> [f64; 3] {
    let phi = closure_keeping(rates, q, limits);
    [
        r * rates.beta(0) - phi[0],
        r * rates.beta(1) - phi[1] - u * q[0],
        r * rates.beta(2) - phi[2] - 2.0 * u * q[1],
    ]
}

/// Why a steady state could not be found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the Distribution-Moment steady state did not converge ({0})")]
pub struct SteadyStateError(pub &'static str);

/// The steady state `moment_rates = 0` at attachment factor r and shortening rate u, by damped
/// Newton from `guess`.
pub(crate) fn steady_state(
    rates: &Rates,
    r: f64,
    u: f64,
    guess: [f64; 3],
) -> Result<[f64; 3], SteadyStateError> {
    let residual = |q: &Vector3<f64>| Vector3::from(moment_rates(rates, &[q[0], q[1], q[2]], r, u));
    let mut q = Vector3::from(guess);
    for _ in 0..200 {
        let f = residual(&q);
        let scale = rates.f1.max(rates.g2) * r.max(1e-300);
        if f.norm() <= 1e-14 * scale {
            return Ok([q[0], q[1], q[2]]);
        }
        let mut jac = Matrix3::zeros();
        for j in 0..3 {
            let h = 1e-7 * q[j].abs().max(1e-3 * r.max(1e-12));
            let mut qp = q;
            qp[j] += h;
            let mut qm = q;
            qm[j] -= h;
            jac.set_column(j, &((residual(&qp) - residual(&qm)) / (2.0 * h)));
        }
        let step = jac
            .lu()
            .solve(&(-f))
            .ok_or(SteadyStateError("singular Jacobian"))?;
        let mut lambda = 1.0;
        let f_norm = f.norm();
        loop {
            let trial = q + step * lambda;
            let valid = trial[0] > 0.0 && trial[2] / trial[0] > (trial[1] / trial[0]).powi(2);
            if valid && residual(&trial).norm() < f_norm * (1.0 - 1e-4 * lambda) {
                q = trial;
                break;
            }
            lambda *= 0.5;
            if lambda < 1e-10 {
                // Converged as far as rounding allows.
                if f_norm <= 1e-10 * scale {
                    return Ok([q[0], q[1], q[2]]);
                }
                return Err(SteadyStateError("line search failed"));
            }
        }
    }
    Err(SteadyStateError("too many iterations"))
}

/// The isometric steady state at r = 1 (docs/model.md §6: (0.684179, 0.437663, 0.321696) with
/// Huxley's rates).
pub(crate) fn isometric_steady_state(rates: &Rates) -> Result<[f64; 3], SteadyStateError> {
    // The exact isometric distribution (f1/(f1+g1) on [0,1]) is a good start.
    let n = rates.f1 / (rates.f1 + rates.g1);
    steady_state(rates, 1.0, 0.0, [n, n / 2.0, n / 3.0])
}

/// Steady moments at r = 1 for each shortening rate in `us` (ascending from 0 or descending
/// from 0), by continuation from the isometric state.
pub fn steady_curve(rates: &Rates, us: &[f64]) -> Result<Vec<[f64; 3]>, SteadyStateError> {
    let mut q = isometric_steady_state(rates)?;
    let mut u_prev = 0.0;
    let mut out = Vec::with_capacity(us.len());
    for &u in us {
        // Small continuation steps keep Newton in its basin.
        let n = ((u - u_prev).abs() / (0.02 * rates.f1)).ceil().max(1.0) as usize;
        for i in 1..=n {
            let ui = u_prev + (u - u_prev) * i as f64 / n as f64;
            q = steady_state(rates, 1.0, ui, q)?;
        }
        u_prev = u;
        out.push(q);
    }
    Ok(out)
}

/// The unloaded shortening rate (h/s): the u at which the steady Q1 is zero.
pub(crate) fn unloaded_shortening_rate(rates: &Rates) -> Result<f64, SteadyStateError> {
    let mut q = isometric_steady_state(rates)?;
    let du = 0.05 * rates.f1;
    let mut u = 0.0;
    // March until Q1 changes sign, then bisect on the bracket.
    loop {
        let next = steady_state(rates, 1.0, u + du, q)?;
        if next[1] <= 0.0 {
            let (mut lo, mut hi, mut q_lo) = (u, u + du, q);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                let qm = steady_state(rates, 1.0, mid, q_lo)?;
                if qm[1] > 0.0 {
                    lo = mid;
                    q_lo = qm;
                } else {
                    hi = mid;
                }
                if hi - lo <= 1e-13 * hi {
                    break;
                }
            }
            return Ok(0.5 * (lo + hi));
        }
        q = next;
        u += du;
        if u > 1e3 * rates.f1 {
            return Err(SteadyStateError("no unloaded velocity found"));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn huxley_rates() -> Rates {
        Rates {
            f1: 43.3,
            g1: 10.0,
            g2: 209.0,
            g3: 0.0,
        }
    }

    /// The closure is continuous in the moments, also where they stop being a distribution's
    /// (Q0 crossing zero with Q1, Q2 ≠ 0, as the integrator's noise leaves them in a relaxed
    /// muscle): the implicit solver's Newton iteration must never meet a jump there.
    #[test]
    fn closure_is_continuous_where_bonds_vanish() {
        let rates = huxley_rates();
        for (q1, q2) in [(1e-7, 5e-7), (-1e-7, 5e-7), (1e-9, 1e-12), (0.0, 0.0)] {
            for q0 in [0.0f64, 1e-12, 1e-11, 1e-10, 1e-9] {
                let d = 1e-6 * q0.max(1e-15);
                let lo = closure(&rates, &[q0 - d, q1, q2]);
                let hi = closure(&rates, &[q0 + d, q1, q2]);
                for k in 0..3 {
                    let jump = (hi[k] - lo[k]).abs();
                    // A Lipschitz bound: rates of at most a few times g2 per unit of moment.
                    assert!(
                        jump <= 1e4 * rates.g2 * 2.0 * d + 1e-300,
                        "φ{k} jumps by {jump:e} at Q0 = {q0:e} (Q1 = {q1:e}, Q2 = {q2:e})"
                    );
                }
            }
        }
    }

    /// Φ and ϕ computed together agree with the separate functions (libm's erfc) to a few ulps
    /// of exp(-τ²/2), on both sides of every branch of erfc.
    #[test]
    fn shared_exponential_keeps_cdf_and_pdf() {
        let mut tau = -40.0;
        while tau <= 40.0 {
            let (cdf, pdf) = normal_cdf_pdf(tau);
            let (c, d) = (normal_cdf(tau), normal_pdf(tau));
            let tol = 4.0 * f64::EPSILON * (1.0 + 0.5 * tau * tau);
            // Far in the tail both underflow to subnormals, where ulps are absolute.
            let err = (cdf - c).abs();
            assert!(
                err <= tol * c.abs() + f64::MIN_POSITIVE,
                "Φ({tau}) = {cdf:e}, libm {c:e}"
            );
            assert_eq!(pdf, d, "ϕ({tau})");
            tau += 0.0137;
        }
        assert!(normal_cdf_pdf(f64::NAN).0.is_nan());
    }

    /// Physical moments never reach the guard: the isometric steady state's closure balances
    /// attachment exactly (`φ = β` at r = 1), as the plain Gaussian closure does.
    #[test]
    fn closure_is_the_gaussian_one_for_physical_moments() {
        let rates = huxley_rates();
        let q = isometric_steady_state(&rates).unwrap();
        let phi = closure(&rates, &q);
        for (k, phi_k) in phi.iter().enumerate() {
            assert!((phi_k - rates.beta(k)).abs() < 1e-12 * rates.beta(k).abs().max(1.0));
        }
    }
}
