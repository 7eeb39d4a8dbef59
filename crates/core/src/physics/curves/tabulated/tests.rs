//! The tabulated curve against R's FMM spline and SciPy (crates/core/tests/reference/tabulated/, written by
//! scripts/fmm_spline_reference.py), against its own defining properties (through the points,
//! C² at them, FMM's end conditions, cubics reproduced, slope and integral consistent with the
//! value, the inverse undoing it), on the four curves of data/ceinms/uncalibratedSubject.xml as
//! the reference holds them (their values, the active curve's peak, the overshoots the module's
//! header reports; that the subject file's reader gives these very points is tested by the
//! measured-data crate, crates/measured/tests/subject_curves.rs), and on bad points and hostile
//! arguments.

use super::rising::stationary_points;
use super::{Knot, TabulatedCurve, TabulatedCurveError};

const POINTS: &str = include_str!("../../../../tests/reference/tabulated/fmm_points.csv");
const VALUES: &str = include_str!("../../../../tests/reference/tabulated/fmm_values.csv");

/// The subject file's curves, in the reference's names.
const SUBJECT_CURVES: [&str; 4] = [
    "activeForceLength",
    "passiveForceLength",
    "forceVelocity",
    "tendonForceStrain",
];

/// A table's rows without its comment line and header, split at commas.
fn rows(table: &str) -> impl Iterator<Item = Vec<&str>> {
    table
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').collect())
}

fn num(s: &str) -> f64 {
    s.parse().unwrap()
}

/// The reference's curves by name, in order, with their points.
fn reference_points() -> Vec<(String, Vec<f64>, Vec<f64>)> {
    let mut out: Vec<(String, Vec<f64>, Vec<f64>)> = Vec::new();
    for r in rows(POINTS) {
        if out.last().map(|c| c.0.as_str()) != Some(r[0]) {
            out.push((r[0].to_string(), Vec::new(), Vec::new()));
        }
        let c = out.last_mut().unwrap();
        c.1.push(num(r[2]));
        c.2.push(num(r[3]));
    }
    out
}

/// The subject file's four curves, from the reference's points.
fn subject_curves() -> [TabulatedCurve; 4] {
    let points = reference_points();
    SUBJECT_CURVES.map(|name| {
        let (_, x, y) = points.iter().find(|c| c.0 == name).unwrap();
        TabulatedCurve::new(x, y).unwrap()
    })
}

/// The second derivative `2c + 6d·dx` (not part of the curve's interface).
fn second(curve: &TabulatedCurve, x: f64) -> f64 {
    let k = curve.locate(x).unwrap();
    2.0 * k.cubic.c + 6.0 * k.cubic.d * (x - k.x)
}

/// The interval pairs (start point, next point).
fn intervals(curve: &TabulatedCurve) -> impl Iterator<Item = (&Knot, &Knot)> {
    curve.knots.windows(2).map(|w| (&w[0], &w[1]))
}

/// The largest |a − b| over pairs, relative to `scale`.
fn worst(pairs: &[(f64, f64)], scale: f64) -> f64 {
    pairs
        .iter()
        .map(|(a, b)| (a - b).abs() / scale)
        .fold(0.0, f64::max)
}

fn largest(values: impl Iterator<Item = f64>) -> f64 {
    values.map(f64::abs).fold(0.0, f64::max)
}

#[test]
fn r_agrees_to_rounding() {
    let points = reference_points();
    for (name, x, y) in &points {
        let curve = TabulatedCurve::new(x, y).unwrap();
        let at: Vec<Vec<f64>> = rows(VALUES)
            .filter(|r| r[0] == name.as_str())
            .map(|r| r[1..].iter().map(|s| num(s)).collect())
            .collect();
        // Every point and seven places inside each interval.
        assert_eq!(at.len(), 8 * (x.len() - 1) + 1, "{name}");
        let column = |i: usize, f: &dyn Fn(f64) -> f64| {
            let pairs: Vec<(f64, f64)> = at.iter().map(|r| (f(r[0]), r[i])).collect();
            let scale = largest(at.iter().map(|r| r[i])).max(f64::MIN_POSITIVE);
            worst(&pairs, scale)
        };
        let value = column(1, &|v| curve.value(v));
        let slope = column(2, &|v| curve.slope(v));
        let second_derivative = column(3, &|v| second(&curve, v));
        let integral = column(4, &|v| curve.integral(v));
        // Measured: at most 5.4e-16 in every column (random9's integral).
        for (what, gap) in [
            ("value", value),
            ("slope", slope),
            ("second", second_derivative),
            ("integral", integral),
        ] {
            assert!(
                gap < 4e-15,
                "{name}: {what} differs by {gap:e} of its largest"
            );
        }
    }
}

