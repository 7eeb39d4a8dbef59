//! The muscle physics (docs/model.md): pure functions and plain state, no I/O.

pub mod activation;
pub mod contractile;
pub mod energetics;
pub mod joint;
pub mod model;
pub mod models;
pub mod moment_arm;
pub mod mtu;
pub mod muscle_model;
pub mod observables;
pub mod parallel_element;
pub mod params;
pub mod plant;
pub mod spring;
pub mod stepping;
pub mod stiffness;
pub mod tendon;
pub mod topology;
