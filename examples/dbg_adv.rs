use muscle_actuator::config::ActuatorConfig;
use muscle_actuator::physics::model::ModelKind;
use muscle_actuator::sim::Actuator;
fn main() {
    let mut a = Actuator::new(&ActuatorConfig::default(), ModelKind::Hill, 1000.0).unwrap();
    a.set_excitation(0, 0.6);
    for k in 0..5 {
        a.step().unwrap();
        println!("tick {k} stats {:?}", a.simulation().stats());
    }
}
