//! The subject file's reader gives the four curves of data/ceinms/uncalibratedSubject.xml with
//! exactly the points that R's and SciPy's reference splines were computed from
//! (crates/core/tests/reference/tabulated/fmm_points.csv, written by
//! scripts/fmm_spline_reference.py), so the engine's spline tests against that reference speak
//! for the subject's curves.

use muscle_actuator_measured::measured::Subject;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The reference's points of the curve `name`, `(x, y)` in order.
fn reference_points(table: &str, name: &str) -> Vec<(f64, f64)> {
    table
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|r| r[0] == name)
        .map(|r| (r[2].parse().unwrap(), r[3].parse().unwrap()))
        .collect()
}

#[test]
fn the_subject_files_curves_are_the_reference_points() {
    let xml = std::fs::read_to_string(root().join("data/ceinms/uncalibratedSubject.xml")).unwrap();
    let table = std::fs::read_to_string(
        root().join("crates/core/tests/reference/tabulated/fmm_points.csv"),
    )
    .unwrap();
    let subject = Subject::parse(&xml).unwrap();
    let c = &subject.defaults.curves;
    let tendon = c.tendon_force_strain.as_ref().unwrap();
    for (curve, name) in [
        (&c.active_force_length, "activeForceLength"),
        (&c.passive_force_length, "passiveForceLength"),
        (&c.force_velocity, "forceVelocity"),
        (tendon, "tendonForceStrain"),
    ] {
        let expected = reference_points(&table, name);
        assert!(expected.len() > 10, "{name}: {} points", expected.len());
        let got: Vec<(f64, f64)> = curve
            .x()
            .iter()
            .copied()
            .zip(curve.y().iter().copied())
            .collect();
        assert_eq!(got, expected, "{name}");
    }
}
