//! A limb's parameters, of its muscles and its joints (docs/model.md §1, §6, §8), their embedded
//! defaults and their validation; the energetics table's data (§11) in [`energetics_table`].
//!
//! Everything is SI: m, s, N, kg. The defaults are the paper's Appendix A, Table 1.

use serde::{Deserialize, Serialize};

mod activation_rules;
mod curve_rules;
pub(crate) mod curve_set;
pub(crate) mod energetics_table;
pub(crate) mod formulation;
pub(crate) mod tabulated_points;

use curve_set::CurveSet;
use formulation::{ActivationKind, FibreKind, TendonKind};
use tabulated_points::TabulatedCurves;

pub(crate) use energetics_table::{EnergeticsParams, EnergyModel};

/// Shape of the force–length curve f(l_m) (docs/model.md §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ForceLengthShape {
    /// `max(0, 1 - ((l/lopt - 1)/w)^2)`: our reading of the paper's eq. (3).
    #[default]
    Parabola,
    /// `exp(-((l/lopt - 1)/w)^2)`: the documented alternative.
    Gaussian,
}

/// Parameters of one muscle–tendon unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MuscleParams {
    /// Muscle mass M carried by the fibre, kg.
    pub mass: f64,
    /// Maximum isometric force Fmax, N.
    pub f_max: f64,
    /// Optimal fibre length lopt, m.
    pub l_opt: f64,
    /// Maximum unloaded shortening velocity vmax, m/s.
    pub v_max: f64,
    /// Activation time constant, s.
    pub t_act: f64,
    /// Deactivation time constant, s.
    pub t_deact: f64,
    /// Width w of the force–length curve (dimensionless).
    pub fl_width: f64,
    /// Shape of the force–length curve.
    pub fl_shape: ForceLengthShape,
    /// Eccentric force asymptote N of the Hill force–velocity curve (our choice, docs/model.md §3).
    pub eccentric_asymptote: f64,
    /// Tendon exponential shape k_te, 1/m.
    pub k_te: f64,
    /// Tendon spring constant of the exponential part k_tl, N/m.
    pub k_tl: f64,
    /// Tendon spring constant of the linear part k_t, N/m.
    pub k_t: f64,
    /// Tendon slack length l_ts, m.
    pub l_ts: f64,
    /// Tendon length where it turns linear, m. `None` derives it by force continuity (docs/model.md §4).
    pub l_tc: Option<f64>,
    /// Tendon force where it turns linear, N.
    pub(crate) f_tc: f64,
    /// Parallel element exponential shape k_me, 1/m.
    pub k_me: f64,
    /// Parallel spring constant of the exponential part k_ml, N/m.
    pub k_ml: f64,
    /// Parallel spring constant of the linear part k_m, N/m.
    pub k_m: f64,
    /// Passive muscle slack length l_ms, m.
    pub l_ms: f64,
    /// Length where the parallel spring turns linear l_mc, m.
    pub l_mc: f64,
    /// Force where the parallel spring turns linear F_mc, N.
    pub(crate) f_mc: f64,
    /// Parallel damping B_m, N s/m.
    pub b_m: f64,
    /// The curve set of the tendon, the parallel element, the active force–length relation and
    /// the Hill force–velocity relation (docs/model.md §4b); written out only when not the
    /// paper's.
    #[serde(skip_serializing_if = "CurveSet::is_paper")]
    pub curves: CurveSet,
    /// Tendon strain at one normalised force of an OpenSim curve set (OpenSim's
    /// `tendon_strain_at_one_norm_force`, `FmaxTendonStrain`); `None`: the set's default.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tendon_strain: Option<f64>,
    /// Fibre strain at one normalised passive force of an OpenSim curve set (OpenSim's
    /// `passive_fiber_strain_at_one_norm_force`, `FmaxMuscleStrain`); `None`: the set's default.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub passive_strain: Option<f64>,
    /// DeGroote 2016's active force–length width scale (OpenSim's `active_force_width_scale`,
    /// >= 1); `None`: 1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub active_force_width_scale: Option<f64>,
    /// Thelen 2003's active force–length shape γ (OpenSim's `KshapeActive`); `None`: 0.45.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kshape_active: Option<f64>,
    /// Thelen 2003's passive shape k_PE (OpenSim's `KshapePassive`); `None`: 5.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kshape_passive: Option<f64>,
    /// Thelen 2003's force–velocity shape Af (OpenSim's `Af`); `None`: 0.25.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub af: Option<f64>,
    /// Thelen 2003's eccentric force asymptote Flen, normalised (OpenSim's `Flen`, > 1);
    /// `None`: 1.4.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flen: Option<f64>,
    /// How the fibre moves: with mass (the paper's, the default) or in equilibrium with the
    /// tendon (docs/model.md §5b); written out only when not the default.
    #[serde(skip_serializing_if = "FibreKind::is_massed")]
    pub fibre: FibreKind,
    /// Whether the tendon stretches (the default) or is rigid (docs/model.md §5b); written out
    /// only when not the default.
    #[serde(skip_serializing_if = "TendonKind::is_elastic")]
    pub tendon: TendonKind,
    /// Pennation angle α_opt at optimal fibre length, rad, the muscle's thickness constant
    /// (docs/model.md §5b); 0, the default, lays the fibres along the tendon and is not written
    /// out.
    #[serde(skip_serializing_if = "is_zero")]
    pub pennation: f64,
    /// The optimal fibre length's lengthening at low activation s: the active force–length
    /// relation is read at `l_m / (l_opt (1 + s (1 − a)))` (docs/model.md §3b; CEINMS's
    /// `percentageChange`, Lloyd & Besier 2003 after Huijing 1996), in [0, 1); `None`: 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub optimal_length_shift: Option<f64>,
    /// How excitation becomes activation (docs/model.md §2, §2b); written out only when not the
    /// paper's first order.
    #[serde(skip_serializing_if = "ActivationKind::is_first_order")]
    pub activation: ActivationKind,
    /// Lloyd & Besier's C1 (|C1| < 1), needed with `activation = "lloyd_besier"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub c1: Option<f64>,
    /// Lloyd & Besier's C2 (|C2| < 1), needed with `activation = "lloyd_besier"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub c2: Option<f64>,
    /// The activation nonlinearity's shape factor A, in [-3, 3]; `None`: 0, linear.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shape_factor: Option<f64>,
    /// The electromechanical delay, s, in [0, 0.5]; `None`: 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub em_delay: Option<f64>,
    /// The sample rate C1 and C2 belong to, Hz; `None`: the tick rate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub neural_rate_hz: Option<f64>,
    /// Cross-bridge parameters of the Huxley models.
    pub crossbridge: CrossBridgeParams,
    /// Energetics: the phenomenological heat-rate model and the energy constants (§11).
    pub energetics: EnergeticsParams,
    /// The curves of `curves = "tabulated"`, as points (§4b); needed with that set only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tabulated: Option<TabulatedCurves>,
}

