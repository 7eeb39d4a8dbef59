//! EMG from Python (docs/python.md "Subjects, EMG and calibration"): the crate's raw-EMG chain
//! (`emg::envelope`: mean removed, Butterworth band-pass, rectified, low-pass, normalised) and
//! Lloyd & Besier's activation (`emg::neural`, the recursion with its delay, then
//! `emg::nonlinearity`, the shape factor), on one signal `(samples,)` or several
//! `(signals, samples)`, with the GIL released.

use crate::config::count;
use crate::error_kinds::py_err;
use crate::errors::{config_error, input_error, unknown_name};
use crate::inputs::{checked, float_array};
use muscle_actuator_core::emg::{
    activation, linear_envelopes, neural_activation, BandPass, EmgError, EnvelopeOptions, LowPass,
    NeuralParams, Normalisation, Phase, ShapeFactor,
};
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

/// The phases by name.
const PHASES: [(&str, Phase); 2] = [("zero-phase", Phase::ZeroPhase), ("causal", Phase::Causal)];
/// The normalisation by the signals' own peak, by name.
const SIGNAL_PEAK: &str = "signal-peak";

/// The rows of `obj`: one signal (samples,) or several (signals, samples), every sample finite;
/// the values (C order), the rows' count and length, and the shape.
fn signals(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<f64>, usize, usize, Vec<usize>)> {
    let a = float_array(obj, what)?;
    let shape = a.shape().to_vec();
    let values = match shape.len() {
        1 => checked(&a, what, &[None], "samples")?,
        _ => checked(&a, what, &[None, None], "signals, samples")?,
    }
    .to_vec();
    let (n, samples) = match shape[..] {
        [s] => (1, s),
        [n, s] => (n, s),
        _ => (0, 0),
    };
    Ok((values, n, samples, shape))
}

/// The `n` rows of `samples` values each of `values`.
fn rows_of(values: &[f64], n: usize, samples: usize) -> Vec<&[f64]> {
    (0..n)
        .map(|k| &values[k * samples..(k + 1) * samples])
        .collect()
}

/// `rows` (each of the same length) as an array of `shape`.
fn shaped<'py>(
    py: Python<'py>,
    rows: Vec<Vec<f64>>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = rows.into_iter().flatten().collect();
    Ok(PyArray1::from_vec(py, flat).reshape(shape)?.into_any())
}

/// The phase named `name`.
fn phase_of(name: &str) -> PyResult<Phase> {
    PHASES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, p)| *p)
        .ok_or_else(|| {
            unknown_name(format!(
                "unknown phase {:?}: expected zero-phase or causal",
                muscle_actuator_core::text::excerpt(name)
            ))
        })
}

/// The normalisation of `obj`: None or "none", "signal-peak", or a number (an MVC peak).
fn normalisation_of(obj: &Bound<'_, PyAny>) -> PyResult<Normalisation> {
    if obj.is_none() {
        return Ok(Normalisation::None);
    }
    if obj.is_instance_of::<PyString>() {
        let name: String = obj.extract()?;
        return match name.as_str() {
            "none" => Ok(Normalisation::None),
            SIGNAL_PEAK => Ok(Normalisation::SignalPeak),
            _ => Err(unknown_name(format!(
                "unknown normalisation {:?}: expected signal-peak, none or a number (an MVC peak)",
                muscle_actuator_core::text::excerpt(&name)
            ))),
        };
    }
    obj.extract::<f64>()
        .map(Normalisation::MvcPeak)
        .map_err(|_| input_error("normalisation must be \"signal-peak\", None or a number"))
}

/// The chain's options from the arguments of `emg_envelope`.
#[allow(clippy::too_many_arguments)]
fn options(
    remove_mean: bool,
    band_pass: Option<(f64, f64)>,
    band_pass_order: i64,
    low_pass_hz: f64,
    low_pass_order: i64,
    phase: &str,
    normalisation: &Bound<'_, PyAny>,
) -> PyResult<EnvelopeOptions> {
    let band_pass_order = count("band_pass_order", band_pass_order)?;
    Ok(EnvelopeOptions {
        remove_mean,
        band_pass: band_pass.map(|(low_hz, high_hz)| BandPass {
            low_hz,
            high_hz,
            order: band_pass_order,
        }),
        low_pass: LowPass {
            cut_off_hz: low_pass_hz,
            order: count("low_pass_order", low_pass_order)?,
        },
        phase: phase_of(phase)?,
        normalisation: normalisation_of(normalisation)?,
    })
}

