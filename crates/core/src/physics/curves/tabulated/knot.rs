//! One point of a tabulated curve with the cubic that starts there, and the search for the point
//! that starts the interval holding an x.

use super::fmm::Cubic;

/// One point, the cubic that starts there, and the curve's integral from the first point to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Knot {
    /// The point's x.
    pub x: f64,
    /// The point's y.
    pub y: f64,
    /// The cubic from this point to the next (FMM's at the last point).
    pub cubic: Cubic,
    /// `∫ y dx` from the first point to this one.
    pub integral: f64,
}

impl Knot {
    /// The cubic at dx past the point, `y + dx (b + dx (c + dx d))` (FMM's `SEVAL`).
    pub(super) fn value(&self, dx: f64) -> f64 {
        let Cubic { b, c, d } = self.cubic;
        self.y + dx * (b + dx * (c + dx * d))
    }

    /// Its slope, `b + dx (2c + 3d dx)`.
    pub(super) fn slope(&self, dx: f64) -> f64 {
        let Cubic { b, c, d } = self.cubic;
        b + dx * (2.0 * c + 3.0 * dx * d)
    }

    /// Its integral from the point to dx past it, `dx (y + dx (b/2 + dx (c/3 + dx d/4)))`.
    pub(crate) fn integral_to(&self, dx: f64) -> f64 {
        let Cubic { b, c, d } = self.cubic;
        dx * (self.y + dx * (b / 2.0 + dx * (c / 3.0 + dx * d / 4.0)))
    }
}

/// The point that starts the interval holding x: `x_k ≤ x < x_{k+1}`, the last point at x_{n−1}
/// (CEINMS's `getAbscissaPoint` takes `x_k < x ≤ x_{k+1}`; the two agree at a point to
/// rounding). None outside the points and for NaN.
#[inline]
pub(super) fn locate(knots: &[Knot], x: f64) -> Option<&Knot> {
    let (first, last) = (knots[0].x, knots[knots.len() - 1].x);
    if !(x >= first && x <= last) {
        return None;
    }
    Some(&knots[knots.partition_point(|k| k.x <= x) - 1])
}
