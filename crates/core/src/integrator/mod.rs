//! Time integration: the implicit stepper used on every tick (ESDIRK methods of second to fourth
//! order over an iteration matrix that may exploit the system's structure). The adaptive
//! explicit reference solver the tests compare it with is test support
//! (tests/common/reference.rs).
//!
//! - `esdirk`: the stepper (stages, simplified Newton, sub-step control).
//! - `tableau`: its tableaux, TR-BDF2, ARK3(2)4L\[2\]SA and ESDIRK4(3)6L\[2\]SA.
//! - `dense`, `arrowhead`: iteration matrices, general and for the plant's structure.

pub(crate) mod arrowhead;
pub(crate) mod dense;
pub(crate) mod esdirk;
pub(crate) mod tableau;

/// A first-order ODE system `dy/dt = f(t, y)`.
pub(crate) trait OdeSystem {
    /// Evaluates `dy = f(t, y)`.
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]);
    /// Typical magnitude of each component (the absolute tolerance unit and the
    /// finite-difference step scale), written to `out`.
    fn scales(&self, out: &mut [f64]);
}

/// The iteration matrix `I - d J` of the implicit stages: how its Jacobian J is evaluated, how it
/// is factorised and solved. Implementations keep their own storage (no allocation per call).
pub(crate) trait IterationMatrix<S: OdeSystem + ?Sized> {
    /// Evaluates J at (t, y), with `f0 = f(t, y)` given; returns the right-hand-side evaluations
    /// (or their equivalent in work) it took.
    fn update_jacobian(&mut self, sys: &S, t: f64, y: &[f64], f0: &[f64]) -> u64;
    /// Factorises `I - d J`; false when it is singular.
    fn factorise(&mut self, d: f64) -> bool;
    /// Solves `(I - d J) x = b` in place with the last factorisation.
    fn solve(&mut self, b: &mut [f64]);
}

/// The implicit stages did not converge even with a fresh Jacobian and halved steps.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("implicit step did not converge at t = {t}")]
pub(crate) struct ConvergenceError {
    /// Time at which the step started, s.
    pub t: f64,
}

/// Work counters, for benchmarks and reports.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Right-hand-side evaluations (Jacobian evaluations included, in their equivalent).
    pub rhs_evals: u64,
    /// Jacobian evaluations.
    pub jacobians: u64,
    /// Factorisations of the iteration matrix.
    pub factorisations: u64,
    /// Linear solves with it.
    pub solves: u64,
    /// Sub-steps taken.
    pub substeps: u64,
    /// Steps rejected or split.
    pub rejected: u64,
}

impl std::ops::Add for Stats {
    type Output = Stats;
    fn add(self, o: Stats) -> Stats {
        Stats {
            rhs_evals: self.rhs_evals + o.rhs_evals,
            jacobians: self.jacobians + o.jacobians,
            factorisations: self.factorisations + o.factorisations,
            solves: self.solves + o.solves,
            substeps: self.substeps + o.substeps,
            rejected: self.rejected + o.rejected,
        }
    }
}
