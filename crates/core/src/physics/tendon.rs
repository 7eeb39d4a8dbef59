//! The series elastic element, the tendon (docs/model.md §4, paper eqs. 4–5), with the curves of
//! the muscle's set (§4b).

use crate::physics::curves::quintic_bezier::SegmentedBezier;
use crate::physics::curves::tabulated::{self, TabulatedCurve};
use crate::physics::curves::{degroote2016, millard2012, thelen2003, CurveSet};
use crate::physics::limb_params::MuscleParams;
use crate::physics::spring::ExpLinearSpring;
use std::sync::Arc;

/// The tendon's spring, with l_tc derived by force continuity unless configured.
pub fn tendon(p: &MuscleParams) -> ExpLinearSpring {
    ExpLinearSpring {
        k_l: p.k_tl,
        k_e: p.k_te,
        l_s: p.l_ts,
        l_c: p.l_tc(),
        f_c: p.f_tc,
        k: p.k_t,
    }
}

/// The tendon strain at one normalised force in force: the configured `tendon_strain`, else
/// the curve set's default (DeGroote 2016 and Millard 2012: 0.049, Thelen 2003: 0.04; NaN for the
/// paper's set, whose tendon has none, and for tabulated curves, whose points set it).
pub fn tendon_strain(p: &MuscleParams) -> f64 {
    let default = match p.curves {
        CurveSet::Paper | CurveSet::Tabulated => f64::NAN,
        CurveSet::DeGroote2016 => degroote2016::DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE,
        CurveSet::Thelen2003 => thelen2003::DEFAULT_FMAX_TENDON_STRAIN,
        CurveSet::Millard2012 => millard2012::DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE,
    };
    p.tendon_strain.unwrap_or(default)
}

/// A muscle's tendon: the paper's spring, or an OpenSim set's normalised curve scaled by Fmax and
/// the slack length, `F_T = Fmax f_T(l_T / l_s)`.
#[derive(Debug, Clone, PartialEq)]
pub enum Tendon {
    /// The paper's exponential-then-linear spring (§4).
    Paper(ExpLinearSpring),
    /// DeGroote 2016's exponential, not clipped: slightly negative when slack.
    DeGroote2016 {
        /// Fmax, N.
        f_max: f64,
        /// Slack length l_s, m.
        l_s: f64,
        /// Shape kT from the tendon strain ([`degroote2016::tendon_shape`]).
        k_t: f64,
    },
    /// Thelen 2003's toe and linear part, zero when slack.
    Thelen2003 {
        /// Fmax, N.
        f_max: f64,
        /// Slack length l_s, m.
        l_s: f64,
        /// Strain at one normalised force ε₀T.
        strain: f64,
    },
    /// Millard 2012's quintic Bézier curve, zero when slack.
    Millard2012 {
        /// Fmax, N.
        f_max: f64,
        /// Slack length l_s, m.
        l_s: f64,
        /// The curve of l̃_T (`millard2012::tendon_force_length_curve`).
        curve: Arc<SegmentedBezier>,
    },
    /// The muscle's own points of force against strain `l_T / l_s - 1`, interpolated as CEINMS
    /// does, a strain below 0 taken as 0 as CEINMS takes it (lib/NMSmodel/Lloyd2003Muscle
    /// `calculateTendonStrain`): a slack tendon carries the curve's value at 0 and no
    /// stiffness, whatever the spline does in the padding below; its energy from slack length.
    Tabulated {
        /// Fmax, N.
        f_max: f64,
        /// Slack length l_s, m.
        l_s: f64,
        /// The curve of the strain.
        curve: Arc<TabulatedCurve>,
    },
}

impl Tendon {
    /// The tendon of the muscle's curve set.
    pub fn new(p: &MuscleParams) -> Self {
        let (f_max, l_s) = (p.f_max, p.l_ts);
        match p.curves {
            CurveSet::Paper => Tendon::Paper(tendon(p)),
            CurveSet::DeGroote2016 => Tendon::DeGroote2016 {
                f_max,
                l_s,
                k_t: degroote2016::tendon_shape(tendon_strain(p)),
            },
            CurveSet::Thelen2003 => Tendon::Thelen2003 {
                f_max,
                l_s,
                strain: tendon_strain(p),
            },
            CurveSet::Tabulated => Tendon::Tabulated {
                f_max,
                l_s,
                curve: Arc::new(tabulated::of_points(
                    p.tabulated.as_ref().map(|t| &t.tendon_force_strain),
                )),
            },
            CurveSet::Millard2012 => Tendon::Millard2012 {
                f_max,
                l_s,
                curve: Arc::new(
                    millard2012::tendon_force_length_curve(tendon_strain(p))
                        .unwrap_or_else(|_| SegmentedBezier::undefined()),
                ),
            },
        }
    }

