//! `predict --out` and `--plot` (docs/emg.md "Prediction"): the prediction recorded as an ordinary
//! run, which loads with one state per tick, replays bit for bit, compares with itself and
//! exports the forces of `--muscles-csv` at the kinematic samples; the figures as PNG and SVG;
//! and a predict that fails, before the drive or after it, leaves neither the recording nor the
//! figures behind.

#[path = "common/cli.rs"]
mod cli;
#[path = "../crates/measured/tests/common/trials.rs"]
mod trials;

use cli::{assert_clean_failure, bin, read_csv, run_ok, stderr, temp_dir};
use muscle_actuator_core::physics::MuscleParams;
use muscle_actuator_measured::subject::calibrate::Bounds;
use muscle_actuator_measured::subject::{SubjectModel, UnitModel};
use muscle_actuator_recording::runs::{load_run, AttachmentMeta};
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::process::Output;
use trials::{own_channels, times, SyntheticTrial};

/// The units of the synthetic trial.
const UNITS: [&str; 2] = ["flexor", "extensor"];
/// Its EMG: from 1.0 s at 1 kHz, 401 samples; the kinematics from 1.05 s at 250 Hz to 1.4 s.
const EMG_START_S: f64 = 1.0;
const EMG_RATE_HZ: f64 = 1000.0;
/// Ticks of the drive: one per EMG sample up to the last kinematic sample (1.398 s).
const TICKS: u64 = 398;

/// The files of a synthetic trial: the subject, the map, the trial's folder.
struct Files {
    subject: PathBuf,
    map: PathBuf,
    trial: PathBuf,
}

/// Two units of the paper's muscle (the second twice as strong) spanning the degree of freedom
/// `d` with opposite arms, their lengths swinging by ±4 mm around the resting one under EMG that
/// rises and falls; `moment` gives the measured moment at a time.
fn write_files(dir: &Path, moment: &dyn Fn(f64) -> f64) -> Files {
    let p = MuscleParams::default();
    let mut strong = p.clone();
    strong.f_max *= 2.0;
    let rest = p.l_opt + p.l_ts;
    let emg_times = times(EMG_START_S, EMG_RATE_HZ, 401);
    let kinematic_times = times(1.05, 250.0, 88);
    let n = kinematic_times.len();
    let emg = |phase: f64| -> Vec<f64> {
        let e = |t: f64| 0.4 + 0.35 * (TAU * 4.0 * t + phase).sin();
        emg_times.iter().map(|&t| e(t)).collect()
    };
    let length = |sign: f64| -> Vec<f64> {
        let l = |t: f64| rest + sign * 0.004 * (TAU * 3.0 * t).sin();
        kinematic_times.iter().map(|&t| l(t)).collect()
    };
    let trial = SyntheticTrial {
        units: &UNITS,
        emg: vec![emg(0.0), emg(2.0)],
        emg_times: emg_times.clone(),
        lengths: vec![length(1.0), length(-1.0)],
        arms: vec![vec![0.03; n], vec![-0.02; n]],
        moment: kinematic_times.iter().map(|&t| moment(t)).collect(),
        kinematic_times,
        dof: "d",
    };
    let files = Files {
        subject: dir.join("subject.toml"),
        map: dir.join("map.xml"),
        trial: dir.join("trial"),
    };
    trial.write(&files.trial);
    let subject = SubjectModel {
        id: "test".into(),
        units: (UNITS.iter().zip([p, strong]))
            .map(|(name, params)| UnitModel {
                name: (*name).into(),
                params,
            })
            .collect(),
        dofs: vec![("d".into(), UNITS.iter().map(|u| u.to_string()).collect())],
        calibration: None,
        bounds: Bounds::default(),
    };
    std::fs::write(&files.subject, subject.to_toml_string().unwrap()).unwrap();
    std::fs::write(&files.map, own_channels(&UNITS)).unwrap();
    files
}

/// A measured moment that varies.
fn swinging(t: f64) -> f64 {
    5.0 * (TAU * 3.0 * t).sin()
}

/// `predict` of `files` with `--model hill`, the moments' CSV as `dir/moments.csv`, then
/// `extra`.
fn predict(files: &Files, dir: &Path, extra: &[&Path]) -> Output {
    bin()
        .args(["predict", "--model", "hill", "--subject"])
        .arg(&files.subject)
        .arg("--excitations")
        .arg(&files.map)
        .arg("--trial")
        .arg(&files.trial)
        .arg("--csv")
        .arg(dir.join("moments.csv"))
        .args(extra)
        .output()
        .unwrap()
}

