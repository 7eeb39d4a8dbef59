//! Neural activation u from the normalised EMG envelope e, Lloyd & Besier's (2003)
//! second-order recursion, once per sample k:
//!
//! `u_k = α e_{k-d} - β1 u_{k-1} - β2 u_{k-2}`, `β1 = C1 + C2`, `β2 = C1 C2`,
//! `α = 1 + β1 + β2`,
//!
//! with |C1| < 1 and |C2| < 1. α makes the steady-state gain 1 (a constant e gives u = e). The
//! characteristic polynomial `z² + β1 z + β2 = (z + C1)(z + C2)` has the real roots -C1 and
//! -C2, inside the unit circle by the bounds, so the recursion is stable; C1 = C2 is the
//! critically damped case (a repeated root). A positive C puts its root on the negative real
//! axis: a mode that alternates in sign from sample to sample. The electromechanical delay d is
//! a whole number of samples.
//!
//! CEINMS (Pizzolato et al. 2015; its sources, repository CEINMS/CEINMS, read for this):
//! in `lib/NMSmodel/Activation/ExponentialActivation.cpp`,
//! `setFilterParameters` sets β1 = c1 + c2, β2 = c1 c2, α = 1 + β1 + β2, and `updateActivation`
//! runs the same recursion (the current sample, no delay inside). It bounds neither coefficient
//! in the model; its calibration bounds each one on its own, in an absolute range: [-0.995,
//! -0.005] in `lib/Calibration/SimAnnealParameters/StrengthCoefficients_ShapeFactor_C1_C2_
//! TendonSlackLength_single.cpp`, [-0.95, -0.05] in its test calibration
//! (`TestCfg/Calibration/calibrationTest_ParamSet.xml`). No bound of C2 relative to C1 is there.
//! Its test subject before calibration has C1 = 0.768956, C2 = -0.990048
//! (`TestData/unix/uncalibratedSubject.xml`). Here the bounds are Lloyd & Besier's, |C1| < 1
//! and |C2| < 1, which all of these satisfy.
//!
//! The sample period of the constants: CEINMS steps the recursion once per frame of its EMG
//! input (`src/ModelEvaluationOffline.cpp`: `setEmgs`, `updateActivations`, `pushState` for each
//! EMG frame; the muscle-tendon integration has its own times), so C1 and C2 belong to the
//! period of the EMG envelope they were calibrated on. It applies the delay as a shift of the
//! EMG frames' times (`emgTime = frame.time + globalEmDelay`), not as a count of samples. At
//! its third frame it sets both past outputs to the mean of the first two inputs (`noOfEmg_ ==
//! 2`); here the state starts at rest, or where `NeuralActivation::settle` puts it.
//!
//! When the model's tick differs from the EMG period, the exact course is to run the recursion
//! at the EMG period and resample its output. `NeuralParams::at_period` converts the
//! constants instead, by matching roots: a root r over period T becomes r^(T'/T) over T', i.e.
//! `C' = -(-C)^(T'/T)`, which keeps each mode's time constant and the unit gain. It is not exact:
//! the recursion has no zeros that scale with the period, so the forced response (to a step,
//! say) differs from the original by a fraction of a sample period in timing. A positive C
//! (a root on the negative real axis) has no counterpart at another period (a real power of a
//! negative root is not real): refused.
//!
//! A delay in seconds becomes `round(delay / T)` samples, halves away from zero (the nearest
//! sample, within T/2 of the delay asked for).

use crate::emg::error::{check_finite, EmgError};
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};

/// Longest electromechanical delay accepted, s. Delays of 10 to 100 ms are usual (Lloyd &
/// Besier 2003); this leaves room while bounding the delay line.
pub(crate) const MAX_DELAY_S: f64 = 0.5;
/// Longest delay line, samples (0.5 s at 131 kHz).
pub(crate) const MAX_DELAY_SAMPLES: usize = 1 << 16;

/// `β1 = C1 + C2` (Lloyd & Besier 2003, the recursion's coefficients).
pub(crate) fn beta1(c1: f64, c2: f64) -> f64 {
    c1 + c2
}

/// `β2 = C1 C2` (Lloyd & Besier 2003, the recursion's coefficients).
pub(crate) fn beta2(c1: f64, c2: f64) -> f64 {
    c1 * c2
}

