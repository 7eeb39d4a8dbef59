//! The configuration's schema: a limb of joints, and muscles that span them through moment arms;
//! the embedded default (the `elbow`, docs/model.md §8) and the topology a configuration
//! describes.

use super::stepper::{StepperConfig, StepperError};
use crate::physics::limb_params::{EnergyModel, JointParams, MuscleParams};
use crate::physics::models::ModelKind;
use crate::physics::moment_arm::MomentArm;
use crate::physics::stepping::Stepping;
use crate::physics::topology::{Anchor, MuscleSpec, Span, Topology};
use serde::{Deserialize, Serialize};

/// Pulley radius of the default elbow, m (docs/model.md §8).
pub const DEFAULT_RADIUS: f64 = 0.03;
/// Extra length of a default path over l_opt + l_ts with the joints at 0 rad, m (§8).
pub(crate) const DEFAULT_PATH_PRESTRETCH: f64 = 0.002;

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
    /// The `[stepper]` table: the adaptive sub-steps' accuracy (empty: each model's own; then
    /// not written out).
    #[serde(default, skip_serializing_if = "StepperConfig::is_empty")]
    pub stepper: StepperConfig,
}

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
            stepper: StepperConfig::default(),
        }
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
    /// Muscle names, in order.
    pub fn muscle_names(&self) -> Vec<String> {
        self.muscles.iter().map(|m| m.name.clone()).collect()
    }

    /// Joint names, in order.
    pub fn joint_names(&self) -> Vec<String> {
        self.joints.iter().map(|j| j.name.clone()).collect()
    }

    /// This configuration with every muscle's phenomenological energy model set to `m` (the
    /// node's `energy_model` parameter, `--energy-model` on the command line).
    pub fn with_energy_model(mut self, m: EnergyModel) -> Self {
        for muscle in &mut self.muscles {
            muscle.params.energetics.energy_model = m;
        }
        self
    }

    /// The stepping of a run of `model` on this configuration: `substeps` fixed sub-steps if
    /// given, else the model's own with the `[stepper]` table's values
    /// (`StepperConfig::stepping`; a table set with fixed sub-steps is refused).
    pub fn stepping(
        &self,
        model: ModelKind,
        substeps: Option<usize>,
    ) -> Result<Stepping, StepperError> {
        self.stepper.stepping(model, substeps)
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
}
