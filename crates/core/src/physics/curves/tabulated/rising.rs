//! The rising part of a tabulated curve, the stretch that [`super::TabulatedCurve::argument_at`]
//! inverts: the longest stretch on which the spline rises (its slope positive but at isolated
//! points) that holds the steepest place of the interval whose points rise the most. Anchoring
//! on the points rather than on the spline keeps the bulges a spline makes in long padding
//! intervals out (CEINMS's force–velocity curve rises by 2.71 between its padding points at
//! ṽ = −10 and −1, more than its true rise of 1.75).

use super::knot::{locate, Knot};

/// One stretch of an interval between the stationary points of its cubic.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Span {
    from: f64,
    to: f64,
    rising: bool,
}

/// The stretch `[start, end]` on which the curve rises, its values there, and the intervals
/// (indices of their first points) holding its two ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct RisingPart {
    pub start: f64,
    pub end: f64,
    pub start_value: f64,
    pub end_value: f64,
    /// The interval with `x_first ≤ start < x_{first+1}`.
    pub first: usize,
    /// The interval with `x_last < end ≤ x_{last+1}`.
    pub last: usize,
}

/// The rising part of the curve through `knots`; None where no two consecutive points rise.
pub(super) fn rising_part(knots: &[Knot]) -> Option<RisingPart> {
    let anchor = steepest_place(knots, steepest_rising_interval(knots)?);
    let spans = spans(knots);
    let at = spans
        .iter()
        .position(|s| s.rising && s.from <= anchor && anchor <= s.to)?;
    let lo = (0..=at).rev().take_while(|&i| spans[i].rising).last()?;
    let hi = (at..spans.len()).take_while(|&i| spans[i].rising).last()?;
    let (start, end) = (spans[lo].from, spans[hi].to);
    Some(RisingPart {
        start,
        end,
        start_value: value_at(knots, start),
        end_value: value_at(knots, end),
        first: knots.partition_point(|k| k.x <= start) - 1,
        last: knots.partition_point(|k| k.x < end) - 1,
    })
}

/// The spline at an x between the first and the last point.
fn value_at(knots: &[Knot], x: f64) -> f64 {
    locate(knots, x).map_or(f64::NAN, |k| k.value(x - k.x))
}

/// The interval whose points rise the most, `y_{i+1} − y_i > 0` (the first of equals).
fn steepest_rising_interval(knots: &[Knot]) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (i, pair) in knots.windows(2).enumerate() {
        let rise = pair[1].y - pair[0].y;
        if rise > best.map_or(0.0, |(_, r)| r) {
            best = Some((i, rise));
        }
    }
    best.map(|(i, _)| i)
}

/// Where the cubic of interval i is steepest: at an end, or at the vertex of its slope's
/// parabola, `dx = −c/(3d)`, where that is a maximum inside. Its slope there is at least the
/// points' mean slope, so positive for a rising interval.
fn steepest_place(knots: &[Knot], i: usize) -> f64 {
    let (k, h) = (&knots[i], knots[i + 1].x - knots[i].x);
    let vertex = -k.cubic.c / (3.0 * k.cubic.d);
    let mut best = (0.0, k.slope(0.0));
    for dx in [h, vertex] {
        if dx > 0.0 && dx <= h && k.slope(dx) > best.1 {
            best = (dx, k.slope(dx));
        }
    }
    if best.0 == h {
        knots[i + 1].x
    } else {
        k.x + best.0
    }
}

/// Every interval cut at the stationary points inside it, in order, each piece marked rising
/// where its slope midway is positive.
fn spans(knots: &[Knot]) -> Vec<Span> {
    let mut out = Vec::with_capacity(3 * knots.len());
    for pair in knots.windows(2) {
        let (k, h) = (&pair[0], pair[1].x - pair[0].x);
        let (roots, count) = stationary_points(k, h);
        let mut from = 0.0;
        for to in roots[..count].iter().copied().chain([h]) {
            let rising = k.slope(0.5 * (from + to)) > 0.0;
            let x = |dx: f64| if dx == h { pair[1].x } else { k.x + dx };
            out.push(Span {
                from: x(from),
                to: x(to),
                rising,
            });
            from = to;
        }
    }
    out
}

/// The roots inside (0, h) of the cubic's slope `b + 2c·dx + 3d·dx²`, ascending, by the
/// quadratic formula in its cancellation-free form (q = −(B + sign(B)·√disc)/2, roots q/A and
/// C/q).
pub(super) fn stationary_points(k: &Knot, h: f64) -> ([f64; 2], usize) {
    let (a, b, c) = (3.0 * k.cubic.d, 2.0 * k.cubic.c, k.cubic.b);
    let mut roots = [f64::NAN; 2];
    if a == 0.0 {
        roots[0] = -c / b;
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            roots = [q / a, c / q];
        }
    }
    let mut inside = [0.0; 2];
    let mut count = 0;
    for r in roots {
        if r > 0.0 && r < h {
            inside[count] = r;
            count += 1;
        }
    }
    if count == 2 && inside[0] > inside[1] {
        inside.swap(0, 1);
    }
    // A double root touches zero slope without a change of sign: no stationary point between.
    if count == 2 && inside[0] == inside[1] {
        count = 0;
    }
    (inside, count)
}
