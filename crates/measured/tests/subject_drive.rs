//! Units driven by measured lengths (docs/emg.md "Prediction"): a unit held isometric is the same
//! muscle clamped (docs/model.md §8c), for the Hill and the Distribution-Moment models, with
//! mass and as an equilibrium fibre; its joint moment is its force times its moment arm. The
//! `predict` command: the node package's tests/predict.rs.

#[path = "common/trials.rs"]
mod trials;

use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{FibreKind, Inputs, MuscleParams, Plant, Topology};
use muscle_actuator_core::sim::{default_stepping, Simulation};
use muscle_actuator_measured::measured::{ExcitationMap, Trial};
use muscle_actuator_measured::subject::{PreparedTrial, SubjectModel};
use std::path::PathBuf;
use trials::{isometric_files, pulse};

/// A fresh folder for one test's files.
fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("muscle_actuator_{tag}_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The tendon force of the muscle clamped at `length` after each tick of the pulse at 1 kHz
/// (the first entry at rest).
fn clamped_forces(params: &MuscleParams, model: ModelKind, length: f64) -> Vec<f64> {
    let plant = Plant::new(&Topology::clamped("m", params.clone(), length), model).unwrap();
    let mut sim =
        Simulation::new(plant, 1000.0, default_stepping(model), Inputs::zeros(1, 0)).unwrap();
    let force = |sim: &Simulation| {
        let a = sim.activations()[0];
        sim.plant()
            .fibre_state(sim.state(), 0, a, sim.inputs())
            .tendon_force
    };
    let mut out = vec![force(&sim)];
    for k in 0..400 {
        sim.inputs_mut().excitation[0] = pulse(1.0 + k as f64 / 1000.0);
        sim.step().unwrap();
        out.push(force(&sim));
    }
    out
}

/// A unit whose measured length never changes is the muscle clamped at that length: the same
/// tendon force at every kinematic sample (every fourth tick), for both ODE models, the paper's
/// muscle with mass and an equilibrium fibre with pennation 0; its moment is force × arm.
#[test]
fn a_unit_held_isometric_is_the_clamped_muscle() {
    let dir = temp_dir("subject_isometric");
    let mut equilibrium = MuscleParams::default();
    equilibrium.fibre = FibreKind::Equilibrium;
    for (k, params) in [MuscleParams::default(), equilibrium]
        .into_iter()
        .enumerate()
    {
        let length = params.l_opt + params.l_ts + 0.002;
        for model in [ModelKind::HILL, ModelKind::HUXLEY] {
            let (subject, map, trial) = isometric_files(
                &dir.join(format!("{k}{}", model.name())),
                params.clone(),
                length,
            );
            let subject = SubjectModel::read(&subject).unwrap();
            let map = ExcitationMap::read(&map).unwrap();
            let trial = Trial::read(&trial).unwrap();
            let prepared = PreparedTrial::new(&subject, &map, &trial, &["d".into()]).unwrap();
            assert_eq!(prepared.ticks(), 400);
            let p = prepared
                .run(
                    std::slice::from_ref(&params),
                    model,
                    default_stepping(model),
                )
                .unwrap();
            let clamped = clamped_forces(&params, model, length);
            let peak = clamped.iter().cloned().fold(0.0, f64::max);
            assert!(peak > 0.5 * params.f_max, "{}: peak {peak}", model.name());
            for (s, f) in p.force[0].iter().enumerate() {
                let want = clamped[4 * s];
                assert!(
                    (f - want).abs() <= 1e-6 * params.f_max,
                    "{} sample {s}: driven {f} N, clamped {want} N",
                    model.name()
                );
                assert!((p.moment[0][s] - 0.03 * f).abs() <= 1e-12 * params.f_max);
            }
        }
    }
}
