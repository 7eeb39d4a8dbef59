//! The package's exceptions (docs/python.md#errors): `Error`, a `ValueError`, and its kinds —
//! `ConfigError`, `InputError`, `StepError` (also a `RuntimeError`), `RecordingError`,
//! `UnknownNameError` (also a `KeyError`) and `FileNotFound` (also a `FileNotFoundError`).
//! Which kind each of the crates' errors raises is [`crate::error_kinds`]'s; the errors this crate
//! finds itself (arguments of the wrong type or shape) are raised where they are found.

use pyo3::exceptions::{
    PyBaseException, PyFileNotFoundError, PyKeyError, PyRuntimeError, PyValueError,
};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyTuple, PyType};

/// Ticks stepped between two checks of Python's signals (Ctrl-C) in a long call.
pub const CHUNK_TICKS: u64 = 10_000;

/// The kinds of error, each a Python class of the module `muscle_actuator`.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum ErrorKind {
    Error,
    Config,
    Input,
    Step,
    Recording,
    UnknownName,
    FileNotFound,
}

impl ErrorKind {
    pub const ALL: [ErrorKind; 7] = [
        ErrorKind::Error,
        ErrorKind::Config,
        ErrorKind::Input,
        ErrorKind::Step,
        ErrorKind::Recording,
        ErrorKind::UnknownName,
        ErrorKind::FileNotFound,
    ];

    pub fn name(self) -> &'static str {
        match self {
            ErrorKind::Error => "Error",
            ErrorKind::Config => "ConfigError",
            ErrorKind::Input => "InputError",
            ErrorKind::Step => "StepError",
            ErrorKind::Recording => "RecordingError",
            ErrorKind::UnknownName => "UnknownNameError",
            ErrorKind::FileNotFound => "FileNotFound",
        }
    }

    fn doc(self) -> &'static str {
        match self {
            ErrorKind::Error => "Every error of muscle_actuator (a ValueError).",
            ErrorKind::Config => {
                "A bad configuration, override, stepping, rate or thread count; a bad scenario file."
            }
            ErrorKind::Input => {
                "Bad inputs: excitations, external torques, joint motions, tick counts or outputs \
                 of the wrong shape, type or value; nothing was changed."
            }
            ErrorKind::Step => {
                "A tick failed (the implicit solver did not converge, or the state became \
                 non-finite). Attributes: `tick` (the tick that failed), `reason`, and \
                 `instance` for a batch."
            }
            ErrorKind::Recording => "A recording that cannot be read (damaged, or not of this program).",
            ErrorKind::UnknownName => {
                "An unknown model, energy model, muscle, joint, output or scenario name (also a \
                 KeyError)."
            }
            ErrorKind::FileNotFound => {
                "A configuration, scenario or recording file that does not exist (also a \
                 FileNotFoundError)."
            }
        }
    }

    /// The class, made once per interpreter with `type(name, bases, namespace)` (a class with
    /// two built-in bases cannot be made by `create_exception!`).
    pub fn class(self, py: Python<'_>) -> PyResult<Bound<'_, PyType>> {
        static CLASSES: [PyOnceLock<Py<PyType>>; 7] = [const { PyOnceLock::new() }; 7];
        let slot = &CLASSES[self as usize];
        if let Some(c) = slot.get(py) {
            return Ok(c.bind(py).clone());
        }
        let base = |k: ErrorKind| k.class(py).map(|c| c.into_any());
        let bases = match self {
            ErrorKind::Error => PyTuple::new(py, [py.get_type::<PyValueError>().into_any()])?,
            ErrorKind::Config | ErrorKind::Input | ErrorKind::Recording => {
                PyTuple::new(py, [base(ErrorKind::Error)?])?
            }
            ErrorKind::Step => PyTuple::new(
                py,
                [
                    base(ErrorKind::Error)?,
                    py.get_type::<PyRuntimeError>().into_any(),
                ],
            )?,
            ErrorKind::UnknownName => PyTuple::new(
                py,
                [
                    base(ErrorKind::Error)?,
                    py.get_type::<PyKeyError>().into_any(),
                ],
            )?,
            ErrorKind::FileNotFound => PyTuple::new(
                py,
                [
                    base(ErrorKind::Error)?,
                    py.get_type::<PyFileNotFoundError>().into_any(),
                ],
            )?,
        };
        let ns = PyDict::new(py);
        ns.set_item("__module__", "muscle_actuator")?;
        ns.set_item("__doc__", self.doc())?;
        if self == ErrorKind::UnknownName {
            // KeyError's str() quotes the message; the message is shown as it is.
            ns.set_item(
                "__str__",
                py.get_type::<PyBaseException>().getattr("__str__")?,
            )?;
        }
        let class = py
            .get_type::<PyType>()
            .call1((self.name(), bases, ns))?
            .cast_into::<PyType>()?;
        Ok(slot.get_or_init(py, || class.unbind()).bind(py).clone())
    }

    /// An exception of this kind with `msg` (a `FileNotFound` also carries `errno` ENOENT).
    pub fn err(self, msg: impl Into<String>) -> PyErr {
        let msg: String = msg.into();
        Python::attach(|py| {
            let class = match self.class(py) {
                Ok(c) => c,
                Err(e) => return e,
            };
            let err = PyErr::from_type(class, msg);
            if self == ErrorKind::FileNotFound {
                // Setting an attribute of a new exception cannot fail but for memory; the
                // message carries the same fact.
                if let Ok(enoent) = py.import("errno").and_then(|m| m.getattr("ENOENT")) {
                    let _ = err.value(py).setattr("errno", enoent);
                }
            }
            err
        })
    }
}

pub fn config_error(msg: impl Into<String>) -> PyErr {
    ErrorKind::Config.err(msg)
}
pub fn input_error(msg: impl Into<String>) -> PyErr {
    ErrorKind::Input.err(msg)
}
pub fn unknown_name(msg: impl Into<String>) -> PyErr {
    ErrorKind::UnknownName.err(msg)
}

/// The `StepError` of a failed tick (of batch instance `instance`, if any).
pub fn step_error(py: Python<'_>, tick: u64, reason: &str, instance: Option<usize>) -> PyErr {
    let msg = match instance {
        Some(k) => format!("instance {k}: tick {tick} failed: {reason}"),
        None => format!("tick {tick} failed: {reason}"),
    };
    with_step_attributes(py, ErrorKind::Step.err(msg), tick, reason, instance)
}

/// `err` with the attributes of the failed tick: `tick`, `reason` and `instance`.
pub fn with_step_attributes(
    py: Python<'_>,
    err: PyErr,
    tick: u64,
    reason: &str,
    instance: Option<usize>,
) -> PyErr {
    let v = err.value(py);
    // Setting attributes on a new exception instance cannot fail but for memory; the message
    // carries the same facts.
    let _ = v.setattr("tick", tick);
    let _ = v.setattr("reason", reason);
    let _ = v.setattr("instance", instance);
    err
}
