//! The values of the node's parameters, and what they build.

use crate::ros::clock::ClockMode;
use muscle_actuator_core::config::{ActuatorConfig, ConfigError};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::EnergyModel;
use muscle_actuator_core::sim::Actuator;

/// Why the parameters give no actuator.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// The configuration they name cannot be used.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// The actuator cannot be set up (model, rate, limb).
    #[error(transparent)]
    Actuator(#[from] muscle_actuator_core::sim::SetupError),
}

/// The values of the node's parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeParams {
    /// Contractile-element model.
    pub model: ModelKind,
    /// Tick rate, Hz.
    pub rate_hz: f64,
    /// State publication rate, Hz; 0 (or >= rate_hz) = every tick.
    pub publish_rate_hz: f64,
    /// Configuration file ("" = the embedded default).
    pub config: String,
    /// Record to MCAP.
    pub record: bool,
    /// Directory for recordings ("" = no recording).
    pub record_dir: String,
    /// How ticks are paced and stamped (fixed at start-up).
    pub clock: ClockMode,
    /// `sim`: simulated seconds per wall-clock second; 0 = as fast as the steps go.
    pub real_time_factor: f64,
    /// `sim`, `lockstep`: `/clock` messages per simulated second; 0 = every tick.
    pub clock_rate_hz: f64,
    /// Driven joints: ticks without a `JointState` after which their input is reported stale.
    pub joint_state_timeout_ticks: i64,
    /// The phenomenological energy model of every muscle; `None` (the parameter empty): each
    /// muscle's `energetics.energy_model` from the configuration.
    pub energy_model: Option<EnergyModel>,
    /// The live view's TCP port (the Foxglove WebSocket protocol, docs/live-view.md); 0 = off
    /// (fixed at start-up).
    pub foxglove_port: u16,
}

impl NodeParams {
    /// Loads the configuration these parameters name, with `energy_model` applied.
    pub fn load_config(&self) -> Result<ActuatorConfig, ConfigError> {
        let cfg = if self.config.is_empty() {
            ActuatorConfig::default()
        } else {
            ActuatorConfig::resolve(&self.config)?
        };
        Ok(match self.energy_model {
            Some(m) => cfg.with_energy_model(m),
            None => cfg,
        })
    }

    /// Builds the actuator these parameters describe (checks the whole set).
    pub fn build(&self) -> Result<Actuator, BuildError> {
        let cfg = self.load_config()?;
        Actuator::new(&cfg, self.model, self.rate_hz).map_err(BuildError::from)
    }

    /// Publish every `n`th tick.
    pub fn publish_every(&self) -> u64 {
        publish_every(self.rate_hz, self.publish_rate_hz)
    }

    /// Publish `/clock` every `n`th tick.
    pub fn clock_every(&self) -> u64 {
        publish_every(self.rate_hz, self.clock_rate_hz)
    }
}

/// Publish every `n`th tick for a tick rate and a publication rate (0 = every tick).
pub fn publish_every(rate_hz: f64, publish_rate_hz: f64) -> u64 {
    if publish_rate_hz <= 0.0 || publish_rate_hz >= rate_hz {
        1
    } else {
        (rate_hz / publish_rate_hz).round().max(1.0) as u64
    }
}
