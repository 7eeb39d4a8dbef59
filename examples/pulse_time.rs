//! The `pulse` scenario run in-process (`Scenario::run`: one clamped muscle, 3000 ticks of 1 ms,
//! the run's records kept), as `simulate pulse` runs it: µs per muscle-tick, Hill then Huxley
//! DM, ROUNDS times, one line each (`MODEL µs_per_tick force_at_2s_N`); each followed by the
//! same ticks through the scenario's runner without keeping records (`MODEL-steps …`), the
//! stepping alone, and the runner's set-up (`MODEL-setup …`, per tick of the run: the plant
//! built, its checks, the DM calibration). The first round's names end in `-first`: a process's
//! first run also pays for its first touch of the heap and the code (a `simulate` command is
//! one such run; a Python session or a sweep runs many). Run beside OpenSim's muscles by
//! `benches/opensim_pulse.sh`, beside another commit by `benches/pulse_paired.sh` (so it reads
//! nothing of a run's records: the force comes from the runner, whose API both commits share).
//!
//! With `PULSE_FORMULATIONS=1` (benches/opensim_pulse.sh sets it), each round also runs both
//! models on an equilibrium fibre and on a rigid tendon (docs/model.md §5b), and on an
//! equilibrium fibre with DeGroote's curves, as `MODEL-equilibrium`, `MODEL-rigid` and
//! `MODEL-degroote-equilibrium` lines.
//!
//!   cargo run --release --example pulse_time -- [ROUNDS]     (default 5, the first included)
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::curves::CurveSet;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{FibreKind, MuscleParams, TendonKind};
use muscle_actuator_core::sim::{default_stepping, Scenario};
use std::hint::black_box;
use std::time::Instant;

const TICKS: u32 = 3000;

fn main() {
    let rounds: usize = std::env::args()
        .nth(1)
        .map_or(5, |s| s.parse().expect("ROUNDS: a count"));
    let cfg = ActuatorConfig::default();
    let sc = Scenario::built_in("pulse", &MuscleParams::default()).unwrap();
    for round in 0..rounds {
        // The process's first round pays for its first touch of the heap and the code.
        let first = if round == 0 { "-first" } else { "" };
        for model in [ModelKind::HILL, ModelKind::HUXLEY] {
            let t0 = Instant::now();
            black_box(
                sc.run(&cfg, model, 1000.0, default_stepping(model))
                    .unwrap(),
            );
            let run_us = t0.elapsed().as_secs_f64() * 1e6 / TICKS as f64;
            let t0 = Instant::now();
            let mut runner = sc
                .runner(&cfg, model, 1000.0, default_stepping(model))
                .unwrap();
            let setup_us = t0.elapsed().as_secs_f64() * 1e6 / TICKS as f64;
            let mut force = f64::NAN;
            let t0 = Instant::now();
            for k in 1..=TICKS {
                runner.step().unwrap();
                if k == 2000 {
                    force = runner.record().muscles[0].force;
                }
            }
            let steps_us = t0.elapsed().as_secs_f64() * 1e6 / TICKS as f64;
            let name = model.name();
            println!("{name}{first} {run_us:.3} {force:.1}");
            println!("{name}-steps{first} {steps_us:.3} {force:.1}");
            println!("{name}-setup{first} {setup_us:.3} {force:.1}");
        }
        if std::env::var("PULSE_FORMULATIONS").is_ok() {
            for (label, fibre, tendon, curves) in [
                (
                    "equilibrium",
                    FibreKind::Equilibrium,
                    TendonKind::Elastic,
                    CurveSet::Paper,
                ),
                (
                    "rigid",
                    FibreKind::Equilibrium,
                    TendonKind::Rigid,
                    CurveSet::Paper,
                ),
                (
                    "degroote-equilibrium",
                    FibreKind::Equilibrium,
                    TendonKind::Elastic,
                    CurveSet::DeGroote2016,
                ),
            ] {
                let mut cfg = cfg.clone();
                for m in &mut cfg.muscles {
                    (m.params.fibre, m.params.tendon) = (fibre, tendon);
                    m.params.curves = curves;
                }
                for model in [ModelKind::HILL, ModelKind::HUXLEY] {
                    let t0 = Instant::now();
                    let run = sc
                        .run(&cfg, model, 1000.0, default_stepping(model))
                        .unwrap();
                    let run_us = t0.elapsed().as_secs_f64() * 1e6 / TICKS as f64;
                    let force = run
                        .records()
                        .nth(2000)
                        .map_or(f64::NAN, |r| r.muscles[0].force);
                    println!("{}-{label}{first} {run_us:.3} {force:.1}", model.name());
                }
            }
        }
    }
}