/// The four images of `--plot dir/fig.png`.
fn figures(dir: &Path) -> [PathBuf; 4] {
    ["fig.png", "fig.svg", "fig_forces.png", "fig_forces.svg"].map(|n| dir.join(n))
}

/// The temporaries left in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    (std::fs::read_dir(dir).unwrap())
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp-"))
        .collect()
}

/// `series[x]` for a fractional tick x, linearly between the ticks around it.
fn at_tick(series: &[f64], x: f64) -> f64 {
    let k = (x.floor().max(0.0) as usize).min(series.len() - 1);
    let next = (k + 1).min(series.len() - 1);
    let w = (x - k as f64).clamp(0.0, 1.0);
    series[k] + w * (series[next] - series[k])
}

/// Per unit, its force at every tick from `export`'s table (rows by tick, then unit).
fn exported_forces(csv: &Path, rate_hz: f64) -> Vec<Vec<f64>> {
    let (header, rows) = read_csv(&std::fs::read_to_string(csv).unwrap());
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (time, name, force) = (col("time"), col("name"), col("force"));
    let mut forces = vec![Vec::new(); UNITS.len()];
    for row in &rows {
        let i = UNITS.iter().position(|u| *u == row[name]).unwrap();
        let tick = row[time].parse::<f64>().unwrap() * rate_hz;
        assert_eq!(
            tick.round() as usize,
            forces[i].len(),
            "rows out of tick order"
        );
        forces[i].push(row[force].parse::<f64>().unwrap());
    }
    forces
}

