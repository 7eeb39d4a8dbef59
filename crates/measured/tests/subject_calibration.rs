//! Calibration (docs/emg.md "Calibration"): moments the model makes itself with known
//! parameters, plus noise, are calibrated back to those parameters, for the Hill and the
//! Distribution-Moment models; the same seed gives the same result on one thread and on two; and
//! on the person's own data, a subject calibrated on three trials predicts the other three above
//! the floor docs/emg.md states.

#[path = "common/trials.rs"]
mod trials;

use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::default_stepping;
use muscle_actuator_measured::measured::rating::rate;
use muscle_actuator_measured::measured::{ExcitationMap, Subject, Trial};
use muscle_actuator_measured::subject::calibrate::{Problem, Quantity, Settings};
use muscle_actuator_measured::subject::{PreparedTrial, SubjectModel};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/ceinms")
}

/// The person's subject with the knee spanned by `units` only.
fn knee_subject(units: &[&str]) -> SubjectModel {
    let xml = Subject::read(&data().join("uncalibratedSubject.xml")).unwrap();
    let mut s = SubjectModel::of_ceinms(&xml).unwrap();
    s.dofs = vec![(
        "R_knee_fe".into(),
        units.iter().map(|u| u.to_string()).collect(),
    )];
    s
}

fn map() -> ExcitationMap {
    ExcitationMap::read(&data().join("emgGenerator-16To34.xml")).unwrap()
}

fn prepared(subject: &SubjectModel, dir: &Path) -> PreparedTrial {
    let trial = Trial::read(dir).unwrap();
    PreparedTrial::new(subject, &map(), &trial, &["R_knee_fe".into()]).unwrap()
}

/// A deterministic standard normal sequence (xorshift64* and Box–Muller).
fn normals(seed: u64, n: usize) -> Vec<f64> {
    let mut x = seed.max(1);
    let mut uniform = || {
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        ((x.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let (u, v) = (uniform(), uniform());
            (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        })
        .collect()
}

/// Copies of `trials` whose knee moment is the one `truth` makes, plus noise of `noise` times
/// its standard deviation; the other degrees of freedom left out.
fn synthetic_trials(
    problem: &Problem,
    truth: &[f64],
    names: &[&str],
    noise: f64,
    tag: &str,
) -> Vec<PathBuf> {
    let params = problem.params_at(truth);
    let out = temp_dir(tag);
    names
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let p = problem.trials[k]
                .run(&params, problem.model, problem.stepping)
                .unwrap();
            let m = &p.moment[0];
            let mean = m.iter().sum::<f64>() / m.len() as f64;
            let sd = (m.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / m.len() as f64).sqrt();
            let e = normals(k as u64 + 7, m.len());
            let noisy: Vec<f64> = m.iter().zip(e).map(|(x, e)| x + noise * sd * e).collect();
            let dir = out.join(name);
            std::fs::create_dir_all(&dir).unwrap();
            for f in ["emg.txt", "lmt.txt", "R_knee_feMa.txt"] {
                std::fs::copy(data().join(name).join(f), dir.join(f)).unwrap();
            }
            std::fs::write(
                dir.join("R_knee_feTorque.txt"),
                trials::table(&["R_knee_fe"], &p.times, &[noisy]),
            )
            .unwrap();
            dir
        })
        .collect()
}

