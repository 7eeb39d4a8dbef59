//! The actuator configuration file (TOML): muscles and joint, each parameter overridable.
//!
//! ```toml
//! [joint]
//! name = "elbow"
//! radius = 0.03
//!
//! [[muscle]]
//! name = "flexor"          # the agonist: pulls towards positive joint angles
//! f_max = 4000.0
//!
//! [[muscle]]
//! name = "extensor"        # the antagonist
//! [muscle.crossbridge]
//! pde_cells = 400
//! ```
//! Anything left out keeps its embedded default (Table 1 of the paper, MODEL.md §1).

use crate::physics::params::{JointParams, MuscleParams, ParamError};
use crate::physics::plant::Attachment;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One muscle of the actuator: its name and parameters.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MuscleConfig {
    /// Name used in commands and published states.
    pub name: String,
    /// Model parameters (everything not given takes its Table 1 default).
    #[serde(flatten)]
    pub params: MuscleParams,
}

/// The antagonistic actuator: one joint, the agonist (first muscle) and the antagonist (second).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ActuatorConfig {
    /// The joint.
    pub joint: JointParams,
    /// Exactly two muscles: agonist (flexor, positive direction), then antagonist.
    #[serde(rename = "muscle")]
    pub muscles: Vec<MuscleConfig>,
}

/// The file's form before the muscle tables are split into name and parameters (serde cannot
/// combine `flatten` with `deny_unknown_fields`, and a misspelt parameter must be an error).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    #[serde(default)]
    joint: JointParams,
    muscle: Option<Vec<toml::Table>>,
}

fn default_muscles() -> Vec<MuscleConfig> {
    ["flexor", "extensor"]
        .into_iter()
        .map(|n| MuscleConfig {
            name: n.into(),
            params: MuscleParams::default(),
        })
        .collect()
}

impl Default for ActuatorConfig {
    fn default() -> Self {
        Self {
            joint: JointParams::default(),
            muscles: default_muscles(),
        }
    }
}

/// Why a configuration could not be used.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// The file could not be read.
    #[error("cannot read configuration file {path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    /// The file is not valid TOML for this schema.
    #[error("configuration file {path}: {message}")]
    Parse { path: String, message: String },
    /// One or more parameters break their rules.
    #[error("{}", .0.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("\n"))]
    Invalid(Vec<ParamError>),
}

/// Extra length of both paths over lopt + l_ts at θ = 0 (MODEL.md §8 default geometry), m.
pub const DEFAULT_PATH_PRESTRETCH: f64 = 0.002;

impl ActuatorConfig {
    /// The muscles' parameters, agonist first.
    pub fn muscle_params(&self) -> Vec<MuscleParams> {
        self.muscles.iter().map(|m| m.params.clone()).collect()
    }

    /// The joint attachment of the two muscles: the configured path length, or
    /// lopt + l_ts + 2 mm of the agonist.
    pub fn joint_attachment(&self) -> Attachment {
        let path_length = self.joint.path_length.unwrap_or_else(|| {
            let p = &self.muscles[0].params;
            p.l_opt + p.l_ts + DEFAULT_PATH_PRESTRETCH
        });
        Attachment::Joint {
            params: self.joint.clone(),
            path_length,
        }
    }

    /// Reads and validates a TOML configuration file.
    pub fn from_file(path: &Path) -> Result<Self, ConfigError> {
        let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Io {
            path: path.display().to_string(),
            source,
        })?;
        Self::from_toml_str(&text).map_err(|e| match e {
            ConfigError::Parse { message, .. } => ConfigError::Parse {
                path: path.display().to_string(),
                message,
            },
            other => other,
        })
    }

    /// Parses and validates TOML text.
    pub fn from_toml_str(text: &str) -> Result<Self, ConfigError> {
        let parse_err = |message: String| ConfigError::Parse {
            path: "<text>".into(),
            message,
        };
        let raw: RawConfig =
            toml::from_str(text).map_err(|e| parse_err(e.to_string().trim().replace('\n', " ")))?;
        let muscles = match raw.muscle {
            None => default_muscles(),
            Some(tables) => tables
                .into_iter()
                .enumerate()
                .map(|(i, mut table)| {
                    let name = match table.remove("name") {
                        Some(toml::Value::String(s)) => s,
                        Some(other) => {
                            return Err(parse_err(format!(
                                "muscle[{i}].name must be a string, found {other}"
                            )))
                        }
                        None => return Err(parse_err(format!("muscle[{i}] has no name"))),
                    };
                    let params =
                        MuscleParams::deserialize(toml::Value::Table(table)).map_err(|e| {
                            parse_err(format!("muscle {name:?}: {}", e.to_string().trim()))
                        })?;
                    Ok(MuscleConfig { name, params })
                })
                .collect::<Result<Vec<_>, _>>()?,
        };
        let cfg = ActuatorConfig {
            joint: raw.joint,
            muscles,
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// All rule violations, one error each; `Ok` when the configuration is usable.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let mut errors = Vec::new();
        self.joint.validate(&mut errors);
        if self.muscles.len() != 2 {
            errors.push(ParamError {
                parameter: "muscle".into(),
                value: format!("{} entries", self.muscles.len()),
                rule: "the antagonistic actuator needs exactly two muscles (agonist, antagonist)",
            });
        }
        for (i, m) in self.muscles.iter().enumerate() {
            if m.name.trim().is_empty() {
                errors.push(ParamError {
                    parameter: format!("muscle[{i}].name"),
                    value: "\"\"".into(),
                    rule: "must not be empty",
                });
            }
            if self.muscles[..i].iter().any(|o| o.name == m.name) {
                errors.push(ParamError {
                    parameter: format!("muscle[{i}].name"),
                    value: format!("{:?}", m.name),
                    rule: "must be unique",
                });
            }
            m.params
                .validate(&format!("muscle.{}.", m.name), &mut errors);
        }
        if errors.is_empty() {
            Ok(())
        } else {
            Err(ConfigError::Invalid(errors))
        }
    }

    /// Warnings that do not stop the program (a configured l_tc that breaks continuity).
    pub fn warnings(&self) -> Vec<String> {
        self.muscles
            .iter()
            .filter_map(|m| m.params.continuity_warning(&format!("muscle.{}.", m.name)))
            .collect()
    }
}
