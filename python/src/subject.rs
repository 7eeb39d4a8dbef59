//! Subjects, predictions and calibration (docs/python.md "Subjects, EMG and calibration"): the
//! crate's `subject` module as the command line's `predict` and `calibrate` call it
//! (src/cli/subject.rs), with the GIL released while units step.
//!
//! - `Subject`: a subject (CEINMS XML or the project's TOML), its units, degrees of freedom and
//!   parameters; pickles as its TOML text;
//! - `_predict`: a subject driven through one trial, as a `Prediction` (numpy arrays, ratings,
//!   the command line's CSV columns);
//! - `_calibrate`: a subject's parameters fitted to trials' moments by CMA-ES.

use crate::config::{count, parse_model};
use crate::error_kinds::{drive_error_in, subject_file_error, ToPyErr};
use crate::errors::{config_error, input_error, unknown_name, ErrorKind};
use crate::prediction::PyPrediction;
use muscle_actuator_core::sim::default_stepping;
use muscle_actuator_core::text::excerpt;
use muscle_actuator_measured::measured::{repeated_folder, ExcitationMap, MeasuredError, Trial};
use muscle_actuator_measured::subject::calibrate::{
    CalibrateError, Outcome, Problem, Settings, MAX_EVALUATIONS, MIN_EVALUATIONS,
};
use muscle_actuator_measured::subject::{DriveError, PreparedTrial, SubjectModel};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

/// Most threads a calibration may ask (the command line's `--threads`).
pub const MAX_THREADS: usize = 256;

/// A str or os.PathLike as a path.
fn path_of(py: Python<'_>, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<PathBuf> {
    if obj.is_instance_of::<PyString>() {
        return Ok(PathBuf::from(obj.extract::<String>()?));
    }
    py.import("os")?
        .getattr("fspath")?
        .call1((obj,))
        .and_then(|p| p.extract::<String>())
        .map(PathBuf::from)
        .map_err(|_| input_error(format!("{what} must be a str or a path")))
}

/// Whether `obj` is one path (a str or an os.PathLike) rather than a sequence of them.
fn is_one_path(obj: &Bound<'_, PyAny>) -> bool {
    obj.is_instance_of::<PyString>() || obj.hasattr("__fspath__").unwrap_or(false)
}

/// Shown path: at most 200 characters, as the command line quotes it.
fn shown(path: &Path) -> String {
    path.display().to_string().chars().take(200).collect()
}

/// A subject: CEINMS's XML or the project's TOML (docs/emg.md "Subject files").
#[pyclass(module = "muscle_actuator._core", name = "Subject", frozen)]
pub struct PySubject {
    model: SubjectModel,
}

