//! The curves of Thelen (2003), J Biomech Eng 125(1), as OpenSim 4.6 computes them in
//! `OpenSim/Actuators/Thelen2003Muscle.cpp` (opensim-core: `calcfal`, `calcfpe`, `calcfse`,
//! `calcdlceN` and their derivatives), with the muscle's default properties (docs/model.md §4b).
//! Pure closed forms of normalised quantities:
//!
//! - fibre length `l̃ = l_M / l_opt`;
//! - fibre velocity `ṽ = v_M / (v_max l_opt)`, lengthening positive, `v_max` in optimal fibre
//!   lengths per second (OpenSim's `max_contraction_velocity`, default 10);
//! - tendon length `l̃_T = l_T / l_s` (l_s: tendon slack length), strain `l̃_T - 1`;
//! - forces as fractions of the maximum isometric force.
//!
//! The force–velocity relation runs backwards in OpenSim: the muscle computes the multiplier
//! from its force balance and the fibre velocity from the multiplier ([`force_velocity_inverse`],
//! OpenSim's `calcdlceN`, Thelen 2003 eqs. 6–7, extrapolated linearly outside
//! `0 < f_V < 0.95 Flen`). [`force_velocity`] is that relation solved for the multiplier, in
//! closed form. It depends on activation: Thelen's maximum velocity is `(0.25 + 0.75 a) v_max`.

/// OpenSim's default `FmaxTendonStrain`, the tendon strain at one normalised force (0.033 before,
/// as Thelen2003Muscle.cpp notes).
pub const DEFAULT_FMAX_TENDON_STRAIN: f64 = 0.04;
/// OpenSim's default `FmaxMuscleStrain`, the passive fibre strain at one normalised force
/// (Thelen 2003: 0.6 for young adults).
pub(crate) const DEFAULT_FMAX_MUSCLE_STRAIN: f64 = 0.6;
/// OpenSim's default `KshapeActive`, the Gaussian's shape γ (Thelen 2003 eq. 3: 0.45).
pub(crate) const DEFAULT_KSHAPE_ACTIVE: f64 = 0.45;
/// OpenSim's default `KshapePassive`, the passive exponential shape k_PE (Thelen 2003 eq. 2: 5).
pub(crate) const DEFAULT_KSHAPE_PASSIVE: f64 = 5.0;
/// OpenSim's default `Af`, the force–velocity shape (Thelen 2003 eq. 7: 0.25).
pub(crate) const DEFAULT_AF: f64 = 0.25;
/// OpenSim's default `Flen`, the eccentric force asymptote (1.8 before, as Thelen2003Muscle.cpp
/// notes).
pub(crate) const DEFAULT_FLEN: f64 = 1.4;
/// OpenSim's default `fv_linear_extrap_threshold`: above this fraction of Flen the
/// force–velocity relation is extrapolated linearly (an OpenSim addition, not in the paper).
pub(crate) const DEFAULT_FV_LINEAR_EXTRAP_THRESHOLD: f64 = 0.95;

/// Tendon toe shape kToe (Thelen 2003 eq. 4; `kToe` in Thelen2003Muscle.cpp).
pub(crate) const TOE_SHAPE: f64 = 3.0;
/// Normalised tendon force where the toe turns linear, FToe = 33/100 (Thelen 2003 eq. 4;
/// `Ftoe` in Thelen2003Muscle.cpp).
pub(crate) const TOE_FORCE: f64 = 33.0 / 100.0;

/// Active force–length multiplier `f_L(l̃) = exp(-(l̃ - 1)²/γ)` (Thelen 2003 eq. 3; `calcfal`).
/// γ: `KshapeActive`.
pub fn active_force_length(norm_fiber_length: f64, kshape_active: f64) -> f64 {
    let x = (norm_fiber_length - 1.0) * (norm_fiber_length - 1.0);
    (-x / kshape_active).exp()
}

/// `df_L/dl̃ = -2 (l̃ - 1)/γ exp(-(l̃ - 1)²/γ)` (`calcDfalDlceN`).
pub(crate) fn active_force_length_derivative(norm_fiber_length: f64, kshape_active: f64) -> f64 {
    let t1 = norm_fiber_length - 1.0;
    let t2 = 1.0 / kshape_active;
    -2.0 * t1 * t2 * (-(t1 * t1) * t2).exp()
}

