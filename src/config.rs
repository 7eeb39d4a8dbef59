//! The actuator configuration (TOML): joints, and muscles that span them through moment arms
//! (README, "Configuration"). Every parameter can be overridden; anything left out keeps its
//! embedded default (Table 1 of the paper for muscles, docs/model.md §1 and §8).
//!
//! ```toml
//! [[joint]]
//! name = "elbow"
//! inertia = 0.06
//!
//! [[muscle]]
//! name = "flexor"
//! f_max = 4000.0
//! path_length = 0.4164          # m, with every spanned joint at 0 rad
//! [[muscle.span]]
//! joint = "elbow"
//! moment_arm = 0.03             # m; or [c0, c1, …], a polynomial in the joint angle
//! ```
//!
//! The antagonistic pair of earlier versions is still read: a single `[joint]` table with a
//! pulley `radius` (and optional common `path_length`), and two muscles without spans, the first
//! pulling towards positive angles; or one, which replaces the default muscle of its name.
//!
//! Built-in configurations by name: `elbow` (the default) and `arm` (after OpenSim's arm26).

use crate::physics::moment_arm::MomentArm;
use crate::physics::params::{JointParams, MuscleParams, ParamError};
use crate::physics::topology::{Anchor, MuscleSpec, Span, Topology};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Built-in configurations: (name, TOML text). `elbow` is the embedded default.
pub const BUILT_IN: &[(&str, &str)] = &[
    ("elbow", include_str!("../configs/elbow.toml")),
    ("arm", include_str!("../configs/arm.toml")),
];

/// A joint a muscle spans, by name, and its moment arm there.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpanConfig {
    /// The joint's name.
    pub joint: String,
    /// r(θ), m: a constant, or polynomial coefficients `[c0, c1, …]` (m, m/rad, …).
    pub moment_arm: MomentArm,
    /// A polynomial arm may change sign inside the joint's range only when this says so (a
    /// muscle whose line of action crosses the joint's axis).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub changes_sign: bool,
}

/// One muscle: its name, parameters, path and the joints it spans.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MuscleConfig {
    /// Name used in commands and published states.
    pub name: String,
    /// Model parameters (everything not given takes its Table 1 default).
    #[serde(flatten)]
    pub params: MuscleParams,
    /// Path length with every spanned joint at 0 rad, m. `None`: l_opt + l_ts + 2 mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path_length: Option<f64>,
    /// The joints it spans.
    #[serde(rename = "span")]
    pub spans: Vec<SpanConfig>,
}

/// The limb: joints and the muscles that drive them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ActuatorConfig {
    /// The joints.
    #[serde(rename = "joint")]
    pub joints: Vec<JointParams>,
    /// The muscles.
    #[serde(rename = "muscle")]
    pub muscles: Vec<MuscleConfig>,
}

/// The single `[joint]` table of the antagonistic-pair form: the joint's parameters, a pulley
/// `radius` (the flexor's moment arm is +r, the extensor's -r) and a common `path_length`.
struct PairJoint {
    joint: JointParams,
    radius: Option<f64>,
    path_length: Option<f64>,
}

impl PairJoint {
    /// The pair's own rules: a positive radius and path length.
    fn check(&self) -> Result<(), ConfigError> {
        let mut errors = Vec::new();
        for (key, v) in [("radius", self.radius), ("path_length", self.path_length)] {
            if let Some(v) = v {
                if !(v.is_finite() && v > 0.0) {
                    errors.push(rule(format!("joint.{key}"), v, "must be > 0"));
                }
            }
        }
        if errors.is_empty() {
            Ok(())
        } else {
            Err(ConfigError::Invalid(errors))
        }
    }

    fn from_table(mut t: toml::Table) -> Result<Self, String> {
        let mut number = |key: &str| -> Result<Option<f64>, String> {
            t.remove(key)
                .map(|v| {
                    f64::deserialize(v)
                        .map_err(|e| format!("joint.{key}: {}", e.to_string().trim()))
                })
                .transpose()
        };
        let radius = number("radius")?;
        let path_length = number("path_length")?;
        let joint = JointParams::deserialize(toml::Value::Table(t))
            .map_err(|e| format!("joint: {}", e.to_string().trim()))?;
        Ok(Self {
            joint,
            radius,
            path_length,
        })
    }
}

