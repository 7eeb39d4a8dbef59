//! A plant stepped at a fixed tick: inputs held over each tick, activation advanced exactly,
//! the mechanics and moments by TR-BDF2 sub-steps, the full model's grid by characteristics.
//! Deterministic and allocation-free per tick.

use crate::integrator::trbdf2::TrBdf2;
use crate::integrator::OdeSystem;
use crate::physics::activation::activation_after;
use crate::physics::contractile::huxley_grid::CrossBridgeGrid;
use crate::physics::joint;
use crate::physics::model::ModelKind;
use crate::physics::plant::{Attachment, HeldClosure, Inputs, Plant};
use crate::sim::snapshot::{JointSnapshot, MuscleSnapshot};
use nalgebra::SVector;

/// Largest state vector (joint with two Huxley muscles).
pub const MAX_DIM: usize = 12;
/// Room of the full model's grid, in units of ξ (long tails after fast lengthening).
const GRID_EXTENT: f64 = 64.0;

/// How a tick is divided into implicit sub-steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stepping {
    /// Sub-steps chosen by the local error estimate: each below `tolerance` times the state's
    /// scales, at most `max_substeps` per tick.
    Adaptive {
        /// Relative local error tolerance.
        tolerance: f64,
        /// Most sub-steps per tick.
        max_substeps: usize,
    },
    /// A fixed number of equal sub-steps per tick (the full model always steps this way).
    Fixed(usize),
}

/// Local error tolerances of the adaptive stepping, relative to the state's scales, per model:
/// chosen so that 1 kHz ticks meet MODEL.md §10 against the reference solver with a margin of at
/// least 2 on every scenario (tests/integrator_accuracy.rs prints the deviations).
pub const HILL_TOLERANCE: f64 = 1e-5;
/// See [`HILL_TOLERANCE`]; the DM model's stiff cross-bridge spring needs a tighter one.
pub const HUXLEY_TOLERANCE: f64 = 2e-6;

/// The default stepping of each model.
pub fn default_stepping(model: ModelKind) -> Stepping {
    match model {
        ModelKind::Hill => Stepping::Adaptive {
            tolerance: HILL_TOLERANCE,
            max_substeps: 64,
        },
        ModelKind::Huxley => Stepping::Adaptive {
            tolerance: HUXLEY_TOLERANCE,
            max_substeps: 64,
        },
        ModelKind::HuxleyPde => Stepping::Fixed(20),
    }
}

/// A tick that could not be computed; the simulation is left as it was before the tick.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("tick {tick} failed: {reason}; the simulation must be reset")]
pub struct StepError {
    /// The tick that failed.
    pub tick: u64,
    /// What went wrong.
    pub reason: &'static str,
}

/// The plant's ODE over one tick, with activations in closed form from the tick's start.
struct TickOde<'a> {
    plant: &'a Plant,
    inputs: &'a Inputs,
    a0: [f64; 2],
    /// The last (t, activations) computed: Newton iterates at one stage time many times.
    memo: std::cell::Cell<(f64, [f64; 2])>,
}

impl<'a> TickOde<'a> {
    fn new(plant: &'a Plant, inputs: &'a Inputs, a0: [f64; 2]) -> Self {
        Self {
            plant,
            inputs,
            a0,
            memo: std::cell::Cell::new((f64::NAN, [0.0; 2])),
        }
    }

    fn activations(&self, t: f64) -> [f64; 2] {
        let (t_memo, a_memo) = self.memo.get();
        if t_memo == t {
            return a_memo;
        }
        let a = self.compute_activations(t);
        self.memo.set((t, a));
        a
    }

    fn compute_activations(&self, t: f64) -> [f64; 2] {
        let mut a = [0.0; 2];
        for (i, mtu) in self.plant.mtus.iter().enumerate() {
            let p = &mtu.params;
            a[i] = activation_after(self.a0[i], self.inputs.excitation[i], t, p.t_act, p.t_deact);
        }
        a
    }
}

impl<const N: usize> OdeSystem<N> for TickOde<'_> {
    fn rhs(&self, t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        let act = self.activations(t);
        self.plant
            .derivatives(t, y.as_slice(), &act, self.inputs, dy.as_mut_slice());
    }
    fn scales(&self) -> SVector<f64, N> {
        let mut s = SVector::<f64, N>::zeros();
        self.plant.scales(s.as_mut_slice());
        s
    }
}

