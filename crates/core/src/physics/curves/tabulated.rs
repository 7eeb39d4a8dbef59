//! Tabulated curves: a normalised curve given as points (x, y), such as the shared curves of a
//! CEINMS subject file (`activeForceLength`, `passiveForceLength`, `forceVelocity`,
//! `tendonForceStrain`; data/ceinms/uncalibratedSubject.xml), interpolated exactly as CEINMS
//! interpolates them, so that a subject calibrated in CEINMS means the same curves here.
//!
//! # How CEINMS interpolates
//!
//! CEINMS holds each curve as a `Curve<CurveMode::Offline>` (lib/NMSmodel/MTU.h, `typedef
//! Curve<CurveMode::Offline> CurveOffline`), whose interpolation defaults to
//! `CurveMode::Cubic` (lib/Curve/Curve.h); lib/NMSmodel/SetupDataStructure.cpp fills it with
//! the file's points (`resetPointsWith(x, y)`). lib/Curve/Curve.cpp then:
//!
//! - builds the cubic spline of Forsythe, Malcolm & Moler (1977), Computer Methods for
//!   Mathematical Computations, the `SPLINE` routine ("translated from a Fortran version printed
//!   in … pp 77-8", `computeCoefficients(Int2Type<CurveMode::Cubic>)`; here tabulated/fmm.rs): twice
//!   continuously differentiable, through every point, with FMM's end conditions: the third
//!   derivative at each end is that of the cubic through the four points nearest it ("Third
//!   derivatives at x_.at(0) and x_.at(n-1) are obtained from divided differences"). Despite the
//!   file's comment ("coefficients of natural splines") it is not the natural spline; it
//!   reproduces any cubic exactly (four points or more), a parabola through three points and a
//!   line through two;
//! - evaluates `y_k + dx (b_k + dx (c_k + dx d_k))` on the interval that holds x (`getValue`,
//!   FMM's `SEVAL`), found by `std::lower_bound` (`getAbscissaPoint`): the interval with
//!   `x_k < x ≤ x_{k+1}`. Here the interval is the one with `x_k ≤ x < x_{k+1}`, so that the
//!   curve takes each point's y exactly; the two agree at a point to rounding, by continuity;
//! - outside the points, `getValue` holds the end values: y_0 below x_0, y_{n−1} above
//!   x_{n−1}. [`TabulatedCurve::value`] does the same, and its slope and integral follow
//!   that held value (slope 0, integral growing by the end value per unit). CEINMS's
//!   `getFirstDerivative` instead returns the spline's end slopes b_0 and b_{n−1} there, a slope
//!   its own value does not have; with the subject file's padding points (x = −5 … 5,
//!   −10 … 10, −10 … 20) a muscle hardly leaves the points (CEINMS clamps the normalised
//!   velocity to [−1, 1], lib/NMSmodel/MTU.cpp `updateMuscleForce`).
//!
//! Matching CEINMS is the point of the choice: a calibrated subject's parameters (optimal fibre
//! length, tendon slack length, strength) were fitted with these very curves.
//!
//! # Quirks of the spline on CEINMS's curves
//!
//! A cubic spline through a kink or a long flat padding interval overshoots. On the curves of
//! data/ceinms/uncalibratedSubject.xml, at the stationary points of their cubics (the tests
//! check these figures):
//!
//! - active force–length: peak 1.000434 at l̃ = 1.00735 (the points' highest is 0.993333 at
//!   1.045), 1.000198 at l̃ = 1; below zero by 1.160e-4 at 0.2329, 3.24e-6 at 0.4029, 1.54e-6
//!   at 1.6192 and 1.022e-4 at 1.8608; above zero in the padding by 9.12e-4 at −2.5 and
//!   2.98e-4 at 3.6;
//! - passive force–length: −5.03e-4 at −2.0 (padding), 2.0000149 at 1.6004 and 2.0105 at 3.30
//!   above its plateau of 2;
//! - force–velocity: a bulge to 2.7077 at ṽ = −7.084 between the padding points −10 and −1, a
//!   dip to −0.01407 at −1.2394, and past its last inner point (0.8) up to 1.8143 at 1.4934 and
//!   down to 0.4686 at 7.2055 (CEINMS evaluates it on [−1, 1] only);
//! - tendon force–strain: −1.2238 at strain −5.0 (padding), 1.88e-4 at −0.00142 and −5.88e-4
//!   at −0.00038 next to the slack strain, 345.0018 at 14.6 above its plateau of 345.
//!
//! # The inverse
//!
//! `TabulatedCurve::argument_at` inverts the curve's rising part (tabulated/rising.rs): the
//! longest stretch on which the spline rises that holds the steepest place of the interval
//! whose points rise the most. Below and above the values it takes there it returns the
//! stretch's ends; the flat and falling parts (a tendon's slack padding, its plateau, the
//! descending limb of the active curve) are never inverted. On the subject file's curves the
//! rising parts run between stationary points: l̃ from 0.40294 to 1.00735 (active), 0.99962 to
//! 1.60038 (passive), ṽ from −1.23938 to 1.49336, strain from −0.00038 to 9.20038 (tendon).
//!
//! # Why written here
//!
//! No crate builds FMM's end conditions: `splines` (Catmull–Rom, Bézier, cosine, linear and step
//! keys), `enterpolation` (linear, Bézier and B-spline curves from given control points, no
//! interpolating spline solve), `peroxide` (`CubicSpline`: natural only; Hermite splines with
//! Akima or quadratic slopes), `cubic-splines` (natural, periodic, given first or second
//! derivatives) and `ndarray-interp` (natural, not-a-knot, clamped, periodic) each give a
//! different spline through the same points. The tests compare with R's
//! `splinefun(method = "fmm")` and SciPy (crates/core/tests/reference/tabulated/, written by
//! scripts/fmm_spline_reference.py).
//!
//! Evaluation neither allocates nor panics: NaN gives NaN, ±∞ the held end values.

