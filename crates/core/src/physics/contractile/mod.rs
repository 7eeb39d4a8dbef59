//! Contractile elements: Hill-type, and Huxley-type cross-bridges (Distribution-Moment and full).
//! The mathematics only; the models built on it are in [`crate::physics::models`]. The files
//! are the crate's modules; what other crates use of them is re-exported here.
//!
//! - `force_length`: f(l_m), shared by both kinds ([`force_length()`]); `hill_equation`: Hill's
//!   force–velocity equation ([`force_velocity`]) and the Hill element's force (§3);
//! - `crossbridge`: Huxley's attachment and detachment rates ([`Rates`], §6);
//! - `distribution_moment`: Zahalak's moment equations and their closure, the DM steady states
//!   ([`steady_curve`], §6); `closure_limits`: its limits' values kept for the fluxes at a
//!   tick's end (§11.1);
//! - `huxley_grid`: the full model's bond distribution by characteristics ([`CrossBridgeGrid`],
//!   §7); `huxley_exact`: its closed-form steady states ([`steady_q1`], §7);
//! - `crossbridge_scale`: the cross-bridge models scaled to a muscle's Fmax and vmax
//!   ([`CrossBridgeScale`], §6–7).
//!
//! Sections are those of docs/model.md.

pub(crate) mod closure_limits;
pub(crate) mod crossbridge;
pub(crate) mod crossbridge_scale;
pub(crate) mod distribution_moment;
pub(crate) mod force_length;
pub(crate) mod hill_equation;
pub(crate) mod huxley_exact;
pub(crate) mod huxley_grid;

pub use self::{
    crossbridge::Rates,
    crossbridge_scale::{calibrate_distribution_moment, calibrate_exact, CrossBridgeScale},
    distribution_moment::{steady_curve, SteadyStateError},
    force_length::force_length,
    hill_equation::force_velocity,
    huxley_exact::steady_q1,
    huxley_grid::CrossBridgeGrid,
};

#[cfg(test)]
mod tests;
