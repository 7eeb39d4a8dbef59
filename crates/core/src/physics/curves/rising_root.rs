//! Where a rising function of one variable crosses zero inside a bracket: the solve behind the
//! tabulated and the quintic Bézier curves' evaluations and inverses ([`super::tabulated`],
//! [`super::quintic_bezier`]). Written here rather than taken from a root-finding crate: the
//! loop is a dozen lines, must not allocate or fail, and takes the function's slope, which the
//! curves have in closed form.

/// Iterations at the most: a step that would leave the bracket halves it instead, so 100 shrink
/// any bracket of doubles below one ulp; Newton's steps converge in a few.
const MAX_ITERATIONS: usize = 100;

/// The x in `[lo, hi]` at which the rising `f` crosses zero (`f(lo) <= 0 <= f(hi)`),
/// `f_and_slope` giving its value and slope at x: Newton's method from `x0`, kept inside the
/// bracket every evaluation shrinks, bisection where a step would leave it. It stops at a value
/// within `residual` of zero, or at a step or bracket below `resolution` (the rounding of x).
pub(crate) fn rising_root(
    f_and_slope: impl Fn(f64) -> (f64, f64),
    (mut lo, mut hi): (f64, f64),
    x0: f64,
    residual: f64,
    resolution: f64,
) -> f64 {
    let mut x = x0.clamp(lo, hi);
    for _ in 0..MAX_ITERATIONS {
        let (r, slope) = f_and_slope(x);
        if r.abs() <= residual {
            return x;
        }
        if r < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let newton = x - r / slope;
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - x).abs() <= resolution || hi - lo <= resolution {
            return next;
        }
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_root_of_a_rising_cubic_and_of_a_flat_start() {
        // x³ + x - 3 rises everywhere; its root is 1.2134116627622296.
        let f = |x: f64| (x * x * x + x - 3.0, 3.0 * x * x + 1.0);
        let x = rising_root(f, (0.0, 2.0), 0.0, 0.0, 4.0 * f64::EPSILON);
        assert!((x - 1.213_411_662_762_229_6).abs() < 1e-15, "{x}");
        // Flat at the start (slope 0): Newton's first step is bisection, and it still converges.
        let g = |x: f64| (x * x - 0.25, 2.0 * x);
        let x = rising_root(g, (0.0, 1.0), 0.0, 0.0, 4.0 * f64::EPSILON);
        assert!((x - 0.5).abs() < 1e-15, "{x}");
        // NaN in, a point of the bracket out: no panic, no loop without end.
        let x = rising_root(|_| (f64::NAN, f64::NAN), (0.0, 1.0), 0.5, 0.0, f64::EPSILON);
        assert!((0.0..=1.0).contains(&x));
    }
}
