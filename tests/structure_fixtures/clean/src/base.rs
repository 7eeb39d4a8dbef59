//! The bottom layer; its tests live in base/tests.rs.

#[cfg(test)]
mod tests;

pub struct Unit;

pub fn unit() -> Unit {
    Unit
}
