//! docs/model.md §10: at 1 kHz the tick results stay within 1e-3 Fmax (force) and 1e-6 m (length) of
//! a tight-tolerance adaptive reference (Dop853 from `ode_solvers`, an explicit method sharing
//! nothing with the implicit stepper) on every scenario, and runs are bit-identical.

mod common;

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{MuscleParams, Stepping};
use muscle_actuator_core::sim::{default_stepping, Scenario};
use std::path::Path;

const FORCE_TOL: f64 = 1e-3 * 3913.0;
const LENGTH_TOL: f64 = 1e-6;

fn stepping(model: ModelKind) -> Stepping {
    // TOL=... overrides the tolerance, to study the accuracy/cost trade-off.
    match (
        std::env::var("TOL").ok().and_then(|s| s.parse().ok()),
        default_stepping(model),
    ) {
        (Some(tolerance), Stepping::Adaptive { max_substeps, .. }) => Stepping::Adaptive {
            tolerance,
            max_substeps,
        },
        (_, s) => s,
    }
}

fn check(sc: &Scenario, model: ModelKind) {
    let (df, dl) = common::worst_deviation_from_reference(
        sc,
        &ActuatorConfig::default(),
        model,
        1000.0,
        stepping(model),
    );
    println!(
        "{} {model}: worst |dF| = {df:.3e} N, worst |dl_m| = {dl:.3e} m",
        sc.name
    );
    assert!(
        df <= FORCE_TOL,
        "{} {model}: force deviation {df} N > {FORCE_TOL} N",
        sc.name
    );
    assert!(
        dl <= LENGTH_TOL,
        "{} {model}: length deviation {dl} m > {LENGTH_TOL} m",
        sc.name
    );
}

fn built_in(name: &str) -> Scenario {
    Scenario::built_in(name, &MuscleParams::default()).unwrap()
}

fn joint_scenario() -> Scenario {
    Scenario::from_file(
        &Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("scenarios/example.toml"),
    )
    .unwrap()
}

#[test]
fn pulse_hill_matches_reference() {
    check(&built_in("pulse"), ModelKind::HILL);
}
#[test]
fn pulse_huxley_matches_reference() {
    check(&built_in("pulse"), ModelKind::HUXLEY);
}
#[test]
fn energy_10hz_hill_matches_reference() {
    check(&built_in("energy-10hz"), ModelKind::HILL);
}
#[test]
fn energy_100hz_hill_matches_reference() {
    check(&built_in("energy-100hz"), ModelKind::HILL);
}
#[test]
fn energy_10hz_huxley_matches_reference() {
    check(&built_in("energy-10hz"), ModelKind::HUXLEY);
}
#[test]
fn energy_100hz_huxley_matches_reference() {
    check(&built_in("energy-100hz"), ModelKind::HUXLEY);
}
#[test]
fn joint_scenario_hill_matches_reference() {
    check(&joint_scenario(), ModelKind::HILL);
}
#[test]
fn joint_scenario_huxley_matches_reference() {
    check(&joint_scenario(), ModelKind::HUXLEY);
}

/// Fixed sub-steps (TR-BDF2): halving the step divides the error by about four (second order),
/// which also shows the reference is far more accurate than the stepper.
#[test]
fn fixed_stepping_converges_at_second_order() {
    let sc = built_in("pulse");
    let (_, e8) = common::worst_deviation_from_reference(
        &sc,
        &ActuatorConfig::default(),
        ModelKind::HILL,
        1000.0,
        Stepping::Fixed(8),
    );
    let (_, e16) = common::worst_deviation_from_reference(
        &sc,
        &ActuatorConfig::default(),
        ModelKind::HILL,
        1000.0,
        Stepping::Fixed(16),
    );
    let order = (e8 / e16).log2();
    println!("fixed 8 vs 16 sub-steps: {e8:.3e} / {e16:.3e} m, observed order {order:.2}");
    assert!((1.7..2.5).contains(&order), "observed order {order}");
}

/// Same inputs at the same ticks: bit-identical outputs, for every model.
#[test]
fn runs_are_bit_identical() {
    let cfg = ActuatorConfig::default();
    for (sc, model) in [
        (built_in("pulse"), ModelKind::HILL),
        (built_in("pulse"), ModelKind::HUXLEY),
        (built_in("energy-100hz"), ModelKind::HUXLEY_PDE),
        (joint_scenario(), ModelKind::HUXLEY),
    ] {
        let a = sc
            .run(&cfg, model, 1000.0, default_stepping(model))
            .unwrap();
        let b = sc
            .run(&cfg, model, 1000.0, default_stepping(model))
            .unwrap();
        assert_eq!(a.len(), b.len());
        for (ra, rb) in a.records().zip(b.records()) {
            for (ma, mb) in ra.muscles.iter().zip(rb.muscles) {
                assert_eq!(
                    ma.force.to_bits(),
                    mb.force.to_bits(),
                    "{} {model} t={}",
                    sc.name,
                    ra.time
                );
                assert_eq!(ma.fiber_length.to_bits(), mb.fiber_length.to_bits());
                assert_eq!(ma.q1.to_bits(), mb.q1.to_bits());
            }
        }
    }
}

/// The full model has no ODE form for an adaptive reference; its reference is itself with ten
/// times the sub-steps (the grid advances exactly for each sub-step's motion, so what converges
/// is the coupling of grid and mechanics). Same bounds as docs/model.md §10.
#[test]
fn full_model_ticks_match_a_ten_times_finer_run() {
    let cfg = ActuatorConfig::default();
    for name in ["pulse", "energy-100hz"] {
        let sc = built_in(name);
        let Stepping::Fixed(n) = default_stepping(ModelKind::HUXLEY_PDE) else {
            panic!()
        };
        let a = sc
            .run(&cfg, ModelKind::HUXLEY_PDE, 1000.0, Stepping::Fixed(n))
            .unwrap();
        let b = sc
            .run(&cfg, ModelKind::HUXLEY_PDE, 1000.0, Stepping::Fixed(10 * n))
            .unwrap();
        let (mut df, mut dl) = (0.0f64, 0.0f64);
        for (ra, rb) in a.records().zip(b.records()) {
            df = df.max((ra.muscles[0].force - rb.muscles[0].force).abs());
            dl = dl.max((ra.muscles[0].fiber_length - rb.muscles[0].fiber_length).abs());
        }
        println!("{name} huxley-pde: worst |dF| = {df:.3e} N, worst |dl_m| = {dl:.3e} m against 10x sub-steps");
        assert!(
            df <= FORCE_TOL && dl <= LENGTH_TOL,
            "{name}: {df} N, {dl} m"
        );
    }
}
