//! One independent part of a limb (joints connected by muscles, and those muscles), stepped
//! over a tick with its own sub-steps: a busy joint does not make its quiet neighbours take
//! small steps. Its ODE is the plant's equations with the activations in closed form (the
//! paper's first order) or linear within the tick towards its end value (Lloyd & Besier's,
//! [`crate::sim::neural_drive`]).

use crate::integrator::arrowhead::{ArrowheadJacobian, ArrowheadMatrix};
use crate::integrator::{esdirk::Esdirk, tableau::Tableau};
use crate::integrator::{OdeSystem, Stats};
use crate::physics::activation::activation_after;
use crate::physics::energetics::metabolic::MetabolicSample;
use crate::physics::energetics::probe::ExcitationTerms;
use crate::physics::limb_params::formulation::ActivationKind;
use crate::physics::models::SubstepMotion;
use crate::physics::plant::{Inputs, Plant};
use crate::physics::stepping::Stepping;
use crate::sim::energy::{MuscleEnergy, TickEnergy};
use crate::sim::jacobian::{self, JacobianScratch, PlantSystem};
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};
use std::cell::RefCell;

/// The activations at one time within the tick (Newton iterates at one stage time many times),
/// and the Jacobian's scratch space.
#[derive(Debug, Clone)]
struct ActivationMemo {
    t: f64,
    a: Vec<f64>,
    scratch: JacobianScratch,
}

/// A plant's ODE over one tick of length `dt`, with activations in closed form from the tick's
/// start, or linear from it to the tick's end value `a1` for the muscles listed in `neural`
/// (None when there are none).
struct TickOde<'a> {
    plant: &'a Plant,
    inputs: &'a Inputs,
    a0: &'a [f64],
    a1: &'a [f64],
    neural: Option<&'a [usize]>,
    dt: f64,
    memo: &'a RefCell<ActivationMemo>,
}

impl TickOde<'_> {
    /// Makes sure the memo holds the activations at t.
    #[inline]
    fn at(&self, t: f64) {
        let mut m = self.memo.borrow_mut();
        if m.t == t {
            return;
        }
        for (i, mtu) in self.plant.mtus.iter().enumerate() {
            let p = &mtu.params;
            m.a[i] = activation_after(self.a0[i], self.inputs.excitation[i], t, p.t_act, p.t_deact);
        }
        if let Some(neural) = self.neural {
            let s = t / self.dt;
            for &i in neural {
                m.a[i] = self.a0[i] * (1.0 - s) + self.a1[i] * s;
            }
        }
        m.t = t;
    }
}

impl PlantSystem for TickOde<'_> {
    fn jacobian(&self, t: f64, y: &[f64], f0: &[f64], jac: &mut ArrowheadJacobian) -> u64 {
        self.at(t);
        let mut m = self.memo.borrow_mut();
        let m = &mut *m;
        jacobian::eval_jacobian(self.plant, t, y, &m.a, self.inputs, f0, jac, &mut m.scratch)
    }
}

impl OdeSystem for TickOde<'_> {
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.at(t);
        let m = self.memo.borrow();
        self.plant.derivatives(t, y, &m.a, self.inputs, dy);
    }
    fn scales(&self, out: &mut [f64]) {
        self.plant.scales(out);
    }
}

/// An independent part of the plant (joints connected by muscles, and those muscles), stepped
/// with its own sub-steps: a busy joint does not make its quiet neighbours take small steps.
#[derive(Debug, Clone)]
pub(crate) struct Part {
    plant: Plant,
    /// Global index of each local muscle and joint, and of each local state variable.
    muscles: Vec<usize>,
    joints: Vec<usize>,
    state_map: Vec<usize>,
    y: Vec<f64>,
    /// The adaptive stepping's carried sub-step size, s.
    h: f64,
    saved_h: f64,
    inputs: Inputs,
    a0: Vec<f64>,
    /// The activations at the tick's end of the muscles with Lloyd & Besier's activation
    /// (`neural`, their local indices), given by the whole before each tick.
    a1: Vec<f64>,
    neural: Vec<usize>,
    lm_before: Vec<f64>,
    memo: RefCell<ActivationMemo>,
    /// The ESDIRK stepper: ARK3(2)4L\[2\]SA (third order) for adaptive sub-steps, TR-BDF2 (second
    /// order) for fixed ones.
    stepper: Esdirk<ArrowheadMatrix>,
    /// Its muscles' energetics over the last tick, until the whole commits them.
    energy: Vec<TickEnergy>,
}

