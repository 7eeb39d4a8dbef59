//! The `predict` command (docs/emg.md "Prediction"): it writes the moments' CSV and rates them,
//! as the library's drive gives them; every kind of bad input is one clear line, a non-zero exit
//! and nothing written; lengths a little beyond a fibre's reach are held. The drive itself:
//! crates/measured/tests/subject_drive.rs.

#[path = "common/cli.rs"]
mod cli;
#[path = "../crates/measured/tests/common/trials.rs"]
mod trials;

use cli::{assert_clean_failure, bin, read_csv, run_ok, stderr, temp_dir};
use muscle_actuator_core::physics::MuscleParams;
use std::path::Path;
use trials::{isometric_files, own_channels};

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
    // An empty subject file, named .xml or not: neither form, said as such.
    for name in ["empty.xml", "empty.toml"] {
        let empty = dir.join(name);
        std::fs::write(&empty, "\n").unwrap();
        assert_clean_failure(&predict(&empty, &map, &trial), &[name, "the file is empty"]);
    }
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
    // A degree of freedom neither the subject nor the trial has: the valid ones named.
    let o = bin()
        .args(["predict", "--dofs", "knee", "--subject"])
        .arg(&subject)
        .arg("--excitations")
        .arg(&map)
        .arg("--trial")
        .arg(&trial)
        .output()
        .unwrap();
    assert_clean_failure(&o, &["no degree of freedom \"knee\"; it has d"]);
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

/// Without `--csv` (or any other output) `predict` rates the moments on standard output and
/// writes nothing.
#[test]
fn predict_rates_without_writing_when_no_output_is_asked() {
    let dir = temp_dir("subject_predict_ratings_only");
    let params = MuscleParams::default();
    let (subject, map, trial) =
        isometric_files(&dir, params.clone(), params.l_opt + params.l_ts + 0.002);
    let before: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    let o = run_ok(
        bin()
            .args(["predict", "--model", "hill", "--subject"])
            .arg(&subject)
            .arg("--excitations")
            .arg(&map)
            .arg("--trial")
            .arg(&trial),
    );
    let table = String::from_utf8(o.stdout).unwrap();
    assert!(
        table.contains("R2") && table.lines().any(|l| l.starts_with("d ")),
        "{table}"
    );
    let after: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    assert_eq!(before, after);
}

/// An output that cannot be made is refused before the work, and nothing is left of the others
/// (no figure, no CSV, no folder made for them); folders an output needs are made as `mkdir -p`
/// does, for the CSVs and figures as for the recording.
#[test]
fn outputs_are_all_made_or_none() {
    let dir = temp_dir("subject_predict_all_or_none");
    let params = MuscleParams::default();
    let (subject, map, trial) =
        isometric_files(&dir, params.clone(), params.l_opt + params.l_ts + 0.002);
    let listing = |d: &Path| {
        let mut v: Vec<_> = walk(d);
        v.sort();
        v
    };
    let before = listing(&dir);
    let blocked = dir.join("a_file");
    std::fs::write(&blocked, "not a folder").unwrap();
    let before_blocked = listing(&dir);
    let predict = |plot: &Path, csv: &Path, muscles: &Path| {
        let mut c = bin();
        c.args(["predict", "--model", "hill", "--subject"])
            .arg(&subject)
            .arg("--excitations")
            .arg(&map)
            .arg("--trial")
            .arg(&trial)
            .arg("--plot")
            .arg(plot)
            .arg("--csv")
            .arg(csv)
            .arg("--muscles-csv")
            .arg(muscles);
        c
    };
    let o = predict(
        &dir.join("new/figs/p.png"),
        &dir.join("new/m.csv"),
        &blocked.join("u.csv"),
    )
    .output()
    .unwrap();
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("a_file/u.csv") && e.lines().count() == 1, "{e}");
    assert_eq!(listing(&dir), before_blocked);
    std::fs::remove_file(&blocked).unwrap();
    assert_eq!(listing(&dir), before);
    run_ok(&mut predict(
        &dir.join("new/figs/p.png"),
        &dir.join("new/m.csv"),
        &dir.join("other/u.csv"),
    ));
    for made in [
        "new/figs/p.png",
        "new/figs/p.svg",
        "new/figs/p_forces.png",
        "new/figs/p_forces.svg",
        "new/m.csv",
        "other/u.csv",
    ] {
        assert!(dir.join(made).is_file(), "{made}");
    }
}

/// Every file and folder under `d`.
fn walk(d: &Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(d).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(walk(&p));
        }
        out.push(p);
    }
    out
}
