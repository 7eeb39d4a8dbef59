//! A Hill element's force–velocity relation of its curve set (docs/model.md §3, §4b), in m/s,
//! and the velocity at which it balances a force (an equilibrium fibre, §5b).

use crate::physics::contractile::hill_equation::{force_velocity, force_velocity_derivative};
use crate::physics::curves::quintic_bezier::SegmentedBezier;
use crate::physics::curves::tabulated::{self, TabulatedCurve};
use crate::physics::curves::{degroote2016, millard2012, thelen2003, CurveSet};
use crate::physics::limb_params::MuscleParams;
use std::sync::Arc;

/// The fastest an equilibrium fibre moves, in units of vmax: where no velocity balances the
/// force (an element without active force and no damper, or a force beyond what the curve
/// reaches) the fibre moves this fast (docs/model.md §5b). Ten times vmax lies beyond every
/// curve's working range (the paper's relation is flat past vmax shortening, Thelen's and
/// DeGroote's are extrapolated there), so a balance that exists is always inside.
pub(crate) const BALANCE_VELOCITY_BOUND: f64 = 10.0;

/// Iterations of the balance's safeguarded Newton method: each at least halves the bracket, so
/// 200 resolve ±10 vmax to far below one ulp; it stops after 4–8 in practice.
const BALANCE_MAX_ITERATIONS: usize = 200;

/// A Hill element's force–velocity relation of its curve set (docs/model.md §3, §4b), at the
/// fibre's lengthening velocity v (m/s) normalised as `ṽ = v / vmax` (vmax in m/s, OpenSim's
/// `max_contraction_velocity · l_opt`).
#[derive(Debug, Clone, PartialEq)]
pub enum HillForceVelocity {
    /// The paper's eq. (2) and the project's eccentric continuation ([`force_velocity`]).
    Paper {
        /// vmax, m/s.
        v_max: f64,
        /// Eccentric asymptote N.
        eccentric_asymptote: f64,
    },
    /// DeGroote 2016's inverse hyperbolic sine ([`degroote2016::force_velocity`]).
    DeGroote2016 {
        /// vmax, m/s.
        v_max: f64,
    },
    /// Thelen 2003's relation, which depends on activation
    /// ([`thelen2003::force_velocity`]).
    Thelen2003 {
        /// vmax, m/s.
        v_max: f64,
        /// Its shape (Af, Flen; OpenSim's extrapolation threshold).
        shape: thelen2003::ForceVelocityShape,
    },
    /// Millard 2012's quintic Bézier curve (`millard2012::force_velocity_curve`).
    Millard2012 {
        /// vmax, m/s.
        v_max: f64,
        /// The curve of ṽ.
        curve: Arc<SegmentedBezier>,
    },
    /// The muscle's own points, interpolated as CEINMS does, read at ṽ within [−1, 1] as CEINMS
    /// reads them (lib/NMSmodel/Lloyd2003Muscle `calculateNormalisedFiberVelocity`): flat beyond
    /// ±vmax, whatever the spline does in the padding there, so that the equilibrium fibre's
    /// balance never falls as v rises.
    Tabulated {
        /// vmax, m/s.
        v_max: f64,
        /// The curve of ṽ.
        curve: Arc<TabulatedCurve>,
    },
}

impl HillForceVelocity {
    /// The relation of the muscle's curve set.
    pub fn new(p: &MuscleParams) -> Self {
        let v_max = p.v_max;
        match p.curves {
            CurveSet::Paper => HillForceVelocity::Paper {
                v_max,
                eccentric_asymptote: p.eccentric_asymptote,
            },
            CurveSet::DeGroote2016 => HillForceVelocity::DeGroote2016 { v_max },
            CurveSet::Thelen2003 => {
                let default = thelen2003::ForceVelocityShape::default();
                HillForceVelocity::Thelen2003 {
                    v_max,
                    shape: thelen2003::ForceVelocityShape {
                        af: p.af.unwrap_or(default.af),
                        flen: p.flen.unwrap_or(default.flen),
                        ..default
                    },
                }
            }
            CurveSet::Tabulated => HillForceVelocity::Tabulated {
                v_max,
                curve: Arc::new(tabulated::of_points(
                    p.tabulated.as_ref().map(|t| &t.force_velocity),
                )),
            },
            CurveSet::Millard2012 => HillForceVelocity::Millard2012 {
                v_max,
                curve: Arc::new({
                    let shape = millard2012::Shape::of(p);
                    millard2012::force_velocity_curve(
                        shape.concentric_slope_at_vmax,
                        shape.eccentric_slope_at_vmax,
                    )
                    .unwrap_or_else(|_| SegmentedBezier::undefined())
                }),
            },
        }
    }

