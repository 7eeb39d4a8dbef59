//! How a calibrated subject was calibrated: its `[calibration]` table.

use serde::{Deserialize, Serialize};

/// How a calibrated subject was calibrated (its `[calibration]` table).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CalibrationRecord {
    /// The trials' names.
    pub trials: Vec<String>,
    /// The degrees of freedom whose moments were matched.
    pub dofs: Vec<String>,
    /// The contractile model.
    pub model: String,
    /// The optimiser and its crate.
    pub optimiser: String,
    /// Its seed.
    pub seed: u64,
    /// Objective evaluations made.
    pub evaluations: usize,
    /// The objective (mean of `1 − R²`) at the start.
    pub start_cost: f64,
    /// The objective at the result.
    pub cost: f64,
    /// The calibrated parameters' values, by name.
    pub parameters: toml::Table,
    /// After each generation: `[evaluations, best cost]`.
    pub history: Vec<[f64; 2]>,
    /// Whether the calibration was stopped (Ctrl-C) before its evaluations were spent: the
    /// parameters are then the best found so far. Written only when true.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub stopped: bool,
}
