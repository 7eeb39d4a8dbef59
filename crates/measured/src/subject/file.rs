//! A subject as the project's own TOML file (docs/emg.md "Subject files"), which a user may
//! keep editing, and reading a subject from either that or CEINMS's XML.
//!
//! ```toml
//! [subject]
//! id = "testSubject00"
//!
//! [calibration]          # only in a calibrated subject: what it was calibrated on, and how
//! trials = ["_FastWalking_", …]
//! dofs = ["R_knee_fe"]
//! model = "hill"
//! optimiser = "CMA-ES (cmaes 0.2.2)"
//! seed = 1
//! …
//!
//! [bounds]              # a calibration's bounds, each optional (docs/emg.md)
//! strength = [0.5, 2.5]
//!
//! [[dof]]
//! name = "R_knee_fe"
//! units = ["bicfemlh_r", …]
//!
//! [tabulated]            # curves every tabulated muscle without its own uses
//! active_force_length = [[0.4, 0.0], …]
//! …
//!
//! [[muscle]]             # one per unit: `name`, then the keys of a configuration's muscle
//! name = "bicfemlh_r"
//! f_max = 896.0
//! …
//! ```

use crate::measured::Subject;
use crate::subject::bounds::Bounds;
pub(crate) use crate::subject::calibration_record::CalibrationRecord;
use crate::subject::units::{SubjectModel, UnitModel};
use muscle_actuator_core::files::{read_regular_file, MAX_FILE_BYTES};
use muscle_actuator_core::physics::{MuscleParams, TabulatedCurves};
use muscle_actuator_core::text::{excerpt, one_line, toml_error};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A subject file that cannot be read or is not one.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "{}{path}: {reason}",
    if .kind.is_some() { "cannot read subject file " } else { "" }
)]
pub struct SubjectFileError {
    /// The file (at most 200 characters).
    pub path: String,
    /// What is wrong, on one line.
    pub reason: String,
    /// The I/O error's kind when the file could not be read (`NotFound` for a missing file).
    pub kind: Option<std::io::ErrorKind>,
}

impl SubjectFileError {
    /// Whether the file does not exist.
    pub fn is_not_found(&self) -> bool {
        self.kind == Some(std::io::ErrorKind::NotFound)
    }
}

/// The `[subject]` table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Header {
    id: String,
}

/// A `[[dof]]` table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct DofEntry {
    name: String,
    units: Vec<String>,
}

/// A `[[muscle]]` table, for writing.
#[derive(Serialize)]
struct MuscleEntry<'a> {
    name: &'a str,
    #[serde(flatten)]
    params: &'a MuscleParams,
}

/// The file, for writing.
#[derive(Serialize)]
struct FileOut<'a> {
    subject: Header,
    #[serde(skip_serializing_if = "Option::is_none")]
    calibration: Option<&'a CalibrationRecord>,
    bounds: &'a Bounds,
    dof: Vec<DofEntry>,
    #[serde(skip_serializing_if = "Option::is_none")]
    tabulated: Option<&'a TabulatedCurves>,
    muscle: Vec<MuscleEntry<'a>>,
}

impl SubjectModel {
    /// Reads a subject: CEINMS's XML (a file whose first non-blank character is `<`) or the
    /// project's TOML; checked (each muscle's parameters by the configuration's rules). An empty
    /// file is neither.
    pub fn read(path: &Path) -> Result<SubjectModel, SubjectFileError> {
        let shown: String = path.display().to_string().chars().take(200).collect();
        let fail = |reason: String| SubjectFileError {
            path: shown.clone(),
            reason: one_line(&reason),
            kind: None,
        };
        let bytes = read_regular_file(path, MAX_FILE_BYTES).map_err(|e| SubjectFileError {
            kind: Some(e.kind()),
            ..fail(e.to_string())
        })?;
        let text = String::from_utf8(bytes).map_err(|e| fail(format!("not UTF-8 text: {e}")))?;
        if text.trim().is_empty() {
            return Err(fail(
                "the file is empty: a subject is CEINMS's XML or the project's TOML".into(),
            ));
        }
        if text.trim_start().starts_with('<') {
            let subject = Subject::parse(&text).map_err(|e| fail(e.to_string()))?;
            SubjectModel::of_ceinms(&subject).map_err(|e| fail(e.to_string()))
        } else {
            SubjectModel::from_toml_str(&text).map_err(fail)
        }
    }