#[pymethods]
impl PySubject {
    /// Reads a subject file: CEINMS's XML or the project's TOML, checked.
    #[staticmethod]
    fn read(py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<Self> {
        let path = path_of(py, path, "path")?;
        let model = py
            .detach(|| SubjectModel::read(&path))
            .map_err(|e| subject_file_error(&e))?;
        Ok(PySubject { model })
    }
    /// A subject from the project's TOML text.
    #[staticmethod]
    fn from_toml(text: &str) -> PyResult<Self> {
        SubjectModel::from_toml_str(text)
            .map(|model| PySubject { model })
            .map_err(|reason| config_error(format!("subject TOML: {reason}")))
    }
    /// The project's TOML text (what `muscle_actuator subject --out` writes).
    fn to_toml(&self) -> PyResult<String> {
        self.model
            .to_toml_string()
            .map_err(|reason| ErrorKind::Error.err(reason))
    }
    #[getter]
    fn id(&self) -> String {
        self.model.id.clone()
    }
    /// The units' names, in the subject's order.
    #[getter]
    fn units(&self) -> Vec<String> {
        self.model.units.iter().map(|u| u.name.clone()).collect()
    }
    /// Per degree of freedom, the units that span it.
    #[getter]
    fn dofs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (dof, units) in &self.model.dofs {
            d.set_item(dof, units)?;
        }
        Ok(d)
    }
    /// How the subject was calibrated (its `[calibration]` table), or None.
    #[getter]
    fn calibration<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.model
            .calibration
            .as_ref()
            .map(|c| to_python(py, toml::Value::try_from(c)))
            .transpose()
    }
    /// The bounds a calibration keeps its parameters within (the `[bounds]` table).
    #[getter]
    fn bounds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, toml::Value::try_from(self.model.bounds))
    }
    /// A unit's parameters under the keys of its `[[muscle]]` table.
    fn unit_params<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let unit = self.model.unit(name).ok_or_else(|| {
            let units = self.units();
            let more = if units.len() > 6 { ", …" } else { "" };
            unknown_name(format!(
                "the subject has no unit {:?} ({} units: {}{more})",
                excerpt(name),
                units.len(),
                units[..units.len().min(6)].join(", ")
            ))
        })?;
        to_python(py, toml::Value::try_from(&unit.params))
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PySubject>()
            .is_ok_and(|o| o.get().model == self.model)
    }
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let text = slf.get().to_toml()?;
        let ctor = py.get_type::<Self>().getattr("from_toml")?;
        Ok((ctor, PyTuple::new(py, [text])?))
    }
    fn __repr__(&self) -> String {
        let dofs: Vec<&str> = self.model.dofs.iter().map(|(d, _)| d.as_str()).collect();
        format!(
            "Subject({:?}, {} units, dofs [{}]{})",
            self.model.id,
            self.model.units.len(),
            dofs.join(", "),
            if self.model.calibration.is_some() {
                ", calibrated"
            } else {
                ""
            }
        )
    }
}

/// A value as the TOML file writes it (`toml::Value::try_from`), as Python values (dicts,
/// lists, floats, strs).
fn to_python<'py>(
    py: Python<'py>,
    value: Result<toml::Value, toml::ser::Error>,
) -> PyResult<Bound<'py, PyAny>> {
    let v = value.map_err(|e| ErrorKind::Error.err(format!("cannot write as TOML: {e}")))?;
    pythonize::pythonize(py, &v).map_err(|e| ErrorKind::Error.err(e.to_string()))
}

