//! The dense iteration matrix: the Jacobian by forward differences over every component, LU with
//! partial pivoting. The general fallback (any system); the plant uses the block-arrowhead one.

// Index loops over several parallel vectors read better than zipped iterators here.
#![allow(clippy::needless_range_loop)]

#[cfg(test)]
use crate::integrator::{IterationMatrix, OdeSystem};
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};

/// Dense `I - d J`, row-major, with its LU: the general iteration matrix, which the tests check
/// the plant's arrowhead one against.
#[cfg(test)]
#[derive(Debug, Clone)]
pub(crate) struct DenseMatrix {
    n: usize,
    jac: Vec<f64>,
    lu: Lu,
    yp: Vec<f64>,
    fp: Vec<f64>,
    scales: Vec<f64>,
}

#[cfg(test)]
impl DenseMatrix {
    /// Storage for an n-dimensional system.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            n,
            jac: vec![0.0; n * n],
            lu: Lu::new(n),
            yp: vec![0.0; n],
            fp: vec![0.0; n],
            scales: vec![0.0; n],
        }
    }
}

#[cfg(test)]
impl<S: OdeSystem + ?Sized> IterationMatrix<S> for DenseMatrix {
    fn update_jacobian(&mut self, sys: &S, t: f64, y: &[f64], f0: &[f64]) -> u64 {
        let n = self.n;
        sys.scales(&mut self.scales);
        self.yp.copy_from_slice(y);
        for j in 0..n {
            let h = 1e-7 * y[j].abs().max(self.scales[j]);
            let keep = self.yp[j];
            self.yp[j] = keep + h;
            let h_exact = self.yp[j] - keep;
            sys.rhs(t, &self.yp, &mut self.fp);
            self.yp[j] = keep;
            for i in 0..n {
                self.jac[i * n + j] = (self.fp[i] - f0[i]) / h_exact;
            }
        }
        n as u64
    }

    fn factorise(&mut self, d: f64) -> bool {
        let n = self.n;
        for i in 0..n {
            for j in 0..n {
                let id = if i == j { 1.0 } else { 0.0 };
                self.lu.rows[i * n + j] = id - self.jac[i * n + j] * d;
            }
        }
        self.lu.factorise()
    }

    fn solve(&mut self, b: &mut [f64]) {
        self.lu.solve(b);
    }
}

/// LU factorisation with partial pivoting of a small dense matrix, row-major, in place.
///
/// Written by hand: the textbook Doolittle elimination on preallocated storage (nalgebra's
/// dynamic LU allocates on every factorisation), with the row-major layout that makes the
/// substitutions plain dot products.
#[derive(Debug, Clone)]
pub(crate) struct Lu {
    n: usize,
    /// The matrix to factorise; after `factorise`, L (unit, below) and U (on and above).
    pub rows: Vec<f64>,
    perm: Vec<usize>,
    pivot_row: Vec<f64>,
    x: Vec<f64>,
}

impl Lu {
    /// Storage for an n × n matrix.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            n,
            rows: vec![0.0; n * n],
            perm: (0..n).collect(),
            pivot_row: vec![0.0; n],
            x: vec![0.0; n],
        }
    }

    /// Factorises `rows` in place; false if it is singular.
    pub(crate) fn factorise(&mut self) -> bool {
        let n = self.n;
        for (i, p) in self.perm.iter_mut().enumerate() {
            *p = i;
        }
        let rows = &mut self.rows;
        for k in 0..n {
            let (mut piv, mut best) = (k, rows[k * n + k].abs());
            for i in k + 1..n {
                if rows[i * n + k].abs() > best {
                    piv = i;
                    best = rows[i * n + k].abs();
                }
            }
            if !(best > 0.0 && best.is_finite()) {
                return false;
            }
            if piv != k {
                for c in 0..n {
                    rows.swap(piv * n + c, k * n + c);
                }
                self.perm.swap(piv, k);
            }
            self.pivot_row.copy_from_slice(&rows[k * n..k * n + n]);
            let inv = 1.0 / self.pivot_row[k];
            for i in k + 1..n {
                let row = &mut rows[i * n..i * n + n];
                let l = row[k] * inv;
                row[k] = l;
                if l != 0.0 {
                    for (v, p) in row[k + 1..].iter_mut().zip(&self.pivot_row[k + 1..]) {
                        *v -= l * p;
                    }
                }
            }
        }
        true
    }

    /// Solves `A x = b` in place.
    pub(crate) fn solve(&mut self, b: &mut [f64]) {
        let n = self.n;
        let x = &mut self.x;
        for i in 0..n {
            let row = &self.rows[i * n..i * n + n];
            let dot: f64 = row[..i].iter().zip(&x[..i]).map(|(l, v)| l * v).sum();
            x[i] = b[self.perm[i]] - dot;
        }
        for i in (0..n).rev() {
            let row = &self.rows[i * n..i * n + n];
            let dot: f64 = row[i + 1..]
                .iter()
                .zip(&x[i + 1..])
                .map(|(u, v)| u * v)
                .sum();
            x[i] = (x[i] - dot) / row[i];
        }
        b.copy_from_slice(x);
    }
}

