//! `subject` (docs/emg.md): a CEINMS subject (XML) or the project's TOML written as the
//! project's TOML; and what the subject commands (`subject`, `predict`, `calibrate`) share:
//! their error, a trial prepared, `--dofs` parsed, an output written whole.

use super::SubjectError;
use muscle_actuator_core::files::write_atomically;
use muscle_actuator_core::text::excerpt;
use muscle_actuator_measured::measured::{ExcitationMap, Trial};
use muscle_actuator_measured::subject::{PreparedTrial, SubjectModel};
use std::path::{Path, PathBuf};

/// Shown path: at most 200 characters.
pub(super) fn shown(path: &Path) -> String {
    path.display().to_string().chars().take(200).collect()
}

/// `--dofs a,b,c` as names: none empty, none twice.
pub(super) fn parse_dofs(dofs: &str) -> Result<Vec<String>, SubjectError> {
    let names: Vec<String> = dofs.split(',').map(|d| d.trim().to_string()).collect();
    if names.iter().any(String::is_empty) {
        return Err(SubjectError::Dofs(format!(
            "{:?} has an empty name",
            excerpt(dofs)
        )));
    }
    for (i, n) in names.iter().enumerate() {
        if names[..i].contains(n) {
            return Err(SubjectError::Dofs(format!(
                "{:?} is given twice",
                excerpt(n)
            )));
        }
    }
    Ok(names)
}

/// A trial read and prepared for `dofs` (all the trial's when None).
pub(super) fn prepare(
    subject: &SubjectModel,
    map: &ExcitationMap,
    dir: &Path,
    dofs: Option<&[String]>,
) -> Result<PreparedTrial, SubjectError> {
    let trial = Trial::read(dir)?;
    let dofs: Vec<String> = match dofs {
        Some(d) => d.to_vec(),
        None => trial.dofs().map(str::to_string).collect(),
    };
    let prepared =
        PreparedTrial::new(subject, map, &trial, &dofs).map_err(|error| SubjectError::Drive {
            path: shown(dir),
            error: Box::new(error),
        })?;
    for (dof, units) in &prepared.unused_arms {
        eprintln!(
            "warning: {}: {}Ma.txt has moment arms of units the subject does not count on {}, \
             left out of its moment: {}",
            shown(dir),
            excerpt(dof),
            excerpt(dof),
            excerpt(&units.join(", "))
        );
    }
    Ok(prepared)
}

/// Writes `text` to `path` whole (nothing under the name unless all of it).
pub(super) fn write(path: &Path, text: &str) -> Result<(), SubjectError> {
    write_atomically(path, text.as_bytes()).map_err(|e| SubjectError::Write {
        path: shown(path),
        reason: e.to_string(),
    })
}

/// What `subject` is asked.
#[derive(clap::Args)]
pub struct Args {
    /// The subject file (.xml or .toml).
    file: PathBuf,
    /// The TOML subject file to write.
    #[arg(long)]
    out: PathBuf,
}

/// Runs `subject FILE --out OUT.toml`.
pub(super) fn run(a: Args) -> Result<(), SubjectError> {
    convert(&a.file, &a.out)
}

/// The subject `file` (CEINMS XML or the project's TOML) written to `out` as the project's TOML.
fn convert(file: &Path, out: &Path) -> Result<(), SubjectError> {
    muscle_actuator_core::files::check_not_an_input(out, &[file])?;
    let subject = SubjectModel::read(file)?;
    let text = subject
        .to_toml_string()
        .map_err(|reason| SubjectError::Write {
            path: shown(out),
            reason,
        })?;
    write(out, &text)?;
    eprintln!(
        "{}: {} units, {} degrees of freedom -> {}",
        subject.id,
        subject.units.len(),
        subject.dofs.len(),
        shown(out)
    );
    Ok(())
}
