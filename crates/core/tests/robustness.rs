//! No user input makes the physics panic: random but valid parameter sets (every parameter
//! scaled by up to 10^±1.5) and random inputs either run with finite outputs or end in a clean
//! error, for every model.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::Actuator;

/// A small deterministic generator (SplitMix64), so failures reproduce.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn factor(&mut self) -> f64 {
        10f64.powf(3.0 * self.next() - 1.5)
    }
}

#[test]
fn random_valid_configurations_never_panic() {
    let mut rng = Rng(20261122);
    let (mut ran, mut refused) = (0, 0);
    for case in 0..40 {
        let mut cfg = ActuatorConfig::default();
        for m in &mut cfg.muscles {
            let p = &mut m.params;
            for v in [
                &mut p.mass,
                &mut p.f_max,
                &mut p.v_max,
                &mut p.t_act,
                &mut p.t_deact,
                &mut p.k_te,
                &mut p.k_tl,
                &mut p.k_t,
                &mut p.k_me,
                &mut p.k_ml,
                &mut p.k_m,
                &mut p.b_m,
            ] {
                *v *= rng.factor();
            }
            p.fl_width *= 0.5 + rng.next();
            p.crossbridge.pde_cells = 50;
        }
        cfg.joints[0].inertia *= rng.factor();
        cfg.joints[0].damping *= rng.factor();
        if cfg.validate().is_err() {
            refused += 1;
            continue;
        }
        for model in ModelKind::all() {
            let Ok(mut act) = Actuator::new(&cfg, model, 1000.0) else {
                refused += 1;
                continue;
            };
            ran += 1;
            for _ in 0..60 {
                act.set_excitation(0, rng.next());
                act.set_excitation(1, rng.next());
                act.set_external_torque(0, 20.0 * (rng.next() - 0.5));
                match act.step() {
                    Ok(()) => {
                        let j = act.joints()[0];
                        assert!(
                            j.position.is_finite() && j.torque.is_finite(),
                            "case {case} {model}"
                        );
                        assert!(act
                            .muscles()
                            .iter()
                            .all(|m| m.force.is_finite() && m.stiffness.is_finite()));
                    }
                    Err(_) => act.reset(),
                }
            }
        }
    }
    println!("ran {ran} actuators, {refused} refused");
    assert!(ran > 60, "too few runnable cases: {ran}");
}

/// A random but valid input signal over a run: levels held (steps), reached by ramps, or held
/// briefly (pulses: intervals from 1 ms to 0.5 s, log-uniform).
struct RandomSignal {
    /// (time s, level, reached by a ramp from the previous level).
    points: Vec<(f64, f64, bool)>,
}

impl RandomSignal {
    fn new(rng: &mut Rng, duration: f64, level: &mut dyn FnMut(&mut Rng) -> f64) -> Self {
        let mut points = vec![(0.0, level(rng), false)];
        let mut t = 0.0;
        loop {
            t += 10f64.powf(-3.0 + 2.7 * rng.next());
            if t >= duration {
                return Self { points };
            }
            let ramp = rng.next() < 0.3;
            points.push((t, level(rng), ramp));
        }
    }

    fn at(&self, t: f64) -> f64 {
        let k = self.points.partition_point(|p| p.0 <= t);
        let (t1, v1, _) = self.points[k - 1];
        match self.points.get(k) {
            Some(&(t2, v2, true)) => v1 + (v2 - v1) * (t - t1) / (t2 - t1),
            _ => v1,
        }
    }
}

/// Excitation levels in [0, 1], with the bounds themselves often.
fn excitation_level(rng: &mut Rng) -> f64 {
    match rng.next() {
        x if x < 0.3 => 0.0,
        x if x < 0.4 => 1.0,
        _ => rng.next(),
    }
}

/// The most torque the muscles spanning each joint can exert at θ = 0, N m (Σ |r| Fmax).
fn muscle_capacity(cfg: &ActuatorConfig) -> Vec<f64> {
    cfg.joints
        .iter()
        .map(|j| {
            cfg.muscles
                .iter()
                .flat_map(|m| m.spans.iter().map(move |s| (m, s)))
                .filter(|(_, s)| s.joint == j.name)
                .map(|(m, s)| s.moment_arm.at(0.0).abs() * m.params.f_max)
                .sum()
        })
        .collect()
}