/// Every reference curve.
fn all_curves() -> Vec<(String, TabulatedCurve)> {
    reference_points()
        .into_iter()
        .map(|(name, x, y)| (name, TabulatedCurve::new(&x, &y).unwrap()))
        .collect()
}

#[test]
fn the_spline_passes_through_every_point_and_is_c2_at_each() {
    for (name, curve) in all_curves() {
        for (x, y) in curve.points() {
            assert_eq!(curve.value(x).to_bits(), y.to_bits(), "{name} at {x}");
        }
        let scale_y = largest(curve.points().map(|p| p.1));
        let scale_b = largest(curve.knots.iter().map(|k| k.cubic.b));
        let scale_c = largest(curve.knots.iter().map(|k| k.cubic.c)).max(f64::MIN_POSITIVE);
        let (mut value, mut slope, mut second_derivative) = (0.0_f64, 0.0_f64, 0.0_f64);
        for (k, next) in intervals(&curve) {
            let h = next.x - k.x;
            value = value.max((k.value(h) - next.y).abs() / scale_y);
            slope = slope.max((k.slope(h) - next.cubic.b).abs() / scale_b);
            let left = 2.0 * k.cubic.c + 6.0 * k.cubic.d * h;
            second_derivative = second_derivative.max((left - 2.0 * next.cubic.c).abs() / scale_c);
        }
        // Measured: at most 6.3e-16 (forceVelocity's values).
        assert!(
            value < 4e-15 && slope < 4e-15 && second_derivative < 4e-15,
            "{name}"
        );
    }
}

/// f[x_0, …, x_3] by the divided-difference table.
fn divided_difference(x: &[f64], y: &[f64]) -> f64 {
    let mut f = y.to_vec();
    for order in 1..x.len() {
        for i in (order..x.len()).rev() {
            f[i] = (f[i] - f[i - 1]) / (x[i] - x[i - order]);
        }
    }
    f[x.len() - 1]
}

#[test]
fn the_ends_have_fmms_third_derivatives() {
    for (name, x, y) in reference_points() {
        let curve = TabulatedCurve::new(&x, &y).unwrap();
        let n = x.len();
        let (first, last) = (&curve.knots[0], &curve.knots[n - 2]);
        let (left, right) = if n >= 4 {
            let left = divided_difference(&x[..4], &y[..4]);
            let right = divided_difference(&x[n - 4..], &y[n - 4..]);
            (6.0 * left, 6.0 * right)
        } else {
            (0.0, 0.0)
        };
        let scale = largest(curve.knots.iter().map(|k| 6.0 * k.cubic.d)).max(1.0);
        let gap = ((6.0 * first.cubic.d - left).abs() + (6.0 * last.cubic.d - right).abs()) / scale;
        // Measured: at most 7.4e-16 (cubic4).
        assert!(gap < 1e-14, "{name}: {gap:e}");
    }
    // Two points: the line; three: the parabola through them.
    let line = TabulatedCurve::new(&[0.5, 2.0], &[1.0, -0.5]).unwrap();
    assert_eq!((line.value(1.25), line.slope(1.9)), (0.25, -1.0));
    let parabola = |v: f64| 1.0 + 4.0 * v - 5.5 * v * v;
    let x = [0.0, 0.3, 1.0];
    let three = TabulatedCurve::new(&x, &x.map(parabola)).unwrap();
    for i in 0..=40 {
        let v = -0.0 + i as f64 / 40.0;
        assert!((three.value(v) - parabola(v)).abs() < 1e-15, "at {v}");
        assert!((three.slope(v) - (4.0 - 11.0 * v)).abs() < 1e-14, "at {v}");
    }
}

