//! A plant stepped at a fixed tick: inputs held over each tick, activation advanced exactly, the
//! mechanics and the contractile states by implicit sub-steps, independent parts of the limb
//! apart (sim::part), models with state outside the ODE (the full Huxley grid) through their
//! sub-step hooks. Deterministic and allocation-free per tick, for any topology and any
//! contractile model.

use crate::integrator::Stats;
use crate::physics::models::ModelKind;
use crate::physics::observables::EnergeticsOutputs;
use crate::physics::plant::{Inputs, Plant};
use crate::sim::energy::MuscleEnergy;
use crate::sim::neural_drive::NeuralDrive;
use crate::sim::part::Part;
use crate::sim::setup_error::SetupError;
use crate::sim::snapshot::{JointSnapshot, MuscleSnapshot, StateSnapshot};
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};
use rayon::prelude::*;
use std::sync::Arc;

use crate::physics::stepping::Stepping;

/// Most threads a simulation steps its parts on.
pub(crate) const MAX_THREADS: usize = 256;

/// Highest tick rate, Hz (a sanity bound: 100 kHz).
pub const MAX_RATE_HZ: f64 = 100_000.0;

/// The default stepping of a model (its `ModelSpec::stepping`),
/// that of a configuration without a `[stepper]` table
/// ([`ActuatorConfig::stepping`](crate::config::ActuatorConfig::stepping)).
pub fn default_stepping(model: ModelKind) -> Stepping {
    model.spec().stepping
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

/// A plant with its state, stepped tick by tick.
#[derive(Debug, Clone)]
pub struct Simulation {
    plant: Plant,
    parts: Vec<Part>,
    rate_hz: f64,
    stepping: Stepping,
    inputs: Inputs,
    activation: Vec<f64>,
    /// Per muscle with Lloyd & Besier's activation, its drive (docs/model.md §2b).
    neural: Vec<Option<NeuralDrive>>,
    /// The activations at the end of the tick being stepped, of those muscles.
    activation_end: Vec<f64>,
    /// Whether any muscle has one.
    has_neural: bool,
    y: Vec<f64>,
    tick: u64,
    /// Per muscle: the energetics carried from tick to tick (sim::energy).
    energy: Vec<MuscleEnergy>,
    /// The threads its parts are stepped on (None: the caller's thread alone).
    pool: Option<Arc<rayon::ThreadPool>>,
}

impl Simulation {
    /// A simulation at rest under `inputs` (their tendon forces set the force-driven resting
    /// state), ticking at `rate_hz` with the given sub-stepping.
    pub fn new(
        plant: Plant,
        rate_hz: f64,
        stepping: Stepping,
        inputs: Inputs,
    ) -> Result<Self, SetupError> {
        if !(rate_hz.is_finite() && rate_hz > 0.0) {
            return Err(SetupError::Rate(rate_hz));
        }
        stepping.check()?;
        if stepping.is_adaptive() && !plant.model.is_ode() {
            return Err(SetupError::NeedsFixedSubsteps(plant.model));
        }
        let (n, m, j) = (plant.dim(), plant.muscle_count(), plant.joint_count());
        if inputs.excitation.len() != m
            || inputs.tendon_force.len() != m
            || inputs.external_torque.len() != j
            || inputs.joint_angle.len() != j
            || inputs.joint_velocity.len() != j
        {
            return Err(SetupError::InputSizes {
                muscles: inputs.excitation.len(),
                joints: inputs.external_torque.len(),
                plant_muscles: m,
                plant_joints: j,
            });
        }
        let neural = plant
            .mtus
            .iter()
            .enumerate()
            .map(|(i, mtu)| {
                NeuralDrive::of(&mtu.params, rate_hz)
                    .map_err(|source| SetupError::Activation { muscle: i, source })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let parts = plant
            .components()
            .into_iter()
            .map(|(joints, muscles)| Part::new(&plant, joints, muscles, stepping))
            .collect();
        let mut sim = Self {
            rate_hz,
            stepping,
            inputs: inputs.clone(),
            activation: vec![0.0; m],
            has_neural: neural.iter().any(Option::is_some),
            neural,
            activation_end: vec![0.0; m],
            y: vec![0.0; n],
            tick: 0,
            energy: vec![MuscleEnergy::default(); m],
            pool: None,
            parts,
            plant,
        };
        sim.reset_with(&inputs);
        Ok(sim)
    }

    /// Back to rest under `inputs`, tick 0.
    pub(crate) fn reset_with(&mut self, inputs: &Inputs) {
        self.inputs.clone_from(inputs);
        self.activation.fill(0.0);
        for d in self.neural.iter_mut().flatten() {
            d.reset();
        }
        self.plant.resting_state(&self.inputs, &mut self.y);
        for p in &mut self.parts {
            p.reset();
        }
        for (i, mtu) in self.plant.mtus.iter().enumerate() {
            let terms = mtu.probe.excitation_terms(self.inputs.excitation[i]);
            let rest = self.plant.metabolic(&self.y, i, 0.0, &self.inputs, &terms);
            self.energy[i] = MuscleEnergy::at_rest(rest, terms);
        }
        self.tick = 0;
    }

    /// The plant.
    pub fn plant(&self) -> &Plant {
        &self.plant
    }
    /// Tick rate, Hz.
    pub(crate) fn rate_hz(&self) -> f64 {
        self.rate_hz
    }
    /// How ticks are divided into sub-steps.
    pub fn stepping(&self) -> Stepping {
        self.stepping
    }
    /// Ticks done.
    pub(crate) fn tick(&self) -> u64 {
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
    /// The inputs for the next tick, to change in place (the sizes must stay).
    pub fn inputs_mut(&mut self) -> &mut Inputs {
        &mut self.inputs
    }
    /// The state vector (layout in physics::plant).
    pub fn state(&self) -> &[f64] {
        &self.y
    }
    /// Activations.
    pub fn activations(&self) -> &[f64] {
        &self.activation
    }
    /// The number of independently stepped parts (joints connected by muscles).
    pub fn part_count(&self) -> usize {
        self.parts.len()
    }
    /// Integrator work counters, summed over the parts.
    pub fn stats(&self) -> Stats {
        self.parts
            .iter()
            .fold(Stats::default(), |a, p| a + p.stats())
    }

    /// Steps the parts on `threads` threads (1: on the caller's thread, the default). The parts
    /// are independent and each is stepped by the same code wherever it runs, so the results
    /// are the same to the bit for any number of threads; a limb of one part gains nothing.
    pub(crate) fn set_threads(&mut self, threads: usize) -> Result<(), SetupError> {
        if !(1..=MAX_THREADS).contains(&threads) {
            return Err(SetupError::Threads {
                threads,
                max: MAX_THREADS,
            });
        }
        self.pool = match threads {
            1 => None,
            n => Some(Arc::new(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .thread_name(|i| format!("parts-{i}"))
                    .build()
                    .map_err(|source| SetupError::ThreadPool { threads: n, source })?,
            )),
        };
        Ok(())
    }

    /// The threads its parts are stepped on.
    pub fn threads(&self) -> usize {
        self.pool.as_ref().map_or(1, |p| p.current_num_threads())
    }

    /// Whether its parts are stepped on its threads (more than one thread and one part).
    fn parts_on_threads(&self) -> bool {
        self.pool.is_some() && self.parts.len() > 1
    }

    /// Whether its muscles' published states are computed on its threads (more than one
    /// thread and one muscle).
    fn muscles_on_threads(&self) -> bool {
        self.pool.is_some() && self.plant.muscle_count() > 1
    }

    /// Gathers and steps every part over dt: whether all succeeded, and how many were stepped
    /// (on one thread the parts after a failed one are not). On threads (called within the
    /// pool) each part computes its muscles' energetics where it was stepped
    /// ([`Part::compute_energy`]); on one thread [`Simulation::step`] computes them as it
    /// commits them, by the same code.
    fn step_parts(&mut self, dt: f64) -> (bool, usize) {
        let on_threads = self.parts_on_threads();
        let Self {
            parts,
            y,
            activation,
            activation_end,
            inputs,
            stepping,
            energy,
            ..
        } = self;
        let one = |p: &mut Part| {
            p.gather(y, activation, activation_end, inputs);
            p.step(dt, *stepping)
        };
        if on_threads {
            let ok = parts
                .par_iter_mut()
                .map(|p| {
                    let ok = one(p);
                    if ok && ENERGETICS {
                        p.compute_energy(energy);
                    }
                    ok
                })
                .reduce(|| true, |a, b| a && b);
            return (ok, parts.len());
        }
        let mut stepped = 0;
        for p in parts.iter_mut() {
            stepped += 1;
            if !one(p) {
                return (false, stepped);
            }
        }
        (true, stepped)
    }

    /// Runs `work` within its pool when it has one (its parallel iterators then run on the
    /// pool's threads, the caller's thread waiting once), else here.
    fn in_pool<R: Send>(&mut self, work: impl FnOnce(&mut Self) -> R + Send) -> R {
        match self.pool.clone() {
            Some(pool) => pool.install(|| work(self)),
            None => work(self),
        }
    }

    /// Advances one tick, each part with its own sub-steps. A failed or non-finite result
    /// restores the previous state (of every part) and is reported.
    pub fn step(&mut self) -> Result<(), StepError> {
        if self.parts_on_threads() {
            self.in_pool(Self::step_here)
        } else {
            self.step_here()
        }
    }

    /// Advances one tick and fills `out` with the published state: [`Simulation::step`] then
    /// [`Simulation::fill_snapshot`], with one hand-over to its threads for both. On a failure
    /// `out` is left as it was.
    pub(crate) fn step_and_fill(&mut self, out: &mut StateSnapshot) -> Result<(), StepError> {
        let mut both = |s: &mut Self| {
            s.step_here()?;
            s.fill_here(out, None);
            Ok(())
        };
        if self.parts_on_threads() || self.muscles_on_threads() {
            self.in_pool(both)
        } else {
            both(self)
        }
    }

    /// [`Simulation::step`], within the pool when on threads.
    fn step_here(&mut self) -> Result<(), StepError> {
        let dt = 1.0 / self.rate_hz;
        if self.has_neural {
            self.neural_tick_ends();
        }
        let (ok, stepped) = self.step_parts(dt);
        let finite = ok && self.parts.iter().all(|p| p.is_finite());
        if !finite {
            let reason = if ok {
                "the state became non-finite"
            } else {
                "the implicit solver did not converge (a discontinuous spring or an extreme input?)"
            };
            for p in &mut self.parts[..stepped] {
                p.abandon();
            }
            return Err(StepError {
                tick: self.tick,
                reason,
            });
        }
        if self.has_neural {
            self.neural_commit();
        }
        let on_threads = self.parts_on_threads();
        for p in &self.parts {
            p.scatter(&mut self.y, &mut self.activation);
            for (k, &i) in p.muscles().iter().enumerate().filter(|_| ENERGETICS) {
                let e = &mut self.energy[i];
                if on_threads {
                    e.commit(&p.tick_energy()[k], dt);
                } else {
                    let tick = p.energy_of(k, e);
                    e.commit(&tick, dt);
                }
            }
        }
        // A driven joint shared by several parts: each integrated θ' = ω0 with its own
        // sub-steps; the state holds the rule's value, whatever the rounding.
        self.plant
            .set_driven_motion_after(&self.inputs, dt, &mut self.y);
        self.plant.carry_driven_motion(&self.y, &mut self.inputs);
        self.tick += 1;
        Ok(())
    }

    /// The activations at the end of the tick about to be stepped, of the muscles with Lloyd &
    /// Besier's activation. Out of line: the paper's first order, the common case, keeps the
    /// tick's code as it was.
    #[inline(never)]
    fn neural_tick_ends(&mut self) {
        for (i, d) in self.neural.iter_mut().enumerate() {
            if let Some(d) = d {
                self.activation_end[i] = d.tick_end(self.inputs.excitation[i]);
            }
        }
    }

    /// The kept tick's excitations taken by the recursions ([`NeuralDrive::commit`]).
    #[inline(never)]
    fn neural_commit(&mut self) {
        for (i, d) in self.neural.iter_mut().enumerate() {
            if let Some(d) = d {
                d.commit(self.inputs.excitation[i]);
            }
        }
    }

    /// Fills `out` with the published state (its vectors keep their storage); the muscles'
    /// states on the simulation's threads, each computed by the same code wherever it runs.
    pub fn fill_snapshot(&self, out: &mut StateSnapshot) {
        self.fill_here(out, self.pool.as_deref());
    }

    /// [`Simulation::fill_snapshot`]: with the muscles on its threads, they are handed to
    /// `pool`, or computed here when this runs within the pool already (`pool` None).
    fn fill_here(&self, out: &mut StateSnapshot, pool: Option<&rayon::ThreadPool>) {
        let (m, n) = (self.plant.muscle_count(), self.plant.joint_count());
        out.muscles.resize(m, MuscleSnapshot::default());
        out.joints.resize(n, JointSnapshot::default());
        out.stiffness_matrix.resize(n * n, 0.0);
        let Self {
            plant,
            y,
            activation,
            inputs,
            energy,
            ..
        } = self;
        if self.muscles_on_threads() {
            let states = &mut out.muscles;
            let mut all = || {
                states.par_iter_mut().enumerate().for_each(|(i, s)| {
                    *s = published(plant, y, activation, inputs, &energy[i], i);
                })
            };
            match pool {
                Some(pool) => pool.install(all),
                None => all(),
            }
        } else {
            for (i, (s, e)) in out.muscles.iter_mut().zip(energy.iter()).enumerate() {
                *s = published(plant, y, activation, inputs, e, i);
            }
        }
        let muscles = &out.muscles;
        self.plant.stiffness_matrix(
            &self.y,
            |i| (muscles[i].mtu_stiffness, muscles[i].force),
            &mut out.stiffness_matrix,
        );
        for j in 0..n {
            out.joints[j] = JointSnapshot {
                position: self.y[2 * j],
                velocity: self.y[2 * j + 1],
                torque: 0.0,
                external_torque: self.inputs.external_torque[j],
                stiffness: out.stiffness_matrix[j * n + j],
            };
        }
        let (muscles, joints) = (&out.muscles, &mut out.joints);
        self.plant
            .add_muscle_torques(&self.y, |i| muscles[i].force, |j, t| joints[j].torque += t);
    }

    /// The published state.
    pub fn snapshot(&self) -> StateSnapshot {
        let mut s = StateSnapshot::default();
        self.fill_snapshot(&mut s);
        s
    }

    /// Kinetic energy of the fibre masses and the joints, J.
    pub fn kinetic_energy(&self) -> f64 {
        self.plant.kinetic_energy(&self.y)
    }
}

/// What the simulation carries from tick to tick: the tick, the inputs held over the next one,
/// the activations, the state vector, each muscle's energetics, then each part's own state, then
/// the recursion of each muscle with Lloyd & Besier's activation (none for the paper's). The
/// plant, the rate and the stepping are the rebuilt simulation's, and the saved sizes must be
/// its; the whole plant's contractile elements are never stepped (the parts' are) and the
/// rates at a tick's start are scratch, so neither is saved.
impl SavedState for Simulation {
    fn save_state(&self, out: &mut StateWriter) {
        out.u64(self.tick);
        self.inputs.save_state(out);
        out.f64s(&self.activation);
        out.f64s(&self.y);
        out.usize(self.energy.len());
        for e in &self.energy {
            e.save_state(out);
        }
        out.usize(self.parts.len());
        for p in &self.parts {
            p.save_state(out);
        }
        for d in self.neural.iter().flatten() {
            d.save_state(out);
        }
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        self.tick = input.u64("tick")?;
        self.inputs.restore_state(input)?;
        input.f64s_into("activations", &mut self.activation)?;
        input.f64s_into("state vector", &mut self.y)?;
        input.expect_len("muscles' energetics", self.energy.len())?;
        for (i, e) in self.energy.iter_mut().enumerate() {
            e.restore_state(input)
                .map_err(|e| e.in_part(format!("muscle {i}")))?;
        }
        input.expect_len("parts", self.parts.len())?;
        for (k, p) in self.parts.iter_mut().enumerate() {
            p.restore_state(input)
                .map_err(|e| e.in_part(format!("part {k}")))?;
        }
        for (i, d) in self.neural.iter_mut().enumerate() {
            if let Some(d) = d {
                d.restore_state(input)
                    .map_err(|e| e.in_part(format!("muscle {i}'s neural activation")))?;
            }
        }
        Ok(())
    }
}

/// Whether the tick computes its energetics: always, but in the benchmarks' build that measures
/// what they cost (feature `without-energetics`, docs/benchmarks.md).
const ENERGETICS: bool = !cfg!(feature = "without-energetics");

/// Muscle i's published state: the plant's outputs at state `y` and activations `activation`
/// under `inputs`, with its energetics `e`.
#[inline]
fn published(
    plant: &Plant,
    y: &[f64],
    activation: &[f64],
    inputs: &Inputs,
    e: &MuscleEnergy,
    i: usize,
) -> MuscleSnapshot {
    if !ENERGETICS {
        return plant.outputs(y, activation, inputs, i, &EnergeticsOutputs::default());
    }
    let r = &e.sample.rates;
    let energetics = EnergeticsOutputs {
        metabolic_power: r.metabolic_w,
        activation_heat_rate: r.activation_heat_w,
        shortening_heat_rate: r.shortening_heat_w,
        work_rate: r.work_w,
        bridge_storage_rate: r.storage_w,
        atp_rate: r.atp_rate_mol_s,
        metabolic_energy: e.metabolic_j,
        phenomenological_power: r.phenomenological_w,
        phenomenological_energy: e.phenomenological_j,
    };
    plant.outputs(y, activation, inputs, i, &energetics)
}
