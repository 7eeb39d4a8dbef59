//! A fixture crate without structure problems (see ../../README.md).

pub mod base;
pub mod parts;
pub mod table;
pub mod top;
