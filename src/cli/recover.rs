//! `recover`: a recording cut by a crash (no summary) rewritten as a complete, indexed MCAP
//! file holding everything readable in it.

use super::CliError;
use std::path::PathBuf;

/// What `recover` is asked.
#[derive(clap::Args)]
pub struct Args {
    /// The damaged recording (.mcap).
    input: PathBuf,
    /// The recovered recording (.mcap; not the input).
    output: PathBuf,
}

/// Runs `recover`; a recording read only in part is a warning, not a failure.
pub(super) fn run(a: Args) -> Result<(), CliError> {
    let r = muscle_actuator_recording::recording::recover::recover(&a.input, &a.output)?;
    if let Some(w) = &r.stopped_early {
        eprintln!(
            "warning: {} is truncated (no summary); reading stopped: {}",
            a.input.display(),
            muscle_actuator_core::text::excerpt(w)
        );
    }
    eprintln!("{}", r.line(&a.input, &a.output));
    Ok(())
}