/// The recording loads as a driven run of the units' length coordinates with one state per
/// tick and the inputs of every tick; it replays bit for bit and compares with itself; its
/// exported forces, read at the kinematic samples, are `--muscles-csv`'s; `--plot` writes the
/// PNG and SVG of both figures.
#[test]
fn predict_out_records_the_run_and_plot_draws_it() {
    let dir = temp_dir("subject_recording_ok");
    let files = write_files(&dir, &swinging);
    let (run, muscles) = (dir.join("run.mcap"), dir.join("muscles.csv"));
    let o = predict(
        &files,
        &dir,
        &[
            "--muscles-csv".as_ref(),
            &muscles,
            "--out".as_ref(),
            &run,
            "--plot".as_ref(),
            &dir.join("fig.png"),
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let loaded = load_run(&run).unwrap();
    let meta = &loaded.meta;
    assert_eq!(meta.attachment, AttachmentMeta::Driven);
    // The EMG's rate as its mean sample step gives it.
    let rate_hz = meta.rate_hz;
    assert!((rate_hz - EMG_RATE_HZ).abs() < 1e-9, "{rate_hz}");
    assert_eq!(meta.muscles, UNITS);
    assert_eq!(meta.joints, ["flexor.length", "extensor.length"]);
    assert!(meta.config.joints.iter().all(|j| j.driven));
    let ticks: Vec<u64> = loaded.states.iter().map(|s| s.tick).collect();
    assert_eq!(ticks, (0..=TICKS).collect::<Vec<_>>());
    let motion_ticks: Vec<u64> = loaded.joint_motions.iter().map(|m| m.0).collect();
    assert_eq!(motion_ticks, (0..TICKS).collect::<Vec<_>>());
    assert!(
        loaded.activations.len() > 100,
        "{}",
        loaded.activations.len()
    );
    let exported = dir.join("export.csv");
    run_ok(bin().arg("export").arg(&run).arg("--csv").arg(&exported));
    let forces = exported_forces(&exported, rate_hz);
    let (header, rows) = read_csv(&std::fs::read_to_string(&muscles).unwrap());
    assert_eq!(rows.len(), 88);
    for (i, unit) in UNITS.iter().enumerate() {
        assert_eq!(forces[i].len() as u64, TICKS + 1);
        let col = header
            .iter()
            .position(|h| *h == format!("{unit}.force"))
            .unwrap();
        for row in &rows {
            let t: f64 = row[0].parse().unwrap();
            let want: f64 = row[col].parse().unwrap();
            let got = at_tick(&forces[i], (t - EMG_START_S) * rate_hz);
            assert!(
                (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                "{unit} at {t} s: recorded {got} N, CSV {want} N"
            );
        }
        let peak = forces[i].iter().cloned().fold(0.0, f64::max);
        assert!(peak > 100.0, "{unit}: peak {peak} N");
    }
    let replay = run_ok(
        bin()
            .arg("replay")
            .arg(&run)
            .arg("--out")
            .arg(dir.join("replay.mcap")),
    );
    let said = stderr(&replay);
    assert!(
        said.contains(&format!(
            "{n} of {n} recorded states reproduced bit for bit",
            n = TICKS + 1
        )),
        "{said}"
    );
    let compared = run_ok(bin().arg("compare").arg(&run).arg(&run));
    let table = String::from_utf8_lossy(&compared.stdout);
    assert!(
        table.contains("flexor.force") && table.contains("extensor.force"),
        "{table}"
    );
    for image in figures(&dir) {
        let bytes = std::fs::read(&image).unwrap_or_else(|e| panic!("{}: {e}", image.display()));
        match image.extension().and_then(|e| e.to_str()) {
            Some("png") => assert!(
                bytes.starts_with(b"\x89PNG\r\n\x1a\n"),
                "{}",
                image.display()
            ),
            _ => assert!(
                String::from_utf8_lossy(&bytes).contains("<svg"),
                "{}",
                image.display()
            ),
        }
    }
    assert_eq!(temporaries(&dir), Vec::<String>::new());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A predict that fails leaves no recording, no figure and no temporary: a negative EMG sample
/// (refused before the drive), a measured moment that cannot be rated (after the drive, while
/// the recording is still unnamed), and figures whose folder cannot be made (refused before
/// the drive; a missing folder is made, as for the recording); an output naming
/// an input is refused before anything is written.
#[test]
fn a_failing_predict_leaves_neither_recording_nor_figures() {
    let dir = temp_dir("subject_recording_fail");
    let run = dir.join("run.mcap");
    let plot = dir.join("fig.png");
    let outputs = || {
        [run.clone()]
            .into_iter()
            .chain(figures(&dir))
            .chain([dir.join("moments.csv")])
    };
    let assert_nothing_written = |o: &Output, needles: &[&str]| {
        assert_clean_failure(o, needles);
        for f in outputs() {
            assert!(!f.exists(), "{} written: {}", f.display(), stderr(o));
        }
        assert_eq!(temporaries(&dir), Vec::<String>::new());
    };
    let args = [
        "--out".as_ref(),
        run.as_path(),
        "--plot".as_ref(),
        plot.as_path(),
    ];
    // A negative EMG sample.
    let files = write_files(&dir.join("negative"), &swinging);
    let emg = files.trial.join("emg.txt");
    let text = std::fs::read_to_string(&emg).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    lines[20] = format!("{}\t-0.5\t0.2", lines[20].split('\t').next().unwrap());
    std::fs::write(&emg, lines.join("\n") + "\n").unwrap();
    assert_nothing_written(&predict(&files, &dir, &args), &["negative", "\"flexor\""]);
    // A constant measured moment: the drive runs, the rating fails.
    let files = write_files(&dir.join("constant"), &|_| 2.0);
    assert_nothing_written(&predict(&files, &dir, &args), &["d:"]);
    // Figures into a folder that cannot be made: a file is in its place.
    let files = write_files(&dir.join("good"), &swinging);
    let blocker = dir.join("good").join("blocker");
    std::fs::write(&blocker, "a file").unwrap();
    let nowhere = blocker.join("fig.png");
    let o = predict(
        &files,
        &dir,
        &[
            "--out".as_ref(),
            run.as_path(),
            "--plot".as_ref(),
            nowhere.as_path(),
        ],
    );
    assert_nothing_written(&o, &["blocker/fig.png"]);
    // The recording over the subject file.
    let before = std::fs::read(&files.subject).unwrap();
    let o = predict(&files, &dir, &["--out".as_ref(), files.subject.as_path()]);
    assert_nothing_written(&o, &["subject.toml", "overwrite"]);
    assert_eq!(std::fs::read(&files.subject).unwrap(), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A CEINMS trial recorded with the Distribution-Moment model replays bit for bit (`replay`
/// fails on any difference): its 34 length coordinates cross powers of two and zero, where the
/// angle a tick started from is not told by where it ended alone.
#[test]
fn a_ceinms_trial_replays_bit_for_bit() {
    let dir = temp_dir("subject_recording_ceinms");
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/ceinms");
    let run = dir.join("fast_walking.mcap");
    run_ok(
        bin()
            .args(["predict", "--model", "huxley", "--subject"])
            .arg(data.join("uncalibratedSubject.xml"))
            .arg("--excitations")
            .arg(data.join("emgGenerator-16To34.xml"))
            .arg("--trial")
            .arg(data.join("_FastWalking_"))
            .arg("--csv")
            .arg(dir.join("moments.csv"))
            .arg("--out")
            .arg(&run),
    );
    let replay = run_ok(
        bin()
            .arg("replay")
            .arg(&run)
            .arg("--out")
            .arg(dir.join("r.mcap")),
    );
    let said = stderr(&replay);
    assert!(said.contains("1685 of 1685 recorded states"), "{said}");
    std::fs::remove_dir_all(&dir).unwrap();
}
