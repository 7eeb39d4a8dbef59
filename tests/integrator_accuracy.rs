//! MODEL.md §10: at 1 kHz the tick results stay within 1e-3 Fmax (force) and 1e-6 m (length) of
//! a tight-tolerance adaptive reference on every scenario, and runs are bit-identical.

mod common;

use muscle_actuator::config::ActuatorConfig;
use muscle_actuator::physics::model::ModelKind;
use muscle_actuator::physics::params::MuscleParams;
use muscle_actuator::sim::scenario::Scenario;
use muscle_actuator::sim::simulation::default_substeps;

const FORCE_TOL: f64 = 1e-3 * 3913.0;
const LENGTH_TOL: f64 = 1e-6;

fn check(name: &str, model: ModelKind) {
    let sc = Scenario::built_in(name, &MuscleParams::default()).unwrap();
    let substeps = std::env::var("SUBSTEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default_substeps(model));
    let (df, dl) = common::worst_deviation_from_reference(&sc, model, 1000.0, substeps);
    println!("{name} {model}: worst |dF| = {df:.3e} N, worst |dl_m| = {dl:.3e} m");
    assert!(
        df <= FORCE_TOL,
        "{name} {model}: force deviation {df} N > {FORCE_TOL} N"
    );
    assert!(
        dl <= LENGTH_TOL,
        "{name} {model}: length deviation {dl} m > {LENGTH_TOL} m"
    );
}

#[test]
fn pulse_hill_matches_reference() {
    check("pulse", ModelKind::Hill);
}
#[test]
fn pulse_huxley_matches_reference() {
    check("pulse", ModelKind::Huxley);
}
#[test]
fn energy_10hz_hill_matches_reference() {
    check("energy-10hz", ModelKind::Hill);
}
#[test]
fn energy_100hz_hill_matches_reference() {
    check("energy-100hz", ModelKind::Hill);
}
#[test]
fn energy_10hz_huxley_matches_reference() {
    check("energy-10hz", ModelKind::Huxley);
}
#[test]
fn energy_100hz_huxley_matches_reference() {
    check("energy-100hz", ModelKind::Huxley);
}
