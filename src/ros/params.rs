//! The node's parameters (docs/ros-interface.md): their defaults, types and validation.

use super::clock::ClockMode;
use crate::physics::models::ModelKind;
use crate::physics::params::EnergyModel;
use crate::sim::Actuator;
use crate::{config::ActuatorConfig, text::excerpt};
use ros2_client::ParameterValue;

/// Parameter names.
pub const MODEL: &str = "model";
pub const RATE_HZ: &str = "rate_hz";
pub const PUBLISH_RATE_HZ: &str = "publish_rate_hz";
pub const CONFIG: &str = "config";
pub const RECORD: &str = "record";
pub const RECORD_DIR: &str = "record_dir";
pub const CLOCK: &str = "clock";
pub const REAL_TIME_FACTOR: &str = "real_time_factor";
pub const CLOCK_RATE_HZ: &str = "clock_rate_hz";
pub const JOINT_STATE_TIMEOUT_TICKS: &str = "joint_state_timeout_ticks";
pub const ENERGY_MODEL: &str = "energy_model";
pub const FOXGLOVE_PORT: &str = "foxglove_port";
/// All of them, in the order they are declared.
pub const ALL: [&str; 12] = [
    MODEL,
    RATE_HZ,
    PUBLISH_RATE_HZ,
    CONFIG,
    RECORD,
    RECORD_DIR,
    CLOCK,
    REAL_TIME_FACTOR,
    CLOCK_RATE_HZ,
    JOINT_STATE_TIMEOUT_TICKS,
    ENERGY_MODEL,
    FOXGLOVE_PORT,
];
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
    fn default() -> Self {
        Self {
            model: ModelKind::DEFAULT,
            rate_hz: 1000.0,
            publish_rate_hz: 0.0,
            config: String::new(),
            record: true,
            record_dir: "runs".into(),
            clock: ClockMode::Wall,
            real_time_factor: 0.0,
            clock_rate_hz: 100.0,
            joint_state_timeout_ticks: 100,
            energy_model: None,
            foxglove_port: DEFAULT_FOXGLOVE_PORT,
        }
    }
}

impl NodeParams {
    /// The value of parameter `name` as declared to ROS.
    pub fn value(&self, name: &str) -> Option<ParameterValue> {
        Some(match name {
            MODEL => ParameterValue::String(self.model.name().into()),
            RATE_HZ => ParameterValue::Double(self.rate_hz),
            PUBLISH_RATE_HZ => ParameterValue::Double(self.publish_rate_hz),
            CONFIG => ParameterValue::String(self.config.clone()),
            RECORD => ParameterValue::Boolean(self.record),
            RECORD_DIR => ParameterValue::String(self.record_dir.clone()),
            CLOCK => ParameterValue::String(self.clock.name().into()),
            REAL_TIME_FACTOR => ParameterValue::Double(self.real_time_factor),
            CLOCK_RATE_HZ => ParameterValue::Double(self.clock_rate_hz),
            JOINT_STATE_TIMEOUT_TICKS => ParameterValue::Integer(self.joint_state_timeout_ticks),
            ENERGY_MODEL => ParameterValue::String(
                self.energy_model
                    .map(|m| m.name().to_string())
                    .unwrap_or_default(),
            ),
            FOXGLOVE_PORT => ParameterValue::Integer(i64::from(self.foxglove_port)),
            _ => return None,
        })
    }

    /// Every parameter with its value.
    pub fn values(&self) -> Vec<(&'static str, ParameterValue)> {
        ALL.iter()
            .filter_map(|n| self.value(n).map(|v| (*n, v)))
            .collect()
    }

