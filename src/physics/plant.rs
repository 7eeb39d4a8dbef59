//! The mechanical plant: one or two muscle–tendon units with their attachment (MODEL.md §5, §8),
//! as a first-order system over a flat state vector.
//!
//! State layout: `[θ, ω]` when there is a joint, then for each muscle `[l_m, v]` followed by
//! `[Q0, Q1, Q2]` for the Huxley models. Activations are not part of the state: within a tick
//! they are known in closed form (physics::activation), and the caller passes them in.

use crate::physics::joint;
use crate::physics::model::ModelKind;
use crate::physics::mtu::{Mtu, MtuOutputs};
use crate::physics::params::{JointParams, MuscleParams};

/// What the tendon's far end is attached to.
#[derive(Debug, Clone, PartialEq)]
pub enum Attachment {
    /// The MTU is held at a fixed total length, m.
    Clamped {
        /// Total MTU length L, m.
        length: f64,
    },
    /// An external pull F(t) >= 0 acts on a massless tendon (a push is not transmitted).
    ForceDriven,
    /// Agonist and antagonist on a revolute joint.
    Joint {
        /// The joint parameters.
        params: JointParams,
        /// Path length of both MTUs at θ = 0, m.
        path_length: f64,
    },
}

/// Inputs held over a tick.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Inputs {
    /// Neural excitation per muscle, [0, 1].
    pub excitation: [f64; 2],
    /// External pull on a force-driven tendon, N.
    pub tendon_force: f64,
    /// External torque on the joint, N m.
    pub external_torque: f64,
}

/// The full model's closure over a sub-step: φ taken from the grid at the sub-step's start t0,
/// extrapolated linearly with the slope of the previous sub-step (second order, and no extra
/// pass over the grid): `φ(t) = φ0 + slope (t - t0)`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct HeldClosure {
    /// φ_k at t0, 1/s.
    pub phi: [f64; 3],
    /// dφ_k/dt, 1/s².
    pub slope: [f64; 3],
    /// Start of the sub-step, s (time within the tick).
    pub t0: f64,
}

impl HeldClosure {
    /// φ at time t.
    pub fn at(&self, t: f64) -> [f64; 3] {
        let dt = t - self.t0;
        [
            self.phi[0] + self.slope[0] * dt,
            self.phi[1] + self.slope[1] * dt,
            self.phi[2] + self.slope[2] * dt,
        ]
    }
}

/// One or two MTUs and their attachment.
#[derive(Debug, Clone)]
pub struct Plant {
    /// The muscle–tendon units (agonist first).
    pub mtus: Vec<Mtu>,
    /// Their attachment.
    pub attachment: Attachment,
    /// The model of the contractile elements.
    pub model: ModelKind,
    /// The full model's closure φ per muscle over a sub-step (unused by the other models).
    pub held_closure: [HeldClosure; 2],
    offsets: [usize; 2],
    dim: usize,
}

impl Plant {
    /// Builds the plant; a joint needs exactly two muscles, the other attachments one.
    pub fn new(
        muscles: &[MuscleParams],
        model: ModelKind,
        attachment: Attachment,
    ) -> Result<Self, String> {
        let want = if matches!(attachment, Attachment::Joint { .. }) {
            2
        } else {
            1
        };
        if muscles.len() != want {
            return Err(format!(
                "this attachment needs {want} muscle(s), got {}",
                muscles.len()
            ));
        }
        let mtus = muscles
            .iter()
            .map(|p| Mtu::new(p, model))
            .collect::<Result<Vec<_>, _>>()?;
        let per_muscle = 2 + mtus[0].contractile_dim();
        let base = if want == 2 { 2 } else { 0 };
        Ok(Self {
            mtus,
            attachment,
            model,
            held_closure: [HeldClosure::default(); 2],
            offsets: [base, base + per_muscle],
            dim: base + want * per_muscle,
        })
    }

    /// Length of the state vector.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Index of muscle i's first state variable (l_m).
    pub fn offset(&self, i: usize) -> usize {
        self.offsets[i]
    }

    /// Muscle i's cross-bridge moments (zeros for Hill).
    pub fn moments(&self, y: &[f64], i: usize) -> [f64; 3] {
        let o = self.offsets[i];
        if self.mtus[i].contractile_dim() == 3 {
            [y[o + 2], y[o + 3], y[o + 4]]
        } else {
            [0.0; 3]
        }
    }

