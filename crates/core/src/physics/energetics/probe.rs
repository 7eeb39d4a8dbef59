//! What the phenomenological heat-rate models share (docs/model.md §11.4), as OpenSim's
//! metabolic probes (opensim-core, `Umberger2010MuscleMetabolicsProbe`,
//! `Bhargava2004MuscleMetabolicsProbe`) compute them: the muscle mass, fibre recruitment, the
//! inputs read from the muscle, what they compute from the excitation alone, the parts of the
//! result, and the two clamps.

use std::f64::consts::FRAC_PI_2;

/// Specific tension σ of mammalian muscle, Pa (OpenSim's default).
pub(crate) const SPECIFIC_TENSION_PA: f64 = 0.25e6;
/// Density ρ of mammalian muscle, kg/m³ (OpenSim's default).
pub(crate) const MUSCLE_DENSITY_KG_M3: f64 = 1059.7;
/// Share of slow-twitch fibres r when none is given (OpenSim's default).
pub(crate) const SLOW_TWITCH_RATIO: f64 = 0.5;
/// Least heat rate of an active muscle, W/kg (Umberger et al. 2003, p. 104).
pub(crate) const MIN_HEAT_RATE_W_KG: f64 = 1.0;

/// Muscle mass from its force and fibre length, `(Fmax / σ) ρ lopt`, kg: the volume of muscle
/// whose cross-section gives Fmax at specific tension σ, times density (OpenSim's probes).
pub(crate) fn muscle_mass_kg(f_max_n: f64, l_opt_m: f64, sigma_pa: f64, rho_kg_m3: f64) -> f64 {
    f_max_n / sigma_pa * rho_kg_m3 * l_opt_m
}

/// Bhargava et al. (2004) recruitment: the excitations of the slow- and fast-twitch fibres,
/// `(r sin(π u/2), (1 - r)(1 - cos(π u/2)))`: slow fibres first.
pub(crate) fn recruitment(excitation: f64, slow_twitch_ratio: f64) -> (f64, f64) {
    let (sin, cos) = (FRAC_PI_2 * excitation).sin_cos();
    (
        slow_twitch_ratio * sin,
        (1.0 - slow_twitch_ratio) * (1.0 - cos),
    )
}

/// The recruited share of slow-twitch fibres `u_ST / (u_ST + u_FT)` (1 when u = 0), from the
/// [`recruitment`] at u.
pub(crate) fn recruited_share(excitation: f64, recruited: (f64, f64)) -> f64 {
    if excitation == 0.0 {
        return 1.0;
    }
    let (slow, fast) = recruited;
    slow / (slow + fast)
}

/// Umberger's activation dependence of the activation and maintenance heat, `A^0.6`
/// (Umberger et al. 2003).
pub(crate) fn effort_power(effort: f64) -> f64 {
    effort.powf(0.6)
}

/// What the probes compute from the excitation u alone: Bhargava's recruitment (a sine and a
/// cosine) and its share of slow-twitch fibres, and Umberger's `A^0.6` for A = u. A run
/// computes them once per command rather than at every instant; the rates are the same to the
/// bit.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ExcitationTerms {
    /// Excitation u, [0, 1].
    pub excitation: f64,
    /// [`recruitment`] at u: the slow- and fast-twitch fibres' excitations.
    pub(crate) recruited: (f64, f64),
    /// [`recruited_share`] at u.
    pub(crate) recruited_share: f64,
    /// [`effort_power`] of u.
    pub(crate) excitation_power: f64,
}

impl ExcitationTerms {
    /// The terms of excitation u for a share r of slow-twitch fibres.
    pub fn new(excitation: f64, slow_twitch_ratio: f64) -> Self {
        let recruited = recruitment(excitation, slow_twitch_ratio);
        Self {
            excitation,
            recruited,
            recruited_share: recruited_share(excitation, recruited),
            excitation_power: effort_power(excitation),
        }
    }

    /// [`effort_power`] of A, from the terms where A = u.
    pub(crate) fn effort_power(&self, effort: f64) -> f64 {
        if effort == self.excitation {
            self.excitation_power
        } else {
            effort_power(effort)
        }
    }
}

/// One muscle's constants for a probe.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ProbeMuscle {
    /// Mass the rates per kg apply to, kg.
    pub mass_kg: f64,
    /// Maximum isometric force Fmax, N.
    pub(crate) f_max_n: f64,
    /// Optimal fibre length lopt, m.
    pub(crate) l_opt_m: f64,
    /// Maximum shortening velocity, lopt/s.
    pub(crate) v_max_lopt_s: f64,
    /// Share of slow-twitch fibres r, [0, 1].
    pub(crate) slow_twitch_ratio: f64,
}

/// What a probe reads from the muscle at one instant.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct ProbeInputs {
    /// Excitation u, [0, 1].
    pub excitation: f64,
    /// Activation a, [0, 1].
    pub activation: f64,
    /// Normalised fibre length `l_m / lopt`.
    pub(crate) fibre_length_norm: f64,
    /// Active force–length factor f(l_m) (OpenSim's F_iso multiplier).
    pub force_length: f64,
    /// Fibre lengthening velocity v, m/s.
    pub(crate) fibre_velocity_m_s: f64,
    /// Active fibre force F_CE, N.
    pub(crate) active_force_n: f64,
    /// Passive fibre force (parallel element), N.
    pub(crate) passive_force_n: f64,
}

/// A probe's metabolic power and its parts, W.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct ProbeRates {
    /// Activation and maintenance heat (with the least-heat floor's increase, if any).
    pub(crate) activation_maintenance_w: f64,
    /// Shortening / lengthening heat (with the non-negative-total increase, if any).
    pub(crate) shortening_w: f64,
    /// Mechanical work rate of the contractile element, positive when shortening.
    pub work_w: f64,
}

impl ProbeRates {
    /// Heat rate, W.
    pub(crate) fn heat_w(&self) -> f64 {
        self.activation_maintenance_w + self.shortening_w
    }
    /// Metabolic power, heat plus work, W.
    pub(crate) fn total_w(&self) -> f64 {
        self.heat_w() + self.work_w
    }
}

/// OpenSim's `forbid_negative_total_power`: the shortening heat rises so that the total is not
/// negative (Uchida et al. 2016).
pub(crate) fn forbid_negative_total(mut r: ProbeRates) -> ProbeRates {
    let total = r.total_w();
    if total < 0.0 {
        r.shortening_w -= total;
    }
    r
}

/// The least-heat floor: heat below `MIN_HEAT_RATE_W_KG · mass` is raised to it (Umberger et
/// al. 2003, p. 104). The increase counts as activation and maintenance heat, the part that
/// does not depend on velocity.
pub(crate) fn floor_heat(mut r: ProbeRates, mass_kg: f64) -> ProbeRates {
    let least = MIN_HEAT_RATE_W_KG * mass_kg;
    let heat = r.heat_w();
    if heat < least {
        r.activation_maintenance_w += least - heat;
    }
    r
}

/// The work rate term `-F_CE v` when `include_negative` or shortening, else 0, W.
pub(crate) fn probe_work_w(active_force_n: f64, v_m_s: f64, include_negative: bool) -> f64 {
    if include_negative || v_m_s <= 0.0 {
        -active_force_n * v_m_s
    } else {
        0.0
    }
}
