//! A trial: one folder of CEINMS's tables for one motion of the subject (data/ceinms/README.md).
//!
//! - `emg.txt`: the EMG channels' linear envelopes (2 kHz in the toolbox's data).
//! - `lmt.txt`: the muscle–tendon units' lengths, m (250 Hz).
//! - per degree of freedom `<dof>`: `<dof>Ma.txt`, the moment arms, m, of the units that span
//!   it, and `<dof>Torque.txt`, its inverse-dynamics moment, N m, one column named `<dof>`.
//!
//! A degree of freedom needs both of its files: one without the other is refused
//! ([`TrialError::UnpairedDof`]); a folder without any is a trial without degrees of freedom.
//! Other files are ignored. The tables are cross-checked: the moment arms' columns are units of
//! `lmt.txt`; the moment arms and moments share `lmt.txt`'s times; the EMG starts at or before
//! the kinematics and ends at or after them (in the toolbox's data it starts 130 ms before, so
//! that activation can settle).

use crate::measured::table::Table;
use crate::measured::{shown, MeasuredError};
use muscle_actuator_core::text::excerpt;
use std::collections::BTreeMap;
use std::path::Path;

/// Most entries a trial's folder may have.
pub(crate) const MAX_TRIAL_ENTRIES: usize = 1024;

/// Largest difference between two files' times of one row, s (they are the same samples).
pub(crate) const TIME_TOLERANCE_S: f64 = 1e-9;

/// The moment arms' file of a degree of freedom ends so.
const MOMENT_ARMS: &str = "Ma.txt";
/// The moment's file of a degree of freedom ends so.
const MOMENT: &str = "Torque.txt";

/// One trial's tables, read and cross-checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Trial {
    /// The folder's name (`_FastWalking_`).
    pub name: String,
    /// `emg.txt`: one column per EMG channel, the envelope normalised to the maximum voluntary
    /// contraction (dimensionless).
    pub emg: Table,
    /// `lmt.txt`: one column per muscle–tendon unit, its length, m.
    pub lmt: Table,
    /// Per degree of freedom, `<dof>Ma.txt`: one column per unit that spans it, its moment arm,
    /// m, signed as OpenSim gives it; times those of `lmt`.
    pub moment_arms: BTreeMap<String, Table>,
    /// Per degree of freedom, `<dof>Torque.txt`: its inverse-dynamics moment, N m, in one
    /// column named as the degree of freedom; times those of `lmt`.
    pub moments: BTreeMap<String, Table>,
}

impl Trial {
    /// Reads and cross-checks the trial in the folder `dir`.
    pub fn read(dir: &Path) -> Result<Trial, MeasuredError> {
        let error = |error| MeasuredError::Trial {
            path: shown(dir),
            error,
        };
        let names = file_names(dir)?;
        for file in ["emg.txt", "lmt.txt"] {
            if !names.iter().any(|n| n == file) {
                return Err(error(TrialError::MissingFile { file }));
            }
        }
        let dofs = dof_names(&names).map_err(error)?;
        let emg = Table::read(&dir.join("emg.txt"))?;
        let lmt = Table::read(&dir.join("lmt.txt"))?;
        let mut moment_arms = BTreeMap::new();
        let mut moments = BTreeMap::new();
        for dof in dofs {
            let arms = Table::read(&dir.join(format!("{dof}{MOMENT_ARMS}")))?;
            let moment = Table::read(&dir.join(format!("{dof}{MOMENT}")))?;
            moment_arms.insert(dof.clone(), arms);
            moments.insert(dof, moment);
        }
        let trial = Trial {
            name: dir
                .file_name()
                .map_or_else(|| shown(dir), |n| n.to_string_lossy().into_owned()),
            emg,
            lmt,
            moment_arms,
            moments,
        };
        trial.check().map_err(error)?;
        Ok(trial)
    }

    /// The degrees of freedom, in name order.
    pub fn dofs(&self) -> impl Iterator<Item = &str> {
        self.moments.keys().map(String::as_str)
    }

    /// The inverse-dynamics moment of `dof`, N m, one per row of `lmt`.
    pub fn moment(&self, dof: &str) -> Option<&[f64]> {
        self.moments.get(dof)?.column(0)
    }

