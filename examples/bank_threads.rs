//! A bank of independent elbows (one limb, one part per elbow) stepped on one thread and on
//! several (`Actuator::set_threads`), under the realistic load of `benches/limb.rs` (new random
//! excitations every 100 ms per elbow, the elbows' phases spread), interleaved rounds; prints
//! the best µs per tick of each and the throughput ratio.
//!
//!   cargo run --release --example bank_threads -- [ELBOWS] [THREADS] [ROUNDS] [MODEL]
//!   (defaults: 100 elbows, 2 threads, 5 rounds, huxley)

#[path = "../benches/common/bank.rs"]
mod bank;

use bank::{bank, Lcg};
use muscle_actuator::physics::model::ModelKind;
use muscle_actuator::sim::Actuator;
use std::hint::black_box;
use std::time::Instant;

/// µs per tick over `ticks` ticks of the realistic load, from a settled start.
fn realistic(act: &Actuator, ticks: usize, seed: u64) -> f64 {
    let mut a = act.clone();
    let joints = a.joint_names().len();
    let mut rng = Lcg(seed);
    let t0 = Instant::now();
    for k in 0..ticks {
        for j in 0..joints {
            if (k + j * 100 / joints).is_multiple_of(100) {
                a.set_excitation(2 * j, rng.next());
                a.set_excitation(2 * j + 1, rng.next());
            }
        }
        a.step().unwrap();
    }
    let us = t0.elapsed().as_secs_f64() * 1e6 / ticks as f64;
    black_box(a.state());
    us
}

fn main() {
    let arg = |i: usize, default: &str| std::env::args().nth(i).unwrap_or(default.into());
    let elbows: usize = arg(1, "100").parse().expect("ELBOWS");
    let threads: usize = arg(2, "2").parse().expect("THREADS");
    let rounds: usize = arg(3, "5").parse().expect("ROUNDS");
    let model: ModelKind = arg(4, "huxley").parse().expect("MODEL");
    let cfg = bank(elbows);
    let mut one = Actuator::new(&cfg, model, 1000.0).unwrap();
    for _ in 0..200 {
        one.step().unwrap();
    }
    let mut many = one.clone();
    many.set_threads(threads).unwrap();
    let load = || std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average before: {}", load().trim());
    let (mut best_one, mut best_many) = (f64::INFINITY, f64::INFINITY);
    for r in 0..rounds {
        let a = realistic(&one, 2000, 17 + r as u64);
        let b = realistic(&many, 2000, 17 + r as u64);
        println!("round {r}: 1 thread {a:.1} µs/tick, {threads} threads {b:.1} µs/tick");
        best_one = best_one.min(a);
        best_many = best_many.min(b);
    }
    println!("load average after: {}", load().trim());
    println!(
        "{model}, {elbows} elbows ({} parts): best 1 thread {best_one:.1} µs/tick, {threads} threads {best_many:.1} µs/tick, throughput ratio {:.2}",
        one.simulation().part_count(),
        best_one / best_many
    );
}