impl Default for MuscleParams {
    fn default() -> Self {
        Self {
            mass: 0.95,
            f_max: 3913.0,
            l_opt: 0.0959,
            v_max: 0.5179,
            t_act: 0.0012,
            t_deact: 0.012,
            fl_width: 0.643,
            fl_shape: ForceLengthShape::Parabola,
            eccentric_asymptote: 1.8,
            k_te: 3022.0,
            k_tl: 31140.0,
            k_t: 635540.0,
            l_ts: 0.3185,
            l_tc: None,
            f_tc: 200.0,
            k_me: 90.4,
            k_ml: 487.5,
            k_m: 6770.0,
            l_ms: 0.0959,
            l_mc: 0.125,
            f_mc: 69.4723,
            b_m: 257.1,
            curves: CurveSet::Paper,
            tendon_strain: None,
            passive_strain: None,
            active_force_width_scale: None,
            kshape_active: None,
            kshape_passive: None,
            af: None,
            flen: None,
            fibre: FibreKind::Massed,
            tendon: TendonKind::Elastic,
            pennation: 0.0,
            optimal_length_shift: None,
            activation: ActivationKind::FirstOrder,
            c1: None,
            c2: None,
            shape_factor: None,
            em_delay: None,
            neural_rate_hz: None,
            crossbridge: CrossBridgeParams::default(),
            energetics: EnergeticsParams::default(),
            tabulated: None,
        }
    }
}

