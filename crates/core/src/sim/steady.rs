//! Steady isovelocity states of one muscle at full activation and optimal length
//! (docs/model.md §11.5), for the `steady` command and the steady-state energetics figure.
//!
//! Shortening velocities v_s (m/s, positive shortening) evenly from -vmax to vmax, zero and both
//! ends included. For each, the contractile model's steady force (Hill: `Fmax g(v_s)` with its
//! eccentric branch, §3; DM: its steady moments, §6; the full model: Huxley's closed form, §7)
//! and from it the energetics: the cross-bridge mechanism for the two Huxley models (§11.1–11.3),
//! and every phenomenological model (§11.4) for every contractile model, given that force.

use crate::physics::contractile::crossbridge_scale::{
    calibrate_distribution_moment, calibrate_exact,
};
use crate::physics::contractile::distribution_moment::SteadyStateError;
use crate::physics::energetics::bridge_power::BridgeEnergyScale;
use crate::physics::energetics::isovelocity::{
    dm_curve, exact_point, hill_steady_force, probe_point, SteadyPoint,
};
use crate::physics::limb_params::{EnergyModel, MuscleParams, ParamError};
use crate::physics::models::ModelKind;

/// Velocities when none is given: every 0.05 vmax.
pub const DEFAULT_POINTS: usize = 41;
/// Fewest velocities: -vmax, 0, vmax.
pub const MIN_POINTS: usize = 3;
/// Most velocities (a step of 0.0002 vmax).
pub const MAX_POINTS: usize = 10_001;

/// Why the steady states cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SteadyError {
    /// A number of velocities outside [`MIN_POINTS`]..=[`MAX_POINTS`].
    #[error("--points {0}: must be between {MIN_POINTS} and {MAX_POINTS}")]
    PointsOutOfRange(
        /// The number given.
        usize,
    ),
    /// An even number of velocities (the grid would miss v_s = 0).
    #[error(
        "--points {0}: must be odd, so that the velocities hold 0 as well as -vmax and vmax \
         (e.g. {next})",
        next = .0 + 1
    )]
    EvenPoints(
        /// The number given.
        usize,
    ),
    /// Muscle parameters breaking their rules, joined by `; `.
    #[error("{}", .0.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("; "))]
    Params(
        /// The broken rules.
        Vec<ParamError>,
    ),
    /// The full model with detachment beyond ξ = 1 (g3 ≠ 0), where Huxley's closed form does not
    /// hold.
    #[error(
        "the full model's steady states are Huxley's closed form, which holds for \
         crossbridge.g3 = 0 only (this muscle has g3 = {0})"
    )]
    NonZeroG3(
        /// The muscle's g3.
        f64,
    ),
    /// The Distribution-Moment model's calibration failed.
    #[error("calibrating the Distribution-Moment model: {0}")]
    Calibration(#[source] SteadyStateError),
    /// The continuation of the Distribution-Moment steady states over the velocities failed.
    #[error("{error}{}", failing_velocity(*.at, *.v_max))]
    Continuation {
        /// Why.
        error: SteadyStateError,
        /// The first velocity at which it fails, m/s, if found.
        at: Option<f64>,
        /// The muscle's vmax, m/s.
        v_max: f64,
    },
}

/// ` at v_s = … m/s (… vmax)`, or nothing.
fn failing_velocity(at: Option<f64>, v_max: f64) -> String {
    at.map_or_else(String::new, |v| {
        format!(" at v_s = {v:.6} m/s ({:.4} vmax)", v / v_max)
    })
}

/// Where a row's energy rates come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EnergySource {
    /// The Huxley models' own mechanism: one ATP per detachment, heat from its two sources.
    CrossBridge,
    /// A phenomenological heat-rate model, given the contractile model's force.
    Phenomenological(EnergyModel),
}

impl EnergySource {
    /// Its name in tables and CSV: `crossbridge` or the energy model's name.
    pub fn name(self) -> &'static str {
        match self {
            Self::CrossBridge => "crossbridge",
            Self::Phenomenological(m) => m.name(),
        }
    }
}

/// One steady state of one model with one energy source.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyRow {
    /// The contractile model.
    pub model: ModelKind,
    /// Where the energy rates come from.
    pub source: EnergySource,
    /// Shortening velocity over vmax, v_s / vmax.
    pub v_over_vmax: f64,
    /// The state: v_s (m/s), force (N), ATP rate (mol/s), chemical power, heat, work (W),
    /// efficiency. The work is the one the source counts: `F v_s`, but 0 when lengthening for
    /// Umberger (2010) as published, which counts no negative work (docs/model.md §11.4).
    pub point: SteadyPoint,
    /// Chemical power per kg of the muscle's metabolic mass, W/kg.
    pub chemical_w_kg: f64,
}

impl SteadyRow {
    /// CSV columns, units in the names: the two names, then [`Self::values`].
    pub const FIELDS: [&'static str; 11] = [
        "model",
        "source",
        "v_s_m_s",
        "v_s_over_vmax",
        "force_n",
        "atp_rate_mol_s",
        "chemical_w",
        "heat_w",
        "work_w",
        "efficiency",
        "chemical_w_kg",
    ];

    /// The numbers of [`Self::FIELDS`] after the two names, in that order.
    pub fn values(&self) -> [f64; 9] {
        let p = &self.point;
        [
            p.shortening_velocity_m_s,
            self.v_over_vmax,
            p.force_n,
            p.atp_rate_mol_s,
            p.chemical_w,
            p.heat_w,
            p.work_w,
            p.efficiency,
            self.chemical_w_kg,
        ]
    }
}

