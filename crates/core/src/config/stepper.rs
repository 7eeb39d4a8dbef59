//! The `[stepper]` table: the accuracy setting of the adaptive sub-steps (docs/configuration.md,
//! docs/integration.md).
//!
//! ```toml
//! [stepper]
//! tolerance = 1e-6      # relative local error per sub-step; absent: each model's own
//! max_substeps = 200    # most adaptive sub-steps per tick; absent: each model's own (64)
//! ```
//!
//! Absent, each model steps as its [`ModelSpec::stepping`](crate::physics::models::ModelSpec)
//! says, and the table is not written out (a configuration's TOML, which recordings and saved
//! states carry, stays as it was). The table applies to adaptive stepping only: a run that steps
//! with fixed sub-steps (`--substeps N`, `substeps=`, or the full Huxley model) refuses it
//! ([`StepperError`]) rather than ignore an accuracy it would not deliver.

use super::rule;
use crate::physics::limb_params::ParamError;
use crate::physics::models::ModelKind;
use crate::physics::stepping::{Stepping, MAX_SUBSTEPS};
use serde::{Deserialize, Serialize};

/// Tightest `stepper.tolerance`: below it the error estimate is near the rounding of the state.
pub(crate) const MIN_TOLERANCE: f64 = 1e-10;
/// Loosest `stepper.tolerance`: 10% of the state's scales per sub-step is no accuracy at all.
pub(crate) const MAX_TOLERANCE: f64 = 0.1;

/// The `[stepper]` table: the adaptive sub-steps' tolerance and most sub-steps per tick, each
/// `None` for the model's own.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepperConfig {
    /// Relative local error tolerance of each adaptive sub-step (of the state's scales), from
    /// `MIN_TOLERANCE` to `MAX_TOLERANCE`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Most adaptive sub-steps per tick, 1 to [`MAX_SUBSTEPS`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_substeps: Option<usize>,
}

/// A `[stepper]` value that the run's stepping cannot take: it steps with fixed sub-steps, which
/// have no tolerance.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StepperError {
    /// Fixed sub-steps asked for (`--substeps`, `substeps=`) with a `[stepper]` value.
    #[error(
        "stepper.{key} applies to adaptive sub-steps: it cannot be combined with fixed \
         sub-steps ({substeps} per tick); give one or the other"
    )]
    WithFixedSubsteps {
        /// `tolerance` or `max_substeps`.
        key: &'static str,
        /// The fixed sub-steps per tick asked for.
        substeps: usize,
    },
    /// A `[stepper]` value with a model that steps with fixed sub-steps only (the full Huxley
    /// model).
    #[error(
        "stepper.{key} applies to adaptive sub-steps: the {model} model steps with fixed \
         sub-steps only; leave [stepper] out of its configuration"
    )]
    FixedModel {
        /// `tolerance` or `max_substeps`.
        key: &'static str,
        /// The model.
        model: ModelKind,
    },
}

impl StepperConfig {
    /// Whether the table sets nothing (it is then not written out).
    pub fn is_empty(&self) -> bool {
        self.tolerance.is_none() && self.max_substeps.is_none()
    }

