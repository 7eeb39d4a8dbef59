//! The parallel elastic element and its damper (docs/model.md §4, paper eqs. 6–7), with the
//! curves of the muscle's set (§4b).

use crate::physics::curves::quintic_bezier::SegmentedBezier;
use crate::physics::curves::tabulated::{self, TabulatedCurve};
use crate::physics::curves::{degroote2016, millard2012, thelen2003, CurveSet};
use crate::physics::limb_params::MuscleParams;
use crate::physics::spring::ExpLinearSpring;
use std::sync::Arc;

/// The parallel element's spring F_P(l_m).
pub fn parallel_spring(p: &MuscleParams) -> ExpLinearSpring {
    ExpLinearSpring {
        k_l: p.k_ml,
        k_e: p.k_me,
        l_s: p.l_ms,
        l_c: p.l_mc,
        f_c: p.f_mc,
        k: p.k_m,
    }
}

/// The passive fibre strain at one normalised force in force: the configured `passive_strain`,
/// else the curve set's default (0.6 for DeGroote's and Thelen's, 0.7 for Millard's; NaN for the
/// paper's set, whose spring has none, and for tabulated curves, whose points set it).
pub fn passive_strain(p: &MuscleParams) -> f64 {
    let default = match p.curves {
        CurveSet::Paper | CurveSet::Tabulated => f64::NAN,
        CurveSet::DeGroote2016 => degroote2016::DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE,
        CurveSet::Thelen2003 => thelen2003::DEFAULT_FMAX_MUSCLE_STRAIN,
        CurveSet::Millard2012 => millard2012::DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE,
    };
    p.passive_strain.unwrap_or(default)
}

/// A muscle's parallel elastic element: the paper's spring, or an OpenSim set's normalised
/// passive curve scaled by Fmax and l_opt, `F_PE = Fmax f_PE(l_m / l_opt)`.
#[derive(Debug, Clone, PartialEq)]
pub enum ParallelElement {
    /// The paper's exponential-then-linear spring (§4).
    Paper(ExpLinearSpring),
    /// DeGroote 2016's exponential: zero at 0.2 l_opt, negative below.
    DeGroote2016 {
        /// Fmax, N.
        f_max: f64,
        /// Optimal fibre length l_opt, m.
        l_opt: f64,
        /// Passive strain at one normalised force e0.
        strain: f64,
    },
    /// Thelen 2003's exponential: zero up to l_opt.
    Thelen2003 {
        /// Fmax, N.
        f_max: f64,
        /// Optimal fibre length l_opt, m.
        l_opt: f64,
        /// Passive strain at one normalised force ε₀M.
        strain: f64,
        /// Passive shape k_PE (`KshapePassive`).
        kshape: f64,
    },
    /// Millard 2012's quintic Bézier curve: zero up to l_opt.
    Millard2012 {
        /// Fmax, N.
        f_max: f64,
        /// Optimal fibre length l_opt, m.
        l_opt: f64,
        /// The curve of l̃ (`millard2012::passive_force_length_curve`).
        curve: Arc<SegmentedBezier>,
    },
    /// The muscle's own points, interpolated as CEINMS does; its energy from l_opt.
    Tabulated {
        /// Fmax, N.
        f_max: f64,
        /// Optimal fibre length l_opt, m.
        l_opt: f64,
        /// The curve of l̃.
        curve: Arc<TabulatedCurve>,
    },
}

impl ParallelElement {
    /// The parallel element of the muscle's curve set.
    pub fn new(p: &MuscleParams) -> Self {
        let (f_max, l_opt) = (p.f_max, p.l_opt);
        match p.curves {
            CurveSet::Paper => ParallelElement::Paper(parallel_spring(p)),
            CurveSet::DeGroote2016 => ParallelElement::DeGroote2016 {
                f_max,
                l_opt,
                strain: passive_strain(p),
            },
            CurveSet::Thelen2003 => ParallelElement::Thelen2003 {
                f_max,
                l_opt,
                strain: passive_strain(p),
                kshape: p
                    .kshape_passive
                    .unwrap_or(thelen2003::DEFAULT_KSHAPE_PASSIVE),
            },
            CurveSet::Tabulated => ParallelElement::Tabulated {
                f_max,
                l_opt,
                curve: Arc::new(tabulated::of_points(
                    p.tabulated.as_ref().map(|t| &t.passive_force_length),
                )),
            },
            CurveSet::Millard2012 => ParallelElement::Millard2012 {
                f_max,
                l_opt,
                curve: Arc::new(
                    millard2012::passive_force_length_curve(passive_strain(p))
                        .unwrap_or_else(|_| SegmentedBezier::undefined()),
                ),
            },
        }
    }

