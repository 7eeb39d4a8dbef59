//! `calibrate` (docs/emg.md "Calibration"): a subject's parameters fitted by CMA-ES on
//! trials so that the predicted moments of the degrees of freedom match the measured ones; the
//! calibrated subject written as TOML.

use super::common::{default_model, model_help, parse_model};
use super::subject::{parse_dofs, prepare, shown, write};
use super::CliError;
use super::SubjectError;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::simulation::default_stepping;
use muscle_actuator_measured::measured::ExcitationMap;
use muscle_actuator_measured::subject::calibrate::{Problem, Settings};
use muscle_actuator_measured::subject::SubjectModel;
use std::path::{Path, PathBuf};

/// What `calibrate` is asked.
#[derive(clap::Args)]
pub struct Args {
    /// The subject file (CEINMS XML or the project's TOML).
    #[arg(long)]
    subject: PathBuf,
    /// The EMG-to-unit map (CEINMS's excitation generator XML).
    #[arg(long)]
    excitations: PathBuf,
    /// The trials' folders.
    #[arg(long, num_args = 1.., required = true)]
    trials: Vec<PathBuf>,
    /// The degrees of freedom whose moments are matched, comma-separated (R_knee_fe,...).
    #[arg(long)]
    dofs: String,
    #[arg(long, default_value = default_model(), help = model_help())]
    model: String,
    /// The calibrated subject's TOML file.
    #[arg(long)]
    out: PathBuf,
    /// The optimiser's seed (the same seed, the same result).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Most objective evaluations.
    #[arg(long, default_value_t = DEFAULT_EVALUATIONS)]
    evaluations: usize,
    /// Threads the candidates are evaluated on (default: every core).
    #[arg(long)]
    threads: Option<usize>,
}

/// `calibrate --evaluations` by default.
const DEFAULT_EVALUATIONS: usize = 1000;

/// Runs `calibrate`, with a progress bar.
pub(super) fn run(a: Args) -> Result<(), CliError> {
    let dofs = parse_dofs(&a.dofs)?;
    Ok(calibrate(&Request {
        subject: &a.subject,
        excitations: &a.excitations,
        trials: &a.trials,
        dofs: &dofs,
        model: parse_model(&a.model)?,
        out: &a.out,
        settings: Settings {
            seed: a.seed,
            max_evaluations: a.evaluations,
            threads: a.threads.unwrap_or_else(rayon::current_num_threads),
            ..Default::default()
        },
        progress: true,
    })?)
}

/// A calibration as asked, its options parsed.
struct Request<'a> {
    /// The subject file.
    subject: &'a Path,
    /// The excitation map.
    excitations: &'a Path,
    /// The trials' folders.
    trials: &'a [PathBuf],
    /// The degrees of freedom.
    dofs: &'a [String],
    /// The model.
    model: ModelKind,
    /// The calibrated subject's file.
    out: &'a Path,
    /// The optimiser's settings.
    settings: Settings,
    /// Whether to draw a progress bar.
    progress: bool,
}

/// Most evaluations `--evaluations` may ask.
const MAX_EVALUATIONS: usize = 1_000_000;

/// `calibrate`: the subject's parameters fitted; the calibrated subject written to `out`.
fn calibrate(a: &Request) -> Result<(), SubjectError> {
    if a.trials.is_empty() {
        return Err(SubjectError::Setting(
            "--trials: give at least one trial folder".into(),
        ));
    }
    let s = &a.settings;
    if s.max_evaluations == 0 || s.max_evaluations > MAX_EVALUATIONS {
        return Err(SubjectError::Setting(format!(
            "--evaluations must be 1 to {MAX_EVALUATIONS}, not {}",
            s.max_evaluations
        )));
    }
    if s.threads == 0 || s.threads > 256 {
        return Err(SubjectError::Setting(format!(
            "--threads must be 1 to 256, not {}",
            s.threads
        )));
    }
    muscle_actuator_core::files::check_not_an_input(a.out, &[a.subject, a.excitations])?;
    let subject = SubjectModel::read(a.subject)?;
    let map = ExcitationMap::read(a.excitations)?;
    let trials = a
        .trials
        .iter()
        .map(|dir| prepare(&subject, &map, dir, Some(a.dofs)))
        .collect::<Result<Vec<_>, _>>()?;
    let stepping = default_stepping(a.model);
    let problem = Problem::new(&subject, &map, trials, a.model, stepping).map_err(|error| {
        SubjectError::Drive {
            path: shown(a.subject),
            error: Box::new(error),
        }
    })?;
    let bar = if a.progress {
        let bar = indicatif::ProgressBar::new(s.max_evaluations as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{elapsed_precise} [{bar:30}] {pos}/{len} evaluations, best {msg}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar
    } else {
        indicatif::ProgressBar::hidden()
    };
    let outcome = problem.calibrate(s, |evaluations, best| {
        bar.set_position(evaluations as u64);
        bar.set_message(format!("{best:.4}"));
        std::ops::ControlFlow::Continue(())
    })?;
    bar.finish_and_clear();
    let calibrated = problem.calibrated(&subject, &outcome, s);
    let text = calibrated
        .to_toml_string()
        .map_err(|reason| SubjectError::Write {
            path: shown(a.out),
            reason,
        })?;
    write(a.out, &text)?;
    eprintln!(
        "calibrated {} parameters of {} units on {} trials ({}): mean 1 - R2 {:.4} from {:.4}, {} evaluations -> {}",
        problem.parameters.len(),
        problem.units.len(),
        problem.trials.len(),
        a.dofs.join(", "),
        outcome.cost,
        outcome.start_cost,
        outcome.evaluations,
        shown(a.out)
    );
    Ok(())
}