/// Cross-bridge (Huxley 1957) parameters, docs/model.md §6–7. Rates are Huxley's ratios; one common
/// factor is chosen at start-up so that the model's unloaded shortening velocity equals vmax.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CrossBridgeParams {
    /// Attachment rate slope f1 (relative units).
    pub f1: f64,
    /// Detachment rate slope g1 on [0, 1] (relative units).
    pub g1: f64,
    /// Detachment rate for ξ < 0 (relative units).
    pub g2: f64,
    /// Extra detachment slope for ξ > 1 (Huxley: 0).
    pub g3: f64,
    /// Attachment range h, m.
    pub h: f64,
    /// Optimal half-sarcomere length, m.
    pub(crate) s_hs: f64,
    /// Grid cells per unit ξ of the full Huxley model (method of characteristics).
    pub pde_cells: usize,
}

impl Default for CrossBridgeParams {
    fn default() -> Self {
        Self {
            f1: 43.3,
            g1: 10.0,
            g2: 209.0,
            g3: 0.0,
            h: 15.6e-9,
            s_hs: 1.1e-6,
            pde_cells: 200,
        }
    }
}

/// A revolute joint (docs/model.md §8, §8b): an independent rotational inertia with damping and
/// end stops.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct JointParams {
    /// Joint name as published on `joint_states`.
    pub name: String,
    /// Moment of inertia I, kg m².
    pub inertia: f64,
    /// Viscous damping c, N m s/rad.
    pub damping: f64,
    /// Lower end of the range of motion, rad.
    pub min_angle: f64,
    /// Upper end of the range of motion, rad.
    pub max_angle: f64,
    /// Stiffness of the end stops, N m/rad.
    pub limit_stiffness: f64,
    /// Damping of the end stops, N m s/rad.
    pub limit_damping: f64,
    /// Initial joint angle, rad (a driven joint: the angle it holds until its motion is set).
    pub initial_angle: f64,
    /// Driven by a robot simulator: its angle and velocity are inputs, not integrated (docs/
    /// model.md §8c); inertia, damping and end stops are then unused (still validated).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub driven: bool,
}

impl Default for JointParams {
    fn default() -> Self {
        Self {
            name: "elbow".into(),
            inertia: 0.06,
            damping: 0.05,
            min_angle: -std::f64::consts::FRAC_PI_2,
            max_angle: std::f64::consts::FRAC_PI_2,
            limit_stiffness: 500.0,
            limit_damping: 5.0,
            initial_angle: 0.0,
            driven: false,
        }
    }
}

/// One rule that a parameter breaks.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamError {
    /// Dotted path of the parameter, e.g. `muscle.flexor.f_max`.
    pub parameter: String,
    /// The value found.
    pub value: String,
    /// The rule it breaks.
    pub rule: &'static str,
}

impl std::fmt::Display for ParamError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "invalid parameter {} = {}: {}",
            self.parameter, self.value, self.rule
        )
    }
}

struct Checker<'a> {
    prefix: &'a str,
    errors: &'a mut Vec<ParamError>,
}

impl Checker<'_> {
    fn fail(&mut self, name: &str, value: impl std::fmt::Display, rule: &'static str) {
        self.errors.push(ParamError {
            parameter: format!("{}{}", self.prefix, name),
            value: value.to_string(),
            rule,
        });
    }
    fn positive(&mut self, name: &str, v: f64) {
        if !v.is_finite() {
            self.fail(name, v, "must be a finite number");
        } else if v <= 0.0 {
            self.fail(name, v, "must be > 0");
        }
    }
    fn non_negative(&mut self, name: &str, v: f64) {
        if !v.is_finite() {
            self.fail(name, v, "must be a finite number");
        } else if v < 0.0 {
            self.fail(name, v, "must be >= 0");
        }
    }
    fn finite(&mut self, name: &str, v: f64) {
        if !v.is_finite() {
            self.fail(name, v, "must be a finite number");
        }
    }
}

