//! The curves of Millard et al. (2013), J Biomech Eng 135(2): 021005, as OpenSim 4.6's
//! Millard2012EquilibriumMuscle builds them by default (`ActiveForceLengthCurve`,
//! `ForceVelocityCurve`, `FiberForceLengthCurve`, `TendonForceLengthCurve`, through
//! `SmoothSegmentedFunctionFactory`), docs/model.md §4b: segmented quintic Bézier curves
//! ([`super::quintic_bezier`]) of the same normalised quantities as the other OpenSim sets
//! (fibre length l̃ = l_M/l_opt, velocity ṽ in vmax, lengthening positive, tendon length
//! l̃_T = l_T/l_s, forces in Fmax). Each builder lays out its corners as OpenSim's factory does;
//! the constants are the curves' default properties, each with its OpenSim name.
//!
//! Inside a muscle OpenSim adapts two of them to the formulation
//! (`Millard2012EquilibriumMuscle::extendFinalizeFromProperties`), and so does a muscle here
//! (`Shape::of`): the classic Hill formulation (an equilibrium fibre on an elastic tendon
//! without damper), whose fibre velocity comes from inverting the force–velocity curve, keeps an
//! active floor of 0.1 and gives the force–velocity curve end slopes of half the near slopes, so
//! that it stays invertible; every other formulation (damped, rigid tendon, a fibre with mass)
//! has an active floor of 0 and flat ends.

use super::quintic_bezier::{
    corner_control_points, scaled_curviness, ControlPoints, NotACorner, SegmentedBezier,
};
use crate::physics::limb_params::formulation::{FibreKind, TendonKind};
use crate::physics::limb_params::MuscleParams;

/// `min_norm_active_fiber_length`: where the active curve leaves its floor.
pub(crate) const ACTIVE_MIN_NORM_FIBER_LENGTH: f64 = 0.4441;
/// `transition_norm_fiber_length`: where the steep ascending limb turns shallow.
pub(crate) const ACTIVE_TRANSITION_NORM_FIBER_LENGTH: f64 = 0.73;
/// `max_norm_active_fiber_length`: where the descending limb reaches its floor.
pub(crate) const ACTIVE_MAX_NORM_FIBER_LENGTH: f64 = 1.8123;
/// `shallow_ascending_slope`, per normalised length.
pub(crate) const ACTIVE_SHALLOW_ASCENDING_SLOPE: f64 = 0.8616;
/// `minimum_value`: the active curve's floor (never zero, so an equilibrium fibre always has
/// some active force to balance with).
pub(crate) const ACTIVE_MINIMUM_VALUE: f64 = 0.1;
/// The active curve's curviness, fixed by `ActiveForceLengthCurve` (not a property).
pub(crate) const ACTIVE_CURVINESS: f64 = 1.0;

/// `concentric_slope_at_vmax`.
pub(crate) const FV_CONCENTRIC_SLOPE_AT_VMAX: f64 = 0.0;
/// `concentric_slope_near_vmax`.
pub(crate) const FV_CONCENTRIC_SLOPE_NEAR_VMAX: f64 = 0.25;
/// `isometric_slope`.
pub(crate) const FV_ISOMETRIC_SLOPE: f64 = 5.0;
/// `eccentric_slope_at_vmax`.
pub(crate) const FV_ECCENTRIC_SLOPE_AT_VMAX: f64 = 0.0;
/// `eccentric_slope_near_vmax`.
pub(crate) const FV_ECCENTRIC_SLOPE_NEAR_VMAX: f64 = 0.15;
/// `max_eccentric_velocity_force_multiplier`.
pub(crate) const FV_MAX_ECCENTRIC_MULTIPLIER: f64 = 1.4;
/// `concentric_curviness`.
pub(crate) const FV_CONCENTRIC_CURVINESS: f64 = 0.6;
/// `eccentric_curviness`.
pub(crate) const FV_ECCENTRIC_CURVINESS: f64 = 0.9;
/// The force–velocity curve's inner knots, ṽ = ∓0.9 (fixed by the factory).
pub(crate) const FV_NEAR_VMAX: f64 = 0.9;

/// `strain_at_zero_force` of the passive curve.
pub(crate) const PASSIVE_STRAIN_AT_ZERO_FORCE: f64 = 0.0;
/// Default `strain_at_one_norm_force` of the passive curve.
pub(crate) const DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE: f64 = 0.7;
/// The passive curve's slope at low force, the default `stiffness_at_low_force`.
pub(crate) const PASSIVE_STIFFNESS_AT_LOW_FORCE: f64 = 0.2;
/// The passive curve's default stiffness at one normalised force, times its strain range:
/// `stiffness_at_one_norm_force = 2 / (e1 - e0)`.
pub(crate) const PASSIVE_STIFFNESS_TIMES_STRAIN: f64 = 2.0;
/// The passive curve's default curviness.
pub(crate) const PASSIVE_CURVINESS: f64 = 0.75;

