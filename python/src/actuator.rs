//! `Actuator`: the crate's `sim::Actuator` from Python. Inputs are held over the ticks that
//! follow them (zero-order hold, as in the node); one call may advance many ticks, with the GIL
//! released, and record a trajectory of any outputs.

use crate::config::{build, BuildArgs};
use crate::error_kinds::py_err;
use crate::errors::{config_error, input_error, step_error, unknown_name, ErrorKind, CHUNK_TICKS};
use crate::inputs::{checked, float_array, per_name, Kind, Values};
use crate::outputs;
use muscle_actuator_core::sim::{rollout, Actuator, JointSnapshot, MuscleSnapshot, Record};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use std::sync::{Mutex, MutexGuard};

/// A limb of joints and muscles stepped at a fixed tick.
///
/// The actuator sits behind a mutex because a Python object may be reached from several threads
/// (its stepper caches are not `Sync`); the methods that step take `&mut self`, whose
/// `Mutex::get_mut` costs nothing.
#[pyclass(module = "muscle_actuator._core", name = "Actuator")]
pub struct PyActuator {
    inner: Mutex<Actuator>,
}

/// A saved state of an actuator (`Actuator.get_state`), for `set_state`; it pickles.
#[pyclass(module = "muscle_actuator._core", name = "ActuatorState", frozen)]
pub struct PyActuatorState {
    inner: Mutex<Actuator>,
}

/// The actuator behind a mutex, whether or not a panic poisoned it (every step leaves a
/// consistent state: a failed tick restores the previous one).
fn locked(m: &Mutex<Actuator>) -> MutexGuard<'_, Actuator> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl Clone for PyActuator {
    fn clone(&self) -> Self {
        Self::wrap(locked(&self.inner).clone())
    }
}

impl PyActuator {
    pub fn wrap(inner: Actuator) -> Self {
        Self {
            inner: Mutex::new(inner),
        }
    }

    /// The actuator, for a method that reads it.
    pub fn a(&self) -> MutexGuard<'_, Actuator> {
        locked(&self.inner)
    }

    /// The actuator, for a method that has the object exclusively.
    pub fn get_mut(&mut self) -> &mut Actuator {
        self.inner.get_mut().unwrap_or_else(|e| e.into_inner())
    }

    /// Steps `ticks` ticks with the inputs held; the GIL is released for long runs, and Python
    /// signals (Ctrl-C) are checked between chunks.
    pub fn advance(&mut self, py: Python<'_>, ticks: u64) -> PyResult<()> {
        let mut left = ticks;
        while left > 0 {
            let n = left.min(CHUNK_TICKS);
            let a = self.get_mut();
            let r = if n > 8 {
                py.detach(|| (0..n).try_for_each(|_| a.step()))
            } else {
                (0..n).try_for_each(|_| a.step())
            };
            r.map_err(|e| step_error(py, e.tick, e.reason, None))?;
            left -= n;
            if left > 0 {
                py.check_signals()?;
            }
        }
        Ok(())
    }

    /// Sets the excitations and external torques given (None: unchanged).
    pub fn set_inputs(
        &mut self,
        excitation: Option<&Bound<'_, PyAny>>,
        external_torque: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        // Both are checked before either is applied: a refused call changes nothing.
        let u = excitation
            .filter(|o| !o.is_none())
            .map(|o| per_name(o, self.a().muscle_names(), Kind::Excitation))
            .transpose()?;
        let tau = external_torque
            .filter(|o| !o.is_none())
            .map(|o| per_name(o, self.a().joint_names(), Kind::Torque))
            .transpose()?;
        if let Some(u) = u {
            apply(u, |i, v| self.get_mut().set_excitation(i, v));
        }
        if let Some(t) = tau {
            apply(t, |j, v| self.get_mut().set_external_torque(j, v));
        }
        Ok(())
    }

    fn joint_index(&self, joint: &Bound<'_, PyAny>) -> PyResult<usize> {
        let a = self.a();
        let names = a.joint_names();
        if let Ok(k) = joint.extract::<usize>() {
            if k < names.len() {
                return Ok(k);
            }
        } else if let Ok(n) = joint.extract::<String>() {
            if let Some(k) = names.iter().position(|j| *j == n) {
                return Ok(k);
            }
        }
        Err(unknown_name(format!(
            "unknown joint {}: expected one of {}",
            muscle_actuator_core::text::excerpt(&joint.to_string()),
            names.join(", ")
        )))
    }
}