/// The stepper for the plant's state dimension (the variants differ in size; there is one per
/// simulation, so no boxing).
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)]
enum Stepper {
    D2(TrBdf2<2>),
    D5(TrBdf2<5>),
    D6(TrBdf2<6>),
    D12(TrBdf2<12>),
}

impl Stepper {
    fn for_dim(dim: usize) -> Option<Self> {
        Some(match dim {
            2 => Stepper::D2(TrBdf2::new()),
            5 => Stepper::D5(TrBdf2::new()),
            6 => Stepper::D6(TrBdf2::new()),
            12 => Stepper::D12(TrBdf2::new()),
            _ => return None,
        })
    }

    fn step(&mut self, ode: &TickOde, t: f64, h: f64, y: &mut [f64]) -> bool {
        fn run<const N: usize>(
            s: &mut TrBdf2<N>,
            ode: &TickOde,
            t: f64,
            h: f64,
            y: &mut [f64],
        ) -> bool {
            let mut v = SVector::<f64, N>::from_column_slice(&y[..N]);
            let ok = s.step(ode, t, h, &mut v).is_ok();
            y[..N].copy_from_slice(v.as_slice());
            ok
        }
        match self {
            Stepper::D2(s) => run(s, ode, t, h, y),
            Stepper::D5(s) => run(s, ode, t, h, y),
            Stepper::D6(s) => run(s, ode, t, h, y),
            Stepper::D12(s) => run(s, ode, t, h, y),
        }
    }

    fn advance(
        &mut self,
        ode: &TickOde,
        t1: f64,
        y: &mut [f64],
        h: &mut f64,
        tol: f64,
        max_substeps: usize,
    ) -> bool {
        fn run<const N: usize>(
            s: &mut TrBdf2<N>,
            ode: &TickOde,
            t1: f64,
            y: &mut [f64],
            h: &mut f64,
            tol: f64,
            max: usize,
        ) -> bool {
            let mut v = SVector::<f64, N>::from_column_slice(&y[..N]);
            let ok = s.advance(ode, 0.0, t1, &mut v, h, tol, max).is_ok();
            y[..N].copy_from_slice(v.as_slice());
            ok
        }
        match self {
            Stepper::D2(s) => run(s, ode, t1, y, h, tol, max_substeps),
            Stepper::D5(s) => run(s, ode, t1, y, h, tol, max_substeps),
            Stepper::D6(s) => run(s, ode, t1, y, h, tol, max_substeps),
            Stepper::D12(s) => run(s, ode, t1, y, h, tol, max_substeps),
        }
    }

    fn stats(&self) -> crate::integrator::trbdf2::Stats {
        match self {
            Stepper::D2(s) => s.stats,
            Stepper::D5(s) => s.stats,
            Stepper::D6(s) => s.stats,
            Stepper::D12(s) => s.stats,
        }
    }
}

/// A plant with its state, stepped tick by tick.
#[derive(Debug, Clone)]
pub struct Simulation {
    plant: Plant,
    rate_hz: f64,
    stepping: Stepping,
    /// The adaptive stepping's carried sub-step size, s.
    h: f64,
    inputs: Inputs,
    activation: [f64; 2],
    y: [f64; MAX_DIM],
    stepper: Stepper,
    fresh_stepper: Stepper,
    grids: Vec<CrossBridgeGrid>,
    /// The full model's closure at the previous sub-step's start (for the held closure's slope).
    previous_closure: [Option<[f64; 3]>; 2],
    tick: u64,
}

