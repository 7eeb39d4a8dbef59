//! Measured data of people, as the CEINMS toolbox lays it out (Pizzolato et al. 2015, J Biomech
//! 48(14): 3929-3936; the toolbox's test data, data/ceinms/README.md): typed readers, every
//! value checked, nothing simulated.
//!
//! - `table`: a tab-separated table (`emg.txt`, `lmt.txt`, `<dof>Ma.txt`, `<dof>Torque.txt`):
//!   column names, times (s), values.
//! - `trial`: a trial's folder: its EMG, muscle–tendon lengths, and per degree of freedom the
//!   moment arms and the inverse-dynamics moment, cross-checked.
//! - `ceinms_subject`: CEINMS's subject file: per muscle–tendon unit its parameters, the shared
//!   curves (`curve`), the degrees of freedom and the units that span each.
//! - `excitation_map`: how the recorded EMG channels drive the units (CEINMS's
//!   `emgGenerator` file), and the units' excitations from a channel table.
//! - [`rating`]: how well a predicted series matches a measured one: the coefficient of
//!   determination R², Pearson's r², the RMSE and the RMSE over the measured peak.
//! - [`resample`]: a table's column, or any series, at other times (linear, no extrapolation),
//!   a series' time derivative, and for a trial its moments at the kinematics' times and a
//!   unit's length and lengthening rate at any time within them.
//!
//! Every reader takes a path (a regular file of bounded size, [`muscle_actuator_core::files`]) or text, and
//! fails with a [`MeasuredError`] that names the file, then the line (and column or element)
//! and what is wrong, on one line.

pub(crate) mod ceinms_subject;
pub(crate) mod curve;
pub(crate) mod excitation_map;
pub mod rating;
pub mod resample;
pub(crate) mod table;
pub(crate) mod trial;
mod xml;

pub use ceinms_subject::{
    Calibration, Dof, Subject, SubjectCurves, SubjectError, Unit, UnitDefaults,
};
pub use curve::{Curve, CurveError};
pub use excitation_map::{
    EntryError, Excitation, ExcitationMap, ExcitationMapError, UnitExcitation,
};
pub use table::{Table, TableError};
pub use trial::{repeated_folder, Trial, TrialError};
pub use xml::XmlError;

use muscle_actuator_core::text::one_line;
use std::path::Path;

/// Longest path quoted in a message, characters.
const MAX_PATH_CHARS: usize = 200;

/// A file of measured data that cannot be read, or that does not hold what it should. Each
/// message names the file, then what is wrong, on one line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeasuredError {
    /// The file or folder could not be read: missing, not a regular file, larger than its
    /// kind may be (`table::MAX_TABLE_BYTES`, 1 MiB for XML), unreadable.
    #[error("cannot read {path}: {reason}")]
    Io {
        /// The path, as given (at most 200 characters).
        path: String,
        /// Why.
        reason: String,
        /// The I/O error's kind (`NotFound` for a missing file).
        kind: std::io::ErrorKind,
    },
    /// A table file is not a valid table.
    #[error("{path}: {}", one_line(&.error.to_string()))]
    Table {
        /// The file.
        path: String,
        /// What is wrong.
        error: TableError,
    },
    /// A trial's folder lacks a file, or its tables do not agree.
    #[error("{path}: {}", one_line(&.error.to_string()))]
    Trial {
        /// The folder.
        path: String,
        /// What is wrong.
        error: TrialError,
    },
    /// A subject file is not a valid CEINMS subject.
    #[error("{path}: {}", one_line(&.error.to_string()))]
    Subject {
        /// The file.
        path: String,
        /// What is wrong.
        error: SubjectError,
    },
    /// An excitation-map file is not a valid CEINMS `emgGenerator`.
    #[error("{path}: {}", one_line(&.error.to_string()))]
    ExcitationMap {
        /// The file.
        path: String,
        /// What is wrong.
        error: ExcitationMapError,
    },
}

impl MeasuredError {
    /// Whether the file or folder does not exist.
    pub fn is_not_found(&self) -> bool {
        matches!(self, MeasuredError::Io { kind, .. } if *kind == std::io::ErrorKind::NotFound)
    }
}

/// `path` as messages quote it: at most [`MAX_PATH_CHARS`] characters.
pub(crate) fn shown(path: &Path) -> String {
    muscle_actuator_core::text::one_line(&path.display().to_string())
        .chars()
        .take(MAX_PATH_CHARS)
        .collect()
}

/// The bytes of `path`, a regular file of at most `max_bytes` bytes.
pub(crate) fn read_bytes(path: &Path, max_bytes: u64) -> Result<Vec<u8>, MeasuredError> {
    muscle_actuator_core::files::read_regular_file(path, max_bytes).map_err(|e| MeasuredError::Io {
        path: shown(path),
        reason: e.to_string(),
        kind: e.kind(),
    })
}

/// `bytes` as text, or the line (from 1) of the first byte that is not UTF-8.
pub(crate) fn utf8_text(bytes: Vec<u8>) -> Result<String, usize> {
    String::from_utf8(bytes).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        valid.iter().filter(|&&b| b == b'\n').count() + 1
    })
}
