//! A Hill element's force–velocity relation of its curve set (docs/model.md §3, §4b), in m/s,
//! and the velocity at which it balances a force (an equilibrium fibre, §5b).

use crate::physics::contractile::hill_equation::force_velocity;
use crate::physics::curves::{degroote2016, thelen2003, CurveSet};
use crate::physics::params::MuscleParams;

/// The fastest an equilibrium fibre moves, in units of vmax: where no velocity balances the
/// force (an element without active force and no damper, or a force beyond what the curve
/// reaches) the fibre moves this fast (docs/model.md §5b). Ten times vmax lies beyond every
/// curve's working range (the paper's relation is flat past vmax shortening, Thelen's and
/// DeGroote's are extrapolated there), so a balance that exists is always inside.
pub const BALANCE_VELOCITY_BOUND: f64 = 10.0;

/// Iterations of the balance's safeguarded Newton method: each at least halves the bracket, so
/// 200 resolve ±10 vmax to far below one ulp; it stops after 4–8 in practice.
const BALANCE_MAX_ITERATIONS: usize = 200;

/// A Hill element's force–velocity relation of its curve set (docs/model.md §3, §4b), at the
/// fibre's lengthening velocity v (m/s) normalised as `ṽ = v / vmax` (vmax in m/s, OpenSim's
/// `max_contraction_velocity · l_opt`).
#[derive(Debug, Clone, Copy, PartialEq)]
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
    /// ([`thelen2003::force_velocity`], OpenSim's default shape).
    Thelen2003 {
        /// vmax, m/s.
        v_max: f64,
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
            CurveSet::Thelen2003 => HillForceVelocity::Thelen2003 { v_max },
        }
    }

    /// vmax, m/s.
    pub fn v_max(&self) -> f64 {
        match *self {
            HillForceVelocity::Paper { v_max, .. }
            | HillForceVelocity::DeGroote2016 { v_max }
            | HillForceVelocity::Thelen2003 { v_max } => v_max,
        }
    }

    /// The lengthening velocity v (m/s) at which `active g(v, a) + damping v = force` (`active`
    /// = Fmax a f(l_m), N; `damping` N s/m): the equilibrium fibre's balance (docs/model.md §5b).
    /// The left side never falls as v rises, so the root is bracketed in ±[`BALANCE_VELOCITY_BOUND`]
    /// vmax and found by Newton's method with a finite-difference slope, a step that leaves the
    /// bracket replaced by bisection; with no root inside, the bracket's end.
    ///
    /// Written here rather than taken from a root-finding crate: the residual is one line, the
    /// bracket and its saturation rule are the model's, and the loop must not allocate or fail.
    pub fn balance_velocity(&self, active: f64, activation: f64, damping: f64, force: f64) -> f64 {
        let v_max = self.v_max();
        let residual = |v: f64| active * self.at(v, activation) + damping * v - force;
        let (mut lo, mut hi) = (
            -BALANCE_VELOCITY_BOUND * v_max,
            BALANCE_VELOCITY_BOUND * v_max,
        );
        if residual(lo) >= 0.0 {
            return lo;
        }
        if residual(hi) <= 0.0 {
            return hi;
        }
        let h = 1e-7 * v_max;
        let mut v = 0.0;
        for _ in 0..BALANCE_MAX_ITERATIONS {
            let r = residual(v);
            if r == 0.0 {
                return v;
            }
            if r < 0.0 {
                lo = v;
            } else {
                hi = v;
            }
            let slope = (residual(v + h) - r) / h;
            let newton = v - r / slope;
            let next = if newton > lo && newton < hi {
                newton
            } else {
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
            HillForceVelocity::Thelen2003 { v_max } => {
                let shape = thelen2003::ForceVelocityShape::default();
                thelen2003::force_velocity(v / v_max, activation, &shape)
            }
        }
    }
}
