//! Huxley's (1957) steady energetics: the closed forms of `huxley_steady` against his table,
//! against quadrature of the steady distribution, and against the grid of the full model.

use super::quadrature::piecewise;
use super::{assert_rel, HUXLEY};
use crate::physics::contractile::crossbridge::Rates;
use crate::physics::contractile::huxley_exact as exact;
use crate::physics::contractile::huxley_grid::CrossBridgeGrid;
use crate::physics::energetics::bridge_flux::grid_detachment;
use crate::physics::energetics::huxley_steady::*;

/// Huxley's table: with his fractions g1/(f1 + g1) = 3/16, g2/(f1 + g1) = 3.919 (for which
/// V_max = 4 φ_H, φ_H = (f1 + g1) h/2 in our u) at V = φ_H, 2 φ_H, 4 φ_H.
#[test]
fn energy_rate_matches_huxleys_table() {
    let h = Rates {
        f1: 13.0 / 16.0,
        g1: 3.0 / 16.0,
        g2: 3.919,
        g3: 0.0,
    };
    let p0 = exact::steady_q1(&h, 1.0, 0.0);
    let table = [
        (0.0, 1.0, 1.0),
        (1.0, 0.3473, 3.739),
        (2.0, 0.1618, 4.410),
        (4.0, 0.0, 4.834),
    ];
    for (w, force, energy) in table {
        let u = w * (h.f1 + h.g1) / 2.0;
        let p = exact::steady_q1(&h, 1.0, u) / p0;
        assert!((p - force).abs() < 1e-4, "P/P0 at V = {w} φ: {p}");
        let e = energy_rate_ratio(&h, u);
        assert!((e - energy).abs() < 5e-4, "Ė/Ė0 at V = {w} φ: {e}");
        assert_rel(
            steady_atp_flux(&h, 1.0, u) / steady_atp_flux(&h, 1.0, 0.0),
            e,
            1e-14,
            1.0,
            "ratio",
        );
    }
}

/// With the project's ratios 43.3 : 10 : 209 (V_max = 4.0019 φ_H) at V/V_max = 0.25, 0.5, 1:
/// 3.7376, 4.4078, 4.8314 (Huxley's 3.739, 4.410, 4.834 are for his fractions).
#[test]
fn energy_rate_with_the_projects_rates() {
    let u_max = exact::unloaded_shortening_rate(&HUXLEY);
    for (frac, want) in [(0.25, 3.737636), (0.5, 4.407823), (1.0, 4.831393)] {
        let e = energy_rate_ratio(&HUXLEY, frac * u_max);
        assert!((e - want).abs() < 2e-6, "Ė/Ė0 at {frac} V_max: {e}");
    }
}

/// Shortening and lengthening rates (h/s) the tests visit, up to ±2 u_max.
const RATES_H_S: [f64; 9] = [-200.0, -60.0, -5.0, 0.0, 2.0, 13.3, 26.7, 53.3, 106.65];

/// `∫ w(ξ) n(ξ) dξ` of the closed-form steady distribution by quadrature, split where n or the
/// rates change form; the tails are cut where n < e^{-40} of its edge value.
fn steady_integral(u: f64, w: impl Fn(f64) -> f64) -> f64 {
    let lo = if u > 0.0 { -40.0 * u / HUXLEY.g2 } else { 0.0 };
    let hi = if u < 0.0 {
        (1.0 + 80.0 * -u / HUXLEY.g1).sqrt()
    } else {
        1.0
    };
    let n = |x: f64| steady_bonds(&HUXLEY, 1.0, u, x);
    piecewise(|x| w(x) * n(x), &[lo, 0.0, 1.0, hi], 2_000)
}

/// The closed-form n(ξ) solves the steady eq. (9), `-u n' = f - (f + g) n`, and its Q1 is
/// `huxley_exact::steady_q1`.
#[test]
fn steady_distribution_solves_the_steady_equation() {
    for u in RATES_H_S {
        for x in [-0.3, -0.05, 0.1, 0.5, 0.93, 1.2, 2.0] {
            let d = 1e-6;
            let n = |x| steady_bonds(&HUXLEY, 1.0, u, x);
            let slope = (n(x + d) - n(x - d)) / (2.0 * d);
            let rhs = HUXLEY.attach(x) - (HUXLEY.attach(x) + HUXLEY.detach(x)) * n(x);
            assert!(
                (-u * slope - rhs).abs() < 1e-6 * HUXLEY.g2,
                "u = {u}, ξ = {x}"
            );
        }
        let q1 = steady_integral(u, |x| x);
        assert_rel(
            q1,
            exact::steady_q1(&HUXLEY, 1.0, u),
            1e-9,
            1e-12,
            &format!("Q1 at u = {u}"),
        );
    }
}

