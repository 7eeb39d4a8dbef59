//! Bhargava, Pandy & Anderson (2004, J Biomech 37:81) heat rates, as opensim-core's
//! `Bhargava2004MuscleMetabolicsProbe` computes them (docs/model.md §11.4), W.

use crate::physics::energetics::probe::{
    floor_heat, forbid_negative_total, probe_work_w, ExcitationTerms, ProbeInputs, ProbeMuscle,
    ProbeRates,
};

/// Options and constants of the Bhargava model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BhargavaOptions {
    /// Activation heat constants of slow- and fast-twitch fibres, W/kg (40, 133).
    pub(crate) activation_w_kg: [f64; 2],
    /// Maintenance heat constants of slow- and fast-twitch fibres, W/kg (74, 111).
    pub(crate) maintenance_w_kg: [f64; 2],
    /// Shortening heat coefficient `0.16 F_iso + 0.18 F` (shortening) and `0.157 F`
    /// (lengthening) instead of `0.25 F` and 0.
    pub(crate) force_dependent_shortening: bool,
    /// Count negative work (`-F v` when lengthening) in the total.
    pub(crate) negative_work: bool,
    /// Raise the shortening heat so that the total is not negative.
    pub(crate) forbid_negative_total: bool,
    /// Floor the heat rate at 1 W/kg.
    pub(crate) heat_floor: bool,
}

impl Default for BhargavaOptions {
    /// OpenSim's defaults.
    fn default() -> Self {
        Self {
            activation_w_kg: [40.0, 133.0],
            maintenance_w_kg: [74.0, 111.0],
            force_dependent_shortening: false,
            negative_work: true,
            forbid_negative_total: true,
            heat_floor: true,
        }
    }
}

/// Fibre-length dependence of the maintenance heat: piecewise linear through (0, 0.5),
/// (0.5, 0.5), (1, 1), (1.5, 0), (2, 0), constant beyond the ends (OpenSim's default curve).
pub(crate) fn maintenance_length_factor(l_norm: f64) -> f64 {
    const X: [f64; 5] = [0.0, 0.5, 1.0, 1.5, 2.0];
    const Y: [f64; 5] = [0.5, 0.5, 1.0, 0.0, 0.0];
    if l_norm <= X[0] {
        return Y[0];
    }
    for i in 1..X.len() {
        if l_norm <= X[i] {
            let t = (l_norm - X[i - 1]) / (X[i] - X[i - 1]);
            return Y[i - 1] + t * (Y[i] - Y[i - 1]);
        }
    }
    Y[X.len() - 1]
}

/// Heat of the recruited fibres, `mass (c_ST u_ST + c_FT u_FT)`, W.
pub(crate) fn fibre_heat_w(mass_kg: f64, constants_w_kg: [f64; 2], recruited: (f64, f64)) -> f64 {
    mass_kg * (constants_w_kg[0] * recruited.0 + constants_w_kg[1] * recruited.1)
}

/// Shortening heat `-α v`, W, with `α = 0.25 F` shortening and 0 lengthening, or the
/// force-dependent `0.16 F_iso + 0.18 F` / `0.157 F`; F the total fibre force, F_iso = a f(l) Fmax.
pub(crate) fn shortening_heat_w(
    force_dependent: bool,
    f_total: f64,
    f_iso: f64,
    v_m_s: f64,
) -> f64 {
    let alpha = match (force_dependent, v_m_s <= 0.0) {
        (true, true) => 0.16 * f_iso + 0.18 * f_total,
        (true, false) => 0.157 * f_total,
        (false, true) => 0.25 * f_total,
        (false, false) => 0.0,
    };
    -alpha * v_m_s
}

/// The Bhargava rates of one muscle at one instant, W.
#[cfg(test)]
pub(crate) fn bhargava_rates(o: &BhargavaOptions, m: &ProbeMuscle, x: &ProbeInputs) -> ProbeRates {
    let terms = ExcitationTerms::new(x.excitation, m.slow_twitch_ratio);
    bhargava_rates_with(o, m, x, &terms)
}

/// The same with the excitation's terms computed beforehand (`terms.excitation` is
/// `x.excitation`), W.
pub(crate) fn bhargava_rates_with(
    o: &BhargavaOptions,
    m: &ProbeMuscle,
    x: &ProbeInputs,
    terms: &ExcitationTerms,
) -> ProbeRates {
    let recruited = terms.recruited;
    let activation = fibre_heat_w(m.mass_kg, o.activation_w_kg, recruited);
    let maintenance = maintenance_length_factor(x.fibre_length_norm)
        * fibre_heat_w(m.mass_kg, o.maintenance_w_kg, recruited);
    let f_total = x.active_force_n + x.passive_force_n;
    let f_iso = x.activation * x.force_length * m.f_max_n;
    let v = x.fibre_velocity_m_s;
    let mut r = ProbeRates {
        activation_maintenance_w: activation + maintenance,
        shortening_w: shortening_heat_w(o.force_dependent_shortening, f_total, f_iso, v),
        work_w: probe_work_w(x.active_force_n, v, o.negative_work),
    };
    if o.forbid_negative_total {
        r = forbid_negative_total(r);
    }
    if o.heat_floor {
        r = floor_heat(r, m.mass_kg);
    }
    r
}