    /// The key of the first value set, for messages.
    fn first_key(&self) -> &'static str {
        if self.tolerance.is_some() {
            "tolerance"
        } else {
            "max_substeps"
        }
    }

    /// Its rules: a tolerance from [`MIN_TOLERANCE`] to [`MAX_TOLERANCE`], 1 to
    /// [`MAX_SUBSTEPS`] sub-steps.
    pub(super) fn validate(&self, errors: &mut Vec<ParamError>) {
        if let Some(t) = self.tolerance {
            if !(t.is_finite() && (MIN_TOLERANCE..=MAX_TOLERANCE).contains(&t)) {
                errors.push(rule(
                    "stepper.tolerance".into(),
                    t,
                    "must be a finite number from 1e-10 to 0.1 (relative)",
                ));
            }
        }
        if let Some(n) = self.max_substeps {
            if !(1..=MAX_SUBSTEPS).contains(&n) {
                errors.push(rule(
                    "stepper.max_substeps".into(),
                    n,
                    "must be between 1 and 10000",
                ));
            }
        }
    }

    /// The stepping of a run of `model` under this table: `substeps` fixed sub-steps if given,
    /// else the model's own stepping with this table's values in place of its defaults. A value
    /// set here with fixed sub-steps (given, or the model's only stepping) is refused.
    pub(crate) fn stepping(
        &self,
        model: ModelKind,
        substeps: Option<usize>,
    ) -> Result<Stepping, StepperError> {
        let key = self.first_key();
        match (substeps, model.spec().stepping) {
            (Some(n), _) if !self.is_empty() => {
                Err(StepperError::WithFixedSubsteps { key, substeps: n })
            }
            (Some(n), _) => Ok(Stepping::Fixed(n)),
            (
                None,
                Stepping::Adaptive {
                    tolerance,
                    max_substeps,
                },
            ) => Ok(Stepping::Adaptive {
                tolerance: self.tolerance.unwrap_or(tolerance),
                max_substeps: self.max_substeps.unwrap_or(max_substeps),
            }),
            (None, fixed) if self.is_empty() => Ok(fixed),
            (None, _) => Err(StepperError::FixedModel { key, model }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{ActuatorConfig, ConfigError};
    use crate::sim::simulation::default_stepping;

    fn with(text: &str) -> Result<ActuatorConfig, ConfigError> {
        ActuatorConfig::from_toml_str(&format!(
            "[[muscle]]\nname = \"flexor\"\n[[muscle]]\nname = \"extensor\"\n{text}"
        ))
    }

    /// Absent, every model steps as before and the table is not written out.
    #[test]
    fn absent_is_each_models_own_and_not_written() {
        let cfg = ActuatorConfig::default();
        for model in ModelKind::all() {
            assert_eq!(cfg.stepping(model, None), Ok(default_stepping(model)));
            assert_eq!(cfg.stepping(model, Some(7)), Ok(Stepping::Fixed(7)));
        }
        assert!(!toml::to_string(&cfg).unwrap().contains("stepper"));
        assert_eq!(with("").unwrap(), cfg);
    }

    /// Set, it replaces the adaptive models' values, reads back from its TOML, and is refused
    /// with fixed sub-steps.
    #[test]
    fn set_it_applies_to_adaptive_models_and_round_trips() {
        let cfg = with("[stepper]\ntolerance = 1e-7\nmax_substeps = 300\n").unwrap();
        let adaptive = Stepping::Adaptive {
            tolerance: 1e-7,
            max_substeps: 300,
        };
        assert_eq!(cfg.stepping(ModelKind::HILL, None), Ok(adaptive));
        assert_eq!(cfg.stepping(ModelKind::HUXLEY, None), Ok(adaptive));
        let text = toml::to_string(&cfg).unwrap();
        assert!(text.contains("[stepper]"), "{text}");
        assert_eq!(ActuatorConfig::from_toml_str(&text).unwrap(), cfg);
        let e = cfg.stepping(ModelKind::HILL, Some(8)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "stepper.tolerance applies to adaptive sub-steps: it cannot be combined with fixed \
             sub-steps (8 per tick); give one or the other"
        );
        let e = cfg.stepping(ModelKind::HUXLEY_PDE, None).unwrap_err();
        assert!(
            matches!(
                e,
                StepperError::FixedModel {
                    key: "tolerance",
                    ..
                }
            ),
            "{e}"
        );
        // The tolerance alone keeps the model's most sub-steps.
        let cfg = with("[stepper]\ntolerance = 1e-6\n").unwrap();
        assert_eq!(
            cfg.stepping(ModelKind::HILL, None),
            Ok(Stepping::Adaptive {
                tolerance: 1e-6,
                max_substeps: crate::physics::stepping::DEFAULT_MAX_SUBSTEPS
            })
        );
    }

    /// Bad values are refused on one line naming `stepper.tolerance` (or the key).
    #[test]
    fn bad_values_are_refused_on_one_line() {
        for (text, needle) in [
            ("tolerance = 0.0", "stepper.tolerance = 0"),
            ("tolerance = -1e-6", "stepper.tolerance = -0.000001"),
            ("tolerance = 0.5", "stepper.tolerance = 0.5"),
            ("tolerance = 1e-12", "stepper.tolerance"),
            ("tolerance = nan", "stepper.tolerance = NaN"),
            ("tolerance = inf", "stepper.tolerance = inf"),
            ("max_substeps = 0", "stepper.max_substeps = 0"),
            ("tolerance = \"x\"", "stepper"),
            ("tol = 1e-6", "tol"),
        ] {
            let e = with(&format!("[stepper]\n{text}\n"))
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle) && !e.contains('\n'), "{text}: {e}");
        }
        let e = with("[stepper]\ntolerance = 0.5\n").unwrap_err();
        assert!(matches!(e, ConfigError::Invalid(_)), "{e}");
    }
}
