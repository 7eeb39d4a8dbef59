use super::*;
use std::path::PathBuf;

const EMG: &str = "datacolumns 3\ndatarows 5\ntime\tch_a\tch_b\n\
    0.9\t0.1\t0.2\n0.95\t0.1\t0.2\n1\t0.1\t0.2\n1.05\t0.1\t0.2\n1.1\t0.3\t0.4\n";
const LMT: &str = "datacolumns 3\ndatarows 2\ntime\tu1\tu2\n1\t0.3\t0.4\n1.1\t0.31\t0.41\n";
const ARMS: &str = "datacolumns 2\ndatarows 2\ntime\tu2\n1\t0.03\n1.1\t-0.02\n";
const MOMENT: &str = "datacolumns 2\ndatarows 2\ntime\tR_knee_fe\n1\t8.5\n1.1\t-13\n";

/// A temporary folder, removed when dropped.
struct Folder(PathBuf);

impl Drop for Folder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

impl std::ops::Deref for Folder {
    type Target = PathBuf;
    fn deref(&self) -> &PathBuf {
        &self.0
    }
}

/// A fresh folder `tag` holding a good trial, less the files `skip`.
fn folder(tag: &str, skip: &[&str]) -> Folder {
    let dir = std::env::temp_dir().join(format!("measured_trial_{}_{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let files = [
        ("emg.txt", EMG),
        ("lmt.txt", LMT),
        ("R_knee_feMa.txt", ARMS),
        ("R_knee_feTorque.txt", MOMENT),
    ];
    for (name, text) in files.iter().filter(|(n, _)| !skip.contains(n)) {
        std::fs::write(dir.join(name), text).unwrap();
    }
    Folder(dir)
}

fn trial_error(dir: &Path) -> TrialError {
    match Trial::read(dir).unwrap_err() {
        MeasuredError::Trial { error, .. } => error,
        other => panic!("{other}"),
    }
}

#[test]
fn a_trial_reads_its_tables_per_degree_of_freedom() {
    let dir = folder("good", &[]);
    std::fs::write(dir.join("notes.md"), "ignored").unwrap();
    let t = Trial::read(&dir).unwrap();
    assert_eq!(
        t.name,
        format!("measured_trial_{}_good", std::process::id())
    );
    assert_eq!(t.emg.columns(), ["ch_a", "ch_b"]);
    assert_eq!(t.lmt.rows(), 2);
    assert_eq!(t.dofs().collect::<Vec<_>>(), ["R_knee_fe"]);
    assert_eq!(t.moment_arms["R_knee_fe"].columns(), ["u2"]);
    assert_eq!(t.moment("R_knee_fe"), Some(&[8.5, -13.0][..]));
    assert_eq!(t.moment("R_hip_fe"), None);
    // Without degrees of freedom: EMG and lengths only.
    let bare = folder("bare", &["R_knee_feMa.txt", "R_knee_feTorque.txt"]);
    assert_eq!(Trial::read(&bare).unwrap().dofs().count(), 0);
}

#[test]
fn a_missing_file_is_named() {
    let dir = folder("no_emg", &["emg.txt"]);
    let e = Trial::read(&dir).unwrap_err();
    assert!(matches!(
        e,
        MeasuredError::Trial {
            error: TrialError::MissingFile { file: "emg.txt" },
            ..
        }
    ));
    assert_eq!(
        e.to_string(),
        format!(
            "{}: no emg.txt (a trial's folder holds emg.txt, lmt.txt, and per degree of \
             freedom <dof>Ma.txt and <dof>Torque.txt)",
            dir.display()
        )
    );
    let missing = Trial::read(&dir.join("nowhere")).unwrap_err();
    assert!(missing.is_not_found(), "{missing}");
}

#[test]
fn a_degree_of_freedom_needs_both_files() {
    let dir = folder("arms_only", &["R_knee_feTorque.txt"]);
    let e = trial_error(&dir);
    assert_eq!(
        e.to_string(),
        "R_knee_feMa.txt without R_knee_feTorque.txt: a degree of freedom needs both its \
         moment arms and its moment"
    );
    let dir = folder("moment_only", &["R_knee_feMa.txt"]);
    assert!(matches!(
        trial_error(&dir),
        TrialError::UnpairedDof { ref missing, .. } if missing == "R_knee_feMa.txt"
    ));
}

#[test]
fn tables_are_cross_checked() {
    let dir = folder("unknown_unit", &[]);
    std::fs::write(dir.join("R_knee_feMa.txt"), ARMS.replace("u2", "u3")).unwrap();
    assert_eq!(
        trial_error(&dir),
        TrialError::UnknownUnit {
            file: "R_knee_feMa.txt".into(),
            unit: "u3".into()
        }
    );
    let dir = folder("moment_name", &[]);
    std::fs::write(
        dir.join("R_knee_feTorque.txt"),
        MOMENT.replace("R_knee_fe", "knee"),
    )
    .unwrap();
    assert_eq!(
        trial_error(&dir).to_string(),
        "R_knee_feTorque.txt: columns \"knee\", expected one column named \"R_knee_fe\""
    );
    let dir = folder("times", &[]);
    std::fs::write(dir.join("R_knee_feMa.txt"), ARMS.replace("1.1\t", "1.2\t")).unwrap();
    assert_eq!(
        trial_error(&dir),
        TrialError::TimesDiffer {
            file: "R_knee_feMa.txt".into(),
            line: 5,
            time: 1.2,
            lmt_time: 1.1
        }
    );
    let dir = folder("rows", &[]);
    let short = "datacolumns 2\ndatarows 1\ntime\tR_knee_fe\n1\t8.5\n";
    std::fs::write(dir.join("R_knee_feTorque.txt"), short).unwrap();
    assert!(matches!(
        trial_error(&dir),
        TrialError::RowCount {
            rows: 1,
            lmt_rows: 2,
            ..
        }
    ));
}

#[test]
fn a_length_that_no_muscle_has_is_refused_with_its_line_and_unit() {
    for (tag, bad) in [("zero", "0"), ("negative", "-0.173")] {
        let dir = folder(tag, &[]);
        std::fs::write(dir.join("lmt.txt"), LMT.replace("0.41", bad)).unwrap();
        let e = trial_error(&dir);
        assert_eq!(
            e,
            TrialError::LengthNotPositive {
                unit: "u2".into(),
                line: 5,
                length: bad.parse().unwrap(),
            }
        );
        let text = Trial::read(&dir).unwrap_err().to_string();
        assert!(
            text.contains("lmt.txt: line 5: unit \"u2\" has length")
                && text.contains("is positive"),
            "{text}"
        );
    }
}

#[test]
fn the_emg_covers_the_kinematics() {
    let dir = folder("late_emg", &[]);
    std::fs::write(
        dir.join("emg.txt"),
        EMG.replace("0.9\t", "0.8\t").replace("1.1\t", "1.09\t"),
    )
    .unwrap();
    let e = trial_error(&dir);
    assert_eq!(
        e,
        TrialError::EmgDoesNotCover {
            emg_start: 0.8,
            emg_end: 1.09,
            start: 1.0,
            end: 1.1
        }
    );
    let dir = folder("emg_after", &[]);
    let late = "datacolumns 2\ndatarows 2\ntime\tch\n1.01\t0\n1.2\t0\n";
    std::fs::write(dir.join("emg.txt"), late).unwrap();
    assert!(matches!(
        trial_error(&dir),
        TrialError::EmgDoesNotCover { .. }
    ));
}

#[test]
fn a_broken_table_is_named_by_its_file() {
    let dir = folder("broken", &[]);
    std::fs::write(dir.join("lmt.txt"), LMT.replace("0.31", "x")).unwrap();
    let e = Trial::read(&dir).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "{}: line 5, column 2 (u1): \"x\" is not a number",
            dir.join("lmt.txt").display()
        )
    );
}

#[test]
fn a_crowded_folder_is_refused() {
    let dir = folder("crowded", &[]);
    for i in 0..MAX_TRIAL_ENTRIES {
        std::fs::write(dir.join(format!("f{i}")), "").unwrap();
    }
    assert_eq!(
        trial_error(&dir),
        TrialError::TooManyEntries {
            max: MAX_TRIAL_ENTRIES
        }
    );
}
