//! Umberger (2010) heat rates (Umberger, Gerritsen & Martin 2003; Umberger 2010, J R Soc
//! Interface 7:1329), with the options of Uchida et al. (2016, PLoS ONE 11:e0150378), as
//! opensim-core's `Umberger2010MuscleMetabolicsProbe` computes them (docs/model.md §11.4).
//! Rates per kg of muscle, then times the mass; v̄ = v / lopt in lopt/s, negative shortening.

use crate::physics::energetics::probe::{
    floor_heat, forbid_negative_total, probe_work_w, ExcitationTerms, ProbeInputs, ProbeMuscle,
    ProbeRates,
};

/// Options of the Umberger model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct UmbergerOptions {
    /// Aerobic scaling S: 1.5 for aerobic activity, 1.0 for anaerobic (Umberger 2003).
    pub(crate) aerobic_factor: f64,
    /// Replace the fibre-type ratio r by Bhargava's recruited share `u_ST / (u_ST + u_FT)`.
    pub(crate) bhargava_recruitment: bool,
    /// Lengthening heat coefficient k of `S A k α_ST v̄`: 0.3 (Umberger 2010), 4.0 (Umberger
    /// 2003, Uchida 2016).
    pub(crate) lengthening_coefficient: f64,
    /// Count negative work (`-F v` when lengthening) in the total.
    pub(crate) negative_work: bool,
    /// Raise the shortening heat so that the total is not negative.
    pub(crate) forbid_negative_total: bool,
    /// Floor the heat rate at 1 W/kg.
    pub(crate) heat_floor: bool,
}

impl UmbergerOptions {
    /// As published by Umberger (2010).
    pub(crate) fn umberger_2010() -> Self {
        Self {
            aerobic_factor: 1.5,
            bhargava_recruitment: false,
            lengthening_coefficient: 0.3,
            negative_work: false,
            forbid_negative_total: false,
            heat_floor: true,
        }
    }
    /// With the changes of Uchida et al. (2016): OpenSim's defaults.
    pub(crate) fn uchida_2016() -> Self {
        Self {
            bhargava_recruitment: true,
            lengthening_coefficient: 4.0,
            negative_work: true,
            forbid_negative_total: true,
            ..Self::umberger_2010()
        }
    }
}

impl Default for UmbergerOptions {
    fn default() -> Self {
        Self::uchida_2016()
    }
}

/// Activation dependence `A = u` if `u > a`, else `(u + a)/2`.
pub(crate) fn effort(excitation: f64, activation: f64) -> f64 {
    if excitation > activation {
        excitation
    } else {
        0.5 * (excitation + activation)
    }
}

/// The slow-twitch share used: r itself, or Bhargava's recruited share
/// `u_ST / (u_ST + u_FT)` (1 when u = 0) from the excitation's terms.
pub(crate) fn slow_twitch_share(
    terms: &ExcitationTerms,
    ratio: f64,
    bhargava_recruitment: bool,
) -> f64 {
    if bhargava_recruitment {
        terms.recruited_share
    } else {
        ratio
    }
}

/// Activation and maintenance heat, W/kg: `S A^0.6 X`, `X = 128 (1 - r) + 25`; beyond lopt
/// `X (0.4 + 0.6 F_iso)`; `a_power` is `A^0.6`.
pub(crate) fn activation_maintenance_w_kg(
    s: f64,
    a_power: f64,
    share: f64,
    l_norm: f64,
    f_iso: f64,
) -> f64 {
    let x = 128.0 * (1.0 - share) + 25.0;
    let x = if l_norm <= 1.0 {
        x
    } else {
        x * (0.4 + 0.6 * f_iso)
    };
    s * a_power * x
}

/// Shortening heat, W/kg, `v̄ ≤ 0`: `S A² [min(α_ST |v̄|, 100) r + α_FT |v̄| (1 - r)]` with
/// `α_ST = 100 / (V_max/2.5)`, `α_FT = 153 / V_max` (V_max, v̄ in lopt/s).
pub(crate) fn shortening_w_kg(s: f64, a: f64, share: f64, v_norm: f64, v_max: f64) -> f64 {
    // One division: 100 / (V_max / 2.5) = 250 / V_max.
    let inv_v_max = 1.0 / v_max;
    let alpha_slow = 250.0 * inv_v_max;
    let alpha_fast = 153.0 * inv_v_max;
    let slow = (alpha_slow * -v_norm).min(100.0);
    s * a * a * (slow * share + alpha_fast * -v_norm * (1.0 - share))
}

/// Lengthening heat, W/kg, `v̄ > 0`: `S A k α_ST v̄`.
pub(crate) fn lengthening_w_kg(s: f64, a: f64, k: f64, v_norm: f64, v_max: f64) -> f64 {
    s * a * k * (250.0 / v_max) * v_norm
}

/// The Umberger rates of one muscle at one instant, W.
#[cfg(test)]
pub(crate) fn umberger_rates(o: &UmbergerOptions, m: &ProbeMuscle, x: &ProbeInputs) -> ProbeRates {
    let terms = ExcitationTerms::new(x.excitation, m.slow_twitch_ratio);
    umberger_rates_with(o, m, x, &terms)
}

/// The same with the excitation's terms computed beforehand (`terms.excitation` is
/// `x.excitation`), W.
pub(crate) fn umberger_rates_with(
    o: &UmbergerOptions,
    m: &ProbeMuscle,
    x: &ProbeInputs,
    terms: &ExcitationTerms,
) -> ProbeRates {
    let a = effort(x.excitation, x.activation);
    let share = slow_twitch_share(terms, m.slow_twitch_ratio, o.bhargava_recruitment);
    let s = o.aerobic_factor;
    let v_norm = x.fibre_velocity_m_s / m.l_opt_m;
    let a_power = terms.effort_power(a);
    let am = activation_maintenance_w_kg(s, a_power, share, x.fibre_length_norm, x.force_length);
    let mut sh = if v_norm <= 0.0 {
        shortening_w_kg(s, a, share, v_norm, m.v_max_lopt_s)
    } else {
        lengthening_w_kg(s, a, o.lengthening_coefficient, v_norm, m.v_max_lopt_s)
    };
    if x.fibre_length_norm > 1.0 {
        sh *= x.force_length;
    }
    let work = probe_work_w(
        x.active_force_n.max(0.0),
        x.fibre_velocity_m_s,
        o.negative_work,
    );
    let mut r = ProbeRates {
        activation_maintenance_w: am * m.mass_kg,
        shortening_w: sh * m.mass_kg,
        work_w: work,
    };
    if o.forbid_negative_total {
        r = forbid_negative_total(r);
    }
    if o.heat_floor {
        r = floor_heat(r, m.mass_kg);
    }
    r
}
