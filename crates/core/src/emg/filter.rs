//! Filtering by second-order sections: causal, sample by sample ([`SosFilter`], for online use) or
//! over a whole signal ([`filter_causal`], `scipy.signal.sosfilt`), and zero-phase forward and
//! backward over a whole signal ([`filter_zero_phase`], `scipy.signal.sosfiltfilt` with its
//! defaults: odd extension of 3 (2 n_sections + 1 − first-order sections) samples at each end,
//! each pass started in the steady state of its first sample, `scipy.signal.sosfilt_zi`).
//!
//! The filters are written here rather than taken from a crate. Of the crates checked (sci-rs
//! 0.4.1, biquad 0.6.0, idsp 0.23.1), only sci-rs designs Butterworth filters of any order and
//! band and filters forward and backward, and it panics on short signals and other inputs
//! (`assert!`, `unwrap`, `expect` in its padding, `lfilter_zi` and `zpk2sos`) and brings a
//! second nalgebra (0.33) with ndarray, lstsq, kalmanfilt and gaussfilt; biquad designs single
//! RBJ-cookbook biquads (no Butterworth of order N, no band-pass of SciPy's design, no
//! zero-phase filtering); idsp is fixed-point IIR for embedded targets with no Butterworth design.

use crate::emg::error::{check_finite, EmgError};
use crate::emg::sos::{Section, Sos};

/// One section's two delay-line values (direct form II transposed).
type State = [f64; 2];

/// Direct form II transposed through one section: returns the output and updates its state
/// (`scipy.signal.sosfilt`'s inner step; Oppenheim & Schafer 2010, direct form II
/// transposed).
fn section_step(s: &Section, state: &mut State, x: f64) -> f64 {
    let y = s.b[0] * x + state[0];
    state[0] = s.b[1] * x - s.a[1] * y + state[1];
    state[1] = s.b[2] * x - s.a[2] * y;
    y
}

/// One sample through every section, first to last.
fn cascade_step(sos: &Sos, states: &mut [State], x: f64) -> f64 {
    sos.sections()
        .iter()
        .zip(states.iter_mut())
        .fold(x, |v, (s, st)| section_step(s, st, v))
}

/// One section's state in the steady state of a unit step (`scipy.signal.lfilter_zi` for a
/// second-order section): the solution of `zi = Aᵀ zi + B`, with `B = b[1:] - a[1:] b0`, is
/// `zi0 = (B0 + B1)/(1 + a1 + a2)`, `zi1 = B1 - a2 zi0`.
fn section_steady_state(s: &Section) -> State {
    let b0 = s.b[1] - s.a[1] * s.b[0];
    let b1 = s.b[2] - s.a[2] * s.b[0];
    let zi0 = (b0 + b1) / (1.0 + s.a[1] + s.a[2]);
    [zi0, b1 - s.a[2] * zi0]
}

/// The sections' states in the steady state of a unit step (`scipy.signal.sosfilt_zi`): each
/// section's own, scaled by the DC gain `Σb/Σa` of the sections before it.
pub(crate) fn steady_state(sos: &Sos) -> Vec<[f64; 2]> {
    let mut scale = 1.0;
    sos.sections()
        .iter()
        .map(|s| {
            let zi = section_steady_state(s);
            let out = [scale * zi[0], scale * zi[1]];
            scale *= s.b.iter().sum::<f64>() / s.a.iter().sum::<f64>();
            out
        })
        .collect()
}

/// Samples of odd extension at each end for the zero-phase filter, SciPy's default
/// `3 (2 n_sections + 1 - min(#b2 = 0, #a2 = 0))`.
pub(crate) fn pad_len(sos: &Sos) -> usize {
    let n = sos.sections().len();
    let b_zeros = sos.sections().iter().filter(|s| s.b[2] == 0.0).count();
    let a_zeros = sos.sections().iter().filter(|s| s.a[2] == 0.0).count();
    3 * (2 * n + 1 - b_zeros.min(a_zeros))
}

