//! Parts stepped on several threads (`Actuator::set_threads`): the same states, published
//! values and energies to the bit as on one thread, for a limb of independent joints under
//! commands that differ per joint; and the thread count validated.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::Actuator;

/// Every published value and the state vector after each tick, as bits.
fn run(cfg: &ActuatorConfig, model: ModelKind, threads: usize, ticks: usize) -> Vec<Vec<u64>> {
    let mut act = Actuator::new(cfg, model, 1000.0).unwrap();
    act.set_threads(threads).unwrap();
    assert_eq!(act.simulation().threads(), threads);
    let muscles = act.muscle_names().len();
    let mut out = Vec::with_capacity(ticks);
    for t in 0..ticks {
        // Each muscle its own square wave: the parts move at different times, so their
        // sub-step counts differ from part to part.
        for i in 0..muscles {
            let period = 40 + 17 * i;
            let on = (t / period) % 2 == 0;
            act.set_excitation(i, if on { 0.2 + 0.1 * i as f64 } else { 0.05 });
        }
        act.step().unwrap();
        let s = act.state();
        out.push(
            act.simulation()
                .state()
                .iter()
                .copied()
                .chain(s.muscles.iter().flat_map(|m| m.values()))
                .chain(s.joints.iter().flat_map(|j| j.values()))
                .chain(s.stiffness_matrix.iter().copied())
                .map(f64::to_bits)
                .collect(),
        );
    }
    out
}

#[test]
fn threads_give_the_same_run_to_the_bit() {
    let cfg = ActuatorConfig::resolve(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../configs/four_joints.toml"
    ))
    .unwrap();
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        let probe = Actuator::new(&cfg, model, 1000.0).unwrap();
        assert_eq!(
            probe.simulation().part_count(),
            4,
            "four independent joints"
        );
        let one = run(&cfg, model, 1, 400);
        for threads in [2, 3] {
            let many = run(&cfg, model, threads, 400);
            for (t, (a, b)) in one.iter().zip(&many).enumerate() {
                assert_eq!(a, b, "{model}, {threads} threads, tick {t}");
            }
        }
    }
}

#[test]
fn a_thread_count_out_of_range_is_refused() {
    let mut act = Actuator::new(&ActuatorConfig::default(), ModelKind::HILL, 1000.0).unwrap();
    for bad in [0, 257] {
        let e = act.set_threads(bad).unwrap_err();
        assert!(e.to_string().contains(&format!("threads = {bad}")), "{e}");
    }
    assert_eq!(act.simulation().threads(), 1);
}
