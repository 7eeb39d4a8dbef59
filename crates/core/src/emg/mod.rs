//! EMG to muscle activation, the signal side of an EMG-driven model (Lloyd & Besier 2003;
//! Pizzolato et al. 2015, CEINMS): pure functions and small state structs, no I/O. The files
//! are the crate's modules; what other crates use of them is re-exported here.
//!
//! - `butterworth`, `sos`, `filter`: Butterworth low-, high- and band-pass filters as
//!   second-order sections, designed and applied as SciPy does (`butter`, `sosfilt`,
//!   `sosfiltfilt`), causal or zero-phase ([`butterworth()`], [`filter_zero_phase`],
//!   [`SosFilter`]).
//! - `envelope`: the raw-EMG chain: mean removed, band-pass, full-wave rectification, low-pass
//!   to a linear envelope, normalisation ([`linear_envelope`], [`EnvelopeOptions`]).
//! - `neural`: neural activation from the envelope, Lloyd & Besier's second-order recursion
//!   with its electromechanical delay ([`NeuralActivation`], [`neural_activation`]).
//! - `nonlinearity`: activation from neural activation, the exponential shape A
//!   ([`activation`], [`ShapeFactor`]).
//! - `error`: why any of them refuses its input ([`EmgError`]).

pub(crate) mod butterworth;
pub(crate) mod envelope;
pub(crate) mod error;
pub(crate) mod filter;
pub(crate) mod neural;
pub(crate) mod nonlinearity;
pub(crate) mod sos;

pub use self::{
    butterworth::{butterworth, Band, MAX_ORDER},
    envelope::{
        linear_envelope, linear_envelopes, BandPass, EnvelopeOptions, LowPass, Normalisation, Phase,
    },
    error::EmgError,
    filter::{filter_causal, filter_zero_phase, SosFilter},
    neural::{neural_activation, NeuralActivation, NeuralParams},
    nonlinearity::{activation, ShapeFactor},
    sos::{Section, Sos},
};

#[cfg(test)]
mod tests;
