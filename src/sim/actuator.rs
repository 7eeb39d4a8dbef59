//! `Actuator`: the antagonistic joint of the configuration, stepped at a fixed tick.
//!
//! Inputs (excitations, external torque) set between ticks take effect at the next tick and are
//! held constant over it (zero-order hold), so a run is reproducible from its inputs and their
//! ticks. `step` does not allocate.

use crate::config::ActuatorConfig;
use crate::physics::model::ModelKind;
use crate::sim::snapshot::{JointSnapshot, MuscleSnapshot};

/// The state stopped being finite; the caller resets (the actuator is left as it was before).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the simulation state became non-finite at tick {tick}; the joint must be reset")]
pub struct StepError {
    /// The tick that failed.
    pub tick: u64,
}

/// A simulated antagonistic actuator (one joint, two muscles).
pub struct Actuator {
    config: ActuatorConfig,
    model: ModelKind,
    rate_hz: f64,
    tick: u64,
    muscle_names: Vec<String>,
    joint_names: Vec<String>,
    excitation: [f64; 2],
    external_torque: f64,
    muscles: [MuscleSnapshot; 2],
    joint: JointSnapshot,
}

impl Actuator {
    /// Builds the actuator in its initial state (joint at `initial_angle`, at rest, a = 0).
    /// `rate_hz` is the tick rate (> 0, finite).
    pub fn new(config: &ActuatorConfig, model: ModelKind, rate_hz: f64) -> Result<Self, String> {
        config.validate().map_err(|e| e.to_string())?;
        if !(rate_hz.is_finite() && rate_hz > 0.0) {
            return Err(format!(
                "invalid rate_hz = {rate_hz}: must be a finite number > 0"
            ));
        }
        Ok(Self {
            config: config.clone(),
            model,
            rate_hz,
            tick: 0,
            muscle_names: config.muscles.iter().map(|m| m.name.clone()).collect(),
            joint_names: vec![config.joint.name.clone()],
            excitation: [0.0; 2],
            external_torque: 0.0,
            muscles: [MuscleSnapshot::default(); 2],
            joint: JointSnapshot::default(),
        })
    }

    /// The model that drives the muscles.
    pub fn model(&self) -> ModelKind {
        self.model
    }
    /// Tick rate, Hz.
    pub fn rate_hz(&self) -> f64 {
        self.rate_hz
    }
    /// The configuration it was built from.
    pub fn config(&self) -> &ActuatorConfig {
        &self.config
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
        self.tick
    }
    /// Simulated time, s (tick / rate).
    pub fn time(&self) -> f64 {
        self.tick as f64 / self.rate_hz
    }
    /// Sets muscle `index`'s excitation for the following ticks. The caller validates: the value
    /// is clamped to [0, 1] here, and a non-finite value is ignored.
    pub fn set_excitation(&mut self, index: usize, excitation: f64) {
        if excitation.is_finite() {
            if let Some(u) = self.excitation.get_mut(index) {
                *u = excitation.clamp(0.0, 1.0);
            }
        }
    }
    /// Sets the external torque on joint `index`, N m (positive flexes); non-finite is ignored.
    pub fn set_external_torque(&mut self, index: usize, torque: f64) {
        if index == 0 && torque.is_finite() {
            self.external_torque = torque;
        }
    }
    /// Advances one tick. On a non-finite state it returns an error and leaves the state as it
    /// was; call `reset`.
    pub fn step(&mut self) -> Result<(), StepError> {
        todo!("physics core lands here")
    }
    /// Back to the initial state (inputs zeroed, tick 0).
    pub fn reset(&mut self) {
        self.tick = 0;
        self.excitation = [0.0; 2];
        self.external_torque = 0.0;
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
