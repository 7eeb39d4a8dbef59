//! Tests of the EMG module: the filters against SciPy's own (tables written by
//! scripts/scipy_emg_filters.py), the chain on a synthetic signal of known envelope, the
//! recursion against its closed form, the nonlinearity, and every refusal.

mod envelope_synthetic;
mod errors;
mod neural_recursion;
mod nonlinearity_curve;
mod scipy_reference;
