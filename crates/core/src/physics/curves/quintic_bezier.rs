//! Segmented quintic Bézier curves y(x), the form of Millard et al. (2013)'s muscle curves
//! (J Biomech Eng 135(2): 021005; OpenSim's `SmoothSegmentedFunction` and
//! `SegmentedQuinticBezierToolkit`), docs/model.md §4b.
//!
//! A curve is a chain of "corners": each segment is a quintic Bézier curve in the parameter
//! u ∈ [0, 1], `x(u) = Σ_k C(5,k) (1−u)^(5−k) u^k px_k` and likewise y(u), whose six control
//! points join two end points along the lines through them with the given slopes
//! (`corner_control_points`). Consecutive segments share an end point and its slope, so the
//! curve is continuously differentiable. Outside its first and last end points it continues as
//! the straight lines through them with their slopes.
//!
//! Evaluating y at x means solving x(u) = x for u on the segment that holds x. OpenSim starts
//! Newton's method from a cubic-spline guess and stops at |x(u) − x| ≤ 100 ε; here Newton's
//! method is safeguarded by bisection on [0, 1] (`super::rising_root`) and runs until x(u) is
//! within rounding of x, so
//! the two agree to about 1e-13 (tests/curve_sets.rs). Written here rather than taken from a
//! crate: no crate builds Millard's corners, and the evaluation must not allocate.

use super::rising_root::rising_root;

/// The most segments a curve has (Millard's active force–length curve has five).
pub(crate) const MAX_SEGMENTS: usize = 5;

/// Six control points of one coordinate of a quintic Bézier segment.
pub(crate) type ControlPoints = [f64; 6];

/// Binomial coefficients C(5, k).
const BINOMIAL_5: [f64; 6] = [1.0, 5.0, 10.0, 10.0, 5.0, 1.0];
/// Binomial coefficients C(4, k).
const BINOMIAL_4: [f64; 5] = [1.0, 4.0, 6.0, 4.0, 1.0];

/// Why a corner cannot be built: the lines through its end points do not meet on the side that
/// makes a C-shaped corner (OpenSim's `calcQuinticBezierCornerControlPoints` check).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("the lines through ({x0}, {y0}) and ({x1}, {y1}) with slopes {dydx0} and {dydx1} do not form a corner")]
pub(crate) struct NotACorner {
    /// First end point x.
    pub x0: f64,
    /// First end point y.
    pub y0: f64,
    /// Slope at the first end point.
    pub dydx0: f64,
    /// Second end point x.
    pub x1: f64,
    /// Second end point y.
    pub y1: f64,
    /// Slope at the second end point.
    pub dydx1: f64,
}

/// The control points of a corner from (x0, y0) with slope dydx0 to (x1, y1) with slope dydx1
/// (Millard et al. 2013, Appendix; OpenSim's `calcQuinticBezierCornerControlPoints`): the lines
/// through the end points meet at C (at the midpoint's abscissa when the slopes are within
/// √ε of each other); the inner points sit the fraction `c` of the way from each end towards
/// C, doubled, `[P0, P0 + c(C − P0) ×2, P1 + c(C − P1) ×2, P1]`. `c` is the scaled curviness
/// ([`scaled_curviness`]). Refused unless C lies closer to each end than the ends to each other.
pub(crate) fn corner_control_points(
    (x0, y0, dydx0): (f64, f64, f64),
    (x1, y1, dydx1): (f64, f64, f64),
    c: f64,
) -> Result<(ControlPoints, ControlPoints), NotACorner> {
    let xc = if (dydx0 - dydx1).abs() > f64::EPSILON.sqrt() {
        (y1 - y0 - x1 * dydx1 + x0 * dydx0) / (dydx0 - dydx1)
    } else {
        0.5 * (x1 + x0)
    };
    let yc = (xc - x1) * dydx1 + y1;
    let to_first = (xc - x0).powi(2) + (yc - y0).powi(2);
    let to_second = (xc - x1).powi(2) + (yc - y1).powi(2);
    let between = (x1 - x0).powi(2) + (y1 - y0).powi(2);
    if !(between > to_first && between > to_second) {
        return Err(NotACorner {
            x0,
            y0,
            dydx0,
            x1,
            y1,
            dydx1,
        });
    }
    let (x0m, y0m) = (x0 + c * (xc - x0), y0 + c * (yc - y0));
    let (x1m, y1m) = (x1 + c * (xc - x1), y1 + c * (yc - y1));
    Ok(([x0, x0m, x0m, x1m, x1m, x1], [y0, y0m, y0m, y1m, y1m, y1]))
}