impl Part {
    /// The part of `whole` made of these joints and muscles (a component of its topology).
    pub(crate) fn new(
        whole: &Plant,
        joints: Vec<usize>,
        muscles: Vec<usize>,
        stepping: Stepping,
    ) -> Self {
        let plant = whole.subset(&joints, &muscles);
        let mut state_map = Vec::with_capacity(plant.dim());
        for &j in &joints {
            state_map.extend([2 * j, 2 * j + 1]);
        }
        for &i in &muscles {
            let o = whole.offset(i);
            state_map.extend(o..o + whole.mtus[i].state_dim());
        }
        let (n, m) = (plant.dim(), plant.muscle_count());
        let mut dims = Vec::new();
        jacobian::leaf_dims(&plant, &mut dims);
        let matrix = ArrowheadMatrix::new(2 * plant.joint_count(), &dims);
        Self {
            memo: RefCell::new(ActivationMemo {
                t: f64::NAN,
                a: vec![0.0; m],
                scratch: JacobianScratch::new(dims.iter().copied().max().unwrap_or(0), n),
            }),
            stepper: match stepping {
                // Third order for ticks one step covers, fourth while the state moves fast, for
                // the models that gain from it (their `ModelSpec` says so).
                Stepping::Adaptive { .. } if plant.model.spec().fourth_order_transients => {
                    Esdirk::new(n, matrix, Tableau::ark324()).with_high_order(Tableau::esdirk436())
                }
                Stepping::Adaptive { .. } => Esdirk::new(n, matrix, Tableau::ark324()),
                Stepping::Fixed(_) => Esdirk::new(n, matrix, Tableau::trbdf2()),
            },
            y: vec![0.0; n],
            h: 0.0,
            saved_h: 0.0,
            inputs: Inputs::zeros(m, plant.joint_count()),
            a0: vec![0.0; m],
            a1: vec![0.0; m],
            neural: (plant.mtus.iter().enumerate())
                .filter(|(_, mtu)| mtu.params.activation == ActivationKind::LloydBesier)
                .map(|(k, _)| k)
                .collect(),
            lm_before: vec![0.0; m],
            energy: vec![TickEnergy::default(); m],
            plant,
            muscles,
            joints,
            state_map,
        }
    }

    /// Takes this part's state, activations (at the tick's start, and at its end where the
    /// whole computes them) and inputs from the whole; its driven joints start the tick at
    /// their input motion.
    pub(crate) fn gather(
        &mut self,
        y: &[f64],
        activation: &[f64],
        activation_end: &[f64],
        inputs: &Inputs,
    ) {
        for (local, &global) in self.y.iter_mut().zip(&self.state_map) {
            *local = y[global];
        }
        for (k, &i) in self.muscles.iter().enumerate() {
            self.a0[k] = activation[i];
            self.inputs.excitation[k] = inputs.excitation[i];
            self.inputs.tendon_force[k] = inputs.tendon_force[i];
        }
        // Only Lloyd & Besier's muscles read an end value.
        for &k in &self.neural {
            self.a1[k] = activation_end[self.muscles[k]];
        }
        for (k, &j) in self.joints.iter().enumerate() {
            self.inputs.external_torque[k] = inputs.external_torque[j];
            self.inputs.joint_angle[k] = inputs.joint_angle[j];
            self.inputs.joint_velocity[k] = inputs.joint_velocity[j];
        }
        self.plant.set_driven_motion(&self.inputs, &mut self.y);
    }

