//! No user input makes the physics panic: random but valid parameter sets (every parameter
//! scaled by up to 10^±1.5) and random inputs either run with finite outputs or end in a clean
//! error, for every model.

use muscle_actuator::config::ActuatorConfig;
use muscle_actuator::physics::model::ModelKind;
use muscle_actuator::sim::Actuator;

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
