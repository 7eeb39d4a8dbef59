//! The curves of De Groote et al. (2016), Ann Biomed Eng 44(10), as OpenSim 4.6 computes them in
//! `OpenSim/Actuators/DeGrooteFregly2016Muscle.h` and `.cpp` (opensim-core), with the muscle's
//! default properties (docs/model.md §4b). Pure closed forms of normalised quantities:
//!
//! - fibre length `l̃ = l_M / l_opt`;
//! - fibre velocity `ṽ = v_M / (v_max l_opt)`, lengthening positive, `v_max` in optimal fibre
//!   lengths per second (OpenSim's `max_contraction_velocity`, default 10);
//! - tendon length `l̃_T = l_T / l_s` (l_s: tendon slack length);
//! - forces as fractions of the maximum isometric force.
//!
//! OpenSim's constants differ from the paper's supplement where OpenSim made the curves pass
//! through their key points (`f_L(1) = 1`, `f_V(0) = 1`, `f_V(-1) = 0`, `f_T(1) = 0`); the
//! constants below are OpenSim's, and each says where it departs.

/// One Gaussian-like term `[b1, b2, b3, b4]` of the active force–length curve,
/// `b1 exp(-(x - b2)² / (2 (b3 + b4 x)²))`.
pub(crate) type GaussianTerm = [f64; 4];

/// First term (b11, b21, b31, b41): OpenSim's values, from simtk.org/projects/optcntrlmuscle
/// rather than the supplement, b11 adjusted so that `f_L(1) = 1` (DeGrooteFregly2016Muscle.h).
pub(crate) const ACTIVE_TERM_1: GaussianTerm = [
    0.8150671134243542,
    1.055033428970575,
    0.162384573599574,
    0.063303448465465,
];
/// Second term (b12, b22, b32, b42), DeGrooteFregly2016Muscle.h.
pub(crate) const ACTIVE_TERM_2: GaussianTerm = [
    0.433004984392647,
    0.716775413397760,
    -0.029947116970696,
    0.200356847296188,
];
/// Third term (b13, b23, b33, b43); b33 = 0.5 sqrt(0.5) as OpenSim writes it, to 15 digits
/// (DeGrooteFregly2016Muscle.h).
pub(crate) const ACTIVE_TERM_3: GaussianTerm = [0.1, 1.0, 0.353553390593274, 0.0];

/// Exponential shape kPE of the passive curve (De Groote et al. 2016, supplement; OpenSim's
/// `kPE`).
pub(crate) const KPE: f64 = 4.0;
/// Normalised fibre length where the passive curve is zero, OpenSim's `m_minNormFiberLength`
/// (also the lower end of the fibre lengths the muscle allows).
pub(crate) const MIN_NORM_FIBER_LENGTH: f64 = 0.2;

/// Tendon curve c1 (De Groote et al. 2016, supplement).
pub(crate) const C1: f64 = 0.200;
/// Tendon curve c2: 1.0 in OpenSim (0.995 in the paper), so that `f_T(1) = 0` since c2 = c3
/// (DeGrooteFregly2016Muscle.h).
pub(crate) const C2: f64 = 1.0;
/// Tendon curve c3: 0.200 in OpenSim (0.250 in the paper): the force tends to -c3 for a slack
/// tendon (DeGrooteFregly2016Muscle.h).
pub(crate) const C3: f64 = 0.200;

/// Force–velocity d1, solved by OpenSim so that the curve passes through (-1, 0) and (0, 1)
/// (DeGrooteFregly2016Muscle.h; the supplement's rounded value misses both points).
pub(crate) const D1: f64 = -0.3211346127989808;
/// Force–velocity d2 (De Groote et al. 2016, supplement).
pub(crate) const D2: f64 = -8.149;
/// Force–velocity d3 (De Groote et al. 2016, supplement).
pub(crate) const D3: f64 = -0.374;
/// Force–velocity d4, solved by OpenSim with d1 (DeGrooteFregly2016Muscle.h).
pub(crate) const D4: f64 = 0.8825327733249912;