    /// Sets one parameter with the ROS value's own type (as the parameter services deliver it),
    /// checking its rules but not the whole (see [`NodeParams::build`]).
    /// `lenient` (start-up values from `-p` and files) also accepts an integer for a double.
    pub fn set(&mut self, name: &str, value: &ParameterValue, lenient: bool) -> Result<(), String> {
        let as_f64 = |v: &ParameterValue| double(name, v, lenient);
        let as_string = |v: &ParameterValue| string(name, v);
        match name {
            MODEL => {
                let s = as_string(value)?;
                self.model = s.parse::<ModelKind>().map_err(|e| e.to_string())?;
            }
            RATE_HZ => {
                let r = as_f64(value)?;
                if !(r.is_finite() && r > 0.0 && r <= MAX_RATE_HZ) {
                    return Err(format!(
                        "rate_hz = {r} is invalid: must be a finite number > 0 and <= {MAX_RATE_HZ}"
                    ));
                }
                self.rate_hz = r;
            }
            PUBLISH_RATE_HZ => {
                let r = as_f64(value)?;
                if !(r.is_finite() && r >= 0.0) {
                    return Err(format!(
                        "publish_rate_hz = {r} is invalid: must be finite and >= 0 \
                         (0 = publish every tick)"
                    ));
                }
                self.publish_rate_hz = r;
            }
            CONFIG => self.config = as_string(value)?,
            RECORD => match value {
                ParameterValue::Boolean(b) => self.record = *b,
                other => {
                    return Err(format!(
                        "parameter \"record\" must be a bool, got {}",
                        describe(other)
                    ))
                }
            },
            // Empty disables recording, as `record: false` does.
            RECORD_DIR => self.record_dir = as_string(value)?,
            CLOCK => self.clock = as_string(value)?.parse()?,
            REAL_TIME_FACTOR => {
                let f = as_f64(value)?;
                if !(f.is_finite() && (0.0..=MAX_REAL_TIME_FACTOR).contains(&f)) {
                    return Err(format!(
                        "real_time_factor = {f} is invalid: must be from 0 (as fast as possible) \
                         to {MAX_REAL_TIME_FACTOR}"
                    ));
                }
                self.real_time_factor = f;
            }
            CLOCK_RATE_HZ => {
                let r = as_f64(value)?;
                if !(r.is_finite() && r >= 0.0) {
                    return Err(format!(
                        "clock_rate_hz = {r} is invalid: must be finite and >= 0 (0 = every tick)"
                    ));
                }
                self.clock_rate_hz = r;
            }
            JOINT_STATE_TIMEOUT_TICKS => match value {
                ParameterValue::Integer(n) if *n >= 1 => self.joint_state_timeout_ticks = *n,
                other => {
                    return Err(format!(
                        "parameter \"joint_state_timeout_ticks\" must be an integer >= 1, got {}",
                        describe(other)
                    ))
                }
            },
            ENERGY_MODEL => {
                let s = as_string(value)?;
                self.energy_model = if s.is_empty() {
                    None
                } else {
                    Some(s.parse::<EnergyModel>().map_err(|e| {
                        format!("{e} (or empty: each muscle's from the configuration)")
                    })?)
                };
            }
            FOXGLOVE_PORT => match value {
                ParameterValue::Integer(n) if (0..=i64::from(u16::MAX)).contains(n) => {
                    self.foxglove_port = *n as u16
                }
                other => {
                    return Err(format!(
                        "parameter \"foxglove_port\" must be an integer from 0 (off) to {}, \
                         got {}",
                        u16::MAX,
                        describe(other)
                    ))
                }
            },
            other => {
                return Err(format!(
                    "unknown parameter {:?} (known: {})",
                    excerpt(other),
                    ALL.join(", ")
                ))
            }
        }
        Ok(())
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

/// A double parameter's value; `lenient` also accepts an integer.
fn double(name: &str, v: &ParameterValue, lenient: bool) -> Result<f64, String> {
    match v {
        ParameterValue::Double(d) => Ok(*d),
        ParameterValue::Integer(i) if lenient => Ok(*i as f64),
        other => Err(format!(
            "parameter {name:?} must be a double (e.g. 1000.0), got {}",
            describe(other)
        )),
    }
}

/// A string parameter's value: a name ([`MODEL`], [`CLOCK`]) of at most [`MAX_NAME_CHARS`]
/// characters, a path of at most [`MAX_PATH_BYTES`] bytes.
fn string(name: &str, v: &ParameterValue) -> Result<String, String> {
    match v {
        ParameterValue::String(s) => {
            let (limit, too_long) = if name == MODEL || name == CLOCK || name == ENERGY_MODEL {
                ("64 characters", s.chars().count() > MAX_NAME_CHARS)
            } else {
                ("4096 bytes", s.len() > MAX_PATH_BYTES)
            };
            if too_long {
                return Err(format!(
                    "parameter {name:?} is too long ({} bytes, at most {limit}): {}",
                    s.len(),
                    excerpt(s)
                ));
            }
            Ok(s.clone())
        }
        other => Err(format!(
            "parameter {name:?} must be a string, got {}",
            describe(other)
        )),
    }
}

fn describe(v: &ParameterValue) -> String {
    match v {
        ParameterValue::NotSet => "nothing (not set)".into(),
        ParameterValue::Boolean(b) => format!("bool {b}"),
        ParameterValue::Integer(i) => format!("integer {i}"),
        ParameterValue::Double(d) => format!("double {d}"),
        ParameterValue::String(s) => format!("string {:?}", excerpt(s)),
        other => excerpt(&format!("{other:?}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules() {
        let mut p = NodeParams::default();
        assert!(p
            .set(MODEL, &ParameterValue::String("hill".into()), false)
            .is_ok());
        assert_eq!(p.model, ModelKind::HILL);
        let e = p
            .set(MODEL, &ParameterValue::String("bogus".into()), false)
            .unwrap_err();
        assert!(e.contains("bogus"), "{e}");
        assert!(p.set(RATE_HZ, &ParameterValue::Double(0.0), false).is_err());
        assert!(p
            .set(RATE_HZ, &ParameterValue::Double(-5.0), false)
            .is_err());
        assert!(p
            .set(RATE_HZ, &ParameterValue::Double(f64::NAN), false)
            .is_err());
        assert!(p
            .set(RATE_HZ, &ParameterValue::Integer(500), false)
            .is_err());
        assert!(p.set(RATE_HZ, &ParameterValue::Integer(500), true).is_ok());
        assert_eq!(p.rate_hz, 500.0);
        assert!(p
            .set(PUBLISH_RATE_HZ, &ParameterValue::Double(-1.0), false)
            .is_err());
        assert!(p
            .set(RECORD, &ParameterValue::String("yes".into()), false)
            .is_err());
        assert!(p
            .set("nope", &ParameterValue::Boolean(true), false)
            .is_err());
        assert_eq!(publish_every(1000.0, 0.0), 1);
        assert_eq!(publish_every(1000.0, 100.0), 10);
        assert_eq!(publish_every(1000.0, 2000.0), 1);
        assert_eq!(p.values().len(), ALL.len());
        assert_eq!(p.values().len(), 12);
        // foxglove_port: 0 (off) to 65535, integers only.
        assert!(p
            .set(FOXGLOVE_PORT, &ParameterValue::Integer(0), false)
            .is_ok());
        assert_eq!(p.foxglove_port, 0);
        assert!(p
            .set(FOXGLOVE_PORT, &ParameterValue::Integer(65536), false)
            .is_err());
        assert!(p
            .set(FOXGLOVE_PORT, &ParameterValue::Integer(-1), false)
            .is_err());
        assert!(p
            .set(FOXGLOVE_PORT, &ParameterValue::Double(8765.0), false)
            .is_err());
        // energy_model: a name overrides every muscle's, empty keeps the configuration's.
        let s = |v: &str| ParameterValue::String(v.into());
        assert!(p.set(ENERGY_MODEL, &s("bhargava"), false).is_ok());
        let cfg = p.load_config().unwrap();
        assert!(cfg
            .muscles
            .iter()
            .all(|m| m.params.energetics.energy_model == EnergyModel::Bhargava));
        let e = p.set(ENERGY_MODEL, &s("heat"), false).unwrap_err();
        assert!(e.contains("\"heat\"") && e.contains("umberger2010"), "{e}");
        assert_eq!(p.energy_model, Some(EnergyModel::Bhargava));
        assert_eq!(p.value(ENERGY_MODEL), Some(s("bhargava")));
        assert!(p.set(ENERGY_MODEL, &s(""), false).is_ok());
        assert_eq!(p.energy_model, None);
        assert_eq!(p.value(ENERGY_MODEL), Some(s("")));
        assert!(p
            .set(
                JOINT_STATE_TIMEOUT_TICKS,
                &ParameterValue::Integer(0),
                false
            )
            .is_err());
        assert!(p
            .set(
                JOINT_STATE_TIMEOUT_TICKS,
                &ParameterValue::Double(5.0),
                false
            )
            .is_err());
        assert!(p
            .set(CLOCK, &ParameterValue::String("lockstep".into()), false)
            .is_ok());
        assert_eq!(p.clock, ClockMode::Lockstep);
        let e = p
            .set(CLOCK, &ParameterValue::String("sundial".into()), false)
            .unwrap_err();
        assert!(
            e.contains("sundial") && e.contains("wall, sim, lockstep"),
            "{e}"
        );
        for bad in [-1.0, f64::NAN, 1e7] {
            assert!(p
                .set(REAL_TIME_FACTOR, &ParameterValue::Double(bad), false)
                .is_err());
        }
        assert!(p
            .set(REAL_TIME_FACTOR, &ParameterValue::Double(10.0), false)
            .is_ok());
        assert!(p
            .set(CLOCK_RATE_HZ, &ParameterValue::Double(-1.0), false)
            .is_err());
    }

    /// Oversized strings are refused with an excerpt, never echoed whole (a parameter reply of
    /// 70 kB silences the parameter service for that client).
    #[test]
    fn long_strings_are_refused_briefly() {
        let mut p = NodeParams::default();
        for (name, len) in [
            (MODEL, 65),
            (MODEL, 70_000),
            (CONFIG, 4097),
            (RECORD_DIR, 120_000),
        ] {
            let e = p
                .set(name, &ParameterValue::String("m".repeat(len)), false)
                .unwrap_err();
            assert!(e.contains("too long") && e.len() < 200, "{name}: {e}");
        }
        assert!(p
            .set(CONFIG, &ParameterValue::String("c".repeat(4096)), false)
            .is_ok());
        // The excerpt plus the list of the parameters' names.
        let e = p
            .set(&"n".repeat(10_000), &ParameterValue::Boolean(true), false)
            .unwrap_err();
        assert!(e.len() < 100 + ALL.join(", ").len(), "{e}");
        let e = p
            .set(RECORD, &ParameterValue::String("y".repeat(10_000)), false)
            .unwrap_err();
        assert!(e.len() < 200, "{e}");
    }

    #[test]
    fn missing_config_file_is_an_error() {
        let mut p = NodeParams::default();
        p.set(
            CONFIG,
            &ParameterValue::String("/nonexistent/x.toml".into()),
            false,
        )
        .unwrap();
        let e = p.load_config().unwrap_err();
        assert!(e.contains("/nonexistent/x.toml"), "{e}");
    }
}
