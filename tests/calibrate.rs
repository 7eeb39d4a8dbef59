//! The `calibrate` command as long work (docs/emg.md "Calibration"): Ctrl-C stops it after the
//! generation it is in and writes the best parameters so far under `--out`, marked stopped with
//! the evaluations made, which reads back as a subject; an `--out` that cannot be written fails
//! before any evaluation; a trial no parameters can drive is an error, not a calibrated
//! subject; a trial given twice is refused. Uses the person's data (data/ceinms). The
//! calibration itself: crates/measured/tests/subject_calibration.rs.

#[path = "common/cli.rs"]
mod cli;

use cli::{assert_clean_failure, bin, stderr, temp_dir};
use muscle_actuator_measured::subject::SubjectModel;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::time::{Duration, Instant};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data/ceinms")
}

/// `calibrate` of the knee on `trials` (the person's, by default two), with Hill, `evaluations`
/// at most.
fn calibrate_on(trials: &[PathBuf], out: &Path, evaluations: usize) -> std::process::Command {
    let mut cmd = bin();
    cmd.arg("calibrate")
        .arg("--subject")
        .arg(data().join("uncalibratedSubject.xml"))
        .arg("--excitations")
        .arg(data().join("emgGenerator-16To34.xml"))
        .arg("--trials")
        .args(trials)
        .args(["--dofs", "R_knee_fe", "--model", "hill", "--threads", "1"])
        .args(["--evaluations", &evaluations.to_string(), "--out"])
        .arg(out);
    cmd
}

/// [`calibrate_on`] the person's `_FastWalking1_` and `_CrossOvers1_`.
fn calibrate(out: &Path, evaluations: usize) -> std::process::Command {
    let trials = [data().join("_FastWalking1_"), data().join("_CrossOvers1_")];
    calibrate_on(&trials, out, evaluations)
}

#[test]
fn ctrl_c_writes_the_best_so_far_marked_stopped() {
    let dir = temp_dir("calibrate_ctrl_c");
    let out = dir.join("stopped.toml");
    let _ = std::fs::remove_file(&out);
    let mut child = calibrate(&out, 100_000)
        .stderr(Stdio::piped())
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    // The first line (standard error is no terminal here) says that Ctrl-C is honoured.
    let mut err = BufReader::new(child.stderr.take().unwrap());
    let mut first = String::new();
    err.read_line(&mut first).unwrap();
    assert!(first.starts_with("calibrate: "), "{first}");
    assert!(
        first.contains("on 2 trials, at most 100000 evaluations"),
        "{first}"
    );
    // SAFETY: kill(2) with the pid of a child this test started and has not yet waited for.
    assert_eq!(
        unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) },
        0
    );
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("calibrate did not stop within 120 s of Ctrl-C");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let mut rest = String::new();
    err.read_to_string(&mut rest).unwrap();
    assert!(!status.success(), "{rest}");
    assert_ne!(status.code(), Some(101), "panicked: {rest}");
    assert!(
        rest.contains("calibration stopped after ") && rest.contains("marked stopped"),
        "{rest}"
    );
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("stopped = true"), "{text}");
    let subject = SubjectModel::read(&out).unwrap();
    let record = subject.calibration.expect("a calibration record");
    assert!(record.stopped);
    assert!(
        record.evaluations >= 1 && record.evaluations < 100_000,
        "{} evaluations",
        record.evaluations
    );
    assert!(record.cost <= record.start_cost);
    assert_eq!(
        record.history.last().map(|h| h[0] as usize),
        Some(record.evaluations)
    );
}

#[test]
fn an_out_that_cannot_be_written_fails_before_any_evaluation() {
    let dir = temp_dir("calibrate_bad_out");
    let out = dir.join("no such folder").join("s.toml");
    let o = calibrate(&out, 100_000).output().unwrap();
    assert_clean_failure(&o, &["cannot write", "no such folder"]);
    assert!(!stderr(&o).contains("calibrate: "), "{}", stderr(&o));
}

#[test]
fn a_trial_no_parameters_can_drive_is_an_error_and_writes_nothing() {
    let dir = temp_dir("calibrate_unreachable");
    // The person's trial with every unit swinging between 0.2 m and 5 m from row to row: no
    // tendon slack length the calibration may choose keeps a fibre within its reach at both.
    let trial = dir.join("_FastWalking1_");
    std::fs::create_dir_all(&trial).unwrap();
    let source = data().join("_FastWalking1_");
    for entry in std::fs::read_dir(&source).unwrap() {
        let name = entry.unwrap().file_name();
        std::fs::copy(source.join(&name), trial.join(&name)).unwrap();
    }
    let lmt = std::fs::read_to_string(source.join("lmt.txt")).unwrap();
    let long: Vec<String> = (lmt.lines().enumerate())
        .map(|(i, line)| match i {
            0..=2 => line.to_string(),
            _ => {
                let mut cells: Vec<&str> = line.split('\t').collect();
                let length = if i % 2 == 0 { "5" } else { "0.2" };
                cells[1..].iter_mut().for_each(|c| *c = length);
                cells.join("\t")
            }
        })
        .collect();
    std::fs::write(trial.join("lmt.txt"), long.join("\n") + "\n").unwrap();
    let out = dir.join("calibrated.toml");
    let o = calibrate_on(&[trial], &out, 30).output().unwrap();
    assert_clean_failure(
        &o,
        &[
            "no parameters tried could drive the trials: trial _FastWalking1_",
            "optimal lengths long even with its tendon at slack",
        ],
    );
    assert!(!out.exists());
}

#[test]
fn a_trial_given_twice_is_refused_before_any_evaluation() {
    let dir = temp_dir("calibrate_twice");
    let out = dir.join("calibrated.toml");
    let trial = data().join("_FastWalking1_");
    let again = trial.join("..").join("_FastWalking1_");
    let o = calibrate_on(&[trial, again], &out, 30).output().unwrap();
    assert_clean_failure(&o, &["--trials:", "is given twice"]);
    assert!(!stderr(&o).contains("calibrate: "), "{}", stderr(&o));
    assert!(!out.exists());
}
