//! The mechanical plant: a topology of joints and muscle–tendon units (docs/model.md §5, §8b) as
//! a first-order system over a flat state vector, for any contractile model.
//!
//! State layout: `[θ_j, ω_j]` for each joint j, then for each muscle i its formulation's state
//! (`[l_m, v]` for a fibre with mass, `[l_m]` for an equilibrium fibre, none on a rigid tendon:
//! `physics::mtu`) followed by its contractile model's own state (none for Hill, Q0..Q2 for the
//! Huxley models). Activations are
//! not part of the state: within a tick they are known in closed form (physics::activation), and
//! the caller passes them in.
//!
//! A driven joint (`JointParams::driven`, docs/model.md §8c) keeps its two entries, but its
//! angle and velocity at each tick's start are inputs ([`Inputs::joint_angle`],
//! [`Inputs::joint_velocity`]) and its acceleration is zero within the tick: the muscles see the
//! prescribed motion `θ0 + ω0 t`, and the joint sees none of their force.
//!
//! Coupling: muscle i's equations involve only its own state and the angles of the joints it
//! spans; joint j's acceleration involves the tendon forces of the muscles that span it. The
//! Jacobian is therefore block-arrowhead (a block per muscle, a joint block), which
//! `crate::integrator::arrowhead` exploits.

use crate::physics::energetics::metabolic::MetabolicSample;
use crate::physics::energetics::probe::ExcitationTerms;
use crate::physics::joint;
use crate::physics::limb_params::JointParams;
use crate::physics::models::{CeInputs, ModelBuildError, ModelKind};
use crate::physics::mtu::{FibreState, Mechanics, Mtu, TendonEnd};
use crate::physics::observables::{EnergeticsOutputs, MuscleSnapshot};
use crate::physics::stiffness::add_muscle_joint_stiffness;
use crate::physics::topology::{Anchor, Span, Topology};
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};

/// Inputs held over a tick.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Inputs {
    /// Neural excitation per muscle, [0, 1].
    pub excitation: Vec<f64>,
    /// External torque per joint, N m.
    pub external_torque: Vec<f64>,
    /// External pull per muscle on a force-driven tendon, N (ignored for other anchors).
    pub tendon_force: Vec<f64>,
    /// Angle per joint at the tick's start, rad (driven joints only; ignored for the others).
    pub joint_angle: Vec<f64>,
    /// Angular velocity per joint over the tick, rad/s (driven joints only).
    pub joint_velocity: Vec<f64>,
}

impl Inputs {
    /// All zero, for `muscles` muscles and `joints` joints.
    pub fn zeros(muscles: usize, joints: usize) -> Self {
        Self {
            excitation: vec![0.0; muscles],
            external_torque: vec![0.0; joints],
            tendon_force: vec![0.0; muscles],
            joint_angle: vec![0.0; joints],
            joint_velocity: vec![0.0; joints],
        }
    }

    /// Sets every value to 0 (keeps the sizes).
    pub(crate) fn clear(&mut self) {
        self.excitation.fill(0.0);
        self.external_torque.fill(0.0);
        self.tendon_force.fill(0.0);
        self.joint_angle.fill(0.0);
        self.joint_velocity.fill(0.0);
    }
}

/// Every input, in field order; the sizes must be those of the inputs read into.
impl SavedState for Inputs {
    fn save_state(&self, out: &mut StateWriter) {
        let Inputs {
            excitation,
            external_torque,
            tendon_force,
            joint_angle,
            joint_velocity,
        } = self;
        for v in [
            excitation,
            external_torque,
            tendon_force,
            joint_angle,
            joint_velocity,
        ] {
            out.f64s(v);
        }
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        input.f64s_into("excitations", &mut self.excitation)?;
        input.f64s_into("external torques", &mut self.external_torque)?;
        input.f64s_into("tendon forces", &mut self.tendon_force)?;
        input.f64s_into("joint angles", &mut self.joint_angle)?;
        input.f64s_into("joint velocities", &mut self.joint_velocity)
    }
}

