//! Units driven by measured lengths (docs/emg.md "Prediction"): a unit held isometric is the same
//! muscle clamped (docs/model.md §8c), for the Hill and the Distribution-Moment models; its joint
//! moment is its force times its moment arm; `predict` writes the moments' CSV and rates them;
//! and every kind of bad input is one clear line, a non-zero exit and nothing written.

#[path = "common/cli.rs"]
mod cli;
#[path = "common/trials.rs"]
mod trials;

use cli::{assert_clean_failure, bin, read_csv, run_ok, stderr, temp_dir};
use muscle_actuator::measured::{ExcitationMap, Trial};
use muscle_actuator::physics::models::ModelKind;
use muscle_actuator::physics::params::formulation::FibreKind;
use muscle_actuator::physics::params::MuscleParams;
use muscle_actuator::physics::plant::{Inputs, Plant};
use muscle_actuator::physics::topology::Topology;
use muscle_actuator::sim::simulation::{default_stepping, Simulation};
use muscle_actuator::subject::calibrate::Bounds;
use muscle_actuator::subject::{PreparedTrial, SubjectModel, UnitModel};
use std::path::{Path, PathBuf};
use trials::{own_channels, times, SyntheticTrial};

/// The excitation of the isometric test: off, a 100 ms pulse of full excitation, off.
fn pulse(t: f64) -> f64 {
    if (1.05..1.15).contains(&t) {
        1.0
    } else {
        0.0
    }
}

/// A one-unit subject of `params` spanning the degree of freedom `d`.
fn one_unit_subject(params: MuscleParams) -> SubjectModel {
    SubjectModel {
        id: "test".into(),
        units: vec![UnitModel {
            name: "m".into(),
            params,
        }],
        dofs: vec![("d".into(), vec!["m".into()])],
        calibration: None,
        bounds: Bounds::default(),
    }
}

/// Writes the subject, the map and a trial of the unit held at `length` under the pulse (EMG
/// at 1 kHz from 1.0 s to 1.4 s, kinematics at 250 Hz, a 3 cm moment arm); returns the
/// subject's, the map's and the trial's paths.
fn isometric_files(dir: &Path, params: MuscleParams, length: f64) -> (PathBuf, PathBuf, PathBuf) {
    let emg_times = times(1.0, 1000.0, 401);
    let kinematic_times = times(1.0, 250.0, 101);
    let n = kinematic_times.len();
    let trial = SyntheticTrial {
        units: &["m"],
        emg: vec![emg_times.iter().map(|&t| pulse(t)).collect()],
        emg_times,
        lengths: vec![vec![length; n]],
        arms: vec![vec![0.03; n]],
        moment: kinematic_times.iter().map(|t| (10.0 * t).sin()).collect(),
        kinematic_times,
        dof: "d",
    };
    let trial_dir = dir.join("trial");
    trial.write(&trial_dir);
    let subject = dir.join("subject.toml");
    std::fs::write(&subject, one_unit_subject(params).to_toml_string().unwrap()).unwrap();
    let map = dir.join("map.xml");
    std::fs::write(&map, own_channels(&["m"])).unwrap();
    (subject, map, trial_dir)
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

/// `predict` writes `time`, the degree of freedom and `<dof>_measured`, the units' CSV, and a
/// rating line; the CSV's moments are those of the library's drive.
#[test]
fn predict_writes_the_moments_and_rates_them() {
    let dir = temp_dir("subject_predict");
    let params = MuscleParams::default();
    let (subject, map, trial) =
        isometric_files(&dir, params.clone(), params.l_opt + params.l_ts + 0.002);
    let csv = dir.join("moments.csv");
    let muscles = dir.join("muscles.csv");
    let o = run_ok(
        bin()
            .args(["predict", "--model", "hill", "--subject"])
            .args([
                subject.as_os_str(),
                "--excitations".as_ref(),
                map.as_os_str(),
                "--trial".as_ref(),
                trial.as_os_str(),
                "--csv".as_ref(),
                csv.as_os_str(),
                "--muscles-csv".as_ref(),
                muscles.as_os_str(),
            ]),
    );
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("R2") && out.contains("RMSE"), "{out}");
    let (header, rows) = read_csv(&std::fs::read_to_string(&csv).unwrap());
    assert_eq!(header, ["time", "d", "d_measured"]);
    assert_eq!(rows.len(), 101);
    let (header, rows) = read_csv(&std::fs::read_to_string(&muscles).unwrap());
    assert_eq!(
        header,
        ["time", "m.force", "m.activation", "m.fibre_length"]
    );
    let peak = rows
        .iter()
        .map(|r| r[1].parse::<f64>().unwrap())
        .fold(0.0, f64::max);
    assert!(peak > 0.5 * params.f_max, "{peak}");
}