/// OpenSim's default `active_force_width_scale` (widens the active curve; 1: as published).
pub const DEFAULT_ACTIVE_FORCE_WIDTH_SCALE: f64 = 1.0;
/// OpenSim's default `passive_fiber_strain_at_one_norm_force` e0.
pub const DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE: f64 = 0.6;
/// OpenSim's default `tendon_strain_at_one_norm_force` (0.049, as TendonForceLengthCurve's, in
/// place of the paper's kT = 35: OpenSim derives kT from it, [`tendon_shape`]).
pub const DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE: f64 = 0.049;

/// One Gaussian-like term at `x` (OpenSim's `calcGaussianLikeCurve`; the supplement omits the
/// square of the denominator).
pub(crate) fn gaussian_like(x: f64, b: GaussianTerm) -> f64 {
    let [b1, b2, b3, b4] = b;
    let den = b3 + b4 * x;
    b1 * (-0.5 * ((x - b2) * (x - b2)) / (den * den)).exp()
}

/// d/dx of [`gaussian_like`] (OpenSim's `calcGaussianLikeCurveDerivative`):
/// `b1 exp(-(b2 - x)² / (2 (b3 + b4 x)²)) (b2 - x)(b3 + b2 b4) / (b3 + b4 x)³`.
pub(crate) fn gaussian_like_derivative(x: f64, b: GaussianTerm) -> f64 {
    let [b1, b2, b3, b4] = b;
    let den = b3 + b4 * x;
    (b1 * (-((b2 - x) * (b2 - x)) / (2.0 * (den * den))).exp() * (b2 - x) * (b3 + b2 * b4))
        / (den * den * den)
}

/// The curve's argument for a width scale s: `x = (l̃ - 1)/s + 1` (the peak stays at 1).
fn scaled_length(norm_fiber_length: f64, width_scale: f64) -> f64 {
    (norm_fiber_length - 1.0) / width_scale + 1.0
}

/// Active force–length multiplier `f_L(l̃)`, the sum of the three Gaussian-like terms at
/// `(l̃ - 1)/s + 1` (s: `active_force_width_scale`, default 1); dimensionless, 1 at l̃ = 1,
/// though its peak, 1.00107, is at l̃ = 1.0133 (with s = 1).
pub fn active_force_length(norm_fiber_length: f64, width_scale: f64) -> f64 {
    let x = scaled_length(norm_fiber_length, width_scale);
    gaussian_like(x, ACTIVE_TERM_1)
        + gaussian_like(x, ACTIVE_TERM_2)
        + gaussian_like(x, ACTIVE_TERM_3)
}

/// `df_L/dl̃`: the terms' derivatives divided by the width scale.
pub fn active_force_length_derivative(norm_fiber_length: f64, width_scale: f64) -> f64 {
    let x = scaled_length(norm_fiber_length, width_scale);
    (1.0 / width_scale)
        * (gaussian_like_derivative(x, ACTIVE_TERM_1)
            + gaussian_like_derivative(x, ACTIVE_TERM_2)
            + gaussian_like_derivative(x, ACTIVE_TERM_3))
}

/// The passive curve's offset `exp(kPE (l̃_min - 1)/e0)`, its exponential's value at
/// [`MIN_NORM_FIBER_LENGTH`] (OpenSim's `offset`).
fn passive_offset(strain_at_one_norm_force: f64) -> f64 {
    (KPE * (MIN_NORM_FIBER_LENGTH - 1.0) / strain_at_one_norm_force).exp()
}

/// Passive force–length multiplier
/// `f_PE(l̃) = (exp(kPE (l̃ - 1)/e0) - o) / (exp(kPE) - o)`, `o = exp(kPE (0.2 - 1)/e0)`:
/// zero at l̃ = 0.2, 1 at l̃ = 1 + e0, negative below 0.2 (OpenSim's change to the supplement's
/// curve, which is zero at l̃ = 1 and negative below). e0: `passive_fiber_strain_at_one_norm_force`.
pub fn passive_force_length(norm_fiber_length: f64, strain_at_one_norm_force: f64) -> f64 {
    let e0 = strain_at_one_norm_force;
    let offset = passive_offset(e0);
    let denom = KPE.exp() - offset;
    ((KPE * (norm_fiber_length - 1.0) / e0).exp() - offset) / denom
}

