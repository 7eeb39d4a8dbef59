//! The steady tick of `benches/tick.rs` (the default actuator co-contracted, the flexor's
//! command varying slowly) as a plain loop of a given length, for counting its work with
//! `perf stat` (benches/tick_instructions.sh): instructions do not drift with the machine's load
//! as times do.
//!
//!   cargo run --release --example steady_ticks -- MODEL TICKS     (MODEL: hill, huxley)
use muscle_actuator::config::ActuatorConfig;
use muscle_actuator::physics::models::ModelKind;
use muscle_actuator::sim::Actuator;
use std::hint::black_box;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(name), Some(ticks)) = (args.get(1), args.get(2).and_then(|t| t.parse::<u64>().ok()))
    else {
        eprintln!("usage: steady_ticks MODEL TICKS");
        std::process::exit(2);
    };
    let Some(model) = ModelKind::all()
        .into_iter()
        .find(|m| m.name() == name.as_str())
    else {
        eprintln!("steady_ticks: unknown model {name:?}");
        std::process::exit(2);
    };
    // As benches/tick.rs's working_actuator: co-contracted, loaded, after 200 ticks.
    let mut a = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
    a.set_excitation(0, 0.6);
    a.set_excitation(1, 0.3);
    a.set_external_torque(0, 2.0);
    for _ in 0..200 {
        a.step().unwrap();
    }
    let mut force = 0.0;
    for k in 1..=ticks {
        a.set_excitation(0, 0.6 + 0.2 * ((k % 1000) as f64 / 1000.0));
        a.step().unwrap();
        force += black_box(a.muscles()[0].force);
    }
    println!("{force}");
}