    /// vmax, m/s.
    pub fn v_max(&self) -> f64 {
        match *self {
            HillForceVelocity::Paper { v_max, .. }
            | HillForceVelocity::DeGroote2016 { v_max }
            | HillForceVelocity::Thelen2003 { v_max, .. }
            | HillForceVelocity::Millard2012 { v_max, .. }
            | HillForceVelocity::Tabulated { v_max, .. } => v_max,
        }
    }

    /// `dg/dv` at lengthening velocity `v` (m/s) and activation `a`, per m/s.
    #[inline]
    pub fn slope(&self, v: f64, activation: f64) -> f64 {
        match *self {
            HillForceVelocity::Paper {
                v_max,
                eccentric_asymptote,
            } => -force_velocity_derivative(-v, v_max, eccentric_asymptote),
            HillForceVelocity::DeGroote2016 { v_max } => {
                degroote2016::force_velocity_derivative(v / v_max) / v_max
            }
            HillForceVelocity::Thelen2003 { v_max, ref shape } => {
                thelen2003::force_velocity_derivative(v / v_max, activation, shape) / v_max
            }
            HillForceVelocity::Millard2012 { v_max, ref curve } => curve.slope(v / v_max) / v_max,
            HillForceVelocity::Tabulated { v_max, ref curve } => {
                let x = v / v_max;
                if x.abs() > 1.0 {
                    0.0
                } else {
                    curve.slope(x) / v_max
                }
            }
        }
    }

    /// The lengthening velocity (m/s) at which the multiplier is `g`, within ±
    /// [`BALANCE_VELOCITY_BOUND`] vmax: each set's inverse (the paper's branches solved for v_s;
    /// DeGroote's sinh; Thelen's eq. 6 with its extrapolation). Beyond the paper's range (g <= 0,
    /// or g >= N) the nearer bound.
    pub(crate) fn inverse(&self, g: f64, activation: f64) -> f64 {
        let v = match *self {
            HillForceVelocity::Paper {
                v_max,
                eccentric_asymptote: n,
            } => {
                // v_s / vmax on each branch of `force_velocity`, lengthening velocity its negative.
                let vr = if g <= 0.0 {
                    f64::INFINITY
                } else if g <= 1.0 {
                    (1.0 - g) / (1.0 + 4.0 * g)
                } else if g < n {
                    (1.0 - (n - 1.0) / (n - g)) / (5.0 / (n - 1.0))
                } else {
                    f64::NEG_INFINITY
                };
                -vr * v_max
            }
            HillForceVelocity::DeGroote2016 { v_max } => {
                degroote2016::force_velocity_inverse(g) * v_max
            }
            HillForceVelocity::Thelen2003 { v_max, ref shape } => {
                thelen2003::force_velocity_inverse(g, activation, shape) * v_max
            }
            // OpenSim's ForceVelocityInverseCurve is this curve with x and y exchanged; a flat
            // end (the default slopes at ±vmax are 0) saturates at ±vmax.
            HillForceVelocity::Millard2012 { v_max, ref curve } => curve.argument_at(g) * v_max,
            // Its rising part's inverse (the flat padding is never inverted).
            HillForceVelocity::Tabulated { v_max, ref curve } => {
                curve.argument_at(g).clamp(-1.0, 1.0) * v_max
            }
        };
        let bound = BALANCE_VELOCITY_BOUND * self.v_max();
        v.clamp(-bound, bound)
    }

    /// The lengthening velocity v (m/s) at which `active g(v, a) + damping v = force` (`active`
    /// = Fmax a f(l_m), N; `damping` N s/m): the equilibrium fibre's balance (docs/model.md §5b).
    /// The left side never falls as v rises, so the root is bracketed in ±[`BALANCE_VELOCITY_BOUND`]
    /// vmax and found by Newton's method on the relation's own slope ([`Self::slope`]), from the
    /// undamped balance's velocity ([`Self::inverse`], exact when `damping` is 0), a step that
    /// leaves the bracket replaced by bisection; with no root inside, the bracket's end.
    ///
    /// Written here rather than taken from a root-finding crate: the residual is one line, the
    /// bracket and its saturation rule are the model's, and the loop must not allocate or fail.
    pub(crate) fn balance_velocity(
        &self,
        active: f64,
        activation: f64,
        damping: f64,
        force: f64,
    ) -> f64 {
        let v_max = self.v_max();
        let residual = |v: f64| active * self.at(v, activation) + damping * v - force;
        let bound = BALANCE_VELOCITY_BOUND * v_max;
        let (mut lo, mut hi) = (-bound, bound);
        let mut v = if active > 0.0 {
            self.inverse(force / active, activation)
        } else {
            0.0
        };
        // Converged when the residual is down to the rounding of its terms.
        let rounding = 8.0 * f64::EPSILON * (force.abs() + active.abs() + damping * v_max);
        for _ in 0..BALANCE_MAX_ITERATIONS {
            let r = residual(v);
            if r.abs() <= rounding {
                return v;
            }
            if r < 0.0 {
                lo = v;
            } else {
                hi = v;
            }
            let slope = active * self.slope(v, activation) + damping;
            let newton = v - r / slope;
            let next = if newton > lo && newton < hi {
                newton
            } else {
                // A step out of the bracket at a bound not yet evaluated: is there a root inside?
                if newton >= hi && hi == bound && residual(bound) <= 0.0 {
                    return bound;
                }
                if newton <= lo && lo == -bound && residual(-bound) >= 0.0 {
                    return -bound;
                }
                0.5 * (lo + hi)
            };
            let ulps = 4.0 * f64::EPSILON * v.abs().max(v_max);
            if (next - v).abs() <= ulps || hi - lo <= ulps {
                return next;
            }
            v = next;
        }
        v
    }

