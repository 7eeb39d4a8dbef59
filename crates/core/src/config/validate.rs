//! The configuration's rules: every joint named uniquely and spanned, every muscle named
//! uniquely with valid parameters and path, every span on a joint of the configuration with a
//! usable moment arm (one sign over the joint's range unless `changes_sign`); the `[stepper]`
//! table's values within their bounds.

use super::schema::{ActuatorConfig, MuscleConfig, SpanConfig};
use super::{rule, ConfigError};
use crate::physics::curves::tabulated::{TabulatedCurve, TabulatedCurveError};
use crate::physics::limb_params::tabulated_points::{split, TabulatedCurves};
use crate::physics::limb_params::{JointParams, ParamError};
use crate::text::excerpt;

/// A name's rules (`at` names it): not empty, and not `taken` by an earlier one of its kind.
fn check_name(at: String, name: &str, taken: bool, errors: &mut Vec<ParamError>) {
    if name.trim().is_empty() {
        errors.push(rule(at, "\"\"", "must not be empty"));
    } else if taken {
        errors.push(rule(at, format!("{:?}", excerpt(name)), "must be unique"));
    }
}

/// A tabulated muscle's curves (`at` names the table): each a curve the spline can be built
/// through, and each but the active one rising somewhere, since the balance, the tendon's and
/// the parallel element's lengths invert them there (docs/model.md §4b).
fn validate_tabulated(at: &str, t: &TabulatedCurves, errors: &mut Vec<ParamError>) {
    for (key, points) in t.named() {
        let (x, y) = split(points);
        let rule_of = |e: &TabulatedCurveError| match e {
            TabulatedCurveError::Lengths { .. } => "every point must be [x, y]",
            TabulatedCurveError::TooFewPoints { .. } => "needs at least 2 points",
            TabulatedCurveError::NotFiniteX { .. } | TabulatedCurveError::NotFiniteY { .. } => {
                "every x and y must be a finite number"
            }
            TabulatedCurveError::NotIncreasing { .. } => "its x must rise from point to point",
            TabulatedCurveError::Overflow => "its spline overflows: points too far apart",
        };
        match TabulatedCurve::new(&x, &y) {
            Err(e) => errors.push(rule(
                format!("{at}{key}"),
                excerpt(&e.to_string()),
                rule_of(&e),
            )),
            Ok(c) if key != "active_force_length" && c.rising_part().is_none() => {
                errors.push(rule(
                    format!("{at}{key}"),
                    format!("{} points", points.len()),
                    "must rise somewhere (two consecutive points with rising y)",
                ))
            }
            Ok(_) => {}
        }
    }
}

impl ActuatorConfig {
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
            self.validate_joint(k, j, &mut errors);
        }
        let joint_names = self.joint_names().join(", ");
        for (i, m) in self.muscles.iter().enumerate() {
            self.validate_muscle(i, m, &joint_names, &mut errors);
        }
        self.stepper.validate(&mut errors);
        if errors.is_empty() {
            Ok(())
        } else {
            Err(ConfigError::Invalid(errors))
        }
    }

    /// Joint `k`'s rules: a unique, non-empty name, valid parameters, a muscle spanning it.
    fn validate_joint(&self, k: usize, j: &JointParams, errors: &mut Vec<ParamError>) {
        let prefix = format!("joint.{}.", excerpt(&j.name));
        let taken = self.joints[..k].iter().any(|o| o.name == j.name);
        check_name(format!("joint[{k}].name"), &j.name, taken, errors);
        j.validate(&prefix, errors);
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

    /// Muscle `i`'s rules: a unique, non-empty name, valid parameters and path length, at least
    /// one span, each valid ([`Self::validate_span`]).
    fn validate_muscle(
        &self,
        i: usize,
        m: &MuscleConfig,
        joint_names: &str,
        errors: &mut Vec<ParamError>,
    ) {
        let name = excerpt(&m.name);
        let taken = self.muscles[..i].iter().any(|o| o.name == m.name);
        check_name(format!("muscle[{i}].name"), &m.name, taken, errors);
        m.params.validate(&format!("muscle.{name}."), errors);
        if let Some(t) = &m.params.tabulated {
            validate_tabulated(&format!("muscle.{name}.tabulated."), t, errors);
        }
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
            self.validate_span(
                &format!("muscle.{name}.span[{k}]"),
                &m.spans[..k],
                s,
                joint_names,
                errors,
            );
        }
    }

    /// A span's rules (`at` names it; `before` are the muscle's earlier spans): a joint of this
    /// configuration, spanned once, with a finite, non-zero moment arm of 1 to 16 coefficients
    /// that keeps its sign over the joint's range unless `changes_sign`.
    fn validate_span(
        &self,
        at: &str,
        before: &[SpanConfig],
        s: &SpanConfig,
        joint_names: &str,
        errors: &mut Vec<ParamError>,
    ) {
        let Some(joint) = self.joints.iter().find(|j| j.name == s.joint) else {
            errors.push(ParamError {
                parameter: format!("{at}.joint"),
                value: format!("{:?}", excerpt(&s.joint)),
                rule: "names no joint of this configuration",
            });
            errors.last_mut().expect("just pushed").value +=
                &format!(" (joints: {})", excerpt(joint_names));
            return;
        };
        if before.iter().any(|o| o.joint == s.joint) {
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
