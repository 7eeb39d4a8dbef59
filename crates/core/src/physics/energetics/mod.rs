//! Muscle energetics (docs/model.md §11): what a muscle spends, in two families of models. The
//! files are the crate's modules; what other crates use of them is re-exported here.
//!
//! - **Cross-bridge energetics** of the Huxley models (Huxley 1957): each detachment splits one
//!   ATP, so the ATP rate is the detachment flux of the bond distribution (`bridge_flux`: the
//!   Distribution-Moment closure in closed form, the full model's grid by quadrature), and the
//!   heat comes from its own two sources, the free energy not stored as strain when a bridge
//!   attaches and the strain a bridge still holds when it detaches (`bridge_power`:
//!   [`BridgeEnergyScale`]). The steady states of Huxley (1957) in closed form are in
//!   `huxley_steady`.
//! - **Phenomenological heat rates** for any model: Umberger (2010), with the options of Uchida
//!   et al. (2016), and Bhargava et al. (2004), as OpenSim's metabolic probes compute them
//!   (`probe`, `umberger`, `bhargava`; the selection in `phenomenological`).
//!
//! `metabolic` is what a run publishes of them per muscle and instant ([`MetabolicSample`]).
//! `model_inputs`: a muscle's energetics parameters (the configuration's `[muscle.energetics]`)
//! as the models' inputs. `isovelocity` puts both together for isovelocity steady states at full
//! activation and optimal length ([`SteadyPoint`]). Every function is stateless; units are SI (W,
//! J, mol/s, N, m/s) unless a name says otherwise. Velocities follow docs/model.md: `v` lengthens
//! the fibre, `v_s = -v` shortens it; work rates count work done by the contractile element on
//! its load, positive when shortening.

pub(crate) mod bhargava;
pub(crate) mod bridge_flux;
pub(crate) mod bridge_power;
pub(crate) mod huxley_steady;
pub(crate) mod isovelocity;
pub(crate) mod metabolic;
pub(crate) mod model_inputs;
pub(crate) mod phenomenological;
pub(crate) mod probe;
pub(crate) mod umberger;

pub use self::{
    bridge_power::{activation_heat_w, BridgeEnergyParams, BridgeEnergyScale},
    huxley_steady::energy_rate_ratio,
    isovelocity::{exact_isometric_bridge_w, exact_point, SteadyPoint},
    metabolic::{MetabolicRates, MetabolicSample, MuscleProbe},
    probe::ExcitationTerms,
};

#[cfg(test)]
pub(crate) mod tests;
