//! Energy balance (independent of the integrator's own bookkeeping): the work done by the load
//! equals the change of strain and kinetic energy plus the energy dissipated in the dampers, to
//! integration accuracy. Inputs are held over each tick, so the load's work over a tick is the
//! held load times the displacement over the tick.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::MuscleParams;
use muscle_actuator_core::sim::{default_stepping, Actuator, Scenario};

const RATE: f64 = 20_000.0;

/// Passive muscle, force-driven tendon (the paper's Fig. 6 set-up): within a tick the tendon
/// length is fixed, so the load's work F Δl_m goes into the parallel element, the fibre's kinetic
/// energy and the damper.
#[test]
fn force_driven_passive_muscle_balances_energy() {
    for name in ["energy-10hz", "energy-100hz"] {
        for model in [ModelKind::HILL, ModelKind::HUXLEY] {
            let params = MuscleParams::default();
            let sc = Scenario::built_in(name, &params).unwrap();
            let mut runner = sc
                .runner(
                    &ActuatorConfig::default(),
                    model,
                    RATE,
                    default_stepping(model),
                )
                .unwrap();
            let start = runner.record().muscles[0];
            let (mut work, mut dissipated) = (0.0, 0.0);
            let mut prev = start;
            let ticks = (sc.duration * RATE) as usize;
            for k in 0..ticks {
                let load = runner.inputs_at(k as f64 / RATE).tendon_force[0];
                runner.step().unwrap();
                let now = runner.record().muscles[0];
                work += load * (now.fiber_length - prev.fiber_length);
                // Trapezoidal quadrature of the damper power B v².
                let p = |v: f64| params.b_m * v * v;
                dissipated += 0.5 * (p(prev.fiber_velocity) + p(now.fiber_velocity)) / RATE;
                prev = now;
            }
            let kinetic = 0.5 * params.mass * prev.fiber_velocity.powi(2);
            let strain = prev.fiber_energy - start.fiber_energy;
            let residual = work - (strain + kinetic + dissipated);
            let scale = work.abs() + strain.abs() + dissipated;
            println!("{name} {model}: work {work:.6e} J = strain {strain:.6e} + kinetic {kinetic:.3e} + dissipated {dissipated:.6e} (residual {residual:.2e})");
            assert!(
                residual.abs() <= 1e-3 * scale,
                "{name} {model}: residual {residual} J of {scale} J"
            );
        }
    }
}

/// The passive joint under an external torque: the torque's work equals the change of kinetic
/// energy (joint and fibres) and strain energy (two tendons, two parallel elements) plus what the
/// joint damping and the fibre dampers dissipate.
#[test]
fn passive_joint_balances_energy() {
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        let cfg = ActuatorConfig::default();
        let mut act = Actuator::new(&cfg, model, RATE).unwrap();
        let p = &cfg.muscles[0].params;
        let c = cfg.joints[0].damping;
        let energy = |a: &Actuator| -> f64 {
            a.muscles()
                .iter()
                .map(|m| m.tendon_energy + m.fiber_energy)
                .sum::<f64>()
                + a.simulation().kinetic_energy()
        };
        let power = |a: &Actuator| -> f64 {
            c * a.joints()[0].velocity.powi(2)
                + a.muscles()
                    .iter()
                    .map(|m| p.b_m * m.fiber_velocity.powi(2))
                    .sum::<f64>()
        };
        let e0 = energy(&act);
        let (mut work, mut dissipated) = (0.0, 0.0);
        let mut theta = act.joints()[0].position;
        let mut p_prev = power(&act);
        for k in 0..(RATE as usize) {
            let t = k as f64 / RATE;
            let tau = 3.0 * (2.0 * std::f64::consts::PI * 2.0 * t).sin();
            act.set_external_torque(0, tau);
            act.step().unwrap();
            let th = act.joints()[0].position;
            work += tau * (th - theta);
            theta = th;
            let p_now = power(&act);
            dissipated += 0.5 * (p_prev + p_now) / RATE;
            p_prev = p_now;
        }
        let stored = energy(&act) - e0;
        let residual = work - stored - dissipated;
        println!("joint {model}: work {work:.6e} J = stored {stored:.6e} + dissipated {dissipated:.6e} (residual {residual:.2e})");
        assert!(
            theta.abs() > 0.01,
            "the load should move the joint (θ = {theta})"
        );
        assert!(
            residual.abs() <= 1e-3 * (work.abs() + dissipated),
            "{model}: residual {residual} J"
        );
    }
}
