//! EMG to muscle activation, the signal side of an EMG-driven model (Lloyd & Besier 2003;
//! Pizzolato et al. 2015, CEINMS): pure functions and small state structs, no I/O.
//!
//! - [`butterworth`], [`sos`], [`filter`]: Butterworth low-, high- and band-pass filters as
//!   second-order sections, designed and applied as SciPy does (`butter`, `sosfilt`,
//!   `sosfiltfilt`), causal or zero-phase.
//! - [`error`]: why any of them refuses its input.

pub mod butterworth;
pub mod error;
pub mod filter;
pub mod sos;

pub use error::EmgError;

#[cfg(test)]
mod tests;
