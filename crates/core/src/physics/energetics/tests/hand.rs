//! The phenomenological models on cases computed by hand from the published formulas
//! (Umberger 2010 with Uchida et al. 2016's options; Bhargava et al. 2004), each branch once:
//! lengthening, beyond lopt, the heat floor, the non-negative total, force-dependent heat.

use super::assert_rel;
use crate::physics::energetics::bhargava::*;
use crate::physics::energetics::probe::*;
use crate::physics::energetics::umberger::*;

/// A muscle for the hand-computed cases: 1 kg, 1000 N, lopt 0.1 m, V_max 10 lopt/s, r = 0.5.
fn unit_muscle(mass: f64, ratio: f64) -> ProbeMuscle {
    ProbeMuscle {
        mass_kg: mass,
        f_max_n: 1000.0,
        l_opt_m: 0.1,
        v_max_lopt_s: 10.0,
        slow_twitch_ratio: ratio,
    }
}

fn inputs(u: f64, a: f64, l: f64, f_iso: f64, v: f64, active: f64, passive: f64) -> ProbeInputs {
    ProbeInputs {
        excitation: u,
        activation: a,
        fibre_length_norm: l,
        force_length: f_iso,
        fibre_velocity_m_s: v,
        active_force_n: active,
        passive_force_n: passive,
    }
}

/// Lengthening at u = a = 0.1, v = 5 lopt/s, F = 1200 N. Uchida: recruited slow share
/// 0.92704, AM = 1.5 · 0.1^0.6 (128 (1 - 0.92704) + 25) = 12.938; lengthening heat
/// 1.5 · 0.1 · 4 · 25 · 5 = 75 and work -600 leave a negative total, so the heat rises to 600.
/// Umberger 2010: AM = 1.5 · 0.1^0.6 · 89 = 33.534, heat 1.5 · 0.1 · 0.3 · 25 · 5 = 5.625, no work.
#[test]
fn umberger_lengthening_by_hand() {
    let x = inputs(0.1, 0.1, 1.0, 1.0, 0.5, 1200.0, 0.0);
    let r = umberger_rates(&UmbergerOptions::uchida_2016(), &unit_muscle(1.0, 0.5), &x);
    assert_rel(
        r.activation_maintenance_w,
        12.938288482444085,
        1e-12,
        0.0,
        "AM",
    );
    assert_rel(r.work_w, -600.0, 1e-15, 0.0, "work");
    assert_rel(r.heat_w(), 600.0, 1e-12, 0.0, "heat");
    assert!(r.total_w().abs() < 1e-12);
    let r = umberger_rates(
        &UmbergerOptions::umberger_2010(),
        &unit_muscle(1.0, 0.5),
        &x,
    );
    assert_rel(
        r.activation_maintenance_w,
        33.53368386065289,
        1e-12,
        0.0,
        "AM 2010",
    );
    assert_rel(r.shortening_w, 5.625, 1e-12, 0.0, "lengthening heat 2010");
    assert_eq!(r.work_w, 0.0);
}

/// Beyond lopt (l̃ = 1.2, F_iso = 0.8), shortening at 3 lopt/s, u = 1 > a = 0.5 (A = 1):
/// AM = 1.5 · 89 · (0.4 + 0.6 · 0.8) = 117.48; shortening 1.5 (75 · 0.5 + 15.3 · 3 · 0.5) · 0.8
/// = 72.54; work 500 · 0.3 = 150. At rest (u = a = 0.001) the heat is floored at 1 W/kg.
#[test]
fn umberger_length_dependence_and_floor_by_hand() {
    let o = UmbergerOptions::uchida_2016();
    let r = umberger_rates(
        &o,
        &unit_muscle(1.0, 0.5),
        &inputs(1.0, 0.5, 1.2, 0.8, -0.3, 500.0, 0.0),
    );
    assert_rel(r.activation_maintenance_w, 117.48, 1e-12, 0.0, "AM");
    assert_rel(r.shortening_w, 72.54, 1e-12, 0.0, "shortening");
    assert_rel(r.total_w(), 340.02, 1e-12, 0.0, "total");
    let r = umberger_rates(
        &o,
        &unit_muscle(2.0, 0.5),
        &inputs(0.001, 0.001, 1.0, 1.0, 0.0, 0.0, 0.0),
    );
    assert_rel(r.heat_w(), 2.0, 1e-15, 0.0, "floor at 1 W/kg");
    assert_eq!(r.shortening_w, 0.0);
}

