//! Tests of the energetics against independent truth: closed forms, quadrature of the
//! distributions they integrate, OpenSim's published probe values, hand-computed cases.

mod flux;
mod hand;
mod huxley;
mod isovelocity;
mod opensim;
mod power;
pub(crate) mod quadrature;

use crate::physics::contractile::crossbridge::Rates;

/// Huxley's (1957) rates as the project uses them, 1/s.
pub(crate) const HUXLEY: Rates = Rates {
    f1: 43.3,
    g1: 10.0,
    g2: 209.0,
    g3: 0.0,
};

/// `|a - b| <= tol * max(|b|, floor)`, with a message.
#[track_caller]
pub(crate) fn assert_rel(a: f64, b: f64, tol: f64, floor: f64, what: &str) {
    let err = (a - b).abs() / b.abs().max(floor);
    assert!(
        err <= tol,
        "{what}: {a:e} against {b:e}, relative error {err:e} > {tol:e}"
    );
}
