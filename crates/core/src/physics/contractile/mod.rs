//! Contractile elements: Hill-type, and Huxley-type cross-bridges (Distribution-Moment and full).
//! The mathematics only; the models built on it are in [`crate::physics::models`].
//!
//! - [`force_length`]: f(l_m), shared by both kinds; [`hill_equation`]: Hill's force–velocity
//!   equation and the Hill element's force (§3);
//! - [`crossbridge`]: Huxley's attachment and detachment rates (§6);
//! - [`distribution_moment`]: Zahalak's moment equations and their closure (§6);
//!   `closure_limits`: its limits' values kept for the fluxes at a tick's end (§11.1);
//! - [`huxley_grid`]: the full model's bond distribution by characteristics (§7);
//!   [`huxley_exact`]: its closed-form steady states (§7);
//! - [`crossbridge_scale`]: the cross-bridge models scaled to a muscle's Fmax and vmax (§6–7).
//!
//! Sections are those of docs/model.md.

pub(crate) mod closure_limits;
pub mod crossbridge;
pub mod crossbridge_scale;
pub mod distribution_moment;
pub mod force_length;
pub mod hill_equation;
pub mod huxley_exact;
pub mod huxley_grid;
