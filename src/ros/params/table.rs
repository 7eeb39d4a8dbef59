//! The node's parameters, each declared once: name, type, default, how a value is checked and
//! stored, what a change does, and a one-line description. `node --help`, the start-up values
//! (`-p`, `--params-file`), the parameter services (declared in this order, checked and applied
//! by [`ParameterSpec::set`] and [`ParameterSpec::on_change`]), the live view (which reads the
//! parameter services' store) all read [`PARAMETERS`];
//! docs/ros-interface.md's parameters table is checked against it (`docs_table`).
//!
//! Adding a parameter: a field of [`NodeParams`] and one entry here (its row in
//! docs/ros-interface.md follows; the test says what to write).

use super::error::ParameterError;
use super::given::{Given, Kind};
use super::limits::{DEFAULT_FOXGLOVE_PORT, MAX_RATE_HZ, MAX_REAL_TIME_FACTOR};
use super::node_params::NodeParams;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::EnergyModel;
use ros2_client::ParameterValue;

/// A default value (a constant, unlike [`ParameterValue`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DefaultValue {
    Bool(bool),
    Integer(i64),
    Double(f64),
    Str(&'static str),
}

impl DefaultValue {
    pub fn value(self) -> ParameterValue {
        match self {
            DefaultValue::Bool(b) => ParameterValue::Boolean(b),
            DefaultValue::Integer(i) => ParameterValue::Integer(i),
            DefaultValue::Double(d) => ParameterValue::Double(d),
            DefaultValue::Str(s) => ParameterValue::String(s.into()),
        }
    }

    /// As docs/ros-interface.md and `node --help` write it: strings in backticks (`""` when
    /// empty, in `node --help` too), numbers as Rust prints them (`1000.0`).
    pub fn text(self, backticks: bool) -> String {
        match self {
            DefaultValue::Bool(b) => b.to_string(),
            DefaultValue::Integer(i) => i.to_string(),
            DefaultValue::Double(d) => format!("{d:?}"),
            DefaultValue::Str("") if backticks => "`\"\"`".into(),
            DefaultValue::Str("") => "\"\"".into(),
            DefaultValue::Str(s) if backticks => format!("`{s}`"),
            DefaultValue::Str(s) => s.into(),
        }
    }
}

/// What an accepted change at run time does (param_callbacks.rs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OnChange {
    /// Checked by building the actuator it gives, then the tick loop gets it.
    Rebuild,
    /// The tick loop's publication interval.
    PublishEvery,
    /// The tick loop's pacing (`clock` sim).
    RealTimeFactor,
    /// The tick loop's `/clock` interval.
    ClockEvery,
    /// Read at the next start (stored only).
    NextStart,
    /// Fixed at start-up: a change is refused with the reason.
    Refused,
}

/// One parameter.
pub struct ParameterSpec {
    pub name: &'static str,
    pub kind: Kind,
    pub default: DefaultValue,
    pub on_change: OnChange,
    /// One line: what it means (units, what 0 or "" mean); `node --help` shows it.
    pub description: &'static str,
    /// The values it takes, when a list, as `node --help` says it ("one of a|b").
    pub choices: Option<fn() -> String>,
    /// Its value in `p`.
    pub get: fn(&NodeParams) -> ParameterValue,
    /// Checks `g`'s value and stores it in `p`, or says why not (one line).
    pub set: fn(&mut NodeParams, &Given) -> Result<(), ParameterError>,
}

