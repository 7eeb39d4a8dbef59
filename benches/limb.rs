//! Tick cost against the number of muscles, and the stepper's work per tick.
//!
//! `cargo bench --bench limb` (add `-- --separate` to step k separate two-muscle actuators
//! instead of one limb of k joints, the only way a program limited to one joint can run k).
//!
//! Limbs: a bank of k independent antagonistic elbows (2k muscles: 2, 6, 20, 50) and the
//! built-in `arm` (2 joints, 6 muscles, 3 biarticular); the elbow and the arm again with
//! equilibrium fibres (`-eq`) and with rigid tendons (`-rigid`, docs/model.md §5b). Loads, at
//! 1 kHz:
//! - steady: co-contracted and moving, the flexor command varying slowly;
//! - step: the 20 ticks after a full flexor excitation step from rest on every joint;
//! - realistic: every joint's two muscles get new random excitations every 100 ms, the joints'
//!   phases spread over the 100 ms.
//!
//! Printed per case: µs per tick, per actuator (two muscles) and per muscle, the median of
//! several repetitions, with the right-hand-side evaluations, linear solves, factorisations and
//! sub-steps per tick beside them.

#[path = "common/bank.rs"]
mod bank;

use bank::{bank, Lcg};
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{FibreKind, TendonKind};
use muscle_actuator_core::sim::Actuator;
use std::hint::black_box;
use std::time::Instant;

/// What is stepped: one limb, or k separate default actuators.
#[allow(clippy::large_enum_variant)]
enum Plantset {
    Limb(Actuator),
    Separate(Vec<Actuator>),
}

impl Plantset {
    fn new(cfg: &ActuatorConfig, k: usize, separate: bool, model: ModelKind) -> Self {
        if separate {
            let one = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
            Plantset::Separate(vec![one; k])
        } else {
            Plantset::Limb(Actuator::new(cfg, model, 1000.0).unwrap())
        }
    }
    fn muscles(&self) -> usize {
        match self {
            Plantset::Limb(a) => a.muscle_names().len(),
            Plantset::Separate(v) => 2 * v.len(),
        }
    }
    fn set(&mut self, muscle: usize, u: f64) {
        match self {
            Plantset::Limb(a) => a.set_excitation(muscle, u),
            Plantset::Separate(v) => v[muscle / 2].set_excitation(muscle % 2, u),
        }
    }
    fn step(&mut self) {
        match self {
            Plantset::Limb(a) => a.step().unwrap(),
            Plantset::Separate(v) => v.iter_mut().for_each(|a| a.step().unwrap()),
        }
    }
    fn force(&self) -> f64 {
        match self {
            Plantset::Limb(a) => a.muscles()[0].force,
            Plantset::Separate(v) => v[0].muscles()[0].force,
        }
    }
    /// (rhs evaluations, solves, factorisations, sub-steps) so far.
    fn work(&self) -> (u64, u64, u64, u64) {
        let of = |a: &Actuator| {
            let s = a.simulation().stats();
            (s.rhs_evals, s.solves, s.factorisations, s.substeps)
        };
        match self {
            Plantset::Limb(a) => of(a),
            Plantset::Separate(v) => v.iter().map(of).fold((0, 0, 0, 0), |x, y| {
                (x.0 + y.0, x.1 + y.1, x.2 + y.2, x.3 + y.3)
            }),
        }
    }
}

impl Clone for Plantset {
    fn clone(&self) -> Self {
        match self {
            Plantset::Limb(a) => Plantset::Limb(a.clone()),
            Plantset::Separate(v) => Plantset::Separate(v.clone()),
        }
    }
}

