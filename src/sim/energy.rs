//! Energy spent since start, per muscle (docs/model.md §11.6): the metabolic rates at each
//! tick's end, carried to the next tick's start, and their integrals over the ticks.
//!
//! A tick's energy is the trapezoidal rule over the tick, `dt (P(start) + P(end)) / 2`: second
//! order, like the fixed sub-steps, and exact for the powers that vary linearly within a tick.
//! The power at a tick's start is that of the state the previous tick ended in under this
//! tick's excitation: the bridges do not see the excitation (their rates are carried as they
//! were), the phenomenological models do (theirs are recomputed).

use crate::physics::energetics::metabolic::{
    MechanismRates, MetabolicRates, MetabolicSample, MuscleProbe,
};
use crate::physics::energetics::probe::ProbeInputs;
use crate::state_bytes::{SavedState, StateReader, StateWriter};

/// One muscle's energetics carried from tick to tick.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MuscleEnergy {
    /// At the last tick's end (or at rest after a reset).
    pub sample: MetabolicSample,
    /// Metabolic energy since start, J (the integral of `rates.metabolic_w`).
    pub metabolic_j: f64,
    /// The phenomenological model's energy since start, J.
    pub phenomenological_j: f64,
}

impl MuscleEnergy {
    /// At rest: the sample of the resting state, no energy spent.
    pub fn at_rest(sample: MetabolicSample) -> Self {
        Self {
            sample,
            metabolic_j: 0.0,
            phenomenological_j: 0.0,
        }
    }

    /// The rates at the start of a tick under `excitation`: those the last tick ended with,
    /// recomputed only if the excitation changed.
    pub fn rates_at_start(&self, probe: &MuscleProbe, excitation: f64) -> MetabolicRates {
        if excitation == self.sample.probe_inputs.excitation {
            self.sample.rates
        } else {
            self.sample.with_excitation(probe, excitation)
        }
    }

    /// After a tick of `dt` seconds that started at rates `start` and ended at `end`.
    pub fn advance(&mut self, start: &MetabolicRates, end: MetabolicSample, dt: f64) {
        let r = &end.rates;
        self.metabolic_j += 0.5 * dt * (start.metabolic_w + r.metabolic_w);
        self.phenomenological_j += 0.5 * dt * (start.phenomenological_w + r.phenomenological_w);
        self.sample = end;
    }
}

/// The last tick's sample (its mechanism's rates, what the probe read, the published rates;
/// the next tick's start reads them) and the energies since start. Every field is named, so
/// that a field added to these structs fails to compile here until it is saved.
impl SavedState for MuscleEnergy {
    fn save_state(&self, out: &mut StateWriter) {
        let MetabolicSample {
            mechanism,
            probe_inputs,
            rates,
        } = self.sample;
        out.bool(mechanism.is_some());
        let MechanismRates {
            total_w,
            activation_heat_w,
            bridge_heat_w,
            work_w,
            storage_w,
            atp_rate_mol_s,
        } = mechanism.unwrap_or_default();
        let m = [
            total_w,
            activation_heat_w,
            bridge_heat_w,
            work_w,
            storage_w,
            atp_rate_mol_s,
        ];
        let ProbeInputs {
            excitation,
            activation,
            fibre_length_norm,
            force_length,
            fibre_velocity_m_s,
            active_force_n,
            passive_force_n,
        } = probe_inputs;
        let p = [
            excitation,
            activation,
            fibre_length_norm,
            force_length,
            fibre_velocity_m_s,
            active_force_n,
            passive_force_n,
        ];
        let MetabolicRates {
            metabolic_w,
            activation_heat_w,
            shortening_heat_w,
            work_w,
            storage_w,
            atp_rate_mol_s,
            phenomenological_w,
        } = rates;
        let r = [
            metabolic_w,
            activation_heat_w,
            shortening_heat_w,
            work_w,
            storage_w,
            atp_rate_mol_s,
            phenomenological_w,
        ];
        for v in m.into_iter().chain(p).chain(r) {
            out.f64(v);
        }
        out.f64(self.metabolic_j);
        out.f64(self.phenomenological_j);
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), String> {
        let has_mechanism = input.bool("energetics' mechanism flag")?;
        let mut v = || input.f64("energetics");
        let mechanism = MechanismRates {
            total_w: v()?,
            activation_heat_w: v()?,
            bridge_heat_w: v()?,
            work_w: v()?,
            storage_w: v()?,
            atp_rate_mol_s: v()?,
        };
        let probe_inputs = ProbeInputs {
            excitation: v()?,
            activation: v()?,
            fibre_length_norm: v()?,
            force_length: v()?,
            fibre_velocity_m_s: v()?,
            active_force_n: v()?,
            passive_force_n: v()?,
        };
        let rates = MetabolicRates {
            metabolic_w: v()?,
            activation_heat_w: v()?,
            shortening_heat_w: v()?,
            work_w: v()?,
            storage_w: v()?,
            atp_rate_mol_s: v()?,
            phenomenological_w: v()?,
        };
        *self = MuscleEnergy {
            sample: MetabolicSample {
                mechanism: has_mechanism.then_some(mechanism),
                probe_inputs,
                rates,
            },
            metabolic_j: v()?,
            phenomenological_j: v()?,
        };
        Ok(())
    }
}