/// Pulley radius of the default elbow, m (docs/model.md §8).
pub const DEFAULT_RADIUS: f64 = 0.03;
/// Extra length of a default path over l_opt + l_ts with the joints at 0 rad, m (§8).
pub const DEFAULT_PATH_PRESTRETCH: f64 = 0.002;
/// Largest configuration file read, bytes.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

impl Default for ActuatorConfig {
    /// The `elbow`: one joint, flexor and extensor on a 3 cm pulley, Table 1 parameters.
    fn default() -> Self {
        let span = |r: f64| SpanConfig {
            joint: "elbow".into(),
            moment_arm: MomentArm::Constant(r),
            changes_sign: false,
        };
        let muscle = |name: &str, r: f64| MuscleConfig {
            name: name.into(),
            params: MuscleParams::default(),
            path_length: None,
            spans: vec![span(r)],
        };
        Self {
            joints: vec![JointParams::default()],
            muscles: vec![
                muscle("flexor", DEFAULT_RADIUS),
                muscle("extensor", -DEFAULT_RADIUS),
            ],
        }
    }
}

/// Why a configuration could not be used.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// The file could not be read.
    #[error("cannot read configuration file {path}: {reason}")]
    Io {
        /// The path.
        path: String,
        /// Why.
        reason: String,
    },
    /// The file is not valid TOML for this schema.
    #[error("configuration file {path}: {message}")]
    Parse {
        /// The path.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// One or more parameters break their rules.
    #[error("{}", .0.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("\n"))]
    Invalid(Vec<ParamError>),
}

fn rule(parameter: String, value: impl ToString, rule: &'static str) -> ParamError {
    ParamError {
        parameter,
        value: value.to_string(),
        rule,
    }
}