/// Passive force–length multiplier
/// `f_PE(l̃) = (exp(k_PE (l̃ - 1)/ε₀) - 1)/(exp(k_PE) - 1)` for l̃ > 1, 0 below (Thelen 2003
/// eq. 2; `calcfpe`). ε₀: `FmaxMuscleStrain`; k_PE: `KshapePassive`. 1 at l̃ = 1 + ε₀.
pub fn passive_force_length(
    norm_fiber_length: f64,
    fmax_muscle_strain: f64,
    kshape_passive: f64,
) -> f64 {
    if norm_fiber_length > 1.0 {
        let rise = (kshape_passive * (norm_fiber_length - 1.0) / fmax_muscle_strain).exp();
        (rise - 1.0) / (kshape_passive.exp() - 1.0)
    } else {
        0.0
    }
}

/// `df_PE/dl̃ = (k_PE/ε₀) exp(k_PE (l̃ - 1)/ε₀)/(exp(k_PE) - 1)` for l̃ > 1, 0 below
/// (`calcDfpeDlceN`).
pub(crate) fn passive_force_length_derivative(
    norm_fiber_length: f64,
    fmax_muscle_strain: f64,
    kshape_passive: f64,
) -> f64 {
    if norm_fiber_length > 1.0 {
        let t1 = 1.0 / fmax_muscle_strain;
        let t6 = (kshape_passive * (norm_fiber_length - 1.0) * t1).exp();
        kshape_passive * t1 * t6 / (kshape_passive.exp() - 1.0)
    } else {
        0.0
    }
}

/// Tendon strain where the toe turns linear, `ε_toe = 99 ε₀ e³/(166 e³ - 67)` (ε₀:
/// `FmaxTendonStrain`): the exact value that makes the curve's slope continuous and reach 1 at
/// ε₀; Thelen 2003 gives it rounded, 0.609 ε₀ (Thelen2003Muscle.cpp, `eToe`).
pub(crate) fn tendon_toe_strain(fmax_tendon_strain: f64) -> f64 {
    let t1 = TOE_SHAPE.exp();
    (99.0 * fmax_tendon_strain * t1) / (166.0 * t1 - 67.0)
}

/// Stiffness of the tendon's linear part, `k_lin = 0.67/(ε₀ - ε_toe)` (Thelen 2003: 1.712/ε₀,
/// rounded; 1.7119/ε₀ exact; Thelen2003Muscle.cpp, `klin`).
pub(crate) fn tendon_linear_stiffness(fmax_tendon_strain: f64) -> f64 {
    (67.0 / 100.0) / (fmax_tendon_strain - tendon_toe_strain(fmax_tendon_strain))
}

/// Tendon force multiplier at strain `ε = l̃_T - 1` (Thelen 2003 eq. 4; `calcfse`):
/// 0 for ε <= 0; `FToe/(exp(kToe) - 1) (exp(kToe ε/ε_toe) - 1)` up to ε_toe;
/// `k_lin (ε - ε_toe) + FToe` beyond. 1 at ε = ε₀ (`FmaxTendonStrain`).
pub fn tendon_force_length(norm_tendon_length: f64, fmax_tendon_strain: f64) -> f64 {
    let x = norm_tendon_length - 1.0;
    let e_toe = tendon_toe_strain(fmax_tendon_strain);
    if x > e_toe {
        tendon_linear_stiffness(fmax_tendon_strain) * (x - e_toe) + TOE_FORCE
    } else if x > 0.0 {
        (TOE_FORCE / (TOE_SHAPE.exp() - 1.0)) * ((TOE_SHAPE * x / e_toe).exp() - 1.0)
    } else {
        0.0
    }
}

/// `df_T/dl̃_T`: 0, `FToe/(exp(kToe) - 1) (kToe/ε_toe) exp(kToe ε/ε_toe)`, or k_lin
/// (`calcDfseDtlN`).
pub fn tendon_force_length_derivative(norm_tendon_length: f64, fmax_tendon_strain: f64) -> f64 {
    let x = norm_tendon_length - 1.0;
    let e_toe = tendon_toe_strain(fmax_tendon_strain);
    if x > e_toe {
        tendon_linear_stiffness(fmax_tendon_strain)
    } else if x > 0.0 {
        (TOE_FORCE / (TOE_SHAPE.exp() - 1.0)) * (TOE_SHAPE / e_toe) * (TOE_SHAPE * x / e_toe).exp()
    } else {
        0.0
    }
}

