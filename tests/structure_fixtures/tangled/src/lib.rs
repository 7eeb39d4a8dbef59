//! A fixture crate with structure problems (see ../../README.md).

pub mod big;
pub mod feeder;
pub mod parts;
pub mod store;