fn apply(values: Values, mut set: impl FnMut(usize, f64)) {
    match values {
        Values::All(v) => v.into_iter().enumerate().for_each(|(i, x)| set(i, x)),
        Values::Named(v) => v.into_iter().for_each(|(i, x)| set(i, x)),
    }
}

fn ticks_of(ticks: i64) -> PyResult<u64> {
    u64::try_from(ticks).map_err(|_| input_error(format!("ticks = {ticks} must be >= 0")))
}

#[pymethods]
impl PyActuator {
    #[new]
    #[pyo3(signature = (config=None, model="huxley", rate_hz=1000.0, *, energy_model=None, substeps=None, overrides=None, tolerance=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        config: Option<&Bound<'_, PyAny>>,
        model: &str,
        rate_hz: f64,
        energy_model: Option<&str>,
        substeps: Option<i64>,
        overrides: Option<&Bound<'_, PyAny>>,
        tolerance: Option<f64>,
    ) -> PyResult<Self> {
        let args = BuildArgs {
            model,
            rate_hz,
            energy_model,
            substeps,
            tolerance,
        };
        Ok(Self::wrap(build(py, config, &args, overrides)?))
    }

    /// Muscle names, in configuration order.
    #[getter]
    fn muscles(&self) -> Vec<String> {
        self.a().muscle_names().to_vec()
    }
    /// Joint names, in configuration order.
    #[getter]
    fn joints(&self) -> Vec<String> {
        self.a().joint_names().to_vec()
    }
    /// Names of the driven joints (their motion an input, `set_joint_motion`).
    #[getter]
    fn driven_joints(&self) -> Vec<String> {
        let a = self.a();
        let names = a.joint_names();
        a.driven_joints()
            .iter()
            .map(|&j| names[j].clone())
            .collect()
    }
    /// The contractile model's name.
    #[getter]
    fn model(&self) -> &'static str {
        self.a().model().name()
    }
    /// Tick rate, Hz.
    #[getter]
    fn rate_hz(&self) -> f64 {
        self.a().rate_hz()
    }
    /// Ticks since start or reset.
    #[getter]
    fn tick(&self) -> u64 {
        self.a().tick()
    }
    /// Simulated time, s.
    #[getter]
    fn time(&self) -> f64 {
        self.a().time()
    }
    /// The configuration as a dict in the configuration file's form (every value resolved).
    #[getter]
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = toml::to_string(self.a().config())
            .map_err(|e| ErrorKind::Error.err(format!("configuration as TOML: {e}")))?;
        py.import("tomllib")?.getattr("loads")?.call1((text,))
    }
    /// The `MuscleState` field names (the per-muscle outputs), in message order.
    #[classattr]
    fn muscle_fields() -> Vec<&'static str> {
        MuscleSnapshot::FIELDS.to_vec()
    }
    /// The per-joint field names, in message order (as outputs: `joint.` + name).
    #[classattr]
    fn joint_fields() -> Vec<&'static str> {
        JointSnapshot::FIELDS.to_vec()
    }

    /// Holds `excitation` (muscles, in [0, 1]; clamped) and `external_torque` (joints, N m) —
    /// arrays in configuration order or dicts by name; None leaves them as they are — over the
    /// next `ticks` ticks, and steps them. A failed tick raises `StepError`; the ticks before it
    /// stand, and the state is that of the last good tick.
    #[pyo3(signature = (excitation=None, external_torque=None, ticks=1))]
    fn step(
        &mut self,
        py: Python<'_>,
        excitation: Option<&Bound<'_, PyAny>>,
        external_torque: Option<&Bound<'_, PyAny>>,
        ticks: i64,
    ) -> PyResult<()> {
        let ticks = ticks_of(ticks)?;
        self.set_inputs(excitation, external_torque)?;
        self.advance(py, ticks)
    }

    /// Steps one tick per row of `excitation` (ticks × muscles) and of `external_torque` (ticks
    /// × joints; None: as they are) and returns the chosen outputs after each tick, arrays of
    /// shape (ticks, muscles), (ticks, joints) or (ticks, joints, joints). A failed tick raises
    /// `StepError`; the actuator is then at the last good tick.
    #[pyo3(signature = (excitation, external_torque=None, outputs=None))]
    fn rollout<'py>(
        &mut self,
        py: Python<'py>,
        excitation: &Bound<'py, PyAny>,
        external_torque: Option<&Bound<'py, PyAny>>,
        outputs: Option<Vec<String>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let outputs = outputs::named(outputs)?;
        let (m, j) = {
            let a = self.get_mut();
            (a.muscle_names().len(), a.joint_names().len())
        };
        let u = float_array(excitation, "excitation")?;
        let u = checked(&u, "excitation", &[None, Some(m)], "ticks, muscles")?;
        let ticks = u.len() / m.max(1);
        let tau_arr = external_torque
            .filter(|o| !o.is_none())
            .map(|o| float_array(o, "external_torque"))
            .transpose()?;
        let tau = match &tau_arr {
            Some(a) => Some(checked(
                a,
                "external_torque",
                &[Some(ticks), Some(j)],
                "ticks, joints",
            )?),
            None => None,
        };
        let mut bufs = outputs::buffers(&outputs, ticks, m, j);
        let a = self.get_mut();
        let r = py.detach(|| rollout(a, &outputs, u, tau, ticks, &mut bufs));
        r.map_err(|e| step_error(py, e.tick, e.reason, None))?;
        outputs::into_dict(py, &outputs, bufs, &[ticks], m, j)
    }

    /// Back to the initial state (inputs zero, tick 0).
    fn reset(&mut self) {
        self.get_mut().reset();
    }

    /// The outputs named (None: all) after the last tick, a dict of arrays of shape (muscles,),
    /// (joints,) or (joints, joints).
    #[pyo3(signature = (outputs=None))]
    fn observe<'py>(
        &self,
        py: Python<'py>,
        outputs: Option<Vec<String>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let outputs = outputs::named(outputs)?;
        let a = self.a();
        let (m, j) = (a.muscle_names().len(), a.joint_names().len());
        let mut bufs = outputs::buffers(&outputs, 1, m, j);
        let widths = outputs.widths(m, j);
        let mut slices: Vec<&mut [f64]> = bufs.iter_mut().map(|b| b.as_mut_slice()).collect();
        outputs::write_tick(
            &outputs,
            &widths,
            &Record::of(0.0, a.state()),
            0,
            &mut slices,
        );
        drop(slices);
        drop(a);
        outputs::into_dict(py, &outputs, bufs, &[], m, j)
    }

    /// Every `MuscleState` field after the last tick: a dict of arrays, one value per muscle.
    #[getter]
    fn muscle_state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, f) in MuscleSnapshot::FIELDS.iter().enumerate() {
            let v: Vec<f64> = self.a().muscles().iter().map(|m| m.values()[k]).collect();
            d.set_item(f, PyArray1::from_vec(py, v))?;
        }
        Ok(d)
    }
    /// Every joint field after the last tick: a dict of arrays, one value per joint.
    #[getter]
    fn joint_state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, f) in JointSnapshot::FIELDS.iter().enumerate() {
            let v: Vec<f64> = self.a().joints().iter().map(|m| m.values()[k]).collect();
            d.set_item(f, PyArray1::from_vec(py, v))?;
        }
        Ok(d)
    }
    /// The joints' stiffness matrix K after the last tick, N m/rad, (joints, joints).
    #[getter]
    fn stiffness_matrix<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.a().joint_names().len();
        let k = self.a().state().stiffness_matrix.clone();
        Ok(PyArray1::from_vec(py, k).reshape([n, n])?.into_any())
    }

    /// Sets driven joint `joint`'s (name or index) angle (rad) and velocity (rad/s) at the next
    /// tick's start, extrapolated linearly over the tick and carried on until set again.
    #[pyo3(signature = (joint, angle, velocity=0.0))]
    fn set_joint_motion(
        &mut self,
        joint: &Bound<'_, PyAny>,
        angle: f64,
        velocity: f64,
    ) -> PyResult<()> {
        let k = self.joint_index(joint)?;
        let a = self.get_mut();
        if !a.driven_joints().contains(&k) {
            return Err(input_error(format!(
                "joint {:?} is not driven (driven = true in the configuration)",
                a.joint_names()[k]
            )));
        }
        if !(angle.is_finite() && velocity.is_finite()) {
            return Err(input_error(format!(
                "joint motion ({angle}, {velocity}) must be finite"
            )));
        }
        a.set_joint_motion(k, angle, velocity);
        Ok(())
    }
    /// The muscles' net torque on each driven joint after the last tick, N m (what a robot
    /// simulator that owns the joints applies), in the order of `driven_joints`.
    #[getter]
    fn joint_efforts<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.a().joint_efforts().collect())
    }

    /// A saved state (every bit a later tick reads), for `set_state`.
    fn get_state(&self) -> PyActuatorState {
        PyActuatorState {
            inner: Mutex::new(self.a().clone()),
        }
    }
    /// Back to a state `get_state` saved from an actuator of the same configuration, model,
    /// rate and stepping; the next ticks are then those that followed it, bit for bit.
    fn set_state(&mut self, state: &PyActuatorState) -> PyResult<()> {
        let b = locked(&state.inner);
        let a = self.a();
        if a.config() != b.config()
            || a.model() != b.model()
            || a.rate_hz() != b.rate_hz()
            || a.simulation().stepping() != b.simulation().stepping()
        {
            return Err(config_error(
                "the state is of an actuator with another configuration, model, rate or stepping",
            ));
        }
        let saved = b.clone();
        drop((a, b));
        *self.get_mut() = saved;
        Ok(())
    }

    fn copy(&self) -> Self {
        self.clone()
    }
    fn __copy__(&self) -> Self {
        self.clone()
    }
    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> Self {
        self.clone()
    }
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let bytes = PyBytes::new(py, &slf.borrow().a().to_bytes());
        let ctor = py.get_type::<Self>().getattr("_from_bytes")?;
        Ok((ctor, PyTuple::new(py, [bytes])?))
    }
    /// An actuator from the bytes of its pickle.
    #[staticmethod]
    fn _from_bytes(bytes: &[u8]) -> PyResult<Self> {
        Ok(Self::wrap(Actuator::from_bytes(bytes).map_err(py_err)?))
    }
    fn __repr__(&self) -> String {
        let a = self.a();
        format!(
            "Actuator(model={:?}, muscles={:?}, joints={:?}, rate_hz={}, tick={})",
            a.model().name(),
            a.muscle_names(),
            a.joint_names(),
            a.rate_hz(),
            a.tick()
        )
    }
}

#[pymethods]
impl PyActuatorState {
    /// Ticks done when it was saved.
    #[getter]
    fn tick(&self) -> u64 {
        locked(&self.inner).tick()
    }
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let bytes = PyBytes::new(py, &locked(&slf.get().inner).to_bytes());
        let ctor = py.get_type::<Self>().getattr("_from_bytes")?;
        Ok((ctor, PyTuple::new(py, [bytes])?))
    }
    #[staticmethod]
    fn _from_bytes(bytes: &[u8]) -> PyResult<Self> {
        Ok(Self {
            inner: Mutex::new(Actuator::from_bytes(bytes).map_err(py_err)?),
        })
    }
    fn __repr__(&self) -> String {
        let a = locked(&self.inner);
        format!(
            "ActuatorState(model={:?}, tick={})",
            a.model().name(),
            a.tick()
        )
    }
}
