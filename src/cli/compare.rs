//! `compare`: two recordings' differences, peaks and rise times, as a table or JSON, with an
//! optional overlay plot.

use super::CliError;
use muscle_actuator_recording::runs::compare::{compare_files, PlotFn};
use std::path::PathBuf;

/// What `compare` is asked.
#[derive(clap::Args)]
pub struct Args {
    a: PathBuf,
    b: PathBuf,
    /// Overlay plot of the forces (PNG; an SVG is written beside it).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// Runs `compare`.
pub(super) fn run(a: Args) -> Result<(), CliError> {
    let plot_to = (a.plot.as_deref()).map(|p| (p, crate::figures::compare_plot::plot as PlotFn));
    let c = compare_files(&a.a, &a.b, plot_to)?;
    for w in &c.warnings {
        eprintln!("warning: {w}");
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&c)?);
    } else {
        print!("{}", c.table());
    }
    Ok(())
}