/// The four fluxes in closed form against quadrature of the steady distribution.
#[test]
fn steady_fluxes_match_quadrature() {
    let f = |x: f64| HUXLEY.attach(x);
    let g = |x: f64| HUXLEY.detach(x);
    for u in RATES_H_S {
        let x = steady_energy_fluxes(&HUXLEY, 1.0, u);
        let bound_attach = steady_integral(u, f);
        let bound_strain = steady_integral(u, |x| x * x * f(x));
        assert_rel(
            x.detachment,
            steady_integral(u, g),
            1e-9,
            1e-12,
            &format!("D_0, u = {u}"),
        );
        assert_rel(
            x.attachment,
            HUXLEY.beta(0) - bound_attach,
            1e-9,
            1e-12,
            "A_0",
        );
        assert_rel(
            x.strain_in,
            HUXLEY.beta(2) - bound_strain,
            1e-9,
            1e-12,
            "A_2",
        );
        let d2 = steady_integral(u, |x| x * x * g(x));
        assert_rel(x.strain_out, d2, 1e-9, 1e-12, &format!("D_2, u = {u}"));
    }
}

/// Eq. (12) for Q2 in a steady state: `A_2 - D_2 = 2 u Q1`, Q1 from `huxley_exact`.
#[test]
fn steady_strain_balances_the_work() {
    for u in RATES_H_S {
        let x = steady_energy_fluxes(&HUXLEY, 0.6, u);
        let work = 2.0 * u * exact::steady_q1(&HUXLEY, 0.6, u);
        let scale = x.strain_in.abs().max(work.abs());
        assert!(
            (x.strain_in - x.strain_out - work).abs() < 1e-12 * scale,
            "u = {u}"
        );
    }
}

/// A grid of `cells` per unit ξ that also covers the tail of the steady distribution at u:
/// filled with 1 (so that no cell is dropped as empty), then moved with no time passing by a
/// whole number of cells, so that cells enter on the tail's side.
fn covering_grid(cells: usize, u: f64) -> CrossBridgeGrid {
    let reach = if u > 0.0 {
        -40.0 * u / HUXLEY.g2
    } else {
        (1.0 + 80.0 * -u / HUXLEY.g1).sqrt() - 1.0
    };
    let shift = (reach * cells as f64).round() / cells as f64;
    let mut g = CrossBridgeGrid::new(cells, 64.0);
    g.fill(|_| 1.0);
    g.advance(&HUXLEY, 1.0, 0.0, shift);
    g
}

/// The grid's quadrature of the exact steady distribution converges to the closed form at
/// second order: relative error ≤ 1e-3 at the default 200 cells per unit ξ.
#[test]
fn grid_atp_flux_converges_to_the_closed_form() {
    for u in [13.3, 53.3, 106.65, -60.0] {
        let want = steady_atp_flux(&HUXLEY, 1.0, u);
        let err = |cells: usize| {
            let mut g = covering_grid(cells, u);
            g.fill(|x| steady_bonds(&HUXLEY, 1.0, u, x));
            (grid_detachment(&g, &HUXLEY)[0] - want).abs() / want
        };
        let (coarse, fine) = (err(25), err(200));
        assert!(fine <= 1e-3, "u = {u}: {fine:e}");
        assert!(fine < coarse / 16.0, "u = {u}: {coarse:e} → {fine:e}");
    }
}

/// The full model's grid driven at constant velocity until steady reaches Huxley's energy rate
/// at nine velocities from 0 to V_max: relative error ≤ 1e-3 at 200 cells per unit ξ.
#[test]
fn driven_grid_reaches_huxleys_energy_rate() {
    let u_max = exact::unloaded_shortening_rate(&HUXLEY);
    let n_iso = HUXLEY.f1 / (HUXLEY.f1 + HUXLEY.g1);
    for i in 0..9 {
        let u = u_max * i as f64 / 8.0;
        let mut g = CrossBridgeGrid::new(200, 40.0);
        g.fill(|x| if (0.0..=1.0).contains(&x) { n_iso } else { 0.0 });
        // Every bond replaced many times over; a step moves the grid a quarter of a cell.
        let t_end = 0.3 + 4.0 / u.max(1.0);
        let dt = (0.25 / 200.0 / u.max(1e-9)).min(2e-4);
        for _ in 0..(t_end / dt).ceil() as usize {
            g.advance(&HUXLEY, 1.0, dt, -u * dt);
        }
        let got = grid_detachment(&g, &HUXLEY)[0];
        assert_rel(
            got,
            steady_atp_flux(&HUXLEY, 1.0, u),
            1e-3,
            0.0,
            &format!("u = {u}"),
        );
    }
}
