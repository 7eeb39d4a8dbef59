//! `export`: a recording's states as the CSV of `simulate --csv`.

use super::CliError;
use std::path::PathBuf;

/// What `export` is asked.
#[derive(clap::Args)]
pub struct Args {
    /// The recording (.mcap).
    input: PathBuf,
    /// CSV output file ('-' for standard output).
    #[arg(long)]
    csv: PathBuf,
}

/// Runs `export`.
pub(super) fn run(a: Args) -> Result<(), CliError> {
    let s = muscle_actuator_recording::runs::export::export_csv(&a.input, &a.csv)?;
    eprintln!(
        "exported {} states of {} muscles from {}",
        s.states,
        s.muscles,
        a.input.display()
    );
    Ok(())
}