/// Default `strain_at_one_norm_force` of the tendon curve.
pub(crate) const DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE: f64 = 0.049;
/// The tendon's default stiffness at one normalised force, times its strain: `1.375 / e0`
/// ("agrees well with Maganaris and Paul (2002) …", TendonForceLengthCurve).
pub(crate) const TENDON_STIFFNESS_TIMES_STRAIN: f64 = 1.375;
/// The tendon's default `norm_force_at_toe_end`.
pub(crate) const TENDON_NORM_FORCE_AT_TOE_END: f64 = 2.0 / 3.0;
/// The tendon's default curviness.
pub(crate) const TENDON_CURVINESS: f64 = 0.5;

/// The constants a muscle's formulation sets (the module's header).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Shape {
    /// The active curve's floor (`minimum_value`).
    pub active_minimum: f64,
    /// The force–velocity curve's slope at ṽ = −1 and beyond.
    pub concentric_slope_at_vmax: f64,
    /// The force–velocity curve's slope at ṽ = 1 and beyond.
    pub eccentric_slope_at_vmax: f64,
}

impl Shape {
    /// The curves' default properties, as OpenSim's curve components stand on their own.
    pub(crate) const DEFAULT: Shape = Shape {
        active_minimum: ACTIVE_MINIMUM_VALUE,
        concentric_slope_at_vmax: FV_CONCENTRIC_SLOPE_AT_VMAX,
        eccentric_slope_at_vmax: FV_ECCENTRIC_SLOPE_AT_VMAX,
    };

    /// The classic Hill formulation's: floor 0.1, end slopes half the near slopes.
    pub(crate) const CLASSIC: Shape = Shape {
        active_minimum: ACTIVE_MINIMUM_VALUE,
        concentric_slope_at_vmax: 0.5 * FV_CONCENTRIC_SLOPE_NEAR_VMAX,
        eccentric_slope_at_vmax: 0.5 * FV_ECCENTRIC_SLOPE_NEAR_VMAX,
    };

    /// Every other formulation's: floor 0, flat ends.
    pub(crate) const DAMPED: Shape = Shape {
        active_minimum: 0.0,
        concentric_slope_at_vmax: 0.0,
        eccentric_slope_at_vmax: 0.0,
    };

    /// The shape of a muscle's formulation: [`Shape::CLASSIC`] for an equilibrium fibre on an
    /// elastic tendon without damper (b_m = 0), else [`Shape::DAMPED`].
    pub(crate) fn of(p: &MuscleParams) -> Shape {
        let classic =
            p.fibre == FibreKind::Equilibrium && p.tendon == TendonKind::Elastic && p.b_m == 0.0;
        if classic {
            Shape::CLASSIC
        } else {
            Shape::DAMPED
        }
    }
}

/// A corner's end: (x, y, dy/dx).
type End = (f64, f64, f64);

fn corners(
    ends: &[End],
    curviness: &[f64],
) -> Result<Vec<(ControlPoints, ControlPoints)>, NotACorner> {
    ends.windows(2)
        .zip(curviness)
        .map(|(pair, &c)| corner_control_points(pair[0], pair[1], c))
        .collect()
}

/// The active force–length curve f_L(l̃): five corners, from the floor at
/// `ACTIVE_MIN_NORM_FIBER_LENGTH` up the steep and the shallow ascending limbs to 1 at l̃ = 1,
/// down to the floor at `ACTIVE_MAX_NORM_FIBER_LENGTH`; flat at the floor `ylow` outside
/// (`createFiberActiveForceLengthCurve`).
pub(crate) fn active_force_length_curve(ylow: f64) -> Result<SegmentedBezier, NotACorner> {
    let (x0, x1, x2, x3) = (
        ACTIVE_MIN_NORM_FIBER_LENGTH,
        ACTIVE_TRANSITION_NORM_FIBER_LENGTH,
        1.0,
        ACTIVE_MAX_NORM_FIBER_LENGTH,
    );
    let dydx = ACTIVE_SHALLOW_ASCENDING_SLOPE;
    // Half the plateau's width, and the shoulder where the shallow limb meets it.
    let x_delta = 0.05 * x2;
    let xs = x2 - x_delta;
    // The ascending limb's knots are laid out from y = 0, though it starts at ylow.
    let y1 = 1.0 - dydx * (xs - x1);
    let dydx01 = 1.25 * y1 / (x1 - x0);
    let (x01, y01) = (x0 + 0.5 * (x1 - x0), 0.5 * y1);
    let (x1s, y1s) = (x1 + 0.5 * (xs - x1), y1 + 0.5 * (1.0 - y1));
    let x23 = (x2 + x_delta) + 0.5 * (x3 - (x2 + x_delta));
    let dydx23 = -1.0 / ((x3 - x_delta) - (x2 + x_delta));
    let ends = [
        (x0, ylow, 0.0),
        (x01, y01, dydx01),
        (x1s, y1s, dydx),
        (x2, 1.0, 0.0),
        (x23, 0.5, dydx23),
        (x3, ylow, 0.0),
    ];
    let c = scaled_curviness(ACTIVE_CURVINESS);
    Ok(SegmentedBezier::new(&corners(&ends, &[c; 5])?, 0.0, 0.0))
}

