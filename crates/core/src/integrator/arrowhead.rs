//! The block-arrowhead iteration matrix (docs/model.md §8b): a small dense *core* (the joints)
//! coupled with any number of small *leaf* blocks (the muscles) that couple with each other only
//! through the core. `I - d J` is solved by eliminating each leaf block (a Schur complement onto
//! the core), so a factorisation and a solve cost time linear in the number of leaves.
//!
//! With `M = [[I - dA, -dB], [-dC, blockdiag(P_i)]]`, `P_i = I - d D_i`:
//! `S = I - dA - d² Σ_i B_i P_i⁻¹ C_i` on the core; a solve takes `w_i = P_i⁻¹ b_i` per leaf,
//! `S x_core = b_core + d Σ_i B_i w_i`, then `x_i = w_i + d P_i⁻¹ C_i x_core`. The couplings B_i
//! and C_i are sparse (a muscle touches only the joints it spans), given as entry lists.
//!
//! Written by hand: no crate offers an allocation-free structured solve of this shape.

use crate::integrator::dense::{invert, Lu};
use crate::integrator::{IterationMatrix, OdeSystem};
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};

/// One leaf's part of the Jacobian.
#[derive(Debug, Clone, Default)]
pub(crate) struct LeafJacobian {
    /// The leaf's own block D_i, row-major n_i × n_i.
    pub block: Vec<f64>,
    /// Entries of B_i: (core row, leaf column, ∂f_core/∂y_leaf).
    pub to_core: Vec<(usize, usize, f64)>,
    /// Entries of C_i: (leaf row, core column, ∂f_leaf/∂y_core).
    pub from_core: Vec<(usize, usize, f64)>,
}

/// The Jacobian of an arrowhead system, by blocks.
#[derive(Debug, Clone, Default)]
pub(crate) struct ArrowheadJacobian {
    /// The core block A, row-major core × core.
    pub core: Vec<f64>,
    /// One per leaf, in order.
    pub leaves: Vec<LeafJacobian>,
}

/// A system whose state is a core followed by leaf blocks, with a block-arrowhead Jacobian.
pub(crate) trait ArrowheadSystem: OdeSystem {
    /// Evaluates the Jacobian at (t, y) (with `f0 = f(t, y)`) into `jac`, whose vectors are
    /// sized already (entry lists are cleared and refilled). Returns the work in equivalent
    /// right-hand-side evaluations.
    fn eval_jacobian(&self, t: f64, y: &[f64], f0: &[f64], jac: &mut ArrowheadJacobian) -> u64;
}

#[derive(Debug, Clone)]
struct Leaf {
    offset: usize,
    n: usize,
    /// `P = I - d D`, overwritten by the inversion.
    p: Vec<f64>,
    /// `P⁻¹`, row-major n × n: the blocks are small (2 to 5), so a solve is one matrix–vector
    /// product instead of two substitutions with pivoting.
    inverse: Vec<f64>,
    w: Vec<f64>,
}

/// Cores up to this size are inverted explicitly (solves become matrix–vector products).
const SMALL_CORE: usize = 8;

/// `I - d J` of an arrowhead system, factorised by leaf elimination.
#[derive(Debug, Clone)]
pub(crate) struct ArrowheadMatrix {
    core: usize,
    jac: ArrowheadJacobian,
    leaves: Vec<Leaf>,
    schur: Lu,
    /// The Schur complement's inverse when the core is small (then used instead of the LU).
    schur_inverse: Vec<f64>,
    d: f64,
    x_core: Vec<f64>,
}

impl ArrowheadMatrix {
    /// Storage for a core of `core` variables and leaves of the given lengths.
    pub(crate) fn new(core: usize, leaf_dims: &[usize]) -> Self {
        let mut offset = core;
        let leaves = leaf_dims
            .iter()
            .map(|&n| {
                let leaf = Leaf {
                    offset,
                    n,
                    p: vec![0.0; n * n],
                    inverse: vec![0.0; n * n],
                    w: vec![0.0; n],
                };
                offset += n;
                leaf
            })
            .collect();
        Self {
            core,
            jac: ArrowheadJacobian {
                core: vec![0.0; core * core],
                leaves: leaf_dims
                    .iter()
                    .map(|&n| LeafJacobian {
                        block: vec![0.0; n * n],
                        to_core: Vec::new(),
                        from_core: Vec::new(),
                    })
                    .collect(),
            },
            leaves,
            schur: Lu::new(core),
            schur_inverse: vec![0.0; if core <= SMALL_CORE { core * core } else { 0 }],
            d: 0.0,
            x_core: vec![0.0; core],
        }
    }
}

