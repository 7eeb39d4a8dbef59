//! The phenomenological energy model a run selects (docs/model.md §11.4): Umberger (2010)
//! or Bhargava et al. (2004), each with its options.

use crate::physics::energetics::bhargava::{self, BhargavaOptions};
use crate::physics::energetics::probe::{ExcitationTerms, ProbeInputs, ProbeMuscle, ProbeRates};
use crate::physics::energetics::umberger::{self, UmbergerOptions};

/// A phenomenological energy model, selectable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum PhenomenologicalModel {
    /// Umberger (2010), options as given (OpenSim's defaults: Uchida et al. 2016).
    Umberger(UmbergerOptions),
    /// Bhargava et al. (2004), options as given (OpenSim's defaults).
    Bhargava(BhargavaOptions),
}

impl PhenomenologicalModel {
    /// Whether it reads the passive fibre force (Bhargava's shortening heat counts the whole
    /// fibre force); the others need not be given it.
    pub(crate) fn reads_passive_force(&self) -> bool {
        matches!(self, Self::Bhargava(_))
    }

    /// Its rates for one muscle at one instant.
    pub(crate) fn rates(&self, m: &ProbeMuscle, x: &ProbeInputs) -> ProbeRates {
        self.rates_with(
            m,
            x,
            &ExcitationTerms::new(x.excitation, m.slow_twitch_ratio),
        )
    }

    /// The same with the excitation's terms computed beforehand (`terms.excitation` is
    /// `x.excitation`).
    pub(crate) fn rates_with(
        &self,
        m: &ProbeMuscle,
        x: &ProbeInputs,
        terms: &ExcitationTerms,
    ) -> ProbeRates {
        match self {
            Self::Umberger(o) => umberger::umberger_rates_with(o, m, x, terms),
            Self::Bhargava(o) => bhargava::bhargava_rates_with(o, m, x, terms),
        }
    }
}
