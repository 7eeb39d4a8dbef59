//! The muscle physics (docs/model.md): pure functions and plain state, no I/O.
//!
//! - [`limb_params`]: the parameters of the muscles and joints and their defaults (§1, §6, §8);
//! - [`activation`]: excitation to activation (§2);
//! - [`contractile`]: the contractile elements' mathematics (§3, §6, §7); [`models`]: the
//!   interface a model implements, the models, one file each, and [`MODELS`], the one place
//!   where they are named;
//! - [`curves`]: the curve sets, the paper's and OpenSim's DeGroote 2016 and Thelen 2003 (§4b);
//! - [`spring`], [`tendon`], [`parallel_element`]: the passive elements (§4);
//! - [`mtu`]: one muscle–tendon unit (§5); [`moment_arm`], `joint`, [`topology`]: the limb
//!   (§8, §8b); [`plant`]: the whole limb as one ODE (§5, §8b);
//! - [`stiffness`]: fibre, muscle–tendon and joint stiffness (§8); [`observables`]: the fields
//!   observable about a muscle and a joint;
//! - [`stepping`]: how a tick is divided into sub-steps (§10);
//! - [`energetics`]: what a muscle spends, cross-bridge and phenomenological models (§11).
//!
//! [`MODELS`]: models::MODELS

pub mod activation;
pub mod contractile;
pub mod curves;
pub mod energetics;
pub(crate) mod joint;
pub mod limb_params;
pub mod models;
pub mod moment_arm;
pub mod mtu;
pub mod observables;
pub mod parallel_element;
pub(crate) mod pennation;
pub mod plant;
pub mod spring;
pub mod stepping;
pub mod stiffness;
pub mod tendon;
pub mod topology;