/// The toe's scale `FToe/(exp(kToe) - 1)`.
fn toe_scale() -> f64 {
    TOE_FORCE / (TOE_SHAPE.exp() - 1.0)
}

/// The normalised tendon length at which the tendon carries `f` (the inverse of
/// [`tendon_force_length`]): `1 + (ε_toe/kToe) ln(1 + f/(FToe/(exp(kToe) - 1)))` up to FToe,
/// `1 + ε_toe + (f - FToe)/k_lin` beyond; 1 (slack) for f <= 0.
pub(crate) fn tendon_force_length_inverse(norm_tendon_force: f64, fmax_tendon_strain: f64) -> f64 {
    let f = norm_tendon_force;
    let e_toe = tendon_toe_strain(fmax_tendon_strain);
    if f <= 0.0 {
        1.0
    } else if f <= TOE_FORCE {
        1.0 + e_toe / TOE_SHAPE * (f / toe_scale()).ln_1p()
    } else {
        1.0 + e_toe + (f - TOE_FORCE) / tendon_linear_stiffness(fmax_tendon_strain)
    }
}

/// `∫_1^{l̃_T} f_T(x) dx`, the tendon curve's integral from slack length (the tendon's strain
/// energy is this times l_s Fmax): 0 for a slack tendon;
/// `(FToe/(exp(kToe) - 1)) ((ε_toe/kToe)(exp(kToe d/ε_toe) - 1) - d)`, `d = min(ε, ε_toe)`, plus
/// `FToe y + k_lin y²/2`, `y = ε - ε_toe`, beyond the toe.
pub(crate) fn tendon_force_length_integral(
    norm_tendon_length: f64,
    fmax_tendon_strain: f64,
) -> f64 {
    let x = norm_tendon_length - 1.0;
    if x <= 0.0 {
        return 0.0;
    }
    let e_toe = tendon_toe_strain(fmax_tendon_strain);
    let d = x.min(e_toe);
    let toe = toe_scale() * (e_toe / TOE_SHAPE * (TOE_SHAPE * d / e_toe).exp_m1() - d);
    if x <= e_toe {
        toe
    } else {
        let y = x - e_toe;
        toe + TOE_FORCE * y + 0.5 * tendon_linear_stiffness(fmax_tendon_strain) * y * y
    }
}

/// The normalised fibre length at which the passive curve is `f` (the inverse of
/// [`passive_force_length`]): `1 + (ε₀/k_PE) ln(1 + f (exp(k_PE) - 1))`; 1 for f <= 0.
pub(crate) fn passive_force_length_inverse(
    norm_passive_force: f64,
    fmax_muscle_strain: f64,
    kshape_passive: f64,
) -> f64 {
    if norm_passive_force <= 0.0 {
        1.0
    } else {
        let rise = norm_passive_force * kshape_passive.exp_m1();
        1.0 + fmax_muscle_strain / kshape_passive * rise.ln_1p()
    }
}

/// `∫_1^{l̃} f_PE(x) dx`, the passive curve's integral from optimal length, where it starts (the
/// fibre's strain energy is this times l_opt Fmax):
/// `((ε₀/k_PE)(exp(k_PE (l̃ - 1)/ε₀) - 1) - (l̃ - 1))/(exp(k_PE) - 1)` for l̃ > 1, else 0.
pub(crate) fn passive_force_length_integral(
    norm_fiber_length: f64,
    fmax_muscle_strain: f64,
    kshape_passive: f64,
) -> f64 {
    let x = norm_fiber_length - 1.0;
    if x <= 0.0 {
        return 0.0;
    }
    let rise = (kshape_passive * x / fmax_muscle_strain).exp_m1();
    (fmax_muscle_strain / kshape_passive * rise - x) / kshape_passive.exp_m1()
}

/// The force–velocity relation's properties: `Af`, `Flen` and `fv_linear_extrap_threshold`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceVelocityShape {
    /// Shape Af (dimensionless).
    pub af: f64,
    /// Eccentric asymptote Flen, normalised force (> 1).
    pub flen: f64,
    /// Fraction of Flen above which the relation is linear (> 1/Flen).
    pub linear_extrap_threshold: f64,
}