mod fmm;
mod knot;
mod rising;
#[cfg(test)]
mod tests;

use crate::physics::curves::rising_root::rising_root;
use crate::physics::limb_params::tabulated_points::{split, Points};
use fmm::Cubic;
use knot::Knot;
use rising::RisingPart;

/// Why points do not make a tabulated curve; indices count from 0.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TabulatedCurveError {
    /// Another count of y than of x.
    #[error("{x} x points and {y} y points")]
    Lengths {
        /// The x count.
        x: usize,
        /// The y count.
        y: usize,
    },
    /// Fewer than two points.
    #[error("{points} point(s), a tabulated curve has at least two")]
    TooFewPoints {
        /// The count.
        points: usize,
    },
    /// An x that is NaN or infinite.
    #[error("x[{index}] = {value} is not finite")]
    NotFiniteX {
        /// Its index.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A y that is NaN or infinite.
    #[error("y[{index}] = {value} is not finite")]
    NotFiniteY {
        /// Its index.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// An x not above the one before.
    #[error("x[{index}] = {x} is not above x[{}] = {previous}", .index - 1)]
    NotIncreasing {
        /// Its index.
        index: usize,
        /// Its value.
        x: f64,
        /// The one before.
        previous: f64,
    },
    /// Points so far apart, so close or so large that the spline's coefficients or its
    /// integral overflow.
    #[error(
        "the spline through the points overflows (a coefficient or its integral is not finite)"
    )]
    Overflow,
}

/// A curve y(x) through points, by CEINMS's cubic spline (the module's header), holding its end
/// values outside them. Its x and y are whatever the points are in (a normalised fibre length,
/// velocity or tendon strain; a force as a fraction of the maximum isometric force).
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedCurve {
    knots: Vec<Knot>,
    rising: Option<RisingPart>,
    /// The slope outside the points: 0, NaN for [`TabulatedCurve::undefined`].
    held_slope: f64,
}