    /// Tension at fibre length `l_m`, N.
    #[inline(always)]
    pub fn force(&self, l_m: f64) -> f64 {
        match *self {
            ParallelElement::Paper(ref s) => s.force(l_m),
            ParallelElement::DeGroote2016 {
                f_max,
                l_opt,
                strain,
            } => f_max * degroote2016::passive_force_length(l_m / l_opt, strain),
            ParallelElement::Thelen2003 {
                f_max,
                l_opt,
                strain,
                kshape,
            } => f_max * thelen2003::passive_force_length(l_m / l_opt, strain, kshape),
            ParallelElement::Millard2012 {
                f_max,
                l_opt,
                ref curve,
            } => f_max * curve.value(l_m / l_opt),
            ParallelElement::Tabulated {
                f_max,
                l_opt,
                ref curve,
            } => f_max * curve.value(l_m / l_opt),
        }
    }

    /// Stiffness dF/dl_m, N/m.
    #[inline]
    pub fn stiffness(&self, l_m: f64) -> f64 {
        match *self {
            ParallelElement::Paper(ref s) => s.stiffness(l_m),
            ParallelElement::DeGroote2016 {
                f_max,
                l_opt,
                strain,
            } => f_max / l_opt * degroote2016::passive_force_length_derivative(l_m / l_opt, strain),
            ParallelElement::Thelen2003 {
                f_max,
                l_opt,
                strain,
                kshape,
            } => {
                let x = l_m / l_opt;
                f_max / l_opt * thelen2003::passive_force_length_derivative(x, strain, kshape)
            }
            ParallelElement::Millard2012 {
                f_max,
                l_opt,
                ref curve,
            } => f_max / l_opt * curve.slope(l_m / l_opt),
            ParallelElement::Tabulated {
                f_max,
                l_opt,
                ref curve,
            } => f_max / l_opt * curve.slope(l_m / l_opt),
        }
    }

    /// Strain energy, J: `∫ F` from the length where the force is zero (the paper's, Thelen's
    /// and Millard's slack length, l_ms and l_opt; DeGroote's 0.2 l_opt, as OpenSim has it).
    pub fn energy(&self, l_m: f64) -> f64 {
        match *self {
            ParallelElement::Paper(ref s) => s.energy(l_m),
            ParallelElement::DeGroote2016 {
                f_max,
                l_opt,
                strain,
            } => f_max * l_opt * degroote2016::passive_force_length_integral(l_m / l_opt, strain),
            ParallelElement::Thelen2003 {
                f_max,
                l_opt,
                strain,
                kshape,
            } => {
                let x = l_m / l_opt;
                f_max * l_opt * thelen2003::passive_force_length_integral(x, strain, kshape)
            }
            ParallelElement::Millard2012 {
                f_max,
                l_opt,
                ref curve,
            } => f_max * l_opt * curve.integral(l_m / l_opt),
            ParallelElement::Tabulated {
                f_max,
                l_opt,
                ref curve,
            } => f_max * l_opt * curve.integral_between(1.0, l_m / l_opt),
        }
    }

    /// Fibre length at which the element carries `force`, m; for a force <= 0 the length where
    /// its force is zero (l_ms, 0.2 l_opt for DeGroote's, l_opt for Thelen's and Millard's).
    pub fn length_at_force(&self, force: f64) -> f64 {
        match *self {
            ParallelElement::Paper(ref s) => s.length_at_force(force),
            ParallelElement::DeGroote2016 {
                f_max,
                l_opt,
                strain,
            } => {
                let f = force.max(0.0) / f_max;
                l_opt * degroote2016::passive_force_length_inverse(f, strain)
            }
            ParallelElement::Thelen2003 {
                f_max,
                l_opt,
                strain,
                kshape,
            } => {
                let f = force / f_max;
                l_opt * thelen2003::passive_force_length_inverse(f, strain, kshape)
            }
            ParallelElement::Millard2012 {
                f_max,
                l_opt,
                ref curve,
            } => l_opt * curve.argument_at(force.max(0.0) / f_max),
            ParallelElement::Tabulated {
                f_max,
                l_opt,
                ref curve,
            } => l_opt * curve.argument_at(force.max(0.0) / f_max),
        }
    }
}

/// Parallel damper `F_d = B_m v`, N (v: lengthening velocity, m/s).
pub(crate) fn damper_force(b_m: f64, v: f64) -> f64 {
    b_m * v
}