#[test]
fn a_cubic_is_reproduced_to_rounding() {
    let p = |v: f64| 0.3 - 2.0 * v + 1.5 * v * v - 0.7 * v * v * v;
    let dp = |v: f64| -2.0 + 3.0 * v - 2.1 * v * v;
    let antiderivative = |v: f64| 0.3 * v - v * v + 0.5 * v.powi(3) - 0.175 * v.powi(4);
    let x = [-1.7, -1.1, -0.95, 0.0, 0.2, 0.9, 1.85, 2.4, 3.1];
    let curve = TabulatedCurve::new(&x, &x.map(p)).unwrap();
    let (mut value, mut slope, mut integral) = (0.0_f64, 0.0_f64, 0.0_f64);
    for i in 0..=480 {
        let v = -1.7 + 4.8 * i as f64 / 480.0;
        value = value.max((curve.value(v) - p(v)).abs());
        slope = slope.max((curve.slope(v) - dp(v)).abs());
        integral =
            integral.max((curve.integral(v) - (antiderivative(v) - antiderivative(-1.7))).abs());
    }
    // |p| ≤ 12.3 and |p'| ≤ 13.2 on [−1.7, 3.1]; measured 5.3e-15, 1.8e-14 and 4.9e-15.
    assert!(
        value < 5e-14 && slope < 2e-13 && integral < 5e-14,
        "{value} {slope} {integral}"
    );
}

#[test]
fn the_slope_is_the_central_difference_of_the_value() {
    // On a cubic the central difference of step s exceeds the slope by d·s² exactly, so
    // Richardson's (4 D(s/2) − D(s))/3 leaves only the rounding of the values, ~ε·|y|/s.
    for (name, curve) in all_curves() {
        let scale = largest(curve.knots.iter().map(|k| k.cubic.b));
        let y_scale = largest(curve.points().map(|p| p.1));
        let central = |v: f64, s: f64| (curve.value(v + s) - curve.value(v - s)) / (2.0 * s);
        let mut worst_ratio = 0.0_f64;
        for (k, next) in intervals(&curve) {
            let w = next.x - k.x;
            let step = 1e-3 * w;
            let bound = 1e-13 * scale + 16.0 * f64::EPSILON * y_scale / step;
            for j in 1..10 {
                let v = k.x + w * j as f64 / 10.0;
                let difference = (4.0 * central(v, 0.5 * step) - central(v, step)) / 3.0;
                worst_ratio = worst_ratio.max((curve.slope(v) - difference).abs() / bound);
            }
        }
        // Measured: at most 0.45 of the bound (passiveForceLength).
        assert!(worst_ratio <= 1.0, "{name}: {worst_ratio}");
    }
}

/// Composite Simpson's rule of `f` over [a, b] in panels that never straddle one of `cuts`
/// (Simpson is exact on each cubic piece, so only rounding remains).
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, cuts: &[f64], panels: usize) -> f64 {
    let mut edges = vec![a];
    edges.extend(cuts.iter().copied().filter(|&c| c > a && c < b));
    edges.push(b);
    let mut sum = 0.0;
    for w in edges.windows(2) {
        let h = (w[1] - w[0]) / panels as f64;
        for i in 0..panels {
            let lo = w[0] + i as f64 * h;
            sum += h / 6.0 * (f(lo) + 4.0 * f(lo + 0.5 * h) + f(lo + h));
        }
    }
    sum
}

#[test]
fn the_integral_is_simpsons_rule_of_the_value() {
    for (name, curve) in all_curves() {
        let (x0, x1) = curve.domain();
        let w = x1 - x0;
        let cuts: Vec<f64> = curve.points().map(|p| p.0).collect();
        let scale = largest(curve.points().map(|p| p.1)) * (w + 3.0);
        let mut gap = 0.0_f64;
        for (a, b) in [
            (x0, x1),
            (x0 + 0.31 * w, x1 - 0.17 * w),
            (x1 - 0.05 * w, x0 + 0.4 * w),
            (x0 - 1.0, x1 + 2.0),
        ] {
            let quadrature = simpson(|v| curve.value(v), a.min(b), a.max(b), &cuts, 64);
            let signed = if a < b { quadrature } else { -quadrature };
            gap = gap.max((curve.integral_between(a, b) - signed).abs() / scale);
        }
        // Measured: at most 9.9e-16 (cubic4).
        assert!(gap < 1e-14, "{name}: {gap:e}");
    }
}

