//! A cross-bridge model's scale ([`CrossBridgeScale`]): its rates, isometric moments and length
//! per unit ξ, from the start-up calibration of the cross-bridge models to the muscle's Fmax and
//! vmax (docs/model.md §6–7).

use crate::physics::contractile::crossbridge::Rates;
use crate::physics::contractile::distribution_moment::{self, SteadyStateError};
use crate::physics::contractile::huxley_exact;
use crate::physics::limb_params::MuscleParams;
use std::sync::{Mutex, MutexGuard};

/// Physical scaling of one cross-bridge model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrossBridgeScale {
    /// Rates in 1/s (Huxley's ratios times the common factor).
    pub rates: Rates,
    /// The common rate factor.
    pub(crate) rate_scale: f64,
    /// The model's own isometric steady moments at r = 1.
    pub q_iso: [f64; 3],
    /// Muscle length change per unit ξ, `L_h = lopt h / s_hs`, m.
    pub l_h: f64,
    /// `Fmax / Q1_iso`, N.
    pub(crate) force_per_q1: f64,
}

impl CrossBridgeScale {
    /// Shortening rate u in h/s from the fibre's lengthening velocity v (m/s): `u = -v / L_h`.
    pub fn shortening_rate(&self, v: f64) -> f64 {
        -v / self.l_h
    }
    /// `F_CE = Fmax Q1 / Q1_iso`, N.
    pub fn force(&self, q1: f64) -> f64 {
        self.force_per_q1 * q1
    }
    /// `k_CE = (Fmax / Q1_iso) Q0 / L_h`, N/m.
    pub(crate) fn stiffness(&self, q0: f64) -> f64 {
        self.force_per_q1 * q0 / self.l_h
    }
    /// `E_CE = ½ (Fmax / Q1_iso) L_h Q2`, J.
    pub(crate) fn energy(&self, q2: f64) -> f64 {
        0.5 * self.force_per_q1 * self.l_h * q2
    }
}

fn huxley_rates(p: &MuscleParams) -> Rates {
    let x = &p.crossbridge;
    Rates {
        f1: x.f1,
        g1: x.g1,
        g2: x.g2,
        g3: x.g3,
    }
}

fn l_h(p: &MuscleParams) -> f64 {
    p.l_opt * p.crossbridge.h / p.crossbridge.s_hs
}

/// How many distinct rate ratios [`unit_steady_states`] keeps.
const MEMO_SIZE: usize = 64;

/// The ratios' steady states solved so far (their bits; the isometric moments, the unloaded
/// shortening rate), oldest first, at most `MEMO_SIZE`.
type Memo = Vec<([u64; 4], [f64; 3], f64)>;
static MEMO: Mutex<Memo> = Mutex::new(Vec::new());

fn memo() -> MutexGuard<'static, Memo> {
    // What a panic elsewhere left is still whole: entries are pushed complete.
    MEMO.lock().unwrap_or_else(|e| e.into_inner())
}

/// The DM model's isometric steady moments and unloaded shortening rate for the rate ratios
/// `unit`. A function of the four ratios alone, solved by damped Newton (about 0.15 ms), and
/// the same for nearly every muscle (Huxley's ratios): the solutions of the last `MEMO_SIZE`
/// distinct ratios are kept for the process, so that building an actuator (a Python
/// `Actuator`, each instance of a rollout, each scenario run) does not solve them again. The
/// values are the solver's, to the bit.
fn unit_steady_states(unit: &Rates) -> Result<([f64; 3], f64), SteadyStateError> {
    let key = [unit.f1, unit.g1, unit.g2, unit.g3].map(f64::to_bits);
    if let Some(&(_, q_iso, u_max)) = memo().iter().find(|e| e.0 == key) {
        return Ok((q_iso, u_max));
    }
    let q_iso = distribution_moment::isometric_steady_state(unit)?;
    let u_max = distribution_moment::unloaded_shortening_rate(unit)?;
    let mut memo = memo();
    if !memo.iter().any(|e| e.0 == key) {
        if memo.len() >= MEMO_SIZE {
            memo.remove(0);
        }
        memo.push((key, q_iso, u_max));
    }
    Ok((q_iso, u_max))
}

/// Calibrates the DM model from its own steady states: force scale from its isometric Q1, rate
/// scale so that its unloaded shortening velocity is vmax.
pub fn calibrate_distribution_moment(
    p: &MuscleParams,
) -> Result<CrossBridgeScale, SteadyStateError> {
    let unit = huxley_rates(p);
    let (q_iso, u_max) = unit_steady_states(&unit)?;
    let l_h = l_h(p);
    let rate_scale = p.v_max / l_h / u_max;
    Ok(CrossBridgeScale {
        rates: unit.scaled(rate_scale),
        rate_scale,
        q_iso,
        l_h,
        force_per_q1: p.f_max / q_iso[1],
    })
}

/// Calibrates the full Huxley model from its exact steady states (docs/model.md §7).
pub fn calibrate_exact(p: &MuscleParams) -> CrossBridgeScale {
    let unit = huxley_rates(p);
    let q_iso = huxley_exact::isometric_moments(&unit, 1.0);
    let u_max = huxley_exact::unloaded_shortening_rate(&unit);
    let l_h = l_h(p);
    let rate_scale = p.v_max / l_h / u_max;
    CrossBridgeScale {
        rates: unit.scaled(rate_scale),
        rate_scale,
        q_iso,
        l_h,
        force_per_q1: p.f_max / q_iso[1],
    }
}

/// The Hill model's short-range stiffness at full activation and optimal length,
/// `k_iso = (Fmax / Q1_iso) Q0_iso / L_h` with the DM calibration (docs/model.md §8), N/m.
pub(crate) fn hill_isometric_stiffness(dm: &CrossBridgeScale) -> f64 {
    dm.stiffness(dm.q_iso[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kept solutions are the solver's to the bit, and no more than `MEMO_SIZE` are kept.
    #[test]
    fn kept_steady_states_equal_the_solvers_and_stay_bounded() {
        let base = huxley_rates(&MuscleParams::default());
        for k in 0..MEMO_SIZE + 10 {
            let unit = Rates {
                g2: base.g2 * (1.0 + 0.01 * k as f64),
                ..base
            };
            for _ in 0..2 {
                let (q, u) = unit_steady_states(&unit).unwrap();
                let q_direct = distribution_moment::isometric_steady_state(&unit).unwrap();
                let u_direct = distribution_moment::unloaded_shortening_rate(&unit).unwrap();
                assert_eq!(q.map(f64::to_bits), q_direct.map(f64::to_bits));
                assert_eq!(u.to_bits(), u_direct.to_bits());
            }
            assert!(memo().len() <= MEMO_SIZE, "{} kept", memo().len());
        }
    }
}