    /// Muscle i's tendon length, m.
    pub fn tendon_length(&self, y: &[f64], i: usize, inputs: &Inputs) -> f64 {
        let l_m = y[self.offsets[i]];
        match &self.attachment {
            Attachment::Clamped { length } => length - l_m,
            Attachment::ForceDriven => self.mtus[i].tendon.length_at_force(inputs.tendon_force),
            Attachment::Joint {
                params,
                path_length,
            } => {
                let path = if i == 0 {
                    joint::agonist_path(*path_length, params.radius, y[0])
                } else {
                    joint::antagonist_path(*path_length, params.radius, y[0])
                };
                path - l_m
            }
        }
    }

    /// Muscle i's tendon force, N.
    pub fn tendon_force(&self, y: &[f64], i: usize, inputs: &Inputs) -> f64 {
        match self.attachment {
            Attachment::ForceDriven => inputs.tendon_force.max(0.0),
            _ => self.mtus[i].tendon.force(self.tendon_length(y, i, inputs)),
        }
    }

    /// `dy/dt` at state y with activations `act`; `t` (time within the tick, s) only matters to
    /// the full model's held closure.
    pub fn derivatives(&self, t: f64, y: &[f64], act: &[f64], inputs: &Inputs, dy: &mut [f64]) {
        let mut tendon_forces = [0.0; 2];
        for (i, mtu) in self.mtus.iter().enumerate() {
            let o = self.offsets[i];
            let (l_m, v) = (y[o], y[o + 1]);
            let q = self.moments(y, i);
            let f_se = self.tendon_force(y, i, inputs);
            tendon_forces[i] = f_se;
            let f_ce = mtu.ce_force(act[i], l_m, v, &q);
            dy[o] = v;
            dy[o + 1] = mtu.fibre_acceleration(f_se, f_ce, l_m, v);
            if mtu.contractile_dim() == 3 {
                let held = (self.model == ModelKind::HuxleyPde).then(|| self.held_closure[i].at(t));
                let dq = mtu.moment_rates(act[i], l_m, v, &q, held.as_ref());
                dy[o + 2..o + 5].copy_from_slice(&dq);
            }
        }
        if let Attachment::Joint { params, .. } = &self.attachment {
            dy[0] = y[1];
            dy[1] = joint::angular_acceleration(
                params,
                y[0],
                y[1],
                tendon_forces[0],
                tendon_forces[1],
                inputs.external_torque,
            );
        }
    }

    /// Typical magnitudes of the state components (tolerance units).
    pub fn scales(&self, out: &mut [f64]) {
        if matches!(self.attachment, Attachment::Joint { .. }) {
            out[0] = 1e-1;
            out[1] = 1.0;
        }
        for (i, mtu) in self.mtus.iter().enumerate() {
            let o = self.offsets[i];
            out[o] = mtu.params.l_opt;
            out[o + 1] = mtu.params.v_max;
            if mtu.contractile_dim() == 3 {
                out[o + 2..o + 5].fill(mtu.crossbridge.q_iso[0]);
            }
        }
    }

    /// The resting state: joint at its initial angle and at rest, each fibre where tendon and
    /// parallel element balance, no bonds.
    pub fn resting_state(&self, inputs: &Inputs, y: &mut [f64]) {
        y.fill(0.0);
        let theta = match &self.attachment {
            Attachment::Joint { params, .. } => params.initial_angle,
            _ => 0.0,
        };
        if matches!(self.attachment, Attachment::Joint { .. }) {
            y[0] = theta;
        }
        for (i, mtu) in self.mtus.iter().enumerate() {
            let o = self.offsets[i];
            y[o] = match &self.attachment {
                Attachment::Clamped { length } => mtu.resting_fibre_length(*length),
                Attachment::ForceDriven => mtu.parallel.length_at_force(inputs.tendon_force),
                Attachment::Joint {
                    params,
                    path_length,
                } => {
                    let path = if i == 0 {
                        joint::agonist_path(*path_length, params.radius, theta)
                    } else {
                        joint::antagonist_path(*path_length, params.radius, theta)
                    };
                    mtu.resting_fibre_length(path)
                }
            };
        }
    }

    /// Muscle i's observable outputs.
    pub fn outputs(&self, y: &[f64], act: &[f64], inputs: &Inputs, i: usize) -> MtuOutputs {
        let o = self.offsets[i];
        let l_t = self.tendon_length(y, i, inputs);
        let mut out = self.mtus[i].outputs(act[i], y[o], y[o + 1], &self.moments(y, i), l_t);
        if matches!(self.attachment, Attachment::ForceDriven) {
            out.tendon_force = inputs.tendon_force.max(0.0);
        }
        out
    }
}
