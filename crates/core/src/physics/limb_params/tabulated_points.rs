//! The points of a muscle's tabulated curves (`curves = "tabulated"`, docs/model.md §4b,
//! docs/configuration.md "Curve sets"): four lists of `[x, y]` points, as a CEINMS subject gives
//! them; `crate::physics::curves::tabulated` interpolates them.

use serde::{Deserialize, Serialize};

/// A curve as points `[x, y]`, x rising.
pub type Points = Vec<[f64; 2]>;

/// The four curves of a tabulated muscle, each normalised as CEINMS normalises it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TabulatedCurves {
    /// Active force–length: `[l_M / l_opt, force / Fmax]`.
    pub active_force_length: Points,
    /// Passive force–length: `[l_M / l_opt, force / Fmax]`.
    pub passive_force_length: Points,
    /// Force–velocity: `[v_M / vmax (lengthening positive), multiplier]`.
    pub force_velocity: Points,
    /// Tendon force–strain: `[l_T / l_s - 1, force / Fmax]`.
    pub tendon_force_strain: Points,
}

impl TabulatedCurves {
    /// Each curve with its key, in the order of the table.
    pub fn named(&self) -> [(&'static str, &Points); 4] {
        [
            ("active_force_length", &self.active_force_length),
            ("passive_force_length", &self.passive_force_length),
            ("force_velocity", &self.force_velocity),
            ("tendon_force_strain", &self.tendon_force_strain),
        ]
    }
}

/// A curve's abscissae and ordinates, apart.
pub(crate) fn split(points: &Points) -> (Vec<f64>, Vec<f64>) {
    points.iter().map(|&[x, y]| (x, y)).unzip()
}
