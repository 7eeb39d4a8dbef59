//! The steady table against independent truth: Huxley's (1957) closed forms for the full model,
//! quadrature of the DM closure's Gaussian, Hill's g(v), and the energy balance of a steady
//! state; the grid, the refusals, and a model that is none of the three.

use super::*;
use crate::physics::contractile::crossbridge_scale::CrossBridgeScale;
use crate::physics::contractile::distribution_moment::steady_curve;
use crate::physics::contractile::hill_equation::force_velocity;
use crate::physics::contractile::huxley_exact::steady_q1;
use crate::physics::energetics::bridge_power::AVOGADRO_PER_MOL;
use crate::physics::energetics::tests::assert_rel;
use crate::physics::energetics::tests::quadrature::piecewise;

fn table(model: ModelKind, points: usize) -> Vec<SteadyRow> {
    steady_table(&MuscleParams::default(), model, points).unwrap()
}

fn of(rows: &[SteadyRow], source: EnergySource) -> Vec<SteadyRow> {
    rows.iter()
        .copied()
        .filter(|r| r.source == source)
        .collect()
}

const UMBERGER: EnergySource = EnergySource::Phenomenological(EnergyModel::Umberger);
const UMBERGER_2010: EnergySource = EnergySource::Phenomenological(EnergyModel::Umberger2010);

/// The grid: odd counts, -1, 0 and 1 exact, symmetric, even steps.
#[test]
fn velocities_span_minus_to_plus_vmax_through_zero() {
    for n in [3, 41, 1001, MAX_POINTS] {
        let f = velocity_fractions(n);
        assert_eq!((f.len(), f[0], f[n / 2], f[n - 1]), (n, -1.0, 0.0, 1.0));
        for i in 0..n {
            assert_eq!(f[i], -f[n - 1 - i]);
            assert_rel(
                f[i],
                -1.0 + 2.0 * i as f64 / (n - 1) as f64,
                1e-15,
                1.0,
                "step",
            );
        }
    }
    let rows = table(ModelKind::HILL, 3);
    let v: Vec<f64> = rows
        .iter()
        .map(|r| r.point.shortening_velocity_m_s)
        .collect();
    let v_max = MuscleParams::default().v_max;
    assert_eq!(v[..3], [-v_max, 0.0, v_max]);
}

#[test]
fn points_out_of_range_or_even_are_refused() {
    for n in [0, 1, 2, 4, 40, 10_002, 10_003, 100_000, usize::MAX] {
        let e = steady_table(&MuscleParams::default(), ModelKind::HILL, n).unwrap_err();
        assert!(matches!(
            e,
            SteadyError::PointsOutOfRange(k) | SteadyError::EvenPoints(k) if k == n
        ));
        let e = e.to_string();
        assert!(e.contains(&format!("--points {n}")), "{e}");
    }
    assert!(check_points(3).is_ok() && check_points(MAX_POINTS).is_ok());
}

/// Rows: the cross-bridge set for the Huxley models only, then one set per energy model.
#[test]
fn one_row_set_per_energy_source() {
    for (model, sets) in [
        (ModelKind::HILL, 3),
        (ModelKind::HUXLEY, 4),
        (ModelKind::HUXLEY_PDE, 4),
    ] {
        let rows = table(model, 41);
        assert_eq!(rows.len(), 41 * sets, "{model}");
        let mut sources: Vec<&str> = rows.iter().map(|r| r.source.name()).collect();
        sources.dedup();
        let mut want = vec!["umberger", "umberger2010", "bhargava"];
        if sets == 4 {
            want.insert(0, "crossbridge");
        }
        assert_eq!(sources, want, "{model}");
        assert!(rows.iter().all(|r| r.model == model));
    }
}