/// Bhargava at u = a = 1, r = 0.5, lopt: (40 + 133)/2 + (74 + 111)/2 = 179 W/kg.
#[test]
fn bhargava_isometric_by_hand() {
    let o = BhargavaOptions::default();
    let r = bhargava_rates(
        &o,
        &unit_muscle(2.0, 0.5),
        &inputs(1.0, 1.0, 1.0, 1.0, 0.0, 1000.0, 0.0),
    );
    assert_rel(r.total_w(), 358.0, 1e-12, 0.0, "2 kg × 179 W/kg");
}

/// Shortening at 0.2 m/s, u = a = 0.6, r = 0.3, l̃ = 0.75, F = 400 N active + 50 N passive,
/// 1.5 kg: u_ST = 0.3 sin(0.3π), u_FT = 0.7 (1 - cos(0.3π)); activation 72.128, maintenance
/// 0.75 × 74.984 = 56.238, shortening 0.25 · 450 · 0.2 = 22.5, work 80. Force-dependent
/// shortening at 0.1 m/s, u = a = 0.8, f = 0.9: (0.16 · 0.8 · 0.9 · 1000 + 0.18 · 520) · 0.1.
#[test]
fn bhargava_shortening_by_hand() {
    let o = BhargavaOptions::default();
    let r = bhargava_rates(
        &o,
        &unit_muscle(1.5, 0.3),
        &inputs(0.6, 0.6, 0.75, 1.0, -0.2, 400.0, 50.0),
    );
    assert_rel(
        r.activation_maintenance_w,
        72.12809541610517 + 56.2379210684985,
        1e-12,
        0.0,
        "A + M",
    );
    assert_rel(r.shortening_w, 22.5, 1e-12, 0.0, "S");
    assert_rel(r.work_w, 80.0, 1e-12, 0.0, "W");
    let o = BhargavaOptions {
        force_dependent_shortening: true,
        ..o
    };
    let r = bhargava_rates(
        &o,
        &unit_muscle(1.0, 0.5),
        &inputs(0.8, 0.8, 1.0, 0.9, -0.1, 500.0, 20.0),
    );
    assert_rel(r.shortening_w, 20.88, 1e-12, 0.0, "force-dependent S");
    assert_rel(r.total_w(), 209.39014811508014, 1e-12, 0.0, "total");
}

/// Force-dependent lengthening at 0.4 m/s with negative work, u = a = 0.2, l̃ = 1.6 (no
/// maintenance): activation 9.4351, heat -0.157 · 800 · 0.4 and work -320 sum negative, so
/// the heat rises to 320 and the total is 0.
#[test]
fn bhargava_lengthening_by_hand() {
    let o = BhargavaOptions {
        force_dependent_shortening: true,
        ..BhargavaOptions::default()
    };
    let r = bhargava_rates(
        &o,
        &unit_muscle(1.0, 0.5),
        &inputs(0.2, 0.2, 1.6, 0.5, 0.4, 800.0, 0.0),
    );
    assert_rel(
        r.activation_maintenance_w,
        9.435081553871239,
        1e-12,
        0.0,
        "A",
    );
    assert_rel(r.heat_w(), 320.0, 1e-12, 0.0, "heat");
    assert!(r.total_w().abs() < 1e-12);
}

#[test]
fn maintenance_follows_the_fibre_length_curve() {
    for (l, want) in [
        (-1.0, 0.5),
        (0.25, 0.5),
        (0.75, 0.75),
        (1.0, 1.0),
        (1.25, 0.5),
        (1.75, 0.0),
        (3.0, 0.0),
    ] {
        assert_rel(
            maintenance_length_factor(l),
            want,
            1e-15,
            1e-15,
            &format!("L({l})"),
        );
    }
}