/// The largest pennation at optimal length, rad: OpenSim's `maximum_pennation_angle`,
/// acos(0.1), the angle at which [`crate::physics::pennation`] holds shorter fibres.
pub(crate) const MAX_PENNATION: f64 = 1.4706289056333368;

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// Relative force jump at l_tc above which a configured l_tc is reported as discontinuous.
pub(crate) const TENDON_CONTINUITY_TOLERANCE: f64 = 1e-3;

impl MuscleParams {
    /// Tendon length where the tendon turns linear, by force continuity (docs/model.md §4):
    /// `l_tc = l_ts + ln(1 + F_tc k_te / k_tl) / k_te`.
    pub fn derived_l_tc(&self) -> f64 {
        self.l_ts + (1.0 + self.f_tc * self.k_te / self.k_tl).ln() / self.k_te
    }

    /// l_tc in force: the configured one, or the derived one.
    pub(crate) fn l_tc(&self) -> f64 {
        self.l_tc.unwrap_or_else(|| self.derived_l_tc())
    }

    /// The formulation rules (docs/model.md §5b): a rigid tendon needs an equilibrium fibre (a
    /// fibre with mass on it would ride on the joint) and has no strain to set; pennation lies in
    /// [0, acos 0.1) and needs an equilibrium fibre.
    fn validate_formulation(&self, c: &mut Checker<'_>) {
        let alpha = self.pennation;
        if !alpha.is_finite() || !(0.0..MAX_PENNATION).contains(&alpha) {
            c.fail(
                "pennation",
                alpha,
                "must be >= 0 and < 1.4706 rad (84.3°, OpenSim's largest pennation angle)",
            );
        } else if alpha > 0.0 && self.fibre == FibreKind::Massed {
            c.fail(
                "pennation",
                alpha,
                "needs fibre = \"equilibrium\" (the fibre with mass moves along the tendon)",
            );
        }
        if self.tendon != TendonKind::Rigid {
            return;
        }
        if self.fibre == FibreKind::Massed {
            c.fail(
                "tendon",
                "rigid",
                "needs fibre = \"equilibrium\" (a rigid tendon leaves a fibre with mass no \
                 motion of its own)",
            );
        }
        if let Some(v) = self.tendon_strain {
            c.fail("tendon_strain", v, "does not apply to a rigid tendon");
        }
    }