/// Every parameter, in the order they are declared.
pub const PARAMETERS: &[ParameterSpec] = &[
    ParameterSpec {
        name: "model",
        kind: Kind::Name,
        default: DefaultValue::Str("huxley"),
        on_change: OnChange::Rebuild,
        description: "contractile model",
        choices: Some(|| format!("one of {}", ModelKind::names_joined("|", "|"))),
        get: |p| ParameterValue::String(p.model.name().into()),
        set: |p, g| {
            p.model = g.string()?.parse::<ModelKind>()?;
            Ok(())
        },
    },
    ParameterSpec {
        name: "rate_hz",
        kind: Kind::Double,
        default: DefaultValue::Double(1000.0),
        on_change: OnChange::Rebuild,
        description: "tick rate, Hz",
        choices: None,
        get: |p| ParameterValue::Double(p.rate_hz),
        set: |p, g| {
            let r = g.double()?;
            if !(r.is_finite() && r > 0.0 && r <= MAX_RATE_HZ) {
                return Err(ParameterError::RateHz(r));
            }
            p.rate_hz = r;
            Ok(())
        },
    },
    ParameterSpec {
        name: "publish_rate_hz",
        kind: Kind::Double,
        default: DefaultValue::Double(0.0),
        on_change: OnChange::PublishEvery,
        description: "~/state rate, Hz; 0 = every tick",
        choices: None,
        get: |p| ParameterValue::Double(p.publish_rate_hz),
        set: |p, g| {
            let r = g.double()?;
            if !(r.is_finite() && r >= 0.0) {
                return Err(ParameterError::PublishRateHz(r));
            }
            p.publish_rate_hz = r;
            Ok(())
        },
    },
    ParameterSpec {
        name: "config",
        kind: Kind::Path,
        default: DefaultValue::Str(""),
        on_change: OnChange::Rebuild,
        description: "the limb: a TOML file or built in, \"\" = elbow",
        choices: Some(|| {
            let names: Vec<&str> = muscle_actuator_core::config::BUILT_IN
                .iter()
                .map(|(n, _)| *n)
                .collect();
            format!("built in: {}", names.join("|"))
        }),
        get: |p| ParameterValue::String(p.config.clone()),
        set: |p, g| {
            p.config = g.string()?;
            Ok(())
        },
    },
    ParameterSpec {
        name: "record",
        kind: Kind::Bool,
        default: DefaultValue::Bool(true),
        on_change: OnChange::NextStart,
        description: "record the run to MCAP",
        choices: None,
        get: |p| ParameterValue::Boolean(p.record),
        set: |p, g| match g.value {
            ParameterValue::Boolean(b) => {
                p.record = *b;
                Ok(())
            }
            other => Err(ParameterError::NotBool {
                name: g.name,
                got: Given::describe(other),
            }),
        },
    },
    ParameterSpec {
        name: "record_dir",
        kind: Kind::Path,
        default: DefaultValue::Str("runs"),
        on_change: OnChange::NextStart,
        description: "directory of the recordings; \"\" = no recording",
        choices: None,
        get: |p| ParameterValue::String(p.record_dir.clone()),
        // Empty disables recording, as `record: false` does.
        set: |p, g| {
            p.record_dir = g.string()?;
            Ok(())
        },
    },
    ParameterSpec {
        name: "clock",
        kind: Kind::Name,
        default: DefaultValue::Str("wall"),
        on_change: OnChange::Refused,
        description: "how ticks are paced and stamped, fixed at start-up",
        choices: Some(|| format!("one of {}", crate::ros::clock::ClockMode::NAMES.join("|"))),
        get: |p| ParameterValue::String(p.clock.name().into()),
        set: |p, g| {
            p.clock = g.string()?.parse()?;
            Ok(())
        },
    },
    ParameterSpec {
        name: "real_time_factor",
        kind: Kind::Double,
        default: DefaultValue::Double(0.0),
        on_change: OnChange::RealTimeFactor,
        description: "clock sim: simulated s per wall s; 0 = as fast as it goes",
        choices: None,
        get: |p| ParameterValue::Double(p.real_time_factor),
        set: |p, g| {
            let f = g.double()?;
            if !(f.is_finite() && (0.0..=MAX_REAL_TIME_FACTOR).contains(&f)) {
                return Err(ParameterError::RealTimeFactor(f));
            }
            p.real_time_factor = f;
            Ok(())
        },
    },
    ParameterSpec {
        name: "clock_rate_hz",
        kind: Kind::Double,
        default: DefaultValue::Double(100.0),
        on_change: OnChange::ClockEvery,
        description: "/clock per simulated second; 0 = every tick",
        choices: None,
        get: |p| ParameterValue::Double(p.clock_rate_hz),
        set: |p, g| {
            let r = g.double()?;
            if !(r.is_finite() && r >= 0.0) {
                return Err(ParameterError::ClockRateHz(r));
            }
            p.clock_rate_hz = r;
            Ok(())
        },
    },
    ParameterSpec {
        name: "joint_state_timeout_ticks",
        kind: Kind::Integer,
        default: DefaultValue::Integer(100),
        on_change: OnChange::NextStart,
        description: "driven joints: ticks without a joint state before a warning",
        choices: None,
        get: |p| ParameterValue::Integer(p.joint_state_timeout_ticks),
        set: |p, g| match g.value {
            ParameterValue::Integer(n) if *n >= 1 => {
                p.joint_state_timeout_ticks = *n;
                Ok(())
            }
            other => Err(ParameterError::NotCount {
                name: g.name,
                got: Given::describe(other),
            }),
        },
    },
    ParameterSpec {
        name: "energy_model",
        kind: Kind::Name,
        default: DefaultValue::Str(""),
        on_change: OnChange::Rebuild,
        description: "every muscle's energy model, \"\" = the configuration's",
        choices: Some(|| format!("or one of {}", EnergyModel::ALL.map(|m| m.name()).join("|"))),
        get: |p| {
            ParameterValue::String(
                p.energy_model
                    .map(|m| m.name().to_string())
                    .unwrap_or_default(),
            )
        },
        set: |p, g| {
            let s = g.string()?;
            p.energy_model = if s.is_empty() {
                None
            } else {
                Some(
                    s.parse::<EnergyModel>()
                        .map_err(ParameterError::EnergyModel)?,
                )
            };
            Ok(())
        },
    },
    ParameterSpec {
        name: "foxglove_port",
        kind: Kind::Integer,
        default: DefaultValue::Integer(DEFAULT_FOXGLOVE_PORT as i64),
        on_change: OnChange::Refused,
        description: "the live view's TCP port; 0 = off; fixed at start-up",
        choices: None,
        get: |p| ParameterValue::Integer(i64::from(p.foxglove_port)),
        set: |p, g| match g.value {
            ParameterValue::Integer(n) if (0..=i64::from(u16::MAX)).contains(n) => {
                p.foxglove_port = *n as u16;
                Ok(())
            }
            other => Err(ParameterError::NotPort {
                name: g.name,
                got: Given::describe(other),
            }),
        },
    },
];