/// A causal filter stepped one sample at a time, its state kept between calls; it allocates
/// only when made.
#[derive(Debug, Clone)]
pub struct SosFilter {
    sos: Sos,
    states: Vec<State>,
    steady: Vec<State>,
}

impl SosFilter {
    /// The filter at rest (zero state), as `scipy.signal.sosfilt` starts.
    pub fn new(sos: Sos) -> Self {
        let steady = steady_state(&sos);
        let states = vec![[0.0; 2]; sos.sections().len()];
        SosFilter {
            sos,
            states,
            steady,
        }
    }

    /// The next output for input `x`. A NaN or infinite input makes this and later outputs NaN
    /// until [`reset`](Self::reset) or [`settle`](Self::settle).
    pub fn step(&mut self, x: f64) -> f64 {
        cascade_step(&self.sos, &mut self.states, x)
    }

    /// Back to rest (zero state).
    pub fn reset(&mut self) {
        self.states.iter_mut().for_each(|s| *s = [0.0; 2]);
    }

    /// The state of a filter that has seen `x` for ever: its next output for `x` is its DC
    /// gain times `x` (`sosfilt_zi · x`).
    pub fn settle(&mut self, x: f64) {
        for (s, zi) in self.states.iter_mut().zip(&self.steady) {
            *s = [zi[0] * x, zi[1] * x];
        }
    }

    /// The sections.
    pub fn sos(&self) -> &Sos {
        &self.sos
    }
}

/// `x` filtered causally from rest (`scipy.signal.sosfilt(sos, x)`); refuses a non-finite
/// sample.
pub fn filter_causal(sos: &Sos, x: &[f64]) -> Result<Vec<f64>, EmgError> {
    check_finite(x)?;
    let mut states = vec![[0.0; 2]; sos.sections().len()];
    Ok(x.iter()
        .map(|&v| cascade_step(sos, &mut states, v))
        .collect())
}

/// `x` with `edge` samples of odd extension at each end: `2 x[0] - x[edge..0]` before,
/// `2 x[n-1] - x[n-2..n-2-edge]` after (`scipy.signal._arraytools.odd_ext`); `x.len() > edge`.
fn odd_extension(x: &[f64], edge: usize) -> Vec<f64> {
    let n = x.len();
    let (first, last) = (x[0], x[n - 1]);
    let before = (1..=edge).rev().map(|i| 2.0 * first - x[i]);
    let after = (1..=edge).map(|i| 2.0 * last - x[n - 1 - i]);
    before.chain(x.iter().copied()).chain(after).collect()
}

/// One causal pass over `x` from the steady state of its first sample.
fn pass_from_steady(sos: &Sos, zi: &[State], x: &[f64]) -> Vec<f64> {
    let x0 = x.first().copied().unwrap_or(0.0);
    let mut states: Vec<State> = zi.iter().map(|z| [z[0] * x0, z[1] * x0]).collect();
    x.iter()
        .map(|&v| cascade_step(sos, &mut states, v))
        .collect()
}

/// `x` filtered forward then backward, so with no phase shift and the magnitude response
/// squared (`scipy.signal.sosfiltfilt(sos, x)`, its default padding and initial conditions).
/// Needs more samples than `pad_len`; refuses a non-finite sample.
pub fn filter_zero_phase(sos: &Sos, x: &[f64]) -> Result<Vec<f64>, EmgError> {
    check_finite(x)?;
    let edge = pad_len(sos);
    if x.len() <= edge {
        return Err(EmgError::TooShort {
            len: x.len(),
            needed: edge + 1,
        });
    }
    let zi = steady_state(sos);
    let ext = odd_extension(x, edge);
    let mut y = pass_from_steady(sos, &zi, &ext);
    y.reverse();
    let mut y = pass_from_steady(sos, &zi, &y);
    y.reverse();
    Ok(y[edge..edge + x.len()].to_vec())
}