#[test]
fn the_argument_undoes_the_value_on_the_rising_part() {
    for (name, curve) in all_curves() {
        let Some((start, end)) = curve.rising_part() else {
            // Only the falling line has none.
            assert_eq!(name, "line2");
            assert!(curve.argument_at(0.3).is_nan());
            continue;
        };
        let steepest = (0..=1000)
            .map(|i| curve.slope(start + (end - start) * i as f64 / 1000.0))
            .fold(0.0, f64::max);
        let mut gap = 0.0_f64;
        for i in 1..2000 {
            let v = start + (end - start) * i as f64 / 2000.0;
            if curve.slope(v) > 1e-3 * steepest {
                gap = gap.max((curve.argument_at(curve.value(v)) - v).abs() / (end - start));
            }
        }
        // Measured: at most 1.1e-13 of the rising part's width (forceVelocity).
        assert!(gap < 1e-12, "{name}: {gap:e}");
        let (below, above) = (curve.value(start), curve.value(end));
        assert_eq!(curve.argument_at(below - 1.0), start);
        assert_eq!(curve.argument_at(above + 1.0), end);
        assert_eq!(curve.argument_at(f64::INFINITY), end);
        assert_eq!(curve.argument_at(f64::NEG_INFINITY), start);
        assert!(curve.argument_at(f64::NAN).is_nan());
    }
}

/// Every stationary point of the spline, `(x, y)`, in order.
fn extremes(curve: &TabulatedCurve) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for (k, next) in intervals(curve) {
        let (roots, count) = stationary_points(k, next.x - k.x);
        out.extend(roots[..count].iter().map(|&dx| (k.x + dx, k.value(dx))));
    }
    out
}

/// The stationary points the module's header reports, `(x, y)` to the digits given, per curve
/// (the ones within 1e-6 of a point's value left out).
const EXTREMES: [&[(f64, f64)]; 4] = [
    &[
        (-2.5, 9.124e-4),
        (0.2329, -1.160e-4),
        (0.4029, -3.243e-6),
        (1.00735, 1.000434),
        (1.6192, -1.543e-6),
        (1.8608, -1.022e-4),
        (3.6, 2.982e-4),
    ],
    &[(-2.001, -5.025e-4), (1.6004, 2.0000149), (3.301, 2.0105)],
    &[
        (-7.0843, 2.7077),
        (-1.2394, -1.4071e-2),
        (1.4934, 1.8143),
        (7.2055, 0.46863),
    ],
    &[
        (-5.001, -1.2238),
        (-0.001423, 1.885e-4),
        (-0.000384, -5.884e-4),
        (14.601, 345.0018),
    ],
];

#[test]
fn the_overshoots_are_those_the_module_header_reports() {
    for ((curve, name), expected) in subject_curves().iter().zip(SUBJECT_CURVES).zip(EXTREMES) {
        let found = extremes(curve);
        for &(x, y) in expected {
            let (fx, fy) = *found
                .iter()
                .min_by(|a, b| (a.0 - x).abs().total_cmp(&(b.0 - x).abs()))
                .unwrap();
            assert!(
                (fx - x).abs() < 1e-3 * x.abs().max(1.0),
                "{name}: {fx} for {x}"
            );
            assert!(
                (fy - y).abs() <= 5e-4 * y.abs(),
                "{name}: {fy} for {y} at {x}"
            );
        }
        // Sampling finds nothing beyond the stationary points and the points themselves.
        let levels: Vec<f64> = found
            .iter()
            .map(|e| e.1)
            .chain(curve.points().map(|p| p.1))
            .collect();
        let lowest = levels.iter().copied().fold(f64::INFINITY, f64::min);
        let highest = levels.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let (x0, x1) = curve.domain();
        for i in 0..=100_000 {
            let v = curve.value(x0 + (x1 - x0) * i as f64 / 100_000.0);
            assert!(
                v >= lowest && v <= highest,
                "{name}: {v} outside [{lowest}, {highest}]"
            );
        }
    }
}