/// Random valid input sequences (excitation steps, pulses and ramps in [0, 1]; external torques
/// within ± each joint's muscle capacity) step to the end with a finite state, for every model,
/// on the elbow and on the arm (biarticular muscles), at several tick rates. A tick may fail only
/// for a genuinely non-finite state; valid inputs never make it fail. (The DM closure's guard at
/// Q0 → 0 once made the solver fail here: docs/model.md §6, "Guards".)
#[test]
fn random_valid_input_sequences_step_to_the_end() {
    let cases = |default: usize| {
        std::env::var("ROBUSTNESS_CASES")
            .ok()
            .and_then(|v| v.parse::<usize>().ok())
            .map_or(default, |n| n.min(default * 100))
    };
    let mut rng = Rng(0x5EED_0010);
    let mut total_ticks = 0u64;
    for (model, n_cases, duration) in [
        (ModelKind::HILL, cases(1000), 1.0),
        (ModelKind::HUXLEY, cases(1000), 1.0),
        (ModelKind::HUXLEY_PDE, cases(6), 0.3),
    ] {
        for case in 0..n_cases {
            let config = if case % 4 == 3 { "arm" } else { "elbow" };
            let mut cfg = ActuatorConfig::resolve(config).unwrap();
            if model == ModelKind::HUXLEY_PDE {
                for m in &mut cfg.muscles {
                    m.params.crossbridge.pde_cells = 50;
                }
            }
            let rate = [250.0, 500.0, 1000.0, 2000.0][case % 4];
            let capacity = muscle_capacity(&cfg);
            let excitations: Vec<RandomSignal> = cfg
                .muscles
                .iter()
                .map(|_| RandomSignal::new(&mut rng, duration, &mut excitation_level))
                .collect();
            let torques: Vec<RandomSignal> = capacity
                .iter()
                .map(|&cap| {
                    RandomSignal::new(&mut rng, duration, &mut |r: &mut Rng| {
                        // Magnitudes log-uniform from a thousandth of the capacity to all
                        // of it: small loads let a released joint swing freely.
                        let magnitude = cap * 10f64.powf(-3.0 * r.next());
                        match r.next() {
                            x if x < 0.2 => 0.0,
                            x if x < 0.6 => magnitude,
                            _ => -magnitude,
                        }
                    })
                })
                .collect();
            let mut act = Actuator::new(&cfg, model, rate).unwrap();
            let ticks = (duration * rate) as u64;
            for k in 0..ticks {
                let t = k as f64 / rate;
                for (i, s) in excitations.iter().enumerate() {
                    act.set_excitation(i, s.at(t));
                }
                for (j, s) in torques.iter().enumerate() {
                    act.set_external_torque(j, s.at(t));
                }
                if let Err(e) = act.step() {
                    panic!(
                        "{model} case {case} ({config}, {rate} Hz): {e}\n excitations {:?}\n \
                         torques {:?}",
                        excitations.iter().map(|s| &s.points).collect::<Vec<_>>(),
                        torques.iter().map(|s| &s.points).collect::<Vec<_>>(),
                    );
                }
                let finite = act
                    .muscles()
                    .iter()
                    .all(|m| m.values().iter().all(|v| v.is_finite()))
                    && act
                        .joints()
                        .iter()
                        .all(|j| j.values().iter().all(|v| v.is_finite()));
                assert!(finite, "{model} case {case}: non-finite output at tick {k}");
            }
            total_ticks += ticks;
        }
        println!("{model}: {n_cases} random input sequences stepped to the end");
    }
    println!("{total_ticks} ticks in all");
}

/// A relaxed muscle stretched fast: the flexor fully excited for 5 s, relaxed for 0.3 s, excited
/// for 0.4 s and relaxed again while the extensor (0.15) and a -0.5 N m load swing the joint into
/// extension. Its moments fall to the integrator's noise (Q0 ≈ -2e-11 with Q1 ≈ 1e-7), where the
/// DM closure must be continuous as Q0 crosses zero (docs/model.md §6, "Guards"): with a guard
/// that switches at Q0 = 1e-12 the solver fails at tick 5937.
#[test]
fn a_relaxed_muscle_stretched_fast_steps_with_every_model() {
    let cfg = ActuatorConfig::default();
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        let mut act = Actuator::new(&cfg, model, 1000.0).unwrap();
        act.set_excitation(1, 0.15);
        act.set_external_torque(0, -0.5);
        for k in 0..6500u64 {
            let t = k as f64 / 1000.0;
            let on = t < 5.0 || (5.3..5.701).contains(&t);
            act.set_excitation(0, if on { 1.0 } else { 0.0 });
            if let Err(e) = act.step() {
                panic!("{model}: {e}");
            }
        }
        let j = act.joints()[0];
        assert!(j.position.is_finite() && j.position < 0.0, "{model}: {j:?}");
    }
}