    /// Tension at tendon length `l`, N.
    #[inline(always)]
    pub fn force(&self, l: f64) -> f64 {
        match *self {
            Tendon::Paper(ref s) => s.force(l),
            Tendon::DeGroote2016 { f_max, l_s, k_t } => {
                f_max * degroote2016::tendon_force_length(l / l_s, k_t)
            }
            Tendon::Thelen2003 { f_max, l_s, strain } => {
                f_max * thelen2003::tendon_force_length(l / l_s, strain)
            }
            Tendon::Millard2012 {
                f_max,
                l_s,
                ref curve,
            } => f_max * curve.value(l / l_s),
            Tendon::Tabulated {
                f_max,
                l_s,
                ref curve,
            } => f_max * curve.value((l / l_s - 1.0).max(0.0)),
        }
    }

    /// Stiffness dF/dl, N/m.
    #[inline(always)]
    pub fn stiffness(&self, l: f64) -> f64 {
        match *self {
            Tendon::Paper(ref s) => s.stiffness(l),
            Tendon::DeGroote2016 { f_max, l_s, k_t } => {
                f_max / l_s * degroote2016::tendon_force_length_derivative(l / l_s, k_t)
            }
            Tendon::Thelen2003 { f_max, l_s, strain } => {
                f_max / l_s * thelen2003::tendon_force_length_derivative(l / l_s, strain)
            }
            Tendon::Millard2012 {
                f_max,
                l_s,
                ref curve,
            } => f_max / l_s * curve.slope(l / l_s),
            Tendon::Tabulated {
                f_max,
                l_s,
                ref curve,
            } => {
                let strain = l / l_s - 1.0;
                if strain < 0.0 {
                    0.0
                } else {
                    f_max / l_s * curve.slope(strain)
                }
            }
        }
    }

    /// Strain energy `∫_{l_s}^{l} F(x) dx`, J (for DeGroote's negative force below slack length
    /// also positive, as OpenSim has it).
    pub fn energy(&self, l: f64) -> f64 {
        match *self {
            Tendon::Paper(ref s) => s.energy(l),
            Tendon::DeGroote2016 { f_max, l_s, k_t } => {
                f_max * l_s * degroote2016::tendon_force_length_integral(l / l_s, k_t)
            }
            Tendon::Thelen2003 { f_max, l_s, strain } => {
                f_max * l_s * thelen2003::tendon_force_length_integral(l / l_s, strain)
            }
            Tendon::Millard2012 {
                f_max,
                l_s,
                ref curve,
            } => f_max * l_s * curve.integral(l / l_s),
            Tendon::Tabulated {
                f_max,
                l_s,
                ref curve,
            } => f_max * l_s * curve.integral_between(0.0, (l / l_s - 1.0).max(0.0)),
        }
    }

    /// Length at which the tendon carries `force`, m; the slack length for a force <= 0 (a
    /// force-driven tendon transmits no push, docs/model.md §5).
    pub fn length_at_force(&self, force: f64) -> f64 {
        match *self {
            Tendon::Paper(ref s) => s.length_at_force(force),
            Tendon::DeGroote2016 { l_s, .. }
            | Tendon::Thelen2003 { l_s, .. }
            | Tendon::Millard2012 { l_s, .. }
            | Tendon::Tabulated { l_s, .. }
                if force <= 0.0 =>
            {
                l_s
            }
            Tendon::DeGroote2016 { f_max, l_s, k_t } => {
                l_s * degroote2016::tendon_force_length_inverse(force / f_max, k_t)
            }
            Tendon::Thelen2003 { f_max, l_s, strain } => {
                l_s * thelen2003::tendon_force_length_inverse(force / f_max, strain)
            }
            Tendon::Millard2012 {
                f_max,
                l_s,
                ref curve,
            } => l_s * curve.argument_at(force / f_max),
            Tendon::Tabulated {
                f_max,
                l_s,
                ref curve,
            } => l_s * (1.0 + curve.argument_at(force / f_max)),
        }
    }
}