/// Why a plant cannot be built from a topology.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlantError {
    /// A topology without muscles.
    #[error("the plant needs at least one muscle")]
    NoMuscle,
    /// A span over a joint the topology does not have.
    #[error("muscle {muscle:?} spans joint index {joint} of {joints}")]
    SpanOutOfRange {
        /// The muscle's name.
        muscle: String,
        /// The joint index it spans.
        joint: usize,
        /// The number of joints.
        joints: usize,
    },
    /// A rigid tendon pulled by an external force: nothing would set its fibre's length.
    #[error(
        "muscle {0:?}: a rigid tendon needs a path over joints (a force-driven tendon must be \
         elastic)"
    )]
    RigidForceDriven(String),
    /// A muscle's contractile model cannot be built.
    #[error(transparent)]
    Model(#[from] ModelBuildError),
}

/// The muscles, their anchors and the joints they drive.
#[derive(Debug, Clone)]
pub struct Plant {
    /// The joints.
    pub joints: Vec<JointParams>,
    /// The muscle–tendon units, in topology order.
    pub mtus: Vec<Mtu>,
    /// Where each muscle's tendon is attached.
    pub(crate) anchors: Vec<Anchor>,
    /// The model of the contractile elements.
    pub model: ModelKind,
    offsets: Vec<usize>,
    dim: usize,
}

impl Plant {
    /// Builds the plant of a topology (checked: spans name existing joints).
    pub fn new(topology: &Topology, model: ModelKind) -> Result<Self, PlantError> {
        if topology.muscles.is_empty() {
            return Err(PlantError::NoMuscle);
        }
        let n_joints = topology.joints.len();
        for m in &topology.muscles {
            if let Anchor::Path { spans, .. } = &m.anchor {
                if let Some(s) = spans.iter().find(|s| s.joint >= n_joints) {
                    return Err(PlantError::SpanOutOfRange {
                        muscle: m.name.clone(),
                        joint: s.joint,
                        joints: n_joints,
                    });
                }
            }
        }
        if let Some(m) = topology.muscles.iter().find(|m| {
            matches!(m.anchor, Anchor::ForceDriven) && Mechanics::of(&m.params) == Mechanics::Rigid
        }) {
            return Err(PlantError::RigidForceDriven(m.name.clone()));
        }
        let mtus = topology
            .muscles
            .iter()
            .map(|m| Mtu::new(&m.params, model))
            .collect::<Result<Vec<_>, _>>()?;
        let mut offsets = Vec::with_capacity(mtus.len());
        let mut dim = 2 * n_joints;
        for m in &mtus {
            offsets.push(dim);
            dim += m.state_dim();
        }
        Ok(Self {
            joints: topology.joints.clone(),
            mtus,
            anchors: topology.muscles.iter().map(|m| m.anchor.clone()).collect(),
            model,
            offsets,
            dim,
        })
    }

    /// Length of the state vector.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Number of muscles.
    pub fn muscle_count(&self) -> usize {
        self.mtus.len()
    }

    /// Number of joints.
    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// Index of muscle i's first state variable (l_m).
    pub(crate) fn offset(&self, i: usize) -> usize {
        self.offsets[i]
    }

