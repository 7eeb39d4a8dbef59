//! Overrides of single configuration values by dotted keys (a sweep's per-instance parameters,
//! docs/python.md):
//!
//! - `muscle.NAME.KEY` (a muscle parameter, `path_length`), `muscle.NAME.energetics.KEY`,
//!   `muscle.NAME.span.JOINT.KEY` (`moment_arm`, `changes_sign`);
//! - `muscle.*.…`: the same key on every muscle;
//! - `joint.NAME.KEY` (a joint parameter), `joint.*.KEY`;
//! - `stepper.KEY` (`tolerance`, `max_substeps`: the `[stepper]` table).
//!
//! The configuration is written out as its TOML table, the values set there, and the table read
//! back as a file is: every override meets the rules and messages of the configuration file.

use super::{ActuatorConfig, ConfigError, ParseError};
use crate::physics::limb_params::ParamError;
use crate::text::excerpt;

/// Why overrides cannot be applied, on one line (the text of [`ConfigError::Overrides`]).
#[derive(Debug, thiserror::Error)]
pub enum OverridesError {
    /// The configuration does not write out as a TOML table.
    #[error("configuration as TOML: {0}")]
    ToTable(
        /// The serializer's reason, on one line.
        String,
    ),
    /// One override cannot be set.
    #[error("override {:?}: {error}", excerpt(.key))]
    Key {
        /// The dotted key.
        key: String,
        /// Why.
        error: OverrideKeyError,
    },
    /// The overridden table does not write out as TOML text.
    #[error("as TOML: {0}")]
    ToText(
        /// The serializer's reason, on one line.
        String,
    ),
    /// The overridden configuration does not read back (a value of the wrong type, an unknown
    /// key).
    #[error("{}", crate::text::one_line(&.0.to_string()))]
    Parse(ParseError),
    /// The overridden configuration breaks rules: every broken rule, joined by `; `.
    #[error("{}", .0.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("; ").replace('\n', " "))]
    Invalid(Vec<ParamError>),
    /// Any other refusal of the overridden configuration.
    #[error("{}", .0.to_string().replace('\n', " "))]
    Config(Box<ConfigError>),
}

impl OverridesError {
    /// Whether an override names a muscle, joint or span the configuration does not have.
    pub fn is_unknown_name(&self) -> bool {
        matches!(
            self,
            OverridesError::Key {
                error: OverrideKeyError::UnknownName { .. } | OverrideKeyError::UnknownSpan { .. },
                ..
            }
        )
    }
}

/// Why one override (a dotted key and its value) cannot be set in the configuration's table.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum OverrideKeyError {
    /// The key does not start with `muscle.NAME.` or `joint.NAME.`, nor is `stepper.KEY`.
    #[error("expected muscle.NAME.KEY, joint.NAME.KEY (NAME may be *) or stepper.KEY")]
    BadKey,
    /// No muscle or joint of that name.
    #[error("no {kind} named {:?}", excerpt(.name))]
    UnknownName {
        /// `muscle` or `joint`.
        kind: &'static str,
        /// The name.
        name: String,
    },
    /// The configuration has no muscles, or no joints, to set a value of.
    #[error("the configuration has no {kind}")]
    NoEntries {
        /// `muscle` or `joint`.
        kind: &'static str,
    },
    /// The key is a name.
    #[error("a name cannot be overridden")]
    Name,
    /// The muscle's `energetics` is not a table.
    #[error("energetics is not a table")]
    EnergeticsNotATable,
    /// The key is a span's joint.
    #[error("a span's joint cannot be overridden")]
    SpanJoint,
    /// The muscle has no span over that joint.
    #[error("no span over joint {:?}", excerpt(.joint))]
    UnknownSpan {
        /// The joint named.
        joint: String,
    },
    /// After the name, neither `KEY`, `energetics.KEY` nor `span.JOINT.KEY`.
    #[error("expected KEY, energetics.KEY or span.JOINT.KEY after the name")]
    BadPath,
}

/// `cfg` with each `(key, value)` set in turn, validated as a configuration file; an error is
/// [`ConfigError::Overrides`], on one line (several broken rules joined by `; `).
pub fn with_overrides(
    cfg: &ActuatorConfig,
    overrides: &[(String, toml::Value)],
) -> Result<ActuatorConfig, ConfigError> {
    if overrides.is_empty() {
        return Ok(cfg.clone());
    }
    let one_line = |e: &dyn std::fmt::Display| e.to_string().replace('\n', " ");
    let mut table =
        toml::Table::try_from(cfg).map_err(|e| OverridesError::ToTable(one_line(&e)))?;
    for (key, value) in overrides {
        set(&mut table, key, value.clone()).map_err(|error| OverridesError::Key {
            key: key.clone(),
            error,
        })?;
    }
    let text = toml::to_string(&table).map_err(|e| OverridesError::ToText(one_line(&e)))?;
    ActuatorConfig::from_written_toml(&text).map_err(|e| {
        ConfigError::Overrides(match e {
            ConfigError::Parse { error, .. } => OverridesError::Parse(error),
            ConfigError::Invalid(errors) => OverridesError::Invalid(errors),
            ConfigError::Overrides(e) => e,
            other => OverridesError::Config(Box::new(other)),
        })
    })
}

