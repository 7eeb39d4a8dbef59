//! The muscle physics (docs/model.md): pure functions and plain state, no I/O. The files below
//! are the crate's modules; what other crates use of them is re-exported here, and the four
//! folders ([`contractile`], [`curves`], [`energetics`], [`models`]) are facades of their own.
//!
//! - `limb_params`: the parameters of the muscles and joints ([`MuscleParams`], [`JointParams`]),
//!   their defaults and their rules (§1, §6, §8);
//! - `activation`: excitation to activation (§2);
//! - [`contractile`]: the contractile elements' mathematics (§3, §6, §7); [`models`]: the
//!   interface a model implements, the models, one file each, and [`MODELS`], the one place
//!   where they are named;
//! - [`curves`]: the curve sets, the paper's and OpenSim's DeGroote 2016 and Thelen 2003 (§4b);
//! - `spring`, `tendon`, `parallel_element`: the passive elements (§4);
//! - `mtu`: one muscle–tendon unit ([`Mtu`], §5); `moment_arm`, `joint`, `topology`: the limb
//!   (§8, §8b); `plant`: the whole limb as one ODE ([`Plant`], §5, §8b);
//! - `stiffness`: fibre, muscle–tendon and joint stiffness (§8); `observables`: the fields
//!   observable about a muscle and a joint (re-exported by [`crate::sim`]);
//! - `stepping`: how a tick is divided into sub-steps ([`Stepping`], §10);
//! - [`energetics`]: what a muscle spends, cross-bridge and phenomenological models (§11).
//!
//! [`MODELS`]: models::MODELS

pub mod contractile;
pub mod curves;
pub mod energetics;
pub mod models;

pub(crate) mod activation;
pub(crate) mod joint;
pub(crate) mod limb_params;
pub(crate) mod moment_arm;
pub(crate) mod mtu;
pub(crate) mod observables;
pub(crate) mod parallel_element;
pub(crate) mod pennation;
pub(crate) mod plant;
pub(crate) mod spring;
pub(crate) mod stepping;
pub(crate) mod stiffness;
pub(crate) mod tendon;
pub(crate) mod topology;

pub use self::{
    activation::activation_rate,
    limb_params::{
        curve_set::{CurveSet, UnknownCurveSet},
        energetics_table::{EnergeticsParams, EnergyModel, UnknownEnergyModel},
        formulation::{ActivationKind, FibreKind, TendonKind, UnknownKind},
        tabulated_points::{Points, TabulatedCurves},
        CrossBridgeParams, ForceLengthShape, JointParams, MuscleParams, ParamError,
    },
    moment_arm::MomentArm,
    mtu::{FibreState, Mtu, TendonEnd},
    parallel_element::{parallel_spring, passive_strain, ParallelElement},
    plant::{Inputs, Plant, PlantError},
    spring::ExpLinearSpring,
    stepping::{Stepping, SteppingError, DEFAULT_MAX_SUBSTEPS, MAX_SUBSTEPS},
    stiffness::series_stiffness,
    tendon::{tendon, tendon_strain, Tendon},
    topology::{MuscleSpec, Span, Topology},
};