impl<S: ArrowheadSystem + ?Sized> IterationMatrix<S> for ArrowheadMatrix {
    fn update_jacobian(&mut self, sys: &S, t: f64, y: &[f64], f0: &[f64]) -> u64 {
        sys.eval_jacobian(t, y, f0, &mut self.jac)
    }

    fn factorise(&mut self, d: f64) -> bool {
        let nc = self.core;
        self.d = d;
        let s = &mut self.schur.rows;
        for i in 0..nc {
            for j in 0..nc {
                let id = if i == j { 1.0 } else { 0.0 };
                s[i * nc + j] = id - self.jac.core[i * nc + j] * d;
            }
        }
        for (leaf, lj) in self.leaves.iter_mut().zip(&self.jac.leaves) {
            let n = leaf.n;
            for i in 0..n {
                for j in 0..n {
                    let id = if i == j { 1.0 } else { 0.0 };
                    leaf.p[i * n + j] = id - lj.block[i * n + j] * d;
                }
            }
            if !invert(&mut leaf.p, &mut leaf.inverse, n) {
                return false;
            }
            // S -= d² B P⁻¹ C, entry by entry.
            for &(lr, cc, gamma) in &lj.from_core {
                for &(cr, lc, beta) in &lj.to_core {
                    s[cr * nc + cc] -= d * d * beta * leaf.inverse[lc * n + lr] * gamma;
                }
            }
        }
        if nc <= SMALL_CORE {
            invert(&mut self.schur.rows, &mut self.schur_inverse, nc)
        } else {
            self.schur.factorise()
        }
    }

    fn solve(&mut self, b: &mut [f64]) {
        let nc = self.core;
        let d = self.d;
        // The core's right-hand side b_core + d Σ_i B_i w_i gathers in b itself.
        for (leaf, lj) in self.leaves.iter_mut().zip(&self.jac.leaves) {
            let n = leaf.n;
            let bl = &b[leaf.offset..leaf.offset + n];
            for (r, w) in leaf.w.iter_mut().enumerate() {
                let row = &leaf.inverse[r * n..r * n + n];
                *w = row.iter().zip(bl).map(|(p, v)| p * v).sum();
            }
            for &(cr, lc, beta) in &lj.to_core {
                b[cr] += d * beta * leaf.w[lc];
            }
        }
        if nc > SMALL_CORE {
            self.x_core.copy_from_slice(&b[..nc]);
            self.schur.solve(&mut self.x_core);
            b[..nc].copy_from_slice(&self.x_core);
        } else {
            let mut x = [0.0; SMALL_CORE];
            for (r, out) in x[..nc].iter_mut().enumerate() {
                let row = &self.schur_inverse[r * nc..r * nc + nc];
                *out = row.iter().zip(&b[..nc]).map(|(p, v)| p * v).sum();
            }
            // Two stores per element: no call to memcpy for these few numbers.
            for (r, &v) in x[..nc].iter().enumerate() {
                b[r] = v;
                self.x_core[r] = v;
            }
        }
        // x_i = w_i + d P⁻¹ C_i x_core, written straight into b (a copy of a few numbers is a
        // call to memcpy, measurable at this size).
        for (leaf, lj) in self.leaves.iter().zip(&self.jac.leaves) {
            let n = leaf.n;
            let out = &mut b[leaf.offset..leaf.offset + n];
            for (r, (x, &w)) in out.iter_mut().zip(&leaf.w).enumerate() {
                let mut v = w;
                for &(lr, cc, gamma) in &lj.from_core {
                    v += d * gamma * self.x_core[cc] * leaf.inverse[r * n + lr];
                }
                *x = v;
            }
        }
    }
}

/// An entry list of a leaf's coupling: (row, column, value) with the row below `rows` and the
/// column below `cols`.
fn save_entries(out: &mut StateWriter, entries: &[(usize, usize, f64)]) {
    out.usize(entries.len());
    for &(r, c, v) in entries {
        out.usize(r);
        out.usize(c);
        out.f64(v);
    }
}

fn restore_entries(
    input: &mut StateReader,
    what: &str,
    (rows, cols): (usize, usize),
    entries: &mut Vec<(usize, usize, f64)>,
) -> Result<(), StateError> {
    let n = input.usize(what, usize::MAX)?;
    input.check_room(n, 24, what)?;
    entries.clear();
    for _ in 0..n {
        let r = input.usize(what, rows.saturating_sub(1))?;
        let c = input.usize(what, cols.saturating_sub(1))?;
        entries.push((r, c, input.f64(what)?));
    }
    if n > 0 && rows * cols == 0 {
        return Err(StateError::Invalid(format!(
            "{what}: entries saved for an empty block"
        )));
    }
    Ok(())
}