/// Three knee units on distinct channels, two trials, a known parameter set different from the
/// start in every parameter, its moments with 2 % noise: calibrated back to it.
fn identifiable(model: ModelKind, evaluations: usize) {
    let units = ["vaslat_r", "bicfemlh_r", "gasmed_r"];
    let subject = knee_subject(&units);
    let names = ["_FastWalking_", "_CrossOvers1_"];
    let real: Vec<PreparedTrial> = names
        .iter()
        .map(|n| prepared(&subject, &data().join(n)))
        .collect();
    let stepping = default_stepping(model);
    let problem = Problem::new(&subject, &map(), real, model, stepping).unwrap();
    let truth: Vec<f64> = problem
        .parameters
        .iter()
        .enumerate()
        .map(|(k, p)| match p.quantity {
            Quantity::C1 => -0.97,
            Quantity::C2 => -0.9,
            Quantity::ShapeFactor => -1.5,
            Quantity::EmDelay => 0.04,
            Quantity::Strength => [1.6, 0.8, 1.3][k % 3],
            Quantity::SlackFibreLength => [0.9, 1.0, 1.1][k % 3],
            Quantity::OptimalFibreLength => [1.05, 0.95, 1.0][k % 3],
            Quantity::MaxVelocity => 20.0,
        })
        .collect();
    let dirs = synthetic_trials(
        &problem,
        &truth,
        &names,
        0.02,
        &format!("ident_{}", model.name()),
    );
    let trials: Vec<PreparedTrial> = dirs.iter().map(|d| prepared(&subject, d)).collect();
    let problem = Problem::new(&subject, &map(), trials, model, stepping).unwrap();
    let settings = Settings {
        seed: 3,
        max_evaluations: evaluations,
        threads: 2,
        ..Settings::default()
    };
    let outcome = problem
        .calibrate(&settings, |_, _| ControlFlow::Continue(()))
        .unwrap();
    let show = || {
        problem
            .parameters
            .iter()
            .zip(truth.iter().zip(&outcome.values))
            .map(|(p, (t, v))| format!("{} {t:.3} -> {v:.3}", p.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    eprintln!(
        "{}: cost {:.5} from {:.4} in {} evaluations; {}",
        model.name(),
        outcome.cost,
        outcome.start_cost,
        outcome.evaluations,
        show()
    );
    // The noise alone costs 0.02² = 0.0004 of each trial's variance: the fit must come down to
    // twice that, and the noiseless moments of the result must be the truth's.
    assert!(
        outcome.cost < 0.0008,
        "{}: cost {}",
        model.name(),
        outcome.cost
    );
    let (want, got) = (
        problem.params_at(&truth),
        problem.params_at(&outcome.values),
    );
    for t in &problem.trials {
        let m = t.run(&want, model, stepping).unwrap().moment.remove(0);
        let p = t.run(&got, model, stepping).unwrap().moment.remove(0);
        let r2 = rate(&m, &p).unwrap().r_squared;
        assert!(r2 > 0.999, "{}: {}: R2 {r2}", model.name(), t.name);
    }
    // The bounds each parameter is recovered within (docs/emg.md "Identifiability").
    for (p, (t, v)) in problem
        .parameters
        .iter()
        .zip(truth.iter().zip(&outcome.values))
    {
        let tolerance = match p.quantity {
            // The recursion's poles −C1, −C2 are interchangeable: checked below.
            Quantity::C1 | Quantity::C2 => continue,
            Quantity::ShapeFactor => 0.5,
            Quantity::EmDelay => 0.01,
            Quantity::Strength => 0.1 * t,
            Quantity::SlackFibreLength => 0.05,
            Quantity::OptimalFibreLength => 0.15,
            Quantity::MaxVelocity => 0.1 * t,
        };
        assert!((v - t).abs() <= tolerance, "{}: {}", model.name(), show());
    }
    // The slow pole (0.97: a 16 ms time constant at 2 kHz) is recovered; the fast one (0.9,
    // 5 ms) trades against the delay, and only the response it makes together is checked above.
    let slow = (-outcome.values[0]).max(-outcome.values[1]);
    assert!((slow - 0.97).abs() < 0.02, "{}", show());
}

#[test]
fn known_parameters_are_recovered_hill() {
    identifiable(ModelKind::HILL, 4000);
}

#[test]
fn known_parameters_are_recovered_distribution_moment() {
    identifiable(ModelKind::HUXLEY, 4000);
}

/// The person's knee: calibrated on two walking trials and one cut, the other three predicted
/// (never a calibration trial reported as a prediction): each above the floor of docs/emg.md,
/// and better than the subject before calibration. The same seed on one thread gives the same
/// parameters bit for bit.
#[test]
fn calibrated_on_three_trials_the_person_s_other_three_are_predicted() {
    let all = [
        "bicfemlh_r",
        "bicfemsh_r",
        "gaslat_r",
        "gasmed_r",
        "gra_r",
        "recfem_r",
        "sar_r",
        "semimem_r",
        "semiten_r",
        "tfl_r",
        "vasint_r",
        "vaslat_r",
        "vasmed_r",
    ];
    let subject = knee_subject(&all);
    let (fit, held_out) = (
        ["_FastWalking_", "_CrossOvers1_", "_FastWalking9_"],
        ["_FastWalking1_", "_CrossOvers6_", "_CrossOvers7_"],
    );
    let trials = fit
        .iter()
        .map(|n| prepared(&subject, &data().join(n)))
        .collect();
    let model = ModelKind::HILL;
    let problem = Problem::new(&subject, &map(), trials, model, default_stepping(model)).unwrap();
    let settings = Settings {
        seed: 1,
        max_evaluations: 300,
        threads: 2,
        ..Settings::default()
    };
    let outcome = problem
        .calibrate(&settings, |_, _| ControlFlow::Continue(()))
        .unwrap();
    let calibrated = problem.calibrated(&subject, &outcome, &settings);
    for name in held_out {
        let t = prepared(&calibrated, &data().join(name));
        let params = calibrated.params_of(&t.units).unwrap();
        let before = subject.params_of(&t.units).unwrap();
        // As `predict` does: lengths a little beyond a fibre's reach held at it.
        let r = |params: &[_]| {
            let mut t = t.clone();
            t.hold_within_reach(params).unwrap();
            let p = t.run(params, model, default_stepping(model)).unwrap();
            rate(&p.measured[0], &p.moment[0]).unwrap()
        };
        let (after, start) = (r(&params), r(&before));
        eprintln!(
            "{name}: R2 {:.3} (uncalibrated {:.3}), r2 {:.3}, RMSE {:.1} N m",
            after.r_squared, start.r_squared, after.pearson_r_squared, after.rmse
        );
        assert!(after.r_squared > FLOOR_R2, "{name}: {after:?}");
        assert!(after.r_squared > start.r_squared + 0.2, "{name}");
    }
}

/// A trial's moment arms of units the subject does not count on a degree of freedom are named
/// for the caller to say, not left out in silence.
#[test]
fn moment_arms_the_subject_leaves_out_are_named() {
    let subject = knee_subject(&["vaslat_r", "bicfemlh_r", "gasmed_r"]);
    let t = prepared(&subject, &data().join("_FastWalking_"));
    assert_eq!(t.unused_arms.len(), 1, "{:?}", t.unused_arms);
    let (dof, units) = &t.unused_arms[0];
    assert_eq!(dof, "R_knee_fe");
    let has = |u: &str| units.iter().any(|x| x == u);
    assert!(has("vasmed_r") && has("semiten_r"), "{units:?}");
    assert!(!has("vaslat_r") && !has("gasmed_r"), "{units:?}");
}

/// A calibration makes at most the evaluations it is given: whole CMA-ES generations that fit
/// (a budget below a generation's size makes that one generation smaller).
#[test]
fn the_budget_is_never_exceeded() {
    let subject = knee_subject(&["vaslat_r", "bicfemlh_r", "gasmed_r"]);
    let trials = vec![prepared(&subject, &data().join("_FastWalking_"))];
    let model = ModelKind::HILL;
    let problem = Problem::new(&subject, &map(), trials, model, default_stepping(model)).unwrap();
    // CMA-ES's population for the searched parameters (Hansen 2016): 4 + ⌊3 ln n⌋.
    let lambda = 4 + (3.0 * (problem.searched.len() as f64).ln()).floor() as usize;
    for budget in [2, lambda - 1, lambda, 2 * lambda + 1, 3 * lambda - 1] {
        let settings = Settings {
            max_evaluations: budget,
            threads: 2,
            ..Settings::default()
        };
        let mut seen = Vec::new();
        let outcome = problem
            .calibrate(&settings, |n, _| {
                seen.push(n);
                ControlFlow::Continue(())
            })
            .unwrap();
        let want = if budget < lambda {
            budget
        } else {
            budget / lambda * lambda
        };
        assert_eq!(outcome.evaluations, want, "budget {budget}, λ {lambda}");
        assert_eq!(seen.last(), Some(&want), "{seen:?}");
    }
}

/// The floor of a held-out trial's knee R² after the test's short calibration (docs/emg.md).
const FLOOR_R2: f64 = 0.3;

/// A fresh folder for one test's files.
fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("muscle_actuator_{tag}_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}
