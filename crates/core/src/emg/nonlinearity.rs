//! Activation from neural activation: `a = (exp(A u) - 1)/(exp(A) - 1)` (Lloyd & Besier 2003),
//! the shape factor A bending the line a = u: concave for A < 0 (activation rises fast at low
//! excitation), convex for A > 0, the line itself in the limit A → 0.
//!
//! CEINMS (`lib/NMSmodel/Activation/ExponentialActivation.cpp`, `updateActivation`) evaluates
//! the same formula as written, with no guard at A = 0 (where it gives 0/0) and no bound on A in
//! the model; its calibration bounds A to [-2.999, -0.001] (the hard-coded
//! `StrengthCoefficients_ShapeFactor_C1_C2_TendonSlackLength_single.cpp` and the `shapeFactor`
//! range of its test calibration), and its test subject before calibration has A = 0.101198
//! (`TestData/unix/uncalibratedSubject.xml`). Lloyd & Besier calibrate A within (-3, 0).
//!
//! Accepted here: A in [-3, 3]. The curve for -A is the curve for A turned half a turn about
//! (½, ½) (`a₋A(u) = 1 - a_A(1 - u)`), so the range is the calibrated one, (-3, 0), its limit
//! -3 included, and its mirror, which holds CEINMS's uncalibrated 0.101198. Beyond it the curve
//! leaves the shapes fitted to muscle; the formula itself stays finite up to |A| ≈ 700.
//!
//! Here the formula is evaluated as `expm1(A u)/expm1(A)` (exact to rounding for small A u) and,
//! for |A| below `LINEAR_BELOW`, by its Taylor series in A to second order,
//! `u (1 + A (u - 1)/2 + A² (u - 1)(2u - 1)/12)`, whose error there is below 1e-17: no 0/0, and
//! the two sides meet to rounding at the switch.

use crate::emg::error::EmgError;

/// Lowest shape factor accepted.
pub(crate) const MIN_SHAPE_FACTOR: f64 = -3.0;
/// Highest shape factor accepted.
pub(crate) const MAX_SHAPE_FACTOR: f64 = 3.0;
/// Below this |A| the series replaces the quotient (the next term of the series, at most
/// |A|³/384 over u in [0, 1], is then under 1e-17).
pub(crate) const LINEAR_BELOW: f64 = 1e-5;

/// The shape factor A, checked to lie in `[`MIN_SHAPE_FACTOR``, `MAX_SHAPE_FACTOR`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeFactor(f64);

impl ShapeFactor {
    /// A checked: finite and within [-3, 3].
    pub fn new(a: f64) -> Result<Self, EmgError> {
        if (MIN_SHAPE_FACTOR..=MAX_SHAPE_FACTOR).contains(&a) {
            Ok(ShapeFactor(a))
        } else {
            Err(EmgError::ShapeFactor {
                value: a,
                min: MIN_SHAPE_FACTOR,
                max: MAX_SHAPE_FACTOR,
            })
        }
    }

    /// A.
    pub fn value(self) -> f64 {
        self.0
    }
}

/// `(exp(A u) - 1)/(exp(A) - 1)` as `expm1(A u)/expm1(A)`, for A ≠ 0 (Lloyd & Besier 2003).
fn exponential(u: f64, a: f64) -> f64 {
    (a * u).exp_m1() / a.exp_m1()
}

/// The same to second order in A about A = 0: `u (1 + A (u - 1)/2 + A² (u - 1)(2u - 1)/12)`.
fn near_linear(u: f64, a: f64) -> f64 {
    u * (1.0 + a * (u - 1.0) / 2.0 + a * a * (u - 1.0) * (2.0 * u - 1.0) / 12.0)
}

/// Activation for neural activation `u`, clamped to [0, 1] first as CEINMS clamps its excitation
/// (`setEmg`); 0 ↦ 0, 1 ↦ 1, increasing. A NaN `u` gives NaN.
pub fn activation(u: f64, shape: ShapeFactor) -> f64 {
    let u = u.clamp(0.0, 1.0);
    let a = shape.value();
    if a.abs() < LINEAR_BELOW {
        near_linear(u, a)
    } else {
        exponential(u, a)
    }
}
