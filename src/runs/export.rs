//! `export`: a recording's `~/state` samples as the CSV table of `simulate --csv`.
//!
//! The recording is read by [`super::load_run`] (the same strict reader and checks as replay and
//! compare), turned back into the [`Run`] that `simulate` builds — one record per recorded state,
//! at time tick / rate, as `simulate` computes it — and written by [`crate::csv::write_csv`]. For
//! a recording of `simulate --out` the table is therefore `simulate --csv`'s, byte for byte; a
//! node recording gives one row per published state and muscle (every tick, or every tick of
//! `publish_rate_hz`).

use super::{load_run, LoadedRun};
use crate::sim::scenario::{Record, Run};
use std::path::Path;

/// The run a recording holds: its states as records (time = tick / rate), with the muscles,
/// joints and spans of its metadata. Fails on a recording without any state.
pub fn run_of(loaded: &LoadedRun) -> Result<Run, String> {
    let meta = &loaded.meta;
    if loaded.states.is_empty() {
        return Err("the recording holds no actuator state".into());
    }
    let topology = meta.topology();
    let muscle_joints = (0..topology.muscles.len())
        .map(|i| topology.spans(i).iter().map(|s| s.joint).collect())
        .collect();
    let records = loaded
        .states
        .iter()
        .map(|s| Record {
            // As `Simulation::time`, so that the numbers are simulate's to the bit.
            time: s.tick as f64 / meta.rate_hz,
            muscles: s.muscles.iter().map(|m| m.state).collect(),
            joints: s.joints.clone(),
            stiffness_matrix: s.stiffness_matrix.clone(),
        })
        .collect();
    Ok(Run {
        scenario: meta.source.clone(),
        model: meta.model,
        rate_hz: meta.rate_hz,
        muscle_names: meta.muscles.clone(),
        joint_names: meta.joints.clone(),
        muscle_joints,
        records,
    })
}

/// What an export wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportSummary {
    /// Recorded states (one row each per muscle).
    pub states: usize,
    pub muscles: usize,
}

/// Writes the states of the recording `input` as CSV to `csv` (`-`: standard output).
pub fn export_csv(input: &Path, csv: &Path) -> Result<ExportSummary, String> {
    crate::files::check_not_an_input(csv, &[input])?;
    let loaded = load_run(input)?;
    // A recording cut by a crash is read up to the cut, and said so once (as replay does).
    if let Some(w) = &loaded.warning {
        eprintln!("warning: {w}");
    }
    let run = run_of(&loaded).map_err(|e| format!("{}: {e}", input.display()))?;
    crate::csv::write_csv_to(&run, csv)?;
    Ok(ExportSummary {
        states: run.records.len(),
        muscles: run.muscle_names.len(),
    })
}