/// The normalised linear envelope(s) of raw EMG sampled at `rate_hz` (`emg_envelope`).
#[pyfunction]
#[pyo3(signature = (raw, rate_hz, remove_mean, band_pass, band_pass_order, low_pass_hz, low_pass_order, phase, normalisation))]
#[allow(clippy::too_many_arguments)]
pub fn _emg_envelope<'py>(
    py: Python<'py>,
    raw: &Bound<'py, PyAny>,
    rate_hz: f64,
    remove_mean: bool,
    band_pass: Option<(f64, f64)>,
    band_pass_order: i64,
    low_pass_hz: f64,
    low_pass_order: i64,
    phase: &str,
    normalisation: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let options = options(
        remove_mean,
        band_pass,
        band_pass_order,
        low_pass_hz,
        low_pass_order,
        phase,
        normalisation,
    )?;
    let (values, n, samples, shape) = signals(raw, "raw")?;
    let rows = py
        .detach(|| linear_envelopes(&rows_of(&values, n, samples), rate_hz, &options))
        .map_err(py_err)?;
    shaped(py, rows, &shape)
}

/// The chain's defaults (`EnvelopeOptions::default()`) under `emg_envelope`'s keywords.
#[pyfunction]
pub fn _emg_envelope_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let o = EnvelopeOptions::default();
    let d = PyDict::new(py);
    d.set_item("remove_mean", o.remove_mean)?;
    d.set_item("band_pass", o.band_pass.map(|b| (b.low_hz, b.high_hz)))?;
    d.set_item("band_pass_order", o.band_pass.map_or(0, |b| b.order))?;
    d.set_item("low_pass_hz", o.low_pass.cut_off_hz)?;
    d.set_item("low_pass_order", o.low_pass.order)?;
    let phase = PHASES.iter().find(|(_, p)| *p == o.phase).map(|(n, _)| *n);
    d.set_item("phase", phase)?;
    match o.normalisation {
        Normalisation::None => d.set_item("normalisation", py.None())?,
        Normalisation::SignalPeak => d.set_item("normalisation", SIGNAL_PEAK)?,
        Normalisation::MvcPeak(v) => d.set_item("normalisation", v)?,
    }
    Ok(d)
}

/// One signal's activation: the recursion from rest, then the nonlinearity.
fn activation_of(
    e: &[f64],
    params: NeuralParams,
    shape: ShapeFactor,
    delay: usize,
) -> Result<Vec<f64>, EmgError> {
    Ok(neural_activation(e, params, delay)?
        .into_iter()
        .map(|u| activation(u, shape))
        .collect())
}

/// Lloyd & Besier's activation of excitation(s) in [0, 1], one per sample: the second-order
/// recursion with C1, C2 and a delay of `delay_samples` samples, from rest, then the
/// nonlinearity of shape factor A (`neural_activation`).
#[pyfunction]
#[pyo3(signature = (excitation, c1, c2, shape_factor, delay_samples=0))]
pub fn _neural_activation<'py>(
    py: Python<'py>,
    excitation: &Bound<'py, PyAny>,
    c1: f64,
    c2: f64,
    shape_factor: f64,
    delay_samples: i64,
) -> PyResult<Bound<'py, PyAny>> {
    let params = NeuralParams::new(c1, c2).map_err(py_err)?;
    let shape = ShapeFactor::new(shape_factor).map_err(py_err)?;
    let delay = usize::try_from(delay_samples)
        .map_err(|_| config_error(format!("delay_samples = {delay_samples} must be >= 0")))?;
    let (values, n, samples, dims) = signals(excitation, "excitation")?;
    let rows = py
        .detach(|| {
            rows_of(&values, n, samples)
                .into_iter()
                .map(|e| activation_of(e, params, shape, delay))
                .collect::<Result<Vec<_>, _>>()
        })
        .map_err(py_err)?;
    shaped(py, rows, &dims)
}
