//! The default `elbow` gives the results of the two-muscle program it grew from
//! (docs/validation.md, "The program this grew from"): the CSVs in `crates/core/tests/reference/` were
//! written by that program (`simulate SCENARIO --model M --csv`) for the pulse, energy and joint
//! scenarios and every model. This program reproduces them within the accuracy bounds of
//! docs/model.md §10 (force 1e-3 Fmax, length 1e-6 m), not to rounding: its block-arrowhead
//! stepper solves the same equations with another Jacobian (docs/model.md §8b). The deviations
//! are printed per file.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::MuscleParams;
use muscle_actuator_core::sim::{default_stepping, Scenario};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

const FORCE_TOL: f64 = 1e-3 * 3913.0;
const LENGTH_TOL: f64 = 1e-6;

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// Column name → values, from CSV text (read with the `csv` crate).
fn columns(text: &str) -> HashMap<String, Vec<String>> {
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = r
        .headers()
        .expect("a header")
        .iter()
        .map(String::from)
        .collect();
    let mut cols: HashMap<String, Vec<String>> =
        header.iter().map(|h| (h.clone(), Vec::new())).collect();
    for row in r.records() {
        for (h, v) in header.iter().zip(row.expect("a row").iter()) {
            cols.get_mut(h).expect("header").push(v.to_string());
        }
    }
    cols
}

fn numbers(v: &[String]) -> Vec<f64> {
    v.iter().map(|x| x.parse().expect("a number")).collect()
}

/// The reference's column names mapped to this program's: the reference's `joint_*` columns
/// are named by joint here (`elbow.*`).
fn today_name(reference: &str) -> String {
    match reference.strip_prefix("joint_") {
        Some(field) => format!("elbow.{field}"),
        None => reference.to_string(),
    }
}

/// Largest deviation of a column, relative to the column's largest magnitude.
struct Deviation {
    relative: f64,
    force: f64,
    length: f64,
}

fn compare(reference: &Path, model: ModelKind, scenario: &Scenario) -> Deviation {
    let cfg = ActuatorConfig::default();
    let run = scenario
        .run(&cfg, model, 1000.0, default_stepping(model))
        .unwrap();
    let mut now = Vec::new();
    muscle_actuator_core::csv::write_csv(&run, &mut now).unwrap();
    let now = columns(std::str::from_utf8(&now).unwrap());
    let old = columns(&std::fs::read_to_string(reference).unwrap());
    assert_eq!(old["name"], now["name"], "{}: rows", reference.display());
    let mut d = Deviation {
        relative: 0.0,
        force: 0.0,
        length: 0.0,
    };
    for (name, values) in &old {
        if name == "name" {
            continue;
        }
        let (a, b) = (numbers(values), numbers(&now[&today_name(name)]));
        let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        if scale > 0.0 {
            if worst / scale > 1e-13 {
                println!(
                    "  {name}: {:.2e} of its largest magnitude {scale:.3e}",
                    worst / scale
                );
            }
            d.relative = d.relative.max(worst / scale);
        } else {
            assert_eq!(worst, 0.0, "{}: {name} was all zero", reference.display());
        }
        if name.ends_with("force") {
            d.force = d.force.max(worst);
        }
        if name.ends_with("length") {
            d.length = d.length.max(worst);
        }
    }
    d
}

#[test]
fn the_elbow_reproduces_the_reference_runs() {
    let params = MuscleParams::default();
    let joint = Scenario::from_file(&root().join("scenarios/example.toml")).unwrap();
    let mut checked = 0;
    for model in ModelKind::all() {
        for (file, scenario) in [
            ("pulse", Scenario::built_in("pulse", &params).unwrap()),
            (
                "energy-10hz",
                Scenario::built_in("energy-10hz", &params).unwrap(),
            ),
            (
                "energy-100hz",
                Scenario::built_in("energy-100hz", &params).unwrap(),
            ),
            ("example", joint.clone()),
        ] {
            let path = root().join(format!("crates/core/tests/reference/{file}_{model}.csv"));
            let d = compare(&path, model, &scenario);
            println!(
                "{file} {model}: worst |dF| {:.2e} N, |dl| {:.2e} m, relative {:.2e}",
                d.force, d.length, d.relative
            );
            assert!(d.force <= FORCE_TOL, "{file} {model}: force {} N", d.force);
            assert!(
                d.length <= LENGTH_TOL,
                "{file} {model}: length {} m",
                d.length
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 12);
}
