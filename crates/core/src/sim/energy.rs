//! Energy spent since start, per muscle (docs/model.md §11.6): the metabolic rates at each
//! tick's end, carried to the next tick's start, and their integrals over the ticks.
//!
//! A tick's energy is the trapezoidal rule over the tick, `dt (P(start) + P(end)) / 2`: second
//! order, like the fixed sub-steps, and exact for the powers that vary linearly within a tick.
//! The power at a tick's start is that of the state the previous tick ended in under this
//! tick's excitation: the bridges do not see the excitation (their rates are carried as they
//! were), the phenomenological models do (theirs are recomputed). What those compute from the
//! excitation alone is computed once per command and kept with the energies.

use crate::physics::energetics::metabolic::{
    EnergyPowers, MetabolicRates, MetabolicSample, MuscleProbe,
};
use crate::physics::energetics::probe::{ExcitationTerms, ProbeInputs};
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};

/// One muscle's energetics carried from tick to tick.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct MuscleEnergy {
    /// At the last tick's end (or at rest after a reset).
    pub sample: MetabolicSample,
    /// The phenomenological model's terms of the last command's excitation.
    pub terms: ExcitationTerms,
    /// Metabolic energy since start, J (the integral of `rates.metabolic_w`).
    pub metabolic_j: f64,
    /// The phenomenological model's energy since start, J.
    pub phenomenological_j: f64,
}

impl MuscleEnergy {
    /// At rest: the sample of the resting state taken under `terms`, no energy spent.
    pub(crate) fn at_rest(sample: MetabolicSample, terms: ExcitationTerms) -> Self {
        Self {
            sample,
            terms,
            metabolic_j: 0.0,
            phenomenological_j: 0.0,
        }
    }

    /// The terms of `excitation`: the kept ones if it is the last command's.
    fn terms_of(&self, probe: &MuscleProbe, excitation: f64) -> ExcitationTerms {
        if excitation == self.terms.excitation {
            self.terms
        } else {
            probe.excitation_terms(excitation)
        }
    }

    /// A tick under `excitation` whose end state gives `end_of(terms)` (the sample at the
    /// tick's end, given the excitation's terms): the powers at the tick's start are the last
    /// sample's, the phenomenological model's evaluated again if the excitation changed. Changes
    /// nothing, so that the parts of a limb compute it wherever they are stepped;
    /// [`MuscleEnergy::commit`] carries it on.
    pub(crate) fn tick(
        &self,
        probe: &MuscleProbe,
        excitation: f64,
        end_of: impl FnOnce(&ExcitationTerms) -> MetabolicSample,
    ) -> TickEnergy {
        let terms = self.terms_of(probe, excitation);
        let end = end_of(&terms);
        let start = if end.probe_inputs.excitation == self.sample.probe_inputs.excitation {
            self.sample.powers()
        } else {
            self.sample.powers_with_excitation(probe, &terms)
        };
        TickEnergy { terms, start, end }
    }

    /// Carries a tick of `dt` seconds on ([`MuscleEnergy::tick`]): its energies integrated, its
    /// end sample and terms kept for the next.
    pub(crate) fn commit(&mut self, tick: &TickEnergy, dt: f64) {
        let (start, r) = (&tick.start, &tick.end.rates);
        self.metabolic_j += 0.5 * dt * (start.metabolic_w + r.metabolic_w);
        self.phenomenological_j += 0.5 * dt * (start.phenomenological_w + r.phenomenological_w);
        self.terms = tick.terms;
        self.sample = tick.end;
    }
}

/// One muscle's energetics over one tick, before [`MuscleEnergy::commit`] carries them on.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct TickEnergy {
    /// The terms of the tick's excitation.
    pub terms: ExcitationTerms,
    /// The two powers at the tick's start.
    pub start: EnergyPowers,
    /// The sample at the tick's end.
    pub end: MetabolicSample,
}

/// The last tick's sample (whether its rates are the bridges', what the probe read, the
/// published rates; the next tick's start reads them), the last command's excitation terms and
/// the energies since start. Every field is named, so that a field added to these structs fails
/// to compile here until it is saved.
impl SavedState for MuscleEnergy {
    fn save_state(&self, out: &mut StateWriter) {
        let MetabolicSample {
            bridges,
            probe_inputs,
            rates,
        } = self.sample;
        out.bool(bridges);
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
        let ExcitationTerms {
            excitation: u,
            recruited: (slow, fast),
            recruited_share,
            excitation_power,
        } = self.terms;
        let t = [u, slow, fast, recruited_share, excitation_power];
        for v in p.into_iter().chain(r).chain(t) {
            out.f64(v);
        }
        out.f64(self.metabolic_j);
        out.f64(self.phenomenological_j);
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        let bridges = input.bool("energetics' bridges flag")?;
        let mut v = || input.f64("energetics");
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
        let terms = ExcitationTerms {
            excitation: v()?,
            recruited: (v()?, v()?),
            recruited_share: v()?,
            excitation_power: v()?,
        };
        *self = MuscleEnergy {
            sample: MetabolicSample {
                bridges,
                probe_inputs,
                rates,
            },
            terms,
            metabolic_j: v()?,
            phenomenological_j: v()?,
        };
        Ok(())
    }
}