/// The curve of a muscle's points (`curves = "tabulated"`), [`TabulatedCurve::undefined`]
/// where there are none or they make no curve (validation refuses both first).
pub(crate) fn of_points(points: Option<&Points>) -> TabulatedCurve {
    points
        .and_then(|p| {
            let (x, y) = split(p);
            TabulatedCurve::new(&x, &y).ok()
        })
        .unwrap_or_else(TabulatedCurve::undefined)
}

impl TabulatedCurve {
    /// The spline through `(x[i], y[i])`: as many y as x, at least two points, all finite, x
    /// strictly increasing, and a spline that does not overflow.
    pub fn new(x: &[f64], y: &[f64]) -> Result<TabulatedCurve, TabulatedCurveError> {
        check_points(x, y)?;
        let mut knots: Vec<Knot> = x
            .iter()
            .zip(y)
            .zip(fmm::cubics(x, y))
            .map(|((&x, &y), cubic)| Knot {
                x,
                y,
                cubic,
                integral: 0.0,
            })
            .collect();
        for i in 1..knots.len() {
            let previous = &knots[i - 1];
            knots[i].integral = previous.integral + previous.integral_to(x[i] - x[i - 1]);
        }
        let finite = |k: &Knot| {
            let Cubic { b, c, d } = k.cubic;
            [b, c, d, k.integral].iter().all(|v| v.is_finite())
        };
        if !knots.iter().all(finite) {
            return Err(TabulatedCurveError::Overflow);
        }
        Ok(TabulatedCurve {
            rising: rising::rising_part(&knots),
            knots,
            held_slope: 0.0,
        })
    }

    /// A curve that is NaN everywhere: what a constructor holds for points that make no curve,
    /// which validation refuses first (a NaN force then stops the stepper with an error rather
    /// than a wrong number).
    pub(crate) fn undefined() -> Self {
        let nan = Cubic {
            b: f64::NAN,
            c: f64::NAN,
            d: f64::NAN,
        };
        let knot = |x| Knot {
            x,
            y: f64::NAN,
            cubic: nan,
            integral: f64::NAN,
        };
        TabulatedCurve {
            knots: vec![knot(0.0), knot(1.0)],
            rising: None,
            held_slope: f64::NAN,
        }
    }