    /// Gives this part's state and its activations at the tick's end back to the whole.
    pub(crate) fn scatter(&self, y: &mut [f64], activation: &mut [f64]) {
        for (local, &global) in self.y.iter().zip(&self.state_map) {
            y[global] = *local;
        }
        let memo = self.memo.borrow();
        for (k, &i) in self.muscles.iter().enumerate() {
            activation[i] = memo.a[k];
        }
    }

    /// The global indices of its muscles, in local order.
    pub(crate) fn muscles(&self) -> &[usize] {
        &self.muscles
    }

    /// Local muscle k's metabolic rates after a tick (its state, the activation at the tick's
    /// end, the tick's excitation given by the probe's `terms` of it), from this part's own
    /// contractile elements (whose state outside the ODE, the full model's grid, is the one
    /// stepped).
    pub(crate) fn metabolic(&self, k: usize, terms: &ExcitationTerms) -> MetabolicSample {
        let a = self.memo.borrow().a[k];
        self.plant.metabolic(&self.y, k, a, &self.inputs, terms)
    }

    /// Local muscle k's energetics over the tick just stepped ([`MuscleEnergy::tick`]), from
    /// what the whole carries of it.
    pub(crate) fn energy_of(&self, k: usize, carried: &MuscleEnergy) -> TickEnergy {
        let (probe, u) = (&self.plant.mtus[k].probe, self.inputs.excitation[k]);
        carried.tick(probe, u, |terms| self.metabolic(k, terms))
    }

    /// Every muscle's [`Part::energy_of`], from what the whole carries of them (`carried`, by
    /// global muscle index), kept for [`Part::tick_energy`]: for a part stepped on a thread of
    /// its own, which computes them there.
    pub(crate) fn compute_energy(&mut self, carried: &[MuscleEnergy]) {
        for k in 0..self.muscles.len() {
            self.energy[k] = self.energy_of(k, &carried[self.muscles[k]]);
        }
    }

    /// Its muscles' energetics over the last tick, in local order ([`Part::compute_energy`]).
    pub(crate) fn tick_energy(&self) -> &[TickEnergy] {
        &self.energy
    }

    /// Work counters of its stepper.
    pub(crate) fn stats(&self) -> Stats {
        self.stepper.stats
    }

    /// Whether its state and its activations at the tick's end are finite.
    pub(crate) fn is_finite(&self) -> bool {
        self.y.iter().all(|v| v.is_finite()) && self.memo.borrow().a.iter().all(|v| v.is_finite())
    }