impl Default for ForceVelocityShape {
    fn default() -> Self {
        Self {
            af: DEFAULT_AF,
            flen: DEFAULT_FLEN,
            linear_extrap_threshold: DEFAULT_FV_LINEAR_EXTRAP_THRESHOLD,
        }
    }
}

impl ForceVelocityShape {
    /// The multiplier above which the relation is extrapolated, `threshold · Flen`.
    fn upper_multiplier(&self) -> f64 {
        self.linear_extrap_threshold * self.flen
    }

    /// The eccentric branch's `(2 + 2/Af)/(Flen - 1)`.
    fn eccentric_factor(&self) -> f64 {
        (2.0 + 2.0 / self.af) / (self.flen - 1.0)
    }
}

/// Thelen's activation-dependent velocity scale `0.25 + 0.75 a` (Thelen 2003 eq. 6): the
/// maximum shortening velocity at activation a, in units of v_max.
pub(crate) fn velocity_scale(activation: f64) -> f64 {
    0.25 + 0.75 * activation
}

/// Thelen 2003 eq. 7's `b` and `db/df_V` at multiplier f, normalised by a·f_L:
/// `(1 + f/Af, 1/Af)` for f <= 1 (shortening),
/// `((2 + 2/Af)(Flen - f)/(Flen - 1), -(2 + 2/Af)/(Flen - 1))` above (lengthening).
fn hill_denominator(fv: f64, shape: &ForceVelocityShape) -> (f64, f64) {
    if fv <= 1.0 {
        (1.0 + fv / shape.af, 1.0 / shape.af)
    } else {
        let c = shape.eccentric_factor();
        (c * (shape.flen - fv), -c)
    }
}

/// Thelen 2003 eq. 6, `ṽ = (0.25 + 0.75 a)(f - 1)/b` (normalised by a·f_L).
fn thelen_velocity(fv: f64, scale: f64, shape: &ForceVelocityShape) -> f64 {
    let (b, _) = hill_denominator(fv, shape);
    scale * (fv - 1.0) / b
}

/// `dṽ/df_V` of eq. 6, `k/b - k (f - 1) b'/b²` (OpenSim's `calcDdlceDaFalFv`, normalised).
fn thelen_velocity_slope(fv: f64, scale: f64, shape: &ForceVelocityShape) -> f64 {
    let (b, db) = hill_denominator(fv, shape);
    scale / b - (scale * (fv - 1.0) / (b * b)) * db
}

/// Normalised fibre velocity at force–velocity multiplier `f_V` and activation `a` (OpenSim's
/// `calcdlceN` with the active force a·f_L·f_V, normalised by a·f_L, which cancels): eq. 6
/// for `0 < f_V < threshold·Flen`; outside, the tangent line at the nearer end (f_V = 0, where
/// ṽ = -(0.25 + 0.75 a), or threshold·Flen). `a` > 0.
pub fn force_velocity_inverse(
    force_velocity_multiplier: f64,
    activation: f64,
    shape: &ForceVelocityShape,
) -> f64 {
    let fv = force_velocity_multiplier;
    let k = velocity_scale(activation);
    let upper = shape.upper_multiplier();
    if fv > 0.0 && fv < upper {
        return thelen_velocity(fv, k, shape);
    }
    let edge = if fv <= 0.0 { 0.0 } else { upper };
    thelen_velocity(edge, k, shape) + thelen_velocity_slope(edge, k, shape) * (fv - edge)
}