    /// Appends one error per broken rule; `prefix` names the muscle (e.g. `muscle.flexor.`).
    pub(crate) fn validate(&self, prefix: &str, errors: &mut Vec<ParamError>) {
        let mut c = Checker { prefix, errors };
        c.positive("mass", self.mass);
        c.positive("f_max", self.f_max);
        c.positive("l_opt", self.l_opt);
        c.positive("v_max", self.v_max);
        c.positive("t_act", self.t_act);
        c.positive("t_deact", self.t_deact);
        c.positive("fl_width", self.fl_width);
        c.finite("eccentric_asymptote", self.eccentric_asymptote);
        if self.eccentric_asymptote.is_finite() && self.eccentric_asymptote <= 1.0 {
            c.fail(
                "eccentric_asymptote",
                self.eccentric_asymptote,
                "must be > 1",
            );
        }
        c.positive("k_te", self.k_te);
        c.positive("k_tl", self.k_tl);
        c.positive("k_t", self.k_t);
        c.positive("l_ts", self.l_ts);
        c.positive("f_tc", self.f_tc);
        c.positive("k_me", self.k_me);
        c.positive("k_ml", self.k_ml);
        c.positive("k_m", self.k_m);
        c.positive("l_ms", self.l_ms);
        c.positive("l_mc", self.l_mc);
        c.non_negative("f_mc", self.f_mc);
        c.non_negative("b_m", self.b_m);
        if self.l_mc.is_finite() && self.l_ms.is_finite() && self.l_mc <= self.l_ms {
            c.fail("l_mc", self.l_mc, "must be > l_ms");
        }
        if let Some(l_tc) = self.l_tc {
            c.positive("l_tc", l_tc);
            if l_tc.is_finite() && self.l_ts.is_finite() && l_tc < self.l_ts {
                c.fail("l_tc", l_tc, "must be >= l_ts");
            }
        }
        self.validate_curves(&mut c);
        self.validate_formulation(&mut c);
        self.validate_activation(&mut c);
        let x = &self.crossbridge;
        let mut c = Checker {
            prefix: &format!("{prefix}crossbridge."),
            errors: c.errors,
        };
        c.positive("f1", x.f1);
        c.positive("g1", x.g1);
        c.positive("g2", x.g2);
        c.non_negative("g3", x.g3);
        c.positive("h", x.h);
        c.positive("s_hs", x.s_hs);
        if x.pde_cells < 10 || x.pde_cells > 100_000 {
            c.fail("pde_cells", x.pde_cells, "must be between 10 and 100000");
        }
        let e = &self.energetics;
        let mut c = Checker {
            prefix: &format!("{prefix}energetics."),
            errors: c.errors,
        };
        // Bounds of physical sense, wide: they keep every energetics output finite (the ATP
        // rate scales as 1/e, the activation heat as s/(1 - s)).
        let within = |v: f64, lo: f64, hi: f64| v.is_finite() && (lo..=hi).contains(&v);
        if !within(e.atp_free_energy, 1e-21, 1e-17) {
            c.fail(
                "atp_free_energy",
                e.atp_free_energy,
                "must be from 1e-21 to 1e-17 J",
            );
        }
        if !(within(e.hill_a_over_p0, 0.0, 10.0) && e.hill_a_over_p0 > 0.0) {
            c.fail("hill_a_over_p0", e.hill_a_over_p0, "must be > 0 and <= 10");
        }
        if !within(e.activation_share, 0.0, 0.9) {
            c.fail(
                "activation_share",
                e.activation_share,
                "must be in [0, 0.9]",
            );
        }
        if !within(e.slow_twitch_ratio, 0.0, 1.0) {
            c.fail(
                "slow_twitch_ratio",
                e.slow_twitch_ratio,
                "must be in [0, 1]",
            );
        }
        if let Some(m) = e.metabolic_mass {
            if !(within(m, 0.0, 1e3) && m > 0.0) {
                c.fail("metabolic_mass", m, "must be > 0 and <= 1000 kg");
            }
        }
    }

    /// A warning when a configured l_tc breaks force continuity of the tendon (docs/model.md §4).
    pub(crate) fn continuity_warning(&self, prefix: &str) -> Option<String> {
        let l_tc = self.l_tc?;
        let exp_force = self.k_tl / self.k_te * ((self.k_te * (l_tc - self.l_ts)).exp() - 1.0);
        let jump = (exp_force - self.f_tc).abs();
        (jump > TENDON_CONTINUITY_TOLERANCE * self.f_tc).then(|| {
            format!(
                "{prefix}l_tc = {l_tc} breaks tendon force continuity: the exponential part gives \
                 {exp_force:.3} N there, F_tc = {} N (jump {jump:.3} N); continuity needs l_tc = {:.7} m",
                self.f_tc,
                self.derived_l_tc()
            )
        })
    }
}

impl JointParams {
    /// Appends one error per broken rule.
    pub(crate) fn validate(&self, prefix: &str, errors: &mut Vec<ParamError>) {
        let mut c = Checker { prefix, errors };
        c.positive("inertia", self.inertia);
        c.non_negative("damping", self.damping);
        c.finite("min_angle", self.min_angle);
        c.finite("max_angle", self.max_angle);
        if self.min_angle.is_finite()
            && self.max_angle.is_finite()
            && self.min_angle >= self.max_angle
        {
            c.fail("max_angle", self.max_angle, "must be > min_angle");
        }
        c.non_negative("limit_stiffness", self.limit_stiffness);
        c.non_negative("limit_damping", self.limit_damping);
        c.finite("initial_angle", self.initial_angle);
        if self.initial_angle.is_finite()
            && (self.initial_angle < self.min_angle || self.initial_angle > self.max_angle)
        {
            c.fail(
                "initial_angle",
                self.initial_angle,
                "must lie within [min_angle, max_angle]",
            );
        }
    }
}