/// The factorisation and its work vectors (a kept factorisation is solved with on later
/// ticks); the permutation must be one of `0..n`.
impl SavedState for Lu {
    fn save_state(&self, out: &mut StateWriter) {
        out.f64s(&self.rows);
        out.usize(self.perm.len());
        for &p in &self.perm {
            out.usize(p);
        }
        out.f64s(&self.pivot_row);
        out.f64s(&self.x);
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        input.f64s_into("LU factors", &mut self.rows)?;
        input.expect_len("LU permutation", self.n)?;
        let mut seen = vec![false; self.n];
        for p in self.perm.iter_mut() {
            *p = input.usize("LU permutation", self.n.saturating_sub(1))?;
            if std::mem::replace(&mut seen[*p], true) {
                return Err(StateError::Invalid(format!(
                    "LU permutation: row {p} appears twice"
                )));
            }
        }
        input.f64s_into("LU pivot row", &mut self.pivot_row)?;
        input.f64s_into("LU work vector", &mut self.x)
    }
}

/// Inverts the n × n row-major matrix `a` into `inv` by Gauss–Jordan elimination with partial
/// pivoting (`a` is overwritten); false if it is singular. For the small blocks of the
/// arrowhead matrix, where a solve by the explicit inverse is one matrix–vector product.
pub(crate) fn invert(a: &mut [f64], inv: &mut [f64], n: usize) -> bool {
    inv.fill(0.0);
    for i in 0..n {
        inv[i * n + i] = 1.0;
    }
    for k in 0..n {
        let (mut piv, mut best) = (k, a[k * n + k].abs());
        for i in k + 1..n {
            if a[i * n + k].abs() > best {
                piv = i;
                best = a[i * n + k].abs();
            }
        }
        if !(best > 0.0 && best.is_finite()) {
            return false;
        }
        if piv != k {
            for c in 0..n {
                a.swap(piv * n + c, k * n + c);
                inv.swap(piv * n + c, k * n + c);
            }
        }
        let p = 1.0 / a[k * n + k];
        for c in 0..n {
            a[k * n + c] *= p;
            inv[k * n + c] *= p;
        }
        for i in 0..n {
            if i == k {
                continue;
            }
            let f = a[i * n + k];
            if f != 0.0 {
                for c in 0..n {
                    a[i * n + c] -= f * a[k * n + c];
                    inv[i * n + c] -= f * inv[k * n + c];
                }
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_jordan_inverts() {
        let m = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let (mut a, mut inv) = (m, [0.0; 9]);
        assert!(invert(&mut a, &mut inv, 3));
        for i in 0..3 {
            for j in 0..3 {
                let p: f64 = (0..3).map(|k| m[i * 3 + k] * inv[k * 3 + j]).sum();
                assert!((p - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14);
            }
        }
        assert!(!invert(&mut [1.0, 2.0, 2.0, 4.0], &mut [0.0; 4], 2));
    }

    #[test]
    fn lu_solves_a_pivoting_system() {
        let m = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let mut lu = Lu::new(3);
        lu.rows.copy_from_slice(&m);
        assert!(lu.factorise());
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| m[i * 3 + j] * x[j]).sum())
            .collect();
        lu.solve(&mut b);
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-14, "{b:?}");
        }
        let mut singular = Lu::new(2);
        singular.rows.copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
        assert!(!singular.factorise());
    }
}
