//! The node's parameters (docs/ros-interface.md): their values ([`NodeParams`]); their names,
//! defaults, types and checks are declared once, in [`table::PARAMETERS`].

#[cfg(test)]
mod docs_table;
mod given;
pub mod table;

pub use given::Given;
pub use table::{spec, OnChange, ParameterSpec, PARAMETERS};

use super::clock::ClockMode;
use crate::physics::model::ModelKind;
use crate::physics::params::EnergyModel;
use crate::sim::Actuator;
use crate::{config::ActuatorConfig, text::excerpt};
use ros2_client::ParameterValue;

/// The live view's port unless set: Foxglove's own default for a WebSocket connection
/// (`ws://localhost:8765`), so that a first-time user connects without looking it up.
pub const DEFAULT_FOXGLOVE_PORT: u16 = 8765;
/// Highest `real_time_factor` (beyond it, 0 = as fast as possible is the honest value).
pub const MAX_REAL_TIME_FACTOR: f64 = 1e6;

/// Upper bound on the tick rate (the simulation's).
pub use crate::sim::simulation::MAX_RATE_HZ;
/// Longest `model` value, characters (a model name).
pub const MAX_NAME_CHARS: usize = 64;
/// Longest `config` and `record_dir` values, bytes (PATH_MAX).
pub const MAX_PATH_BYTES: usize = 4096;

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

impl Default for NodeParams {
    /// Every parameter at its default ([`ParameterSpec::default`]).
    fn default() -> Self {
        // Placeholders, each replaced below by its parameter's default.
        let mut p = Self {
            model: ModelKind::DEFAULT,
            rate_hz: 0.0,
            publish_rate_hz: 0.0,
            config: String::new(),
            record: false,
            record_dir: String::new(),
            clock: ClockMode::Wall,
            real_time_factor: 0.0,
            clock_rate_hz: 0.0,
            joint_state_timeout_ticks: 0,
            energy_model: None,
            foxglove_port: 0,
        };
        for s in PARAMETERS {
            // Every default passes its own check (`table`'s tests); a failure is a bug there.
            if let Err(e) = p.set(s.name, &s.default.value(), false) {
                unreachable!("the default of parameter {} is invalid: {e}", s.name);
            }
        }
        p
    }
}

impl NodeParams {
    /// The value of parameter `name` as declared to ROS.
    pub fn value(&self, name: &str) -> Option<ParameterValue> {
        spec(name).map(|s| (s.get)(self))
    }

    /// Every parameter with its value, in [`PARAMETERS`]' order.
    pub fn values(&self) -> Vec<(&'static str, ParameterValue)> {
        PARAMETERS.iter().map(|s| (s.name, (s.get)(self))).collect()
    }

    /// Sets one parameter with the ROS value's own type (as the parameter services deliver it),
    /// checking its rules but not the whole (see [`NodeParams::build`]).
    /// `lenient` (start-up values from `-p` and files) also accepts an integer for a double.
    pub fn set(&mut self, name: &str, value: &ParameterValue, lenient: bool) -> Result<(), String> {
        let Some(spec) = spec(name) else {
            return Err(format!(
                "unknown parameter {:?} (known: {})",
                excerpt(name),
                table::names().join(", ")
            ));
        };
        (spec.set)(
            self,
            &Given {
                spec,
                value,
                lenient,
            },
        )
    }

    /// Loads the configuration these parameters name, with `energy_model` applied.
    pub fn load_config(&self) -> Result<ActuatorConfig, String> {
        let cfg = if self.config.is_empty() {
            ActuatorConfig::default()
        } else {
            ActuatorConfig::resolve(&self.config).map_err(|e| e.to_string())?
        };
        Ok(match self.energy_model {
            Some(m) => cfg.with_energy_model(m),
            None => cfg,
        })
    }