/// `α = 1 + β1 + β2`, the gain that makes the steady state u = e (Lloyd & Besier 2003).
pub(crate) fn alpha(beta1: f64, beta2: f64) -> f64 {
    1.0 + beta1 + beta2
}

/// `value` as the coefficient `name` if finite and within (-1, 1).
fn check_coefficient(name: &'static str, value: f64) -> Result<f64, EmgError> {
    if value.is_finite() && value.abs() < 1.0 {
        Ok(value)
    } else {
        Err(EmgError::Coefficient { name, value })
    }
}

/// A sample period that is finite and above zero, s.
fn check_period(period_s: f64) -> Result<f64, EmgError> {
    if period_s.is_finite() && period_s > 0.0 {
        Ok(period_s)
    } else {
        Err(EmgError::SamplePeriod { value_s: period_s })
    }
}

/// The coefficient whose root -C' over the new period equals the root -C raised to `ratio`
/// (new period over old): `C' = -(-C)^ratio`; C ≤ 0.
fn coefficient_at_ratio(c: f64, ratio: f64) -> f64 {
    -(-c).powf(ratio)
}

/// The recursion's coefficients C1 and C2, checked to lie in (-1, 1), for the sample period at
/// which they were calibrated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeuralParams {
    c1: f64,
    c2: f64,
}

impl NeuralParams {
    /// C1 and C2, each finite and within (-1, 1).
    pub fn new(c1: f64, c2: f64) -> Result<Self, EmgError> {
        Ok(NeuralParams {
            c1: check_coefficient("C1", c1)?,
            c2: check_coefficient("C2", c2)?,
        })
    }

    /// C1.
    pub fn c1(&self) -> f64 {
        self.c1
    }

    /// C2.
    pub fn c2(&self) -> f64 {
        self.c2
    }

    /// β1.
    pub(crate) fn beta1(&self) -> f64 {
        beta1(self.c1, self.c2)
    }

    /// β2.
    pub(crate) fn beta2(&self) -> f64 {
        beta2(self.c1, self.c2)
    }

    /// α.
    pub(crate) fn alpha(&self) -> f64 {
        alpha(self.beta1(), self.beta2())
    }

    /// The coefficients for a recursion stepped every `to_period_s` instead of every
    /// `from_period_s`, by matching roots (module doc: approximate for the forced response).
    /// Refuses a positive C1 or C2 and periods that are not finite and above zero.
    pub(crate) fn at_period(&self, from_period_s: f64, to_period_s: f64) -> Result<Self, EmgError> {
        let ratio = check_period(to_period_s)? / check_period(from_period_s)?;
        for (name, value) in [("C1", self.c1), ("C2", self.c2)] {
            if value > 0.0 {
                return Err(EmgError::NoOtherPeriod { name, value });
            }
        }
        NeuralParams::new(
            coefficient_at_ratio(self.c1, ratio),
            coefficient_at_ratio(self.c2, ratio),
        )
    }
}

/// The delay in whole samples nearest `delay_s` at `sample_period_s`: `round(delay / T)`,
/// halves away from zero. Refuses a delay outside `0, [`MAX_DELAY_S``] or over
/// `MAX_DELAY_SAMPLES` samples.
pub(crate) fn delay_samples(delay_s: f64, sample_period_s: f64) -> Result<usize, EmgError> {
    let period = check_period(sample_period_s)?;
    if !(0.0..=MAX_DELAY_S).contains(&delay_s) {
        return Err(EmgError::Delay {
            value_s: delay_s,
            max_s: MAX_DELAY_S,
        });
    }
    let samples = (delay_s / period).round();
    if samples > MAX_DELAY_SAMPLES as f64 {
        return Err(EmgError::DelaySamples {
            samples: samples.min(usize::MAX as f64) as usize,
            max: MAX_DELAY_SAMPLES,
        });
    }
    Ok(samples as usize)
}

/// The recursion with its state: the two previous outputs and a delay line of d samples (a ring
/// allocated when made, never after).
#[derive(Debug, Clone)]
pub struct NeuralActivation {
    params: NeuralParams,
    u1: f64,
    u2: f64,
    line: Vec<f64>,
    head: usize,
}

