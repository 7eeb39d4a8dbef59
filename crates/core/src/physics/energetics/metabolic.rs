//! One muscle's metabolic rates at one instant, as a run publishes them (docs/model.md §11.6):
//! the mechanism's (the Huxley models' bridges and their calcium handling) where the model has
//! bonds, the phenomenological model's for every model, and which of the two is the muscle's
//! metabolic power.

use crate::physics::energetics::bridge_flux::EnergyFluxes;
use crate::physics::energetics::bridge_power::{
    activation_heat_w, bridge_powers, BridgeEnergyScale,
};
use crate::physics::energetics::phenomenological::PhenomenologicalModel;
use crate::physics::energetics::probe::{ExcitationTerms, ProbeInputs, ProbeMuscle, ProbeRates};

/// The cross-bridge energetics of one muscle's model: the scale from fluxes to watts and the
/// bridges' isometric chemical power at full activation (the activation cost's scale), W.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BridgeEnergetics {
    /// Fluxes to watts and moles.
    pub scale: BridgeEnergyScale,
    /// The bridges' own isometric chemical power at full activation and optimal length, W.
    pub(crate) isometric_bridge_w: f64,
    /// The activation heat at full activation, [`activation_heat_w`] at a = 1, W: it is
    /// proportional to a.
    pub(crate) full_activation_heat_w: f64,
}

impl BridgeEnergetics {
    /// From the scale and the bridges' isometric chemical power at full activation (W).
    pub(crate) fn new(scale: BridgeEnergyScale, isometric_bridge_w: f64) -> Self {
        Self {
            scale,
            isometric_bridge_w,
            full_activation_heat_w: activation_heat_w(
                1.0,
                scale.activation_share,
                isometric_bridge_w,
            ),
        }
    }
}

/// The mechanism's rates: where the free energy of the ATP goes, W (ATP in mol/s).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct MechanismRates {
    /// Chemical power, ATP counted as it is split at detachment, plus the activation cost.
    pub(crate) total_w: f64,
    /// Activation (calcium-handling) heat.
    pub activation_heat_w: f64,
    /// The bridges' heat: free energy not stored at attachment plus strain released at
    /// detachment.
    pub(crate) bridge_heat_w: f64,
    /// Work of the contractile element on its load, `F_CE v_s`.
    pub work_w: f64,
    /// Rate of change of the energy the attached bridges hold: their strain energy less the
    /// free energy of the ATP they have yet to split, `dE_CE/dt - e N_hs B dQ0/dt`.
    pub storage_w: f64,
    /// ATP split per second: by detachments, and by the calcium pumps at e per molecule.
    pub atp_rate_mol_s: f64,
}

/// The mechanism's rates from the fluxes, the activation a, the contractile force (N) and the
/// fibre's lengthening velocity (m/s).
pub(crate) fn mechanism_rates(
    b: &BridgeEnergetics,
    fluxes: &EnergyFluxes,
    activation: f64,
    force_n: f64,
    lengthening_velocity_m_s: f64,
) -> MechanismRates {
    let p = bridge_powers(&b.scale, fluxes, force_n, lengthening_velocity_m_s);
    let act = activation * b.full_activation_heat_w;
    MechanismRates {
        total_w: p.chemical_w + act,
        activation_heat_w: act,
        bridge_heat_w: p.heat_w(),
        work_w: p.work_w,
        // Counted at detachment the chemical power is that at attachment less e N_hs B dQ0/dt.
        storage_w: p.stored_rate_w - (p.chemical_at_attachment_w - p.chemical_w),
        atp_rate_mol_s: p.atp_rate_mol_s + act * b.scale.atp_mol_per_j,
    }
}

/// A muscle's phenomenological model, with the constants it reads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MuscleProbe {
    /// The model and its options.
    pub(crate) model: PhenomenologicalModel,
    /// The muscle's constants (mass, Fmax, lopt, vmax, fibre types).
    pub(crate) muscle: ProbeMuscle,
    /// Moles of ATP per joule at the energy per ATP (for its ATP equivalent),
    /// [`crate::physics::energetics::bridge_power::atp_mol_per_j`], mol/J.
    pub(crate) atp_mol_per_j: f64,
}

