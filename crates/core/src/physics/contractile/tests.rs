//! Cross-bridge models: the full Huxley model (method of characteristics) against the closed-form
//! oracle of docs/model.md §7, and the Distribution-Moment model's published steady state,
//! homogeneity and calibration (docs/model.md §6).

use crate::physics::contractile::crossbridge::Rates;
use crate::physics::contractile::crossbridge_scale::{
    calibrate_distribution_moment, calibrate_exact,
};
use crate::physics::contractile::distribution_moment as dm;
use crate::physics::contractile::huxley_exact as exact;
use crate::physics::contractile::huxley_grid::CrossBridgeGrid;
use crate::physics::limb_params::MuscleParams;

const HUXLEY: Rates = Rates {
    f1: 43.3,
    g1: 10.0,
    g2: 209.0,
    g3: 0.0,
};

#[test]
fn oracle_matches_published_numbers() {
    let q = exact::isometric_moments(&HUXLEY, 1.0);
    for (a, b) in q.iter().zip([0.812383, 0.406191, 0.270794]) {
        assert!((a - b).abs() < 1e-6, "{q:?}");
    }
    let u_max = exact::unloaded_shortening_rate(&HUXLEY);
    assert!((u_max - 106.6516).abs() < 1e-4, "u_max = {u_max}");
}

/// Drives the grid kinematically at constant u until steady, returns Q1.
fn grid_steady_q1(cells: usize, u: f64) -> f64 {
    let mut g = CrossBridgeGrid::new(cells, 40.0);
    let n_iso = HUXLEY.f1 / (HUXLEY.f1 + HUXLEY.g1);
    g.fill(|xi| {
        if (0.0..=1.0).contains(&xi) {
            n_iso
        } else {
            0.0
        }
    });
    // Long enough for every bond to be replaced several times over; each step moves the grid
    // by a quarter of a cell at most.
    let t_end = 0.3 + 4.0 / u.abs().max(1.0);
    let dt = (0.25 / cells as f64 / u.abs().max(1e-9)).min(2e-4);
    let steps = (t_end / dt).ceil() as usize;
    for _ in 0..steps {
        g.advance(&HUXLEY, 1.0, dt, -u * dt);
    }
    g.moments()[1]
}

#[test]
fn full_model_force_velocity_matches_oracle() {
    let u_max = exact::unloaded_shortening_rate(&HUXLEY);
    let q1_iso = exact::isometric_moments(&HUXLEY, 1.0)[1];
    for frac in [-1.0, -0.5, -0.2, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0] {
        let u = frac * u_max;
        let q1 = grid_steady_q1(200, u);
        let want = exact::steady_q1(&HUXLEY, 1.0, u);
        let err = (q1 - want).abs() / q1_iso;
        println!("u = {u:9.3} h/s: grid Q1 {q1:.6}, oracle {want:.6}, error {err:.1e} of Q1_iso");
        assert!(err <= 1e-3, "u = {u}: grid {q1} vs oracle {want}");
    }
}

#[test]
fn full_model_isometric_rise_matches_oracle() {
    let mut g = CrossBridgeGrid::new(400, 4.0);
    let dt = 1e-4;
    let q1_iso = exact::isometric_moments(&HUXLEY, 1.0)[1];
    for k in 1..=2000 {
        g.advance(&HUXLEY, 1.0, dt, 0.0);
        if k % 100 == 0 {
            let t = k as f64 * dt;
            let want = exact::isometric_rise_q1(&HUXLEY, 1.0, t);
            let got = g.moments()[1];
            assert!(
                (got - want).abs() / q1_iso <= 1e-3,
                "t = {t}: grid {got} vs oracle {want}"
            );
        }
    }
}

#[test]
fn grid_error_shrinks_with_resolution() {
    let u = 0.5 * exact::unloaded_shortening_rate(&HUXLEY);
    let want = exact::steady_q1(&HUXLEY, 1.0, u);
    let coarse = (grid_steady_q1(25, u) - want).abs();
    let fine = (grid_steady_q1(200, u) - want).abs();
    assert!(
        fine < coarse / 4.0,
        "coarse error {coarse:.2e}, fine {fine:.2e}"
    );
}

#[test]
fn dm_isometric_state_matches_model_md() {
    let q = dm::isometric_steady_state(&HUXLEY).unwrap();
    for (a, b) in q.iter().zip([0.684179, 0.437663, 0.321696]) {
        assert!((a - b).abs() < 2e-6, "DM Q_iso = {q:?}");
    }
}

#[test]
fn dm_steady_state_is_homogeneous_in_r() {
    let base = dm::steady_state(
        &HUXLEY,
        1.0,
        30.0,
        dm::isometric_steady_state(&HUXLEY).unwrap(),
    )
    .unwrap();
    for r in [0.1, 0.37, 0.8] {
        let guess = [base[0] * r * 1.1, base[1] * r * 0.9, base[2] * r];
        let q = dm::steady_state(&HUXLEY, r, 30.0, guess).unwrap();
        for k in 0..3 {
            assert!(
                (q[k] - r * base[k]).abs() <= 1e-9 * base[k].abs(),
                "r = {r}: {q:?} vs {base:?}"
            );
        }
    }
}

#[test]
fn calibration_gives_fmax_isometric_and_zero_force_at_vmax() {
    let p = MuscleParams::default();
    for scale in [
        calibrate_distribution_moment(&p).unwrap(),
        calibrate_exact(&p),
    ] {
        // Isometric tetanus at lopt (r = 1): the model's own steady Q1 maps to Fmax.
        assert!((scale.force(scale.q_iso[1]) - p.f_max).abs() < 1e-9 * p.f_max);
    }
    let cal = calibrate_distribution_moment(&p).unwrap();
    let u_at_vmax = cal.shortening_rate(-p.v_max);
    let q = dm::steady_curve(&cal.rates, &[u_at_vmax]).unwrap()[0];
    assert!(
        cal.force(q[1]).abs() < 1e-6 * p.f_max,
        "DM force at vmax: {} N",
        cal.force(q[1])
    );
    let exact_cal = calibrate_exact(&p);
    let q1 = exact::steady_q1(&exact_cal.rates, 1.0, exact_cal.shortening_rate(-p.v_max));
    assert!(exact_cal.force(q1).abs() < 1e-6 * p.f_max);
}

#[test]
fn dm_closure_never_lets_a_nan_out() {
    for q in [
        [0.0, 0.0, 0.0],
        [1e-300, 0.0, 0.0],
        [1e-13, 1e-13, 1e-13],
        [0.5, 0.25, 0.125],
        [0.5, 2.0, 0.1],
        [-1e-9, 1e-9, 0.0],
    ] {
        let rates = dm::moment_rates(&HUXLEY, &q, 0.7, 50.0);
        assert!(rates.iter().all(|v| v.is_finite()), "{q:?} -> {rates:?}");
    }
}
