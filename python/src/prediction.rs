//! `Prediction`: a subject driven through a trial, as Python sees it (docs/python.md
//! "Subjects"): arrays, ratings, DataFrames, and pickling for Ray workers.

use crate::errors::input_error;
use muscle_actuator_measured::measured::rating::rate;
use muscle_actuator_measured::subject::Prediction;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyImportError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// A pickled prediction's trial, model, clamped excitations and held lengths.
type Meta = (String, String, usize, usize);
/// A pickled prediction's times, units, forces, activations, fibre lengths, degrees of freedom,
/// moments and measured moments.
type Series = (
    Vec<f64>,
    Vec<String>,
    Vec<Vec<f64>>,
    Vec<Vec<f64>>,
    Vec<Vec<f64>>,
    Vec<String>,
    Vec<Vec<f64>>,
    Vec<Vec<f64>>,
);

/// A subject driven through a trial: moments, forces, activations and fibre lengths at the
/// trial's kinematic samples.
#[pyclass(module = "muscle_actuator._core", name = "Prediction", frozen)]
pub struct PyPrediction {
    pub(crate) p: Prediction,
    pub(crate) trial: String,
    pub(crate) model: String,
    pub(crate) clamped_excitations: usize,
    pub(crate) held_lengths: usize,
}

/// Rows of `series` (one per unit) as a 2-D array (units, samples).
fn rows<'py>(py: Python<'py>, series: &[Vec<f64>], samples: usize) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = series.iter().flatten().copied().collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([series.len(), samples])?
        .into_any())
}

/// Per name, its series as a 1-D array.
fn by_name<'py>(
    py: Python<'py>,
    names: &[String],
    series: &[Vec<f64>],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (n, s) in names.iter().zip(series) {
        d.set_item(n, PyArray1::from_slice(py, s))?;
    }
    Ok(d)
}