/// A curviness in [0, 1] as the corner's fraction `0.1 + 0.8 curviness` (OpenSim's
/// `scaleCurviness`).
pub(crate) fn scaled_curviness(curviness: f64) -> f64 {
    0.1 + 0.8 * curviness
}

/// The Bézier polynomial of control points `p` at u.
fn bernstein(p: &ControlPoints, u: f64) -> f64 {
    let v = 1.0 - u;
    let mut sum = 0.0;
    for k in 0..6 {
        sum += BINOMIAL_5[k] * v.powi(5 - k as i32) * u.powi(k as i32) * p[k];
    }
    sum
}

/// d/du of [`bernstein`]: `5 Σ C(4,k) (1−u)^(4−k) u^k (p_{k+1} − p_k)`.
fn bernstein_derivative(p: &ControlPoints, u: f64) -> f64 {
    let v = 1.0 - u;
    let mut sum = 0.0;
    for k in 0..5 {
        sum += BINOMIAL_4[k] * v.powi(4 - k as i32) * u.powi(k as i32) * (p[k + 1] - p[k]);
    }
    5.0 * sum
}

/// The u in [0, 1] at which the rising Bézier polynomial `p` takes the value `target` (which
/// lies between p[0] and p[5]), from the linear guess, to rounding ([`rising_root`]).
fn solve_u(p: &ControlPoints, target: f64) -> f64 {
    let span = p[5] - p[0];
    let guess = if span != 0.0 {
        (target - p[0]) / span
    } else {
        0.5
    };
    let rounding = 4.0 * f64::EPSILON * (p[0].abs().max(p[5].abs()).max(target.abs()));
    rising_root(
        |u| (bernstein(p, u) - target, bernstein_derivative(p, u)),
        (0.0, 1.0),
        guess,
        rounding,
        f64::EPSILON,
    )
}

/// Gauss–Legendre nodes on [−1, 1], five points: exact for polynomials up to degree 9, so for
/// `y(u) x'(u)` on a quintic segment (Abramowitz & Stegun 1964, Table 25.4).
const GAUSS_NODES: [f64; 5] = [
    -0.906_179_845_938_664,
    -0.538_469_310_105_683_1,
    0.0,
    0.538_469_310_105_683_1,
    0.906_179_845_938_664,
];
/// Weights of [`GAUSS_NODES`].
const GAUSS_WEIGHTS: [f64; 5] = [
    0.236_926_885_056_189_1,
    0.478_628_670_499_366_5,
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_5,
    0.236_926_885_056_189_1,
];

/// One segment: the control points of x(u) and y(u).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Segment {
    x: ControlPoints,
    y: ControlPoints,
}

impl Segment {
    /// `∫ y dx` from the segment's start to u: `∫_0^u y(s) x'(s) ds`, exactly by five-point
    /// Gauss–Legendre.
    fn integral_to(&self, u: f64) -> f64 {
        let half = 0.5 * u;
        let mut sum = 0.0;
        for (node, weight) in GAUSS_NODES.iter().zip(GAUSS_WEIGHTS) {
            let s = half * (node + 1.0);
            sum += weight * bernstein(&self.y, s) * bernstein_derivative(&self.x, s);
        }
        half * sum
    }
}

