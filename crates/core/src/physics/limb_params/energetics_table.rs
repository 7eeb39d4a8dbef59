//! The configuration's `[muscle.energetics]` table (docs/model.md §11, docs/configuration.md):
//! the energy model by name and the energetics constants of one muscle, as data. What they
//! mean to the energetics (their defaults, the cross-bridge parameters, the probes' muscle) is
//! in `physics::energetics::model_inputs`, which reads this module; this module reads none of
//! `physics`, so that the parameters of a muscle do not depend on the models that use them.

use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// The phenomenological energy model of a muscle (docs/model.md §11.4), by the name the
/// configuration, the `energy_model` node parameter and `--energy-model` use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum EnergyModel {
    /// Umberger (2010) with the options of Uchida et al. (2016): OpenSim's defaults.
    #[default]
    #[serde(rename = "umberger")]
    Umberger,
    /// Umberger (2010) as published.
    #[serde(rename = "umberger2010")]
    Umberger2010,
    /// Bhargava et al. (2004), OpenSim's defaults.
    #[serde(rename = "bhargava")]
    Bhargava,
}

impl EnergyModel {
    /// Every energy model, in the order of the documentation.
    pub const ALL: [EnergyModel; 3] = [Self::Umberger, Self::Umberger2010, Self::Bhargava];

    /// Its name in configurations, parameters and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Umberger => "umberger",
            Self::Umberger2010 => "umberger2010",
            Self::Bhargava => "bhargava",
        }
    }

    /// A label for plots and tables.
    pub fn label(self) -> &'static str {
        match self {
            Self::Umberger => "Umberger 2010 (Uchida 2016 options)",
            Self::Umberger2010 => "Umberger 2010 (as published)",
            Self::Bhargava => "Bhargava 2004",
        }
    }

    /// The names, comma-separated (for messages and help).
    pub fn names() -> String {
        Self::ALL.map(|m| m.name()).join(", ")
    }
}

impl std::fmt::Display for EnergyModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown energy model name (quoted as a short excerpt).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown energy model {0:?}: expected one of {names}", names = EnergyModel::names())]
pub struct UnknownEnergyModel(pub String);

impl FromStr for EnergyModel {
    type Err = UnknownEnergyModel;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| UnknownEnergyModel(s.chars().take(64).collect()))
    }
}

/// Energetics parameters of one muscle (docs/model.md §11; SI). Their defaults are those of
/// `physics::energetics` (`impl Default` in `physics::energetics::model_inputs`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EnergeticsParams {
    /// The phenomenological heat-rate model, computed for every contractile model (and the
    /// metabolic power of the Hill model).
    pub energy_model: EnergyModel,
    /// Free energy of ATP hydrolysis e, J per molecule (100 zJ ≈ 60 kJ/mol in working muscle).
    pub atp_free_energy: f64,
    /// Hill's (1938) heat coefficient a / P0, which sets the energy per ATP over a bridge's
    /// strain energy (Huxley 1957; docs/model.md §11.2).
    pub hill_a_over_p0: f64,
    /// Share of the isometric ATP turnover at full activation spent on calcium handling, [0, 0.9].
    pub activation_share: f64,
    /// Share of slow-twitch fibres r, [0, 1] (the phenomenological models).
    pub(crate) slow_twitch_ratio: f64,
    /// Mass the phenomenological rates per kg apply to, kg. Not given: OpenSim's
    /// `(Fmax / σ) ρ lopt` with σ = 0.25 MPa and ρ = 1059.7 kg/m³ (the configuration's `mass`
    /// is the fibre's moving mass of eq. 8, not the muscle's).
    pub metabolic_mass: Option<f64>,
}