impl Simulation {
    /// A simulation at rest under `inputs` (their tendon force sets the force-driven resting
    /// state), ticking at `rate_hz` with `substeps` implicit steps per tick.
    pub fn new(
        plant: Plant,
        rate_hz: f64,
        stepping: Stepping,
        inputs: Inputs,
    ) -> Result<Self, String> {
        if !(rate_hz.is_finite() && rate_hz > 0.0) {
            return Err(format!(
                "invalid rate_hz = {rate_hz}: must be a finite number > 0"
            ));
        }
        match stepping {
            Stepping::Fixed(n) if n == 0 || n > 10_000 => {
                return Err(format!(
                    "invalid substeps = {n}: must be between 1 and 10000"
                ));
            }
            Stepping::Adaptive {
                tolerance,
                max_substeps,
            } => {
                if !(tolerance.is_finite() && tolerance > 0.0) {
                    return Err(format!(
                        "invalid tolerance = {tolerance}: must be a finite number > 0"
                    ));
                }
                if max_substeps == 0 || max_substeps > 10_000 {
                    return Err(format!(
                        "invalid max_substeps = {max_substeps}: must be between 1 and 10000"
                    ));
                }
                if plant.model == ModelKind::HuxleyPde {
                    return Err("the huxley-pde model needs a fixed number of sub-steps".into());
                }
            }
            Stepping::Fixed(_) => {}
        }
        let stepper = Stepper::for_dim(plant.dim())
            .ok_or_else(|| format!("no stepper for a state of dimension {}", plant.dim()))?;
        let grids = match plant.model {
            ModelKind::HuxleyPde => plant
                .mtus
                .iter()
                .map(|m| CrossBridgeGrid::new(m.params.crossbridge.pde_cells, GRID_EXTENT))
                .collect(),
            _ => Vec::new(),
        };
        let mut sim = Self {
            plant,
            rate_hz,
            stepping,
            h: 0.0,
            inputs,
            activation: [0.0; 2],
            y: [0.0; MAX_DIM],
            fresh_stepper: stepper.clone(),
            stepper,
            grids,
            previous_closure: [None; 2],
            tick: 0,
        };
        sim.reset(inputs);
        Ok(sim)
    }

    /// Back to rest under `inputs`, tick 0.
    pub fn reset(&mut self, inputs: Inputs) {
        self.inputs = inputs;
        self.activation = [0.0; 2];
        self.plant
            .resting_state(&inputs, &mut self.y[..self.plant.dim()]);
        for g in &mut self.grids {
            g.reset();
        }
        self.previous_closure = [None; 2];
        self.stepper = self.fresh_stepper.clone();
        self.h = 0.0;
        self.tick = 0;
    }

