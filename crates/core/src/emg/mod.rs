//! EMG to muscle activation, the signal side of an EMG-driven model (Lloyd & Besier 2003;
//! Pizzolato et al. 2015, CEINMS): pure functions and small state structs, no I/O.
//!
//! - [`butterworth`], [`sos`], [`filter`]: Butterworth low-, high- and band-pass filters as
//!   second-order sections, designed and applied as SciPy does (`butter`, `sosfilt`,
//!   `sosfiltfilt`), causal or zero-phase.
//! - [`envelope`]: the raw-EMG chain: mean removed, band-pass, full-wave rectification, low-pass
//!   to a linear envelope, normalisation.
//! - [`neural`]: neural activation from the envelope, Lloyd & Besier's second-order recursion
//!   with its electromechanical delay.
//! - [`nonlinearity`]: activation from neural activation, the exponential shape A.
//! - [`error`]: why any of them refuses its input.

pub mod butterworth;
pub mod envelope;
pub mod error;
pub mod filter;
pub mod neural;
pub mod nonlinearity;
pub mod sos;

pub use error::EmgError;

#[cfg(test)]
mod tests;
