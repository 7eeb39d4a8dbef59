//! A facade over its two files.

pub mod left;
pub mod right;

pub use left::Left;
pub use right::Right;