/// The force–velocity curve f_V(ṽ): 0 at ṽ = −1, 1 at 0, the eccentric multiplier at 1, with
/// knots at ∓`FV_NEAR_VMAX`; straight with the end slopes `dydx_c` (at ṽ = −1) and `dydx_e`
/// (at 1) beyond ±1 (`createFiberForceVelocityCurve`).
pub(crate) fn force_velocity_curve(
    dydx_c: f64,
    dydx_e: f64,
) -> Result<SegmentedBezier, NotACorner> {
    let (dydx_near_c, dydx_near_e) = (FV_CONCENTRIC_SLOPE_NEAR_VMAX, FV_ECCENTRIC_SLOPE_NEAR_VMAX);
    let y_e = FV_MAX_ECCENTRIC_MULTIPLIER;
    // The inner knots on the average of the end's two slopes.
    let (x_near_c, x_near_e) = (-FV_NEAR_VMAX, FV_NEAR_VMAX);
    let y_near_c = 0.5 * dydx_near_c * (x_near_c + 1.0) + 0.5 * dydx_c * (x_near_c + 1.0);
    let y_near_e = y_e + 0.5 * dydx_near_e * (x_near_e - 1.0) + 0.5 * dydx_e * (x_near_e - 1.0);
    let ends = [
        (-1.0, 0.0, dydx_c),
        (x_near_c, y_near_c, dydx_near_c),
        (0.0, 1.0, FV_ISOMETRIC_SLOPE),
        (x_near_e, y_near_e, dydx_near_e),
        (1.0, y_e, dydx_e),
    ];
    let (cc, ce) = (
        scaled_curviness(FV_CONCENTRIC_CURVINESS),
        scaled_curviness(FV_ECCENTRIC_CURVINESS),
    );
    Ok(SegmentedBezier::new(
        &corners(&ends, &[cc, cc, ce, ce])?,
        dydx_c,
        dydx_e,
    ))
}

/// The passive force–length curve f_PE(l̃) for a strain at one normalised force `e1`: zero up
/// to l̃ = 1, a foot of slope `PASSIVE_STIFFNESS_AT_LOW_FORCE`, then 1 at `1 + e1` with slope
/// `2 / e1`, straight beyond (`createFiberForceLengthCurve`). Needs 0 < e1 < 5 (the foot's slope
/// below the mean slope 1/e1).
pub(crate) fn passive_force_length_curve(e1: f64) -> Result<SegmentedBezier, NotACorner> {
    let e0 = PASSIVE_STRAIN_AT_ZERO_FORCE;
    let k_iso = PASSIVE_STIFFNESS_TIMES_STRAIN / (e1 - e0);
    let k_low = PASSIVE_STIFFNESS_AT_LOW_FORCE;
    let (x_zero, x_iso) = (1.0 + e0, 1.0 + e1);
    let delta = (0.1 / k_iso).min(0.1 * (x_iso - x_zero));
    let x_low = x_zero + delta;
    let x_foot = x_zero + 0.5 * (x_low - x_zero);
    let y_low = k_low * (x_low - x_foot);
    let ends = [
        (x_zero, 0.0, 0.0),
        (x_low, y_low, k_low),
        (x_iso, 1.0, k_iso),
    ];
    let c = scaled_curviness(PASSIVE_CURVINESS);
    Ok(SegmentedBezier::new(&corners(&ends, &[c; 2])?, 0.0, k_iso))
}

/// The tendon force–length curve f_T(l̃_T) for a strain at one normalised force `e_iso`: zero
/// when slack, a toe up to `TENDON_NORM_FORCE_AT_TOE_END`, then straight with slope
/// `1.375 / e_iso` through 1 at `1 + e_iso` (`createTendonForceLengthCurve`).
pub(crate) fn tendon_force_length_curve(e_iso: f64) -> Result<SegmentedBezier, NotACorner> {
    let k_iso = TENDON_STIFFNESS_TIMES_STRAIN / e_iso;
    let x_iso = 1.0 + e_iso;
    let y_toe = TENDON_NORM_FORCE_AT_TOE_END;
    let x_toe = (y_toe - 1.0) / k_iso + x_iso;
    // The toe's line meets the axis right of l̃_T = 1, which limits its curvature.
    let x_foot = 1.0 + (x_toe - 1.0) / 10.0;
    let y_toe_mid = 0.5 * y_toe;
    let x_toe_mid = (y_toe_mid - 1.0) / k_iso + x_iso;
    let dydx_toe_mid = y_toe_mid / (x_toe_mid - x_foot);
    let x_toe_ctrl = x_foot + 0.5 * (x_toe_mid - x_foot);
    let y_toe_ctrl = dydx_toe_mid * (x_toe_ctrl - x_foot);
    let ends = [
        (1.0, 0.0, 0.0),
        (x_toe_ctrl, y_toe_ctrl, dydx_toe_mid),
        (x_toe, y_toe, k_iso),
    ];
    let c = scaled_curviness(TENDON_CURVINESS);
    Ok(SegmentedBezier::new(&corners(&ends, &[c; 2])?, 0.0, k_iso))
}