/// The force–velocity multiplier at normalised fibre velocity `ṽ` and activation `a`: the
/// inverse of [`force_velocity_inverse`], in closed form. With `k = 0.25 + 0.75 a`:
/// `(k + ṽ)/(k - ṽ/Af)` for `-k < ṽ <= 0`; `(k + c Flen ṽ)/(k + c ṽ)`,
/// `c = (2 + 2/Af)/(Flen - 1)`, for lengthening up to the threshold; linear beyond either end.
/// Below `ṽ = -k` the multiplier is negative, as the muscle's force balance gives it; OpenSim's
/// `calcfvInv` (used only to initialise the fibre length) clamps it at 0.
pub fn force_velocity(
    norm_fiber_velocity: f64,
    activation: f64,
    shape: &ForceVelocityShape,
) -> f64 {
    let v = norm_fiber_velocity;
    let k = velocity_scale(activation);
    let upper = shape.upper_multiplier();
    let v_lower = thelen_velocity(0.0, k, shape);
    let v_upper = thelen_velocity(upper, k, shape);
    if v <= v_lower {
        (v - v_lower) / thelen_velocity_slope(0.0, k, shape)
    } else if v >= v_upper {
        upper + (v - v_upper) / thelen_velocity_slope(upper, k, shape)
    } else if v <= 0.0 {
        (k + v) / (k - v / shape.af)
    } else {
        let c = shape.eccentric_factor();
        (k + c * shape.flen * v) / (k + c * v)
    }
}

