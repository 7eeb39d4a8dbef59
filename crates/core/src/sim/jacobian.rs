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
//! - An equilibrium fibre or a rigid tendon (docs/model.md §5b): the muscle's coupling to the
//!   joints it spans, both ways, by forward differences too, of its equations and its tendon
//!   force against the joints' angles and velocities (a rigid tendon's force depends on both).
//!   The analytic rows above are those of a fibre with mass.
//!
//! The cost is linear in the number of muscles; the full right-hand side is never evaluated.

use crate::integrator::arrowhead::{ArrowheadJacobian, ArrowheadSystem};
use crate::physics::joint;
use crate::physics::mtu::{Mechanics, TendonEnd};
use crate::physics::plant::{Inputs, Plant};
use crate::physics::topology::Anchor;

/// Scratch storage for the muscle blocks' differences.
#[derive(Debug, Clone, Default)]
pub(crate) struct JacobianScratch {
    s: Vec<f64>,
    ds: Vec<f64>,
    scales: Vec<f64>,
    /// A copy of the state whose joint entries are perturbed (muscles without mass).
    y: Vec<f64>,
}

impl JacobianScratch {
    /// Room for muscles of up to `n` state variables in a plant of `dim` (no allocation when
    /// a Jacobian is evaluated).
    pub(crate) fn new(n: usize, dim: usize) -> Self {
        Self {
            s: vec![0.0; n],
            ds: vec![0.0; n],
            scales: vec![0.0; n],
            y: Vec::with_capacity(dim),
        }
    }
}

/// Core and leaf sizes of a plant: `2 × joints`, then each muscle's state length.
pub(crate) fn leaf_dims(plant: &Plant, out: &mut Vec<usize>) {
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
    // A copy of the state whose joint entries the massless muscles' differences perturb, made
    // once per Jacobian (its room is kept from one to the next).
    if plant.mtus.iter().any(|m| m.mechanics != Mechanics::Massed) {
        scratch.y.clear();
        scratch.y.extend_from_slice(y);
    }
    for (i, mtu) in plant.mtus.iter().enumerate() {
        let o = plant.offset(i);
        let n = mtu.state_dim();
        widest = widest.max(n);
        let leaf = &mut jac.leaves[i];
        leaf.to_core.clear();
        leaf.from_core.clear();
        let end = plant.tendon_end(y, i, inputs);
        // A massless muscle's tendon force at y (its joint rows read it), from its coupling.
        let mut f_se = 0.0;
        if mtu.mechanics != Mechanics::Massed {
            f_se = coupling_by_differences(plant, t, y, act, inputs, f0, i, core, scratch, leaf);
        } else if let (TendonEnd::Path { length: l, .. }, Anchor::Path { spans, .. }) =
            (end, &plant.anchors[i])
        {
            let l_m = y[o];
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
        // A massless muscle's tendon force follows its own state: the joint rows see that.
        let force_rows = mtu.mechanics != Mechanics::Massed;
        for c in 0..n {
            let h = 1e-7 * s[c].abs().max(scales[c]);
            let keep = s[c];
            s[c] = keep + h;
            let h_exact = s[c] - keep;
            let f = mtu.derivatives(t, act[i], s, end, ds);
            s[c] = keep;
            for r in 0..n {
                leaf.block[r * n + c] = (ds[r] - f0[o + r]) / h_exact;
            }
            if force_rows {
                let df = (f - f_se) / h_exact;
                for sp in plant.spans(i) {
                    let j = sp.joint;
                    if !plant.joints[j].driven {
                        let r = sp.moment_arm.at(y[2 * j]);
                        leaf.to_core
                            .push((2 * j + 1, c, r * df / plant.joints[j].inertia));
                    }
                }
            }
        }
    }
    widest as u64
}

/// Muscle i's coupling to the joints it spans, for a muscle without mass (docs/model.md §5b),
/// by forward differences in each spanned joint's angle and velocity: its rows' dependence on
/// them (`from_core`) and the joints' torque rows' (`core`). Its own rows' dependence on its
/// state, and the torque rows' on it, are left to the own block. `scratch.y` holds a copy of
/// `y`, perturbed and restored here. Returns the muscle's tendon force at `y`, N.
#[allow(clippy::too_many_arguments)]
fn coupling_by_differences(
    plant: &Plant,
    t: f64,
    y: &[f64],
    act: &[f64],
    inputs: &Inputs,
    f0: &[f64],
    i: usize,
    core: &mut [f64],
    scratch: &mut JacobianScratch,
    leaf: &mut crate::integrator::arrowhead::LeafJacobian,
) -> f64 {
    let nc = 2 * plant.joint_count();
    let (mtu, o, n) = (&plant.mtus[i], plant.offset(i), plant.mtus[i].state_dim());
    let JacobianScratch { s, ds, y: yp, .. } = scratch;
    let (s, ds) = (&mut s[..n], &mut ds[..n]);
    s.copy_from_slice(&y[o..o + n]);
    let spans = plant.spans(i);
    // The muscle's torque on each joint it spans at the unperturbed state.
    let f_se = mtu.derivatives(t, act[i], s, plant.tendon_end(y, i, inputs), ds);
    for sp in spans {
        for c in [2 * sp.joint, 2 * sp.joint + 1] {
            let keep = yp[c];
            let scale = if c % 2 == 0 { 1e-1 } else { 1.0 };
            yp[c] = keep + 1e-7 * keep.abs().max(scale);
            let h = yp[c] - keep;
            let f = mtu.derivatives(t, act[i], s, plant.tendon_end(yp, i, inputs), ds);
            for r in 0..n {
                let d = (ds[r] - f0[o + r]) / h;
                if d != 0.0 {
                    leaf.from_core.push((r, c, d));
                }
            }
            for sk in spans {
                let k = sk.joint;
                if plant.joints[k].driven {
                    continue;
                }
                let torque = sk.moment_arm.at(yp[2 * k]) * f - sk.moment_arm.at(y[2 * k]) * f_se;
                core[(2 * k + 1) * nc + c] += torque / h / plant.joints[k].inertia;
            }
            yp[c] = keep;
        }
    }
    f_se
}

/// Anything that can lend the plant and the tick's inputs gets the arrowhead structure.
pub(crate) trait PlantSystem {
    /// Fills the Jacobian (see `eval_jacobian`).
    fn jacobian(&self, t: f64, y: &[f64], f0: &[f64], jac: &mut ArrowheadJacobian) -> u64;
}

impl<T: PlantSystem + crate::integrator::OdeSystem> ArrowheadSystem for T {
    fn eval_jacobian(&self, t: f64, y: &[f64], f0: &[f64], jac: &mut ArrowheadJacobian) -> u64 {
        self.jacobian(t, y, f0, jac)
    }
}