#[test]
fn ceinms_curves_take_their_points_and_the_active_one_peaks_near_optimal_length() {
    let [active, passive, velocity, tendon] = subject_curves();
    assert_eq!(active.value(1.045), 0.993333);
    assert_eq!(active.value(0.4035), 0.0);
    assert_eq!(passive.value(1.0), 0.0);
    assert_eq!(passive.value(1.6), 2.0);
    assert_eq!((velocity.value(-1.0), velocity.value(0.0)), (0.0, 1.0));
    assert_eq!(velocity.value(0.8), 1.75);
    assert_eq!((tendon.value(0.0), tendon.value(0.0123)), (0.0, 0.227));
    assert_eq!(tendon.value(9.2), 345.0);
    // The peak: the highest stationary point, 1.000434 at l̃ = 1.00735.
    let (x, y) = extremes(&active)
        .into_iter()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    assert!(
        (x - 1.00735).abs() < 1e-5 && (y - 1.000434).abs() < 1e-6,
        "{x} {y}"
    );
    assert!(active.slope(x).abs() < 1e-12);
    // At optimal length 1.000198: the points have no point at l̃ = 1.
    assert!(
        (active.value(1.0) - 1.000198).abs() < 1e-6,
        "{}",
        active.value(1.0)
    );
    // The rising parts: the ascending limb, the passive rise, the force–velocity curve from
    // below ṽ = −1 to past its last inner point, the tendon from its slack to its plateau.
    let parts = [
        (&active, 0.402938, 1.007352),
        (&passive, 0.999616, 1.600384),
        (&velocity, -1.239384, 1.493360),
        (&tendon, -0.000384, 9.200384),
    ];
    for (curve, start, end) in parts {
        let (s, e) = curve.rising_part().unwrap();
        assert!(
            (s - start).abs() < 1e-6 && (e - end).abs() < 1e-6,
            "{s} {e}"
        );
    }
    // The tendon's inverse: its slack at zero force, a strain inside the points for 100, and
    // its plateau's start for any force above the plateau.
    assert!(
        tendon.argument_at(0.0).abs() < 1e-15,
        "{}",
        tendon.argument_at(0.0)
    );
    assert!((tendon.value(tendon.argument_at(100.0)) - 100.0).abs() < 1e-12);
    assert_eq!(tendon.argument_at(400.0), tendon.rising_part().unwrap().1);
}

#[test]
fn outside_the_points_the_end_values_are_held() {
    for (name, curve) in all_curves() {
        let ((x0, y0), (x1, y1)) = (
            curve.points().next().unwrap(),
            curve.points().last().unwrap(),
        );
        for d in [1e-12, 0.5, 3.0, 1e300] {
            assert_eq!(
                (curve.value(x0 - d), curve.value(x1 + d)),
                (y0, y1),
                "{name}"
            );
            assert_eq!(
                (curve.slope(x0 - d), curve.slope(x1 + d)),
                (0.0, 0.0),
                "{name}"
            );
        }
        let whole = curve.integral(x1);
        assert!((curve.integral(x1 + 2.0) - whole - 2.0 * y1).abs() < 1e-12 * whole.abs().max(1.0));
        assert!(
            (curve.integral(x0 - 1.5) + 1.5 * y0).abs() < 1e-15,
            "{name}"
        );
        assert_eq!(curve.integral(x0), 0.0);
        // Inside, the spline's own end slopes (CEINMS's getFirstDerivative keeps them outside).
        assert_eq!(curve.slope(x0), curve.knots[0].cubic.b);
    }
}

