//! The antagonistic joint (docs/model.md §8): directions, co-contraction stiffening, stiffness
//! composition.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::series_stiffness;
use muscle_actuator_core::sim::Actuator;

fn settle(act: &mut Actuator, seconds: f64) {
    for _ in 0..(seconds * act.rate_hz()) as usize {
        act.step().unwrap();
    }
}

#[test]
fn rest_is_an_equilibrium() {
    for model in ModelKind::all() {
        let mut act = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
        settle(&mut act, 0.2);
        let j = act.joints()[0];
        assert!(
            j.position.abs() < 1e-9 && j.velocity.abs() < 1e-9,
            "{model}: {j:?}"
        );
        // Both MTUs carry the same small pretension from the 2 mm pre-stretch.
        let (f0, f1) = (act.muscles()[0].force, act.muscles()[1].force);
        assert!(f0 > 0.1 && (f0 - f1).abs() < 1e-9, "{model}: {f0} {f1}");
    }
}

#[test]
fn flexor_alone_flexes_and_extensor_alone_extends() {
    for model in ModelKind::all() {
        for (muscle, sign) in [(0usize, 1.0), (1, -1.0)] {
            let mut act = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
            act.set_excitation(muscle, 0.2);
            settle(&mut act, 0.02);
            let early = act.joints()[0];
            assert!(
                sign * early.torque > 0.0,
                "{model}, muscle {muscle}: torque {}",
                early.torque
            );
            settle(&mut act, 0.3);
            let j = act.joints()[0];
            assert!(
                sign * j.position > 0.05,
                "{model}, muscle {muscle}: θ = {}",
                j.position
            );
        }
    }
}

#[test]
fn external_torque_moves_the_joint_its_way() {
    for tau in [2.0, -2.0] {
        let mut act = Actuator::new(&ActuatorConfig::default(), ModelKind::HUXLEY, 1000.0).unwrap();
        act.set_external_torque(0, tau);
        settle(&mut act, 0.5);
        let th = act.joints()[0].position;
        assert!(th * tau > 0.0 && th.abs() > 0.01, "τ = {tau}: θ = {th}");
    }
}

#[test]
fn co_contraction_raises_joint_stiffness_monotonically() {
    for model in ModelKind::all() {
        let mut previous = 0.0;
        for step in 0..=5 {
            let u = 0.2 * step as f64;
            let mut act = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
            act.set_excitation(0, u);
            act.set_excitation(1, u);
            settle(&mut act, 0.4);
            let j = act.joints()[0];
            assert!(
                j.position.abs() < 1e-6,
                "{model}: symmetric co-contraction keeps θ = 0 ({})",
                j.position
            );
            assert!(
                j.stiffness > previous,
                "{model}: u = {u}: K = {} not above {previous}",
                j.stiffness
            );
            previous = j.stiffness;
        }
        println!("{model}: joint stiffness at full co-contraction {previous:.1} N m/rad");
    }
}

#[test]
fn joint_stiffness_is_the_series_and_parallel_composition() {
    let cfg = ActuatorConfig::default();
    let mut act = Actuator::new(&cfg, ModelKind::HUXLEY, 1000.0).unwrap();
    act.set_excitation(0, 0.5);
    act.set_excitation(1, 0.3);
    settle(&mut act, 0.3);
    let sim = act.simulation();
    let r = muscle_actuator_core::config::DEFAULT_RADIUS;
    let mut k_total = 0.0;
    for (i, m) in act.muscles().iter().enumerate() {
        let mtu = &sim.plant().mtus[i];
        let k_fibre = m.stiffness + mtu.parallel.stiffness(m.fiber_length);
        let k_mtu = series_stiffness(k_fibre, mtu.tendon.stiffness(m.tendon_length));
        assert!((k_mtu - m.mtu_stiffness).abs() <= 1e-9 * k_mtu);
        assert!(k_mtu < k_fibre && k_mtu < mtu.tendon.stiffness(m.tendon_length));
        k_total += k_mtu;
    }
    let k = act.joints()[0].stiffness;
    assert!(
        (k - r * r * k_total).abs() <= 1e-9 * k,
        "{k} vs {}",
        r * r * k_total
    );
}

/// Absurd loads end in a clean error or a finite state within bounded time, never a hang, a
/// panic or a NaN; after a reset the actuator works again.
#[test]
fn extreme_inputs_fail_cleanly_and_reset_recovers() {
    for model in ModelKind::all() {
        for tau in [1e308, -1e12, 1e6] {
            let mut act = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
            act.set_excitation(0, 1.0);
            act.set_external_torque(0, tau);
            let mut failed = false;
            for _ in 0..200 {
                match act.step() {
                    Ok(()) => {
                        let j = act.joints()[0];
                        assert!(
                            j.position.is_finite() && j.stiffness.is_finite(),
                            "{model} τ={tau}"
                        );
                        assert!(act
                            .muscles()
                            .iter()
                            .all(|m| m.force.is_finite() && m.q1.is_finite()));
                    }
                    Err(e) => {
                        assert!(e.to_string().contains("reset"), "{e}");
                        failed = true;
                        break;
                    }
                }
            }
            if failed {
                act.reset();
                assert_eq!(act.tick(), 0);
                act.set_excitation(0, 0.3);
                settle(&mut act, 0.1);
                assert!(
                    act.joints()[0].position > 0.0,
                    "{model}: works again after reset"
                );
            }
        }
    }
}