/// (a) The full model against Huxley (1957): the bridges' chemical power over its isometric
/// value is `1 + (f1/g1)(1 - e^{-φ})/φ`, φ = (f1 + g1)/(2|u|), u = v_s/L_h, on both sides; the
/// activation cost, a constant `s/(1 - s)` times the bridges' isometric power, is taken off
/// first (the isometric row holds `Ė0/(1 - s)`). The force is `Fmax Q1(u)/Q1(0)` of
/// `huxley_exact::steady_q1`. At 1/4, 1/2 and 1 vmax the ratio is 3.7376, 4.4078, 4.8314
/// (docs/model.md §11.3).
#[test]
fn full_model_rows_are_huxleys_closed_form() {
    let p = MuscleParams::default();
    let s = p.energetics.activation_share;
    let scale = calibrate_exact(&p);
    let rows = of(&table(ModelKind::HUXLEY_PDE, 41), EnergySource::CrossBridge);
    let iso = rows[20].point.chemical_w;
    let bridges = |r: &SteadyRow| (r.point.chemical_w - s * iso) / ((1.0 - s) * iso);
    let (f1, g1) = (scale.rates.f1, scale.rates.g1);
    for r in &rows {
        let u = r.point.shortening_velocity_m_s / scale.l_h;
        let want = if u == 0.0 {
            1.0
        } else {
            let phi = (f1 + g1) / (2.0 * u.abs());
            1.0 + f1 / g1 * (1.0 - (-phi).exp()) / phi
        };
        assert_rel(bridges(r), want, 1e-12, 1.0, &format!("Ė/Ė0 at u = {u}"));
        let force = p.f_max * steady_q1(&scale.rates, 1.0, u) / steady_q1(&scale.rates, 1.0, 0.0);
        assert_rel(r.point.force_n, force, 1e-12, p.f_max, "force");
    }
    for (i, want) in [(25, 3.7376), (30, 4.4078), (40, 4.8314)] {
        assert!((bridges(&rows[i]) - want).abs() < 5e-5, "{:?}", rows[i]);
    }
}

/// The DM closure's ATP flux `D_0 = ∫ g(ξ) n(ξ) dξ` for the Gaussian n of moments q, by
/// quadrature over ±12 standard deviations, split where g jumps or bends (ξ = 0, 1).
fn gaussian_atp_flux(scale: &CrossBridgeScale, q: [f64; 3]) -> f64 {
    let mean = q[1] / q[0];
    let sd = (q[2] / q[0] - mean * mean).sqrt();
    let (lo, hi) = (mean - 12.0 * sd, mean + 12.0 * sd);
    let n = |x: f64| {
        q[0] * (-0.5 * ((x - mean) / sd).powi(2)).exp() / (sd * (2.0 * std::f64::consts::PI).sqrt())
    };
    let breaks = [lo, 0.0f64.clamp(lo, hi), 1.0f64.clamp(lo, hi), hi];
    piecewise(|x| scale.rates.detach(x) * n(x), &breaks, 400)
}

/// (b) DM rows' ATP rate against quadrature of its own Gaussian closure at its steady moments:
/// `N_hs B (D_0(v) + s/(1 - s) D_0(0)) / N_A`, the second term the activation cost.
#[test]
fn dm_atp_rate_is_the_quadrature_of_its_gaussian() {
    let p = MuscleParams::default();
    let s = p.energetics.activation_share;
    let scale = calibrate_distribution_moment(&p).unwrap();
    let bridges = BridgeEnergyScale::new(&scale, &p, &p.energetics.bridge()).bridges_per_xi;
    let iso = gaussian_atp_flux(&scale, steady_curve(&scale.rates, &[0.0]).unwrap()[0]);
    let rows = of(&table(ModelKind::HUXLEY, 21), EnergySource::CrossBridge);
    for r in &rows {
        let u = r.point.shortening_velocity_m_s / scale.l_h;
        let q = steady_curve(&scale.rates, &[u]).unwrap()[0];
        let d0 = gaussian_atp_flux(&scale, q);
        let want = bridges * (d0 + s / (1.0 - s) * iso) / AVOGADRO_PER_MOL;
        assert_rel(
            r.point.atp_rate_mol_s,
            want,
            1e-9,
            0.0,
            &format!("ATP at u = {u}"),
        );
    }
}

/// (c) Every row: chemical power = heat + work (no energy stored in a steady state), work =
/// F v_s (Umberger 2010 as published counts no negative work: 0 when lengthening), W/kg = W over the metabolic mass. Hill rows' force is `Fmax g(v_s)`; every
/// phenomenological set of a Huxley model takes the force of its cross-bridge set.
#[test]
fn every_row_balances_and_takes_its_models_force() {
    let p = MuscleParams::default();
    let mass = p.energetics.mass_kg(p.f_max, p.l_opt);
    for model in [ModelKind::HILL, ModelKind::HUXLEY, ModelKind::HUXLEY_PDE] {
        let rows = table(model, 41);
        for (i, r) in rows.iter().enumerate() {
            let x = &r.point;
            let what = format!("{model} {} {x:?}", r.source.name());
            assert_rel(x.heat_w + x.work_w, x.chemical_w, 1e-9, 1.0, &what);
            let uncounted = r.source == UMBERGER_2010 && x.shortening_velocity_m_s < 0.0;
            let work = if uncounted {
                0.0
            } else {
                x.force_n * x.shortening_velocity_m_s
            };
            assert_rel(x.work_w, work, 1e-12, 1.0, &what);
            assert_rel(r.chemical_w_kg, x.chemical_w / mass, 1e-15, 1.0, &what);
            let force = if model == ModelKind::HILL {
                let g = force_velocity(x.shortening_velocity_m_s, p.v_max, p.eccentric_asymptote);
                p.f_max * g
            } else {
                rows[i % 41].point.force_n
            };
            assert_rel(x.force_n, force, 1e-15, 1.0, &what);
        }
    }
}