#[test]
fn bad_points_are_refused_with_their_error() {
    use TabulatedCurveError as E;
    let error = |x: &[f64], y: &[f64]| TabulatedCurve::new(x, y).unwrap_err();
    assert_eq!(error(&[0.0, 1.0], &[0.0]), E::Lengths { x: 2, y: 1 });
    assert_eq!(error(&[0.0], &[0.0]), E::TooFewPoints { points: 1 });
    assert_eq!(error(&[], &[]), E::TooFewPoints { points: 0 });
    let e = error(&[0.0, f64::NAN], &[0.0, 1.0]);
    assert!(matches!(e, E::NotFiniteX { index: 1, value } if value.is_nan()));
    assert_eq!(e.to_string(), "x[1] = NaN is not finite");
    let e = error(&[0.0, 1.0], &[f64::NEG_INFINITY, 1.0]);
    assert_eq!(e.to_string(), "y[0] = -inf is not finite");
    let e = error(&[0.0, 1.0, 1.0], &[0.0; 3]);
    assert_eq!(
        e,
        E::NotIncreasing {
            index: 2,
            x: 1.0,
            previous: 1.0
        }
    );
    assert_eq!(e.to_string(), "x[2] = 1 is not above x[1] = 1");
    assert_eq!(
        error(&[0.0, 2.0, 1.0], &[0.0; 3]).to_string(),
        "x[2] = 1 is not above x[1] = 2"
    );
    // Slopes or second derivatives beyond the doubles.
    assert_eq!(error(&[0.0, 1e-320, 2e-320], &[0.0, 1.0, 0.0]), E::Overflow);
    assert_eq!(
        error(&[0.0, 1.0, 2.0], &[1e308, -1e308, 1e308]),
        E::Overflow
    );
    assert_eq!(
        error(&[0.0, 1e300, 2e300, 3e300], &[0.0, 1.0, 0.0, 1.0]),
        E::Overflow
    );
    for e in [
        E::Overflow,
        E::TooFewPoints { points: 1 },
        E::Lengths { x: 3, y: 2 },
    ] {
        assert!(!e.to_string().contains('\n'), "{e}");
    }
}

#[test]
fn hostile_arguments_never_panic_and_nan_gives_nan() {
    let hostile = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MAX,
        f64::MIN,
        f64::MIN_POSITIVE,
        -0.0,
        5e-324,
        1e200,
    ];
    let mut curves: Vec<TabulatedCurve> = all_curves().into_iter().map(|c| c.1).collect();
    curves.push(TabulatedCurve::undefined());
    curves.push(TabulatedCurve::new(&[-1e6, 0.0, 1e-9, 1e6], &[1e-300, 0.0, 1e12, -3.0]).unwrap());
    for curve in &curves {
        for &v in &hostile {
            let results = [
                curve.value(v),
                curve.slope(v),
                curve.integral(v),
                curve.argument_at(v),
                curve.integral_between(v, 0.5),
                curve.integral_between(0.5, v),
                curve.integral_between(v, v),
            ];
            if v.is_nan() {
                assert!(results[..6].iter().all(|r| r.is_nan()), "{results:?}");
            }
        }
        assert!(
            curve.value(f64::INFINITY) == curve.points().last().unwrap().1
                || curve.value(0.0).is_nan()
        );
    }
    let nan = TabulatedCurve::undefined();
    assert!(nan.value(0.5).is_nan() && nan.slope(7.0).is_nan() && nan.integral(-3.0).is_nan());
    assert!(nan.argument_at(0.5).is_nan() && nan.rising_part().is_none());
}

#[test]
fn points_that_never_rise_have_no_rising_part() {
    let flat = TabulatedCurve::new(&[0.0, 1.0, 2.5, 3.0], &[2.0; 4]).unwrap();
    assert_eq!((flat.value(1.7), flat.slope(1.7)), (2.0, 0.0));
    assert!((flat.integral(3.0) - 6.0).abs() < 1e-15);
    assert!(flat.rising_part().is_none() && flat.argument_at(2.0).is_nan());
    let falling = TabulatedCurve::new(&[0.0, 1.0, 2.0, 4.0], &[3.0, 2.0, 0.5, 0.0]).unwrap();
    assert!(falling.rising_part().is_none());
}