    /// The cross-checks of the module's documentation.
    pub(crate) fn check(&self) -> Result<(), TrialError> {
        for (index, unit) in self.lmt.columns().iter().enumerate() {
            let lengths = self.lmt.column(index).unwrap_or_default();
            if let Some(row) = lengths.iter().position(|&l| l <= 0.0) {
                return Err(TrialError::LengthNotPositive {
                    unit: unit.clone(),
                    line: row + 4,
                    length: lengths[row],
                });
            }
        }
        for (dof, arms) in &self.moment_arms {
            let file = format!("{dof}{MOMENT_ARMS}");
            if let Some(unit) = arms
                .columns()
                .iter()
                .find(|c| self.lmt.column_index(c).is_none())
            {
                return Err(TrialError::UnknownUnit {
                    file,
                    unit: unit.clone(),
                });
            }
            same_times(&file, arms, &self.lmt)?;
        }
        for (dof, moment) in &self.moments {
            let file = format!("{dof}{MOMENT}");
            if moment.columns() != [dof.as_str()] {
                return Err(TrialError::MomentColumns {
                    file,
                    dof: dof.clone(),
                    found: moment.columns().join(" "),
                });
            }
            same_times(&file, moment, &self.lmt)?;
        }
        if !self.moment_arms.keys().eq(self.moments.keys()) {
            return Err(TrialError::DofsDiffer);
        }
        let (emg, lmt) = (&self.emg, &self.lmt);
        if emg.start() > lmt.start() + TIME_TOLERANCE_S || emg.end() < lmt.end() - TIME_TOLERANCE_S
        {
            return Err(TrialError::EmgDoesNotCover {
                emg_start: emg.start(),
                emg_end: emg.end(),
                start: lmt.start(),
                end: lmt.end(),
            });
        }
        Ok(())
    }
}

/// The names (UTF-8 ones; others are no trial's) of the entries of `dir`, at most
/// [`MAX_TRIAL_ENTRIES`].
fn file_names(dir: &Path) -> Result<Vec<String>, MeasuredError> {
    let io = |e: std::io::Error| MeasuredError::Io {
        path: shown(dir),
        reason: e.to_string(),
        kind: e.kind(),
    };
    let mut names = Vec::new();
    for (count, entry) in std::fs::read_dir(dir).map_err(io)?.enumerate() {
        if count == MAX_TRIAL_ENTRIES {
            return Err(MeasuredError::Trial {
                path: shown(dir),
                error: TrialError::TooManyEntries {
                    max: MAX_TRIAL_ENTRIES,
                },
            });
        }
        if let Ok(name) = entry.map_err(io)?.file_name().into_string() {
            names.push(name);
        }
    }
    Ok(names)
}

/// The degrees of freedom of the file names `names`: those with `<dof>Ma.txt` and
/// `<dof>Torque.txt`, in name order; one without the other is refused.
fn dof_names(names: &[String]) -> Result<Vec<String>, TrialError> {
    let dof_of = |suffix: &str| -> Vec<String> {
        let mut dofs: Vec<String> = names
            .iter()
            .filter_map(|n| n.strip_suffix(suffix))
            .filter(|d| !d.is_empty())
            .map(str::to_string)
            .collect();
        dofs.sort();
        dofs
    };
    let (arms, moments) = (dof_of(MOMENT_ARMS), dof_of(MOMENT));
    let unpaired = |dof: &String, present: &str, missing: &str| TrialError::UnpairedDof {
        dof: dof.clone(),
        present: format!("{dof}{present}"),
        missing: format!("{dof}{missing}"),
    };
    if let Some(dof) = arms.iter().find(|d| !moments.contains(d)) {
        return Err(unpaired(dof, MOMENT_ARMS, MOMENT));
    }
    if let Some(dof) = moments.iter().find(|d| !arms.contains(d)) {
        return Err(unpaired(dof, MOMENT, MOMENT_ARMS));
    }
    Ok(arms)
}

/// `table` (the file `file`) has the times of `lmt`.
fn same_times(file: &str, table: &Table, lmt: &Table) -> Result<(), TrialError> {
    if table.rows() != lmt.rows() {
        return Err(TrialError::RowCount {
            file: file.to_string(),
            rows: table.rows(),
            lmt_rows: lmt.rows(),
        });
    }
    let differs = |(t, l): &(&f64, &f64)| (*t - *l).abs() > TIME_TOLERANCE_S;
    match table
        .times()
        .iter()
        .zip(lmt.times())
        .enumerate()
        .find(|(_, p)| differs(p))
    {
        Some((row, (&time, &lmt_time))) => Err(TrialError::TimesDiffer {
            file: file.to_string(),
            line: row + 4,
            time,
            lmt_time,
        }),
        None => Ok(()),
    }
}

