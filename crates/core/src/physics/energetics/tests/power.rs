//! The powers of `bridge_power`: the mapping from moments to molecules, and the energy balance
//! of the bridges, each term from its own source.

use super::assert_rel;
use crate::physics::contractile::crossbridge_scale::{
    calibrate_distribution_moment, calibrate_exact,
};
use crate::physics::contractile::distribution_moment as dm;
use crate::physics::contractile::huxley_grid::CrossBridgeGrid;
use crate::physics::energetics::bridge_flux::{gaussian_fluxes, grid_fluxes};
use crate::physics::energetics::bridge_power::*;
use crate::physics::limb_params::MuscleParams;

/// Counting bridges gives the chemical power per unit flux `e N_hs B = ε/2 C L_h`: the energy
/// per ATP cancels, and ε = 1.5387, k = 0.534 pN/nm with the defaults.
#[test]
fn bridge_count_maps_flux_to_power() {
    let p = MuscleParams::default();
    let e = BridgeEnergyParams::default();
    for scale in [
        calibrate_exact(&p),
        calibrate_distribution_moment(&p).unwrap(),
    ] {
        let s = BridgeEnergyScale::new(&scale, &p, &e);
        let eps = energy_ratio(scale.rates.f1, scale.rates.g1, 0.25);
        assert!((eps - 1.538684).abs() < 1e-6, "{eps}");
        assert!(
            (s.bridge_stiffness_n_m - 5.3411e-4).abs() < 1e-7,
            "{}",
            s.bridge_stiffness_n_m
        );
        let per_flux = 0.5 * eps * scale.force_per_q1 * scale.l_h;
        assert_rel(s.chemical_power_w(1.0), per_flux, 1e-13, 0.0, "e N_hs B");
        assert_rel(
            s.strain_power_w(1.0),
            scale.energy(1.0),
            1e-15,
            0.0,
            "½ C L_h",
        );
        assert_rel(
            s.atp_rate_mol_s(1.0) * AVOGADRO_PER_MOL * 1e-19,
            per_flux,
            1e-13,
            0.0,
            "mol",
        );
    }
}

/// The DM bridges' powers against the model's own mechanics: work `F_CE v_s` with
/// `F_CE = C Q1`, and the stored-energy rate `½ C L_h dQ2/dt` with dQ2/dt from eq. (12).
#[test]
fn dm_powers_match_the_model_mechanics() {
    let p = MuscleParams::default();
    let scale = calibrate_distribution_moment(&p).unwrap();
    let s = BridgeEnergyScale::new(&scale, &p, &BridgeEnergyParams::default());
    for (q, r, v) in [
        (scale.q_iso, 1.0, 0.0),
        ([0.5, 0.3, 0.25], 0.8, -0.1),
        ([0.3, 0.1, 0.12], 0.2, 0.05),
    ] {
        let fluxes = gaussian_fluxes(&scale.rates, r, &q).energy();
        let force = scale.force(q[1]);
        let w = bridge_powers(&s, &fluxes, force, v);
        assert_rel(w.work_w, -force * v, 1e-15, 1e-12, "work");
        let dq = dm::moment_rates(&scale.rates, &q, r, scale.shortening_rate(v));
        assert_rel(w.stored_rate_w, scale.energy(dq[2]), 1e-10, 1.0, "dU/dt");
        let sum = w.heat_w() + w.work_w + w.stored_rate_w;
        assert_rel(
            w.chemical_at_attachment_w,
            sum,
            1e-12,
            1.0,
            "balance at attachment",
        );
        let count = s.chemical_power_w(fluxes.attachment - fluxes.detachment);
        let dn = s.chemical_power_w(dq[0]);
        assert_rel(
            w.chemical_at_attachment_w - w.chemical_w,
            count,
            1e-12,
            1.0,
            "A - D",
        );
        assert_rel(count, dn, 1e-10, 1.0, "e dN/dt");
    }
}

/// The full model's grid shortening from its isometric state at 0.3 vmax for 40 ms: the
/// chemical energy taken up at attachment equals the work plus the heat plus the change of the
/// stored strain energy (`½ C L_h ΔQ2`, Q2 from the grid's moments), each integrated by the
/// trapezoidal rule; counted at detachment it differs by e times the change in bound bridges
/// (`N_hs B ΔQ0`). Residuals below 1e-5 of the chemical energy (measured: 1.4e-6 and 4.2e-6,
/// from the trapezoidal rule and the grid's cell-centre quadrature).
#[test]
fn grid_energy_balances_while_shortening() {
    let p = MuscleParams::default();
    let scale = calibrate_exact(&p);
    let s = BridgeEnergyScale::new(&scale, &p, &BridgeEnergyParams::default());
    let n_iso = scale.rates.f1 / (scale.rates.f1 + scale.rates.g1);
    let mut g = CrossBridgeGrid::new(200, 64.0);
    g.fill(|x| if (0.0..=1.0).contains(&x) { n_iso } else { 0.0 });
    let v = -0.3 * p.v_max;
    let u = scale.shortening_rate(v);
    let dt = 2e-6;
    let powers = |g: &CrossBridgeGrid| {
        let f = grid_fluxes(g, &scale.rates, 1.0).energy();
        bridge_powers(&s, &f, scale.force(g.moments()[1]), v)
    };
    let q_start = g.moments();
    let (mut chem_att, mut chem_det, mut heat, mut work) = (0.0, 0.0, 0.0, 0.0);
    let mut before = powers(&g);
    for _ in 0..20_000 {
        g.advance(&scale.rates, 1.0, dt, -u * dt);
        let after = powers(&g);
        let trapezoid = |f: fn(&BridgePowers) -> f64| 0.5 * dt * (f(&before) + f(&after));
        chem_att += trapezoid(|w| w.chemical_at_attachment_w);
        chem_det += trapezoid(|w| w.chemical_w);
        heat += trapezoid(|w| w.heat_w());
        work += trapezoid(|w| w.work_w);
        before = after;
    }
    let q_end = g.moments();
    let stored = s.strain_power_w(q_end[2] - q_start[2]);
    let residual = chem_att - (work + heat + stored);
    assert!(
        residual.abs() < 1e-5 * chem_att,
        "residual {residual:e} of {chem_att:e} J"
    );
    let bound = s.chemical_power_w(q_end[0] - q_start[0]);
    let residual = chem_att - chem_det - bound;
    assert!(
        residual.abs() < 1e-5 * chem_att,
        "count residual {residual:e} J"
    );
}

#[test]
fn activation_heat_is_a_share_of_the_isometric_turnover() {
    // s/(1 - s) of the bridges' rate: the pumps take s of the total at full activation.
    let h = activation_heat_w(1.0, 0.35, 100.0);
    assert_rel(h / (h + 100.0), 0.35, 1e-15, 0.0, "share");
    assert_rel(
        activation_heat_w(0.5, 0.35, 100.0),
        0.5 * h,
        1e-15,
        0.0,
        "∝ a",
    );
}

#[test]
fn work_is_positive_when_shortening() {
    assert_eq!(work_rate_w(100.0, -0.2), 20.0);
    assert_eq!(work_rate_w(100.0, 0.2), -20.0);
}
