//! Cost of one 1 ms tick of the default actuator (two muscles, joint) per model, and of a whole
//! `simulate pulse` run. `cargo bench --bench tick`.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::MuscleParams;
use muscle_actuator_core::sim::{default_stepping, Actuator, Scenario};
use std::hint::black_box;

/// An actuator in a representative working state: co-contracted, moving, after 200 ticks.
fn working_actuator(model: ModelKind) -> Actuator {
    let mut a = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
    a.set_excitation(0, 0.6);
    a.set_excitation(1, 0.3);
    a.set_external_torque(0, 2.0);
    for _ in 0..200 {
        a.step().unwrap();
    }
    a
}

fn tick(c: &mut Criterion) {
    let mut g = c.benchmark_group("tick_default_actuator");
    for model in ModelKind::all() {
        let mut act = working_actuator(model);
        let mut k = 0u64;
        g.bench_function(model.name(), |b| {
            b.iter(|| {
                // A slowly varying command keeps the Newton iterations honest.
                k += 1;
                act.set_excitation(0, 0.6 + 0.2 * ((k % 1000) as f64 / 1000.0));
                act.step().unwrap();
                black_box(act.muscles()[0].force)
            })
        });
    }
    g.finish();
}

/// The expensive case of the adaptive stepping: the first 20 ticks after a full flexor
/// excitation step from rest (time per 20 ticks; divide by 20 for the mean per tick).
fn tick_transient(c: &mut Criterion) {
    let mut g = c.benchmark_group("twenty_ticks_after_excitation_step");
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        let rest = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
        g.bench_function(model.name(), |b| {
            b.iter_batched(
                || {
                    let mut a = rest.clone();
                    a.set_excitation(0, 1.0);
                    a
                },
                |mut a| {
                    for _ in 0..20 {
                        a.step().unwrap();
                    }
                    black_box(a.muscles()[0].force)
                },
                BatchSize::SmallInput,
            )
        });
    }
    g.finish();
}

fn simulate_pulse(c: &mut Criterion) {
    let cfg = ActuatorConfig::default();
    let sc = Scenario::built_in("pulse", &MuscleParams::default()).unwrap();
    let mut g = c.benchmark_group("simulate_pulse_3s");
    g.sample_size(10);
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        g.bench_function(model.name(), |b| {
            b.iter_batched(
                || (),
                |_| {
                    black_box(
                        sc.run(&cfg, model, 1000.0, default_stepping(model))
                            .unwrap(),
                    )
                },
                BatchSize::SmallInput,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, tick, tick_transient, simulate_pulse);
criterion_main!(benches);
