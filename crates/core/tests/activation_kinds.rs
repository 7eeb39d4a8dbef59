//! A muscle's activation kind (docs/model.md §2b, docs/configuration.md "Activation"): Lloyd &
//! Besier's recursion stepped once per tick gives the activation the closed-form solution of its
//! difference equation gives, delayed by exactly its delay in ticks and bent by its
//! nonlinearity; a saved state continues it bit for bit; its constants belong to
//! `neural_rate_hz`; the keys are refused where they do not apply.

mod common;

use common::fixtures::refusal;
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::ActivationKind;
use muscle_actuator_core::sim::Actuator;

const RATE: f64 = 1000.0;

/// The default elbow with the flexor on Lloyd & Besier's activation.
fn elbow(c1: f64, c2: f64, shape: f64, delay_s: f64) -> ActuatorConfig {
    let mut cfg = ActuatorConfig::default();
    let p = &mut cfg.muscles[0].params;
    p.activation = ActivationKind::LloydBesier;
    (p.c1, p.c2, p.shape_factor, p.em_delay) = (Some(c1), Some(c2), Some(shape), Some(delay_s));
    cfg
}

/// The unit step response of `u_n = α e_n − β1 u_{n−1} − β2 u_{n−2}` from rest (distinct roots
/// r1 = −C1, r2 = −C2): `u_n = 1 + P r1^n + Q r2^n`, P and Q from `u_{−1} = u_{−2} = 0`.
fn step_response(c1: f64, c2: f64, n: i32) -> f64 {
    let (r1, r2) = (-c1, -c2);
    // X = P / r1, Y = Q / r2: X + Y = −1 and X / r1 + Y / r2 = −1.
    let y = (1.0 / r1 - 1.0) / (1.0 / r2 - 1.0 / r1);
    let x = -1.0 - y;
    1.0 + x * r1 * r1.powi(n) + y * r2 * r2.powi(n)
}

/// The excitation steps to 1 at the first tick: the flexor's activation after tick k + 1 is
/// the step response at k − d, d the delay in ticks (zero before), through the nonlinearity.
#[test]
fn the_recursion_in_the_engine_is_its_closed_form_delayed_and_bent() {
    let (c1, c2) = (-0.6, -0.3);
    for (shape, delay_s, delay_ticks) in [(0.0, 0.0, 0), (0.0, 0.0034, 3), (-2.0, 0.012, 12)] {
        let cfg = elbow(c1, c2, shape, delay_s);
        let mut a = Actuator::new(&cfg, ModelKind::HILL, RATE).unwrap();
        a.set_excitation(0, 1.0);
        let mut worst: f64 = 0.0;
        for k in 0..200 {
            a.step().unwrap();
            let n = k - delay_ticks;
            let u = if n < 0 { 0.0 } else { step_response(c1, c2, n) };
            let want = if shape == 0.0 {
                u
            } else {
                ((shape * u).exp() - 1.0) / (shape.exp() - 1.0)
            };
            let got = a.muscles()[0].activation;
            if n < 0 {
                assert_eq!(
                    got, 0.0,
                    "A = {shape}, d = {delay_ticks}: tick {k} before the delay"
                );
            }
            worst = worst.max((got - want).abs());
        }
        println!("A = {shape}, delay {delay_ticks} ticks: largest difference {worst:.1e}");
        assert!(worst < 1e-13, "A = {shape}, d = {delay_ticks}: {worst:e}");
        // The extensor keeps the paper's first order: at rest, unexcited.
        assert_eq!(a.muscles()[1].activation, 0.0);
        // Unit gain: the activation has settled at the nonlinearity of 1, i.e. 1.
        assert!((a.muscles()[0].activation - 1.0).abs() < 1e-12);
    }
}

/// A saved state holds the recursion: the restored actuator continues bit for bit, the
/// recursion's past and its delay line included.
#[test]
fn a_saved_state_continues_the_recursion_bit_for_bit() {
    let cfg = elbow(-0.7, -0.2, -1.0, 0.02);
    let mut a = Actuator::new(&cfg, ModelKind::HUXLEY, RATE).unwrap();
    let drive = |a: &mut Actuator, k: usize| {
        a.set_excitation(0, 0.5 + 0.4 * (k as f64 * 0.031).sin());
        a.step().unwrap();
    };
    for k in 0..137 {
        drive(&mut a, k);
    }
    let mut b = Actuator::from_bytes(&a.to_bytes()).unwrap();
    for k in 137..400 {
        drive(&mut a, k);
        drive(&mut b, k);
        assert_eq!(
            a.muscles()[0].activation.to_bits(),
            b.muscles()[0].activation.to_bits(),
            "tick {k}"
        );
        assert_eq!(
            a.muscles()[0].force.to_bits(),
            b.muscles()[0].force.to_bits()
        );
    }
    // A reset forgets the recursion: the same excitations give the same run again.
    a.reset();
    let mut c = Actuator::new(&cfg, ModelKind::HUXLEY, RATE).unwrap();
    for k in 0..50 {
        drive(&mut a, k);
        drive(&mut c, k);
    }
    assert_eq!(
        a.muscles()[0].force.to_bits(),
        c.muscles()[0].force.to_bits()
    );
}

