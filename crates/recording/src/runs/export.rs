//! `export`: a recording's `~/state` samples as the CSV table of `simulate --csv`.
//!
//! The recording is read by [`super::load_run`] (the same strict reader and checks as replay and
//! compare), turned back into the [`Run`] that `simulate` builds — one record per recorded state,
//! at time tick / rate, as `simulate` computes it — and written by [`muscle_actuator_core::csv::write_csv`]. For
//! a recording of `simulate --out` the table is therefore `simulate --csv`'s, byte for byte; a
//! node recording gives one row per published state and muscle (every tick, or every tick of
//! `publish_rate_hz`).

use super::error::{ExportError, RunError};
use super::{load_run, LoadedRun};
use muscle_actuator_core::sim::Run;
use std::path::Path;

/// The run a recording holds: its states as records (time = tick / rate), with the muscles,
/// joints and spans of its metadata. Fails on a recording without any state.
pub fn run_of(loaded: &LoadedRun) -> Result<Run, ExportError> {
    let meta = &loaded.meta;
    if loaded.states.is_empty() {
        return Err(ExportError::NoStates);
    }
    let topology = meta.topology();
    let muscle_joints = (0..topology.muscles.len())
        .map(|i| topology.spans(i).iter().map(|s| s.joint).collect())
        .collect();
    let mut run = Run::new(
        meta.source.clone(),
        meta.model,
        meta.rate_hz,
        meta.muscles.clone(),
        meta.joints.clone(),
        muscle_joints,
        loaded.states.len(),
    );
    let mut muscles = Vec::with_capacity(meta.muscles.len());
    for s in &loaded.states {
        muscles.clear();
        muscles.extend(s.muscles.iter().map(|m| m.state));
        // As `Simulation::time`, so that the numbers are simulate's to the bit.
        let time = s.tick as f64 / meta.rate_hz;
        run.push_parts(time, &muscles, &s.joints, &s.stiffness_matrix)
            .map_err(|reason| ExportError::Record {
                tick: s.tick,
                reason,
            })?;
    }
    Ok(run)
}

/// What an export wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportSummary {
    /// Recorded states (one row each per muscle).
    pub states: usize,
    /// Muscles in each state.
    pub muscles: usize,
}

/// Writes the states of the recording `input` as CSV to `csv` (`-`: standard output).
pub fn export_csv(input: &Path, csv: &Path) -> Result<ExportSummary, RunError> {
    muscle_actuator_core::files::check_not_an_input(csv, &[input])?;
    let loaded = load_run(input)?;
    // A recording cut by a crash is read up to the cut, and said so once (as replay does).
    if let Some(w) = &loaded.warning {
        eprintln!("warning: {w}");
    }
    let run = run_of(&loaded).map_err(|source| RunError::Export {
        path: input.to_path_buf(),
        source,
    })?;
    muscle_actuator_core::csv::write_csv_to(&run, csv)?;
    Ok(ExportSummary {
        states: run.len(),
        muscles: run.muscle_names.len(),
    })
}
