//! CSV output of a run: one row per tick per muscle.
//!
//! Columns: `time`, `name` (the muscle), the `MuscleState` fields in `.msg` order, then for each
//! joint J of the run `J.position`, `J.velocity`, `J.torque`, `J.external_torque`,
//! `J.stiffness` (the `ActuatorState` per-joint fields), filled on the rows of the muscles that
//! span J and empty on the others. The field lists are those of [`crate::sim::MuscleSnapshot`]
//! and [`crate::sim::JointSnapshot`].
//!
//! Every CSV the project writes goes through the `csv` crate ([`writer`]): a name with a comma,
//! a quote or a line break is quoted (RFC 4180), every other field is written as it is, so an
//! ordinary table is the plain comma-joined text. The numbers are formatted here (Rust's
//! shortest round-trip form) and handed to it as text.

use crate::sim::records::Run;
use crate::sim::snapshot::{JointSnapshot, MuscleSnapshot};
use std::fmt::Write as _;
use std::io::Write;
use std::path::Path;

/// Why a text is not one CSV record ([`split_record`]).
#[derive(Debug, thiserror::Error)]
pub enum SplitError {
    /// The text does not read as CSV.
    #[error(transparent)]
    Csv(#[from] ::csv::Error),
    /// The text holds more than one record.
    #[error("more than one line")]
    MoreThanOneLine,
}

/// Why a CSV file cannot be written ([`write_text_to`]).
#[derive(Debug, thiserror::Error)]
pub enum CsvWriteError {
    /// The file cannot be created (its directory missing or unwritable, a directory there).
    #[error("cannot create {}: {source}", .path.display())]
    Create {
        /// The path.
        path: std::path::PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The table cannot be written or the file put in place.
    #[error("cannot write CSV {}: {source}", .path.display())]
    Write {
        /// The path.
        path: std::path::PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

impl CsvWriteError {
    /// The kind of the I/O error.
    pub fn io_kind(&self) -> std::io::ErrorKind {
        match self {
            CsvWriteError::Create { source, .. } | CsvWriteError::Write { source, .. } => {
                source.kind()
            }
        }
    }

    /// Whether the path does not exist (its directory missing).
    pub fn is_not_found(&self) -> bool {
        self.io_kind() == std::io::ErrorKind::NotFound
    }
}

/// The header line's columns for a run with these joints.
pub(crate) fn header(joint_names: &[String]) -> Vec<String> {
    let mut cols = vec!["time".to_string(), "name".to_string()];
    cols.extend(MuscleSnapshot::FIELDS.iter().map(|f| f.to_string()));
    for j in joint_names {
        cols.extend(JointSnapshot::FIELDS.iter().map(|f| format!("{j}.{f}")));
    }
    cols
}

/// A CSV writer on `out`: comma-separated, `\n`-terminated, fields quoted only when they must
/// be (a delimiter, a quote or a line break in them).
pub fn writer<W: Write>(out: W) -> ::csv::Writer<W> {
    ::csv::WriterBuilder::new()
        .terminator(::csv::Terminator::Any(b'\n'))
        .quote_style(::csv::QuoteStyle::Necessary)
        .from_writer(out)
}

/// Writes `x` as a CSV field in Rust's shortest round-trip form (`{x}`), through `buf`.
pub(crate) fn write_number<W: Write>(
    w: &mut ::csv::Writer<W>,
    buf: &mut String,
    x: f64,
) -> ::csv::Result<()> {
    buf.clear();
    let _ = write!(buf, "{x}");
    w.write_field(buf.as_bytes())
}

/// Writes the run as CSV.
pub fn write_csv(run: &Run, out: &mut impl Write) -> std::io::Result<()> {
    let mut w = writer(out);
    w.write_record(header(&run.joint_names))?;
    let mut buf = String::new();
    for rec in run.records() {
        for (i, (m, name)) in rec.muscles.iter().zip(&run.muscle_names).enumerate() {
            write_number(&mut w, &mut buf, rec.time)?;
            w.write_field(name)?;
            for x in m.values() {
                write_number(&mut w, &mut buf, x)?;
            }
            for (j, joint) in rec.joints.iter().enumerate() {
                let spans = run.muscle_joints.get(i).is_some_and(|js| js.contains(&j));
                for x in joint.values() {
                    if spans {
                        write_number(&mut w, &mut buf, x)?;
                    } else {
                        w.write_field("")?;
                    }
                }
            }
            w.write_record(None::<&[u8]>)?;
        }
    }
    w.flush()
}

/// `fields` as one CSV record without its line end (`""` for none): a list of names kept in one
/// text value (a recording's `muscles` and `joints`), read back by [`split_record`].
pub fn join_record(fields: &[String]) -> String {
    if fields.is_empty() {
        return String::new();
    }
    let mut w = writer(Vec::new());
    // Writing to memory cannot fail.
    let _ = w.write_record(fields);
    let mut bytes = w.into_inner().unwrap_or_default();
    bytes.pop(); // the line end
    String::from_utf8(bytes).unwrap_or_default()
}

/// The fields of one CSV record ([`join_record`]'s text); none for an empty text.
pub fn split_record(text: &str) -> Result<Vec<String>, SplitError> {
    let mut r = ::csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(text.as_bytes());
    let mut records = r.records();
    let fields = match records.next() {
        None => Vec::new(),
        Some(rec) => rec?.iter().map(String::from).collect(),
    };
    match records.next() {
        None => Ok(fields),
        Some(_) => Err(SplitError::MoreThanOneLine),
    }
}

/// Writes the run as CSV to the file `path` (`-`: standard output).
pub fn write_csv_to(run: &Run, path: &Path) -> Result<(), CsvWriteError> {
    write_text_to(path, |out| write_csv(run, out))
}

/// Writes a CSV table by `body` to the file `path` (`-`: standard output), buffered; the error
/// names the file. A file is written whole or not at all ([`crate::files::AtomicFile`]).
pub fn write_text_to(
    path: &Path,
    body: impl Fn(&mut std::io::BufWriter<&mut dyn Write>) -> std::io::Result<()>,
) -> Result<(), CsvWriteError> {
    let write = |out: &mut dyn Write| {
        let mut buf = std::io::BufWriter::new(out);
        body(&mut buf)?;
        buf.flush()
    };
    if path.as_os_str() == "-" {
        write(&mut std::io::stdout().lock())
    } else {
        let mut f =
            crate::files::AtomicFile::create(path).map_err(|source| CsvWriteError::Create {
                path: path.to_path_buf(),
                source,
            })?;
        write(f.file()).and_then(|()| f.commit())
    }
    .map_err(|source| CsvWriteError::Write {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file in a missing directory cannot be created, and says it is not found.
    #[test]
    fn a_missing_directory_is_not_found() {
        let path = Path::new("/nonexistent/dir/out.csv");
        let e = write_text_to(path, |_| Ok(())).unwrap_err();
        assert!(
            matches!(e, CsvWriteError::Create { .. }) && e.is_not_found(),
            "{e}"
        );
        assert!(e
            .to_string()
            .starts_with("cannot create /nonexistent/dir/out.csv: "));
    }

    /// One record splits into its fields; two lines are refused.
    #[test]
    fn one_record_splits() {
        let fields = vec!["a".to_string(), "b,c".to_string()];
        assert_eq!(split_record(&join_record(&fields)).unwrap(), fields);
        assert!(matches!(
            split_record("a\nb"),
            Err(SplitError::MoreThanOneLine)
        ));
    }
}