    /// The plant.
    pub fn plant(&self) -> &Plant {
        &self.plant
    }
    /// Tick rate, Hz.
    pub fn rate_hz(&self) -> f64 {
        self.rate_hz
    }
    /// How ticks are divided into sub-steps.
    pub fn stepping(&self) -> Stepping {
        self.stepping
    }
    /// Ticks done.
    pub fn tick(&self) -> u64 {
        self.tick
    }
    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        self.tick as f64 / self.rate_hz
    }
    /// The inputs held over the next tick.
    pub fn inputs(&self) -> &Inputs {
        &self.inputs
    }
    /// Sets the inputs for the next tick.
    pub fn set_inputs(&mut self, inputs: Inputs) {
        self.inputs = inputs;
    }
    /// The state vector (layout in physics::plant).
    pub fn state(&self) -> &[f64] {
        &self.y[..self.plant.dim()]
    }
    /// Activations.
    pub fn activations(&self) -> &[f64] {
        &self.activation[..self.plant.mtus.len()]
    }
    /// The full model's grids (empty for the other models).
    pub fn grids(&self) -> &[CrossBridgeGrid] {
        &self.grids
    }
    /// Integrator work counters.
    pub fn stats(&self) -> crate::integrator::trbdf2::Stats {
        self.stepper.stats()
    }

    /// Advances one tick. A non-finite result restores the previous state and is reported.
    pub fn step(&mut self) -> Result<(), StepError> {
        let dt = 1.0 / self.rate_hz;
        let dim = self.plant.dim();
        let saved_y = self.y;
        let saved_h = self.h;
        let a0 = self.activation;
        let mut ok = true;
        let substeps = match self.stepping {
            Stepping::Adaptive {
                tolerance,
                max_substeps,
            } => {
                let ode = TickOde::new(&self.plant, &self.inputs, a0);
                ok = self.stepper.advance(
                    &ode,
                    dt,
                    &mut self.y[..dim],
                    &mut self.h,
                    tolerance,
                    max_substeps,
                );
                0
            }
            Stepping::Fixed(n) => n,
        };
        let h = dt / substeps.max(1) as f64;
        for k in 0..substeps {
            let t = k as f64 * h;
            if self.plant.model == ModelKind::HuxleyPde {
                for (i, g) in self.grids.iter().enumerate() {
                    let phi = g.closure(self.plant.mtus[i].rates());
                    let slope = match self.previous_closure[i] {
                        Some(prev) => [0, 1, 2].map(|k| (phi[k] - prev[k]) / h),
                        None => [0.0; 3],
                    };
                    self.plant.held_closure[i] = HeldClosure { phi, slope, t0: t };
                    self.previous_closure[i] = Some(phi);
                }
            }
            let mut lm_before = [0.0; 2];
            for (i, l) in lm_before.iter_mut().enumerate().take(self.plant.mtus.len()) {
                *l = self.y[self.plant.offset(i)];
            }
            let ode = TickOde::new(&self.plant, &self.inputs, a0);
            ok &= self.stepper.step(&ode, t, h, &mut self.y[..dim]);
            if self.plant.model == ModelKind::HuxleyPde {
                let a_mid = ode.activations(t + 0.5 * h);
                for (i, g) in self.grids.iter_mut().enumerate() {
                    let mtu = &self.plant.mtus[i];
                    let o = self.plant.offset(i);
                    let l_m = self.y[o];
                    let shift = (l_m - lm_before[i]) / mtu.crossbridge.l_h;
                    let r = a_mid[i] * mtu.overlap(0.5 * (l_m + lm_before[i]));
                    g.advance(mtu.rates(), r, h, shift);
                    self.y[o + 2..o + 5].copy_from_slice(&g.moments());
                }
            }
            if !ok {
                break;
            }
        }
        let ode = TickOde::new(&self.plant, &self.inputs, a0);
        let a1 = ode.activations(dt);
        let finite =
            self.y[..dim].iter().all(|v| v.is_finite()) && a1.iter().all(|v| v.is_finite());
        if !ok || !finite {
            let reason = if ok {
                "the state became non-finite"
            } else {
                "the implicit solver did not converge (a discontinuous spring or an extreme input?)"
            };
            self.y = saved_y;
            self.h = saved_h;
            self.previous_closure = [None; 2];
            self.stepper = self.fresh_stepper.clone();
            return Err(StepError {
                tick: self.tick,
                reason,
            });
        }
        self.activation = a1;
        self.tick += 1;
        Ok(())
    }

    /// Muscle i's published state.
    pub fn muscle_snapshot(&self, i: usize) -> MuscleSnapshot {
        let y = self.state();
        let o = self.plant.offset(i);
        let out = self.plant.outputs(y, &self.activation, &self.inputs, i);
        let q = self.plant.moments(y, i);
        MuscleSnapshot {
            excitation: self.inputs.excitation[i],
            activation: self.activation[i],
            force: out.tendon_force,
            ce_force: out.ce_force,
            pe_force: out.pe_force,
            fiber_length: y[o],
            fiber_velocity: y[o + 1],
            tendon_length: out.tendon_length,
            stiffness: out.ce_stiffness,
            mtu_stiffness: out.mtu_stiffness,
            q0: q[0],
            q1: q[1],
            q2: q[2],
            tendon_energy: out.tendon_energy,
            fiber_energy: out.fibre_energy,
            crossbridge_energy: out.crossbridge_energy,
        }
    }

    /// The joint's published state (None without a joint).
    pub fn joint_snapshot(&self) -> Option<JointSnapshot> {
        if !matches!(self.plant.attachment, Attachment::Joint { .. }) {
            return None;
        }
        let muscles = [self.muscle_snapshot(0), self.muscle_snapshot(1)];
        self.joint_snapshot_with(&muscles)
    }

    /// The joint's published state from the muscles' snapshots just taken (agonist,
    /// antagonist), without computing them again.
    pub fn joint_snapshot_with(&self, muscles: &[MuscleSnapshot; 2]) -> Option<JointSnapshot> {
        let Attachment::Joint { params, .. } = &self.plant.attachment else {
            return None;
        };
        let y = self.state();
        let [ago, ant] = muscles;
        Some(JointSnapshot {
            position: y[0],
            velocity: y[1],
            torque: params.radius * (ago.force - ant.force),
            external_torque: self.inputs.external_torque,
            stiffness: crate::physics::stiffness::joint_stiffness(
                params.radius,
                ago.mtu_stiffness,
                ant.mtu_stiffness,
            ),
        })
    }

    /// Kinetic energy of the fibre masses and the joint, J.
    pub fn kinetic_energy(&self) -> f64 {
        let y = self.state();
        let mut e = 0.0;
        for (i, mtu) in self.plant.mtus.iter().enumerate() {
            let v = y[self.plant.offset(i) + 1];
            e += 0.5 * mtu.params.mass * v * v;
        }
        if let Attachment::Joint { params, .. } = &self.plant.attachment {
            e += joint::kinetic_energy(params, y[1]);
        }
        e
    }
}
