//! Stiffly accurate ESDIRK tableaux with an embedded method, as the stepper
//! ([`super::esdirk`]) takes them: TR-BDF2 ([`trbdf2`]), ARK3(2)4L\[2\]SA's implicit part
//! ([`ark324`]) and ESDIRK4(3)6L\[2\]SA ([`esdirk436`]).

// Index loops over the coefficient arrays read as the tableaux are printed in their sources.
#![allow(clippy::needless_range_loop)]

pub(crate) mod ark324;
pub(crate) mod esdirk436;
pub(crate) mod trbdf2;

/// Most stages of a tableau.
pub(crate) const MAX_STAGES: usize = 6;

/// A stiffly accurate ESDIRK tableau with an embedded method.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Tableau {
    /// Number of stages (the first explicit).
    pub stages: usize,
    /// The diagonal γ.
    pub gamma: f64,
    /// Stage times c_i.
    pub c: [f64; MAX_STAGES],
    /// Coefficients a_ij, row-major, `stages × stages` in a `MAX_STAGES²` array.
    pub a: [[f64; MAX_STAGES]; MAX_STAGES],
    /// `b - b̂`: the weights of the error estimate.
    pub e: [f64; MAX_STAGES],
    /// Order of the embedded method (the error estimate is O(h^(order + 1))).
    pub embedded_order: u32,
    /// Stage predictor weights: `F_s ≈ Σ_j p_sj F_j`, the polynomial through the earlier
    /// stages' (c_j, F_j) evaluated at c_s.
    pub predictor: [[f64; MAX_STAGES]; MAX_STAGES],
}

impl Tableau {
    /// The tableau of these coefficients, with its stage predictor.
    fn from_coefficients(
        stages: usize,
        gamma: f64,
        c: [f64; MAX_STAGES],
        a: [[f64; MAX_STAGES]; MAX_STAGES],
        e: [f64; MAX_STAGES],
        embedded_order: u32,
    ) -> Self {
        Self {
            stages,
            gamma,
            predictor: predictor_weights(&c, stages),
            c,
            a,
            e,
            embedded_order,
        }
    }
}

/// Lagrange weights at each stage time of the polynomial through the earlier stages.
fn predictor_weights(c: &[f64; MAX_STAGES], stages: usize) -> [[f64; MAX_STAGES]; MAX_STAGES] {
    let mut p = [[0.0; MAX_STAGES]; MAX_STAGES];
    for s in 1..stages {
        for j in 0..s {
            p[s][j] = (0..s)
                .filter(|&k| k != j)
                .map(|k| (c[s] - c[k]) / (c[j] - c[k]))
                .product();
        }
    }
    p
}

/// The order conditions the tableaux' tests check.
#[cfg(test)]
mod order_conditions {
    use super::Tableau;

    pub(super) fn dot(u: &[f64], v: &[f64]) -> f64 {
        u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>()
    }

    /// The method's weights b (the last row: stiffly accurate) and the embedding's, b - e.
    pub(super) fn weights(t: &Tableau) -> (Vec<f64>, Vec<f64>) {
        let s = t.stages;
        let b: Vec<f64> = (0..s).map(|j| t.a[s - 1][j]).collect();
        let bh: Vec<f64> = (0..s).map(|j| b[j] - t.e[j]).collect();
        (b, bh)
    }

    /// Each row of a sums to its stage time, within `tol`.
    pub(super) fn assert_row_sums(t: &Tableau, tol: f64) {
        let s = t.stages;
        for i in 0..s {
            let row: f64 = (0..s).map(|j| t.a[i][j]).sum();
            assert!((row - t.c[i]).abs() < tol, "row {i}");
        }
    }

    /// The conditions of order `order` (1 to 4: 1, 2, 4 or 8 trees) on weights `w`, within
    /// `tol`.
    pub(super) fn assert_order(t: &Tableau, w: &[f64], order: usize, tol: f64) {
        let s = t.stages;
        let c: Vec<f64> = t.c[..s].to_vec();
        let pw = |k: i32| c.iter().map(|x| x.powi(k)).collect::<Vec<f64>>();
        let ac = a_times(t, &c);
        let cac: Vec<f64> = (0..s).map(|i| c[i] * ac[i]).collect();
        let list = [
            (w.iter().sum::<f64>(), 1.0),
            (dot(w, &c), 0.5),
            (dot(w, &pw(2)), 1.0 / 3.0),
            (dot(w, &ac), 1.0 / 6.0),
            (dot(w, &pw(3)), 0.25),
            (dot(w, &cac), 1.0 / 8.0),
            (dot(w, &a_times(t, &pw(2))), 1.0 / 12.0),
            (dot(w, &a_times(t, &ac)), 1.0 / 24.0),
        ];
        let trees = [0, 1, 2, 4, 8][order];
        for (k, (got, want)) in list.into_iter().take(trees).enumerate() {
            assert!(
                (got - want).abs() < tol,
                "order {order}, condition {k}: {got}"
            );
        }
    }

    /// `A v`.
    pub(super) fn a_times(t: &Tableau, v: &[f64]) -> Vec<f64> {
        let s = t.stages;
        (0..s)
            .map(|i| (0..s).map(|j| t.a[i][j] * v[j]).sum())
            .collect()
    }
}
