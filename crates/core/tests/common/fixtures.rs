//! Small fixtures of the configuration and scenario tests.

use muscle_actuator_core::config::{ActuatorConfig, ConfigError};
use muscle_actuator_core::sim::{Scenario, Schedule, ScheduledInput, SetupKind, Signal};

/// The message a two-muscle configuration is refused with whose flexor has the TOML lines
/// `muscle_keys` (its tables, `[muscle.…]`, last); panics if it is accepted or refused for
/// anything but its values.
pub fn refusal(muscle_keys: &str) -> String {
    let text =
        format!("[[muscle]]\nname = \"flexor\"\n{muscle_keys}\n[[muscle]]\nname = \"extensor\"\n");
    match ActuatorConfig::from_toml_str(&text) {
        Ok(_) => panic!("accepted: {muscle_keys}"),
        Err(e @ (ConfigError::Invalid(_) | ConfigError::Parse { .. })) => e.to_string(),
        Err(other) => panic!("{muscle_keys}: unexpected {other}"),
    }
}

/// The first muscle clamped at `length` (m), its excitation held at `u`, for `seconds`.
pub fn clamped(u: f64, length: f64, seconds: f64) -> Scenario {
    Scenario {
        name: "isometric".into(),
        duration: seconds,
        attachment: SetupKind::Clamped,
        length: Some(length),
        initial_force: 0.0,
        inputs: vec![ScheduledInput {
            signal: Signal::Excitation,
            muscle: None,
            joint: None,
            schedule: Schedule::Constant { value: u },
        }],
    }
}