/// Sets `key` = `value` in the configuration's table.
fn set(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<(), OverrideKeyError> {
    let parts: Vec<&str> = key.split('.').collect();
    if let ["stepper", key] = parts.as_slice() {
        // The `[stepper]` table (made if absent); its keys are checked as it is read back.
        let stepper = table
            .entry("stepper")
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        if let Some(t) = stepper.as_table_mut() {
            t.insert((*key).to_string(), value);
        }
        return Ok(());
    }
    let (kind, name, rest) = match parts.as_slice() {
        ["muscle", name, rest @ ..] if !rest.is_empty() => ("muscle", *name, rest),
        ["joint", name, rest @ ..] if !rest.is_empty() => ("joint", *name, rest),
        _ => return Err(OverrideKeyError::BadKey),
    };
    let entries = named_tables(table, kind)?;
    let mut found = false;
    for t in entries {
        if name == "*" || t.get("name").and_then(|n| n.as_str()) == Some(name) {
            found = true;
            set_in(t, rest, value.clone())?;
        }
    }
    if !found {
        return Err(OverrideKeyError::UnknownName {
            kind,
            name: name.to_string(),
        });
    }
    Ok(())
}

/// The `[[muscle]]` or `[[joint]]` tables.
fn named_tables<'a>(
    table: &'a mut toml::Table,
    kind: &'static str,
) -> Result<impl Iterator<Item = &'a mut toml::Table>, OverrideKeyError> {
    match table.get_mut(kind) {
        Some(toml::Value::Array(a)) => Ok(a.iter_mut().filter_map(|v| v.as_table_mut())),
        _ => Err(OverrideKeyError::NoEntries { kind }),
    }
}

