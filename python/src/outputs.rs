//! The outputs a trajectory carries (`muscle_actuator_core::sim::Outputs`: by the names of
//! the one field list) as numpy arrays.

use crate::error_kinds::py_err;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

pub use muscle_actuator_core::sim::{write_tick, Outputs};

/// The outputs named (None: all): an unknown name refused as an `UnknownNameError`, a repeated
/// one as an `InputError`.
pub fn named(names: Option<Vec<String>>) -> PyResult<Outputs> {
    Outputs::named(names).map_err(py_err)
}

/// One buffer per output for `lead` leading entries (instances × ticks) of their widths.
pub fn buffers(outputs: &Outputs, lead: usize, m: usize, j: usize) -> Vec<Vec<f64>> {
    outputs
        .widths(m, j)
        .iter()
        .map(|w| vec![0.0; lead * w])
        .collect()
}

/// The buffers as a dict of numpy arrays of shape `lead ++ trailing shape` (no copy).
pub fn into_dict<'py>(
    py: Python<'py>,
    outputs: &Outputs,
    buffers: Vec<Vec<f64>>,
    lead: &[usize],
    m: usize,
    j: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (((key, _), buf), tail) in outputs.keys.iter().zip(buffers).zip(outputs.shapes(m, j)) {
        let shape: Vec<usize> = lead.iter().chain(&tail).copied().collect();
        let a = PyArray1::from_vec(py, buf).reshape(shape)?;
        d.set_item(key, a)?;
    }
    Ok(d)
}
