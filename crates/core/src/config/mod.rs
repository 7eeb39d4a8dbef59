//! The actuator configuration (TOML): joints, and muscles that span them through moment arms
//! (docs/configuration.md). Every parameter can be overridden; anything left out keeps its
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
//! The antagonistic-pair form is read too (`pair`): a single `[joint]` table with a pulley
//! `radius` (and optional common `path_length`), and two muscles without spans, the first
//! pulling towards positive angles; or one, which replaces the default muscle of its name.
//!
//! An optional `[stepper]` table sets the accuracy of the adaptive sub-steps for every model
//! (`stepper`).
//!
//! Built-in configurations by name: `elbow` (the default) and `arm` (after OpenSim's arm26).
//!
//! - `schema`: the structs, the default and the topology a configuration describes.
//! - `pair`: the antagonistic-pair form.
//! - `parse`: built-in names, files and TOML text; `parse_error`: why TOML does not fit.
//! - `validate`: the rules and the warnings.
//! - `overrides`: single values set by dotted keys (`muscle.flexor.k_t`, `stepper.tolerance`;
//!   [`with_overrides`]).
//! - `stepper`: the `[stepper]` table, the adaptive sub-steps' accuracy, and the stepping of a
//!   run.
//!
//! The files are the crate's modules; what other crates use of them is re-exported here.

pub(crate) mod overrides;
pub(crate) mod pair;
pub(crate) mod parse;
pub(crate) mod parse_error;
pub(crate) mod schema;
pub(crate) mod stepper;
mod unknown_key;
pub(crate) mod validate;

pub use self::{
    overrides::{with_overrides, OverrideKeyError, OverridesError},
    // BUILT_IN: the built-in configurations' names and texts (the text helpers that quote them
    // are `crate::text`'s).
    parse::BUILT_IN,
    parse_error::ParseError,
    schema::{ActuatorConfig, MuscleConfig, SpanConfig, DEFAULT_RADIUS},
    stepper::{StepperConfig, StepperError},
};
use crate::physics::limb_params::ParamError;

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
        /// The kind of the I/O error (`NotFound` for a missing file, `InvalidData` for bytes that
        /// are not UTF-8 text).
        kind: std::io::ErrorKind,
    },
    /// The file is not valid TOML for this schema (the reason on one line).
    #[error("configuration file {path}: {}", crate::text::one_line(&.error.to_string()))]
    Parse {
        /// The path (`<text>` for text, `<built-in NAME>` for a built-in configuration).
        path: String,
        /// What is wrong.
        error: ParseError,
    },
    /// One or more parameters break their rules.
    #[error("{}", .0.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("\n"))]
    Invalid(Vec<ParamError>),
    /// Overrides of single values ([`with_overrides`]) that cannot be applied, or that give a
    /// configuration breaking its rules: one line (a caller may prefix it, e.g. with the sweep's
    /// instance).
    #[error("overrides: {0}")]
    Overrides(#[from] OverridesError),
}

impl ConfigError {
    /// Whether the configuration file does not exist.
    pub fn is_not_found(&self) -> bool {
        matches!(self, ConfigError::Io { kind, .. } if *kind == std::io::ErrorKind::NotFound)
    }

    /// Whether an override names a muscle, joint or span the configuration does not have.
    pub fn is_unknown_name(&self) -> bool {
        matches!(self, ConfigError::Overrides(e) if e.is_unknown_name())
    }
}

/// The error of `parameter` = `value` breaking `rule`.
fn rule(parameter: String, value: impl ToString, rule: &'static str) -> ParamError {
    ParamError {
        parameter,
        value: value.to_string(),
        rule,
    }
}
