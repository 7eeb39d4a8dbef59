//! A bank of independent elbows (one limb, one part per elbow) stepped on one thread and on
//! several (`Actuator::set_threads`), under the realistic load of `benches/limb.rs` (new random
//! excitations every 100 ms per elbow, the elbows' phases spread), in rounds of 1000 ticks on
//! each, back to back; prints the median over the rounds of each round's throughput ratio (a
//! round is short enough that the machine's drifting load weighs on both of its runs alike),
//! their range, and the median µs per tick of each.
//!
//!   cargo run --release --example bank_threads -- [ELBOWS] [THREADS] [ROUNDS] [MODEL]
//!   (defaults: 100 elbows, 2 threads, 21 rounds, huxley)

#[path = "../benches/common/bank.rs"]
mod bank;

use bank::{bank, Lcg};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::Actuator;
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
    let rounds: usize = arg(3, "21").parse().expect("ROUNDS");
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
    let (mut ones, mut manys, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
    for r in 0..rounds {
        let a = realistic(&one, 1000, 17 + r as u64);
        let b = realistic(&many, 1000, 17 + r as u64);
        println!("round {r}: 1 thread {a:.1} µs/tick, {threads} threads {b:.1} µs/tick");
        ones.push(a);
        manys.push(b);
        ratios.push(a / b);
    }
    println!("load average after: {}", load().trim());
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
    println!(
        "{model}, {elbows} elbows ({} parts): median 1 thread {:.1} µs/tick, {threads} threads {:.1} µs/tick; throughput ratio, median of {rounds} rounds {:.2} (range {lo:.2}-{hi:.2})",
        one.simulation().part_count(),
        median(&mut ones),
        median(&mut manys),
        median(&mut ratios),
    );
}

/// The median of `v` (reordered).
fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}
