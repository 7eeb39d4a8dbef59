//! Curve sets: the normalised curves a Hill-type muscle is made of, from three sources
//! (docs/model.md §4b). A set is named in configurations by [`CurveSet::name`].
//!
//! - `paper`: the paper's force–length and force–velocity curves (§3), the default;
//! - [`degroote2016`]: DeGrooteFregly2016Muscle's curves as OpenSim 4.6 computes them;
//! - [`thelen2003`]: Thelen2003Muscle's curves as OpenSim 4.6 computes them (these two are
//!   modules of their own: their functions share their names);
//! - `millard2012`: Millard2012EquilibriumMuscle's quintic Bézier curves as OpenSim 4.6 builds
//!   them (`quintic_bezier`: [`SegmentedBezier`]);
//! - `rising_root`: the bracketed Newton solve the point-wise curves evaluate and invert with;
//! - `tabulated`: curves given as points ([`TabulatedCurve`]), by the cubic spline CEINMS
//!   interpolates its subject files' curves with;
//! - `overlap`, `force_velocity`: a muscle's active force–length and Hill force–velocity
//!   ([`HillForceVelocity`]) relations of its set, in SI units (the tendon's and the parallel
//!   element's are [`crate::physics::Tendon`] and `physics::parallel_element::ParallelElement`).
//!
//! A muscle names its set by the parameter `curves` ([`CurveSet`], defined with the parameters).
//!
//! [`CurveSet::evaluate`] evaluates one [`Curve`] of a set, with the set's default constants, at
//! a normalised argument: fibre length `l̃ = l_M/l_opt`, fibre velocity `ṽ` (lengthening
//! positive; 0 and 1 at ṽ = 0 and -1), tendon length `l̃_T = l_T/l_s`. The results are forces
//! as fractions of the maximum isometric force. crates/core/tests/reference/opensim_curves.csv holds
//! OpenSim's own values of the three OpenSim sets (scripts/opensim_curves.py).

pub mod degroote2016;
pub mod thelen2003;

pub(crate) mod force_velocity;
pub(crate) mod millard2012;
pub(crate) mod overlap;
pub(crate) mod paper;
pub(crate) mod quintic_bezier;
pub(crate) mod rising_root;
pub(crate) mod tabulated;

use crate::physics::limb_params::MuscleParams;
pub use crate::physics::{
    curves::{
        force_velocity::HillForceVelocity,
        quintic_bezier::SegmentedBezier,
        tabulated::{TabulatedCurve, TabulatedCurveError},
    },
    limb_params::curve_set::{CurveSet, UnknownCurveSet},
};

/// One normalised curve of a set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Curve {
    /// Active force–length multiplier at normalised fibre length l̃.
    ActiveForceLength,
    /// Passive (parallel element) force at normalised fibre length l̃.
    PassiveForceLength,
    /// Force–velocity multiplier at normalised fibre velocity ṽ (at full activation where the
    /// curve depends on activation, [`thelen2003`]).
    ForceVelocity,
    /// Tendon force at normalised tendon length l̃_T.
    TendonForceLength,
}

impl Curve {
    /// Every curve.
    pub const ALL: [Curve; 4] = [
        Curve::ActiveForceLength,
        Curve::PassiveForceLength,
        Curve::ForceVelocity,
        Curve::TendonForceLength,
    ];

    /// Its name, as in crates/core/tests/reference/opensim_curves.csv.
    pub fn name(self) -> &'static str {
        match self {
            Curve::ActiveForceLength => "active_force_length",
            Curve::PassiveForceLength => "passive_force_length",
            Curve::ForceVelocity => "force_velocity",
            Curve::TendonForceLength => "tendon_force_length",
        }
    }
}

impl CurveSet {
    /// `curve` of this set at the normalised argument `x`, with the set's default constants
    /// (the paper's: `MuscleParams::default()`'s width, shape and eccentric asymptote). `None`
    /// for the paper's passive and tendon curves, which are not normalised (docs/model.md §4),
    /// and for `tabulated`, whose curves are each muscle's own points.
    pub fn evaluate(self, curve: Curve, x: f64) -> Option<f64> {
        match self {
            CurveSet::Paper => evaluate_paper(curve, x),
            CurveSet::DeGroote2016 => Some(evaluate_degroote2016(curve, x)),
            CurveSet::Thelen2003 => Some(evaluate_thelen2003(curve, x)),
            CurveSet::Millard2012 => Some(evaluate_millard2012(curve, x)),
            // A tabulated muscle's curves are its own points: the set has no curves of its own.
            CurveSet::Tabulated => None,
        }
    }
}

fn evaluate_paper(curve: Curve, x: f64) -> Option<f64> {
    let p = MuscleParams::default();
    match curve {
        Curve::ActiveForceLength => Some(paper::active_force_length(x, p.fl_width, p.fl_shape)),
        Curve::ForceVelocity => Some(paper::force_velocity(x, p.eccentric_asymptote)),
        Curve::PassiveForceLength | Curve::TendonForceLength => None,
    }
}

fn evaluate_degroote2016(curve: Curve, x: f64) -> f64 {
    use degroote2016 as d;
    match curve {
        Curve::ActiveForceLength => d::active_force_length(x, d::DEFAULT_ACTIVE_FORCE_WIDTH_SCALE),
        Curve::PassiveForceLength => {
            d::passive_force_length(x, d::DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE)
        }
        Curve::ForceVelocity => d::force_velocity(x),
        Curve::TendonForceLength => {
            let k_t = d::tendon_shape(d::DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE);
            d::tendon_force_length(x, k_t)
        }
    }
}

fn evaluate_thelen2003(curve: Curve, x: f64) -> f64 {
    use thelen2003 as t;
    match curve {
        Curve::ActiveForceLength => t::active_force_length(x, t::DEFAULT_KSHAPE_ACTIVE),
        Curve::PassiveForceLength => {
            t::passive_force_length(x, t::DEFAULT_FMAX_MUSCLE_STRAIN, t::DEFAULT_KSHAPE_PASSIVE)
        }
        Curve::ForceVelocity => t::force_velocity(x, 1.0, &t::ForceVelocityShape::default()),
        Curve::TendonForceLength => t::tendon_force_length(x, t::DEFAULT_FMAX_TENDON_STRAIN),
    }
}

fn evaluate_millard2012(curve: Curve, x: f64) -> f64 {
    use millard2012 as m;
    let shape = m::Shape::DEFAULT;
    let built = match curve {
        Curve::ActiveForceLength => m::active_force_length_curve(shape.active_minimum),
        Curve::PassiveForceLength => {
            m::passive_force_length_curve(m::DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE)
        }
        Curve::ForceVelocity => m::force_velocity_curve(
            shape.concentric_slope_at_vmax,
            shape.eccentric_slope_at_vmax,
        ),
        Curve::TendonForceLength => {
            m::tendon_force_length_curve(m::DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE)
        }
    };
    // The defaults always form corners (tests below).
    built.map_or(f64::NAN, |c| c.value(x))
}

#[cfg(test)]
mod tests;
