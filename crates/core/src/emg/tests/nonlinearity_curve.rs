//! The nonlinearity at its ends, against direct evaluation of `(exp(A u) - 1)/(exp(A) - 1)`,
//! increasing, symmetric about (½, ½) under A → -A, continuous across the switch to its series
//! at |A| = 1e-5, and its accepted range.

use crate::emg::error::EmgError;
use crate::emg::nonlinearity::{activation, ShapeFactor, LINEAR_BELOW};

/// CEINMS's uncalibrated value, the calibrated range's ends and inside, both sides of the
/// switch, zero, the positive end.
const SHAPES: [f64; 10] = [
    -3.0, -2.999, -1.0, -0.001, -1e-6, 0.0, 1e-6, 0.101198, 1.0, 3.0,
];

fn a(u: f64, shape: f64) -> f64 {
    activation(u, ShapeFactor::new(shape).unwrap())
}

#[test]
fn ends_map_to_themselves() {
    for s in SHAPES {
        assert_eq!(a(0.0, s), 0.0, "A {s}");
        assert_eq!(a(1.0, s), 1.0, "A {s}");
        assert_eq!(a(-0.5, s), 0.0, "clamped below, A {s}");
        assert_eq!(a(1.5, s), 1.0, "clamped above, A {s}");
    }
}

#[test]
fn interior_matches_direct_evaluation() {
    let mut worst = 0.0f64;
    for s in SHAPES {
        for i in 1..100 {
            let u = i as f64 / 100.0;
            // Direct evaluation loses digits to cancellation when A u is small (about ε/|A u|):
            // below |A| = 1e-3 the reference is the quotient of expm1s, exact to rounding.
            let direct = if s == 0.0 {
                u
            } else if s.abs() < 1e-3 {
                (s * u).exp_m1() / s.exp_m1()
            } else {
                ((s * u).exp() - 1.0) / (s.exp() - 1.0)
            };
            let d = (a(u, s) - direct).abs() / direct;
            assert!(d <= 1e-10, "A {s}, u {u}: {} vs {direct}", a(u, s));
            if s.abs() >= 0.1 {
                worst = worst.max(d);
            }
        }
    }
    eprintln!(
        "nonlinearity: largest relative difference from direct evaluation (|A| ≥ 0.1) {worst:.2e}"
    );
    assert!(worst <= 1e-12);
}

#[test]
fn increasing_and_turned_half_about_the_centre_under_minus_a() {
    for s in SHAPES {
        let curve: Vec<f64> = (0..=10_000).map(|i| a(i as f64 / 10_000.0, s)).collect();
        assert!(curve.windows(2).all(|w| w[1] > w[0]), "A {s}");
        for i in 0..=100 {
            let u = i as f64 / 100.0;
            assert!(
                (a(u, -s) - (1.0 - a(1.0 - u, s))).abs() <= 1e-15,
                "A {s}, u {u}"
            );
        }
    }
    assert!(
        a(0.2, -2.0) > 0.2 && a(0.2, 2.0) < 0.2,
        "concave below 0, convex above"
    );
}

#[test]
fn continuous_across_the_switch_to_the_series() {
    let mut worst = 0.0f64;
    for sign in [-1.0, 1.0] {
        let below = ShapeFactor::new(sign * LINEAR_BELOW * (1.0 - 1e-12)).unwrap();
        let above = ShapeFactor::new(sign * LINEAR_BELOW).unwrap();
        for i in 0..=1000 {
            let u = i as f64 / 1000.0;
            worst = worst.max((activation(u, below) - activation(u, above)).abs());
        }
    }
    eprintln!("nonlinearity: largest jump across |A| = 1e-5 {worst:.2e}");
    assert!(worst <= 1e-15, "{worst}");
    assert_eq!(a(0.37, 0.0), 0.37);
}

#[test]
fn shape_factor_range() {
    for ok in [-3.0, 3.0, 0.0, 0.101198, -2.999] {
        assert_eq!(ShapeFactor::new(ok).map(ShapeFactor::value), Ok(ok));
    }
    for bad in [-3.0001, 3.5, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert!(
            matches!(ShapeFactor::new(bad), Err(EmgError::ShapeFactor { .. })),
            "{bad}"
        );
    }
}