impl MuscleConfig {
    /// The path length in force: the configured one or l_opt + l_ts + 2 mm.
    pub fn path_length(&self) -> f64 {
        self.path_length
            .unwrap_or(self.params.l_opt + self.params.l_ts + DEFAULT_PATH_PRESTRETCH)
    }
}

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
        let muscle_tables = match raw.remove("muscle") {
            None => None,
            Some(toml::Value::Array(a)) => Some(
                a.into_iter()
                    .enumerate()
                    .map(|(i, v)| match v {
                        toml::Value::Table(t) => Ok(t),
                        _ => Err(parse_err(format!("muscle[{i}] must be a table"))),
                    })
                    .collect::<Result<Vec<_>, _>>()?,
            ),
            Some(_) => {
                return Err(parse_err(
                    "`muscle` must be an array of tables ([[muscle]])".into(),
                ))
            }
        };
        let mut muscles = match muscle_tables {
            None => Vec::new(),
            Some(tables) => tables
                .into_iter()
                .enumerate()
                .map(|(i, t)| muscle_from_table(i, t).map_err(parse_err))
                .collect::<Result<Vec<_>, _>>()?,
        };
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
                // The antagonistic-pair form: one `[joint]` table (or none), muscles without
                // spans.
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
                let spanless = muscles.iter().all(|m| m.spans.is_empty());
                if muscles.is_empty() || spanless {
                    let mut cfg = ActuatorConfig::default();
                    if let Some(p) = &pair {
                        p.check()?;
                    }
                    let (radius, path_length) = match pair {
                        Some(p) => {
                            cfg.joints = vec![p.joint];
                            (p.radius.unwrap_or(DEFAULT_RADIUS), p.path_length)
                        }
                        None => (DEFAULT_RADIUS, None),
                    };
                    match muscles.len() {
                        0 => {}
                        // One muscle of the pair given: the other keeps its default.
                        1 => {
                            let m = muscles.remove(0);
                            let Some(k) = cfg.muscles.iter().position(|d| d.name == m.name) else {
                                return Err(ConfigError::Invalid(vec![rule(
                                    format!("muscle.{}", excerpt(&m.name)),
                                    "not a muscle of the pair",
                                    "a single muscle without `span` replaces the default pair's \
                                     muscle of the same name (flexor or extensor); give two to \
                                     replace both (agonist first), or give each muscle a \
                                     [[muscle.span]] for other topologies",
                                )]));
                            };
                            cfg.muscles[k] = m;
                        }
                        2 => cfg.muscles = muscles,
                        n => {
                            return Err(ConfigError::Invalid(vec![rule(
                                "muscle".into(),
                                format!("{n} entries"),
                                "muscles without `span` form an antagonistic pair on one joint: \
                                 one (replacing the default muscle of its name) or two (agonist, \
                                 antagonist); give each muscle a [[muscle.span]] for other \
                                 topologies",
                            )]));
                        }
                    }
                    cfg.set_pair_geometry(radius, path_length);
                    cfg.validate()?;
                    return Ok(cfg);
                }
                match pair {
                    Some(p) if p.radius.is_some() || p.path_length.is_some() => {
                        return Err(parse_err(
                            "joint.radius and joint.path_length belong to the antagonistic pair \
                             (muscles without spans); with [[muscle.span]] give each muscle its \
                             moment arms and path_length"
                                .into(),
                        ))
                    }
                    Some(p) => vec![p.joint],
                    None => vec![JointParams::default()],
                }
            }
        };
        let cfg = ActuatorConfig { joints, muscles };
        cfg.validate()?;
        Ok(cfg)
    }

    /// The antagonistic pair's geometry on its single joint: the first muscle's moment arm +r,
    /// the second's -r, both on one path length (the first muscle's l_opt + l_ts + 2 mm unless
    /// given).
    fn set_pair_geometry(&mut self, radius: f64, path_length: Option<f64>) {
        let joint = self.joints[0].name.clone();
        let l0 = path_length.unwrap_or_else(|| self.muscles[0].path_length());
        for (k, m) in self.muscles.iter_mut().enumerate() {
            let r = if k == 0 { radius } else { -radius };
            m.spans = vec![SpanConfig {
                joint: joint.clone(),
                moment_arm: MomentArm::Constant(r),
                changes_sign: false,
            }];
            m.path_length = Some(l0);
        }
        if path_length.is_none()
            && self
                .muscles
                .iter()
                .all(|m| m.params == self.muscles[0].params)
        {
            // Equal muscles: each default path is the common one; keep it implicit.
            for m in &mut self.muscles {
                m.path_length = None;
            }
        }
    }

    /// Muscle names, in order.
    pub fn muscle_names(&self) -> Vec<String> {
        self.muscles.iter().map(|m| m.name.clone()).collect()
    }

    /// Joint names, in order.
    pub fn joint_names(&self) -> Vec<String> {
        self.joints.iter().map(|j| j.name.clone()).collect()
    }

    /// The topology this configuration describes (validate first: unknown joints are skipped).
    pub fn topology(&self) -> Topology {
        let muscles = self
            .muscles
            .iter()
            .map(|m| MuscleSpec {
                name: m.name.clone(),
                params: m.params.clone(),
                anchor: Anchor::Path {
                    path_length: m.path_length(),
                    spans: m
                        .spans
                        .iter()
                        .filter_map(|s| {
                            let joint = self.joints.iter().position(|j| j.name == s.joint)?;
                            Some(Span {
                                joint,
                                moment_arm: s.moment_arm.clone(),
                            })
                        })
                        .collect(),
                },
            })
            .collect();
        Topology {
            joints: self.joints.clone(),
            muscles,
        }
    }

    /// All rule violations, one error each; `Ok` when the configuration is usable.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let mut errors = Vec::new();
        if self.joints.is_empty() {
            errors.push(rule("joint".into(), "none", "at least one joint is needed"));
        }
        if self.muscles.is_empty() {
            errors.push(rule(
                "muscle".into(),
                "none",
                "at least one muscle is needed",
            ));
        }
        for (k, j) in self.joints.iter().enumerate() {
            let prefix = format!("joint.{}.", excerpt(&j.name));
            if j.name.trim().is_empty() {
                errors.push(rule(
                    format!("joint[{k}].name"),
                    "\"\"",
                    "must not be empty",
                ));
            } else if self.joints[..k].iter().any(|o| o.name == j.name) {
                errors.push(rule(
                    format!("joint[{k}].name"),
                    format!("{:?}", excerpt(&j.name)),
                    "must be unique",
                ));
            }
            j.validate(&prefix, &mut errors);
            if !self
                .muscles
                .iter()
                .any(|m| m.spans.iter().any(|s| s.joint == j.name))
            {
                errors.push(rule(
                    format!("joint.{}", excerpt(&j.name)),
                    "no muscle",
                    "every joint must be spanned by at least one muscle",
                ));
            }
        }
        let joint_names = self.joint_names().join(", ");
        for (i, m) in self.muscles.iter().enumerate() {
            let name = excerpt(&m.name);
            if m.name.trim().is_empty() {
                errors.push(rule(
                    format!("muscle[{i}].name"),
                    "\"\"",
                    "must not be empty",
                ));
            } else if self.muscles[..i].iter().any(|o| o.name == m.name) {
                errors.push(rule(
                    format!("muscle[{i}].name"),
                    format!("{name:?}"),
                    "must be unique",
                ));
            }
            m.params.validate(&format!("muscle.{name}."), &mut errors);
            if let Some(l0) = m.path_length {
                if !(l0.is_finite() && l0 > 0.0) {
                    errors.push(rule(
                        format!("muscle.{name}.path_length"),
                        l0,
                        "must be a finite number > 0",
                    ));
                }
            }
            if m.spans.is_empty() {
                errors.push(rule(
                    format!("muscle.{name}.span"),
                    "none",
                    "a muscle must span at least one joint ([[muscle.span]] with joint and moment_arm)",
                ));
            }
            for (k, s) in m.spans.iter().enumerate() {
                let at = format!("muscle.{name}.span[{k}]");
                let Some(joint) = self.joints.iter().find(|j| j.name == s.joint) else {
                    errors.push(ParamError {
                        parameter: format!("{at}.joint"),
                        value: format!("{:?}", excerpt(&s.joint)),
                        rule: "names no joint of this configuration",
                    });
                    errors.last_mut().expect("just pushed").value +=
                        &format!(" (joints: {})", excerpt(&joint_names));
                    continue;
                };
                if m.spans[..k].iter().any(|o| o.joint == s.joint) {
                    errors.push(rule(
                        format!("{at}.joint"),
                        format!("{:?}", excerpt(&s.joint)),
                        "a muscle spans each joint at most once",
                    ));
                }
                let c = s.moment_arm.coefficients();
                if c.is_empty() || c.len() > 16 {
                    errors.push(rule(
                        format!("{at}.moment_arm"),
                        format!("{} coefficients", c.len()),
                        "must be a number or 1 to 16 polynomial coefficients",
                    ));
                } else if c.iter().any(|v| !v.is_finite()) {
                    errors.push(rule(
                        format!("{at}.moment_arm"),
                        format!("{c:?}"),
                        "must be finite",
                    ));
                } else if c.iter().all(|v| *v == 0.0) {
                    errors.push(rule(
                        format!("{at}.moment_arm"),
                        "0",
                        "must not be zero (leave the joint out instead)",
                    ));
                } else if joint.min_angle.is_finite()
                    && joint.max_angle.is_finite()
                    && joint.min_angle < joint.max_angle
                    && !s.changes_sign
                    && !s.moment_arm.keeps_sign_on(joint.min_angle, joint.max_angle)
                {
                    errors.push(rule(
                        format!("{at}.moment_arm"),
                        format!("{c:?}"),
                        "changes sign (or is zero) inside the joint's range; set \
                         changes_sign = true if the muscle's line of action really crosses the \
                         joint's axis",
                    ));
                }
            }
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
            .filter_map(|m| {
                m.params
                    .continuity_warning(&format!("muscle.{}.", excerpt(&m.name)))
            })
            .collect()
    }
}