    /// Parses and checks the project's TOML form.
    pub fn from_toml_str(text: &str) -> Result<SubjectModel, String> {
        let mut raw: toml::Table = toml::from_str(text).map_err(|e| toml_error(&e, text))?;
        if let Some(k) = raw.keys().find(|k| {
            ![
                "subject",
                "calibration",
                "bounds",
                "dof",
                "tabulated",
                "muscle",
            ]
            .contains(&k.as_str())
        }) {
            return Err(format!(
                "unknown key {:?} (expected subject, calibration, bounds, dof, tabulated, muscle)",
                excerpt(k)
            ));
        }
        let header: Header =
            take(&mut raw, "subject")?.ok_or("no [subject] table: not a subject file")?;
        let calibration: Option<CalibrationRecord> = take(&mut raw, "calibration")?;
        let bounds: Bounds = take(&mut raw, "bounds")?.unwrap_or_default();
        let dofs: Vec<DofEntry> = take(&mut raw, "dof")?.unwrap_or_default();
        let shared: Option<TabulatedCurves> = take(&mut raw, "tabulated")?;
        let tables = match raw.remove("muscle") {
            Some(toml::Value::Array(a)) => a,
            Some(_) => return Err("muscle must be an array of tables ([[muscle]])".into()),
            None => return Err("no [[muscle]] table: a subject needs at least one unit".into()),
        };
        let mut units = Vec::with_capacity(tables.len());
        for (i, v) in tables.into_iter().enumerate() {
            let toml::Value::Table(mut t) = v else {
                return Err(format!("muscle[{i}] must be a table"));
            };
            let name = match t.remove("name") {
                Some(toml::Value::String(s)) if !s.trim().is_empty() => s,
                _ => return Err(format!("muscle[{i}] needs a name (a non-empty string)")),
            };
            if units.iter().any(|u: &UnitModel| u.name == name) {
                return Err(format!("muscle {:?} is given twice", excerpt(&name)));
            }
            let mut params = MuscleParams::deserialize(toml::Value::Table(t))
                .map_err(|e| format!("muscle {:?}: {}", excerpt(&name), e.to_string().trim()))?;
            if params.tabulated.is_none() {
                params.tabulated.clone_from(&shared);
            }
            units.push(UnitModel { name, params });
        }
        let mut out = Vec::with_capacity(dofs.len());
        for d in dofs {
            if d.units.is_empty() {
                return Err(format!("dof {:?} names no unit", excerpt(&d.name)));
            }
            if let Some(u) = d
                .units
                .iter()
                .find(|u| !units.iter().any(|m| &m.name == *u))
            {
                return Err(format!(
                    "dof {:?} names unit {:?}, which no [[muscle]] describes",
                    excerpt(&d.name),
                    excerpt(u)
                ));
            }
            out.push((d.name, d.units));
        }
        let model = SubjectModel {
            id: header.id,
            units,
            dofs: out,
            calibration,
            bounds,
        };
        model.check()?;
        Ok(model)
    }

    /// The project's TOML form: the curves every unit shares written once under `[tabulated]`.
    pub fn to_toml_string(&self) -> Result<String, String> {
        let first = self.units.first().and_then(|u| u.params.tabulated.as_ref());
        let shared = first.filter(|t| {
            self.units
                .iter()
                .all(|u| u.params.tabulated.as_ref() == Some(*t))
        });
        let stripped: Vec<MuscleParams> = self
            .units
            .iter()
            .map(|u| {
                let mut p = u.params.clone();
                if shared.is_some() {
                    p.tabulated = None;
                }
                p
            })
            .collect();
        let out = FileOut {
            subject: Header {
                id: self.id.clone(),
            },
            calibration: self.calibration.as_ref(),
            bounds: &self.bounds,
            dof: self
                .dofs
                .iter()
                .map(|(name, units)| DofEntry {
                    name: name.clone(),
                    units: units.clone(),
                })
                .collect(),
            tabulated: shared,
            muscle: self
                .units
                .iter()
                .zip(&stripped)
                .map(|(u, params)| MuscleEntry {
                    name: &u.name,
                    params,
                })
                .collect(),
        };
        let body = toml::to_string(&out).map_err(|e| format!("cannot write the subject: {e}"))?;
        Ok(format!(
            "# A subject's muscle–tendon units for muscle_actuator (docs/emg.md \"Subject files\").\n\
             # Each [[muscle]] takes the keys of a configuration's muscle (docs/configuration.md).\n\n{body}"
        ))
    }
}

/// The table `key` of `raw`, deserialised; None when absent.
fn take<T: serde::de::DeserializeOwned>(
    raw: &mut toml::Table,
    key: &str,
) -> Result<Option<T>, String> {
    raw.remove(key)
        .map(|v| T::deserialize(v).map_err(|e| format!("{key}: {}", e.to_string().trim())))
        .transpose()
}
