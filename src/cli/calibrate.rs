//! `calibrate` (docs/emg.md "Calibration"): a subject's parameters fitted by CMA-ES on
//! trials so that the predicted moments of the degrees of freedom match the measured ones; the
//! calibrated subject written as TOML.

use super::common::{default_model, model_help, parse_model};
use super::subject::{parse_dofs, prepare, shown};
use super::CliError;
use super::SubjectError;
use muscle_actuator_core::files::AtomicFile;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::default_stepping;
use muscle_actuator_measured::measured::{repeated_folder, ExcitationMap};
use muscle_actuator_measured::subject::calibrate::{
    CalibrateError, Problem, Settings, MAX_EVALUATIONS, MIN_EVALUATIONS,
};
use muscle_actuator_measured::subject::SubjectModel;
use std::io::{IsTerminal, Write};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

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
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    seed: u64,
    /// Most objective evaluations.
    #[arg(long, default_value_t = DEFAULT_EVALUATIONS, allow_negative_numbers = true)]
    evaluations: usize,
    /// Threads the candidates are evaluated on (default: every core).
    #[arg(long, allow_negative_numbers = true)]
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

/// `calibrate`: the subject's parameters fitted; the calibrated subject written to `out`.
fn calibrate(a: &Request) -> Result<(), SubjectError> {
    if a.trials.is_empty() {
        return Err(SubjectError::Setting(
            "--trials: give at least one trial folder".into(),
        ));
    }
    if let Some(again) = repeated_folder(a.trials) {
        return Err(SubjectError::Setting(format!(
            "--trials: {} is given twice; each trial counts once",
            shown(again)
        )));
    }
    let s = &a.settings;
    if !(MIN_EVALUATIONS..=MAX_EVALUATIONS).contains(&s.max_evaluations) {
        return Err(SubjectError::Setting(format!(
            "--evaluations must be {MIN_EVALUATIONS} to {MAX_EVALUATIONS}, not {}",
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
    let mut file = AtomicFile::create(a.out).map_err(|e| SubjectError::Write {
        path: shown(a.out),
        reason: e.to_string(),
    })?;
    let outcome = {
        let stop = StopOnInterrupt::install().map_err(|e| SubjectError::Write {
            path: "the Ctrl-C handler".into(),
            reason: e.to_string(),
        })?;
        let mut progress = Progress::new(a.progress, s.max_evaluations);
        progress.start(&problem);
        let r = problem.calibrate(s, |evaluations, best| {
            progress.show(evaluations, best);
            if stop.asked() {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        });
        progress.finish();
        r
    };
    let (outcome, stopped) = match outcome {
        Ok(o) => (o, None),
        Err(CalibrateError::Stopped {
            evaluations,
            of,
            best,
        }) => (*best, Some((evaluations, of))),
        Err(e) => return Err(e.into()),
    };
    let calibrated = problem.calibrated(&subject, &outcome, s);
    let text = calibrated
        .to_toml_string()
        .map_err(|reason| SubjectError::Write {
            path: shown(a.out),
            reason,
        })?;
    let written = file
        .file()
        .write_all(text.as_bytes())
        .and_then(|()| file.commit());
    written.map_err(|e| SubjectError::Write {
        path: shown(a.out),
        reason: e.to_string(),
    })?;
    if let Some((evaluations, of)) = stopped {
        return Err(SubjectError::Stopped {
            evaluations,
            of,
            out: shown(a.out),
        });
    }
    let trials = problem.trials.len();
    eprintln!(
        "calibrated {} parameters of {} units on {trials} trial{} ({}): mean 1 - R2 {:.4} from {:.4}, {} evaluations -> {}",
        problem.parameters.len(),
        problem.units.len(),
        if trials == 1 { "" } else { "s" },
        a.dofs.join(", "),
        outcome.cost,
        outcome.start_cost,
        outcome.evaluations,
        shown(a.out)
    );
    Ok(())
}

/// Ctrl-C (SIGINT) asks the calibration to stop after the generation it is in, while this
/// lives; a second Ctrl-C ends the process at once (exit status 130). Dropped, its actions are
/// removed but the default one is not restored (signal-hook leaves its handler in place), so a
/// Ctrl-C while the result is written is ignored and the file is written whole.
struct StopOnInterrupt {
    asked: Arc<AtomicBool>,
    ids: [signal_hook::SigId; 2],
}

impl StopOnInterrupt {
    fn install() -> std::io::Result<StopOnInterrupt> {
        use signal_hook::consts::SIGINT;
        let asked = Arc::new(AtomicBool::new(false));
        // In this order: the second signal finds the flag set by the first and exits.
        let exit = signal_hook::flag::register_conditional_shutdown(SIGINT, 130, asked.clone())?;
        let flag = signal_hook::flag::register(SIGINT, asked.clone())?;
        Ok(StopOnInterrupt {
            asked,
            ids: [exit, flag],
        })
    }

    fn asked(&self) -> bool {
        self.asked.load(Ordering::Relaxed)
    }
}

impl Drop for StopOnInterrupt {
    fn drop(&mut self) {
        for id in self.ids {
            signal_hook::low_level::unregister(id);
        }
    }
}

/// How the calibration shows its progress: a bar on a terminal; otherwise (a log, a pipe, CI) a
/// line at the start and then at most every [`PROGRESS_LINE_S`] seconds.
struct Progress {
    bar: indicatif::ProgressBar,
    lines: Option<std::time::Instant>,
    of: usize,
}

/// Seconds between two progress lines when standard error is no terminal.
const PROGRESS_LINE_S: u64 = 10;

impl Progress {
    fn new(wanted: bool, of: usize) -> Progress {
        let terminal = std::io::stderr().is_terminal();
        let bar = if wanted && terminal {
            let bar = indicatif::ProgressBar::new(of as u64);
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
        let lines = (wanted && !terminal).then(std::time::Instant::now);
        Progress { bar, lines, of }
    }

    /// The line that says what starts (no terminal only): Ctrl-C is honoured from here on.
    fn start(&self, problem: &Problem) {
        if self.lines.is_some() {
            let trials = problem.trials.len();
            eprintln!(
                "calibrate: {} parameters of {} units on {trials} trial{}, at most {} evaluations (Ctrl-C stops after the generation and writes the best so far)",
                problem.parameters.len(),
                problem.units.len(),
                if trials == 1 { "" } else { "s" },
                self.of
            );
        }
    }

    fn show(&mut self, evaluations: usize, best: f64) {
        self.bar.set_position(evaluations as u64);
        self.bar.set_message(format!("{best:.4}"));
        if let Some(last) = &mut self.lines {
            if last.elapsed().as_secs() >= PROGRESS_LINE_S {
                *last = std::time::Instant::now();
                eprintln!(
                    "calibrate: {evaluations}/{} evaluations, best {best:.4}",
                    self.of
                );
            }
        }
    }

    fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
