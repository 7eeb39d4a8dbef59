//! The exception of a failed tick (bad input is a `ValueError`, raised where it is checked).

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

pyo3::create_exception!(
    _core,
    StepError,
    PyRuntimeError,
    "A tick failed (the implicit solver did not converge, or the state became non-finite). \
     Attributes: `tick` (the tick that failed), `reason`, and `instance` for a batch."
);

/// Ticks stepped between two checks of Python's signals (Ctrl-C) in a long call.
pub const CHUNK_TICKS: u64 = 10_000;

/// The `StepError` of a failed tick (of batch instance `instance`, if any).
pub fn step_error(py: Python<'_>, tick: u64, reason: &str, instance: Option<usize>) -> PyErr {
    let msg = match instance {
        Some(k) => format!("instance {k}: tick {tick} failed: {reason}"),
        None => format!("tick {tick} failed: {reason}"),
    };
    let err = StepError::new_err(msg);
    let v = err.value(py);
    // Setting attributes on a new exception instance cannot fail but for memory; the message
    // carries the same facts.
    let _ = v.setattr("tick", tick);
    let _ = v.setattr("reason", reason);
    let _ = v.setattr("instance", instance);
    err
}
