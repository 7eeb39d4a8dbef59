//! `muscle_actuator._core`: the engine of the `muscle_actuator` crate as a Python extension
//! module (docs/python.md). The physics is the crate's, called as the command line and the node
//! call it; this layer converts and checks what crosses from Python, and releases the GIL
//! around every call that steps.
//!
//! - [`config`]: configurations, overrides, models, rates and steppings from Python values;
//! - [`inputs`]: arrays and dicts of inputs, checked;
//! - [`errors`]: the package's exceptions (`Error` and its kinds), and which a failure raises;
//! - [`outputs`]: the outputs a trajectory records, by field name, as numpy arrays (the stepping
//!   over per-tick inputs is the crate's `sim::rollout`);
//! - [`actuator`]: `Actuator` and its saved states;
//! - [`rollout`]: batched stepping on a thread pool;
//! - [`runs`]: `simulate`, `read_recording`, `compare`;
//! - [`subject`]: `Subject`, `Prediction`, `predict`, `calibrate`;
//! - [`emg`]: `emg_envelope`, `neural_activation`.

mod actuator;
mod config;
mod emg;
mod error_kinds;
mod errors;
mod inputs;
mod outputs;
mod prediction;
mod rollout;
mod runs;
mod subject;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<actuator::PyActuator>()?;
    m.add_class::<actuator::PyActuatorState>()?;
    for kind in errors::ErrorKind::ALL {
        m.add(kind.name(), kind.class(m.py())?)?;
    }
    m.add_function(wrap_pyfunction!(rollout::_rollout_new, m)?)?;
    m.add_function(wrap_pyfunction!(rollout::_rollout_actuators, m)?)?;
    m.add_function(wrap_pyfunction!(runs::_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(runs::_read_recording, m)?)?;
    m.add_function(wrap_pyfunction!(runs::_compare, m)?)?;
    m.add_class::<subject::PySubject>()?;
    m.add_class::<prediction::PyPrediction>()?;
    m.add_function(wrap_pyfunction!(subject::_predict, m)?)?;
    m.add_function(wrap_pyfunction!(subject::_calibrate, m)?)?;
    m.add_function(wrap_pyfunction!(emg::_emg_envelope, m)?)?;
    m.add_function(wrap_pyfunction!(emg::_emg_envelope_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(emg::_neural_activation, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
