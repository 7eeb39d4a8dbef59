//! The muscle physics (MODEL.md): pure functions and plain state, no I/O.

pub mod model;
pub mod params;