/// Constants given for another rate are converted by keeping each root's time constant: with
/// constants for 1 kHz, a 500 Hz tick's recursion leaves the step's transient decaying per
/// second as at 1 kHz (0.2 s after the step, within 20 %); taken unconverted, the 500 Hz
/// recursion would be 0.98^100 against 0.98^200 from its end, 7.5 times as far.
#[test]
fn constants_for_another_rate_keep_their_time_constants() {
    let mut at_1khz = elbow(-0.98, -0.9, 0.0, 0.0);
    at_1khz.muscles[0].params.neural_rate_hz = Some(1000.0);
    let remaining = |cfg: &ActuatorConfig, rate: f64| {
        let mut a = Actuator::new(cfg, ModelKind::HILL, rate).unwrap();
        a.set_excitation(0, 1.0);
        for _ in 0..(0.2 * rate) as usize {
            a.step().unwrap();
        }
        1.0 - a.muscles()[0].activation
    };
    let fast = remaining(&at_1khz, 1000.0);
    let slow = remaining(&at_1khz, 500.0);
    let mut unconverted = at_1khz.clone();
    unconverted.muscles[0].params.neural_rate_hz = None;
    let naive = remaining(&unconverted, 500.0);
    println!("0.2 s after the step, 1 - a: {fast:.4e} at 1 kHz, {slow:.4e} at 500 Hz converted, {naive:.4e} unconverted");
    assert!((slow / fast - 1.0).abs() < 0.2, "{fast} {slow}");
    assert!(naive / fast > 5.0, "{fast} {naive}");
    // A positive C has no counterpart at another rate: refused when the simulation is built.
    let mut bad = at_1khz.clone();
    bad.muscles[0].params.c1 = Some(0.5);
    let err = Actuator::new(&bad, ModelKind::HILL, 500.0)
        .unwrap_err()
        .to_string();
    println!("{err}");
    assert!(
        err.contains("muscle 0's activation") && err.contains("C1"),
        "{err}"
    );
    assert!(Actuator::new(&bad, ModelKind::HILL, 1000.0).is_ok());
}

/// Each bad setting is refused on one line naming the key and its rule; the default writes
/// none of the keys.
#[test]
fn bad_activation_settings_are_refused_on_one_line() {
    let lb = "activation = \"lloyd_besier\"\n";
    let cases: Vec<(String, Vec<&str>)> = vec![
        (
            "activation = \"second_order\"".into(),
            vec!["first_order, lloyd_besier"],
        ),
        (
            "c1 = -0.5".into(),
            vec!["muscle.flexor.c1", "lloyd_besier\" only"],
        ),
        (
            "em_delay = 0.02".into(),
            vec!["muscle.flexor.em_delay", "only"],
        ),
        (
            format!("{lb}c2 = -0.5"),
            vec!["muscle.flexor.c1", "is needed"],
        ),
        (
            format!("{lb}c1 = -0.5"),
            vec!["muscle.flexor.c2", "is needed"],
        ),
        (
            format!("{lb}c1 = -1.0\nc2 = -0.5"),
            vec!["muscle.flexor.c1", "> -1 and < 1"],
        ),
        (
            format!("{lb}c1 = -0.5\nc2 = -0.5\nshape_factor = -4.0"),
            vec!["muscle.flexor.shape_factor", "-3"],
        ),
        (
            format!("{lb}c1 = -0.5\nc2 = -0.5\nem_delay = 0.6"),
            vec!["muscle.flexor.em_delay", "0.5 s"],
        ),
        (
            format!("{lb}c1 = -0.5\nc2 = -0.5\nneural_rate_hz = 0.0"),
            vec!["muscle.flexor.neural_rate_hz", "> 0"],
        ),
    ];
    for (keys, needles) in &cases {
        let message = refusal(keys);
        println!("{keys:?}: {message}");
        assert_eq!(message.lines().count(), 1, "{keys}: {message}");
        for n in needles {
            assert!(message.contains(n), "{keys}: {message:?} lacks {n:?}");
        }
    }
    let default = toml::to_string(&ActuatorConfig::default()).unwrap();
    for key in [
        "activation",
        "c1",
        "c2",
        "shape_factor",
        "em_delay",
        "neural_rate_hz",
    ] {
        let line = format!("\n{key} = ");
        assert!(!default.contains(&line), "{key} in\n{default}");
    }
    let cfg = elbow(-0.5, -0.4, -1.0, 0.01);
    let back = ActuatorConfig::from_toml_str(&toml::to_string(&cfg).unwrap()).unwrap();
    assert_eq!(back, cfg);
}
