//! The curve sets `degroote2016` and `thelen2003` against OpenSim 4.6's own evaluation of them,
//! tests/reference/opensim_curves.csv (written by scripts/opensim_curves.py): every row, every
//! curve OpenSim exposes, within `REL_TOL` of OpenSim's value relative to the curve's scale.

use muscle_actuator_core::physics::curves::{degroote2016 as dgf, thelen2003, Curve, CurveSet};
use std::collections::BTreeMap;

const REFERENCE: &str = include_str!("../../../tests/reference/opensim_curves.csv");

/// Allowed difference, relative to `max(|OpenSim's value|, FLOOR)`.
const REL_TOL: f64 = 1e-12;
/// Below this magnitude a difference counts as absolute (curves that cross zero: a relative
/// error there measures the cancellation, not the formula).
const FLOOR: f64 = 1e-3;

/// The Rust function for a row's set and curve; every name in the file must have one.
fn rust_curve(set: &str, curve: &str) -> Box<dyn Fn(f64) -> f64> {
    if let Some(c) = Curve::ALL.into_iter().find(|c| c.name() == curve) {
        let set: CurveSet = set.parse().expect("a curve set's name");
        return Box::new(move |x| set.evaluate(c, x).expect("an OpenSim set has every curve"));
    }
    let k_t = dgf::tendon_shape(dgf::DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE);
    let e0 = dgf::DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE;
    let shape = thelen2003::ForceVelocityShape::default();
    match (set, curve) {
        ("degroote2016", "active_force_length_derivative") => Box::new(|x| {
            dgf::active_force_length_derivative(x, dgf::DEFAULT_ACTIVE_FORCE_WIDTH_SCALE)
        }),
        ("degroote2016", "passive_force_length_derivative") => {
            Box::new(move |x| dgf::passive_force_length_derivative(x, e0))
        }
        ("degroote2016", "force_velocity_inverse") => Box::new(dgf::force_velocity_inverse),
        ("degroote2016", "tendon_force_length_derivative") => {
            Box::new(move |x| dgf::tendon_force_length_derivative(x, k_t))
        }
        ("degroote2016", "tendon_force_length_inverse") => {
            Box::new(move |x| dgf::tendon_force_length_inverse(x, k_t))
        }
        ("thelen2003", "tendon_force_length_derivative") => Box::new(|x| {
            thelen2003::tendon_force_length_derivative(x, thelen2003::DEFAULT_FMAX_TENDON_STRAIN)
        }),
        ("thelen2003", "force_velocity_half_activation") => {
            Box::new(move |x| thelen2003::force_velocity(x, 0.5, &shape))
        }
        _ => panic!("no Rust curve for {set}/{curve}"),
    }
}

#[derive(Default)]
struct Worst {
    rows: usize,
    /// Largest |Rust - OpenSim| / max(|OpenSim|, FLOOR).
    scaled: f64,
    /// Largest |Rust - OpenSim| / |OpenSim| over the rows where OpenSim's value is not zero.
    relative: f64,
    at: f64,
}

#[test]
fn every_row_matches_opensim() {
    let mut lines = REFERENCE.lines();
    let header = lines.next().unwrap();
    assert!(header.starts_with("# OpenSim version 4.6-"), "{header}");
    assert_eq!(lines.next(), Some("set,curve,x,value"));
    let mut worst: BTreeMap<(String, String), Worst> = BTreeMap::new();
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 4, "{line}");
        let (x, opensim): (f64, f64) = (f[2].parse().unwrap(), f[3].parse().unwrap());
        let rust = rust_curve(f[0], f[1])(x);
        let diff = (rust - opensim).abs();
        let w = worst.entry((f[0].into(), f[1].into())).or_default();
        w.rows += 1;
        if opensim != 0.0 {
            w.relative = w.relative.max(diff / opensim.abs());
        }
        let scaled = diff / opensim.abs().max(FLOOR);
        if scaled >= w.scaled {
            (w.scaled, w.at) = (scaled, x);
        }
    }
    let mut failed = Vec::new();
    for ((set, curve), w) in &worst {
        println!(
            "{set:13} {curve:34} {:3} rows  max scaled error {:.2e}  max relative {:.2e}  (at x = {})",
            w.rows, w.scaled, w.relative, w.at
        );
        if w.scaled > REL_TOL {
            failed.push(format!("{set}/{curve}"));
        }
    }
    assert!(failed.is_empty(), "beyond {REL_TOL:e}: {failed:?}");
    // Every curve of both OpenSim sets is in the file.
    for set in ["degroote2016", "thelen2003"] {
        for c in Curve::ALL {
            assert!(
                worst.contains_key(&(set.to_string(), c.name().to_string())),
                "{set}/{}",
                c.name()
            );
        }
    }
}

/// Thelen's force–velocity rows are OpenSim's (velocity, multiplier) pairs, computed by OpenSim
/// from the multiplier: the Rust velocity from the multiplier (`calcdlceN`) must give the row's
/// velocity.
#[test]
fn thelen_velocity_from_multiplier_matches_opensim() {
    let shape = thelen2003::ForceVelocityShape::default();
    let mut worst: f64 = 0.0;
    let mut rows = 0;
    for line in REFERENCE.lines().skip(2) {
        let f: Vec<&str> = line.split(',').collect();
        let activation = match (f[0], f[1]) {
            ("thelen2003", "force_velocity") => 1.0,
            ("thelen2003", "force_velocity_half_activation") => 0.5,
            _ => continue,
        };
        let (velocity, multiplier): (f64, f64) = (f[2].parse().unwrap(), f[3].parse().unwrap());
        let rust = thelen2003::force_velocity_inverse(multiplier, activation, &shape);
        worst = worst.max((rust - velocity).abs() / velocity.abs().max(FLOOR));
        rows += 1;
    }
    println!("thelen2003 force_velocity_inverse: {rows} rows, max scaled error {worst:.2e}");
    assert_eq!(rows, 120);
    assert!(worst <= REL_TOL, "{worst:e}");
}