/// The subject of `obj`: a `Subject`, or a path read as one.
fn subject_of(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<SubjectModel> {
    if let Ok(s) = obj.cast::<PySubject>() {
        return Ok(s.get().model.clone());
    }
    if !is_one_path(obj) {
        return Err(input_error("subject must be a Subject, a str or a path"));
    }
    PySubject::read(py, obj).map(|s| s.model)
}

/// Degree-of-freedom names: one str, or a sequence of them; none empty, none twice.
fn dof_names(obj: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    let names: Vec<String> = if obj.is_instance_of::<PyString>() {
        vec![obj.extract()?]
    } else {
        obj.extract()
            .map_err(|_| input_error("dofs must be a str or a sequence of str"))?
    };
    if names.is_empty() {
        return Err(input_error("dofs: give at least one degree of freedom"));
    }
    for (i, n) in names.iter().enumerate() {
        if n.trim().is_empty() {
            return Err(input_error("dofs: a name is empty"));
        }
        if names[..i].contains(n) {
            return Err(input_error(format!(
                "dofs: {:?} is given twice",
                excerpt(n)
            )));
        }
    }
    Ok(names)
}

/// What fails in a subject command, told apart once the GIL is held again.
enum Failure {
    /// The excitation map or a trial's files.
    Measured(Box<MeasuredError>),
    /// A trial (its folder) that cannot be driven.
    Drive(PathBuf, Box<DriveError>),
    /// The calibration cannot run.
    Calibrate(CalibrateError),
}

impl Failure {
    fn measured(e: MeasuredError) -> Self {
        Failure::Measured(Box::new(e))
    }
    fn drive(dir: &Path, e: DriveError) -> Self {
        Failure::Drive(dir.to_path_buf(), Box::new(e))
    }
    fn into_py(self, py: Python<'_>) -> PyErr {
        match self {
            Failure::Measured(e) => e.to_py(py),
            Failure::Drive(path, e) => drive_error_in(py, &shown(&path), &e),
            Failure::Calibrate(e) => e.to_py(py),
        }
    }
}

/// A trial read and prepared for `dofs` (all the trial's when None), as the command line's.
fn prepare(
    subject: &SubjectModel,
    map: &ExcitationMap,
    dir: &Path,
    dofs: Option<&[String]>,
) -> Result<PreparedTrial, Failure> {
    let trial = Trial::read(dir).map_err(Failure::measured)?;
    let dofs: Vec<String> = match dofs {
        Some(d) => d.to_vec(),
        None => trial.dofs().map(str::to_string).collect(),
    };
    PreparedTrial::new(subject, map, &trial, &dofs).map_err(|e| Failure::drive(dir, e))
}

/// `muscle_actuator predict`: the subject driven through the trial in the folder `trial`, its
/// units excited through the map `excitations`.
#[pyfunction]
#[pyo3(signature = (subject, excitations, trial, model="huxley", dofs=None))]
pub fn _predict(
    py: Python<'_>,
    subject: &Bound<'_, PyAny>,
    excitations: &Bound<'_, PyAny>,
    trial: &Bound<'_, PyAny>,
    model: &str,
    dofs: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyPrediction> {
    let kind = parse_model(model)?;
    let subject = subject_of(py, subject)?;
    let map_path = path_of(py, excitations, "excitations")?;
    let dir = path_of(py, trial, "trial")?;
    let dofs = dofs.filter(|d| !d.is_none()).map(dof_names).transpose()?;
    let (p, prepared, held_lengths) = py
        .detach(|| {
            let map = ExcitationMap::read(&map_path).map_err(Failure::measured)?;
            let mut prepared = prepare(&subject, &map, &dir, dofs.as_deref())?;
            let params = subject
                .params_of(&prepared.units)
                .map_err(|e| Failure::drive(&dir, e))?;
            let held = prepared
                .hold_within_reach(&params)
                .map_err(|e| Failure::drive(&dir, e))?;
            let p = prepared
                .run(&params, kind, default_stepping(kind))
                .map_err(|e| Failure::drive(&dir, e))?;
            Ok((p, prepared, held.map_or(0, |h| h.samples)))
        })
        .map_err(|e: Failure| e.into_py(py))?;
    Ok(PyPrediction {
        p,
        trial: prepared.name,
        model: kind.name().to_string(),
        clamped_excitations: prepared.clamped_excitations,
        held_lengths,
    })
}

/// The optimiser's settings from Python values, checked as the command line checks them.
fn settings(seed: &Bound<'_, PyAny>, evaluations: i64, threads: Option<i64>) -> PyResult<Settings> {
    let seed: u64 = seed
        .extract()
        .map_err(|_| config_error("seed must be an integer from 0 to 2**64 - 1"))?;
    let max_evaluations = count("evaluations", evaluations)?;
    if !(MIN_EVALUATIONS..=MAX_EVALUATIONS).contains(&max_evaluations) {
        return Err(config_error(format!(
            "evaluations must be {MIN_EVALUATIONS} to {MAX_EVALUATIONS}, not {evaluations}"
        )));
    }
    let threads = match threads {
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
        Some(t) => count("threads", t)?,
    };
    if threads == 0 || threads > MAX_THREADS {
        return Err(config_error(format!(
            "threads must be 1 to {MAX_THREADS}, not {threads}"
        )));
    }
    Ok(Settings {
        seed,
        max_evaluations,
        threads,
        ..Settings::default()
    })
}

/// The trials' folders: one path, or a sequence of them (at least one).
fn trial_dirs(py: Python<'_>, trials: &Bound<'_, PyAny>) -> PyResult<Vec<PathBuf>> {
    let dirs = if is_one_path(trials) {
        vec![path_of(py, trials, "trials")?]
    } else {
        trials
            .try_iter()
            .map_err(|_| input_error("trials must be a path or a sequence of paths"))?
            .map(|t| path_of(py, &t?, "a trial"))
            .collect::<PyResult<Vec<_>>>()?
    };
    if dirs.is_empty() {
        return Err(input_error("trials: give at least one trial folder"));
    }
    if let Some(again) = repeated_folder(&dirs) {
        let shown: String = again.display().to_string().chars().take(200).collect();
        return Err(input_error(format!(
            "trials: {shown} is given twice; each trial counts once"
        )));
    }
    Ok(dirs)
}

/// The calibration's result as a dict: costs, evaluations, history, parameters by name.
fn outcome_dict<'py>(
    py: Python<'py>,
    problem: &Problem,
    outcome: &Outcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("cost", outcome.cost)?;
    d.set_item("start_cost", outcome.start_cost)?;
    d.set_item("evaluations", outcome.evaluations)?;
    d.set_item("history", PyList::new(py, &outcome.history)?)?;
    let params = PyDict::new(py);
    for (p, v) in problem.parameters.iter().zip(&outcome.values) {
        params.set_item(&p.name, v)?;
    }
    d.set_item("parameters", params)?;
    Ok(d)
}

/// `muscle_actuator calibrate`: the subject's parameters fitted to the trials' moments of
/// `dofs`; the calibrated subject and the result.
#[pyfunction]
#[pyo3(signature = (subject, excitations, trials, dofs, model, seed, evaluations, threads))]
#[allow(clippy::too_many_arguments)]
pub fn _calibrate<'py>(
    py: Python<'py>,
    subject: &Bound<'py, PyAny>,
    excitations: &Bound<'py, PyAny>,
    trials: &Bound<'py, PyAny>,
    dofs: &Bound<'py, PyAny>,
    model: &str,
    seed: &Bound<'py, PyAny>,
    evaluations: i64,
    threads: Option<i64>,
) -> PyResult<(PySubject, Bound<'py, PyDict>)> {
    let kind = parse_model(model)?;
    let settings = settings(seed, evaluations, threads)?;
    let subject = subject_of(py, subject)?;
    let map_path = path_of(py, excitations, "excitations")?;
    let dirs = trial_dirs(py, trials)?;
    let dofs = dof_names(dofs)?;
    let interrupted: std::sync::Mutex<Option<PyErr>> = std::sync::Mutex::new(None);
    let (problem, outcome) = py
        .detach(|| {
            let map = ExcitationMap::read(&map_path).map_err(Failure::measured)?;
            let prepared = dirs
                .iter()
                .map(|dir| prepare(&subject, &map, dir, Some(&dofs)))
                .collect::<Result<Vec<_>, _>>()?;
            let problem = Problem::new(&subject, &map, prepared, kind, default_stepping(kind))
                .map_err(|e| Failure::drive(&dirs[0], e))?;
            // Ctrl-C between generations stops it, as KeyboardInterrupt (the GIL taken back
            // for the check only).
            let outcome = problem
                .calibrate(&settings, |_, _| {
                    match Python::attach(|py| py.check_signals()) {
                        Ok(()) => ControlFlow::Continue(()),
                        Err(e) => {
                            *interrupted.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                            ControlFlow::Break(())
                        }
                    }
                })
                .map_err(Failure::Calibrate)?;
            Ok((problem, outcome))
        })
        .map_err(|e: Failure| {
            let signal = interrupted.lock().unwrap_or_else(|p| p.into_inner()).take();
            match (signal, e) {
                (Some(signal), Failure::Calibrate(stopped)) => {
                    let _ = signal
                        .value(py)
                        .call_method1("add_note", (stopped.to_string(),));
                    signal
                }
                (_, e) => e.into_py(py),
            }
        })?;
    let calibrated = problem.calibrated(&subject, &outcome, &settings);
    let result = outcome_dict(py, &problem, &outcome)?;
    Ok((PySubject { model: calibrated }, result))
}
