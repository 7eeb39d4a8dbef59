//! A muscle's Lloyd & Besier activation over the ticks (docs/model.md §2b): the recursion of
//! `crate::emg::neural` stepped once per tick on the tick's excitation (an EMG envelope sample),
//! its output through the nonlinearity (`crate::emg::nonlinearity`) as the activation at the
//! tick's end; within the tick the activation moves linearly from the tick's start to it.
//!
//! The tick's output is computed before the tick is stepped and the sample taken only once the
//! tick has been kept ([`NeuralDrive::commit`]): a failed tick leaves the recursion as it was.
//!
//! C1 and C2 belong to the period of `neural_rate_hz` (default: the tick rate); at another tick
//! rate they are converted by keeping each root's time constant
//! ([`crate::emg::neural::NeuralParams::at_period`], which refuses a positive C). The delay is a
//! whole number of ticks, the nearest to `em_delay`.

use crate::emg::neural::{delay_samples, NeuralActivation, NeuralParams};
use crate::emg::nonlinearity::{activation, ShapeFactor};
use crate::emg::EmgError;
use crate::physics::limb_params::formulation::ActivationKind;
use crate::physics::limb_params::MuscleParams;
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};

/// One muscle's recursion, its nonlinearity and the output computed for the tick being
/// stepped.
#[derive(Debug, Clone)]
pub(crate) struct NeuralDrive {
    recursion: NeuralActivation,
    shape: ShapeFactor,
    /// The neural activation `next` gave for the tick being stepped.
    pending: f64,
}

impl NeuralDrive {
    /// The drive of a muscle with `activation = "lloyd_besier"` at a tick rate of `rate_hz`;
    /// None for the paper's first order. The parameters are validated ones (C1, C2 present).
    pub(crate) fn of(p: &MuscleParams, rate_hz: f64) -> Result<Option<Self>, EmgError> {
        if p.activation != ActivationKind::LloydBesier {
            return Ok(None);
        }
        let tick = 1.0 / rate_hz;
        let given = NeuralParams::new(p.c1.unwrap_or(f64::NAN), p.c2.unwrap_or(f64::NAN))?;
        let params = match p.neural_rate_hz {
            Some(r) if r != rate_hz => given.at_period(1.0 / r, tick)?,
            _ => given,
        };
        let delay = delay_samples(p.em_delay.unwrap_or(0.0), tick)?;
        Ok(Some(NeuralDrive {
            recursion: NeuralActivation::new(params, delay)?,
            shape: ShapeFactor::new(p.shape_factor.unwrap_or(0.0))?,
            pending: 0.0,
        }))
    }

    /// The activation at the end of the tick whose excitation is `u`, the sample not yet taken.
    pub(crate) fn tick_end(&mut self, u: f64) -> f64 {
        self.pending = self.recursion.next(u);
        activation(self.pending, self.shape)
    }

    /// Takes the excitation `u` of the tick just kept, whose output [`Self::tick_end`] gave.
    pub(crate) fn commit(&mut self, u: f64) {
        self.recursion.take(u, self.pending);
    }

    /// At rest: no excitation in the recursion's past or its delay line.
    pub(crate) fn reset(&mut self) {
        self.recursion.reset();
        self.pending = 0.0;
    }
}

/// The recursion's state (the pending output is recomputed before every tick).
impl SavedState for NeuralDrive {
    fn save_state(&self, out: &mut StateWriter) {
        self.recursion.save_state(out);
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        self.recursion.restore_state(input)
    }
}
