//! Reading a configuration: a built-in one by name, a file, or TOML text, in either form (joints
//! and muscles with spans, or the antagonistic pair of [`super::pair`]); the result is validated.

use super::pair::{pair_config, single_joint, PairJoint};
use super::schema::{ActuatorConfig, MuscleConfig, SpanConfig};
use super::ConfigError;
use crate::files::{read_regular_file, MAX_FILE_BYTES};
use crate::physics::params::{JointParams, MuscleParams};
use crate::text::{excerpt, one_line, toml_error};
use serde::Deserialize;
use std::path::Path;

/// Built-in configurations: (name, TOML text). `elbow` is the embedded default.
pub const BUILT_IN: &[(&str, &str)] = &[
    ("elbow", include_str!("../../../../configs/elbow.toml")),
    ("arm", include_str!("../../../../configs/arm.toml")),
];

impl ActuatorConfig {
    /// A built-in configuration by name, else a file path.
    pub fn resolve(name_or_path: &str) -> Result<Self, ConfigError> {
        match BUILT_IN.iter().find(|(n, _)| *n == name_or_path) {
            Some((name, text)) => Self::from_toml_str(text).map_err(|e| match e {
                ConfigError::Parse { message, .. } => ConfigError::Parse {
                    path: format!("<built-in {name}>"),
                    message,
                },
                other => other,
            }),
            None => Self::from_file(Path::new(name_or_path)),
        }
    }

    /// Names of the built-in configurations.
    pub fn built_in_names() -> String {
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
        let io = |reason: String| ConfigError::Io {
            path: shown.clone(),
            reason,
        };
        let bytes = read_regular_file(path, MAX_FILE_BYTES).map_err(|e| {
            io(if e.kind() == std::io::ErrorKind::NotFound {
                format!("{e} (built-in configurations: {})", Self::built_in_names())
            } else {
                e.to_string()
            })
        })?;
        let text = String::from_utf8(bytes).map_err(|e| io(e.to_string()))?;
        Self::from_toml_str(&text).map_err(|e| match e {
            ConfigError::Parse { message, .. } => ConfigError::Parse {
                path: shown.clone(),
                message,
            },
            other => other,
        })
    }

    /// Parses and validates TOML text.
    pub fn from_toml_str(text: &str) -> Result<Self, ConfigError> {
        let parse_err = |message: String| ConfigError::Parse {
            path: "<text>".into(),
            message: one_line(&message),
        };
        let mut raw: toml::Table =
            toml::from_str(text).map_err(|e| parse_err(toml_error(&e, text)))?;
        if let Some(k) = raw.keys().find(|k| *k != "joint" && *k != "muscle") {
            return Err(parse_err(format!(
                "unknown key {:?}: expected `joint` and `muscle`",
                excerpt(k)
            )));
        }
        let muscles = muscles_from(raw.remove("muscle")).map_err(parse_err)?;
        let joints = match raw.remove("joint") {
            Some(toml::Value::Array(a)) => a
                .into_iter()
                .enumerate()
                .map(|(i, v)| {
                    JointParams::deserialize(v)
                        .map_err(|e| parse_err(format!("joint[{i}]: {}", e.to_string().trim())))
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
                    Some(_) => {
                        return Err(parse_err(
                            "`joint` must be a table or an array of tables".into(),
                        ))
                    }
                };
                if muscles.is_empty() || muscles.iter().all(|m| m.spans.is_empty()) {
                    return pair_config(pair, muscles);
                }
                single_joint(pair).map_err(parse_err)?
            }
        };
        let cfg = ActuatorConfig { joints, muscles };
        cfg.validate()?;
        Ok(cfg)
    }
}

/// The `[[muscle]]` tables, in order (none when the key is absent).
fn muscles_from(value: Option<toml::Value>) -> Result<Vec<MuscleConfig>, String> {
    let tables = match value {
        None => return Ok(Vec::new()),
        Some(toml::Value::Array(a)) => a
            .into_iter()
            .enumerate()
            .map(|(i, v)| match v {
                toml::Value::Table(t) => Ok(t),
                _ => Err(format!("muscle[{i}] must be a table")),
            })
            .collect::<Result<Vec<_>, _>>()?,
        Some(_) => return Err("`muscle` must be an array of tables ([[muscle]])".into()),
    };
    tables
        .into_iter()
        .enumerate()
        .map(|(i, t)| muscle_from_table(i, t))
        .collect()
}

fn muscle_from_table(i: usize, mut table: toml::Table) -> Result<MuscleConfig, String> {
    let name = match table.remove("name") {
        Some(toml::Value::String(s)) => s,
        Some(other) => {
            return Err(format!(
                "muscle[{i}].name must be a string, found {}",
                excerpt(&other.to_string())
            ))
        }
        None => return Err(format!("muscle[{i}] has no name")),
    };
    let shown = excerpt(&name);
    let path_length = match table.remove("path_length") {
        None => None,
        Some(v) => Some(
            f64::deserialize(v)
                .map_err(|e| format!("muscle {shown:?}: path_length: {}", e.to_string().trim()))?,
        ),
    };
    let spans = match table.remove("span") {
        None => Vec::new(),
        Some(v) => Vec::<SpanConfig>::deserialize(v)
            .map_err(|e| format!("muscle {shown:?}: span: {}", e.to_string().trim()))?,
    };
    let params = MuscleParams::deserialize(toml::Value::Table(table))
        .map_err(|e| format!("muscle {shown:?}: {}", e.to_string().trim()))?;
    Ok(MuscleConfig {
        name,
        params,
        path_length,
        spans,
    })
}
