//! Batched stepping: B independent actuators, each with its own inputs (and parameters), over T
//! ticks, on a pool of threads with the GIL released. Each actuator is stepped alone, in order,
//! by one thread, so the results are those of stepping it by itself, whatever the thread count.

use crate::actuator::PyActuator;
use crate::config::{build, BuildArgs};
use crate::errors::{config_error, input_error, step_error, ErrorKind};
use crate::inputs::{checked, float_array};
use crate::outputs;
use muscle_actuator_core::sim::{rollout as run_one, Actuator, StepError};
use numpy::PyUntypedArrayMethods;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;
use std::sync::{Arc, Mutex, OnceLock};

/// The worker threads: `threads` (None: one per core), at least 1. A pool of each size is
/// started once and kept (the last 4 sizes asked for), so that a call does not pay for starting
/// threads.
fn pool(threads: Option<i64>) -> PyResult<Arc<rayon::ThreadPool>> {
    /// The pools kept, by their number of threads.
    type Pools = Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>>;
    static POOLS: OnceLock<Pools> = OnceLock::new();
    let n = match threads
        .map(|t| crate::config::count("threads", t))
        .transpose()?
    {
        Some(0) => return Err(config_error("threads = 0 must be >= 1")),
        Some(n) => n.min(1024),
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let mut pools = POOLS
        .get_or_init(|| Mutex::new(Vec::new()))
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some((_, p)) = pools.iter().find(|(k, _)| *k == n) {
        return Ok(p.clone());
    }
    let p = rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .map_err(|e| PyOSError::new_err(format!("cannot start {n} threads: {e}")))?;
    let p = Arc::new(p);
    if pools.len() >= 4 {
        pools.remove(0);
    }
    pools.push((n, p.clone()));
    Ok(p)
}

/// Steps the actuators (all of the same muscles and joints) over the inputs and returns the
/// outputs as arrays (B, T, …). The first failed tick (lowest instance) raises `StepError`.
fn run_batch<'py>(
    py: Python<'py>,
    actuators: &mut [&mut Actuator],
    excitation: &Bound<'py, PyAny>,
    external_torque: Option<&Bound<'py, PyAny>>,
    outputs: Option<Vec<String>>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyDict>> {
    let outputs = outputs::named(outputs)?;
    let b = actuators.len();
    let (m, j) = (
        actuators[0].muscle_names().len(),
        actuators[0].joint_names().len(),
    );
    let u = float_array(excitation, "excitation")?;
    let u = checked(
        &u,
        "excitation",
        &[Some(b), None, Some(m)],
        "instances, ticks, muscles",
    )?;
    let ticks = u.len() / (b * m).max(1);
    let tau_arr = external_torque
        .filter(|o| !o.is_none())
        .map(|o| float_array(o, "external_torque"))
        .transpose()?;
    let tau = match &tau_arr {
        Some(a) => Some(checked(
            a,
            "external_torque",
            &[Some(b), Some(ticks), Some(j)],
            "instances, ticks, joints",
        )?),
        None => None,
    };
    let widths = outputs.widths(m, j);
    let mut bufs = outputs::buffers(&outputs, b * ticks, m, j);
    // Per instance, its slice of every output buffer (empty ones too, so that the k-th slice is
    // always the k-th output's).
    let mut per: Vec<Vec<&mut [f64]>> = (0..b).map(|_| Vec::with_capacity(widths.len())).collect();
    for (buf, w) in bufs.iter_mut().zip(&widths) {
        let mut rest = buf.as_mut_slice();
        for slices in per.iter_mut() {
            let (mine, after) = rest.split_at_mut(ticks * w);
            slices.push(mine);
            rest = after;
        }
    }
    let pool = pool(threads)?;
    let outputs_ref = &outputs;
    let results: Vec<Result<(), StepError>> = py.detach(|| {
        pool.install(|| {
            actuators
                .par_iter_mut()
                .zip(per.par_iter_mut())
                .enumerate()
                .map(|(k, (a, slices))| {
                    let uk = &u[k * ticks * m..(k + 1) * ticks * m];
                    let tk = tau.map(|t| &t[k * ticks * j..(k + 1) * ticks * j]);
                    run_one(a, outputs_ref, uk, tk, ticks, slices)
                })
                .collect()
        })
    });
    drop(per);
    if let Some((k, e)) = results
        .into_iter()
        .enumerate()
        .find_map(|(k, r)| r.err().map(|e| (k, e)))
    {
        return Err(step_error(py, e.tick, e.reason, Some(k)));
    }
    outputs::into_dict(py, &outputs, bufs, &[b, ticks], m, j)
}

/// `err` (of building instance `k`) with "instance k: " before its message, of the same class.
fn with_instance(py: Python<'_>, err: PyErr, k: usize) -> PyErr {
    let msg = format!("instance {k}: {}", err.value(py));
    match pyo3::types::PyTuple::new(py, [msg.as_str()])
        .and_then(|args| err.value(py).setattr("args", args))
    {
        Ok(()) => err,
        Err(_) => ErrorKind::Error.err(msg),
    }
}

/// `rollout` of new actuators: B built from one configuration, each with its own overrides.
#[pyfunction]
#[pyo3(signature = (config, model, excitation, external_torque=None, *, rate_hz=1000.0, energy_model=None, substeps=None, overrides=None, outputs=None, threads=None, tolerance=None))]
#[allow(clippy::too_many_arguments)]
pub fn _rollout_new<'py>(
    py: Python<'py>,
    config: Option<&Bound<'py, PyAny>>,
    model: &str,
    excitation: &Bound<'py, PyAny>,
    external_torque: Option<&Bound<'py, PyAny>>,
    rate_hz: f64,
    energy_model: Option<&str>,
    substeps: Option<i64>,
    overrides: Option<&Bound<'py, PyAny>>,
    outputs: Option<Vec<String>>,
    threads: Option<i64>,
    tolerance: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let b = batch_size(excitation)?;
    let per_instance: Vec<Option<Bound<'py, PyAny>>> = match overrides.filter(|o| !o.is_none()) {
        None => vec![None; b],
        Some(o) => {
            let list = o
                .cast::<PyList>()
                .map_err(|_| config_error("overrides must be a list of dicts, one per instance"))?;
            if list.len() != b {
                return Err(config_error(format!(
                    "overrides has {} entries: expected one per instance ({b})",
                    list.len()
                )));
            }
            list.iter().map(Some).collect()
        }
    };
    let args = BuildArgs {
        model,
        rate_hz,
        energy_model,
        substeps,
        tolerance,
    };
    let mut built = Vec::with_capacity(b);
    for (k, o) in per_instance.iter().enumerate() {
        let a = build(py, config, &args, o.as_ref()).map_err(|e| with_instance(py, e, k))?;
        built.push(a);
    }
    if built
        .iter()
        .any(|a| a.muscle_names() != built[0].muscle_names())
    {
        return Err(config_error(
            "every instance must have the same muscles and joints",
        ));
    }
    let mut refs: Vec<&mut Actuator> = built.iter_mut().collect();
    run_batch(py, &mut refs, excitation, external_torque, outputs, threads)
}