/// The first of `dirs` that names the same folder as an earlier one (the same path, or another
/// path to it: a link, `./x` and `x`), so that a calibration counts no trial twice.
pub fn repeated_folder(dirs: &[std::path::PathBuf]) -> Option<&Path> {
    (dirs.iter().enumerate())
        .find(|(i, d)| {
            dirs[..*i]
                .iter()
                .any(|e| muscle_actuator_core::files::same_file(e, d))
        })
        .map(|(_, d)| d.as_path())
}

/// What is wrong with a trial's folder; file names are those in it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TrialError {
    /// More entries than `MAX_TRIAL_ENTRIES`.
    #[error("more than {max} entries in the folder (a trial's folder holds its tables)")]
    TooManyEntries {
        /// The limit.
        max: usize,
    },
    /// `emg.txt` or `lmt.txt` is missing.
    #[error(
        "no {file} (a trial's folder holds emg.txt, lmt.txt, and per degree of freedom \
         <dof>Ma.txt and <dof>Torque.txt)"
    )]
    MissingFile {
        /// The missing file.
        file: &'static str,
    },
    /// A degree of freedom with one of its two files.
    #[error(
        "{} without {}: a degree of freedom needs both its moment arms and its moment",
        excerpt(.present),
        excerpt(.missing)
    )]
    UnpairedDof {
        /// The degree of freedom.
        dof: String,
        /// The file there.
        present: String,
        /// The file missing.
        missing: String,
    },
    /// A muscle–tendon length that is zero or negative (no muscle has it).
    #[error(
        "lmt.txt: line {line}: unit {:?} has length {length} m; a muscle-tendon length is positive",
        excerpt(.unit)
    )]
    LengthNotPositive {
        /// The unit.
        unit: String,
        /// The line of the row.
        line: usize,
        /// The length, m.
        length: f64,
    },
    /// A moment-arm column that is no unit of `lmt.txt`.
    #[error("{}: column {:?} is not a unit of lmt.txt", excerpt(.file), excerpt(.unit))]
    UnknownUnit {
        /// The moment arms' file.
        file: String,
        /// The column.
        unit: String,
    },
    /// A moment table with other columns than the one named as its degree of freedom.
    #[error(
        "{}: columns {:?}, expected one column named {:?}",
        excerpt(.file),
        excerpt(.found),
        excerpt(.dof)
    )]
    MomentColumns {
        /// The moment's file.
        file: String,
        /// The degree of freedom.
        dof: String,
        /// Its columns, separated by spaces.
        found: String,
    },
    /// The moment arms' and the moments' degrees of freedom differ (only for a trial not read
    /// from a folder, which refuses it per degree of freedom).
    #[error("the moment arms' degrees of freedom are not the moments'")]
    DofsDiffer,
    /// A table with another count of rows than `lmt.txt`.
    #[error("{}: {rows} rows, lmt.txt has {lmt_rows}", excerpt(.file))]
    RowCount {
        /// The file.
        file: String,
        /// Its rows.
        rows: usize,
        /// `lmt.txt`'s.
        lmt_rows: usize,
    },
    /// A table whose times are not `lmt.txt`'s.
    #[error("{}: line {line}: time {time} s, lmt.txt's is {lmt_time} s", excerpt(.file))]
    TimesDiffer {
        /// The file.
        file: String,
        /// The line of the row.
        line: usize,
        /// Its time, s.
        time: f64,
        /// `lmt.txt`'s time of that row, s.
        lmt_time: f64,
    },
    /// The EMG does not span the kinematics.
    #[error(
        "the EMG ({emg_start} s to {emg_end} s) does not cover the kinematics of lmt.txt \
         ({start} s to {end} s): it must start at or before them and end at or after them"
    )]
    EmgDoesNotCover {
        /// The EMG's first time, s.
        emg_start: f64,
        /// The EMG's last time, s.
        emg_end: f64,
        /// `lmt.txt`'s first time, s.
        start: f64,
        /// `lmt.txt`'s last time, s.
        end: f64,
    },
}

#[cfg(test)]
mod tests;
