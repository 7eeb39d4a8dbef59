//! The curve sets `degroote2016`, `thelen2003` and `millard2012` against OpenSim 4.6's own
//! evaluation of them,
//! crates/core/tests/reference/opensim_curves.csv (written by scripts/opensim_curves.py): every row, every
//! curve OpenSim exposes, within `REL_TOL` of OpenSim's value relative to the curve's scale
//! (Millard's derivatives and integrals within looser bounds, [`tolerance`], and the integrals
//! also against an independent quadrature).

use crate::physics::curves::quintic_bezier::SegmentedBezier;
use crate::physics::curves::{
    degroote2016 as dgf, millard2012 as mil, thelen2003, Curve, CurveSet,
};
use std::collections::BTreeMap;

const REFERENCE: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/reference/opensim_curves.csv"
));

/// Allowed difference, relative to `max(|OpenSim's value|, FLOOR)`.
const REL_TOL: f64 = 1e-12;
/// Below this magnitude a difference counts as absolute (curves that cross zero: a relative
/// error there measures the cancellation, not the formula).
const FLOOR: f64 = 1e-3;

/// Millard's derivatives: OpenSim solves x(u) = x only to |x(u) - x| <= 100 ε
/// (`SegmentedQuinticBezierToolkit::calcU`), which moves dy/dx = y'(u)/x'(u) by up to about
/// 1e-10 where x'(u) is small; the values themselves agree within `REL_TOL`.
const MILLARD_DERIVATIVE_TOL: f64 = 1e-9;
/// Millard's integrals: OpenSim integrates the curve numerically and fits a spline through 100
/// points a segment (`SmoothSegmentedFunction`), good to about 1e-5 of the curve's scale; the
/// Rust integral is exact (five-point Gauss–Legendre on a degree-9 polynomial), which
/// `millard_integrals_match_a_fine_quadrature` checks.
const MILLARD_INTEGRAL_TOL: f64 = 2e-4;

/// The bound on a row's scaled error.
fn tolerance(set: &str, curve: &str) -> f64 {
    match set {
        "millard2012" if curve.ends_with("_derivative") => MILLARD_DERIVATIVE_TOL,
        "millard2012" if curve.ends_with("_integral") => MILLARD_INTEGRAL_TOL,
        _ => REL_TOL,
    }
}

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
        ("millard2012", _) => millard_curve(curve),
        _ => panic!("no Rust curve for {set}/{curve}"),
    }
}

/// Millard's derivatives and integrals, from the curves built with the default constants.
fn millard_curve(name: &str) -> Box<dyn Fn(f64) -> f64> {
    let (base, what) = name
        .rsplit_once('_')
        .expect("a Millard row beyond the four curves names a derivative or an integral");
    let curve: SegmentedBezier = match base {
        "active_force_length" => mil::active_force_length_curve(mil::ACTIVE_MINIMUM_VALUE),
        "passive_force_length" => {
            mil::passive_force_length_curve(mil::DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE)
        }
        "force_velocity" => mil::force_velocity_curve(
            mil::FV_CONCENTRIC_SLOPE_AT_VMAX,
            mil::FV_ECCENTRIC_SLOPE_AT_VMAX,
        ),
        "tendon_force_length" => {
            mil::tendon_force_length_curve(mil::DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE)
        }
        _ => panic!("no Millard curve {base}"),
    }
    .expect("the default constants form corners");
    match what {
        "derivative" => Box::new(move |x| curve.slope(x)),
        "integral" => Box::new(move |x| curve.integral(x)),
        _ => panic!("no Millard {what} of {base}"),
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
        if w.scaled > tolerance(set, curve) {
            failed.push(format!("{set}/{curve}"));
        }
    }
    assert!(failed.is_empty(), "beyond their bounds: {failed:?}");
    // Every curve of the three OpenSim sets is in the file.
    for set in ["degroote2016", "thelen2003", "millard2012"] {
        for c in Curve::ALL {
            assert!(
                worst.contains_key(&(set.to_string(), c.name().to_string())),
                "{set}/{}",
                c.name()
            );
        }
    }
}

/// Millard's integrals against composite Simpson's rule on the curve's own values (4000
/// intervals from the curve's first end point; error of order 1e-14 on these smooth pieces),
/// inside the curve, across its segment joints and on its linear continuation.
#[test]
fn millard_integrals_match_a_fine_quadrature() {
    let curves = [
        (
            "passive",
            mil::passive_force_length_curve(mil::DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE).unwrap(),
            1.0,
            [1.003, 1.05, 1.3, 1.7, 1.9],
        ),
        (
            "tendon",
            mil::tendon_force_length_curve(mil::DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE).unwrap(),
            1.0,
            [1.001, 1.01, 1.02, 1.04, 1.08],
        ),
    ];
    for (name, curve, start, ends) in curves {
        for end in ends {
            let n = 4000;
            let h = (end - start) / n as f64;
            let mut sum = curve.value(start) + curve.value(end);
            for i in 1..n {
                let w = if i % 2 == 1 { 4.0 } else { 2.0 };
                sum += w * curve.value(start + i as f64 * h);
            }
            let simpson = sum * h / 3.0;
            let exact = curve.integral(end);
            println!("{name} to {end}: {exact:.15e} (Simpson {simpson:.15e})");
            assert!(
                (exact - simpson).abs() <= 1e-12 * simpson.abs().max(1e-3),
                "{name} to {end}: {exact} vs {simpson}"
            );
        }
        assert_eq!(curve.integral(start), 0.0, "{name}");
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
