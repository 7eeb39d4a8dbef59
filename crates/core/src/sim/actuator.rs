//! `Actuator`: the limb of the configuration (any joints and muscles), stepped at a fixed tick.
//!
//! Inputs (excitations, external torques) set between ticks take effect at the next tick and are
//! held constant over it (zero-order hold), so a run is reproducible from its inputs and their
//! ticks. `step` does not allocate.
//!
//! A driven joint (`driven = true` in the configuration) is not integrated: its angle and
//! velocity are inputs too ([`Actuator::set_joint_motion`]), extrapolated linearly over the tick
//! (`θ0 + ω0 t`), and [`Actuator::joint_efforts`] is the muscles' net torque on each of them,
//! what a robot simulator that owns the joint applies.

use crate::config::ActuatorConfig;
use crate::physics::models::ModelKind;
use crate::physics::plant::{Inputs, Plant};
use crate::physics::stepping::Stepping;
use crate::sim::setup_error::SetupError;
use crate::sim::simulation::{Simulation, StepError};
use crate::sim::snapshot::{JointSnapshot, MuscleSnapshot, StateSnapshot};

/// A simulated limb: the joints and muscles of a configuration.
#[derive(Debug, Clone)]
pub struct Actuator {
    config: ActuatorConfig,
    sim: Simulation,
    muscle_names: Vec<String>,
    joint_names: Vec<String>,
    driven: Vec<usize>,
    state: StateSnapshot,
}

impl Actuator {
    /// Builds the actuator in its initial state (joints at their initial angles, at rest, a = 0).
    /// `rate_hz` is the tick rate (> 0, finite). It steps as the configuration's `[stepper]`
    /// table says ([`ActuatorConfig::stepping`]), by default as the model does.
    pub fn new(
        config: &ActuatorConfig,
        model: ModelKind,
        rate_hz: f64,
    ) -> Result<Self, SetupError> {
        Self::with_stepping(config, model, rate_hz, config.stepping(model, None)?)
    }

    /// As `new`, with a chosen sub-stepping (the configuration's `[stepper]` table is not
    /// consulted).
    pub fn with_stepping(
        config: &ActuatorConfig,
        model: ModelKind,
        rate_hz: f64,
        stepping: Stepping,
    ) -> Result<Self, SetupError> {
        config.validate()?;
        let plant = Plant::new(&config.topology(), model)?;
        let mut inputs = Inputs::zeros(plant.muscle_count(), plant.joint_count());
        initial_joint_motion(config, &mut inputs);
        let sim = Simulation::new(plant, rate_hz, stepping, inputs)?;
        let mut actuator = Self {
            config: config.clone(),
            sim,
            muscle_names: config.muscle_names(),
            joint_names: config.joint_names(),
            driven: (config.joints.iter().enumerate())
                .filter(|(_, j)| j.driven)
                .map(|(k, _)| k)
                .collect(),
            state: StateSnapshot::default(),
        };
        actuator.sim.fill_snapshot(&mut actuator.state);
        Ok(actuator)
    }

