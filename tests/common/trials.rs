//! Synthetic measured trials in CEINMS's layout (data/ceinms/README.md): the tables, an
//! excitation map, written to a folder, for the subject commands' tests. Included by path
//! (`#[path = "common/trials.rs"] mod trials;`).
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::Path;

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