/// Reads `path` if it is a regular file of at most `max_bytes` bytes. The type and size are
/// checked before reading, so a device (`/dev/zero`), a FIFO or a directory is refused instead of
/// read without end or waited on; the read itself stops after `max_bytes` + 1 bytes, so a file
/// that grows meanwhile cannot make it allocate more. Errors give the reason only (the caller
/// names the file).
pub fn read_regular_file(path: &Path, max_bytes: u64) -> std::io::Result<Vec<u8>> {
    use std::io::{Error, ErrorKind, Read};
    use std::os::unix::fs::OpenOptionsExt;
    let check = |meta: &std::fs::Metadata| -> std::io::Result<()> {
        if !meta.is_file() {
            return Err(Error::new(ErrorKind::InvalidInput, "not a regular file"));
        }
        if meta.len() > max_bytes {
            return Err(Error::new(
                ErrorKind::InvalidInput,
                format!(
                    "{} bytes, more than the {max_bytes} such a file may have",
                    meta.len()
                ),
            ));
        }
        Ok(())
    };
    check(&std::fs::metadata(path)?)?;
    // Non-blocking open: should the path become a FIFO after the check above, opening it does
    // not wait for a writer; the check is repeated on the open file.
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)?;
    let meta = file.metadata()?;
    check(&meta)?;
    let mut buf = Vec::with_capacity(meta.len() as usize);
    file.take(max_bytes + 1).read_to_end(&mut buf)?;
    if buf.len() as u64 > max_bytes {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            format!("grew beyond the {max_bytes} bytes such a file may have while read"),
        ));
    }
    Ok(buf)
}

