//! The plant's Jacobian by blocks (docs/model.md §8b), for the block-arrowhead iteration matrix:
//! the joints are the core, each muscle a leaf.
//!
//! - Joint rows: `θ_j' = ω_j`; `ω_j' = (Σ_i r_ij F_SE,i - c ω_j + τ_ext + τ_limit) / I_j`, so
//!   `∂ω_j'/∂θ_k = (Σ_i r_ij k_SE,i (-r_ik) + δ_jk (Σ_i F_SE,i dr_ij/dθ_j + ∂τ_limit/∂θ)) / I_j`
//!   and `∂ω_j'/∂l_m,i = r_ij (-k_SE,i) / I_j` (the tendon force falls as the fibre lengthens).
//! - Muscle rows: only the fibre acceleration sees the joints, through the tendon:
//!   `∂v_i'/∂θ_k = k_SE,i (-r_ik) / M_i`.
//! - A driven joint (docs/model.md §8c): `θ_j' = ω_j`, `ω_j' = 0`; its ω row is zero, so the
//!   muscles still see its angle but do not feed back into it.
//! - A muscle's own block: forward differences of its equations alone, its path held (so the
//!   tendon force follows the fibre length), a few evaluations of one muscle each.
//!
//! The cost is linear in the number of muscles; the full right-hand side is never evaluated.

use crate::integrator::arrowhead::{ArrowheadJacobian, ArrowheadSystem};
use crate::physics::joint;
use crate::physics::plant::{Inputs, Plant};
use crate::physics::topology::Anchor;

/// Scratch storage for the muscle blocks' differences.
#[derive(Debug, Clone, Default)]
pub(crate) struct JacobianScratch {
    s: Vec<f64>,
    ds: Vec<f64>,
    scales: Vec<f64>,
}

impl JacobianScratch {
    /// Room for muscles of up to `n` state variables.
    pub fn new(n: usize) -> Self {
        Self {
            s: vec![0.0; n],
            ds: vec![0.0; n],
            scales: vec![0.0; n],
        }
    }
}

/// Core and leaf sizes of a plant: `2 × joints`, then each muscle's state length.
pub fn leaf_dims(plant: &Plant, out: &mut Vec<usize>) {
    out.clear();
    out.extend(plant.mtus.iter().map(|m| m.state_dim()));
}

/// Fills `jac` with the Jacobian of the plant's equations at (t, y) under activations `act`;
/// `f0` are the derivatives there. Returns the work in equivalent full evaluations.
#[allow(clippy::too_many_arguments)]
pub(crate) fn eval_jacobian(
    plant: &Plant,
    t: f64,
    y: &[f64],
    act: &[f64],
    inputs: &Inputs,
    f0: &[f64],
    jac: &mut ArrowheadJacobian,
    scratch: &mut JacobianScratch,
) -> u64 {
    let nc = 2 * plant.joint_count();
    let core = &mut jac.core;
    core.fill(0.0);
    for (j, p) in plant.joints.iter().enumerate() {
        core[2 * j * nc + 2 * j + 1] = 1.0;
        if p.driven {
            continue;
        }
        let (d_theta, d_omega) = joint::limit_torque_slopes(p, y[2 * j], y[2 * j + 1]);
        core[(2 * j + 1) * nc + 2 * j + 1] = (-p.damping + d_omega) / p.inertia;
        core[(2 * j + 1) * nc + 2 * j] = d_theta / p.inertia;
    }
    let mut widest = 0;
    for (i, mtu) in plant.mtus.iter().enumerate() {
        let o = plant.offset(i);
        let n = mtu.state_dim();
        widest = widest.max(n);
        let leaf = &mut jac.leaves[i];
        leaf.to_core.clear();
        leaf.from_core.clear();
        let l_m = y[o];
        // The tendon force as a function of this muscle's own state, its path held.
        let path = plant.path_length(y, i);
        let tendon_force = |l_m: f64| match path {
            Some(l) => mtu.tendon.force(l - l_m),
            None => inputs.tendon_force[i].max(0.0),
        };
        if let (Some(l), Anchor::Path { spans, .. }) = (path, &plant.anchors[i]) {
            let l_t = l - l_m;
            let (f_se, k_se) = (mtu.tendon.force(l_t), mtu.tendon.stiffness(l_t));
            for s in spans {
                let (j, theta) = (s.joint, y[2 * s.joint]);
                let inertia = plant.joints[j].inertia;
                let r = s.moment_arm.at(theta);
                leaf.from_core.push((1, 2 * j, k_se * -r / mtu.params.mass));
                if plant.joints[j].driven {
                    continue;
                }
                core[(2 * j + 1) * nc + 2 * j] += s.moment_arm.slope(theta) * f_se / inertia;
                for s2 in spans {
                    let r2 = s2.moment_arm.at(y[2 * s2.joint]);
                    core[(2 * j + 1) * nc + 2 * s2.joint] += r * k_se * -r2 / inertia;
                }
                leaf.to_core.push((2 * j + 1, 0, r * -k_se / inertia));
            }
        }
        // The muscle's own block by forward differences.
        let (s, ds, scales) = (
            &mut scratch.s[..n],
            &mut scratch.ds[..n],
            &mut scratch.scales[..n],
        );
        s.copy_from_slice(&y[o..o + n]);
        mtu.scales(scales);
        for c in 0..n {
            let h = 1e-7 * s[c].abs().max(scales[c]);
            let keep = s[c];
            s[c] = keep + h;
            let h_exact = s[c] - keep;
            mtu.derivatives(t, act[i], s, tendon_force(s[0]), ds);
            s[c] = keep;
            for r in 0..n {
                leaf.block[r * n + c] = (ds[r] - f0[o + r]) / h_exact;
            }
        }
    }
    widest as u64
}

/// Anything that can lend the plant and the tick's inputs gets the arrowhead structure.
pub trait PlantSystem {
    /// The plant.
    fn plant(&self) -> &Plant;
    /// Fills the Jacobian (see `eval_jacobian`).
    fn jacobian(&self, t: f64, y: &[f64], f0: &[f64], jac: &mut ArrowheadJacobian) -> u64;
}

impl<T: PlantSystem + crate::integrator::OdeSystem> ArrowheadSystem for T {
    fn core_dim(&self) -> usize {
        2 * self.plant().joint_count()
    }
    fn leaf_dims(&self, out: &mut Vec<usize>) {
        leaf_dims(self.plant(), out);
    }
    fn eval_jacobian(&self, t: f64, y: &[f64], f0: &[f64], jac: &mut ArrowheadJacobian) -> u64 {
        self.jacobian(t, y, f0, jac)
    }
}
