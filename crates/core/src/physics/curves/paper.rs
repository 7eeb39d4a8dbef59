//! The paper's contractile curves (docs/model.md §3) in the normalised form of the other curve
//! sets: fibre length `l̃ = l_m / lopt` and fibre velocity `ṽ = v / vmax`, lengthening positive
//! (the paper's `v' = v_s / vmax` is shortening positive, so `ṽ = -v'`; its vmax is in m/s, not
//! optimal lengths per second). The passive elements, exponential-then-linear springs with
//! constants in N/m and 1/m (§4), have no normalised form independent of the muscle, so the set
//! has no passive or tendon curve here.

use crate::physics::contractile::{force_length, hill_equation};
use crate::physics::limb_params::ForceLengthShape;

/// Force–length factor `f(l̃)`: the paper's eq. (3) with lopt = 1 (parabola or Gaussian of width
/// `w`, [`force_length::force_length`]).
pub(crate) fn active_force_length(
    norm_fiber_length: f64,
    width: f64,
    shape: ForceLengthShape,
) -> f64 {
    force_length::force_length(norm_fiber_length, 1.0, width, shape)
}

/// Force–velocity factor `g(-ṽ)`: the paper's eq. (2) for shortening and the project's
/// continuation to the eccentric asymptote N for lengthening
/// ([`hill_equation::force_velocity`]); 0 at ṽ = -1, 1 at ṽ = 0.
pub(crate) fn force_velocity(norm_fiber_velocity: f64, eccentric_asymptote: f64) -> f64 {
    hill_equation::force_velocity(-norm_fiber_velocity, 1.0, eccentric_asymptote)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalised_paper_curves_are_the_papers() {
        let shape = ForceLengthShape::Parabola;
        assert_eq!(active_force_length(1.0, 0.643, shape), 1.0);
        assert_eq!(active_force_length(0.3, 0.643, shape), 0.0);
        assert_eq!(force_velocity(0.0, 1.8), 1.0);
        assert_eq!(force_velocity(-1.0, 1.8), 0.0);
        // (1 - v')/(1 + 4 v') at v' = 0.5.
        assert!((force_velocity(-0.5, 1.8) - 1.0 / 6.0).abs() < 1e-15);
        assert!(force_velocity(0.5, 1.8) > 1.0 && force_velocity(0.5, 1.8) < 1.8);
    }
}
