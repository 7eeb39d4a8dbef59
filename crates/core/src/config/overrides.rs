//! Overrides of single configuration values by dotted keys (a sweep's per-instance parameters,
//! docs/python.md):
//!
//! - `muscle.NAME.KEY` (a muscle parameter, `path_length`), `muscle.NAME.energetics.KEY`,
//!   `muscle.NAME.span.JOINT.KEY` (`moment_arm`, `changes_sign`);
//! - `muscle.*.…`: the same key on every muscle;
//! - `joint.NAME.KEY` (a joint parameter), `joint.*.KEY`.
//!
//! The configuration is written out as its TOML table, the values set there, and the table read
//! back as a file is: every override meets the rules and messages of the configuration file.

use super::{ActuatorConfig, ConfigError};
use crate::text::excerpt;

/// `cfg` with each `(key, value)` set in turn, validated as a configuration file; an error is
/// [`ConfigError::Overrides`], on one line (several broken rules joined by `; `).
pub fn with_overrides(
    cfg: &ActuatorConfig,
    overrides: &[(String, toml::Value)],
) -> Result<ActuatorConfig, ConfigError> {
    if overrides.is_empty() {
        return Ok(cfg.clone());
    }
    let invalid = |message: String| ConfigError::Overrides(message.replace('\n', " "));
    let mut table =
        toml::Table::try_from(cfg).map_err(|e| invalid(format!("configuration as TOML: {e}")))?;
    for (key, value) in overrides {
        set(&mut table, key, value.clone())
            .map_err(|e| invalid(format!("override {:?}: {e}", excerpt(key))))?;
    }
    let text = toml::to_string(&table).map_err(|e| invalid(format!("as TOML: {e}")))?;
    ActuatorConfig::from_toml_str(&text).map_err(|e| match e {
        ConfigError::Parse { message, .. } => invalid(message),
        ConfigError::Invalid(errors) => invalid(
            (errors.iter().map(|e| e.to_string()))
                .collect::<Vec<_>>()
                .join("; "),
        ),
        other => invalid(other.to_string()),
    })
}

/// Sets `key` = `value` in the configuration's table.
fn set(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<(), String> {
    let parts: Vec<&str> = key.split('.').collect();
    let (kind, name, rest) = match parts.as_slice() {
        [kind @ ("muscle" | "joint"), name, rest @ ..] if !rest.is_empty() => (*kind, *name, rest),
        _ => return Err("expected muscle.NAME.KEY or joint.NAME.KEY (NAME may be *)".into()),
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
        return Err(format!("no {kind} named {:?}", excerpt(name)));
    }
    Ok(())
}

/// The `[[muscle]]` or `[[joint]]` tables.
fn named_tables<'a>(
    table: &'a mut toml::Table,
    kind: &str,
) -> Result<impl Iterator<Item = &'a mut toml::Table>, String> {
    match table.get_mut(kind) {
        Some(toml::Value::Array(a)) => Ok(a.iter_mut().filter_map(|v| v.as_table_mut())),
        _ => Err(format!("the configuration has no {kind}")),
    }
}

/// Sets the key path `rest` (`KEY`, `energetics.KEY` or `span.JOINT.KEY`) within one entry.
fn set_in(entry: &mut toml::Table, rest: &[&str], value: toml::Value) -> Result<(), String> {
    match rest {
        ["name"] => Err("a name cannot be overridden".into()),
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
                None => Err("energetics is not a table".into()),
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
                Some(_) => Err("a span's joint cannot be overridden".into()),
                None => Err(format!("no span over joint {:?}", excerpt(joint))),
            }
        }
        _ => Err("expected KEY, energetics.KEY or span.JOINT.KEY after the name".into()),
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
