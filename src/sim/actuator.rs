//! `Actuator`: the antagonistic joint of the configuration, stepped at a fixed tick.
//!
//! Inputs (excitations, external torque) set between ticks take effect at the next tick and are
//! held constant over it (zero-order hold), so a run is reproducible from its inputs and their
//! ticks. `step` does not allocate.

use crate::config::ActuatorConfig;
use crate::physics::model::ModelKind;
use crate::physics::plant::{Inputs, Plant};
use crate::sim::simulation::{default_stepping, Simulation, StepError, Stepping};
use crate::sim::snapshot::{JointSnapshot, MuscleSnapshot};

/// A simulated antagonistic actuator (one joint, two muscles).
#[derive(Debug, Clone)]
pub struct Actuator {
    config: ActuatorConfig,
    sim: Simulation,
    muscle_names: Vec<String>,
    joint_names: Vec<String>,
    muscles: [MuscleSnapshot; 2],
    joint: JointSnapshot,
}

impl Actuator {
    /// Builds the actuator in its initial state (joint at `initial_angle`, at rest, a = 0).
    /// `rate_hz` is the tick rate (> 0, finite).
    pub fn new(config: &ActuatorConfig, model: ModelKind, rate_hz: f64) -> Result<Self, String> {
        Self::with_stepping(config, model, rate_hz, default_stepping(model))
    }

    /// As `new`, with a chosen sub-stepping.
    pub fn with_stepping(
        config: &ActuatorConfig,
        model: ModelKind,
        rate_hz: f64,
        stepping: Stepping,
    ) -> Result<Self, String> {
        config.validate().map_err(|e| e.to_string())?;
        let plant = Plant::new(&config.muscle_params(), model, config.joint_attachment())?;
        let sim = Simulation::new(plant, rate_hz, stepping, Inputs::default())?;
        let mut actuator = Self {
            config: config.clone(),
            sim,
            muscle_names: config.muscles.iter().map(|m| m.name.clone()).collect(),
            joint_names: vec![config.joint.name.clone()],
            muscles: [MuscleSnapshot::default(); 2],
            joint: JointSnapshot::default(),
        };
        actuator.refresh();
        Ok(actuator)
    }

    fn refresh(&mut self) {
        self.muscles = [self.sim.muscle_snapshot(0), self.sim.muscle_snapshot(1)];
        self.joint = self
            .sim
            .joint_snapshot_with(&self.muscles)
            .unwrap_or_default();
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
    /// Muscle names: agonist, antagonist.
    pub fn muscle_names(&self) -> &[String] {
        &self.muscle_names
    }
    /// Joint names (one joint).
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
    /// is clamped to [0, 1] here, and a non-finite value is ignored.
    pub fn set_excitation(&mut self, index: usize, excitation: f64) {
        if excitation.is_finite() && index < 2 {
            let mut inputs = *self.sim.inputs();
            inputs.excitation[index] = excitation.clamp(0.0, 1.0);
            self.sim.set_inputs(inputs);
        }
    }
    /// Sets the external torque on joint `index`, N m (positive flexes); non-finite is ignored.
    pub fn set_external_torque(&mut self, index: usize, torque: f64) {
        if index == 0 && torque.is_finite() {
            let mut inputs = *self.sim.inputs();
            inputs.external_torque = torque;
            self.sim.set_inputs(inputs);
        }
    }
    /// Advances one tick. On a non-finite state it returns an error and leaves the state as it
    /// was; call `reset`.
    pub fn step(&mut self) -> Result<(), StepError> {
        self.sim.step()?;
        self.refresh();
        Ok(())
    }
    /// Back to the initial state (inputs zeroed, tick 0).
    pub fn reset(&mut self) {
        self.sim.reset(Inputs::default());
        self.refresh();
    }
    /// Muscle states after the last tick: agonist, antagonist.
    pub fn muscles(&self) -> &[MuscleSnapshot] {
        &self.muscles
    }
    /// Joint states after the last tick (one joint).
    pub fn joints(&self) -> &[JointSnapshot] {
        std::slice::from_ref(&self.joint)
    }
}
