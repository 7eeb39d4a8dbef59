//! `predict` (docs/emg.md "Prediction"): a subject's units driven through a measured trial by
//! its EMG and lengths; the joint moments against the measured ones, rated (R², r², RMSE), as
//! CSV, a recording and figures.

use super::common::{default_model, model_help, parse_model};
use super::prediction_run::{record_prediction, PredictionRunError};
use super::staged::Staged;
use super::subject::{parse_dofs, prepare, shown};
use super::CliError;
use super::SubjectError;
use crate::figures::FigureError;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::MuscleParams;
use muscle_actuator_core::sim::default_stepping;
use muscle_actuator_core::text::excerpt;
use muscle_actuator_measured::measured::rating::{rate, Rating};
use muscle_actuator_measured::measured::ExcitationMap;
use muscle_actuator_measured::subject::{Prediction, PreparedTrial, SubjectModel};
use muscle_actuator_recording::runs::{ObservedRun, RunError};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// What `predict` is asked.
#[derive(Debug, clap::Args)]
pub struct Args {
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
    pub csv: Option<PathBuf>,
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
    #[arg(long, default_value = default_model(), help = model_help())]
    pub model: String,
}

/// Runs `predict`: the ratings as a table on standard output.
pub(super) fn run(a: Args) -> Result<(), CliError> {
    let ratings = predict(&a, parse_model(&a.model)?)?;
    print!(
        "{}",
        ratings_table(&a.trial.display().to_string(), &ratings)
    );
    Ok(())
}

/// `predict` with `model`: the subject through the trial; the moments' CSV, the units' CSV, the
/// recording and the figures, a rating per degree of freedom on standard output. Every output
/// is checked before the work (its folders made as `mkdir -p` does), made under a temporary
/// name after it, and all are renamed into place at the end, the recording last: a failure
/// leaves none of them.
fn predict(a: &Args, model: ModelKind) -> Result<Vec<(String, Rating)>, SubjectError> {
    let mut staged = Staged::default();
    check_outputs(a, &mut staged)?;
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
        let figures = crate::figures::subject_plot::stage(&p, &ratings, &prepared.name, plot)
            .map_err(|e| not_drawn(plot, e))?;
        figures.into_iter().for_each(|f| staged.push(f));
    }
    if let Some(path) = &a.csv {
        staged
            .text(path, &moments_csv(&p))
            .map_err(not_written(path))?;
    }
    if let Some(path) = &a.muscles_csv {
        staged
            .text(path, &muscles_csv(&p))
            .map_err(not_written(path))?;
    }
    staged.commit().map_err(|(path, e)| not_written(&path)(e))?;
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

/// The output `path` that could not be written.
fn not_written(path: &Path) -> impl FnOnce(std::io::Error) -> SubjectError + '_ {
    move |e| SubjectError::Write {
        path: shown(path),
        reason: e.to_string(),
    }
}

/// Every output of `predict` (the figures' four files) refused if it names one of its inputs
/// (the subject, the map, the trial's files) or another of its outputs, or if it cannot be
/// made (probed in `staged`, its folders made).
fn check_outputs(a: &Args, staged: &mut Staged) -> Result<(), SubjectError> {
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
    let named = [a.csv.as_ref(), a.muscles_csv.as_ref(), a.out.as_ref()];
    for out in named.into_iter().flatten().chain(&figures) {
        muscle_actuator_core::files::check_not_an_input(out, &inputs)?;
        staged.probe(out).map_err(not_written(out))?;
        inputs.push(out);
    }
    Ok(())
}

/// The units of `prepared` with `params` driven through the trial under `model`; with `--out`,
/// recorded (not yet under the output's name).
fn drive(
    a: &Args,
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
fn ratings(p: &Prediction) -> Result<Vec<(String, Rating)>, SubjectError> {
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
fn ratings_table(trial: &str, ratings: &[(String, Rating)]) -> String {
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
fn moments_csv(p: &Prediction) -> String {
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
fn muscles_csv(p: &Prediction) -> String {
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
