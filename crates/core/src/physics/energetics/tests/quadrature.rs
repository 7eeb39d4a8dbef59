//! Composite Gauss–Legendre quadrature, for integrals the code under test computes otherwise.
//! Its nodes are interior, so a rate that jumps at a piece's end is taken from the inside.

/// Nodes and weights of the 5-point Gauss–Legendre rule on [-1, 1].
const GAUSS_5: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// `∫_a^b f` by the 5-point rule on each of `n` equal intervals.
pub(crate) fn gauss(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    (0..n)
        .map(|i| {
            let mid = a + (i as f64 + 0.5) * h;
            GAUSS_5
                .iter()
                .map(|(x, w)| w * f(mid + 0.5 * h * x))
                .sum::<f64>()
                * 0.5
                * h
        })
        .sum()
}

/// `∫ f` over the pieces between consecutive `breaks` (f smooth on each), `n` intervals each.
pub(crate) fn piecewise(f: impl Fn(f64) -> f64, breaks: &[f64], n: usize) -> f64 {
    breaks
        .windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| gauss(&f, w[0], w[1], n))
        .sum()
}

#[test]
fn gauss_integrates_a_gaussian_and_a_jump() {
    let pdf = |x: f64| (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt();
    let i = piecewise(pdf, &[-12.0, 0.0, 12.0], 200);
    assert!((i - 1.0).abs() < 1e-14, "{i}");
    let step = |x: f64| if x < 0.0 { 3.0 } else { x };
    let i = piecewise(step, &[-1.0, 0.0, 1.0], 1);
    assert!((i - 3.5).abs() < 1e-14, "{i}");
}
