//! The subject commands' cost on the person's data (data/ceinms, docs/emg.md): one evaluation of
//! each trial (the 13 knee units driven through it) per model, in µs per unit-tick; then a whole
//! calibration of the knee on the six trials, on one thread and on `THREADS`, its wall time and
//! the ratio, and its cost; each calibration from the same seed, so the runs do the same work.
//!
//!   cargo run --release --example calibration_time -- [EVALUATIONS] [THREADS] [MODEL...]
//!   (defaults: 1000 evaluations, 2 threads, hill and huxley)

use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::default_stepping;
use muscle_actuator_measured::measured::{ExcitationMap, Subject, Trial};
use muscle_actuator_measured::subject::calibrate::{Problem, Settings};
use muscle_actuator_measured::subject::{PreparedTrial, SubjectModel};
use std::ops::ControlFlow;
use std::path::Path;
use std::time::Instant;

const TRIALS: [&str; 6] = [
    "_FastWalking_",
    "_FastWalking1_",
    "_FastWalking9_",
    "_CrossOvers1_",
    "_CrossOvers6_",
    "_CrossOvers7_",
];

/// Evaluations of one trial timed per model: the median of `rounds`.
fn unit_tick_us(t: &PreparedTrial, subject: &SubjectModel, model: ModelKind, rounds: usize) -> f64 {
    let params = subject.params_of(&t.units).unwrap();
    let mut times: Vec<f64> = (0..rounds)
        .map(|_| {
            let t0 = Instant::now();
            std::hint::black_box(t.run(&params, model, default_stepping(model)).unwrap());
            t0.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[rounds / 2] * 1e6 / (t.ticks() * t.units.len()) as f64
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let evaluations: usize = args.first().map_or(Ok(1000), |s| s.parse())?;
    let threads: usize = args.get(1).map_or(Ok(2), |s| s.parse())?;
    let models: Vec<ModelKind> = if args.len() > 2 {
        args[2..]
            .iter()
            .map(|m| m.parse())
            .collect::<Result<_, _>>()?
    } else {
        vec![ModelKind::HILL, ModelKind::HUXLEY]
    };
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/ceinms");
    let subject = SubjectModel::of_ceinms(&Subject::read(&data.join("uncalibratedSubject.xml"))?)?;
    let map = ExcitationMap::read(&data.join("emgGenerator-16To34.xml"))?;
    let dofs = ["R_knee_fe".to_string()];
    let trials: Vec<PreparedTrial> = TRIALS
        .iter()
        .map(|n| {
            PreparedTrial::new(&subject, &map, &Trial::read(&data.join(n))?, &dofs)
                .map_err(Into::into)
        })
        .collect::<Result<_, Box<dyn std::error::Error>>>()?;
    println!("one evaluation, µs per unit-tick (median of 5; 13 units at 2 kHz):");
    for model in &models {
        let per: Vec<String> = trials
            .iter()
            .map(|t| format!("{} {:.2}", t.name, unit_tick_us(t, &subject, *model, 5)))
            .collect();
        println!("  {:<10} {}", model.name(), per.join(", "));
    }
    for model in &models {
        let problem = Problem::new(
            &subject,
            &map,
            trials.clone(),
            *model,
            default_stepping(*model),
        )?;
        let mut walls = Vec::new();
        for n in [1, threads] {
            let settings = Settings {
                seed: 1,
                max_evaluations: evaluations,
                threads: n,
                ..Settings::default()
            };
            let t0 = Instant::now();
            let outcome = problem.calibrate(&settings, |_, _| ControlFlow::Continue(()))?;
            let wall = t0.elapsed().as_secs_f64();
            println!(
                "calibration {:<8} {n} thread(s): {wall:.1} s, {} evaluations, mean 1 - R2 {:.4} (from {:.4})",
                model.name(),
                outcome.evaluations,
                outcome.cost,
                outcome.start_cost
            );
            walls.push(wall);
        }
        println!("  {} threads / 1: {:.2}x", threads, walls[0] / walls[1]);
    }
    Ok(())
}