impl NeuralActivation {
    /// At rest (past outputs and delayed inputs zero), with a delay of `delay_samples` samples
    /// (at most `MAX_DELAY_SAMPLES`).
    pub fn new(params: NeuralParams, delay_samples: usize) -> Result<Self, EmgError> {
        if delay_samples > MAX_DELAY_SAMPLES {
            return Err(EmgError::DelaySamples {
                samples: delay_samples,
                max: MAX_DELAY_SAMPLES,
            });
        }
        Ok(NeuralActivation {
            params,
            u1: 0.0,
            u2: 0.0,
            line: vec![0.0; delay_samples],
            head: 0,
        })
    }

    /// At rest, with the delay `delay_s` rounded to whole samples of `sample_period_s`
    /// (`delay_samples`).
    pub fn with_delay_s(
        params: NeuralParams,
        delay_s: f64,
        sample_period_s: f64,
    ) -> Result<Self, EmgError> {
        NeuralActivation::new(params, delay_samples(delay_s, sample_period_s)?)
    }

    /// The delay, samples.
    pub fn delay_samples(&self) -> usize {
        self.line.len()
    }

    /// The coefficients.
    pub fn params(&self) -> NeuralParams {
        self.params
    }

    /// A sample as the recursion takes it: clamped to [0, 1] as CEINMS clamps its excitation
    /// (`setEmg`); a NaN counts as 0, so the state stays finite.
    fn admitted(e: f64) -> f64 {
        if e.is_nan() {
            0.0
        } else {
            e.clamp(0.0, 1.0)
        }
    }

    /// The next neural activation for envelope sample `e`, as [`Self::step`] gives it, without
    /// taking the sample: for a caller that takes it ([`Self::take`]) only once the step it
    /// belongs to has been kept.
    pub(crate) fn next(&self, e: f64) -> f64 {
        // The input of d samples ago: the delay line's oldest, or e itself without delay.
        let e_d = self
            .line
            .get(self.head)
            .copied()
            .unwrap_or(Self::admitted(e));
        let p = &self.params;
        p.alpha() * e_d - p.beta1() * self.u1 - p.beta2() * self.u2
    }

    /// Takes sample `e`, whose output [`Self::next`] gave as `u`.
    pub(crate) fn take(&mut self, e: f64, u: f64) {
        if let Some(slot) = self.line.get_mut(self.head) {
            *slot = Self::admitted(e);
            self.head = (self.head + 1) % self.line.len();
        }
        self.u2 = self.u1;
        self.u1 = u;
    }

    /// The next neural activation for envelope sample `e` (clamped as [`Self::next`] says),
    /// the sample taken.
    pub(crate) fn step(&mut self, e: f64) -> f64 {
        let u = self.next(e);
        self.take(e, u);
        u
    }

    /// Back to rest.
    pub(crate) fn reset(&mut self) {
        self.settle(0.0);
    }

    /// The steady state of a constant input `e` (clamped to [0, 1]; NaN counts as 0): past
    /// outputs and delayed inputs all `e`.
    pub(crate) fn settle(&mut self, e: f64) {
        let e = if e.is_nan() { 0.0 } else { e.clamp(0.0, 1.0) };
        self.u1 = e;
        self.u2 = e;
        self.line.iter_mut().for_each(|v| *v = e);
        self.head = 0;
    }
}

/// What the recursion carries from sample to sample: its last two outputs, then its delay line
/// from the oldest sample on (so that a restored line starts at its head). The coefficients and
/// the delay are the rebuilt recursion's, and the saved line must be as long.
impl SavedState for NeuralActivation {
    fn save_state(&self, out: &mut StateWriter) {
        out.f64(self.u1);
        out.f64(self.u2);
        out.usize(self.line.len());
        let (recent, oldest) = self.line.split_at(self.head);
        for &v in oldest.iter().chain(recent) {
            out.f64(v);
        }
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        self.u1 = input.f64("neural activation u[k-1]")?;
        self.u2 = input.f64("neural activation u[k-2]")?;
        input.f64s_into("neural activation's delay line", &mut self.line)?;
        self.head = 0;
        Ok(())
    }
}

/// Neural activation of a whole envelope from rest, delay `delay_samples`; refuses a
/// non-finite sample.
pub fn neural_activation(
    envelope: &[f64],
    params: NeuralParams,
    delay_samples: usize,
) -> Result<Vec<f64>, EmgError> {
    check_finite(envelope)?;
    let mut state = NeuralActivation::new(params, delay_samples)?;
    Ok(envelope.iter().map(|&e| state.step(e)).collect())
}
