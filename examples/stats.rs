use muscle_actuator::config::ActuatorConfig;
use muscle_actuator::physics::model::ModelKind;
use muscle_actuator::sim::Actuator;
fn main() {
    for model in [ModelKind::Hill, ModelKind::Huxley] {
        let mut a = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
        a.set_excitation(0, 0.6);
        a.set_excitation(1, 0.3);
        for _ in 0..200 {
            a.step().unwrap();
        }
        let s0 = a.simulation().stats();
        for k in 0..1000 {
            a.set_excitation(0, 0.6 + 0.2 * (k as f64 / 1000.0));
            a.step().unwrap();
        }
        let s1 = a.simulation().stats();
        println!(
            "{model}: per tick rhs {:.1} jac {:.3} lu {:.3} rej {}",
            (s1.rhs_evals - s0.rhs_evals) as f64 / 1000.0,
            (s1.jacobians - s0.jacobians) as f64 / 1000.0,
            (s1.factorisations - s0.factorisations) as f64 / 1000.0,
            s1.rejected
        );
    }
}
