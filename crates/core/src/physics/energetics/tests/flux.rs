//! The fluxes of `bridge_flux`: the DM closed forms against quadrature of the Gaussian they
//! integrate, and both models' fluxes against the closure φ of eq. (12) they must split.

use super::quadrature::piecewise;
use super::{assert_rel, HUXLEY};
use crate::physics::contractile::crossbridge::Rates;
use crate::physics::contractile::distribution_moment::{self as dm, normal_cdf, normal_pdf};
use crate::physics::contractile::huxley_grid::CrossBridgeGrid;
use crate::physics::energetics::bridge_flux::*;

/// `∫ ξ^k rate(ξ) Q0 N(ξ; p, sd²) dξ` by quadrature, split at the rates' breakpoints.
fn gaussian_integral(rate: impl Fn(f64) -> f64, q0: f64, p: f64, sd: f64, k: i32) -> f64 {
    let density = |x: f64| q0 * normal_pdf((x - p) / sd) / sd;
    let (lo, hi) = (p - 14.0 * sd, p + 14.0 * sd);
    let breaks = [lo, 0.0f64.clamp(lo, hi), 1.0f64.clamp(lo, hi), hi];
    piecewise(|x| x.powi(k) * rate(x) * density(x), &breaks, 400)
}

/// Moments (Q0, Q0 p, Q0 (p² + sd²)) of a Gaussian.
fn moments(q0: f64, p: f64, sd: f64) -> [f64; 3] {
    [q0, q0 * p, q0 * (p * p + sd * sd)]
}

/// Distributions the DM model meets: its isometric state, shortening and lengthening, wide
/// and narrow, centred off the attachment range.
const GAUSSIANS: [(f64, f64, f64); 6] = [
    (0.684179, 0.639688, 0.246958),
    (0.4, 0.3, 0.35),
    (0.2, -0.1, 0.2),
    (0.6, 1.3, 0.5),
    (0.05, 0.5, 0.02),
    (1.0, 2.5, 1.5),
];

#[test]
fn dm_closed_forms_match_quadrature_of_the_gaussian() {
    let with_g3 = Rates { g3: 57.0, ..HUXLEY };
    for rates in [HUXLEY, with_g3] {
        for (q0, p, sd) in GAUSSIANS {
            let q = moments(q0, p, sd);
            let det = gaussian_detachment(&rates, &q);
            let bound = gaussian_bound_attachment(&rates, &q);
            for k in 0..3 {
                let want = gaussian_integral(|x| rates.detach(x), q0, p, sd, k as i32);
                assert_rel(det[k], want, 1e-9, 1e-12, &format!("D_{k} at {q:?}"));
                let want = gaussian_integral(|x| rates.attach(x), q0, p, sd, k as i32);
                assert_rel(bound[k], want, 1e-9, 1e-12, &format!("∫ξ^{k} f n at {q:?}"));
            }
        }
    }
}

/// The ATP flux in the form `Q0 [g2 Φ(-p/q) + g1 (p Φ(p/q) + q ϕ(p/q))]` (g3 = 0).
#[test]
fn dm_atp_flux_has_the_two_term_closed_form() {
    for (q0, p, sd) in GAUSSIANS {
        let t = p / sd;
        let want = q0
            * (HUXLEY.g2 * normal_cdf(-t) + HUXLEY.g1 * (p * normal_cdf(t) + sd * normal_pdf(t)));
        let got = gaussian_detachment(&HUXLEY, &moments(q0, p, sd))[0];
        assert_rel(got, want, 1e-13, 1e-300, "ψ0");
    }
}

/// `∫ ξ^k f n + D_k = φ_k` for the DM closure, also where its guards act (no Gaussian part,
/// clamped mean and variance), so `dQ/dt = A - D - k u Q_{k-1}` holds with the model's own φ.
#[test]
fn dm_fluxes_split_the_closure() {
    let mut cases: Vec<[f64; 3]> = GAUSSIANS
        .iter()
        .map(|&(a, b, c)| moments(a, b, c))
        .collect();
    cases.extend([
        [-1e-9, 2e-9, 1e-9],
        [0.0, 0.0, 0.0],
        [1e-6, 1e-4, 1e-2],
        [0.5, 0.25, 0.125],
    ]);
    for q in cases {
        let phi = dm::closure(&HUXLEY, &q);
        let (b, d) = (
            gaussian_bound_attachment(&HUXLEY, &q),
            gaussian_detachment(&HUXLEY, &q),
        );
        for k in 0..3 {
            assert_rel(
                b[k] + d[k],
                phi[k],
                1e-12,
                1e-12,
                &format!("φ_{k} at {q:?}"),
            );
        }
    }
}