/// `df_PE/dl̃ = kPE exp(kPE (l̃ - 1)/e0) / (e0 (exp(kPE) - o))`.
pub fn passive_force_length_derivative(
    norm_fiber_length: f64,
    strain_at_one_norm_force: f64,
) -> f64 {
    let e0 = strain_at_one_norm_force;
    let offset = passive_offset(e0);
    (KPE * ((KPE * (norm_fiber_length - 1.0)) / e0).exp()) / (e0 * (KPE.exp() - offset))
}

/// The normalised fibre length at which the passive curve is `f`:
/// `l̃ = 1 + (e0/kPE) ln(f (exp(kPE) - o) + o)` (the inverse of [`passive_force_length`]; 0.2 at
/// f = 0, NaN below `-o/(exp(kPE) - o)`).
pub(crate) fn passive_force_length_inverse(
    norm_passive_force: f64,
    strain_at_one_norm_force: f64,
) -> f64 {
    let e0 = strain_at_one_norm_force;
    let offset = passive_offset(e0);
    1.0 + e0 / KPE * (norm_passive_force * (KPE.exp() - offset) + offset).ln()
}

/// `∫_{0.2}^{l̃} f_PE(x) dx`, the passive curve's integral from [`MIN_NORM_FIBER_LENGTH`], where
/// it is zero, as OpenSim writes it (`calcPassiveForceMultiplierIntegral`; the fibre's potential
/// energy is this times l_opt Fmax): with `t1 = e0 + kPE (l̃ - 0.2)`,
/// `t1/kPE + (exp(kPE) t1 - e0 exp(kPE (l̃ - 1)/e0)) / (kPE (o - exp(kPE)))`.
pub(crate) fn passive_force_length_integral(
    norm_fiber_length: f64,
    strain_at_one_norm_force: f64,
) -> f64 {
    let e0 = strain_at_one_norm_force;
    let temp1 = e0 + KPE * norm_fiber_length - KPE * MIN_NORM_FIBER_LENGTH;
    let temp2 = (KPE * (norm_fiber_length - 1.0) / e0).exp();
    let temp3 = passive_offset(e0);
    let numer = KPE.exp() * temp1 - e0 * temp2;
    let denom = KPE * (temp3 - KPE.exp());
    temp1 / KPE + numer / denom
}

/// Force–velocity multiplier `f_V(ṽ) = d1 ln(d2 ṽ + d3 + sqrt((d2 ṽ + d3)² + 1)) + d4`
/// (d1 asinh(d2 ṽ + d3) + d4): 0 at ṽ = -1, 1 at ṽ = 0, about 1.794 at ṽ = 1. OpenSim states
/// the domain [-1, 1] and evaluates the formula outside it too (negative below -1).
pub fn force_velocity(norm_fiber_velocity: f64) -> f64 {
    let t = D2 * norm_fiber_velocity + D3;
    D1 * (t + (t * t + 1.0).sqrt()).ln() + D4
}

/// `df_V/dṽ = d1 d2 / sqrt((d2 ṽ + d3)² + 1)`.
pub(crate) fn force_velocity_derivative(norm_fiber_velocity: f64) -> f64 {
    let t = D2 * norm_fiber_velocity + D3;
    D1 * D2 / (t * t + 1.0).sqrt()
}

/// The velocity at which the multiplier is `f`, `ṽ = (sinh((f - d4)/d1) - d3)/d2` (the inverse
/// of [`force_velocity`]; the supplement omits the `- d3`).
pub fn force_velocity_inverse(force_velocity_multiplier: f64) -> f64 {
    ((1.0 / D1 * (force_velocity_multiplier - D4)).sinh() - D3) / D2
}

