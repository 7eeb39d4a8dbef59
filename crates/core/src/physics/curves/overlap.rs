//! A muscle's active force–length relation of its curve set (docs/model.md §3, §4b): the
//! overlap factor λ(l_m) that every contractile model reads, of the fibre length in m.

use crate::physics::contractile::force_length::{force_length, force_length_slope};
use crate::physics::curves::quintic_bezier::SegmentedBezier;
use crate::physics::curves::tabulated::{self, TabulatedCurve};
use crate::physics::curves::{degroote2016, millard2012, thelen2003, CurveSet};
use crate::physics::limb_params::{ForceLengthShape, MuscleParams};
use std::sync::Arc;

/// A muscle's active force–length relation, the filament-overlap factor λ(l_m) every contractile
/// model reads (docs/model.md §3, §4b): the paper's eq. (3), or an OpenSim set's curve at
/// `l_m / l_opt`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ActiveForceLength {
    /// The paper's parabola or Gaussian ([`force_length`]).
    Paper {
        /// Optimal fibre length, m.
        l_opt: f64,
        /// Width w.
        width: f64,
        /// Shape.
        shape: ForceLengthShape,
    },
    /// DeGroote 2016's three Gaussian-like terms.
    DeGroote2016 {
        /// Optimal fibre length, m.
        l_opt: f64,
        /// Width scale (`active_force_width_scale`).
        width_scale: f64,
    },
    /// Thelen 2003's Gaussian.
    Thelen2003 {
        /// Optimal fibre length, m.
        l_opt: f64,
        /// Shape γ (`KshapeActive`).
        kshape: f64,
    },
    /// Millard 2012's quintic Bézier curve.
    Millard2012 {
        /// Optimal fibre length, m.
        l_opt: f64,
        /// The curve of l̃ ([`millard2012::active_force_length_curve`]).
        curve: Arc<SegmentedBezier>,
    },
    /// The muscle's own points, interpolated as CEINMS does.
    Tabulated {
        /// Optimal fibre length, m.
        l_opt: f64,
        /// The curve of l̃.
        curve: Arc<TabulatedCurve>,
    },
}

impl ActiveForceLength {
    /// The relation of the muscle's curve set.
    pub(crate) fn new(p: &MuscleParams) -> Self {
        let l_opt = p.l_opt;
        match p.curves {
            CurveSet::Paper => ActiveForceLength::Paper {
                l_opt,
                width: p.fl_width,
                shape: p.fl_shape,
            },
            CurveSet::DeGroote2016 => ActiveForceLength::DeGroote2016 {
                l_opt,
                width_scale: p
                    .active_force_width_scale
                    .unwrap_or(degroote2016::DEFAULT_ACTIVE_FORCE_WIDTH_SCALE),
            },
            CurveSet::Thelen2003 => ActiveForceLength::Thelen2003 {
                l_opt,
                kshape: p.kshape_active.unwrap_or(thelen2003::DEFAULT_KSHAPE_ACTIVE),
            },
            CurveSet::Tabulated => ActiveForceLength::Tabulated {
                l_opt,
                curve: Arc::new(tabulated::of_points(
                    p.tabulated.as_ref().map(|t| &t.active_force_length),
                )),
            },
            CurveSet::Millard2012 => ActiveForceLength::Millard2012 {
                l_opt,
                curve: Arc::new(
                    millard2012::active_force_length_curve(
                        millard2012::Shape::of(p).active_minimum,
                    )
                    .unwrap_or_else(|_| SegmentedBezier::undefined()),
                ),
            },
        }
    }

    /// λ(l_m), dimensionless.
    #[inline(always)]
    pub(crate) fn at(&self, l_m: f64) -> f64 {
        match *self {
            ActiveForceLength::Paper {
                l_opt,
                width,
                shape,
            } => force_length(l_m, l_opt, width, shape),
            ActiveForceLength::DeGroote2016 { l_opt, width_scale } => {
                degroote2016::active_force_length(l_m / l_opt, width_scale)
            }
            ActiveForceLength::Thelen2003 { l_opt, kshape } => {
                thelen2003::active_force_length(l_m / l_opt, kshape)
            }
            ActiveForceLength::Millard2012 { l_opt, ref curve } => curve.value(l_m / l_opt),
            ActiveForceLength::Tabulated { l_opt, ref curve } => curve.value(l_m / l_opt),
        }
    }

    /// dλ/dl_m, 1/m.
    pub(crate) fn slope(&self, l_m: f64) -> f64 {
        match *self {
            ActiveForceLength::Paper {
                l_opt,
                width,
                shape,
            } => force_length_slope(l_m, l_opt, width, shape),
            ActiveForceLength::DeGroote2016 { l_opt, width_scale } => {
                degroote2016::active_force_length_derivative(l_m / l_opt, width_scale) / l_opt
            }
            ActiveForceLength::Thelen2003 { l_opt, kshape } => {
                thelen2003::active_force_length_derivative(l_m / l_opt, kshape) / l_opt
            }
            ActiveForceLength::Millard2012 { l_opt, ref curve } => curve.slope(l_m / l_opt) / l_opt,
            ActiveForceLength::Tabulated { l_opt, ref curve } => curve.slope(l_m / l_opt) / l_opt,
        }
    }
}
