//! Offline runs and recordings as arrays: `simulate` runs the command line's own
//! `runs::run_scenario`, `read_recording` reads through the same strict reader as `replay` and
//! `export` (`runs::load_run`, `runs::export::run_of`), and `compare` returns the `compare`
//! command's figures as its `--json` prints them. `muscle_actuator/run.py` wraps the dicts.

use crate::config::{configured, parse_model, resolve_config, with_tolerance};
use crate::error_kinds::{py_err, ToPyErr};
use crate::errors::{input_error, ErrorKind};
use crate::outputs::{self, Outputs};
use muscle_actuator_core::files::check_not_an_input;
use muscle_actuator_core::sim::Run;
use muscle_actuator_recording::runs::RunError;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::path::PathBuf;

/// A str or os.PathLike as a path string.
fn path_of(py: Python<'_>, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<String> {
    if obj.is_instance_of::<PyString>() {
        return obj.extract();
    }
    py.import("os")?
        .getattr("fspath")?
        .call1((obj,))
        .and_then(|p| p.extract())
        .map_err(|_| input_error(format!("{what} must be a str or a path")))
}

/// A run as a dict: its names, rate, time (ticks + 1,) and every output (ticks + 1, …).
fn run_dict<'py>(py: Python<'py>, run: Run) -> PyResult<Bound<'py, PyDict>> {
    let outputs = Outputs::all();
    let (m, j) = (run.muscle_names.len(), run.joint_names.len());
    let n = run.len();
    let widths = outputs.widths(m, j);
    let mut bufs = outputs::buffers(&outputs, n, m, j);
    let mut time = Vec::with_capacity(n);
    {
        let mut slices: Vec<&mut [f64]> = bufs.iter_mut().map(|b| b.as_mut_slice()).collect();
        for (t, rec) in run.records().enumerate() {
            time.push(rec.time);
            outputs::write_tick(&outputs, &widths, &rec, t, &mut slices);
        }
    }
    let d = PyDict::new(py);
    d.set_item("scenario", run.scenario)?;
    d.set_item("model", run.model.name())?;
    d.set_item("rate_hz", run.rate_hz)?;
    d.set_item("muscles", run.muscle_names)?;
    d.set_item("joints", run.joint_names)?;
    d.set_item("muscle_joints", run.muscle_joints)?;
    d.set_item("time", PyArray1::from_vec(py, time))?;
    d.set_item(
        "arrays",
        outputs::into_dict(py, &outputs, bufs, &[n], m, j)?,
    )?;
    Ok(d)
}

/// `muscle_actuator simulate`: the scenario run offline (and recorded to `out`, if given).
#[pyfunction]
#[pyo3(signature = (scenario, model="huxley", config=None, rate_hz=1000.0, substeps=None, energy_model=None, out=None, tolerance=None))]
#[allow(clippy::too_many_arguments)]
pub fn _simulate<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    model: &str,
    config: Option<&Bound<'py, PyAny>>,
    rate_hz: f64,
    substeps: Option<i64>,
    energy_model: Option<&str>,
    out: Option<&Bound<'py, PyAny>>,
    tolerance: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let scenario = path_of(py, scenario, "scenario")?;
    let substeps = substeps
        .map(|n| crate::config::count("substeps", n))
        .transpose()?;
    let model = parse_model(model)?;
    let config_path = match config {
        Some(c) if !c.is_instance_of::<PyDict>() => Some(path_of(py, c, "config")?),
        _ => None,
    };
    let cfg = configured(
        &resolve_config(py, config)?,
        &with_tolerance(Vec::new(), tolerance),
        energy_model,
    )?;
    check_scenario(&scenario, &cfg)?;
    let out = out
        .map(|o| path_of(py, o, "out"))
        .transpose()?
        .map(PathBuf::from);
    if let Some(o) = &out {
        let inputs: Vec<PathBuf> = [Some(scenario.clone()), config_path]
            .into_iter()
            .flatten()
            .map(PathBuf::from)
            .filter(|p| p.is_file())
            .collect();
        let refs: Vec<&std::path::Path> = inputs.iter().map(|p| p.as_path()).collect();
        check_not_an_input(o, &refs).map_err(py_err)?;
    }
    let run = py
        .detach(|| {
            muscle_actuator_recording::runs::run_scenario(
                &scenario,
                &cfg,
                model,
                rate_hz,
                substeps,
                out.as_deref(),
            )
        })
        .map_err(|e| e.to_py(py))?;
    run_dict(py, run)
}

/// The scenario `simulate` names, resolved as `run_scenario` resolves it (its error's exception:
/// [`crate::error_kinds`]).
fn check_scenario(
    scenario: &str,
    cfg: &muscle_actuator_core::config::ActuatorConfig,
) -> PyResult<()> {
    let Some(first) = cfg.muscles.first() else {
        return Ok(());
    };
    muscle_actuator_core::sim::Scenario::resolve(scenario, &first.params)
        .map(|_| ())
        .map_err(py_err)
}

/// A recording (node or `simulate --out`) as `export` reads it; the warning of a file cut by a
/// crash (read up to the cut) is under `warning`.
#[pyfunction]
pub fn _read_recording<'py>(
    py: Python<'py>,
    path: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let path = PathBuf::from(path_of(py, path, "path")?);
    let (run, warning) = py
        .detach(|| {
            let loaded =
                muscle_actuator_recording::runs::load_run(&path).map_err(RunError::from)?;
            let run =
                muscle_actuator_recording::runs::export::run_of(&loaded).map_err(|source| {
                    RunError::Export {
                        path: path.clone(),
                        source,
                    }
                })?;
            Ok::<_, RunError>((run, loaded.warning))
        })
        .map_err(|e| e.to_py(py))?;
    let d = run_dict(py, run)?;
    d.set_item("warning", warning)?;
    Ok(d)
}

/// `muscle_actuator compare A B --json`: the JSON text and the warnings on the files read. With
/// `plot`, first checks that neither of its files (`.png`, `.svg`) is an input; the package
/// draws it (`muscle_actuator/_compare_plot.py`).
#[pyfunction]
#[pyo3(signature = (a, b, plot=None))]
pub fn _compare<'py>(
    py: Python<'py>,
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    plot: Option<&Bound<'py, PyAny>>,
) -> PyResult<(String, Vec<String>)> {
    let a = PathBuf::from(path_of(py, a, "a")?);
    let b = PathBuf::from(path_of(py, b, "b")?);
    let plot = plot
        .map(|p| path_of(py, p, "plot"))
        .transpose()?
        .map(PathBuf::from);
    if let Some(p) = &plot {
        for written in [p.with_extension("png"), p.with_extension("svg")] {
            check_not_an_input(&written, &[a.as_path(), b.as_path()]).map_err(py_err)?;
        }
    }
    py.detach(|| {
        let c = muscle_actuator_recording::runs::compare::compare_files(&a, &b, None)?;
        Ok::<_, RunError>(c)
    })
    .map_err(|e| e.to_py(py))
    .and_then(|c| {
        let json = serde_json::to_string_pretty(&c)
            .map_err(|e| ErrorKind::Error.err(format!("comparison as JSON: {e}")))?;
        Ok((json, c.warnings))
    })
}
