//! The bounds a calibration keeps its parameters within (docs/emg.md "Calibration"; a subject
//! file's `[bounds]` table).

/// The calibrated parameters' bounds: `[low, high]` each (a subject file's `[bounds]` table,
/// every key optional).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Bounds {
    /// C1. The recursion's poles are −C1 and −C2: within (−1, 1) it is stable, and with both in
    /// [0, 1) a smooth low-pass (a negative pole makes the neural activation alternate from
    /// sample to sample). The default keeps the poles in [0, 0.995]: time constants up to 200
    /// samples (100 ms at 2 kHz).
    pub c1: [f64; 2],
    /// C2, as C1.
    pub c2: [f64; 2],
    /// The shape factor A: CEINMS's range (−3, 0), curving activation up at low excitation.
    pub shape_factor: [f64; 2],
    /// The electromechanical delay, s (10–100 ms, Corcos et al. 1992).
    pub em_delay: [f64; 2],
    /// Multiplier of a group's maximum isometric forces (CEINMS's strength coefficients).
    pub strength: [f64; 2],
    /// A group's slack fibre length λ̄, optimal lengths (`slack_fibre_length`, `crate::subject::calibrate::Quantity::SlackFibreLength`): the
    /// fibre's working range in gait (0.5–1.5 l_opt; Arnold & Delp 2011, J Exp Biol 214:
    /// 3102–3112, report 0.6–1.3 across the leg).
    pub slack_fibre_length: [f64; 2],
    /// Multiplier of a group's optimal fibre lengths (±15 %).
    pub optimal_fibre_length: [f64; 2],
    /// The Hill force–velocity curve's reach `v_max / l_opt`, optimal lengths per second, for
    /// every unit (Hill model only).
    pub max_velocity: [f64; 2],
}

impl Default for Bounds {
    fn default() -> Self {
        Bounds {
            c1: [-0.995, 0.0],
            c2: [-0.995, 0.0],
            shape_factor: [-3.0, 0.0],
            em_delay: [0.01, 0.1],
            strength: [0.5, 2.5],
            slack_fibre_length: [0.5, 1.5],
            optimal_fibre_length: [0.85, 1.15],
            max_velocity: [10.0, 500.0],
        }
    }
}

impl Bounds {
    /// Each bound's name and value.
    pub(crate) fn named(&self) -> [(&'static str, [f64; 2]); 8] {
        [
            ("c1", self.c1),
            ("c2", self.c2),
            ("shape_factor", self.shape_factor),
            ("em_delay", self.em_delay),
            ("strength", self.strength),
            ("slack_fibre_length", self.slack_fibre_length),
            ("optimal_fibre_length", self.optimal_fibre_length),
            ("max_velocity", self.max_velocity),
        ]
    }

    /// The first broken rule: each pair finite and rising, within what the parameter may be
    /// (|C| < 1, A in [-3, 3], the delay in [0, 0.5] s, multipliers > 0).
    pub(crate) fn check(&self) -> Result<(), String> {
        for (name, [lo, hi]) in self.named() {
            let (min, max) = match name {
                "c1" | "c2" => (-0.999_999, 0.999_999),
                "shape_factor" => (-3.0, 3.0),
                "em_delay" => (0.0, 0.5),
                _ => (1e-6, 1e6),
            };
            if !(lo.is_finite() && hi.is_finite() && lo <= hi && lo >= min && hi <= max) {
                return Err(format!(
                    "bounds.{name} = [{lo}, {hi}]: must be finite, low <= high, within [{min}, {max}]"
                ));
            }
        }
        Ok(())
    }
}