/// `points` must be in [`MIN_POINTS`]..=[`MAX_POINTS`] and odd, so that the even grid holds
/// v_s = 0 as well as ±vmax.
pub fn check_points(points: usize) -> Result<(), SteadyError> {
    if !(MIN_POINTS..=MAX_POINTS).contains(&points) {
        return Err(SteadyError::PointsOutOfRange(points));
    }
    if points.is_multiple_of(2) {
        return Err(SteadyError::EvenPoints(points));
    }
    Ok(())
}

/// `points` fractions of vmax evenly from -1 to 1: `(2i - m)/m`, m = points - 1, so that -1, 0
/// and 1 are exact and the grid is symmetric. `points` odd and at least 3.
pub(crate) fn velocity_fractions(points: usize) -> Vec<f64> {
    let m = (points - 1) as f64;
    (0..points).map(|i| (2.0 * i as f64 - m) / m).collect()
}

/// The steady states of `params`' muscle under `model` at `points` velocities: for the Huxley
/// models first the cross-bridge rows, then for every model one set per phenomenological energy
/// model ([`EnergyModel::ALL`]), each velocity in ascending order.
pub fn steady_table(
    params: &MuscleParams,
    model: ModelKind,
    points: usize,
) -> Result<Vec<SteadyRow>, SteadyError> {
    check_points(points)?;
    check_params(params)?;
    let fractions = velocity_fractions(points);
    let v_s: Vec<f64> = fractions.iter().map(|f| f * params.v_max).collect();
    let bridges = bridge_points(params, model, &v_s)?;
    let forces: Vec<f64> = match &bridges {
        Some(pts) => pts.iter().map(|p| p.force_n).collect(),
        None => v_s.iter().map(|&v| hill_steady_force(params, v)).collect(),
    };
    let e = &params.energetics;
    let mass_kg = e.mass_kg(params.f_max, params.l_opt);
    let row = |source, (point, &v_over_vmax): (SteadyPoint, &f64)| SteadyRow {
        model,
        source,
        v_over_vmax,
        point,
        chemical_w_kg: point.chemical_w / mass_kg,
    };
    let mut rows = Vec::with_capacity(points * (EnergyModel::ALL.len() + 1));
    if let Some(pts) = bridges {
        rows.extend(
            pts.into_iter()
                .zip(&fractions)
                .map(|x| row(EnergySource::CrossBridge, x)),
        );
    }
    let muscle = e.probe_muscle(params.f_max, params.l_opt, params.v_max);
    for energy_model in EnergyModel::ALL {
        let phen = energy_model.phenomenological();
        let pts = forces
            .iter()
            .zip(&v_s)
            .map(|(&f, &v)| probe_point(&phen, &muscle, e.atp_free_energy, f, v));
        let source = EnergySource::Phenomenological(energy_model);
        rows.extend(pts.zip(&fractions).map(|x| row(source, x)));
    }
    Ok(rows)
}

/// The parameters' own rules (a configuration has checked them already; a caller may not have).
fn check_params(params: &MuscleParams) -> Result<(), SteadyError> {
    let mut errors = Vec::new();
    params.validate("", &mut errors);
    if errors.is_empty() {
        Ok(())
    } else {
        Err(SteadyError::Params(errors))
    }
}

/// The cross-bridge steady states of the Huxley models at `v_s` (m/s); `None` for any other
/// model, which has no mechanism of its own and is taken as Hill's.
fn bridge_points(
    params: &MuscleParams,
    model: ModelKind,
    v_s: &[f64],
) -> Result<Option<Vec<SteadyPoint>>, SteadyError> {
    let bridge = params.energetics.bridge();
    if model == ModelKind::HUXLEY_PDE {
        // Huxley's closed form (huxley_steady, huxley_exact) has no bonds detaching at the extra
        // rate g3 beyond ξ = 1, which lengthening reaches (docs/model.md §11.3).
        let g3 = params.crossbridge.g3;
        if g3 != 0.0 {
            return Err(SteadyError::NonZeroG3(g3));
        }
        let scale = calibrate_exact(params);
        let e = BridgeEnergyScale::new(&scale, params, &bridge);
        return Ok(Some(
            v_s.iter().map(|&v| exact_point(&scale, &e, v)).collect(),
        ));
    }
    if model != ModelKind::HUXLEY {
        return Ok(None);
    }
    let scale = calibrate_distribution_moment(params).map_err(SteadyError::Calibration)?;
    let e = BridgeEnergyScale::new(&scale, params, &bridge);
    dm_curve(&scale, &e, v_s)
        .map(Some)
        .map_err(|error| SteadyError::Continuation {
            error,
            at: first_failure(v_s, |side| dm_curve(&scale, &e, side).is_err()),
            v_max: params.v_max,
        })
}

/// The velocity at which a continuation from v_s = 0 first fails, in the order the DM steady
/// states are continued (`energetics::isovelocity::dm_moments`: the side v_s ≥ 0 by rising |v_s|,
/// then v_s < 0): the shortest failing prefix of each side, by bisection (a continuation is
/// deterministic, so a prefix fails if and only if it reaches the failing velocity).
fn first_failure(v_s: &[f64], fails: impl Fn(&[f64]) -> bool) -> Option<f64> {
    for shortening in [true, false] {
        let mut side: Vec<f64> = v_s
            .iter()
            .copied()
            .filter(|&v| (v >= 0.0) == shortening)
            .collect();
        side.sort_by(|a, b| a.abs().total_cmp(&b.abs()));
        if side.is_empty() || !fails(&side) {
            continue;
        }
        // The empty prefix is taken as passing, the whole side fails.
        let (mut lo, mut hi) = (0, side.len());
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if fails(&side[..mid]) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        return Some(side[hi - 1]);
    }
    None
}

#[cfg(test)]
mod tests;
