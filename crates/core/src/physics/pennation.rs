//! Pennation at constant fibre thickness (docs/model.md §5b; OpenSim's
//! MuscleFixedWidthPennationModel): the fibres lie at angle α to the line of the tendon, and as
//! they change length the muscle keeps its thickness `h = l_opt sin α_opt`, so
//! `sin α = h / l_m`. The fibre's projection on the tendon's line is `l_m cos α =
//! sqrt(l_m² - h²)`, and of its force only `F cos α` pulls on the tendon.

use crate::physics::limb_params::MuscleParams;

/// The least `cos α`: OpenSim's default `maximum_pennation_angle`, acos(0.1) (84.3°). Shorter
/// fibres are taken at this angle, so the projection never vanishes.
pub(crate) const MIN_COS: f64 = 0.1;

/// A muscle's pennation: the constant thickness h (0: fibres along the tendon).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Pennation {
    /// Thickness h = l_opt sin α_opt, m.
    pub height: f64,
}

impl Pennation {
    /// From the muscle's `pennation` (α_opt, rad) and `l_opt`.
    pub(crate) fn new(p: &MuscleParams) -> Self {
        Self {
            height: p.l_opt * p.pennation.sin(),
        }
    }

    /// Whether the fibres lie along the tendon (α = 0 at every length).
    #[inline]
    pub(crate) fn is_none(&self) -> bool {
        self.height == 0.0
    }

    /// `cos α` at fibre length `l_m` (m): `sqrt(1 - (h/l_m)²)`, at least [`MIN_COS`].
    #[inline]
    pub(crate) fn cos(&self, l_m: f64) -> f64 {
        if self.is_none() {
            return 1.0;
        }
        let sin = self.height / l_m;
        (1.0 - sin * sin).max(MIN_COS * MIN_COS).sqrt()
    }

    /// The fibre length whose projection on the tendon's line is `x` (m): `sqrt(x² + h²)`.
    #[inline]
    pub(crate) fn fibre_length(&self, x: f64) -> f64 {
        if self.is_none() {
            x
        } else {
            x.hypot(self.height)
        }
    }

    /// The stiffness along the tendon's line of a fibre of stiffness `k_m` (N/m) carrying force
    /// `f` (N) at length `l_m`: `k_m cos²α + f sin²α / l_m` (the fibre's own stiffness projected,
    /// plus the rotation's; Millard et al. 2013, eq. of the fibre's stiffness along the tendon).
    pub(crate) fn stiffness_along_tendon(&self, k_m: f64, f: f64, l_m: f64) -> f64 {
        if self.is_none() {
            return k_m;
        }
        let c = self.cos(l_m);
        k_m * c * c + f * (1.0 - c * c) / l_m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pennation(alpha: f64) -> Pennation {
        Pennation::new(&MuscleParams {
            pennation: alpha,
            l_opt: 0.1,
            ..MuscleParams::default()
        })
    }

    /// At optimal length the angle is α_opt; the thickness is kept at every length; the
    /// projection and its inverse agree.
    #[test]
    fn thickness_is_constant_and_the_projection_inverts() {
        let p = pennation(0.3);
        assert!((p.cos(0.1) - 0.3f64.cos()).abs() < 1e-15);
        for l_m in [0.06, 0.1, 0.14] {
            let c = p.cos(l_m);
            let sin = (1.0 - c * c).sqrt();
            assert!((l_m * sin - p.height).abs() < 1e-15);
            assert!((p.fibre_length(l_m * c) - l_m).abs() < 1e-15);
        }
        // Far shorter fibres are held at the largest angle.
        assert!((p.cos(0.01) - MIN_COS).abs() < 1e-15);
        assert_eq!(pennation(0.0).cos(0.02), 1.0);
    }

    /// The stiffness along the tendon is the derivative of `F(l_m) cos α` with respect to the
    /// projection `l_m cos α`, for a linear fibre spring.
    #[test]
    fn stiffness_along_the_tendon_is_the_projected_derivative() {
        let p = pennation(0.4);
        let (k, f0) = (5000.0, 300.0);
        let force = |l_m: f64| f0 + k * (l_m - 0.1);
        let along = |x: f64| {
            let l_m = p.fibre_length(x);
            force(l_m) * p.cos(l_m)
        };
        let l_m = 0.105;
        let x = l_m * p.cos(l_m);
        let h = 1e-7;
        let diff = (along(x + h) - along(x - h)) / (2.0 * h);
        let got = p.stiffness_along_tendon(k, force(l_m), l_m);
        assert!((got - diff).abs() < 1e-5 * diff, "{got} vs {diff}");
    }
}
