//! The recursion against its closed form: a unit step from rest gives, for distinct roots
//! p1 = -C1, p2 = -C2 (residues of `α z^(k+2)/((z - 1)(z - p1)(z - p2))`),
//! `u_k = 1 + α p1^(k+2)/((p1 - 1)(p1 - p2)) + α p2^(k+2)/((p2 - 1)(p2 - p1))`, and for a repeated
//! root p, `u_k = 1 + α ((k + 2) p^(k+1)/(p - 1) - p^(k+2)/(p - 1)²)`; unit steady-state gain;
//! the delay exact to the sample; the conversion to another period.

use crate::emg::error::EmgError;
use crate::emg::neural::{
    delay_samples, neural_activation, NeuralActivation, NeuralParams, MAX_DELAY_SAMPLES,
};

/// CEINMS's subject before calibration, Lloyd & Besier's bounds' inside, a repeated root.
const PAIRS: [(f64, f64); 5] = [
    (0.768956, -0.990048),
    (-0.6, -0.3),
    (-0.95, -0.05),
    (0.4, -0.2),
    (-0.7, -0.7),
];

fn step_response(c1: f64, c2: f64, n: usize) -> Vec<f64> {
    neural_activation(&vec![1.0; n], NeuralParams::new(c1, c2).unwrap(), 0).unwrap()
}

fn closed_form(c1: f64, c2: f64, k: i32) -> f64 {
    let (p1, p2) = (-c1, -c2);
    let alpha = (1.0 - p1) * (1.0 - p2);
    if p1 == p2 {
        let p = p1;
        1.0 + alpha
            * (f64::from(k + 2) * p.powi(k + 1) / (p - 1.0) - p.powi(k + 2) / (p - 1.0).powi(2))
    } else {
        1.0 + alpha * p1.powi(k + 2) / ((p1 - 1.0) * (p1 - p2))
            + alpha * p2.powi(k + 2) / ((p2 - 1.0) * (p2 - p1))
    }
}

#[test]
fn alpha_gives_unit_steady_state_gain() {
    for (c1, c2) in PAIRS {
        let p = NeuralParams::new(c1, c2).unwrap();
        assert!((p.alpha() - (1.0 + c1) * (1.0 + c2)).abs() <= 1e-15);
        assert!((p.alpha() / (1.0 + p.beta1() + p.beta2()) - 1.0).abs() <= 1e-15);
        for level in [0.25, 1.0] {
            let u = neural_activation(&vec![level; 3000], p, 0).unwrap();
            assert!((u[2999] - level).abs() <= 1e-12, "{c1} {c2}: {}", u[2999]);
        }
    }
}

#[test]
fn step_response_matches_the_closed_form() {
    let mut worst = 0.0f64;
    for (c1, c2) in PAIRS {
        let u = step_response(c1, c2, 400);
        for (k, uk) in u.iter().enumerate() {
            let d = (uk - closed_form(c1, c2, k as i32)).abs();
            assert!(
                d <= 1e-12,
                "C1 {c1}, C2 {c2}, k {k}: {uk} vs {}",
                closed_form(c1, c2, k as i32)
            );
            worst = worst.max(d);
        }
        assert!((u[0] - (1.0 + c1) * (1.0 + c2)).abs() <= 1e-15, "u_0 = α");
    }
    eprintln!("step response: largest difference from the closed form {worst:.2e}");
}

#[test]
fn repeated_root_is_critically_damped() {
    // No overshoot and a monotonic rise for C1 = C2 < 0 (a repeated positive root).
    let u = step_response(-0.7, -0.7, 300);
    assert!(u.windows(2).all(|w| w[1] >= w[0]));
    assert!(u.iter().all(|&v| v <= 1.0 + 1e-15));
}

#[test]
fn an_impulse_comes_out_exactly_d_samples_later() {
    let p = NeuralParams::new(-0.6, -0.3).unwrap();
    let mut impulse = vec![0.0; 200];
    impulse[0] = 1.0;
    let undelayed = neural_activation(&impulse, p, 0).unwrap();
    for d in [1, 7, 40, 150] {
        let delayed = neural_activation(&impulse, p, d).unwrap();
        assert!(delayed[..d].iter().all(|&v| v == 0.0), "d {d}");
        assert_eq!(delayed[d], p.alpha(), "d {d}");
        assert_eq!(&delayed[d..], &undelayed[..200 - d], "d {d}");
    }
}