    /// The points, in order.
    #[cfg(test)]
    pub(crate) fn points(&self) -> impl ExactSizeIterator<Item = (f64, f64)> + '_ {
        self.knots.iter().map(|k| (k.x, k.y))
    }

    /// The first and the last x, between which the spline runs.
    #[cfg(test)]
    pub(crate) fn domain(&self) -> (f64, f64) {
        (self.first().x, self.last().x)
    }

    /// The stretch `(start, end)` of x that [`TabulatedCurve::argument_at`] inverts (the module's
    /// header); None where no two consecutive points rise.
    pub(crate) fn rising_part(&self) -> Option<(f64, f64)> {
        self.rising.map(|r| (r.start, r.end))
    }

    fn first(&self) -> &Knot {
        &self.knots[0]
    }

    fn last(&self) -> &Knot {
        &self.knots[self.knots.len() - 1]
    }

    /// The point that starts the interval holding x ([`knot::locate`]).
    #[inline]
    fn locate(&self, x: f64) -> Option<&Knot> {
        knot::locate(&self.knots, x)
    }

    /// y at x; the end values outside the points (CEINMS's `getValue`), NaN for NaN.
    pub fn value(&self, x: f64) -> f64 {
        match self.locate(x) {
            Some(k) => k.value(x - k.x),
            None if x.is_nan() => f64::NAN,
            None if x < self.first().x => self.first().y,
            None => self.last().y,
        }
    }

    /// dy/dx at x: the spline's slope between the points, 0 outside them where the value is
    /// held (the module's header says how CEINMS differs), NaN for NaN.
    pub fn slope(&self, x: f64) -> f64 {
        match self.locate(x) {
            Some(k) => k.slope(x - k.x),
            None if x.is_nan() => f64::NAN,
            None => self.held_slope,
        }
    }

    /// `∫ y dx` from the first point to x (negative below it), exact for the piecewise cubic
    /// (each piece integrated in closed form), the held end values included outside: ±∞ at ±∞
    /// unless the end value is 0.
    pub(crate) fn integral(&self, x: f64) -> f64 {
        let (first, last) = (self.first(), self.last());
        match self.locate(x) {
            Some(k) => k.integral + k.integral_to(x - k.x),
            None if x.is_nan() => f64::NAN,
            None if x < first.x => held_integral(first.y, x - first.x),
            None => last.integral + held_integral(last.y, x - last.x),
        }
    }

    /// `∫ y dx` from `from` to `to` (a strain energy from the slack length, say); 0 when they
    /// are equal, infinite ones included.
    pub(crate) fn integral_between(&self, from: f64, to: f64) -> f64 {
        if from == to {
            0.0
        } else {
            self.integral(to) - self.integral(from)
        }
    }

    /// The x at which the curve's rising part ([`TabulatedCurve::rising_part`]) takes the value
    /// y; its start for a y at or below the value there, its end for a y at or above (a tendon's
    /// force beyond its plateau gives the plateau's start, never a place in the padding); NaN for
    /// NaN and for a curve without a rising part.
    pub(crate) fn argument_at(&self, y: f64) -> f64 {
        let Some(r) = self.rising else {
            return f64::NAN;
        };
        if y.is_nan() {
            return f64::NAN;
        }
        if y <= r.start_value {
            return r.start;
        }
        if y >= r.end_value {
            return r.end;
        }
        // The points strictly inside the rising part rise: count those at or below y.
        let k = r.first + self.knots[r.first + 1..=r.last].partition_point(|k| k.y <= y);
        let knot = &self.knots[k];
        let lo = if k == r.first { r.start } else { knot.x };
        let hi = if k == r.last {
            r.end
        } else {
            self.knots[k + 1].x
        };
        knot.x + solve_rising(knot, y, (lo - knot.x, hi - knot.x))
    }
}

/// `∫ y dx` over a distance `d` at the held value `y`: `y·d`, 0 for y = 0 (also at d = ±∞).
fn held_integral(y: f64, d: f64) -> f64 {
    if y == 0.0 {
        0.0
    } else {
        y * d
    }
}

/// The dx in `[lo, hi]` at which the rising cubic of `knot` takes `target` (which lies between
/// its values at lo and hi), from the secant's guess, until the step is below rounding of x
/// ([`rising_root`]).
fn solve_rising(knot: &Knot, target: f64, (lo, hi): (f64, f64)) -> f64 {
    let (below, above) = (knot.value(lo) - target, knot.value(hi) - target);
    let guess = if above > below {
        lo - below * (hi - lo) / (above - below)
    } else {
        0.5 * (lo + hi)
    };
    let rounding = 2.0 * f64::EPSILON * (knot.x.abs() + lo.abs().max(hi.abs()));
    rising_root(
        |dx| (knot.value(dx) - target, knot.slope(dx)),
        (lo, hi),
        guess,
        0.0,
        rounding,
    )
}

/// The points' checks, in the order the error lists them.
fn check_points(x: &[f64], y: &[f64]) -> Result<(), TabulatedCurveError> {
    if x.len() != y.len() {
        return Err(TabulatedCurveError::Lengths {
            x: x.len(),
            y: y.len(),
        });
    }
    if x.len() < 2 {
        return Err(TabulatedCurveError::TooFewPoints { points: x.len() });
    }
    if let Some((index, &value)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(TabulatedCurveError::NotFiniteX { index, value });
    }
    if let Some((index, &value)) = y.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(TabulatedCurveError::NotFiniteY { index, value });
    }
    if let Some(index) = (1..x.len()).find(|&i| x[i] <= x[i - 1]) {
        return Err(TabulatedCurveError::NotIncreasing {
            index,
            x: x[index],
            previous: x[index - 1],
        });
    }
    Ok(())
}
