//! Tests of the EMG module: the filters against SciPy's own (tables written by
//! scripts/scipy_emg_filters.py).

mod scipy_reference;