/// Tendon shape kT from the tendon strain at one normalised force ε₁:
/// `kT = ln((1 + c3)/c1) / (1 + ε₁ - c2)`, so that `f_T(1 + ε₁) = 1` (OpenSim's `m_kT`,
/// DeGrooteFregly2016Muscle.cpp; 36.57 for ε₁ = 0.049).
pub fn tendon_shape(strain_at_one_norm_force: f64) -> f64 {
    ((1.0 + C3) / C1).ln() / (1.0 + strain_at_one_norm_force - C2)
}

/// Tendon force multiplier `f_T(l̃_T) = c1 exp(kT (l̃_T - c2)) - c3`: 0 at l̃_T = 1, 1 at
/// `1 + ε₁`; slightly negative for a slack tendon, tending to -c3 (OpenSim does not clip it).
/// `k_t`: [`tendon_shape`].
pub fn tendon_force_length(norm_tendon_length: f64, k_t: f64) -> f64 {
    C1 * (k_t * (norm_tendon_length - C2)).exp() - C3
}

/// `df_T/dl̃_T = c1 kT exp(kT (l̃_T - c2))`.
pub fn tendon_force_length_derivative(norm_tendon_length: f64, k_t: f64) -> f64 {
    C1 * k_t * (k_t * (norm_tendon_length - C2)).exp()
}

/// The normalised tendon length at which the tendon carries `f`:
/// `l̃_T = ln((f + c3)/c1)/kT + c2` (NaN for f <= -c3).
pub fn tendon_force_length_inverse(norm_tendon_force: f64, k_t: f64) -> f64 {
    ((1.0 / C1) * (norm_tendon_force + C3)).ln() / k_t + C2
}

