//! The groups' strengths solved rather than searched (variable projection, Golub & Pereyra
//! 1973, SIAM J Numer Anal 10(2): 413-432).
//!
//! A unit whose every force is a multiple of its maximum isometric force (the tabulated curves,
//! normalised by it, and a damping scaled with it: `crate::subject::units`) moves the same way
//! at any strength s, its force s times that at strength 1. The moments are then linear in the
//! groups' strengths, `M(t) = Σ_g s_g G_g(t)` with `G_g = Σ_{i∈g} F_i r_i` at strength 1, and
//! the strengths that minimise the objective `Σ_k w_k Σ_t (m_k − Σ_g s_g G_gk)²` (k a trial's
//! degree of freedom, `w_k = 1/Σ(m_k − m̄_k)²`) within their bounds are a bounded linear
//! least-squares problem, solved here exactly by the primal active-set method on its normal
//! equations (Nocedal & Wright 2006, Numerical Optimization, §16.5: Newton steps on the free
//! strengths, cut at the first bound they meet, a bound freed when its multiplier says so).
//! Written by hand: a dozen unknowns with box bounds, no crate of the project's solves bounded
//! least squares, and the step is a few lines of nalgebra.

use nalgebra::{DMatrix, DVector};

/// One trial's degree of freedom: its measured moment, its weight, and per group its column.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Term {
    /// `1 / Σ(m − m̄)²`.
    pub weight: f64,
    /// The measured moment at each sample, N m.
    pub measured: Vec<f64>,
    /// Per group, `G_g` at each sample, N m.
    pub columns: Vec<Vec<f64>>,
}

/// Most active-set iterations (each adds or frees one bound; a few times the unknowns suffice).
const MAX_ITERATIONS: usize = 200;

/// The strengths within `[lo, hi]` that minimise the terms' weighted squared error, starting
/// from `start`, and the mean over terms of the weighted squared error there.
pub(crate) fn best_strengths(terms: &[Term], [lo, hi]: [f64; 2], start: &[f64]) -> (Vec<f64>, f64) {
    let g = start.len();
    let mut a = DMatrix::<f64>::zeros(g, g);
    let mut b = DVector::<f64>::zeros(g);
    for t in terms {
        for p in 0..g {
            b[p] += t.weight * dot(&t.columns[p], &t.measured);
            for q in p..g {
                let v = t.weight * dot(&t.columns[p], &t.columns[q]);
                a[(p, q)] += v;
                a[(q, p)] = a[(p, q)];
            }
        }
    }
    let mut s = DVector::from_iterator(g, start.iter().map(|v| v.clamp(lo, hi)));
    // A group that moves no moment keeps its start; the others are the unknowns.
    let unknowns: Vec<usize> = (0..g).filter(|&p| a[(p, p)] > 0.0).collect();
    let mut free: Vec<usize> = unknowns.clone();
    for _ in 0..MAX_ITERATIONS {
        let gradient = &a * &s - &b;
        let step = newton_step(&a, &gradient, &free);
        let scale = s.amax().max(1.0);
        if step.iter().all(|(_, d)| d.abs() <= 1e-14 * scale) {
            // Optimal on the free set: free the bound whose multiplier has the wrong sign.
            let wrong = unknowns
                .iter()
                .filter(|p| !free.contains(p))
                .map(|&p| {
                    let pull = if s[p] <= lo {
                        -gradient[p]
                    } else {
                        gradient[p]
                    };
                    (p, pull)
                })
                .filter(|&(_, pull)| pull > 1e-12 * b.amax().max(1.0))
                .max_by(|x, y| x.1.total_cmp(&y.1));
            match wrong {
                Some((p, _)) => free.push(p),
                None => break,
            }
            continue;
        }
        // The longest step toward the free set's optimum that stays within the bounds.
        let mut alpha = 1.0;
        let mut blocking = None;
        for &(p, d) in &step {
            let room = if d < 0.0 {
                (lo - s[p]) / d
            } else if d > 0.0 {
                (hi - s[p]) / d
            } else {
                f64::INFINITY
            };
            if room < alpha {
                alpha = room.max(0.0);
                blocking = Some(p);
            }
        }
        for &(p, d) in &step {
            s[p] = (s[p] + alpha * d).clamp(lo, hi);
        }
        if let Some(p) = blocking {
            s[p] = if step.iter().any(|&(q, d)| q == p && d < 0.0) {
                lo
            } else {
                hi
            };
            free.retain(|&q| q != p);
        }
    }
    let s: Vec<f64> = s.iter().copied().collect();
    let e = mean_error(terms, &s);
    (s, e)
}

