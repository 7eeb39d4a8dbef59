//! The subject commands (docs/emg.md): `subject` (a CEINMS subject as the project's TOML),
//! `predict` (a subject driven through a trial: moments against the measured ones, rated) and
//! `calibrate` (a subject's parameters fitted to trials' moments).

use super::prediction_run::{record_prediction, PredictionRunError};
use crate::figures::FigureError;
use muscle_actuator_core::files::{write_atomically, OverwritesInput};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::params::MuscleParams;
use muscle_actuator_core::sim::simulation::default_stepping;
use muscle_actuator_core::text::{excerpt, one_line};
use muscle_actuator_measured::measured::rating::{rate, Rating, RatingError};
use muscle_actuator_measured::measured::{ExcitationMap, MeasuredError, Trial};
use muscle_actuator_measured::subject::calibrate::{CalibrateError, Problem, Settings};
use muscle_actuator_measured::subject::{
    DriveError, Prediction, PreparedTrial, SubjectFileError, SubjectModel,
};
use muscle_actuator_recording::runs::{ObservedRun, RunError};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Why a subject command failed.
#[derive(Debug, thiserror::Error)]
pub enum SubjectError {
    /// The subject file.
    #[error(transparent)]
    Subject(#[from] SubjectFileError),
    /// The excitation map or a trial.
    #[error(transparent)]
    Measured(#[from] MeasuredError),
    /// A trial that cannot be driven.
    #[error("{path}: {}", one_line(&.error.to_string()))]
    Drive {
        /// The trial's folder.
        path: String,
        /// What is wrong.
        error: Box<DriveError>,
    },
    /// The calibration cannot run.
    #[error(transparent)]
    Calibrate(#[from] CalibrateError),
    /// A rating that cannot be computed (a constant measured moment).
    #[error("{dof}: {error}")]
    Rating {
        /// The degree of freedom.
        dof: String,
        /// Why.
        error: RatingError,
    },
    /// `--dofs` empty or repeated.
    #[error("--dofs: {0}")]
    Dofs(String),
    /// An output that would overwrite an input.
    #[error(transparent)]
    OutputIsInput(#[from] OverwritesInput),
    /// An output that cannot be written.
    #[error("cannot write {path}: {reason}")]
    Write {
        /// The output.
        path: String,
        /// Why.
        reason: String,
    },
    /// `--threads` or `--evaluations` out of range.
    #[error("{0}")]
    Setting(String),
}

/// Shown path: at most 200 characters.
fn shown(path: &Path) -> String {
    path.display().to_string().chars().take(200).collect()
}

/// `--dofs a,b,c` as names: none empty, none twice.
pub fn parse_dofs(dofs: &str) -> Result<Vec<String>, SubjectError> {
    let names: Vec<String> = dofs.split(',').map(|d| d.trim().to_string()).collect();
    if names.iter().any(String::is_empty) {
        return Err(SubjectError::Dofs(format!(
            "{:?} has an empty name",
            excerpt(dofs)
        )));
    }
    for (i, n) in names.iter().enumerate() {
        if names[..i].contains(n) {
            return Err(SubjectError::Dofs(format!(
                "{:?} is given twice",
                excerpt(n)
            )));
        }
    }
    Ok(names)
}

/// A trial read and prepared for `dofs` (all the trial's when None).
fn prepare(
    subject: &SubjectModel,
    map: &ExcitationMap,
    dir: &Path,
    dofs: Option<&[String]>,
) -> Result<PreparedTrial, SubjectError> {
    let trial = Trial::read(dir)?;
    let dofs: Vec<String> = match dofs {
        Some(d) => d.to_vec(),
        None => trial.dofs().map(str::to_string).collect(),
    };
    PreparedTrial::new(subject, map, &trial, &dofs).map_err(|error| SubjectError::Drive {
        path: shown(dir),
        error: Box::new(error),
    })
}

/// Writes `text` to `path` whole (nothing under the name unless all of it).
fn write(path: &Path, text: &str) -> Result<(), SubjectError> {
    write_atomically(path, text.as_bytes()).map_err(|e| SubjectError::Write {
        path: shown(path),
        reason: e.to_string(),
    })
}

/// `subject FILE --out OUT.toml`: the subject (CEINMS XML or the project's TOML) as the
/// project's TOML.
pub fn convert(file: &Path, out: &Path) -> Result<(), SubjectError> {
    muscle_actuator_core::files::check_not_an_input(out, &[file])?;
    let subject = SubjectModel::read(file)?;
    let text = subject
        .to_toml_string()
        .map_err(|reason| SubjectError::Write {
            path: shown(out),
            reason,
        })?;
    write(out, &text)?;
    eprintln!(
        "{}: {} units, {} degrees of freedom -> {}",
        subject.id,
        subject.units.len(),
        subject.dofs.len(),
        shown(out)
    );
    Ok(())
}

/// What `predict` is asked: the command line's `predict` but its `--model` (parsed apart).
#[derive(Debug, clap::Args)]
pub struct PredictArgs {
    /// The subject file (CEINMS XML or the project's TOML).
    #[arg(long)]
    pub subject: PathBuf,
    /// The EMG-to-unit map (CEINMS's excitation generator XML).
    #[arg(long)]
    pub excitations: PathBuf,
    /// The trial's folder (emg.txt, lmt.txt, <dof>Ma.txt, <dof>Torque.txt).
    #[arg(long)]
    pub trial: PathBuf,
    /// Only these degrees of freedom, comma-separated (default: every one the trial has),
    /// driving only the units that span them.
    #[arg(long)]
    pub dofs: Option<String>,
    /// CSV of the moments: time, then per degree of freedom <dof> and <dof>_measured (N m).
    #[arg(long)]
    pub csv: PathBuf,
    /// CSV of the units: time, then per unit its force (N), activation and fibre length (m).
    #[arg(long)]
    pub muscles_csv: Option<PathBuf>,
    /// Record the run as MCAP, as `simulate --out` does (for replay, compare, export,
    /// Foxglove): the units on their driven length coordinates, tick 0 the first EMG sample.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Plot the moments against the measured ones, one panel per degree of freedom (PNG, an
    /// SVG beside it), and the units' forces as <stem>_forces.png and .svg.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// `predict` with `model`: the subject through the trial; the moments' CSV, the units' CSV, the
/// recording and the figures, a rating per degree of freedom on standard output. Nothing is
/// written before the drive and the ratings succeed, and the recording is renamed into place
/// last.
pub fn predict(a: &PredictArgs, model: ModelKind) -> Result<Vec<(String, Rating)>, SubjectError> {
    check_outputs(a)?;
    let subject = SubjectModel::read(&a.subject)?;
    let map = ExcitationMap::read(&a.excitations)?;
    let dofs = a.dofs.as_deref().map(parse_dofs).transpose()?;
    let mut prepared = prepare(&subject, &map, &a.trial, dofs.as_deref())?;
    let params = subject
        .params_of(&prepared.units)
        .map_err(|error| SubjectError::Drive {
            path: prepared.name.clone(),
            error: Box::new(error),
        })?;
    let held = prepared
        .hold_within_reach(&params)
        .map_err(|error| SubjectError::Drive {
            path: shown(&a.trial),
            error: Box::new(error),
        })?;
    let (p, recording) = drive(a, model, &prepared, &params)?;
    let ratings = ratings(&p)?;
    if let Some(plot) = &a.plot {
        crate::figures::subject_plot::draw(&p, &ratings, &prepared.name, plot)
            .map_err(|e| not_drawn(plot, e))?;
    }
    write(&a.csv, &moments_csv(&p))?;
    if let Some(path) = &a.muscles_csv {
        write(path, &muscles_csv(&p))?;
    }
    if let (Some(recording), Some(out)) = (recording, &a.out) {
        recording.commit().map_err(|e| not_recorded(out, e))?;
    }
    if prepared.clamped_excitations > 0 {
        eprintln!(
            "warning: {} excitation samples above 1 were clamped to 1",
            prepared.clamped_excitations
        );
    }
    if let Some(held) = held {
        eprintln!("warning: {}: {held}", prepared.name);
    }
    Ok(ratings)
}

/// Every output of `predict` (the figures' four files) refused if it names one of its inputs
/// (the subject, the map, the trial's files) or another of its outputs.
fn check_outputs(a: &PredictArgs) -> Result<(), SubjectError> {
    let trial_files: Vec<PathBuf> = std::fs::read_dir(&a.trial)
        .map(|d| d.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    let mut inputs: Vec<&Path> = vec![&a.subject, &a.excitations];
    inputs.extend(trial_files.iter().map(PathBuf::as_path));
    let figures = match &a.plot {
        Some(plot) => (crate::figures::subject_plot::outputs(plot))
            .map_err(|e| not_drawn(plot, e))?
            .to_vec(),
        None => Vec::new(),
    };
    let named = [Some(&a.csv), a.muscles_csv.as_ref(), a.out.as_ref()];
    for out in named.into_iter().flatten().chain(&figures) {
        muscle_actuator_core::files::check_not_an_input(out, &inputs)?;
        inputs.push(out);
    }
    Ok(())
}

/// The units of `prepared` with `params` driven through the trial under `model`; with `--out`,
/// recorded (not yet under the output's name).
fn drive(
    a: &PredictArgs,
    model: ModelKind,
    prepared: &PreparedTrial,
    params: &[MuscleParams],
) -> Result<(Prediction, Option<ObservedRun>), SubjectError> {
    let stepping = default_stepping(model);
    let failed = |error| SubjectError::Drive {
        path: shown(&a.trial),
        error: Box::new(error),
    };
    let Some(out) = &a.out else {
        let p = (prepared.run(params, model, stepping)).map_err(failed)?;
        return Ok((p, None));
    };
    match record_prediction(prepared, params, model, stepping, out) {
        Ok((p, recording)) => Ok((p, Some(recording))),
        Err(PredictionRunError::Drive(error)) => Err(failed(error)),
        Err(PredictionRunError::Run(error)) => Err(not_recorded(out, error)),
    }
}

/// The recording `out` that could not be written, as [`SubjectError::Write`] of the file the
/// error names.
fn not_recorded(out: &Path, error: RunError) -> SubjectError {
    let (path, reason) = match error {
        RunError::Output { path, source } => (path, source.to_string()),
        other => (out.to_path_buf(), other.to_string()),
    };
    SubjectError::Write {
        path: shown(&path),
        reason,
    }
}

/// The figures of `plot` that could not be drawn, as [`SubjectError::Write`] of the file the
/// error names.
fn not_drawn(plot: &Path, error: FigureError) -> SubjectError {
    let (path, reason) = match error {
        FigureError::CreateDir { path, source }
        | FigureError::CreateFile { path, source }
        | FigureError::Write { path, source } => (path, source.to_string()),
        FigureError::Draw { path, source } => (path, source.to_string()),
        other => (plot.to_path_buf(), other.to_string()),
    };
    SubjectError::Write {
        path: shown(&path),
        reason,
    }
}

/// Per degree of freedom, its rating.
pub fn ratings(p: &Prediction) -> Result<Vec<(String, Rating)>, SubjectError> {
    p.dofs
        .iter()
        .zip(p.measured.iter().zip(&p.moment))
        .map(|(dof, (m, q))| {
            rate(m, q)
                .map(|r| (dof.clone(), r))
                .map_err(|error| SubjectError::Rating {
                    dof: dof.clone(),
                    error,
                })
        })
        .collect()
}

/// The ratings as a table.
pub fn ratings_table(trial: &str, ratings: &[(String, Rating)]) -> String {
    let mut s = format!(
        "{trial}\n{:<16} {:>7} {:>7} {:>10} {:>10}\n",
        "dof", "R2", "r2", "RMSE N m", "RMSE/peak"
    );
    for (dof, r) in ratings {
        let _ = writeln!(
            s,
            "{:<16} {:>7.3} {:>7.3} {:>10.2} {:>10.3}",
            excerpt(dof),
            r.r_squared,
            r.pearson_r_squared,
            r.rmse,
            r.rmse_over_peak
        );
    }
    s
}

/// `time`, then per degree of freedom its predicted moment and `<dof>_measured`, N m.
pub fn moments_csv(p: &Prediction) -> String {
    let mut s = String::from("time");
    for d in &p.dofs {
        let _ = write!(s, ",{d},{d}_measured");
    }
    s.push('\n');
    for (k, t) in p.times.iter().enumerate() {
        let _ = write!(s, "{t}");
        for (q, m) in p.moment.iter().zip(&p.measured) {
            let _ = write!(s, ",{},{}", q[k], m[k]);
        }
        s.push('\n');
    }
    s
}

/// `time`, then per unit `<unit>.force` (N), `<unit>.activation`, `<unit>.fibre_length` (m).
pub fn muscles_csv(p: &Prediction) -> String {
    let mut s = String::from("time");
    for u in &p.units {
        let _ = write!(s, ",{u}.force,{u}.activation,{u}.fibre_length");
    }
    s.push('\n');
    for (k, t) in p.times.iter().enumerate() {
        let _ = write!(s, "{t}");
        for i in 0..p.units.len() {
            let _ = write!(
                s,
                ",{},{},{}",
                p.force[i][k], p.activation[i][k], p.fibre_length[i][k]
            );
        }
        s.push('\n');
    }
    s
}

/// What `calibrate` is asked.
pub struct CalibrateArgs<'a> {
    /// The subject file.
    pub subject: &'a Path,
    /// The excitation map.
    pub excitations: &'a Path,
    /// The trials' folders.
    pub trials: &'a [PathBuf],
    /// The degrees of freedom.
    pub dofs: &'a [String],
    /// The model.
    pub model: ModelKind,
    /// The calibrated subject's file.
    pub out: &'a Path,
    /// The optimiser's settings.
    pub settings: Settings,
    /// Whether to draw a progress bar.
    pub progress: bool,
}

/// Most evaluations `--evaluations` may ask.
pub const MAX_EVALUATIONS: usize = 1_000_000;

/// `calibrate`: the subject's parameters fitted; the calibrated subject written to `out`.
pub fn calibrate(a: &CalibrateArgs) -> Result<(), SubjectError> {
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