/// The standard ROS 2 parameter the node reads at start-up besides its own (setup.rs): with
/// `clock` wall, follow `/clock`.
pub const USE_SIM_TIME: &str = "use_sim_time";

/// The parameter named `name`.
pub fn spec(name: &str) -> Option<&'static ParameterSpec> {
    PARAMETERS.iter().find(|s| s.name == name)
}

/// Every parameter's name, in order.
pub fn names() -> Vec<&'static str> {
    PARAMETERS.iter().map(|s| s.name).collect()
}

/// `node --help`'s lines on the parameters: `name (description; choices; default D)` for each,
/// then `use_sim_time`, wrapped at `width` columns under `parameters: `.
pub fn usage(width: usize) -> String {
    let mut items: Vec<String> = PARAMETERS
        .iter()
        .map(|s| {
            let choices = s.choices.map(|c| format!("; {}", c())).unwrap_or_default();
            format!(
                "{} ({}{choices}; default {})",
                s.name,
                s.description,
                s.default.text(false)
            )
        })
        .collect();
    items.push(format!("{USE_SIM_TIME} (follow /clock; default false)"));
    let head = "parameters: ";
    let indent = " ".repeat(head.len());
    let mut out = String::from(head);
    let mut line_len = head.len();
    let text = items.join(", ");
    for (i, word) in text.split(' ').enumerate() {
        if i > 0 {
            if line_len + 1 + word.len() > width {
                out.push('\n');
                out.push_str(&indent);
                line_len = indent.len();
            } else {
                out.push(' ');
                line_len += 1;
            }
        }
        out.push_str(word);
        line_len += word.chars().count();
    }
    out
}
