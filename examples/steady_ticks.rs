//! The steady tick of `benches/tick.rs` (the default actuator co-contracted, the flexor's
//! command varying slowly) as a plain loop of a given length, for counting its work with
//! `perf stat` (benches/tick_instructions.sh): instructions do not drift with the machine's load
//! as times do.
//!
//!   cargo run --release --example steady_ticks -- MODEL TICKS [FORMULATION]
//!
//! MODEL: hill, huxley; FORMULATION (docs/model.md §5b): massed (the default), equilibrium, rigid.
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{FibreKind, TendonKind};
use muscle_actuator_core::sim::Actuator;
use std::hint::black_box;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(name), Some(ticks)) = (args.get(1), args.get(2).and_then(|t| t.parse::<u64>().ok()))
    else {
        eprintln!("usage: steady_ticks MODEL TICKS [massed|equilibrium|rigid]");
        std::process::exit(2);
    };
    let Some(model) = ModelKind::all()
        .into_iter()
        .find(|m| m.name() == name.as_str())
    else {
        eprintln!("steady_ticks: unknown model {name:?}");
        std::process::exit(2);
    };
    let mut cfg = ActuatorConfig::default();
    let (fibre, tendon) = match args.get(3).map(String::as_str) {
        None | Some("massed") => (FibreKind::Massed, TendonKind::Elastic),
        Some("equilibrium") => (FibreKind::Equilibrium, TendonKind::Elastic),
        Some("rigid") => (FibreKind::Equilibrium, TendonKind::Rigid),
        Some(other) => {
            eprintln!("steady_ticks: unknown formulation {other:?}: massed, equilibrium, rigid");
            std::process::exit(2);
        }
    };
    for m in &mut cfg.muscles {
        (m.params.fibre, m.params.tendon) = (fibre, tendon);
    }
    // As benches/tick.rs's working_actuator: co-contracted, loaded, after 200 ticks.
    let mut a = Actuator::new(&cfg, model, 1000.0).unwrap();
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