    /// The multiplier at lengthening velocity `v` (m/s) and activation `a`.
    #[inline]
    pub fn at(&self, v: f64, activation: f64) -> f64 {
        match *self {
            HillForceVelocity::Paper {
                v_max,
                eccentric_asymptote,
            } => force_velocity(-v, v_max, eccentric_asymptote),
            HillForceVelocity::DeGroote2016 { v_max } => degroote2016::force_velocity(v / v_max),
            HillForceVelocity::Thelen2003 { v_max, ref shape } => {
                thelen2003::force_velocity(v / v_max, activation, shape)
            }
            HillForceVelocity::Millard2012 { v_max, ref curve } => curve.value(v / v_max),
            HillForceVelocity::Tabulated { v_max, ref curve } => {
                curve.value((v / v_max).clamp(-1.0, 1.0))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::curves::CurveSet;

    fn relations() -> Vec<HillForceVelocity> {
        // (A tabulated muscle's curve is its own points: tests/curve_sets.rs builds some.)
        CurveSet::ALL
            .iter()
            .filter(|&&s| s != CurveSet::Tabulated)
            .map(|&curves| {
                HillForceVelocity::new(&MuscleParams {
                    curves,
                    ..MuscleParams::default()
                })
            })
            .collect()
    }

    /// The slope is the central difference of the relation, on every branch of every set.
    #[test]
    fn the_slope_is_the_relations_derivative() {
        for fv in relations() {
            let v_max = fv.v_max();
            for i in 0..=80 {
                // Off the branch points (0, the paper's vmax, Thelen's extrapolation edges).
                let v = (-2.0 + 4.0 * (i as f64 + 0.31) / 80.0) * v_max;
                for a in [0.05, 0.5, 1.0] {
                    let h = 1e-6 * v_max;
                    let diff = (fv.at(v + h, a) - fv.at(v - h, a)) / (2.0 * h);
                    let got = fv.slope(v, a);
                    assert!(
                        (got - diff).abs() <= 1e-6 * diff.abs().max(1.0 / v_max),
                        "{fv:?} at v = {v}, a = {a}: {got} vs {diff}"
                    );
                }
            }
        }
    }

    /// The inverse undoes the relation inside the paper's range and every other set's.
    #[test]
    fn the_inverse_undoes_the_relation() {
        for fv in relations() {
            let v_max = fv.v_max();
            for i in 0..=40 {
                let v = (-0.95 + 1.9 * (i as f64 + 0.31) / 40.0) * v_max;
                for a in [0.05, 0.5, 1.0] {
                    let back = fv.inverse(fv.at(v, a), a);
                    assert!(
                        (back - v).abs() <= 1e-9 * v_max,
                        "{fv:?} at {v}, a = {a}: {back}"
                    );
                }
            }
        }
    }

    /// The balance's velocity satisfies it to rounding, with and without a damper, and saturates
    /// at the bracket's end where nothing balances.
    #[test]
    fn the_balance_velocity_balances() {
        for fv in relations() {
            let v_max = fv.v_max();
            let bound = BALANCE_VELOCITY_BOUND * v_max;
            for (active, damping) in [(1000.0, 0.0), (1000.0, 257.0), (20.0, 257.0)] {
                for target in [-50.0, 0.0, 300.0, 999.0, 1300.0] {
                    let a = 0.7;
                    let v = fv.balance_velocity(active, a, damping, target);
                    let r = active * fv.at(v, a) + damping * v - target;
                    if v.abs() < bound {
                        assert!(r.abs() <= 1e-9 * active, "{fv:?}: residual {r} at {v}");
                    } else {
                        // Saturated: even the bracket's end does not reach the target.
                        assert!(
                            r * v.signum() <= 0.0,
                            "{fv:?}: saturated at {v}, residual {r}"
                        );
                    }
                }
            }
            // No active force and no damper: nothing balances a pull.
            assert_eq!(fv.balance_velocity(0.0, 0.0, 0.0, 10.0), bound);
        }
    }
}
