//! A Hill element's force–velocity relation of its curve set (docs/model.md §3, §4b), in m/s.

use crate::physics::contractile::hill_equation::force_velocity;
use crate::physics::curves::{degroote2016, thelen2003, CurveSet};
use crate::physics::params::MuscleParams;

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