struct Measured {
    us_per_tick: f64,
    work_per_tick: (f64, f64, f64, f64),
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

const REPEATS: usize = 5;

fn steady(p: &Plantset) -> Measured {
    let mut base = p.clone();
    for m in 0..base.muscles() {
        base.set(m, if m % 2 == 0 { 0.6 } else { 0.3 });
    }
    for _ in 0..200 {
        base.step();
    }
    let ticks = 1000;
    let mut times = Vec::new();
    let mut work = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..REPEATS {
        let mut a = base.clone();
        let w0 = a.work();
        let t0 = Instant::now();
        for k in 0..ticks {
            a.set(0, 0.6 + 0.2 * ((k % 1000) as f64 / 1000.0));
            a.step();
        }
        times.push(t0.elapsed().as_secs_f64() * 1e6 / ticks as f64);
        black_box(a.force());
        let w1 = a.work();
        work = per_tick(w0, w1, ticks);
    }
    Measured {
        us_per_tick: median(times),
        work_per_tick: work,
    }
}

type Work = (u64, u64, u64, u64);

fn per_tick(w0: Work, w1: Work, ticks: usize) -> (f64, f64, f64, f64) {
    let t = ticks as f64;
    (
        (w1.0 - w0.0) as f64 / t,
        (w1.1 - w0.1) as f64 / t,
        (w1.2 - w0.2) as f64 / t,
        (w1.3 - w0.3) as f64 / t,
    )
}

fn step_response(p: &Plantset) -> Measured {
    let mut times = Vec::new();
    let mut work = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..REPEATS * 4 {
        let mut a = p.clone();
        for m in (0..a.muscles()).step_by(2) {
            a.set(m, 1.0);
        }
        let w0 = a.work();
        let t0 = Instant::now();
        for _ in 0..20 {
            a.step();
        }
        times.push(t0.elapsed().as_secs_f64() * 1e6 / 20.0);
        black_box(a.force());
        work = per_tick(w0, a.work(), 20);
    }
    Measured {
        us_per_tick: median(times),
        work_per_tick: work,
    }
}

fn realistic(p: &Plantset) -> Measured {
    let ticks = 2000;
    let joints = p.muscles() / 2;
    let mut times = Vec::new();
    let mut work = (0.0, 0.0, 0.0, 0.0);
    for r in 0..REPEATS {
        let mut a = p.clone();
        let mut rng = Lcg(17 + r as u64);
        let w0 = a.work();
        let t0 = Instant::now();
        for k in 0..ticks {
            for j in 0..joints {
                if (k + j * 100 / joints.max(1)).is_multiple_of(100) {
                    a.set(2 * j, rng.next());
                    a.set(2 * j + 1, rng.next());
                }
            }
            a.step();
        }
        times.push(t0.elapsed().as_secs_f64() * 1e6 / ticks as f64);
        black_box(a.force());
        work = per_tick(w0, a.work(), ticks);
    }
    Measured {
        us_per_tick: median(times),
        work_per_tick: work,
    }
}

fn main() {
    let separate = std::env::args().any(|a| a == "--separate");
    let quick = std::env::args()
        .any(|a| a == "--bench")
        .then_some(())
        .is_none();
    if quick {
        // `cargo test --benches` runs this once without --bench: a smoke run only.
        let p = Plantset::new(&bank(1), 1, separate, ModelKind::HUXLEY);
        let m = step_response(&p);
        assert!(m.us_per_tick > 0.0);
        return;
    }
    // Warm-up (caches, clock frequency) before the first measured case.
    let warm = Plantset::new(&bank(1), 1, separate, ModelKind::HUXLEY);
    let t0 = Instant::now();
    while t0.elapsed().as_secs_f64() < 1.0 {
        black_box(realistic(&warm).us_per_tick);
    }
    println!(
        "{:<10} {:<7} {:>4} {:<10} {:>10} {:>12} {:>11} {:>8} {:>8} {:>6}",
        "limb",
        "model",
        "mus",
        "load",
        "µs/tick",
        "µs/actuator",
        "µs/muscle",
        "rhs/tick",
        "solve/t",
        "LU/t"
    );
    let mut cases: Vec<(String, ActuatorConfig, usize)> = [1usize, 3, 10, 25]
        .iter()
        .map(|&k| (format!("bank{k}"), bank(k), k))
        .collect();
    if !separate {
        cases.push(("arm".into(), ActuatorConfig::resolve("arm").unwrap(), 3));
        // The formulations of docs/model.md §5b: the elbow and the arm with massless fibres, on
        // elastic and on rigid tendons.
        for (base, cfg, k) in [
            ("bank1", bank(1), 1),
            ("arm", ActuatorConfig::resolve("arm").unwrap(), 3),
        ] {
            for (kind, tendon) in [("eq", TendonKind::Elastic), ("rigid", TendonKind::Rigid)] {
                let mut c = cfg.clone();
                for m in &mut c.muscles {
                    m.params.fibre = FibreKind::Equilibrium;
                    m.params.tendon = tendon;
                }
                cases.push((format!("{base}-{kind}"), c, k));
            }
        }
    }
    // LIMB_CASES=bank1,arm and LIMB_MODELS=hill restrict the table (for profiling).
    let only = |var: &str, name: &str| {
        std::env::var(var).map_or(true, |v| v.split(',').any(|x| x == name))
    };
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        if !only("LIMB_MODELS", model.name()) {
            continue;
        }
        for (name, cfg, k) in &cases {
            if !only("LIMB_CASES", name) {
                continue;
            }
            let p = Plantset::new(cfg, *k, separate, model);
            let muscles = p.muscles();
            for (load, m) in [
                ("steady", steady(&p)),
                ("step", step_response(&p)),
                ("realistic", realistic(&p)),
            ] {
                let (rhs, solves, lu, sub) = m.work_per_tick;
                println!(
                    "{:<10} {:<7} {:>4} {:<10} {:>10.2} {:>12.2} {:>11.3} {:>8.1} {:>8.1} {:>6.2} {:>6.2}",
                    name,
                    model.name(),
                    muscles,
                    load,
                    m.us_per_tick,
                    m.us_per_tick * 2.0 / muscles as f64,
                    m.us_per_tick / muscles as f64,
                    rhs,
                    solves,
                    lu,
                    sub
                );
            }
        }
    }
}