/// The Jacobian and its factorisation (both kept from tick to tick) and the work vectors; the
/// structure (core and leaf sizes) is the rebuilt plant's, and the saved sizes must be its.
impl SavedState for ArrowheadMatrix {
    fn save_state(&self, out: &mut StateWriter) {
        out.f64s(&self.jac.core);
        out.usize(self.leaves.len());
        for (leaf, lj) in self.leaves.iter().zip(&self.jac.leaves) {
            out.f64s(&lj.block);
            save_entries(out, &lj.to_core);
            save_entries(out, &lj.from_core);
            out.f64s(&leaf.p);
            out.f64s(&leaf.inverse);
            out.f64s(&leaf.w);
        }
        self.schur.save_state(out);
        out.f64s(&self.schur_inverse);
        out.f64(self.d);
        out.f64s(&self.x_core);
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        let nc = self.core;
        input.f64s_into("Jacobian core block", &mut self.jac.core)?;
        input.expect_len("Jacobian leaf blocks", self.leaves.len())?;
        for (leaf, lj) in self.leaves.iter_mut().zip(&mut self.jac.leaves) {
            let n = leaf.n;
            input.f64s_into("Jacobian leaf block", &mut lj.block)?;
            restore_entries(
                input,
                "Jacobian leaf-to-core entries",
                (nc, n),
                &mut lj.to_core,
            )?;
            restore_entries(
                input,
                "Jacobian core-to-leaf entries",
                (n, nc),
                &mut lj.from_core,
            )?;
            input.f64s_into("leaf iteration block", &mut leaf.p)?;
            input.f64s_into("leaf inverse", &mut leaf.inverse)?;
            input.f64s_into("leaf work vector", &mut leaf.w)?;
        }
        self.schur.restore_state(input)?;
        input.f64s_into("Schur complement inverse", &mut self.schur_inverse)?;
        self.d = input.f64("iteration matrix's h gamma")?;
        input.f64s_into("core work vector", &mut self.x_core)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random arrowhead Jacobian: solving with the elimination equals a dense LU solve.
    #[test]
    fn elimination_solves_like_a_dense_factorisation() {
        // A small core (inverted explicitly) and a large one (LU).
        for core in [4, 11] {
            elimination_matches_dense(core);
        }
    }

    fn elimination_matches_dense(core: usize) {
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let dims = [2usize, 5, 3, 5];
        let n: usize = core + dims.iter().sum::<usize>();
        let mut m = ArrowheadMatrix::new(core, &dims);
        let mut dense = vec![0.0; n * n];
        for i in 0..core {
            for j in 0..core {
                let v = rnd() * 10.0;
                m.jac.core[i * core + j] = v;
                dense[i * n + j] = v;
            }
        }
        let mut off = core;
        for (k, &nk) in dims.iter().enumerate() {
            let lj = &mut m.jac.leaves[k];
            for i in 0..nk {
                for j in 0..nk {
                    let v = rnd() * 100.0;
                    lj.block[i * nk + j] = v;
                    dense[(off + i) * n + off + j] = v;
                }
            }
            // Two core rows fed by leaf column 0, leaf rows 1 (and 0) fed by two core columns.
            for (cr, lc) in [(1, 0), (core - 1, 0)] {
                let v = rnd() * 50.0;
                lj.to_core.push((cr, lc, v));
                dense[cr * n + off + lc] = v;
            }
            for (lr, cc) in [(1.min(nk - 1), 0), (1.min(nk - 1), 2), (0, 2)] {
                let v = rnd() * 50.0;
                lj.from_core.push((lr, cc, v));
                dense[(off + lr) * n + cc] += v;
            }
            off += nk;
        }
        let d = 0.013;
        assert!(IterationMatrix::<Dummy>::factorise(&mut m, d));
        let mut lu = Lu::new(n);
        for i in 0..n {
            for j in 0..n {
                lu.rows[i * n + j] = if i == j { 1.0 } else { 0.0 } - dense[i * n + j] * d;
            }
        }
        assert!(lu.factorise());
        let b: Vec<f64> = (0..n).map(|_| rnd()).collect();
        let (mut x1, mut x2) = (b.clone(), b.clone());
        IterationMatrix::<Dummy>::solve(&mut m, &mut x1);
        lu.solve(&mut x2);
        for i in 0..n {
            assert!(
                (x1[i] - x2[i]).abs() < 1e-12 * (1.0 + x2[i].abs()),
                "{i}: {x1:?} {x2:?}"
            );
        }
    }

    struct Dummy;
    impl OdeSystem for Dummy {
        fn rhs(&self, _: f64, _: &[f64], _: &mut [f64]) {}
        fn scales(&self, _: &mut [f64]) {}
    }
    impl ArrowheadSystem for Dummy {
        fn eval_jacobian(&self, _: f64, _: &[f64], _: &[f64], _: &mut ArrowheadJacobian) -> u64 {
            0
        }
    }
}