/// Each bad input of `predict`: one line naming the file and the place, a non-zero exit,
/// nothing written under the output's name, no panic.
#[test]
fn bad_inputs_are_refused_cleanly() {
    let dir = temp_dir("subject_bad");
    let params = MuscleParams::default();
    let (subject, map, trial) =
        isometric_files(&dir, params.clone(), params.l_opt + params.l_ts + 0.002);
    let out = dir.join("never.csv");
    let predict = |subject: &Path, map: &Path, trial: &Path| {
        let o = bin()
            .args(["predict", "--subject"])
            .arg(subject)
            .arg("--excitations")
            .arg(map)
            .arg("--trial")
            .arg(trial)
            .arg("--csv")
            .arg(&out)
            .output()
            .unwrap();
        assert!(!out.exists(), "wrote {}: {}", out.display(), stderr(&o));
        o
    };
    // A copy of the good trial with one file replaced.
    let broken = |name: &str, file: &str, edit: &dyn Fn(String) -> String| {
        let d = dir.join(name);
        std::fs::create_dir_all(&d).unwrap();
        for f in std::fs::read_dir(&trial).unwrap() {
            let f = f.unwrap().path();
            std::fs::copy(&f, d.join(f.file_name().unwrap())).unwrap();
        }
        let text = std::fs::read_to_string(d.join(file)).unwrap();
        std::fs::write(d.join(file), edit(text)).unwrap();
        d
    };
    let row = |text: String, k: usize, edit: &dyn Fn(&str) -> String| {
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        lines[k] = edit(&lines[k]);
        lines.join("\n") + "\n"
    };
    // Times that go back.
    let t = broken("backwards", "lmt.txt", &|s| {
        row(s, 5, &|l| l.replacen("1.008", "1.0", 1))
    });
    assert_clean_failure(&predict(&subject, &map, &t), &["lmt.txt", "line 6"]);
    // A missing column: the unit's length.
    let t = broken("nocolumn", "lmt.txt", &|s| s.replace("\tm\n", "\tother\n"));
    assert_clean_failure(&predict(&subject, &map, &t), &["lmt.txt", "\"m\""]);
    // A NaN and a negative EMG sample.
    let t = broken("nan", "emg.txt", &|s| {
        row(s, 10, &|l| {
            format!("{}\tNaN", l.split('\t').next().unwrap())
        })
    });
    assert_clean_failure(&predict(&subject, &map, &t), &["emg.txt", "line 11"]);
    let t = broken("negative", "emg.txt", &|s| {
        row(s, 10, &|l| {
            format!("{}\t-0.5", l.split('\t').next().unwrap())
        })
    });
    assert_clean_failure(&predict(&subject, &map, &t), &["negative", "\"m\""]);
    // Moment arms at other times than the lengths.
    let t = broken("mismatch", "dMa.txt", &|s| {
        row(s, 6, &|l| l.replacen("1.012", "1.0125", 1))
    });
    assert_clean_failure(&predict(&subject, &map, &t), &["dMa.txt"]);
    // A length no fibre of the unit can take: ten times the unit's resting length.
    let long = format!("{}", 10.0 * (params.l_opt + params.l_ts));
    let t = broken("too_long", "lmt.txt", &|s| {
        row(s, 40, &|l| {
            format!("{}\t{long}", l.split('\t').next().unwrap())
        })
    });
    assert_clean_failure(&predict(&subject, &map, &t), &["unit \"m\"", "length"]);
    // A subject file that is not one, and one that names an unknown unit.
    let not_subject = dir.join("not_subject.toml");
    std::fs::write(&not_subject, "[joint]\nname = \"elbow\"\n").unwrap();
    assert_clean_failure(
        &predict(&not_subject, &map, &trial),
        &["not_subject.toml", "joint"],
    );
    let unknown = dir.join("unknown_unit.toml");
    let text = std::fs::read_to_string(&subject).unwrap();
    std::fs::write(&unknown, text.replace("units = [\"m\"]", "units = [\"q\"]")).unwrap();
    assert_clean_failure(
        &predict(&unknown, &map, &trial),
        &["unknown_unit.toml", "\"q\""],
    );
    // A map naming a channel the EMG does not have.
    let bad_map = dir.join("bad_map.xml");
    std::fs::write(
        &bad_map,
        own_channels(&["m"]).replace(">m</emg>", ">x</emg>"),
    )
    .unwrap();
    assert_clean_failure(
        &predict(&subject, &bad_map, &trial),
        &["bad_map.xml", "\"x\""],
    );
}

/// A length a little beyond the reach of the unit's fibre (2 l_opt with the tendon at slack) is
/// held at the reach by `predict`, counted on standard error, and drives the unit exactly as
/// the reach itself does; one further beyond is refused (`bad_inputs_are_refused_cleanly`).
#[test]
fn lengths_a_little_beyond_reach_are_held() {
    let params = MuscleParams::default();
    let reach = params.l_ts + 2.0 * params.l_opt;
    let predict = |name: &str, length: f64| {
        let dir = temp_dir(name);
        let (subject, map, trial) = isometric_files(&dir, params.clone(), length);
        let (csv, muscles) = (dir.join("moments.csv"), dir.join("muscles.csv"));
        let o = run_ok(
            bin()
                .args(["predict", "--model", "hill", "--subject"])
                .arg(&subject)
                .arg("--excitations")
                .arg(&map)
                .arg("--trial")
                .arg(&trial)
                .arg("--csv")
                .arg(&csv)
                .arg("--muscles-csv")
                .arg(&muscles),
        );
        let read = |p: &Path| std::fs::read_to_string(p).unwrap();
        (stderr(&o), read(&csv), read(&muscles))
    };
    let (said, moments, forces) = predict("subject_held", reach + 0.001);
    let (quiet, at_moments, at_forces) = predict("subject_at_reach", reach);
    // 400 ticks at 1 kHz: 401 length samples, every one held.
    assert!(
        said.contains("401 length samples") && said.contains("held") && said.contains("\"m\""),
        "{said}"
    );
    assert!(!quiet.contains("held"), "{quiet}");
    assert_eq!(moments, at_moments);
    assert_eq!(forces, at_forces);
}