/// The peak efficiencies and isometric costs of docs/model.md §11.3 on a 0.002 vmax grid: full
/// model 0.288 at 0.166 vmax, DM 0.307 at 0.09 vmax; 141.39, 136.18 W/kg isometric, Umberger
/// (Uchida options) 133.5 W/kg, Bhargava 179 W/kg.
#[test]
fn the_documented_peaks_and_isometric_costs() {
    let peak = |rows: &[SteadyRow]| {
        rows.iter()
            .map(|r| (r.v_over_vmax, r.point.efficiency))
            .fold((0.0, 0.0), |b, x| if x.1 > b.1 { x } else { b })
    };
    let bhargava = EnergySource::Phenomenological(EnergyModel::Bhargava);
    for (model, v, eta, w_kg) in [
        (ModelKind::HUXLEY_PDE, 0.166, 0.2876, 141.39),
        (ModelKind::HUXLEY, 0.09, 0.3075, 136.18),
    ] {
        let rows = of(&table(model, 1001), EnergySource::CrossBridge);
        let (at, best) = peak(&rows);
        assert!(
            (at - v).abs() < 0.003 && (best - eta).abs() < 1e-3,
            "{model}: {at} {best}"
        );
        assert!((rows[500].chemical_w_kg - w_kg).abs() < 0.01, "{model}");
    }
    let hill = table(ModelKind::HILL, 3);
    assert_rel(
        of(&hill, UMBERGER)[1].chemical_w_kg,
        133.5,
        1e-12,
        0.0,
        "Umberger",
    );
    assert_rel(
        of(&hill, bhargava)[1].chemical_w_kg,
        179.0,
        1e-12,
        0.0,
        "Bhargava",
    );
}

/// A model other than the two Huxley models (the tests' fourth) is taken as Hill's.
#[test]
fn any_other_model_is_taken_as_hill() {
    let copy: ModelKind = "hill-copy".parse().unwrap();
    let (a, b) = (table(ModelKind::HILL, 41), table(copy, 41));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert_eq!((x.source, x.point, y.model), (y.source, y.point, copy));
    }
}

#[test]
fn invalid_parameters_are_refused_not_computed() {
    let p = MuscleParams {
        v_max: 0.0,
        ..Default::default()
    };
    for m in ModelKind::all() {
        let e = steady_table(&p, m, 41).unwrap_err();
        assert!(matches!(e, SteadyError::Params(_)), "{e}");
        assert!(e.to_string().contains("v_max"), "{e}");
    }
}

/// The full model's closed form holds for g3 = 0 only: with g3 > 0 it is refused, not
/// computed as if g3 were 0 (lengthening would carry bonds past ξ = 1).
#[test]
fn the_full_model_with_g3_is_refused() {
    let mut p = MuscleParams::default();
    p.crossbridge.g3 = 5.0;
    let e = steady_table(&p, ModelKind::HUXLEY_PDE, 41).unwrap_err();
    assert_eq!(e, SteadyError::NonZeroG3(5.0));
    assert!(e.to_string().contains("g3 = 5"), "{e}");
    assert!(steady_table(&p, ModelKind::HUXLEY, 41).is_ok());
}

/// The failing velocity is the first of its side, by |v_s|, that fails.
#[test]
fn first_failure_names_the_velocity_where_continuation_fails() {
    let v = [-0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3, 0.4];
    let beyond = |limit: f64| move |side: &[f64]| side.iter().any(|x| x.abs() > limit);
    assert_eq!(first_failure(&v, beyond(0.15)), Some(0.2));
    assert_eq!(first_failure(&v, beyond(0.35)), Some(0.4));
    assert_eq!(first_failure(&v[..3], beyond(0.15)), Some(-0.2));
    assert_eq!(first_failure(&v, beyond(1.0)), None);
    assert_eq!(first_failure(&v, |_| true), Some(0.0));
}