    /// The model that drives the muscles.
    pub fn model(&self) -> ModelKind {
        self.sim.plant().model
    }
    /// Tick rate, Hz.
    pub fn rate_hz(&self) -> f64 {
        self.sim.rate_hz()
    }
    /// The configuration it was built from.
    pub fn config(&self) -> &ActuatorConfig {
        &self.config
    }
    /// The underlying simulation.
    pub fn simulation(&self) -> &Simulation {
        &self.sim
    }
    /// Muscle names, in configuration order.
    pub fn muscle_names(&self) -> &[String] {
        &self.muscle_names
    }
    /// Joint names, in configuration order.
    pub fn joint_names(&self) -> &[String] {
        &self.joint_names
    }
    /// Ticks done since start or reset.
    pub fn tick(&self) -> u64 {
        self.sim.tick()
    }
    /// Simulated time, s (tick / rate).
    pub fn time(&self) -> f64 {
        self.sim.time()
    }
    /// Sets muscle `index`'s excitation for the following ticks. The caller validates: the value
    /// is clamped to [0, 1] here, and a non-finite value or unknown index is ignored.
    pub fn set_excitation(&mut self, index: usize, excitation: f64) {
        if let Some(u) = self.sim.inputs_mut().excitation.get_mut(index) {
            if excitation.is_finite() {
                *u = excitation.clamp(0.0, 1.0);
            }
        }
    }
    /// Sets the external torque on joint `index`, N m; non-finite or unknown is ignored.
    pub fn set_external_torque(&mut self, index: usize, torque: f64) {
        if let Some(t) = self.sim.inputs_mut().external_torque.get_mut(index) {
            if torque.is_finite() {
                *t = torque;
            }
        }
    }
    /// Indices of the driven joints, in configuration order.
    pub fn driven_joints(&self) -> &[usize] {
        &self.driven
    }
    /// Sets driven joint `index`'s motion for the following ticks: its angle (rad) and angular
    /// velocity (rad/s) at the next tick's start, extrapolated linearly over the tick
    /// (`θ(t) = angle + velocity · t`). A motion set once carries on: each later tick starts
    /// where the last one's extrapolation ended, with the same velocity, until it is set again
    /// (between a simulator's joint-state messages: linear extrapolation). Returns false,
    /// changing nothing, for a joint that is not driven, an unknown index or a non-finite value.
    pub fn set_joint_motion(&mut self, index: usize, angle_rad: f64, velocity_rad_s: f64) -> bool {
        if !self.driven.contains(&index) || !angle_rad.is_finite() || !velocity_rad_s.is_finite() {
            return false;
        }
        let inputs = self.sim.inputs_mut();
        inputs.joint_angle[index] = angle_rad;
        inputs.joint_velocity[index] = velocity_rad_s;
        true
    }
    /// The muscles' net torque `Σ_i r_ij F_SE,i` on each driven joint after the last tick, N m,
    /// in configuration order of the driven joints (what the robot simulator must apply).
    pub fn joint_efforts(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.driven.iter().map(|&j| self.state.joints[j].torque)
    }
    /// Advances one tick. On a failure it returns an error and leaves the state as it was; call
    /// `reset`.
    pub fn step(&mut self) -> Result<(), StepError> {
        self.sim.step_and_fill(&mut self.state)
    }
    /// Steps its independent parts on `threads` threads (`Simulation::set_threads`: the same
    /// results to the bit; 1, the default, steps them on the caller's thread).
    pub fn set_threads(&mut self, threads: usize) -> Result<(), SetupError> {
        self.sim.set_threads(threads)
    }
    /// Back to the initial state (inputs zeroed, driven joints at their initial angles and at
    /// rest, tick 0).
    pub fn reset(&mut self) {
        let mut inputs = self.sim.inputs().clone();
        inputs.clear();
        initial_joint_motion(&self.config, &mut inputs);
        self.sim.reset_with(&inputs);
        self.sim.fill_snapshot(&mut self.state);
    }
    /// Its simulation and its published state, for a saved state to be restored into
    /// (sim::saved).
    pub(super) fn restore_target(&mut self) -> (&mut Simulation, &mut StateSnapshot) {
        (&mut self.sim, &mut self.state)
    }
    /// Everything observable after the last tick.
    pub fn state(&self) -> &StateSnapshot {
        &self.state
    }
    /// Muscle states after the last tick, in configuration order.
    pub fn muscles(&self) -> &[MuscleSnapshot] {
        &self.state.muscles
    }
    /// Joint states after the last tick, in configuration order.
    pub fn joints(&self) -> &[JointSnapshot] {
        &self.state.joints
    }
}

/// The driven joints' motion before any is set: their initial angles, at rest.
fn initial_joint_motion(config: &ActuatorConfig, inputs: &mut Inputs) {
    for (k, j) in config.joints.iter().enumerate() {
        inputs.joint_angle[k] = j.initial_angle;
        inputs.joint_velocity[k] = 0.0;
    }
}