    fn ode(&self, dt: f64) -> TickOde<'_> {
        TickOde {
            plant: &self.plant,
            inputs: &self.inputs,
            a0: &self.a0,
            a1: &self.a1,
            neural: (!self.neural.is_empty()).then_some(&self.neural[..]),
            dt,
            memo: &self.memo,
        }
    }

    /// One tick of length dt; false if the implicit solve failed. The activations at dt are in
    /// the memo afterwards.
    pub(crate) fn step(&mut self, dt: f64, stepping: Stepping) -> bool {
        self.saved_h = self.h;
        let mut ok = true;
        let substeps = match stepping {
            Stepping::Adaptive {
                tolerance,
                max_substeps,
            } => {
                let ode = TickOde {
                    plant: &self.plant,
                    inputs: &self.inputs,
                    a0: &self.a0,
                    a1: &self.a1,
                    neural: (!self.neural.is_empty()).then_some(&self.neural[..]),
                    dt,
                    memo: &self.memo,
                };
                ok = self
                    .stepper
                    .advance(
                        &ode,
                        0.0,
                        dt,
                        &mut self.y,
                        &mut self.h,
                        tolerance,
                        max_substeps,
                    )
                    .is_ok();
                0
            }
            Stepping::Fixed(n) => n,
        };
        let h = dt / substeps.max(1) as f64;
        for k in 0..substeps {
            let t = k as f64 * h;
            for i in 0..self.plant.mtus.len() {
                self.lm_before[i] = self.plant.fibre_length(&self.y, i, &self.inputs);
                self.plant.mtus[i].ce.before_substep(t, h);
            }
            let ode = TickOde {
                plant: &self.plant,
                inputs: &self.inputs,
                a0: &self.a0,
                a1: &self.a1,
                neural: (!self.neural.is_empty()).then_some(&self.neural[..]),
                dt,
                memo: &self.memo,
            };
            ok &= self.stepper.step(&ode, t, h, &mut self.y).is_ok();
            ode.at(t + 0.5 * h);
            let memo = self.memo.borrow();
            for i in 0..self.plant.mtus.len() {
                let o = self.plant.offset(i);
                let n = self.plant.mtus[i].state_dim();
                let l_m = self.plant.fibre_length(&self.y, i, &self.inputs);
                let own = o + self.plant.mtus[i].mechanics.dim();
                let mtu = &mut self.plant.mtus[i];
                let motion = SubstepMotion {
                    dt: h,
                    activation_mid: memo.a[i],
                    overlap_mid: mtu.overlap_at(0.5 * (l_m + self.lm_before[i]), memo.a[i]),
                    fibre_length_change: l_m - self.lm_before[i],
                };
                mtu.ce.after_substep(&motion, &mut self.y[own..o + n]);
            }
            drop(memo);
            if !ok {
                break;
            }
        }
        self.ode(dt).at(dt);
        ok
    }

    /// After a failed tick: back to the carried step size, no Jacobian, no sub-step history.
    pub(crate) fn abandon(&mut self) {
        self.h = self.saved_h;
        for m in &mut self.plant.mtus {
            m.ce.forget_history();
        }
        self.stepper.invalidate();
    }

    /// Back to the start: contractile elements with nothing outside their ODE state, no
    /// Jacobian, no carried sub-step size.
    pub(crate) fn reset(&mut self) {
        for m in &mut self.plant.mtus {
            m.ce.reset();
        }
        self.stepper.invalidate();
        self.h = 0.0;
    }
}

/// What a part carries from tick to tick: its contractile elements' own state (the full
/// model's grid), its state and inputs as last gathered, the carried sub-step size, the
/// activation memo (its time and values: the next tick's scatter and energetics read them) and
/// the stepper. Its structure (plant, index maps) and the Jacobian's scratch space, written
/// before every read, are the rebuilt part's.
impl SavedState for Part {
    fn save_state(&self, out: &mut StateWriter) {
        out.usize(self.plant.mtus.len());
        for mtu in &self.plant.mtus {
            mtu.ce.save_state(out);
        }
        out.f64s(&self.y);
        out.f64(self.h);
        out.f64(self.saved_h);
        self.inputs.save_state(out);
        out.f64s(&self.a0);
        out.f64s(&self.lm_before);
        let memo = self.memo.borrow();
        out.f64(memo.t);
        out.f64s(&memo.a);
        self.stepper.save_state(out);
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        input.expect_len("part's muscles", self.plant.mtus.len())?;
        for (k, mtu) in self.plant.mtus.iter_mut().enumerate() {
            (mtu.ce.restore_state(input))
                .map_err(|e| e.in_part(format!("muscle {k} of the part")))?;
        }
        input.f64s_into("part's state", &mut self.y)?;
        self.h = input.f64("carried sub-step")?;
        self.saved_h = input.f64("saved sub-step")?;
        self.inputs.restore_state(input)?;
        input.f64s_into("part's activations at the tick's start", &mut self.a0)?;
        input.f64s_into("part's fibre lengths", &mut self.lm_before)?;
        let memo = self.memo.get_mut();
        memo.t = input.f64("activation memo time")?;
        input.f64s_into("activation memo", &mut memo.a)?;
        self.stepper.restore_state(input)
    }
}