/// In the DM isometric steady state attachment balances detachment for every moment, and its
/// ATP flux in units f1 + g1 = 1 is 0.0950 against the exact model's N (1 - N)/2 = 0.0762:
/// 24.7 % more at the same rates and bridge density.
#[test]
fn dm_isometric_atp_flux_exceeds_the_exact_one_at_equal_rates() {
    let s = HUXLEY.f1 + HUXLEY.g1;
    let unit = HUXLEY.scaled(1.0 / s);
    let q = dm::isometric_steady_state(&unit).unwrap();
    let f = gaussian_fluxes(&unit, 1.0, &q);
    for k in 0..3 {
        assert_rel(
            f.attachment[k],
            f.detachment[k],
            1e-10,
            1e-12,
            "steady A = D",
        );
    }
    let n = HUXLEY.f1 / s;
    let exact = 0.5 * n * (1.0 - n);
    assert!(
        (f.detachment[0] - 0.09502).abs() < 1e-5,
        "{}",
        f.detachment[0]
    );
    assert!((exact - 0.076209).abs() < 1e-6, "{exact}");
    assert!(
        (f.detachment[0] / exact - 1.2469).abs() < 1e-4,
        "{}",
        f.detachment[0] / exact
    );
}

/// A grid filled with a bond distribution.
fn filled_grid(cells: usize, n: impl Fn(f64) -> f64) -> CrossBridgeGrid {
    let mut g = CrossBridgeGrid::new(cells, 8.0);
    g.fill(n);
    g
}

#[test]
fn grid_fluxes_split_its_closure() {
    let rates = Rates { g3: 20.0, ..HUXLEY };
    let g = filled_grid(37, |x| (0.8 * (-((x - 0.4) / 0.45).powi(2)).exp()).max(0.0));
    let phi = g.closure(&rates);
    let (b, d) = (
        grid_bound_attachment(&g, &rates),
        grid_detachment(&g, &rates),
    );
    for k in 0..3 {
        assert_rel(b[k] + d[k], phi[k], 1e-13, 1e-12, &format!("φ_{k}"));
    }
    let f = grid_fluxes(&g, &rates, 0.7);
    for (k, bk) in b.iter().enumerate() {
        assert_rel(
            f.attachment[k],
            0.7 * rates.beta(k) - bk,
            1e-14,
            1e-12,
            "A_k",
        );
    }
}

/// The exact isometric distribution (n = N on [0, 1], cells aligned with 0 and 1): every flux
/// is exact for k = 0, `D_0 = A_0 = N g1/2`; the ξ² fluxes carry the grid's midpoint-rule
/// error, `D_2 = N g1 (1/4 - Δξ²/8)`, `A_2 = f1 (1 - N)/4 + N f1 Δξ²/8`.
#[test]
fn grid_fluxes_of_the_isometric_state_are_exact() {
    let n = HUXLEY.f1 / (HUXLEY.f1 + HUXLEY.g1);
    let g = filled_grid(200, |x| if (0.0..=1.0).contains(&x) { n } else { 0.0 });
    let f = grid_fluxes(&g, &HUXLEY, 1.0);
    assert_rel(f.detachment[0], 0.5 * n * HUXLEY.g1, 1e-12, 0.0, "D_0");
    assert_rel(f.attachment[0], 0.5 * n * HUXLEY.g1, 1e-12, 0.0, "A_0");
    // By cell centres: Σ c³ Δξ = 1/4 - Δξ²/8 over [0, 1].
    let dxi: f64 = 1.0 / 200.0;
    let a2 = 0.25 * HUXLEY.f1 * (1.0 - n) + n * HUXLEY.f1 * dxi * dxi / 8.0;
    assert_rel(f.attachment[2], a2, 1e-12, 0.0, "A_2");
    assert_rel(
        f.detachment[2],
        n * HUXLEY.g1 * (0.25 - dxi * dxi / 8.0),
        1e-12,
        0.0,
        "D_2",
    );
}

/// The fluxes at a state a small step from the last closure evaluation's take Φ and ϕ from that
/// evaluation (closure_limits): equal to a fresh evaluation to rounding, for steps as large as
/// the series' reach and from both models' guards' side; a step beyond the reach is evaluated.
#[test]
fn dm_fluxes_near_the_last_closure_are_a_fresh_evaluation_to_rounding() {
    use crate::physics::contractile::closure_limits::ClosureLimits;
    let with_g3 = Rates { g3: 57.0, ..HUXLEY };
    for rates in [HUXLEY, with_g3] {
        for (q0, p, sd) in GAUSSIANS {
            for step in [1e-9, 1e-7, 3e-6, 2e-5, 1e-3] {
                let limits = ClosureLimits::default();
                let before = moments(q0, p, sd);
                dm::closure_keeping(&rates, &before, Some(&limits));
                let after = moments(q0 * (1.0 + step), p + step * sd, sd * (1.0 - step));
                let near = gaussian_fluxes_near(&rates, 0.8, &after, Some(&limits));
                let fresh = gaussian_fluxes(&rates, 0.8, &after);
                for k in 0..3 {
                    let scale = [q0, q0 * p.abs().max(sd), q0 * (p * p + sd * sd)][k];
                    for (a, b) in [
                        (near.attachment[k], fresh.attachment[k]),
                        (near.detachment[k], fresh.detachment[k]),
                    ] {
                        let tol = 1e-14 * scale * (rates.f1 + rates.g2);
                        assert!(
                            (a - b).abs() <= tol,
                            "k = {k}, step {step:e} at {:?}: {a:e} vs {b:e}",
                            (q0, p, sd)
                        );
                    }
                }
            }
        }
    }
}