/// `df_V/dṽ` of [`force_velocity`], branch by branch: the inverse slopes of the tangent lines
/// outside, `k (1 + 1/Af)/(k - ṽ/Af)²` shortening, `c k (Flen - 1)/(k + c ṽ)²` lengthening.
pub(crate) fn force_velocity_derivative(
    norm_fiber_velocity: f64,
    activation: f64,
    shape: &ForceVelocityShape,
) -> f64 {
    let v = norm_fiber_velocity;
    let k = velocity_scale(activation);
    let upper = shape.upper_multiplier();
    if v <= thelen_velocity(0.0, k, shape) {
        1.0 / thelen_velocity_slope(0.0, k, shape)
    } else if v >= thelen_velocity(upper, k, shape) {
        1.0 / thelen_velocity_slope(upper, k, shape)
    } else if v <= 0.0 {
        let d = k - v / shape.af;
        k * (1.0 + 1.0 / shape.af) / (d * d)
    } else {
        let c = shape.eccentric_factor();
        let d = k + c * v;
        c * k * (shape.flen - 1.0) / (d * d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const EM: f64 = DEFAULT_FMAX_MUSCLE_STRAIN;
    const KP: f64 = DEFAULT_KSHAPE_PASSIVE;
    const ET: f64 = DEFAULT_FMAX_TENDON_STRAIN;

    fn central_difference(f: impl Fn(f64) -> f64, x: f64) -> f64 {
        let h = 1e-6;
        (f(x + h) - f(x - h)) / (2.0 * h)
    }

    #[test]
    fn active_force_length_is_a_gaussian_peaking_at_one() {
        assert_eq!(active_force_length(1.0, DEFAULT_KSHAPE_ACTIVE), 1.0);
        let at = active_force_length(1.0 + 0.45f64.sqrt(), DEFAULT_KSHAPE_ACTIVE);
        assert!((at - (-1.0f64).exp()).abs() < 1e-15);
        for i in 0..=20 {
            let l = 0.4 + 1.2 * i as f64 / 20.0;
            let fd = central_difference(|x| active_force_length(x, 0.45), l);
            assert!(
                (active_force_length_derivative(l, 0.45) - fd).abs() < 1e-8,
                "at {l}"
            );
        }
    }

    #[test]
    fn passive_force_is_zero_to_optimal_length_and_one_at_its_strain() {
        assert_eq!(passive_force_length(1.0, EM, KP), 0.0);
        assert_eq!(passive_force_length(0.7, EM, KP), 0.0);
        assert!((passive_force_length(1.6, EM, KP) - 1.0).abs() < 1e-14);
        for l in [1.1, 1.3, 1.5] {
            let fd = central_difference(|x| passive_force_length(x, EM, KP), l);
            assert!(
                (passive_force_length_derivative(l, EM, KP) - fd).abs() < 1e-7,
                "at {l}"
            );
        }
    }

    #[test]
    fn tendon_force_is_one_at_its_strain_and_continuous_at_the_toe() {
        assert_eq!(tendon_force_length(1.0, ET), 0.0);
        assert!((tendon_force_length(1.0 + ET, ET) - 1.0).abs() < 1e-14);
        let toe = 1.0 + tendon_toe_strain(ET);
        let h = 1e-9;
        let below = tendon_force_length(toe - h, ET);
        let above = tendon_force_length(toe + h, ET);
        assert!((below - TOE_FORCE).abs() < 1e-7 && (above - TOE_FORCE).abs() < 1e-7);
        // The slope is continuous too: ε_toe is exact, not the paper's 0.609 ε₀.
        let (d_below, d_above) = (
            tendon_force_length_derivative(toe - h, ET),
            tendon_force_length_derivative(toe + h, ET),
        );
        assert!(
            (d_below - d_above).abs() < 1e-6 * d_above,
            "{d_below} {d_above}"
        );
        assert!((tendon_toe_strain(ET) / ET - 0.609).abs() < 1e-3);
    }

    #[test]
    fn integrals_differentiate_to_the_curves_and_inverses_undo_them() {
        for i in 0..=40 {
            let lt = 0.99 + 0.07 * i as f64 / 40.0;
            let f = tendon_force_length(lt, ET);
            let fd = central_difference(|x| tendon_force_length_integral(x, ET), lt);
            assert!((fd - f).abs() < 1e-8 * f.max(1.0), "∫f_T' at {lt}");
            if f > 0.0 {
                let back = tendon_force_length_inverse(f, ET);
                assert!((back - lt).abs() < 1e-13, "f_T⁻¹ at {lt}");
            }
            // Off optimal length, where the passive curve's slope jumps.
            let l = 0.9 + 0.8 * (i as f64 + 0.37) / 40.0;
            let f = passive_force_length(l, EM, KP);
            let fd = central_difference(|x| passive_force_length_integral(x, EM, KP), l);
            assert!((fd - f).abs() < 1e-8 * f.max(1.0), "∫f_PE' at {l}");
            if f > 0.0 {
                let back = passive_force_length_inverse(f, EM, KP);
                assert!((back - l).abs() < 1e-13, "f_PE⁻¹ at {l}");
            }
        }
        assert_eq!(tendon_force_length_inverse(0.0, ET), 1.0);
        assert_eq!(passive_force_length_inverse(-1.0, EM, KP), 1.0);
    }

    #[test]
    fn force_velocity_passes_through_its_key_points() {
        let s = ForceVelocityShape::default();
        assert_eq!(force_velocity(0.0, 1.0, &s), 1.0);
        assert!(force_velocity(-1.0, 1.0, &s).abs() < 1e-15);
        // Thelen's maximum shortening velocity falls with activation.
        assert!(force_velocity(-0.625, 0.5, &s).abs() < 1e-15);
        assert!(force_velocity(-1.5, 1.0, &s) < 0.0);
        // Lengthening approaches Flen until the linear extrapolation takes over.
        assert!(force_velocity(0.1, 1.0, &s) > 1.2 && force_velocity(0.1, 1.0, &s) < s.flen);
        assert!(force_velocity(2.0, 1.0, &s) > s.flen);
    }

    #[test]
    fn force_velocity_undoes_its_inverse_across_every_branch() {
        let s = ForceVelocityShape::default();
        for a in [0.05, 0.5, 1.0] {
            for i in 0..=80 {
                let fv = -0.3 + 2.0 * i as f64 / 80.0;
                let v = force_velocity_inverse(fv, a, &s);
                assert!(
                    (force_velocity(v, a, &s) - fv).abs() < 1e-13,
                    "a {a}, fv {fv}"
                );
            }
        }
    }

    #[test]
    fn force_velocity_is_continuous_at_the_extrapolation_thresholds() {
        let s = ForceVelocityShape::default();
        for edge in [0.0, s.linear_extrap_threshold * s.flen] {
            let v = force_velocity_inverse(edge, 1.0, &s);
            let h = 1e-9;
            let (lo, hi) = (
                force_velocity(v - h, 1.0, &s),
                force_velocity(v + h, 1.0, &s),
            );
            assert!(
                (lo - edge).abs() < 1e-7 && (hi - edge).abs() < 1e-7,
                "at {edge}"
            );
            let slope_lo = (force_velocity(v, 1.0, &s) - force_velocity(v - 1e-6, 1.0, &s)) / 1e-6;
            let slope_hi = (force_velocity(v + 1e-6, 1.0, &s) - force_velocity(v, 1.0, &s)) / 1e-6;
            assert!(
                (slope_lo - slope_hi).abs() < 1e-3 * slope_hi.abs().max(1.0),
                "at {edge}"
            );
        }
    }
}