/// `rollout` of existing actuators, advanced in place.
#[pyfunction]
#[pyo3(signature = (actuators, excitation, external_torque=None, *, outputs=None, threads=None))]
pub fn _rollout_actuators<'py>(
    py: Python<'py>,
    actuators: Vec<Bound<'py, PyActuator>>,
    excitation: &Bound<'py, PyAny>,
    external_torque: Option<&Bound<'py, PyAny>>,
    outputs: Option<Vec<String>>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyDict>> {
    if actuators.is_empty() {
        return Err(input_error("no actuators given"));
    }
    let mut guards = Vec::with_capacity(actuators.len());
    for (k, a) in actuators.iter().enumerate() {
        guards.push(
            a.try_borrow_mut()
                .map_err(|_| input_error(format!("actuator {k} is given twice (or is in use)")))?,
        );
    }
    let names = |g: &mut PyRefMut<'_, PyActuator>| {
        let a = g.get_mut();
        (a.muscle_names().to_vec(), a.joint_names().to_vec())
    };
    let first = names(&mut guards[0]);
    if guards.iter_mut().any(|g| names(g) != first) {
        return Err(config_error(
            "every actuator must have the same muscles and joints",
        ));
    }
    let mut refs: Vec<&mut Actuator> = guards.iter_mut().map(|g| g.get_mut()).collect();
    run_batch(py, &mut refs, excitation, external_torque, outputs, threads)
}

/// The number of instances: the leading extent of `excitation`.
fn batch_size(excitation: &Bound<'_, PyAny>) -> PyResult<usize> {
    let a = float_array(excitation, "excitation")?;
    let shape = a.shape().to_vec();
    match shape.as_slice() {
        [b, _, _] if *b > 0 => Ok(*b),
        _ => Err(input_error(format!(
            "excitation has shape {shape:?}: expected [instances, ticks, muscles] with instances >= 1"
        ))),
    }
}
