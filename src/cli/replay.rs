//! `replay`: a recording's inputs through a model again (the recorded one unless named), tick
//! by tick, recorded; with the recorded model every state is compared with the recorded one.

use super::common::parse_model;
use super::CliError;
use std::path::PathBuf;

/// What `replay` is asked.
#[derive(clap::Args)]
pub struct Args {
    /// The recording (.mcap).
    input: PathBuf,
    /// Contractile model (default: the recorded one).
    #[arg(long)]
    model: Option<String>,
    /// Output recording (.mcap).
    #[arg(long)]
    out: PathBuf,
}

/// Runs `replay`; fails when a recorded state is not reproduced bit for bit.
pub(super) fn run(a: Args) -> Result<(), CliError> {
    let model = a.model.as_deref().map(parse_model).transpose()?;
    let s = muscle_actuator_recording::runs::replay(&a.input, model, &a.out)?;
    if let Some(w) = &s.warning {
        eprintln!("warning: {w}");
    }
    if s.compared > 0 {
        eprintln!(
            "replayed {} ticks with {}: {} of {} recorded states reproduced bit for bit{}",
            s.ticks,
            s.model,
            s.identical,
            s.compared,
            s.first_difference
                .map(|t| format!(" (first difference at tick {t})"))
                .unwrap_or_default()
        );
    } else {
        eprintln!(
            "replayed {} ticks with {} into {}",
            s.ticks,
            s.model,
            a.out.display()
        );
    }
    if s.identical < s.compared {
        return Err(CliError::ReplayDiffers);
    }
    Ok(())
}
