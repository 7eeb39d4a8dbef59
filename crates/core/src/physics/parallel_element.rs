//! The parallel elastic element and its damper (docs/model.md §4, paper eqs. 6–7).

use crate::physics::params::MuscleParams;
use crate::physics::spring::ExpLinearSpring;

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

/// Parallel damper `F_d = B_m v`, N (v: lengthening velocity, m/s).
pub(crate) fn damper_force(b_m: f64, v: f64) -> f64 {
    b_m * v
}
