//! What a Python call names: a configuration (built-in name, path or dict), per-instance
//! overrides, a model, an energy model and a stepping, resolved by the crate's own functions so
//! that every refusal carries the command line's message.

use crate::error_kinds::py_err;
use crate::errors::config_error;
use muscle_actuator_core::config::{with_overrides, ActuatorConfig};
use muscle_actuator_core::physics::models::{ModelKind, UnknownModel};
use muscle_actuator_core::physics::{EnergyModel, UnknownEnergyModel};
use muscle_actuator_core::sim::Actuator;
use muscle_actuator_recording::runs::limits;
use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

/// A Python value as a TOML value (numbers, strings, booleans, lists, dicts).
fn toml_value(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<toml::Value> {
    pythonize::depythonize::<toml::Value>(obj)
        .map_err(|e| config_error(format!("{what}: not a TOML value: {e}")))
}

/// The configuration `config` names: a built-in name or a file path (str or os.PathLike), a
/// dict in the configuration file's form, or None (the default elbow). Warnings go to Python's
/// `warnings`. A file that does not exist raises `FileNotFound`, one that does not open
/// `OSError`, and a bad configuration `ConfigError`.
pub fn resolve_config(
    py: Python<'_>,
    config: Option<&Bound<'_, PyAny>>,
) -> PyResult<ActuatorConfig> {
    let cfg = match config {
        None => ActuatorConfig::default(),
        Some(c) if c.is_instance_of::<PyDict>() => {
            let value = toml_value(c, "configuration dict")?;
            let text = toml::to_string(&value)
                .map_err(|e| config_error(format!("configuration dict: {e}")))?;
            ActuatorConfig::from_toml_str(&text).map_err(|e| {
                config_error(
                    e.to_string()
                        .replace("configuration file <text>", "configuration dict"),
                )
            })?
        }
        Some(c) => {
            let name: String = if c.is_instance_of::<PyString>() {
                c.extract()?
            } else {
                let fspath = py.import("os")?.getattr("fspath")?;
                fspath
                    .call1((c,))
                    .and_then(|p| p.extract())
                    .map_err(|_| {
                        config_error(
                            "config must be a built-in name, a path or a dict in the configuration file's form",
                        )
                    })?
            };
            ActuatorConfig::resolve(&name).map_err(py_err)?
        }
    };
    for w in cfg.warnings() {
        PyErr::warn(
            py,
            &py.get_type::<PyUserWarning>(),
            &std::ffi::CString::new(w).unwrap_or_default(),
            1,
        )?;
    }
    Ok(cfg)
}

/// Overrides as (dotted key, value): a dict `{"muscle.flexor.k_t": 2e5, ...}` or None.
pub fn overrides_of(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<(String, toml::Value)>> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(Vec::new());
    };
    let dict = obj
        .cast::<PyDict>()
        .map_err(|_| config_error("overrides must be a dict of dotted keys to values"))?;
    let mut out = Vec::with_capacity(dict.len());
    for (k, v) in dict.iter() {
        let key: String = k
            .extract()
            .map_err(|_| config_error("an override's key must be a string"))?;
        let value = toml_value(
            &v,
            &format!("override {:?}", muscle_actuator_core::text::excerpt(&key)),
        )?;
        out.push((key, value));
    }
    Ok(out)
}

/// `cfg` with the overrides and the energy model applied.
pub fn configured(
    cfg: &ActuatorConfig,
    overrides: &[(String, toml::Value)],
    energy_model: Option<&str>,
) -> PyResult<ActuatorConfig> {
    let cfg = with_overrides(cfg, overrides).map_err(py_err)?;
    Ok(match energy_model {
        Some(name) => cfg.with_energy_model(parse_energy_model(name)?),
        None => cfg,
    })
}

pub fn parse_model(name: &str) -> PyResult<ModelKind> {
    name.parse().map_err(|e: UnknownModel| py_err(e))
}

pub fn parse_energy_model(name: &str) -> PyResult<EnergyModel> {
    name.parse().map_err(|e: UnknownEnergyModel| py_err(e))
}

/// The rate, checked as `--rate-hz` is.
pub fn check_rate(rate_hz: f64) -> PyResult<()> {
    limits::check_rate_hz("rate_hz", rate_hz).map_err(py_err)
}

/// A count from Python (an int may be negative), refused below 0 with its name.
pub fn count(name: &str, v: i64) -> PyResult<usize> {
    usize::try_from(v).map_err(|_| config_error(format!("{name} = {v} must be >= 1")))
}

/// The overrides with the `tolerance=` keyword as one more, `stepper.tolerance` (set last, so
/// it wins over an override of the same key).
pub fn with_tolerance(
    mut overrides: Vec<(String, toml::Value)>,
    tolerance: Option<f64>,
) -> Vec<(String, toml::Value)> {
    if let Some(t) = tolerance {
        overrides.push(("stepper.tolerance".into(), toml::Value::Float(t)));
    }
    overrides
}

/// Fixed sub-steps per tick from Python, checked as `--substeps` is.
pub fn substeps_of(substeps: Option<i64>) -> PyResult<Option<usize>> {
    let substeps = substeps.map(|n| count("substeps", n)).transpose()?;
    if let Some(n) = substeps {
        limits::check_substeps("substeps", n).map_err(py_err)?;
    }
    Ok(substeps)
}

/// What `Actuator(...)` and `rollout(...)` take besides the configuration: the model, the
/// rate, the energy model, fixed sub-steps and the tolerance.
pub struct BuildArgs<'a> {
    /// The model's name.
    pub model: &'a str,
    /// The tick rate, Hz.
    pub rate_hz: f64,
    /// Every muscle's energy model, by name.
    pub energy_model: Option<&'a str>,
    /// Fixed sub-steps per tick.
    pub substeps: Option<i64>,
    /// The adaptive sub-steps' tolerance (`stepper.tolerance`).
    pub tolerance: Option<f64>,
}

/// Builds an actuator from the arguments `Actuator(...)` and `rollout(...)` take.
pub fn build(
    py: Python<'_>,
    config: Option<&Bound<'_, PyAny>>,
    args: &BuildArgs<'_>,
    overrides: Option<&Bound<'_, PyAny>>,
) -> PyResult<Actuator> {
    let model = parse_model(args.model)?;
    check_rate(args.rate_hz)?;
    let substeps = substeps_of(args.substeps)?;
    let cfg = configured(
        &resolve_config(py, config)?,
        &with_tolerance(overrides_of(overrides)?, args.tolerance),
        args.energy_model,
    )?;
    // Fixed sub-steps, or the `[stepper]` table's stepping (by default the model's); a
    // `[stepper]` value with fixed sub-steps is refused.
    let stepping = cfg.stepping(model, substeps).map_err(py_err)?;
    Actuator::with_stepping(&cfg, model, args.rate_hz, stepping).map_err(py_err)
}
