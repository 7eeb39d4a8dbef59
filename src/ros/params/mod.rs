//! The node's parameters (docs/ros-interface.md): their values ([`NodeParams`]); their names,
//! defaults, types and checks are declared once, in [`table::PARAMETERS`].

#[cfg(test)]
mod docs_table;
mod error;
mod given;
mod limits;
mod node_params;
pub mod table;

pub use error::ParameterError;
pub use given::Given;
pub use node_params::{BuildError, NodeParams};
pub use table::{spec, OnChange, PARAMETERS};

use crate::ros::clock::ClockMode;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::text::excerpt;
use ros2_client::ParameterValue;

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
    #[cfg(test)]
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
    pub fn set(
        &mut self,
        name: &str,
        value: &ParameterValue,
        lenient: bool,
    ) -> Result<(), ParameterError> {
        let Some(spec) = spec(name) else {
            return Err(ParameterError::Unknown {
                name: excerpt(name),
                known: table::names().join(", "),
            });
        };
        (spec.set)(
            self,
            &Given {
                name: spec.name,
                kind: spec.kind,
                value,
                lenient,
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use muscle_actuator_core::physics::EnergyModel;

    #[test]
    fn rules() {
        let mut p = NodeParams::default();
        assert!(p
            .set("model", &ParameterValue::String("hill".into()), false)
            .is_ok());
        assert_eq!(p.model, ModelKind::HILL);
        let e = p
            .set("model", &ParameterValue::String("bogus".into()), false)
            .unwrap_err()
            .to_string();
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
        use super::node_params::publish_every;
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
        let e = p
            .set("energy_model", &s("heat"), false)
            .unwrap_err()
            .to_string();
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
            .unwrap_err()
            .to_string();
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
                .unwrap_err()
                .to_string();
            assert!(e.contains("too long") && e.len() < 200, "{name}: {e}");
        }
        assert!(p
            .set("config", &ParameterValue::String("c".repeat(4096)), false)
            .is_ok());
        // The excerpt plus the list of the parameters' names.
        let e = p
            .set(&"n".repeat(10_000), &ParameterValue::Boolean(true), false)
            .unwrap_err()
            .to_string();
        assert!(e.len() < 100 + table::names().join(", ").len(), "{e}");
        let e = p
            .set("record", &ParameterValue::String("y".repeat(10_000)), false)
            .unwrap_err()
            .to_string();
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
        let e = p.load_config().unwrap_err().to_string();
        assert!(e.contains("/nonexistent/x.toml"), "{e}");
    }
}
