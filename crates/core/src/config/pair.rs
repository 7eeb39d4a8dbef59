//! The antagonistic-pair form of a configuration: a single `[joint]` table with a pulley
//! `radius` (and optional common `path_length`), and muscles without spans: two, the first
//! pulling towards positive angles, or one, which replaces the default muscle of its name.

use super::schema::{ActuatorConfig, MuscleConfig, SpanConfig, DEFAULT_RADIUS};
use super::{rule, ConfigError, ParseError};
use crate::physics::limb_params::JointParams;
use crate::physics::moment_arm::MomentArm;
use crate::text::excerpt;
use serde::Deserialize;

/// The single `[joint]` table of the antagonistic-pair form: the joint's parameters, a pulley
/// `radius` (the flexor's moment arm is +r, the extensor's -r) and a common `path_length`.
pub(super) struct PairJoint {
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

    pub(super) fn from_table(mut t: toml::Table) -> Result<Self, ParseError> {
        let mut number = |key: &'static str| {
            t.remove(key)
                .map(|v| {
                    f64::deserialize(v).map_err(|e| ParseError::PairValue {
                        key,
                        reason: e.to_string().trim().to_string(),
                    })
                })
                .transpose()
        };
        let radius = number("radius")?;
        let path_length = number("path_length")?;
        let joint =
            JointParams::deserialize(toml::Value::Table(t)).map_err(|e| ParseError::PairJoint {
                reason: e.to_string().trim().to_string(),
            })?;
        Ok(Self {
            joint,
            radius,
            path_length,
        })
    }
}

/// The configuration of the pair form: the default elbow with the given `[joint]` table (if
/// any) and the given spanless muscles (none, one or two), validated.
pub(super) fn pair_config(
    pair: Option<PairJoint>,
    mut muscles: Vec<MuscleConfig>,
) -> Result<ActuatorConfig, ConfigError> {
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
    Ok(cfg)
}

/// The joints of a configuration whose muscles have spans and whose `joint` is a single table
/// (or absent): that joint (or the default one). A pulley `radius` or common `path_length` there
/// is refused: they belong to the pair form.
pub(super) fn single_joint(pair: Option<PairJoint>) -> Result<Vec<JointParams>, ParseError> {
    match pair {
        Some(p) if p.radius.is_some() || p.path_length.is_some() => {
            Err(ParseError::PairKeysWithSpans)
        }
        Some(p) => Ok(vec![p.joint]),
        None => Ok(vec![JointParams::default()]),
    }
}

impl ActuatorConfig {
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
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One muscle of the pair, without spans: it replaces the default muscle of its name, and
    /// everything else keeps its default (the rule docs/configuration.md states).
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