#[pymethods]
impl PyPrediction {
    /// The trial's name.
    #[getter]
    fn trial(&self) -> String {
        self.trial.clone()
    }
    /// The contractile model.
    #[getter]
    fn model(&self) -> String {
        self.model.clone()
    }
    /// Excitation samples above 1 that were clamped to 1.
    #[getter]
    fn clamped_excitations(&self) -> usize {
        self.clamped_excitations
    }
    /// Length samples beyond their unit's fibre's reach that were held at it (docs/emg.md
    /// "Prediction").
    #[getter]
    fn held_lengths(&self) -> usize {
        self.held_lengths
    }
    /// The kinematic samples' times, s.
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.p.times)
    }
    #[getter]
    fn dofs(&self) -> Vec<String> {
        self.p.dofs.clone()
    }
    #[getter]
    fn units(&self) -> Vec<String> {
        self.p.units.clone()
    }
    /// Per degree of freedom, the predicted moment `Σ F r`, N m.
    #[getter]
    fn moment<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        by_name(py, &self.p.dofs, &self.p.moment)
    }
    /// Per degree of freedom, the measured (inverse-dynamics) moment, N m.
    #[getter]
    fn measured<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        by_name(py, &self.p.dofs, &self.p.measured)
    }
    /// Tendon forces, N, (units, samples).
    #[getter]
    fn force<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        rows(py, &self.p.force, self.p.times.len())
    }
    /// Activations, (units, samples).
    #[getter]
    fn activation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        rows(py, &self.p.activation, self.p.times.len())
    }
    /// Fibre lengths, m, (units, samples).
    #[getter]
    fn fibre_length<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        rows(py, &self.p.fibre_length, self.p.times.len())
    }
    /// Per degree of freedom, the rating of the predicted moment against the measured one:
    /// `r2` (coefficient of determination), `pearson_r2`, `rmse` (N m), `rmse_over_peak`.
    fn ratings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for (dof, (m, q)) in self
            .p
            .dofs
            .iter()
            .zip(self.p.measured.iter().zip(&self.p.moment))
        {
            let r = rate(m, q).map_err(|e| input_error(format!("{dof}: {e}")))?;
            let d = PyDict::new(py);
            d.set_item("r2", r.r_squared)?;
            d.set_item("pearson_r2", r.pearson_r_squared)?;
            d.set_item("rmse", r.rmse)?;
            d.set_item("rmse_over_peak", r.rmse_over_peak)?;
            out.set_item(dof, d)?;
        }
        Ok(out)
    }
    /// Two DataFrames with the command line's CSV columns: the moments (`time`, `<dof>`,
    /// `<dof>_measured`) and the units (`time`, `<unit>.force`, `<unit>.activation`,
    /// `<unit>.fibre_length`). Needs pandas.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let pd = py.import("pandas").map_err(|e| {
            let err =
                PyImportError::new_err("Prediction.to_pandas needs pandas: pip install pandas");
            err.set_cause(py, Some(e));
            err
        })?;
        let moments = PyDict::new(py);
        moments.set_item("time", self.time(py))?;
        for (d, (q, m)) in self
            .p
            .dofs
            .iter()
            .zip(self.p.moment.iter().zip(&self.p.measured))
        {
            moments.set_item(d, PyArray1::from_slice(py, q))?;
            moments.set_item(format!("{d}_measured"), PyArray1::from_slice(py, m))?;
        }
        let muscles = PyDict::new(py);
        muscles.set_item("time", self.time(py))?;
        for (i, u) in self.p.units.iter().enumerate() {
            muscles.set_item(
                format!("{u}.force"),
                PyArray1::from_slice(py, &self.p.force[i]),
            )?;
            let a = PyArray1::from_slice(py, &self.p.activation[i]);
            muscles.set_item(format!("{u}.activation"), a)?;
            let l = PyArray1::from_slice(py, &self.p.fibre_length[i]);
            muscles.set_item(format!("{u}.fibre_length"), l)?;
        }
        let frame = pd.getattr("DataFrame")?;
        Ok((frame.call1((moments,))?, frame.call1((muscles,))?))
    }
    /// Pickles as its fields (`_from_state` checks them back): a prediction made on a Ray
    /// worker or in another process arrives whole.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let me = slf.get();
        let p = &me.p;
        let meta = (
            me.trial.clone(),
            me.model.clone(),
            me.clamped_excitations,
            me.held_lengths,
        );
        let series = (
            p.times.clone(),
            p.units.clone(),
            p.force.clone(),
            p.activation.clone(),
            p.fibre_length.clone(),
            p.dofs.clone(),
            p.moment.clone(),
            p.measured.clone(),
        );
        let state = (meta, series).into_pyobject(py)?;
        let ctor = py.get_type::<Self>().getattr("_from_state")?;
        Ok((ctor, PyTuple::new(py, [state])?))
    }
    /// A prediction from the state `__reduce__` gives, its shapes checked, its times rising and
    /// every value finite.
    #[staticmethod]
    fn _from_state(state: &Bound<'_, PyAny>) -> PyResult<Self> {
        let bad = |what: &str| input_error(format!("not a Prediction's pickled state: {what}"));
        let (meta, series): (Meta, Series) = state.extract().map_err(|_| bad("its layout"))?;
        let (trial, model, clamped_excitations, held_lengths) = meta;
        let (times, units, force, activation, fibre_length, dofs, moment, measured) = series;
        let n = times.len();
        let per_unit = [&force, &activation, &fibre_length];
        if per_unit.iter().any(|s| s.len() != units.len()) {
            return Err(bad("a series per unit"));
        }
        if moment.len() != dofs.len() || measured.len() != dofs.len() {
            return Err(bad("a series per degree of freedom"));
        }
        let all = per_unit.into_iter().chain([&moment, &measured]);
        if all.clone().flatten().any(|s| s.len() != n) {
            return Err(bad("a sample per time"));
        }
        if times.iter().any(|t| !t.is_finite()) || times.windows(2).any(|w| w[0] >= w[1]) {
            return Err(bad("times that rise, each finite"));
        }
        if all.flatten().flatten().any(|x| !x.is_finite()) {
            return Err(bad("finite values"));
        }
        Ok(PyPrediction {
            p: Prediction {
                times,
                units,
                force,
                activation,
                fibre_length,
                dofs,
                moment,
                measured,
            },
            trial,
            model,
            clamped_excitations,
            held_lengths,
        })
    }
    fn __repr__(&self) -> String {
        format!(
            "Prediction(trial {:?}, {}, {} samples, dofs [{}], {} units)",
            self.trial,
            self.model,
            self.p.times.len(),
            self.p.dofs.join(", "),
            self.p.units.len()
        )
    }
}
