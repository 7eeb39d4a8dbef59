//! A muscle's energetics parameters as the energetics models' inputs (docs/model.md §11,
//! docs/configuration.md; the data of the configuration's `[muscle.energetics]` table are
//! `physics::limb_params::energetics_table`): their defaults, the cross-bridge energetics'
//! parameters, the probes' view of the muscle, and each energy model with its options.

use crate::physics::energetics::bhargava::BhargavaOptions;
use crate::physics::energetics::bridge_power::BridgeEnergyParams;
use crate::physics::energetics::phenomenological::PhenomenologicalModel;
use crate::physics::energetics::probe::{
    muscle_mass_kg, ProbeMuscle, MUSCLE_DENSITY_KG_M3, SLOW_TWITCH_RATIO, SPECIFIC_TENSION_PA,
};
use crate::physics::energetics::umberger::UmbergerOptions;
pub(crate) use crate::physics::limb_params::energetics_table::{EnergeticsParams, EnergyModel};

impl EnergyModel {
    /// The model with its options.
    pub(crate) fn phenomenological(self) -> PhenomenologicalModel {
        match self {
            Self::Umberger => PhenomenologicalModel::Umberger(UmbergerOptions::uchida_2016()),
            Self::Umberger2010 => PhenomenologicalModel::Umberger(UmbergerOptions::umberger_2010()),
            Self::Bhargava => PhenomenologicalModel::Bhargava(BhargavaOptions::default()),
        }
    }
}

impl Default for EnergeticsParams {
    fn default() -> Self {
        let b = BridgeEnergyParams::default();
        Self {
            energy_model: EnergyModel::default(),
            atp_free_energy: b.atp_free_energy_j,
            hill_a_over_p0: b.hill_a_over_p0,
            activation_share: b.activation_share,
            slow_twitch_ratio: SLOW_TWITCH_RATIO,
            metabolic_mass: None,
        }
    }
}

impl EnergeticsParams {
    /// The cross-bridge energetics' parameters.
    pub fn bridge(&self) -> BridgeEnergyParams {
        BridgeEnergyParams {
            atp_free_energy_j: self.atp_free_energy,
            hill_a_over_p0: self.hill_a_over_p0,
            activation_share: self.activation_share,
        }
    }

    /// The mass in force, kg: the configured one or OpenSim's from Fmax and lopt.
    pub fn mass_kg(&self, f_max_n: f64, l_opt_m: f64) -> f64 {
        self.metabolic_mass.unwrap_or_else(|| {
            muscle_mass_kg(f_max_n, l_opt_m, SPECIFIC_TENSION_PA, MUSCLE_DENSITY_KG_M3)
        })
    }

    /// The probe's view of a muscle of force `f_max_n`, fibre length `l_opt_m` and maximum
    /// shortening velocity `v_max_m_s`.
    pub(crate) fn probe_muscle(&self, f_max_n: f64, l_opt_m: f64, v_max_m_s: f64) -> ProbeMuscle {
        ProbeMuscle {
            mass_kg: self.mass_kg(f_max_n, l_opt_m),
            f_max_n,
            l_opt_m,
            v_max_lopt_s: v_max_m_s / l_opt_m,
            slow_twitch_ratio: self.slow_twitch_ratio,
        }
    }
}
