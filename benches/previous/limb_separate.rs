//! `benches/limb.rs --separate` adapted to the API of commit dcf2021, the two-muscle program
//! (TR-BDF2, dense 12 × 12 matrix) that docs/benchmarks.md ("Cost against the number of
//! muscles") compares this one with. It is not built here: `benches/previous.sh` drops it into a
//! worktree of dcf2021 as `benches/limb_previous.rs`.
//!
//! The same cases, loads, seeds, repetitions and output columns as `benches/limb.rs`: k
//! separate default actuators (k = 1, 3, 10, 25; 2k muscles), Hill and DM; steady
//! co-contraction, the 20 ticks after a full flexor excitation step from rest, and the realistic
//! load (new random excitations every 100 ms, the actuators' phases spread). That program counts
//! no linear solves or sub-steps: those columns print as NaN.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::Actuator;
use std::hint::black_box;
use std::time::Instant;

/// k separate default actuators.
#[derive(Clone)]
struct Plantset(Vec<Actuator>);

impl Plantset {
    fn new(k: usize, model: ModelKind) -> Self {
        let one = Actuator::new(&ActuatorConfig::default(), model, 1000.0).unwrap();
        Plantset(vec![one; k])
    }
    fn muscles(&self) -> usize {
        2 * self.0.len()
    }
    fn set(&mut self, muscle: usize, u: f64) {
        self.0[muscle / 2].set_excitation(muscle % 2, u)
    }
    fn step(&mut self) {
        self.0.iter_mut().for_each(|a| a.step().unwrap())
    }
    fn force(&self) -> f64 {
        self.0[0].muscles()[0].force
    }
    /// (rhs evaluations, solves, factorisations, sub-steps) so far; solves and sub-steps are
    /// not counted by that program (NaN).
    fn work(&self) -> Work {
        self.0.iter().fold((0, 0), |x, a| {
            let s = a.simulation().stats();
            (x.0 + s.rhs_evals, x.1 + s.factorisations)
        })
    }
}

/// A deterministic generator in [0, 1) (the same as `benches/limb.rs`).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

type Work = (u64, u64);

struct Measured {
    us_per_tick: f64,
    work_per_tick: (f64, f64),
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

const REPEATS: usize = 5;

fn per_tick(w0: Work, w1: Work, ticks: usize) -> (f64, f64) {
    let t = ticks as f64;
    ((w1.0 - w0.0) as f64 / t, (w1.1 - w0.1) as f64 / t)
}

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
    let mut work = (0.0, 0.0);
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
        work = per_tick(w0, a.work(), ticks);
    }
    Measured {
        us_per_tick: median(times),
        work_per_tick: work,
    }
}

fn step_response(p: &Plantset) -> Measured {
    let mut times = Vec::new();
    let mut work = (0.0, 0.0);
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
    let mut work = (0.0, 0.0);
    for r in 0..REPEATS {
        let mut a = p.clone();
        let mut rng = Lcg(17 + r as u64);
        let w0 = a.work();
        let t0 = Instant::now();
        for k in 0..ticks {
            for j in 0..joints {
                if (k + j * 100 / joints.max(1)) % 100 == 0 {
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
    // Warm-up (caches, clock frequency) before the first measured case.
    let warm = Plantset::new(1, ModelKind::Huxley);
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
    let only = |var: &str, name: &str| {
        std::env::var(var).map_or(true, |v| v.split(',').any(|x| x == name))
    };
    for model in [ModelKind::Hill, ModelKind::Huxley] {
        if !only("LIMB_MODELS", model.name()) {
            continue;
        }
        for k in [1usize, 3, 10, 25] {
            let name = format!("bank{k}");
            if !only("LIMB_CASES", &name) {
                continue;
            }
            let p = Plantset::new(k, model);
            let muscles = p.muscles();
            for (load, m) in [
                ("steady", steady(&p)),
                ("step", step_response(&p)),
                ("realistic", realistic(&p)),
            ] {
                let (rhs, lu) = m.work_per_tick;
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
                    f64::NAN,
                    lu,
                    f64::NAN
                );
            }
        }
    }
}
