//! Time integration: the implicit steppers used on every tick (a third-order ESDIRK for adaptive
//! sub-steps, TR-BDF2 for fixed ones, both over an iteration matrix that may exploit the
//! system's structure), and the adaptive explicit reference solver the tests and accuracy
//! reports compare them with.

pub mod arrowhead;
pub mod dense;
pub mod esdirk;
pub mod reference;
pub mod trbdf2;

/// A first-order ODE system `dy/dt = f(t, y)`.
pub trait OdeSystem {
    /// Length of the state vector.
    fn dim(&self) -> usize;
    /// Evaluates `dy = f(t, y)`.
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]);
    /// Typical magnitude of each component (the absolute tolerance unit and the
    /// finite-difference step scale), written to `out`.
    fn scales(&self, out: &mut [f64]);
}

/// The iteration matrix `I - d J` of the implicit stages: how its Jacobian J is evaluated, how it
/// is factorised and solved. Implementations keep their own storage (no allocation per call).
pub trait IterationMatrix<S: OdeSystem + ?Sized> {
    /// Evaluates J at (t, y), with `f0 = f(t, y)` given; returns the right-hand-side evaluations
    /// (or their equivalent in work) it took.
    fn update_jacobian(&mut self, sys: &S, t: f64, y: &[f64], f0: &[f64]) -> u64;
    /// Factorises `I - d J`; false when it is singular.
    fn factorise(&mut self, d: f64) -> bool;
    /// Solves `(I - d J) x = b` in place with the last factorisation.
    fn solve(&mut self, b: &mut [f64]);
}