/// The Newton step on the `free` unknowns (the others held): `A_FF d = −gradient_F`, by LU,
/// or by the SVD's least-squares solution when `A_FF` is singular (two groups whose columns
/// coincide).
fn newton_step(a: &DMatrix<f64>, gradient: &DVector<f64>, free: &[usize]) -> Vec<(usize, f64)> {
    let n = free.len();
    if n == 0 {
        return Vec::new();
    }
    let sub = DMatrix::from_fn(n, n, |i, j| a[(free[i], free[j])]);
    let rhs = DVector::from_fn(n, |i, _| -gradient[free[i]]);
    let d = sub
        .clone()
        .lu()
        .solve(&rhs)
        .filter(|d| d.iter().all(|v| v.is_finite()))
        .or_else(|| sub.svd(true, true).solve(&rhs, 1e-12 * a.amax()).ok())
        .unwrap_or_else(|| DVector::zeros(n));
    free.iter().copied().zip(d.iter().copied()).collect()
}

/// The mean over terms of `w Σ_t (m − Σ_g s_g G_g)²`.
pub(crate) fn mean_error(terms: &[Term], s: &[f64]) -> f64 {
    let sum: f64 = terms
        .iter()
        .map(|t| {
            let sse: f64 = (0..t.measured.len())
                .map(|k| {
                    let p: f64 = t.columns.iter().zip(s).map(|(c, s)| s * c[k]).sum();
                    (t.measured[k] - p).powi(2)
                })
                .sum();
            t.weight * sse
        })
        .sum();
    sum / terms.len().max(1) as f64
}

fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Columns and a measured series made from known strengths are solved back exactly; a
    /// strength outside the bounds lands on its bound, the others the constrained optimum.
    #[test]
    fn strengths_are_recovered_and_bounded() {
        let n = 50;
        let col = |f: fn(f64) -> f64| (0..n).map(|k| f(k as f64 * 0.1)).collect::<Vec<_>>();
        let columns = vec![col(f64::sin), col(f64::cos), col(|x| x * 0.3)];
        let truth = [1.7, 0.6, 2.2];
        let measured: Vec<f64> = (0..n)
            .map(|k| columns.iter().zip(truth).map(|(c, s)| s * c[k]).sum())
            .collect();
        let terms = vec![Term {
            weight: 1.0,
            measured,
            columns,
        }];
        let (s, e) = best_strengths(&terms, [0.5, 2.5], &[1.0; 3]);
        for (got, want) in s.iter().zip(truth) {
            assert!((got - want).abs() < 1e-9, "{s:?}");
        }
        assert!(e < 1e-15);
        let (s, _) = best_strengths(&terms, [0.5, 2.0], &[1.0; 3]);
        assert_eq!(s[2], 2.0);
        // The bounded optimum: no single strength can move within its bounds to lower it.
        let base = mean_error(&terms, &s);
        for p in 0..3 {
            for d in [-1e-4, 1e-4] {
                let mut t = s.clone();
                t[p] += d;
                if (0.5..=2.0).contains(&t[p]) {
                    assert!(mean_error(&terms, &t) >= base * (1.0 - 1e-12), "{s:?}");
                }
            }
        }
    }
}