impl MuscleProbe {
    /// What it computes from excitation u alone.
    pub fn excitation_terms(&self, excitation: f64) -> ExcitationTerms {
        ExcitationTerms::new(excitation, self.muscle.slow_twitch_ratio)
    }

    /// Its rates at one instant, given the terms of its excitation (`terms.excitation` is
    /// `x.excitation`).
    pub(crate) fn rates(&self, x: &ProbeInputs, terms: &ExcitationTerms) -> ProbeRates {
        self.model.rates_with(&self.muscle, x, terms)
    }
}

/// What a run publishes of one muscle's energetics at an instant (the rate fields of
/// `MuscleState.msg`; the energies since start are the integrals of the two totals).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MetabolicRates {
    /// Metabolic power: the mechanism's where there are bridges, else the phenomenological
    /// model's, W.
    pub metabolic_w: f64,
    /// Activation (and, phenomenologically, maintenance) heat, W.
    pub activation_heat_w: f64,
    /// Shortening and lengthening heat (the bridges' heat for the mechanism), W.
    pub shortening_heat_w: f64,
    /// The work rate the metabolic power counts, W (shortening positive).
    pub work_w: f64,
    /// The bridges' storage rate, W (0 for the phenomenological models).
    pub storage_w: f64,
    /// ATP rate, mol/s (phenomenological: its power in ATP at e per molecule).
    pub atp_rate_mol_s: f64,
    /// The phenomenological model's total, W, whatever the contractile model.
    pub phenomenological_w: f64,
}

impl MetabolicRates {
    /// From the mechanism's rates (a model with bridges) and the phenomenological ones.
    /// `atp_mol_per_j` converts the phenomenological power to its ATP equivalent.
    pub(crate) fn of(
        mechanism: Option<&MechanismRates>,
        probe: &ProbeRates,
        atp_mol_per_j: f64,
    ) -> Self {
        match mechanism {
            Some(m) => Self {
                metabolic_w: m.total_w,
                activation_heat_w: m.activation_heat_w,
                shortening_heat_w: m.bridge_heat_w,
                work_w: m.work_w,
                storage_w: m.storage_w,
                atp_rate_mol_s: m.atp_rate_mol_s,
                phenomenological_w: probe.total_w(),
            },
            None => Self {
                metabolic_w: probe.total_w(),
                activation_heat_w: probe.activation_maintenance_w,
                shortening_heat_w: probe.shortening_w,
                work_w: probe.work_w,
                storage_w: 0.0,
                atp_rate_mol_s: probe.total_w() * atp_mol_per_j,
                phenomenological_w: probe.total_w(),
            },
        }
    }
}

/// The two powers a run integrates into energies, W.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct EnergyPowers {
    /// Metabolic power.
    pub metabolic_w: f64,
    /// The phenomenological model's total.
    pub phenomenological_w: f64,
}

/// One muscle's energetics at an instant: the published rates, whether they are the
/// mechanism's, and what the phenomenological model read.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MetabolicSample {
    /// Whether the metabolic power is the mechanism's (a model with bridges).
    pub bridges: bool,
    /// The phenomenological model's inputs.
    pub(crate) probe_inputs: ProbeInputs,
    /// The published rates.
    pub rates: MetabolicRates,
}

impl MetabolicSample {
    /// The two powers at this instant.
    pub(crate) fn powers(&self) -> EnergyPowers {
        EnergyPowers {
            metabolic_w: self.rates.metabolic_w,
            phenomenological_w: self.rates.phenomenological_w,
        }
    }

    /// The two powers of the same instant under another excitation, given by its terms (a
    /// tick's start, where the command changes): the bridges do not see the excitation, the
    /// phenomenological models do.
    pub(crate) fn powers_with_excitation(
        &self,
        probe: &MuscleProbe,
        terms: &ExcitationTerms,
    ) -> EnergyPowers {
        let x = ProbeInputs {
            excitation: terms.excitation,
            ..self.probe_inputs
        };
        let phenomenological_w = probe.rates(&x, terms).total_w();
        EnergyPowers {
            metabolic_w: if self.bridges {
                self.rates.metabolic_w
            } else {
                phenomenological_w
            },
            phenomenological_w,
        }
    }
}