/// `∫_1^{l̃_T} f_T(x) dx`, the tendon curve's integral from slack length (the tendon's potential
/// energy is this times l_s Fmax, as OpenSim's `calcTendonForceMultiplierIntegral` gives it):
/// `(c1/kT)(exp(kT (l̃_T - c2)) - exp(kT (1 - c2))) - c3 (l̃_T - 1)`. Positive on both sides of
/// slack length, where the force is negative.
pub(crate) fn tendon_force_length_integral(norm_tendon_length: f64, k_t: f64) -> f64 {
    C1 / k_t * ((k_t * (norm_tendon_length - C2)).exp() - (k_t * (1.0 - C2)).exp())
        - C3 * (norm_tendon_length - 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    const S: f64 = DEFAULT_ACTIVE_FORCE_WIDTH_SCALE;
    const E0: f64 = DEFAULT_PASSIVE_STRAIN_AT_ONE_NORM_FORCE;

    fn kt() -> f64 {
        tendon_shape(DEFAULT_TENDON_STRAIN_AT_ONE_NORM_FORCE)
    }

    fn central_difference(f: impl Fn(f64) -> f64, x: f64) -> f64 {
        let h = 1e-6;
        (f(x + h) - f(x - h)) / (2.0 * h)
    }

    #[test]
    fn active_force_length_is_one_at_one_but_peaks_just_beyond() {
        assert!((active_force_length(1.0, S) - 1.0).abs() < 1e-15);
        // The sum of the three terms peaks at l̃ = 1.0133 (1.00107), not at 1: OpenSim adjusted
        // b11 for the value at 1 only, so the slope there is 0.160.
        assert!((active_force_length_derivative(1.0, S) - 0.1602).abs() < 1e-4);
        assert!(active_force_length_derivative(1.0132, S) > 0.0);
        assert!(active_force_length_derivative(1.0134, S) < 0.0);
        assert!((active_force_length(1.0133, S) - 1.00107).abs() < 1e-5);
        assert!(active_force_length(0.5, S) < 1.0 && active_force_length(1.5, S) < 1.0);
    }

    #[test]
    fn active_force_length_width_scale_stretches_the_curve() {
        let wide = active_force_length(1.4, 2.0);
        assert!((wide - active_force_length(1.2, 1.0)).abs() < 1e-14);
    }

    #[test]
    fn derivatives_match_central_differences() {
        for i in 0..=32 {
            let l = 0.3 + 1.4 * i as f64 / 32.0;
            let fd = central_difference(|x| active_force_length(x, 1.3), l);
            assert!(
                (active_force_length_derivative(l, 1.3) - fd).abs() < 1e-7,
                "f_L' at {l}"
            );
            let fd = central_difference(|x| passive_force_length(x, E0), l);
            assert!(
                (passive_force_length_derivative(l, E0) - fd).abs() < 1e-7,
                "f_PE' at {l}"
            );
            let lt = 0.97 + 0.12 * i as f64 / 32.0;
            let fd = central_difference(|x| tendon_force_length(x, kt()), lt);
            let d = tendon_force_length_derivative(lt, kt());
            assert!((d - fd).abs() < 1e-6 * d.max(1.0), "f_T' at {lt}");
        }
    }

    #[test]
    fn passive_force_length_is_zero_at_its_minimum_and_one_at_e0() {
        assert_eq!(passive_force_length(MIN_NORM_FIBER_LENGTH, E0), 0.0);
        assert!((passive_force_length(1.0 + E0, E0) - 1.0).abs() < 1e-14);
        assert!(passive_force_length(0.1, E0) < 0.0);
        // At optimal length it is small but not zero: OpenSim's muscle is not slack at lopt.
        assert!(passive_force_length(1.0, E0) > 0.018 && passive_force_length(1.0, E0) < 0.019);
    }

    #[test]
    fn force_velocity_passes_through_its_key_points() {
        assert!((force_velocity(0.0) - 1.0).abs() < 1e-15);
        assert!(force_velocity(-1.0).abs() < 1e-15);
        assert!((force_velocity(1.0) - 1.794).abs() < 1e-3);
    }

    #[test]
    fn force_velocity_inverse_undoes_force_velocity() {
        for i in 0..=40 {
            let v = -1.0 + 2.0 * i as f64 / 40.0;
            assert!(
                (force_velocity_inverse(force_velocity(v)) - v).abs() < 1e-13,
                "at {v}"
            );
        }
    }

    #[test]
    fn integrals_differentiate_to_the_curves_and_inverses_undo_them() {
        for i in 0..=32 {
            let l = 0.25 + 1.5 * i as f64 / 32.0;
            let fd = central_difference(|x| passive_force_length_integral(x, E0), l);
            assert!(
                (fd - passive_force_length(l, E0)).abs() < 1e-8,
                "∫f_PE' at {l}"
            );
            let f = passive_force_length(l, E0);
            assert!(
                (passive_force_length_inverse(f, E0) - l).abs() < 1e-12,
                "f_PE⁻¹ at {l}"
            );
            let lt = 0.97 + 0.12 * i as f64 / 32.0;
            let fd = central_difference(|x| tendon_force_length_integral(x, kt()), lt);
            let f = tendon_force_length(lt, kt());
            assert!((fd - f).abs() < 1e-8 * f.abs().max(1.0), "∫f_T' at {lt}");
            assert!(
                tendon_force_length_integral(lt, kt()) >= 0.0,
                "∫f_T at {lt}"
            );
        }
        assert!(passive_force_length_integral(MIN_NORM_FIBER_LENGTH, E0).abs() < 1e-15);
        assert_eq!(tendon_force_length_integral(1.0, kt()), 0.0);
        assert!((passive_force_length_inverse(0.0, E0) - MIN_NORM_FIBER_LENGTH).abs() < 1e-15);
    }

    #[test]
    fn tendon_force_is_zero_at_slack_and_one_at_its_strain() {
        assert!(tendon_force_length(1.0, kt()).abs() < 1e-15);
        assert!((tendon_force_length(1.049, kt()) - 1.0).abs() < 1e-14);
        assert!((tendon_force_length(0.0, kt()) + C3).abs() < 1e-15);
        for i in 0..=50 {
            let f = 5.0 * i as f64 / 50.0;
            let l = tendon_force_length_inverse(f, kt());
            assert!((tendon_force_length(l, kt()) - f).abs() < 1e-13, "at {f}");
        }
    }
}