/// A curve y(x) of up to `MAX_SEGMENTS` corners whose x rises along each segment, continued
/// linearly outside them.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentedBezier {
    segments: [Segment; MAX_SEGMENTS],
    count: usize,
    /// `∫ y dx` from the first end point to the start of each segment.
    integral_at_start: [f64; MAX_SEGMENTS],
    dydx_first: f64,
    dydx_last: f64,
}

impl SegmentedBezier {
    /// The curve through the given corners (each the `(x, y)` control points of one segment, in
    /// order, joined end to start), with the slopes at its two ends, which its linear
    /// continuations keep. At most `MAX_SEGMENTS`; the caller builds them.
    pub fn new(
        corners: &[(ControlPoints, ControlPoints)],
        dydx_first: f64,
        dydx_last: f64,
    ) -> Self {
        let empty = Segment {
            x: [0.0; 6],
            y: [0.0; 6],
        };
        let mut segments = [empty; MAX_SEGMENTS];
        let count = corners.len().min(MAX_SEGMENTS);
        for (s, &(x, y)) in segments.iter_mut().zip(corners) {
            *s = Segment { x, y };
        }
        let mut integral_at_start = [0.0; MAX_SEGMENTS];
        for i in 1..count {
            integral_at_start[i] = integral_at_start[i - 1] + segments[i - 1].integral_to(1.0);
        }
        SegmentedBezier {
            segments,
            count,
            integral_at_start,
            dydx_first,
            dydx_last,
        }
    }

    /// A curve that is NaN everywhere: what a constructor holds for constants that form no
    /// corners, which validation refuses first (a NaN force then stops the stepper with an
    /// error rather than a wrong number).
    pub(crate) fn undefined() -> Self {
        let corner = ([f64::NAN; 6], [f64::NAN; 6]);
        Self::new(&[corner], f64::NAN, f64::NAN)
    }

    fn first(&self) -> &Segment {
        &self.segments[0]
    }

    fn last(&self) -> &Segment {
        &self.segments[self.count - 1]
    }

    /// The segment holding x and the u at which it reaches x; None outside the curve's ends.
    #[inline]
    fn locate(&self, x: f64) -> Option<(&Segment, usize, f64)> {
        if !(x >= self.first().x[0] && x <= self.last().x[5]) {
            return None;
        }
        let i = self.segments[..self.count]
            .iter()
            .position(|s| x < s.x[5])
            .unwrap_or(self.count - 1);
        let s = &self.segments[i];
        Some((s, i, solve_u(&s.x, x)))
    }

    /// y at x.
    pub fn value(&self, x: f64) -> f64 {
        match self.locate(x) {
            Some((s, _, u)) => bernstein(&s.y, u),
            None if x < self.first().x[0] => {
                self.first().y[0] + self.dydx_first * (x - self.first().x[0])
            }
            // Above the last end, or NaN (which every comparison above refused).
            None => self.last().y[5] + self.dydx_last * (x - self.last().x[5]),
        }
    }

    /// dy/dx at x: `y'(u) / x'(u)` on a segment, the end slopes outside.
    pub fn slope(&self, x: f64) -> f64 {
        match self.locate(x) {
            Some((s, _, u)) => bernstein_derivative(&s.y, u) / bernstein_derivative(&s.x, u),
            None if x < self.first().x[0] => self.dydx_first,
            None => self.dydx_last,
        }
    }

    /// `∫ y dx` from the curve's first end point to x (negative below it), the linear
    /// continuations included.
    pub fn integral(&self, x: f64) -> f64 {
        match self.locate(x) {
            Some((s, i, u)) => self.integral_at_start[i] + s.integral_to(u),
            None if x < self.first().x[0] => {
                let (x0, y0) = (self.first().x[0], self.first().y[0]);
                let d = x - x0;
                y0 * d + 0.5 * self.dydx_first * d * d
            }
            None => {
                let last = self.last();
                let whole = self.integral_at_start[self.count - 1] + last.integral_to(1.0);
                let d = x - last.x[5];
                whole + last.y[5] * d + 0.5 * self.dydx_last * d * d
            }
        }
    }