/// Longest parse error message, characters (it may quote the file).
pub const MAX_MESSAGE_CHARS: usize = 300;

/// A message on one line (whitespace runs, newlines included, made one space), at most
/// [`MAX_MESSAGE_CHARS`] characters.
pub fn one_line(message: &str) -> String {
    let flat = message.split_whitespace().collect::<Vec<_>>().join(" ");
    if flat.chars().count() <= MAX_MESSAGE_CHARS {
        flat
    } else {
        let mut e: String = flat.chars().take(MAX_MESSAGE_CHARS - 3).collect();
        e.push_str("...");
        e
    }
}

/// A TOML parse error of `text` as `line L, column C: message` on one line (the parser's own
/// rendering quotes the whole offending line, however long).
pub fn toml_error(e: &toml::de::Error, text: &str) -> String {
    let at = match e.span() {
        Some(span) => {
            let before = &text.as_bytes()[..span.start.min(text.len())];
            let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
            let column = before.len()
                - before
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |i| i + 1)
                + 1;
            format!("TOML parse error at line {line}, column {column}: ")
        }
        None => "TOML parse error: ".into(),
    };
    one_line(&format!("{at}{}", e.message()))
}

/// A user string as quoted in messages: at most 64 characters.
pub fn excerpt(s: &str) -> String {
    if s.chars().count() <= 64 {
        s.to_string()
    } else {
        let mut e: String = s.chars().take(61).collect();
        e.push_str("...");
        e
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// One muscle of the pair, without spans: it replaces the default muscle of its name, and
    /// everything else keeps its default (the rule the README states).
    #[test]
    fn a_single_pair_muscle_replaces_its_namesake() {
        let default = ActuatorConfig::default();
        let cfg =
            ActuatorConfig::from_toml_str("[[muscle]]\nname = \"extensor\"\nf_max = 1000.0\n")
                .unwrap();
        assert_eq!(cfg.muscle_names(), default.muscle_names());
        assert_eq!(cfg.muscles[0].params, default.muscles[0].params);
        assert_eq!(cfg.muscles[1].params.f_max, 1000.0);
        assert_eq!(cfg.muscles[1].spans, default.muscles[1].spans);
        assert_eq!(cfg.joints, default.joints);
        let e = ActuatorConfig::from_toml_str("[[muscle]]\nname = \"biceps\"\n").unwrap_err();
        assert!(e.to_string().contains("muscle.biceps"), "{e}");
    }
}