/// Sets the key path `rest` (`KEY`, `energetics.KEY` or `span.JOINT.KEY`) within one entry.
fn set_in(
    entry: &mut toml::Table,
    rest: &[&str],
    value: toml::Value,
) -> Result<(), OverrideKeyError> {
    match rest {
        ["name"] => Err(OverrideKeyError::Name),
        [key] => {
            entry.insert((*key).to_string(), value);
            Ok(())
        }
        ["energetics", key] => {
            let e = entry
                .entry("energetics")
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            match e.as_table_mut() {
                Some(t) => {
                    t.insert((*key).to_string(), value);
                    Ok(())
                }
                None => Err(OverrideKeyError::EnergeticsNotATable),
            }
        }
        ["span", joint, key] => {
            let spans = entry.get_mut("span").and_then(|s| s.as_array_mut());
            let span = spans.and_then(|s| {
                s.iter_mut()
                    .filter_map(|v| v.as_table_mut())
                    .find(|t| t.get("joint").and_then(|j| j.as_str()) == Some(*joint))
            });
            match span {
                Some(t) if *key != "joint" => {
                    t.insert((*key).to_string(), value);
                    Ok(())
                }
                Some(_) => Err(OverrideKeyError::SpanJoint),
                None => Err(OverrideKeyError::UnknownSpan {
                    joint: (*joint).to_string(),
                }),
            }
        }
        _ => Err(OverrideKeyError::BadPath),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn over(key: &str, v: toml::Value) -> Result<ActuatorConfig, ConfigError> {
        with_overrides(&ActuatorConfig::default(), &[(key.into(), v)])
    }

    #[test]
    fn sets_muscle_joint_energetics_and_span_values() {
        let c = over("muscle.flexor.k_t", toml::Value::Float(2.5e5)).unwrap();
        assert_eq!(c.muscles[0].params.k_t, 2.5e5);
        assert_ne!(c.muscles[1].params.k_t, 2.5e5);
        let c = over("muscle.*.f_max", toml::Value::Integer(3000)).unwrap();
        assert!(c.muscles.iter().all(|m| m.params.f_max == 3000.0));
        let c = over("joint.elbow.damping", toml::Value::Float(0.2)).unwrap();
        assert_eq!(c.joints[0].damping, 0.2);
        let c = over(
            "muscle.extensor.energetics.energy_model",
            toml::Value::String("bhargava".into()),
        )
        .unwrap();
        assert_ne!(
            c.muscles[1].params.energetics.energy_model,
            c.muscles[0].params.energetics.energy_model
        );
        let c = over(
            "muscle.flexor.span.elbow.moment_arm",
            toml::Value::Float(0.04),
        )
        .unwrap();
        let default = ActuatorConfig::default();
        assert_ne!(
            c.muscles[0].spans[0].moment_arm,
            default.muscles[0].spans[0].moment_arm
        );
        assert_eq!(c.muscles[1].spans, default.muscles[1].spans);
    }

    #[test]
    fn no_overrides_is_the_same_configuration_and_a_round_trip_keeps_every_value() {
        let d = ActuatorConfig::default();
        assert_eq!(with_overrides(&d, &[]).unwrap(), d);
        let arm = ActuatorConfig::resolve("arm").unwrap();
        let same = with_overrides(
            &arm,
            &[(
                "joint.elbow.damping".into(),
                toml::Value::Float(arm.joints[1].damping),
            )],
        )
        .unwrap();
        assert_eq!(same, arm);
    }

    #[test]
    fn refusals_name_the_override_and_the_rule() {
        let msg = |k: &str, v: toml::Value| over(k, v).unwrap_err().to_string();
        assert!(msg("muscle.biceps.k_t", toml::Value::Float(1.0))
            .contains("no muscle named \"biceps\""));
        assert!(msg("muscle.flexor.k_tt", toml::Value::Float(1.0)).contains("k_tt"));
        assert!(msg("muscle.flexor.k_t", toml::Value::Float(-1.0)).contains("k_t"));
        assert!(msg("muscle.flexor.k_t", toml::Value::String("x".into())).contains("k_t"));
        assert!(msg("tendon.k_t", toml::Value::Float(1.0)).contains("expected muscle.NAME.KEY"));
        assert!(msg("muscle.flexor.name", toml::Value::String("x".into())).contains("name cannot"));
        assert!(msg(
            "muscle.flexor.span.knee.moment_arm",
            toml::Value::Float(0.1)
        )
        .contains("no span over joint"));
    }

    /// `stepper.tolerance` and `stepper.max_substeps` set the `[stepper]` table; bad values and
    /// unknown keys are refused on one line naming them.
    #[test]
    fn sets_the_stepper_table() {
        let c = over("stepper.tolerance", toml::Value::Float(1e-6)).unwrap();
        assert_eq!(c.stepper.tolerance, Some(1e-6));
        assert_eq!(c.stepper.max_substeps, None);
        assert_eq!(c.muscles, ActuatorConfig::default().muscles);
        let c = with_overrides(
            &c,
            &[("stepper.max_substeps".into(), toml::Value::Integer(200))],
        )
        .unwrap();
        assert_eq!(
            (c.stepper.tolerance, c.stepper.max_substeps),
            (Some(1e-6), Some(200))
        );
        for (key, v, needle) in [
            (
                "stepper.tolerance",
                toml::Value::Float(0.0),
                "stepper.tolerance = 0",
            ),
            (
                "stepper.tolerance",
                toml::Value::Float(1.0),
                "stepper.tolerance = 1",
            ),
            (
                "stepper.tolerance",
                toml::Value::String("x".into()),
                "stepper",
            ),
            (
                "stepper.max_substeps",
                toml::Value::Integer(0),
                "stepper.max_substeps",
            ),
            ("stepper.tol", toml::Value::Float(1e-6), "tol"),
            (
                "stepper.tolerance.x",
                toml::Value::Float(1e-6),
                "stepper.KEY",
            ),
        ] {
            let e = over(key, v).unwrap_err().to_string();
            assert!(
                e.starts_with("overrides: ") && e.contains(needle) && !e.contains('\n'),
                "{key}: {e}"
            );
        }
    }

    /// An unknown muscle, joint or span is told apart from other refusals.
    #[test]
    fn unknown_names_are_told_apart() {
        let e = over("muscle.biceps.k_t", toml::Value::Float(1.0)).unwrap_err();
        assert!(e.is_unknown_name(), "{e}");
        assert!(matches!(
            &e,
            ConfigError::Overrides(OverridesError::Key {
                error: OverrideKeyError::UnknownName { kind: "muscle", name },
                ..
            }) if name == "biceps"
        ));
        assert_eq!(
            e.to_string(),
            "overrides: override \"muscle.biceps.k_t\": no muscle named \"biceps\""
        );
        let e = over("joint.elbow.nothing.x", toml::Value::Float(1.0)).unwrap_err();
        assert!(!e.is_unknown_name(), "{e}");
        let e = over("muscle.flexor.k_t", toml::Value::Float(-1.0)).unwrap_err();
        assert!(
            matches!(e, ConfigError::Overrides(OverridesError::Invalid(_))),
            "{e}"
        );
    }

    /// Every refusal is one line that starts with `overrides: ` (never "configuration file"),
    /// however many rules the overridden configuration breaks.
    #[test]
    fn refusals_are_one_line_naming_the_overrides() {
        let both = with_overrides(
            &ActuatorConfig::default(),
            &[("muscle.*.k_t".into(), toml::Value::Float(-1.0))],
        );
        let cases = [
            both.unwrap_err().to_string(),
            over("muscle.flexor.k_tt", toml::Value::Float(1.0))
                .unwrap_err()
                .to_string(),
            over("muscle.biceps.k_t", toml::Value::Float(1.0))
                .unwrap_err()
                .to_string(),
            over("tendon.k_t", toml::Value::Float(1.0))
                .unwrap_err()
                .to_string(),
        ];
        for e in &cases {
            assert!(e.starts_with("overrides: "), "{e}");
            assert!(
                !e.contains('\n') && !e.contains("configuration file"),
                "{e}"
            );
        }
        // Both muscles' k_t named, on the one line.
        let e = &cases[0];
        assert!(
            e.contains("muscle.flexor.k_t") && e.contains("muscle.extensor.k_t"),
            "{e}"
        );
    }
}