#[test]
fn delay_in_seconds_rounds_to_the_nearest_sample() {
    assert_eq!(delay_samples(0.04, 0.001), Ok(40));
    assert_eq!(delay_samples(0.3, 0.25), Ok(1));
    assert_eq!(
        delay_samples(0.375, 0.25),
        Ok(2),
        "a half rounds away from zero"
    );
    assert_eq!(delay_samples(0.0, 0.001), Ok(0));
    let state =
        NeuralActivation::with_delay_s(NeuralParams::new(-0.5, -0.5).unwrap(), 0.0152, 0.001)
            .unwrap();
    assert_eq!(state.delay_samples(), 15);
}

#[test]
fn stepped_state_equals_the_whole_signal_and_settles() {
    let p = NeuralParams::new(0.768956, -0.990048).unwrap();
    let e: Vec<f64> = (0..500)
        .map(|k| (0.5 + 0.4 * (k as f64 * 0.05).sin()).clamp(0.0, 1.0))
        .collect();
    let whole = neural_activation(&e, p, 12).unwrap();
    let mut state = NeuralActivation::new(p, 12).unwrap();
    let stepped: Vec<f64> = e.iter().map(|&v| state.step(v)).collect();
    assert_eq!(stepped, whole);
    state.settle(0.4);
    for _ in 0..50 {
        assert!((state.step(0.4) - 0.4).abs() <= 1e-15);
    }
    state.reset();
    assert_eq!(state.step(0.0), 0.0);
    // Out-of-range and NaN inputs are clamped (NaN as 0): the state stays finite.
    assert_eq!(state.step(f64::NAN), 0.0);
    assert!(state.step(7.0).is_finite());
}

#[test]
fn conversion_to_another_period_keeps_the_roots_and_refuses_a_negative_root() {
    let p = NeuralParams::new(-0.6, -0.3).unwrap();
    let half = p.at_period(0.001, 0.0005).unwrap();
    // Two steps of the new roots make one of the old.
    assert!((half.c1().powi(2) - 0.6).abs() <= 1e-15 && (half.c2().powi(2) - 0.3).abs() <= 1e-15);
    let back = half.at_period(0.0005, 0.001).unwrap();
    assert!((back.c1() - p.c1()).abs() <= 1e-15 && (back.c2() - p.c2()).abs() <= 1e-15);
    assert_eq!(p.at_period(0.001, 0.001).unwrap(), p);
    // The forced response is close, not equal: compare the step responses at common times.
    let slow = step_response(p.c1(), p.c2(), 100);
    let fast = step_response(half.c1(), half.c2(), 200);
    let gap = slow
        .iter()
        .enumerate()
        .map(|(k, v)| (v - fast[2 * k + 1]).abs())
        .fold(0.0, f64::max);
    eprintln!("at half the period: step responses differ by at most {gap:.3} at common instants");
    assert!(gap < 0.1, "{gap}");
    let err = NeuralParams::new(0.768956, -0.990048)
        .unwrap()
        .at_period(0.001, 0.002);
    assert_eq!(
        err,
        Err(EmgError::NoOtherPeriod {
            name: "C1",
            value: 0.768956
        })
    );
}

#[test]
fn refusals() {
    for (c1, c2, name) in [
        (1.0, 0.0, "C1"),
        (-1.0, 0.0, "C1"),
        (0.0, f64::NAN, "C2"),
        (0.0, -1.5, "C2"),
    ] {
        match NeuralParams::new(c1, c2) {
            Err(EmgError::Coefficient { name: n, .. }) => assert_eq!(n, name),
            other => panic!("{c1} {c2}: {other:?}"),
        }
    }
    let p = NeuralParams::new(-0.5, -0.5).unwrap();
    for bad in [-0.001, 0.6, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(delay_samples(bad, 0.001), Err(EmgError::Delay { .. })),
            "{bad}"
        );
    }
    for bad in [0.0, -0.001, f64::NAN] {
        assert!(
            matches!(delay_samples(0.01, bad), Err(EmgError::SamplePeriod { .. })),
            "{bad}"
        );
        assert!(
            matches!(p.at_period(0.001, bad), Err(EmgError::SamplePeriod { .. })),
            "{bad}"
        );
    }
    assert!(matches!(
        delay_samples(0.4, 1e-6),
        Err(EmgError::DelaySamples { .. })
    ));
    assert!(matches!(
        delay_samples(0.4, 1e-310),
        Err(EmgError::DelaySamples { .. })
    ));
    assert!(matches!(
        NeuralActivation::new(p, MAX_DELAY_SAMPLES + 1),
        Err(EmgError::DelaySamples { .. })
    ));
    assert!(matches!(
        neural_activation(&[0.1, f64::NAN], p, 0),
        Err(EmgError::NonFiniteSample { index: 1, .. })
    ));
}
