use muscle_actuator::config::ActuatorConfig;
use muscle_actuator::physics::model::ModelKind;
use muscle_actuator::sim::Actuator;
fn main() {
    let model: ModelKind = std::env::args()
        .nth(1)
        .unwrap_or("huxley".into())
        .parse()
        .unwrap();
    let mut a = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
    a.set_excitation(0, 0.6);
    a.set_excitation(1, 0.3);
    let t = std::time::Instant::now();
    let n = 200_000;
    for k in 0..n {
        a.set_excitation(0, 0.6 + 0.2 * ((k % 1000) as f64 / 1000.0));
        a.step().unwrap();
    }
    println!(
        "{model}: {:.3} us/tick",
        t.elapsed().as_secs_f64() * 1e6 / n as f64
    );
}
