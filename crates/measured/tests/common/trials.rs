//! Synthetic measured trials in CEINMS's layout (data/ceinms/README.md): the tables, an
//! excitation map, written to a folder, and a one-unit subject held isometric under a pulse, for
//! the tests of subjects here and of the subject commands (tests/predict.rs and
//! tests/subject_recording.rs of the node package). Included by path
//! (`#[path = "common/trials.rs"] mod trials;`).
#![allow(dead_code)]

use muscle_actuator_core::physics::MuscleParams;
use muscle_actuator_measured::subject::calibrate::Bounds;
use muscle_actuator_measured::subject::{SubjectModel, UnitModel};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A table file: `datacolumns`, `datarows`, the header, the rows (tab-separated).
pub fn table(names: &[&str], times: &[f64], columns: &[Vec<f64>]) -> String {
    let mut s = format!(
        "datacolumns {}\ndatarows {}\ntime\t{}\n",
        names.len() + 1,
        times.len(),
        names.join("\t")
    );
    for (k, t) in times.iter().enumerate() {
        let _ = write!(s, "{t}");
        for c in columns {
            let _ = write!(s, "\t{}", c[k]);
        }
        s.push('\n');
    }
    s
}

/// `n` times from `start` at `rate_hz`.
pub fn times(start: f64, rate_hz: f64, n: usize) -> Vec<f64> {
    (0..n).map(|k| start + k as f64 / rate_hz).collect()
}

/// An excitation map driving each unit from the channel of the same name.
pub fn own_channels(units: &[&str]) -> String {
    let mut s = String::from("<?xml version=\"1.0\"?>\n<emgGenerator>\n<experimental>\n");
    for u in units {
        let _ = writeln!(s, "  <emg id=\"{u}\"/>");
    }
    s.push_str("</experimental>\n<mapping>\n");
    for u in units {
        let _ = writeln!(s, "  <emg id=\"{u}\" operation=\"assign\">{u}</emg>");
    }
    s.push_str("</mapping>\n<output>\n");
    let _ = writeln!(s, "{}", units.join(" "));
    s.push_str("</output>\n</emgGenerator>\n");
    s
}

/// A trial folder: EMG (one channel per unit), lengths, and for one degree of freedom the
/// moment arms and the moment.
pub struct SyntheticTrial<'a> {
    pub units: &'a [&'a str],
    pub emg_times: Vec<f64>,
    pub emg: Vec<Vec<f64>>,
    pub kinematic_times: Vec<f64>,
    pub lengths: Vec<Vec<f64>>,
    pub dof: &'a str,
    pub arms: Vec<Vec<f64>>,
    pub moment: Vec<f64>,
}

impl SyntheticTrial<'_> {
    /// Writes the folder's four files.
    pub fn write(&self, dir: &Path) {
        std::fs::create_dir_all(dir).unwrap();
        let w = |name: &str, text: String| std::fs::write(dir.join(name), text).unwrap();
        w("emg.txt", table(self.units, &self.emg_times, &self.emg));
        w(
            "lmt.txt",
            table(self.units, &self.kinematic_times, &self.lengths),
        );
        w(
            &format!("{}Ma.txt", self.dof),
            table(self.units, &self.kinematic_times, &self.arms),
        );
        w(
            &format!("{}Torque.txt", self.dof),
            table(
                &[self.dof],
                &self.kinematic_times,
                std::slice::from_ref(&self.moment),
            ),
        );
    }
}

/// The excitation of the isometric test: off, a 100 ms pulse of full excitation, off.
pub fn pulse(t: f64) -> f64 {
    if (1.05..1.15).contains(&t) {
        1.0
    } else {
        0.0
    }
}

/// A one-unit subject of `params` spanning the degree of freedom `d`.
pub fn one_unit_subject(params: MuscleParams) -> SubjectModel {
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
pub fn isometric_files(
    dir: &Path,
    params: MuscleParams,
    length: f64,
) -> (PathBuf, PathBuf, PathBuf) {
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
