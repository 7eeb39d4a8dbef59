//! Time integration: the fixed-step implicit stepper used on every tick, and the adaptive
//! explicit reference solver the tests and accuracy reports compare it with.

pub mod reference;
pub mod trbdf2;

use nalgebra::SVector;

/// A first-order ODE system `dy/dt = f(t, y)` of fixed dimension N.
pub trait OdeSystem<const N: usize> {
    /// Evaluates `dy = f(t, y)`.
    fn rhs(&self, t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>);
    /// Typical magnitude of each component: the absolute tolerance unit and the finite-difference
    /// step scale.
    fn scales(&self) -> SVector<f64, N>;
}
