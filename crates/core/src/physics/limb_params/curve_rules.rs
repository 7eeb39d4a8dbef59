//! The rules of a muscle's curve-set keys (docs/configuration.md "Curve sets"): the strains
//! only with an OpenSim set, the `tabulated` table with `curves = "tabulated"` only and needed
//! there, each set's shape constants only with that set and within OpenSim's ranges. The
//! tabulated points themselves are checked by the configuration (`crate::config`), which builds
//! their curves.

use super::curve_set::CurveSet;
use super::{Checker, MuscleParams};

/// The largest passive strain Millard 2012's passive curve can be built with: its foot's slope
/// (`stiffness_at_low_force`, 0.2) must stay below the mean slope `1 / strain`
/// (OpenSim's `createFiberForceLengthCurve` check).
const MILLARD_MAX_PASSIVE_STRAIN: f64 = 5.0;

impl MuscleParams {
    /// The curve-set rules: `tendon_strain` and `passive_strain` only with an OpenSim set, and
    /// positive; each set's shape constants only with that set.
    pub(super) fn validate_curves(&self, c: &mut Checker<'_>) {
        let strains = [
            (
                "tendon_strain",
                self.tendon_strain,
                "applies to an OpenSim curve set only (the paper's tendon is set by k_te, k_tl, \
                 k_t)",
            ),
            (
                "passive_strain",
                self.passive_strain,
                "applies to an OpenSim curve set only (the paper's parallel element is set by \
                 k_me, k_ml, k_m)",
            ),
        ];
        for (name, value, paper_rule) in strains {
            let Some(v) = value else { continue };
            if self.curves.is_paper() {
                c.fail(name, v, paper_rule);
            } else if self.curves == CurveSet::Tabulated {
                c.fail(
                    name,
                    v,
                    "does not apply to tabulated curves (their points set it)",
                );
            } else if name == "passive_strain"
                && self.curves == CurveSet::Millard2012
                && !(v > 0.0 && v < MILLARD_MAX_PASSIVE_STRAIN)
            {
                c.fail(
                    name,
                    v,
                    "must be > 0 and < 5 for curves = \"millard2012\" (its passive curve's foot, \
                     slope 0.2, must be shallower than its mean slope 1/strain)",
                );
            } else {
                c.positive(name, v);
            }
        }
        match (&self.tabulated, self.curves == CurveSet::Tabulated) {
            (None, true) => c.fail(
                "tabulated",
                "(none)",
                "is needed with curves = \"tabulated\" (its four curves as [x, y] points)",
            ),
            (Some(_), false) => c.fail(
                "tabulated",
                "(a table)",
                "applies to curves = \"tabulated\" only",
            ),
            _ => {}
        }
        // Each set's own shape constants, only with that set, within OpenSim's ranges.
        let shapes = [
            (
                "active_force_width_scale",
                self.active_force_width_scale,
                CurveSet::DeGroote2016,
            ),
            ("kshape_active", self.kshape_active, CurveSet::Thelen2003),
            ("kshape_passive", self.kshape_passive, CurveSet::Thelen2003),
            ("af", self.af, CurveSet::Thelen2003),
            ("flen", self.flen, CurveSet::Thelen2003),
        ];
        for (name, value, set) in shapes {
            let Some(v) = value else { continue };
            if self.curves != set {
                c.fail(
                    name,
                    v,
                    match set {
                        CurveSet::DeGroote2016 => "applies to curves = \"degroote2016\" only",
                        _ => "applies to curves = \"thelen2003\" only",
                    },
                );
            } else if name == "active_force_width_scale" {
                if !(v.is_finite() && v >= 1.0) {
                    c.fail(name, v, "must be >= 1 (OpenSim's rule)");
                }
            } else if name == "flen" {
                if !(v.is_finite() && v > 1.0) {
                    c.fail(name, v, "must be > 1 (the eccentric asymptote, normalised)");
                }
            } else {
                c.positive(name, v);
            }
        }
    }
}
