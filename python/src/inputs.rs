//! Inputs from Python, checked before anything is stepped: arrays of any numeric dtype or
//! nested sequences (as float64, C order), of the shape the call names, every value finite;
//! or a dict by name, checked by the node's own rules (`sim::input`: unknown, repeated and
//! non-finite names are refused whole; excitations outside [0, 1] are clamped). A refusal is an
//! `InputError`, or an `UnknownNameError` for a name the limb does not have.

use crate::errors::{input_error, unknown_name};
use muscle_actuator_core::sim::input::{validate_activation, validate_load, Rejection};
use numpy::{PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A float64 array of `obj` (a copy only when its dtype or layout is not already that).
pub fn float_array<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>() {
        if a.is_c_contiguous() {
            return Ok(a.readonly());
        }
    }
    let np = obj.py().import("numpy")?;
    let kwargs = PyDict::new(obj.py());
    kwargs.set_item("dtype", "float64")?;
    let converted = np
        .getattr("ascontiguousarray")?
        .call((obj,), Some(&kwargs))
        .map_err(|e| {
            input_error(format!(
                "{what} must be an array of numbers ({})",
                muscle_actuator_core::text::excerpt(&e.to_string())
            ))
        })?;
    let a = converted
        .cast_into::<PyArrayDyn<f64>>()
        .map_err(|_| input_error(format!("{what} must be an array of numbers")))?;
    Ok(a.readonly())
}

/// Checks the shape (`None`: any extent) and that every value is finite; the values, C order.
pub fn checked<'a>(
    a: &'a PyReadonlyArrayDyn<'_, f64>,
    what: &str,
    shape: &[Option<usize>],
    axes: &str,
) -> PyResult<&'a [f64]> {
    let got = a.shape();
    let fits = got.len() == shape.len()
        && got
            .iter()
            .zip(shape)
            .all(|(g, s)| s.is_none_or(|s| s == *g));
    if !fits {
        let want: Vec<String> = shape
            .iter()
            .map(|s| s.map_or("any".to_string(), |n| n.to_string()))
            .collect();
        return Err(input_error(format!(
            "{what} has shape {got:?}: expected [{}] ({axes})",
            want.join(", ")
        )));
    }
    let values = a
        .as_slice()
        .map_err(|_| input_error(format!("{what} is not contiguous")))?;
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        return Err(input_error(format!(
            "{what}[{}] = {} is not finite",
            index_of(k, got).join(", "),
            values[k]
        )));
    }
    Ok(values)
}

/// The multi-index of flat position k in C order.
fn index_of(mut k: usize, shape: &[usize]) -> Vec<String> {
    let mut idx = vec![String::new(); shape.len()];
    for (d, n) in shape.iter().enumerate().rev() {
        let n = (*n).max(1);
        idx[d] = (k % n).to_string();
        k /= n;
    }
    idx
}

/// Which inputs a call sets: all of them in configuration order, or some by name.
pub enum Values {
    All(Vec<f64>),
    Named(Vec<(usize, f64)>),
}

/// Excitations (`muscle`) or external torques (`joint`): an array of one value per name, or a
/// dict by name.
pub fn per_name(obj: &Bound<'_, PyAny>, names: &[String], kind: Kind) -> PyResult<Values> {
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut keys = Vec::with_capacity(d.len());
        let mut values = Vec::with_capacity(d.len());
        for (k, v) in d.iter() {
            keys.push(k.extract::<String>().map_err(|_| {
                input_error(format!(
                    "{}: a {} name must be a string",
                    kind.what(),
                    kind.noun()
                ))
            })?);
            values.push(v.extract::<f64>().map_err(|_| {
                input_error(format!(
                    "{}: the value for {} must be a number",
                    kind.what(),
                    muscle_actuator_core::sim::input::quote(keys.last().map_or("", |s| s))
                ))
            })?);
        }
        let accepted = match kind {
            Kind::Excitation => validate_activation(&keys, &values, names),
            Kind::Torque => validate_load(&keys, &values, names),
        }
        .map_err(|r| {
            let msg = format!("{}: {r}", kind.what());
            // A name not of this limb is an unknown name; a repeated or non-finite one, bad input.
            match r {
                Rejection::UnknownName { .. } => unknown_name(msg),
                _ => input_error(msg),
            }
        })?;
        return Ok(Values::Named(accepted.values));
    }
    let a = float_array(obj, kind.what())?;
    let v = checked(&a, kind.what(), &[Some(names.len())], kind.axes())?;
    Ok(Values::All(kind.clamp(v)))
}

#[derive(Clone, Copy)]
pub enum Kind {
    Excitation,
    Torque,
}

impl Kind {
    pub fn what(self) -> &'static str {
        match self {
            Kind::Excitation => "excitation",
            Kind::Torque => "external_torque",
        }
    }
    fn noun(self) -> &'static str {
        match self {
            Kind::Excitation => "muscle",
            Kind::Torque => "joint",
        }
    }
    pub fn axes(self) -> &'static str {
        match self {
            Kind::Excitation => "muscles",
            Kind::Torque => "joints",
        }
    }
    /// Excitations clamped to [0, 1] (as the node does); torques as given.
    pub fn clamp(self, v: &[f64]) -> Vec<f64> {
        match self {
            Kind::Excitation => v.iter().map(|u| u.clamp(0.0, 1.0)).collect(),
            Kind::Torque => v.to_vec(),
        }
    }
}
