//! CSV output of a run: one row per tick per muscle.
//!
//! Columns: `time`, `name` (the muscle), the `MuscleState` fields in `.msg` order, then for each
//! joint J of the run `J.position`, `J.velocity`, `J.torque`, `J.external_torque`,
//! `J.stiffness` (the `ActuatorState` per-joint fields), filled on the rows of the muscles that
//! span J and empty on the others. The field lists are those of [`crate::sim::snapshot`].

use crate::sim::scenario::Run;
use crate::sim::snapshot::{JointSnapshot, MuscleSnapshot};
use std::io::Write;
use std::path::Path;

/// The header line's columns for a run with these joints.
pub fn header(joint_names: &[String]) -> Vec<String> {
    let mut cols = vec!["time".to_string(), "name".to_string()];
    cols.extend(MuscleSnapshot::FIELDS.iter().map(|f| f.to_string()));
    for j in joint_names {
        cols.extend(JointSnapshot::FIELDS.iter().map(|f| format!("{j}.{f}")));
    }
    cols
}

/// Writes the run as CSV.
pub fn write_csv(run: &Run, out: &mut impl Write) -> std::io::Result<()> {
    writeln!(out, "{}", header(&run.joint_names).join(","))?;
    let blank = ",".repeat(JointSnapshot::FIELDS.len());
    for rec in run.records() {
        for (i, (m, name)) in rec.muscles.iter().zip(&run.muscle_names).enumerate() {
            write!(out, "{},{}", rec.time, name)?;
            for x in m.values() {
                write!(out, ",{x}")?;
            }
            for (j, joint) in rec.joints.iter().enumerate() {
                if run.muscle_joints.get(i).is_some_and(|js| js.contains(&j)) {
                    for x in joint.values() {
                        write!(out, ",{x}")?;
                    }
                } else {
                    out.write_all(blank.as_bytes())?;
                }
            }
            writeln!(out)?;
        }
    }
    Ok(())
}

/// Writes the run as CSV to the file `path` (`-`: standard output).
pub fn write_csv_to(run: &Run, path: &Path) -> Result<(), String> {
    write_text_to(path, |out| write_csv(run, out))
}

/// Writes a CSV table by `body` to the file `path` (`-`: standard output), buffered; the error
/// names the file. A file is written whole or not at all ([`crate::files::AtomicFile`]).
pub fn write_text_to(
    path: &Path,
    body: impl Fn(&mut std::io::BufWriter<&mut dyn Write>) -> std::io::Result<()>,
) -> Result<(), String> {
    let write = |out: &mut dyn Write| {
        let mut buf = std::io::BufWriter::new(out);
        body(&mut buf)?;
        buf.flush()
    };
    if path.as_os_str() == "-" {
        write(&mut std::io::stdout().lock())
    } else {
        let mut f = crate::files::AtomicFile::create(path)
            .map_err(|e| format!("cannot create {}: {e}", path.display()))?;
        write(f.file()).and_then(|()| f.commit())
    }
    .map_err(|e| format!("cannot write CSV {}: {e}", path.display()))
}