    /// Builds the actuator these parameters describe (checks the whole set).
    pub fn build(&self) -> Result<Actuator, String> {
        let cfg = self.load_config()?;
        Actuator::new(&cfg, self.model, self.rate_hz)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules() {
        let mut p = NodeParams::default();
        assert!(p
            .set("model", &ParameterValue::String("hill".into()), false)
            .is_ok());
        assert_eq!(p.model, ModelKind::HILL);
        let e = p
            .set("model", &ParameterValue::String("bogus".into()), false)
            .unwrap_err();
        assert!(e.contains("bogus"), "{e}");
        assert!(p
            .set("rate_hz", &ParameterValue::Double(0.0), false)
            .is_err());
        assert!(p
            .set("rate_hz", &ParameterValue::Double(-5.0), false)
            .is_err());
        assert!(p
            .set("rate_hz", &ParameterValue::Double(f64::NAN), false)
            .is_err());
        assert!(p
            .set("rate_hz", &ParameterValue::Integer(500), false)
            .is_err());
        assert!(p
            .set("rate_hz", &ParameterValue::Integer(500), true)
            .is_ok());
        assert_eq!(p.rate_hz, 500.0);
        assert!(p
            .set("publish_rate_hz", &ParameterValue::Double(-1.0), false)
            .is_err());
        assert!(p
            .set("record", &ParameterValue::String("yes".into()), false)
            .is_err());
        assert!(p
            .set("nope", &ParameterValue::Boolean(true), false)
            .is_err());
        assert_eq!(publish_every(1000.0, 0.0), 1);
        assert_eq!(publish_every(1000.0, 100.0), 10);
        assert_eq!(publish_every(1000.0, 2000.0), 1);
        assert_eq!(p.values().len(), PARAMETERS.len());
        assert_eq!(p.values().len(), 12);
        // foxglove_port: 0 (off) to 65535, integers only.
        assert!(p
            .set("foxglove_port", &ParameterValue::Integer(0), false)
            .is_ok());
        assert_eq!(p.foxglove_port, 0);
        assert!(p
            .set("foxglove_port", &ParameterValue::Integer(65536), false)
            .is_err());
        assert!(p
            .set("foxglove_port", &ParameterValue::Integer(-1), false)
            .is_err());
        assert!(p
            .set("foxglove_port", &ParameterValue::Double(8765.0), false)
            .is_err());
        // energy_model: a name overrides every muscle's, empty keeps the configuration's.
        let s = |v: &str| ParameterValue::String(v.into());
        assert!(p.set("energy_model", &s("bhargava"), false).is_ok());
        let cfg = p.load_config().unwrap();
        assert!(cfg
            .muscles
            .iter()
            .all(|m| m.params.energetics.energy_model == EnergyModel::Bhargava));
        let e = p.set("energy_model", &s("heat"), false).unwrap_err();
        assert!(e.contains("\"heat\"") && e.contains("umberger2010"), "{e}");
        assert_eq!(p.energy_model, Some(EnergyModel::Bhargava));
        assert_eq!(p.value("energy_model"), Some(s("bhargava")));
        assert!(p.set("energy_model", &s(""), false).is_ok());
        assert_eq!(p.energy_model, None);
        assert_eq!(p.value("energy_model"), Some(s("")));
        assert!(p
            .set(
                "joint_state_timeout_ticks",
                &ParameterValue::Integer(0),
                false
            )
            .is_err());
        assert!(p
            .set(
                "joint_state_timeout_ticks",
                &ParameterValue::Double(5.0),
                false
            )
            .is_err());
        assert!(p
            .set("clock", &ParameterValue::String("lockstep".into()), false)
            .is_ok());
        assert_eq!(p.clock, ClockMode::Lockstep);
        let e = p
            .set("clock", &ParameterValue::String("sundial".into()), false)
            .unwrap_err();
        assert!(
            e.contains("sundial") && e.contains("wall, sim, lockstep"),
            "{e}"
        );
        for bad in [-1.0, f64::NAN, 1e7] {
            assert!(p
                .set("real_time_factor", &ParameterValue::Double(bad), false)
                .is_err());
        }
        assert!(p
            .set("real_time_factor", &ParameterValue::Double(10.0), false)
            .is_ok());
        assert!(p
            .set("clock_rate_hz", &ParameterValue::Double(-1.0), false)
            .is_err());
    }

    /// Oversized strings are refused with an excerpt, never echoed whole (a parameter reply of
    /// 70 kB silences the parameter service for that client).
    #[test]
    fn long_strings_are_refused_briefly() {
        let mut p = NodeParams::default();
        for (name, len) in [
            ("model", 65),
            ("model", 70_000),
            ("config", 4097),
            ("record_dir", 120_000),
        ] {
            let e = p
                .set(name, &ParameterValue::String("m".repeat(len)), false)
                .unwrap_err();
            assert!(e.contains("too long") && e.len() < 200, "{name}: {e}");
        }
        assert!(p
            .set("config", &ParameterValue::String("c".repeat(4096)), false)
            .is_ok());
        // The excerpt plus the list of the parameters' names.
        let e = p
            .set(&"n".repeat(10_000), &ParameterValue::Boolean(true), false)
            .unwrap_err();
        assert!(e.len() < 100 + table::names().join(", ").len(), "{e}");
        let e = p
            .set("record", &ParameterValue::String("y".repeat(10_000)), false)
            .unwrap_err();
        assert!(e.len() < 200, "{e}");
    }

    #[test]
    fn missing_config_file_is_an_error() {
        let mut p = NodeParams::default();
        p.set(
            "config",
            &ParameterValue::String("/nonexistent/x.toml".into()),
            false,
        )
        .unwrap();
        let e = p.load_config().unwrap_err();
        assert!(e.contains("/nonexistent/x.toml"), "{e}");
    }
}
