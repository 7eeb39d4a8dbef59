//! A facade: re-exports of its own files are not edges.

pub mod left;
pub mod right;

pub use left::Left;