    /// The x at which the curve takes the value y, for a curve whose y rises with x: on a
    /// segment, by solving y(u) = y; outside, on the continuations (the nearer end where a
    /// continuation is flat and never reaches y).
    pub(crate) fn argument_at(&self, y: f64) -> f64 {
        let (first, last) = (self.first(), self.last());
        if y.is_nan() {
            return f64::NAN;
        }
        if y < first.y[0] {
            return if self.dydx_first > 0.0 {
                first.x[0] + (y - first.y[0]) / self.dydx_first
            } else {
                first.x[0]
            };
        }
        if y > last.y[5] {
            return if self.dydx_last > 0.0 {
                last.x[5] + (y - last.y[5]) / self.dydx_last
            } else {
                last.x[5]
            };
        }
        let s = self.segments[..self.count]
            .iter()
            .find(|s| y < s.y[5])
            .unwrap_or(last);
        bernstein(&s.x, solve_u(&s.y, y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two corners: up from (0, 0) flat to (1, 0.5) with slope 1, on to (2, 2) with slope 2.
    fn curve() -> SegmentedBezier {
        let c = scaled_curviness(0.5);
        let a = corner_control_points((0.0, 0.0, 0.0), (1.0, 0.5, 1.0), c).unwrap();
        let b = corner_control_points((1.0, 0.5, 1.0), (2.0, 2.0, 2.0), c).unwrap();
        SegmentedBezier::new(&[a, b], 0.0, 2.0)
    }

    #[test]
    fn ends_joints_and_continuations_have_the_given_values_and_slopes() {
        let s = curve();
        for (x, y, dydx) in [(0.0, 0.0, 0.0), (1.0, 0.5, 1.0), (2.0, 2.0, 2.0)] {
            assert!((s.value(x) - y).abs() < 1e-15, "y({x})");
            assert!(
                (s.slope(x) - dydx).abs() < 1e-12,
                "y'({x}) = {}",
                s.slope(x)
            );
            // Both sides of the joint meet.
            let h = 1e-9;
            assert!((s.value(x + h) - s.value(x - h) - 2.0 * h * dydx).abs() < 1e-12);
        }
        assert_eq!(s.value(-1.0), 0.0);
        assert_eq!(s.value(3.0), 4.0);
        assert_eq!((s.slope(-1.0), s.slope(3.0)), (0.0, 2.0));
        // Past the end the integral adds the trapezoid of the straight line.
        let whole = s.integral(2.0);
        assert!((s.integral(3.0) - whole - 3.0).abs() < 1e-14);
    }

    #[test]
    fn the_slope_is_the_difference_and_the_argument_undoes_the_value() {
        let s = curve();
        for i in 1..200 {
            let x = 2.0 * i as f64 / 200.0 + 1e-4;
            let h = 1e-6;
            let diff = (s.value(x + h) - s.value(x - h)) / (2.0 * h);
            assert!((s.slope(x) - diff).abs() < 1e-7, "at {x}");
            let y = s.value(x);
            if s.slope(x) > 1e-3 {
                assert!((s.argument_at(y) - x).abs() < 1e-12, "at {x}");
            }
        }
        // Below the flat start, the start.
        assert_eq!(s.argument_at(-0.3), 0.0);
        assert!((s.argument_at(3.0) - 2.5).abs() < 1e-15);
    }

    #[test]
    fn lines_that_meet_on_the_wrong_side_are_not_a_corner() {
        // Both slopes below the chord's: the lines meet at (6, 3), far beyond the second point.
        let err = corner_control_points((0.0, 0.0, 0.5), (1.0, 1.0, 0.4), 0.5).unwrap_err();
        assert!(err.to_string().contains("do not form a corner"), "{err}");
        let nan = SegmentedBezier::undefined();
        assert!(nan.value(1.0).is_nan() && nan.slope(1.0).is_nan());
    }
}
