//! The muscles against OpenSim 4.6 itself (docs/validation.md "Against OpenSim"): for every
//! reference `crates/core/tests/reference/opensim/CONFIG__MOTION.csv` (OpenSim's DeGrooteFregly2016Muscle,
//! Thelen2003Muscle or Millard2012EquilibriumMuscle, elastic or rigid tendon, pennation 0 or 0.2
//! rad, under a clamped pulse, a ramp stretch and a sinusoid; scripts/opensim_validation.py), the
//! same muscle here
//! (`crates/core/tests/opensim/CONFIG.config.toml`: an equilibrium Hill fibre with the set's curves, the
//! default stepping) under the same motion (`crates/core/tests/opensim/MOTION.scenario.toml`) gives the
//! tendon force and fibre length OpenSim does, within the bounds below, from 0.1 s on (before,
//! the engine's rest at zero activation and OpenSim's equilibrium at 0.01 differ). The inputs the
//! reference was computed from, the engine's activation and path length after each tick, are
//! checked first: a reference made from other inputs fails.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::TendonKind;
use muscle_actuator_core::sim::{default_stepping, Scenario};
use std::path::{Path, PathBuf};

/// The bound on the RMS tendon-force difference, as a fraction of Fmax.
const FORCE_RMS_BOUND: f64 = 0.005;
/// The bound on the RMS fibre-length difference, as a fraction of l_opt.
const LENGTH_RMS_BOUND: f64 = 1e-4;
/// From when the runs are compared, s.
const COMPARED_FROM: f64 = 0.1;
/// The slider in every configuration: L = 0.3 m - 0.02 m/rad × angle.
const PATH: f64 = 0.3;
const ARM: f64 = 0.02;
/// The activation an equilibrium fibre without damper works with at least (docs/model.md §5b),
/// what the reference was given on an elastic tendon.
const FLOOR: f64 = 0.01;

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// (t, activation, mtu_length, tendon_force, fiber_length) per row.
fn read_reference(path: &Path) -> Vec<[f64; 5]> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    assert_eq!(
        lines.next(),
        Some("t,activation,mtu_length,tendon_force,fiber_length")
    );
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3], v[4]]
        })
        .collect()
}

fn rms(x: &[f64]) -> f64 {
    (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
}

#[test]
fn the_muscles_agree_with_opensim() {
    let dir = root().join("crates/core/tests/reference/opensim");
    let mut refs: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .collect();
    refs.sort();
    assert_eq!(refs.len(), 39, "13 muscles × 3 motions in {dir:?}");
    println!(
        "{:<40} {:>14} {:>12} {:>14} {:>12}",
        "case", "RMS ΔF %Fmax", "max ΔF N", "RMS Δl_m µm", "max Δl_m µm"
    );
    let mut failures = Vec::new();
    for path in &refs {
        let name = path.file_stem().unwrap().to_str().unwrap();
        let (config, motion) = name.split_once("__").unwrap();
        let cases = root().join("crates/core/tests/opensim");
        let cfg = ActuatorConfig::from_file(&cases.join(format!("{config}.config.toml"))).unwrap();
        let sc = Scenario::from_file(&cases.join(format!("{motion}.scenario.toml"))).unwrap();
        let p = cfg.muscles[0].params.clone();
        let model = ModelKind::HILL;
        let run = sc
            .run(&cfg, model, 1000.0, default_stepping(model))
            .unwrap();
        let reference = read_reference(path);
        let records: Vec<_> = run.records().collect();
        assert_eq!(records.len(), reference.len(), "{name}: rows");
        let (mut d_force, mut d_length) = (Vec::new(), Vec::new());
        for (r, row) in records.iter().zip(&reference) {
            let m = r.muscles[0];
            // The inputs OpenSim was given are this run's.
            let a = if p.tendon == TendonKind::Elastic {
                m.activation.max(FLOOR)
            } else {
                m.activation
            };
            assert!((r.time - row[0]).abs() < 1e-12, "{name}: time {}", r.time);
            // (Thelen2003Muscle's activation is a state of OpenSim's, read back within 1e-8.)
            assert!(
                (a - row[1]).abs() < 1e-8,
                "{name} at {}: activation",
                r.time
            );
            let length = PATH - ARM * r.joints[0].position;
            assert!(
                (length - row[2]).abs() < 1e-12,
                "{name} at {}: path",
                r.time
            );
            if r.time >= COMPARED_FROM {
                d_force.push(m.force - row[3]);
                d_length.push(m.fiber_length - row[4]);
            }
        }
        let max = |x: &[f64]| x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let (f_rms, l_rms) = (rms(&d_force) / p.f_max, rms(&d_length) / p.l_opt);
        println!(
            "{name:<40} {:>14.4} {:>12.3} {:>14.3} {:>12.3}",
            100.0 * f_rms,
            max(&d_force),
            1e6 * rms(&d_length),
            1e6 * max(&d_length)
        );
        if f_rms > FORCE_RMS_BOUND || l_rms > LENGTH_RMS_BOUND {
            failures.push(format!(
                "{name}: force {f_rms:.2e} Fmax, length {l_rms:.2e} l_opt"
            ));
        }
    }
    assert!(failures.is_empty(), "beyond the bounds: {failures:#?}");
}
