//! The series elastic element, the tendon (docs/model.md §4, paper eqs. 4–5).

use crate::physics::params::MuscleParams;
use crate::physics::spring::ExpLinearSpring;

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
