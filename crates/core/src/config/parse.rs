//! Reading a configuration: a built-in one by name, a file, or TOML text, in either form (joints
//! and muscles with spans, or the antagonistic pair of [`super::pair`]); the result is validated.

use super::pair::{pair_config, single_joint, PairJoint};
use super::schema::{ActuatorConfig, MuscleConfig, SpanConfig};
use super::stepper::StepperConfig;
use super::unknown_key;
use super::{ConfigError, ParseError};
use crate::files::{read_regular_file, MAX_FILE_BYTES};
use crate::physics::limb_params::{JointParams, MuscleParams};
use crate::text::toml_error;
use serde::Deserialize;
use std::path::Path;

/// Built-in configurations: (name, TOML text). `elbow` is the embedded default.
pub const BUILT_IN: &[(&str, &str)] = &[
    ("elbow", include_str!("../../configs/elbow.toml")),
    ("arm", include_str!("../../configs/arm.toml")),
];

impl ActuatorConfig {
    /// A built-in configuration by name, else a file path.
    pub fn resolve(name_or_path: &str) -> Result<Self, ConfigError> {
        match BUILT_IN.iter().find(|(n, _)| *n == name_or_path) {
            Some((name, text)) => Self::from_toml_str(text).map_err(|e| match e {
                ConfigError::Parse { error, .. } => ConfigError::Parse {
                    path: format!("<built-in {name}>"),
                    error,
                },
                other => other,
            }),
            None => Self::from_file(Path::new(name_or_path)),
        }
    }

    /// Names of the built-in configurations.
    pub(crate) fn built_in_names() -> String {
        BUILT_IN
            .iter()
            .map(|(n, _)| *n)
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Reads and validates a TOML configuration file (a regular file of at most 1 MiB).
    pub fn from_file(path: &Path) -> Result<Self, ConfigError> {
        let shown = path
            .display()
            .to_string()
            .chars()
            .take(200)
            .collect::<String>();
        let io = |reason: String, kind| ConfigError::Io {
            path: shown.clone(),
            reason,
            kind,
        };
        let bytes = read_regular_file(path, MAX_FILE_BYTES).map_err(|e| {
            let reason = if e.kind() == std::io::ErrorKind::NotFound {
                format!("{e} (built-in configurations: {})", Self::built_in_names())
            } else {
                e.to_string()
            };
            io(reason, e.kind())
        })?;
        let text = String::from_utf8(bytes)
            .map_err(|e| io(e.to_string(), std::io::ErrorKind::InvalidData))?;
        Self::from_toml_str(&text).map_err(|e| match e {
            ConfigError::Parse { error, .. } => ConfigError::Parse {
                path: shown.clone(),
                error,
            },
            other => other,
        })
    }

    /// Parses and validates TOML text.
    pub fn from_toml_str(text: &str) -> Result<Self, ConfigError> {
        Self::parse_toml(text, Some(text))
    }

    /// As [`ActuatorConfig::from_toml_str`] for text the program wrote (overrides applied): its
    /// errors name no line, which the user never saw.
    pub(crate) fn from_written_toml(text: &str) -> Result<Self, ConfigError> {
        Self::parse_toml(text, None)
    }

    /// `text` parsed; `lines`: the user's text, whose lines errors name.
    fn parse_toml(text: &str, lines: Option<&str>) -> Result<Self, ConfigError> {
        let parse_err = |error: ParseError| ConfigError::Parse {
            path: "<text>".into(),
            error,
        };
        let mut raw: toml::Table =
            toml::from_str(text).map_err(|e| parse_err(ParseError::Toml(toml_error(&e, text))))?;
        if let Some(k) = raw
            .keys()
            .find(|k| !["joint", "muscle", "stepper"].contains(&k.as_str()))
        {
            return Err(parse_err(ParseError::UnknownKey(k.clone())));
        }
        let stepper = match raw.remove("stepper") {
            None => StepperConfig::default(),
            Some(v) => StepperConfig::deserialize(v).map_err(|e| {
                parse_err(ParseError::Stepper {
                    reason: unknown_key::reason(e.to_string().trim(), lines, None),
                })
            })?,
        };
        let muscles = muscles_from(raw.remove("muscle"), lines).map_err(parse_err)?;
        let joints = match raw.remove("joint") {
            Some(toml::Value::Array(a)) => a
                .into_iter()
                .enumerate()
                .map(|(i, v)| {
                    JointParams::deserialize(v).map_err(|e| {
                        parse_err(ParseError::Joint {
                            index: i,
                            reason: unknown_key::reason(e.to_string().trim(), lines, None),
                        })
                    })
                })
                .collect::<Result<Vec<_>, _>>()?,
            pair => {
                // One `[joint]` table (or none): the antagonistic-pair form when the muscles
                // have no spans.
                let pair = match pair {
                    None => None,
                    Some(toml::Value::Table(t)) => {
                        Some(PairJoint::from_table(t).map_err(parse_err)?)
                    }
                    Some(_) => return Err(parse_err(ParseError::JointNotATable)),
                };
                if muscles.is_empty() || muscles.iter().all(|m| m.spans.is_empty()) {
                    let mut cfg = pair_config(pair, muscles)?;
                    if !stepper.is_empty() {
                        cfg.stepper = stepper;
                        cfg.validate()?;
                    }
                    return Ok(cfg);
                }
                single_joint(pair).map_err(parse_err)?
            }
        };
        let cfg = ActuatorConfig {
            joints,
            muscles,
            stepper,
        };
        cfg.validate()?;
        Ok(cfg)
    }
}

/// The `[[muscle]]` tables, in order (none when the key is absent).
fn muscles_from(
    value: Option<toml::Value>,
    lines: Option<&str>,
) -> Result<Vec<MuscleConfig>, ParseError> {
    let tables = match value {
        None => return Ok(Vec::new()),
        Some(toml::Value::Array(a)) => a
            .into_iter()
            .enumerate()
            .map(|(i, v)| match v {
                toml::Value::Table(t) => Ok(t),
                _ => Err(ParseError::MuscleNotATable { index: i }),
            })
            .collect::<Result<Vec<_>, _>>()?,
        Some(_) => return Err(ParseError::MusclesNotAnArray),
    };
    tables
        .into_iter()
        .enumerate()
        .map(|(i, t)| muscle_from_table(i, t, lines))
        .collect()
}

/// The `i`-th `[[muscle]]` table (of the user's text `lines`, if given).
fn muscle_from_table(
    i: usize,
    mut table: toml::Table,
    lines: Option<&str>,
) -> Result<MuscleConfig, ParseError> {
    let name = match table.remove("name") {
        Some(toml::Value::String(s)) => s,
        Some(other) => {
            return Err(ParseError::MuscleNameNotAString {
                index: i,
                found: other.to_string(),
            })
        }
        None => return Err(ParseError::MuscleWithoutName { index: i }),
    };
    let value = |key, e: toml::de::Error| ParseError::MuscleValue {
        muscle: name.clone(),
        key,
        reason: unknown_key::reason(e.to_string().trim(), lines, Some(i)),
    };
    let path_length = match table.remove("path_length") {
        None => None,
        Some(v) => Some(f64::deserialize(v).map_err(|e| value(Some("path_length"), e))?),
    };
    let spans = match table.remove("span") {
        None => Vec::new(),
        Some(v) => Vec::<SpanConfig>::deserialize(v).map_err(|e| value(Some("span"), e))?,
    };
    let params =
        MuscleParams::deserialize(toml::Value::Table(table)).map_err(|e| value(None, e))?;
    Ok(MuscleConfig {
        name,
        params,
        path_length,
        spans,
    })
}
