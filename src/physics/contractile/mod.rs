//! Contractile elements: Hill-type, and Huxley-type cross-bridges (Distribution-Moment and full).

pub mod calibration;
pub mod crossbridge;
pub mod distribution_moment;
pub mod force_length;
pub mod hill;
pub mod huxley_exact;
pub mod huxley_grid;