    /// Muscle i's state: its formulation's, then its contractile model's.
    pub(crate) fn muscle_state<'a>(&self, y: &'a [f64], i: usize) -> &'a [f64] {
        let o = self.offsets[i];
        &y[o..o + self.mtus[i].state_dim()]
    }

    /// The joints muscle i spans.
    pub(crate) fn spans(&self, i: usize) -> &[Span] {
        match &self.anchors[i] {
            Anchor::Path { spans, .. } => spans,
            Anchor::ForceDriven => &[],
        }
    }

    /// Muscle i's path length `L_i(θ)`, m (None for a force-driven tendon).
    #[inline]
    pub fn path_length(&self, y: &[f64], i: usize) -> Option<f64> {
        match &self.anchors[i] {
            Anchor::Path { path_length, spans } => Some(spans.iter().fold(*path_length, |l, s| {
                l - s.moment_arm.excursion(y[2 * s.joint])
            })),
            Anchor::ForceDriven => None,
        }
    }

    /// Muscle i's path lengthening velocity `dL/dt = -Σ_j r_ij(θ_j) ω_j`, m/s (0 for a
    /// force-driven tendon).
    pub(crate) fn path_velocity(&self, y: &[f64], i: usize) -> f64 {
        self.spans(i).iter().fold(0.0, |v, s| {
            v - s.moment_arm.at(y[2 * s.joint]) * y[2 * s.joint + 1]
        })
    }

    /// What holds muscle i's tendon at state y: its path (the velocity only where a rigid
    /// tendon reads it) or the external pull.
    #[inline]
    pub(crate) fn tendon_end(&self, y: &[f64], i: usize, inputs: &Inputs) -> TendonEnd {
        match self.path_length(y, i) {
            Some(length) => TendonEnd::Path {
                length,
                velocity: match self.mtus[i].mechanics {
                    Mechanics::Rigid => self.path_velocity(y, i),
                    Mechanics::Massed | Mechanics::Equilibrium => 0.0,
                },
            },
            None => TendonEnd::Force(inputs.tendon_force[i]),
        }
    }

    /// Muscle i's fibre length at state y, m.
    pub fn fibre_length(&self, y: &[f64], i: usize, inputs: &Inputs) -> f64 {
        match self.mtus[i].mechanics {
            // Only a rigid tendon's fibre needs the path; the others' length is their state.
            Mechanics::Rigid => {
                let end = self.tendon_end(y, i, inputs);
                self.mtus[i].fibre_length(self.muscle_state(y, i), end)
            }
            Mechanics::Massed | Mechanics::Equilibrium => y[self.offsets[i]],
        }
    }

    /// What muscle i's contractile element sees at state y under activation a: a fibre with mass
    /// reads it from its state alone, a massless one from its balance with the tendon.
    pub(crate) fn ce_inputs(
        &self,
        y: &[f64],
        i: usize,
        activation: f64,
        inputs: &Inputs,
    ) -> CeInputs {
        let (mtu, s) = (&self.mtus[i], self.muscle_state(y, i));
        match mtu.mechanics {
            Mechanics::Massed => mtu.ce_inputs(activation, s[0], s[1]),
            Mechanics::Equilibrium | Mechanics::Rigid => {
                mtu.fibre_state(activation, s, self.tendon_end(y, i, inputs))
                    .ce
            }
        }
    }

    /// Muscle i's tendon force at state y under activation a, N (as [`Self::fibre_state`]'s).
    pub fn tendon_force(&self, y: &[f64], i: usize, activation: f64, inputs: &Inputs) -> f64 {
        let end = self.tendon_end(y, i, inputs);
        self.mtus[i].tendon_force(activation, self.muscle_state(y, i), end)
    }

    /// Muscle i's fibre and tendon at state y under activation a (docs/model.md §5b).
    pub fn fibre_state(&self, y: &[f64], i: usize, activation: f64, inputs: &Inputs) -> FibreState {
        let end = self.tendon_end(y, i, inputs);
        self.mtus[i].fibre_state(activation, self.muscle_state(y, i), end)
    }

    /// Muscle i's metabolic rates at state y (see `Mtu::metabolic`).
    pub fn metabolic(
        &self,
        y: &[f64],
        i: usize,
        activation: f64,
        inputs: &Inputs,
        terms: &ExcitationTerms,
    ) -> MetabolicSample {
        let ce = self.ce_inputs(y, i, activation, inputs);
        self.mtus[i].metabolic(terms, activation, &ce, self.muscle_state(y, i))
    }

    /// `dy/dt` at state y with activations `act`; `t` is the time within the tick (it only
    /// matters to models with state outside the ODE).
    pub fn derivatives(&self, t: f64, y: &[f64], act: &[f64], inputs: &Inputs, dy: &mut [f64]) {
        // Joint rows first collect the muscles' torques Σ_i r_ij F_SE,i.
        for j in 0..self.joints.len() {
            dy[2 * j] = y[2 * j + 1];
            dy[2 * j + 1] = 0.0;
        }
        for (i, mtu) in self.mtus.iter().enumerate() {
            let o = self.offsets[i];
            let n = mtu.state_dim();
            let end = self.tendon_end(y, i, inputs);
            let f_se = mtu.derivatives(t, act[i], &y[o..o + n], end, &mut dy[o..o + n]);
            for s in self.spans(i) {
                dy[2 * s.joint + 1] += s.moment_arm.at(y[2 * s.joint]) * f_se;
            }
        }
        for (j, p) in self.joints.iter().enumerate() {
            if p.driven {
                dy[2 * j + 1] = joint::driven_angular_acceleration();
                continue;
            }
            let torque = dy[2 * j + 1];
            dy[2 * j + 1] = joint::angular_acceleration(
                p,
                y[2 * j],
                y[2 * j + 1],
                torque,
                inputs.external_torque[j],
            );
        }
    }

    /// Typical magnitudes of the state components (tolerance units).
    pub fn scales(&self, out: &mut [f64]) {
        for j in 0..self.joints.len() {
            out[2 * j] = 1e-1;
            out[2 * j + 1] = 1.0;
        }
        for (i, mtu) in self.mtus.iter().enumerate() {
            let o = self.offsets[i];
            mtu.scales(&mut out[o..o + mtu.state_dim()]);
        }
    }

    /// The resting state: joints at their initial angles and at rest (driven joints at their
    /// input motion), each fibre where tendon and parallel element balance, no bonds.
    pub(crate) fn resting_state(&self, inputs: &Inputs, y: &mut [f64]) {
        y.fill(0.0);
        for (j, p) in self.joints.iter().enumerate() {
            y[2 * j] = p.initial_angle;
        }
        self.set_driven_motion(inputs, y);
        for (i, mtu) in self.mtus.iter().enumerate() {
            if mtu.mechanics == Mechanics::Rigid {
                continue;
            }
            let o = self.offsets[i];
            y[o] = match self.path_length(y, i) {
                Some(path) => mtu.resting_fibre_length(path),
                None => mtu.parallel.length_at_force(inputs.tendon_force[i]),
            };
        }
    }

    /// Writes the driven joints' input motion (angle, velocity at the tick's start) into the
    /// state; free joints are left alone.
    pub(crate) fn set_driven_motion(&self, inputs: &Inputs, y: &mut [f64]) {
        for (j, p) in self.joints.iter().enumerate() {
            if p.driven {
                y[2 * j] = inputs.joint_angle[j];
                y[2 * j + 1] = inputs.joint_velocity[j];
            }
        }
    }

    /// Writes the driven joints' motion at `dt` after the tick's start (the within-tick rule,
    /// [`joint::prescribed_angle`]) into the state.
    pub(crate) fn set_driven_motion_after(&self, inputs: &Inputs, dt: f64, y: &mut [f64]) {
        for (j, p) in self.joints.iter().enumerate() {
            if p.driven {
                let (theta0, omega0) = (inputs.joint_angle[j], inputs.joint_velocity[j]);
                y[2 * j] = joint::prescribed_angle(theta0, omega0, dt);
                y[2 * j + 1] = omega0;
            }
        }
    }

    /// After a tick: each driven joint's input angle moves on to where the tick's extrapolation
    /// ended (the state's angle), so that a motion set once carries on linearly until it is set
    /// again.
    pub(crate) fn carry_driven_motion(&self, y: &[f64], inputs: &mut Inputs) {
        for (j, p) in self.joints.iter().enumerate() {
            if p.driven {
                inputs.joint_angle[j] = y[2 * j];
            }
        }
    }

    /// Muscle i's observables, with the energetics `e` the stepping computed.
    pub(crate) fn outputs(
        &self,
        y: &[f64],
        act: &[f64],
        inputs: &Inputs,
        i: usize,
        e: &EnergeticsOutputs,
    ) -> MuscleSnapshot {
        let end = self.tendon_end(y, i, inputs);
        let u = inputs.excitation[i];
        self.mtus[i].outputs(u, act[i], self.muscle_state(y, i), end, e)
    }

    /// The joints' net muscle torques `τ_j = Σ_i r_ij(θ_j) F_SE,i` from the muscles' tendon
    /// forces, in one pass over the muscles' spans: `add(j, r_ij F_SE,i)` for each span, in muscle
    /// order (start each τ_j at 0), N m.
    pub fn add_muscle_torques(
        &self,
        y: &[f64],
        tendon_forces: impl Fn(usize) -> f64,
        mut add: impl FnMut(usize, f64),
    ) {
        for i in 0..self.mtus.len() {
            let f = tendon_forces(i);
            for s in self.spans(i) {
                add(s.joint, s.moment_arm.at(y[2 * s.joint]) * f);
            }
        }
    }

    /// The joint stiffness matrix K (row-major `n × n`, N m/rad, docs/model.md §8b) from each
    /// muscle's (MTU stiffness, tendon force), written to `k`.
    pub(crate) fn stiffness_matrix(
        &self,
        y: &[f64],
        muscle: impl Fn(usize) -> (f64, f64),
        k: &mut [f64],
    ) {
        let n = self.joints.len();
        k[..n * n].fill(0.0);
        for i in 0..self.mtus.len() {
            let (k_mtu, f_se) = muscle(i);
            let arms = self.spans(i).iter().map(|s| {
                let theta = y[2 * s.joint];
                (s.joint, s.moment_arm.at(theta), s.moment_arm.slope(theta))
            });
            add_muscle_joint_stiffness(k, n, k_mtu, f_se, arms);
        }
    }

    /// The independent parts of the plant: each a set of joints connected through the muscles
    /// that span them (a biarticular muscle joins its two joints), with those muscles; a muscle
    /// that spans no joint is a part of its own. Returned as (joints, muscles), ascending.
    ///
    /// A driven joint joins nothing (its motion is an input): it belongs to every part with a
    /// muscle that spans it, and a muscle that spans only driven joints is a part of its own.
    pub(crate) fn components(&self) -> Vec<(Vec<usize>, Vec<usize>)> {
        // Union–find over joints.
        let n = self.joints.len();
        let mut parent: Vec<usize> = (0..n).collect();
        fn root(parent: &mut [usize], mut j: usize) -> usize {
            while parent[j] != j {
                parent[j] = parent[parent[j]];
                j = parent[j];
            }
            j
        }
        let free = |s: &&Span| !self.joints[s.joint].driven;
        for i in 0..self.mtus.len() {
            let mut spans = self.spans(i).iter().filter(free);
            if let Some(first) = spans.next() {
                for s in spans {
                    let (a, b) = (root(&mut parent, first.joint), root(&mut parent, s.joint));
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
        let mut parts: Vec<(Vec<usize>, Vec<usize>)> = Vec::new();
        let mut part_of_root = vec![usize::MAX; n];
        for j in (0..n).filter(|&j| !self.joints[j].driven) {
            let r = root(&mut parent, j);
            if part_of_root[r] == usize::MAX {
                part_of_root[r] = parts.len();
                parts.push((Vec::new(), Vec::new()));
            }
            parts[part_of_root[r]].0.push(j);
        }
        for i in 0..self.mtus.len() {
            let spans = self.spans(i);
            let k = match spans.iter().find(free) {
                Some(s) => {
                    let r = root(&mut parent, s.joint);
                    parts[part_of_root[r]].1.push(i);
                    part_of_root[r]
                }
                None => {
                    parts.push((Vec::new(), vec![i]));
                    parts.len() - 1
                }
            };
            let joints = &mut parts[k].0;
            for s in spans.iter().filter(|s| self.joints[s.joint].driven) {
                if !joints.contains(&s.joint) {
                    joints.push(s.joint);
                }
            }
            joints.sort_unstable();
        }
        parts
    }

    /// The plant of some of the joints and muscles (a component: every joint a muscle spans is
    /// among `joints`), joints renumbered in the given order.
    pub(crate) fn subset(&self, joints: &[usize], muscles: &[usize]) -> Plant {
        let renumber = |j: usize| joints.iter().position(|&k| k == j).expect("a component");
        let anchors: Vec<Anchor> = muscles
            .iter()
            .map(|&i| match &self.anchors[i] {
                Anchor::Path { path_length, spans } => Anchor::Path {
                    path_length: *path_length,
                    spans: spans
                        .iter()
                        .map(|s| Span {
                            joint: renumber(s.joint),
                            moment_arm: s.moment_arm.clone(),
                        })
                        .collect(),
                },
                Anchor::ForceDriven => Anchor::ForceDriven,
            })
            .collect();
        let mtus: Vec<Mtu> = muscles.iter().map(|&i| self.mtus[i].clone()).collect();
        let mut offsets = Vec::with_capacity(mtus.len());
        let mut dim = 2 * joints.len();
        for m in &mtus {
            offsets.push(dim);
            dim += m.state_dim();
        }
        Plant {
            joints: joints.iter().map(|&j| self.joints[j].clone()).collect(),
            mtus,
            anchors,
            model: self.model,
            offsets,
            dim,
        }
    }

    /// Kinetic energy of the fibre masses (fibres with mass only) and the free joints, J (a driven joint's inertia is
    /// the robot simulator's).
    pub(crate) fn kinetic_energy(&self, y: &[f64]) -> f64 {
        let mut e = 0.0;
        for (i, mtu) in self.mtus.iter().enumerate() {
            if mtu.mechanics == Mechanics::Massed {
                let v = y[self.offsets[i] + 1];
                e += 0.5 * mtu.params.mass * v * v;
            }
        }
        for (j, p) in self.joints.iter().enumerate().filter(|(_, p)| !p.driven) {
            e += joint::kinetic_energy(p, y[2 * j + 1]);
        }
        e
    }
}
