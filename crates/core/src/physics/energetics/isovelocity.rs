//! Steady isovelocity energetics at full activation and optimal length (docs/model.md §11.5):
//! for each model its steady force at shortening velocity v_s, and from it the ATP rate,
//! chemical power, heat rate, work rate and efficiency, by the cross-bridge energetics (Huxley
//! models) or a phenomenological model (any model, given its force).

use crate::physics::contractile::crossbridge::Rates;
use crate::physics::contractile::crossbridge_scale::CrossBridgeScale;
use crate::physics::contractile::distribution_moment::{self as dm, SteadyStateError};
use crate::physics::contractile::hill_equation::hill_force;
use crate::physics::contractile::huxley_exact;
use crate::physics::curves::force_velocity::HillForceVelocity;
use crate::physics::energetics::bridge_flux::{gaussian_fluxes, EnergyFluxes};
use crate::physics::energetics::bridge_power::{
    activation_heat_w, atp_mol_per_j, bridge_powers, BridgeEnergyScale,
};
use crate::physics::energetics::huxley_steady::{steady_atp_flux, steady_energy_fluxes};
use crate::physics::energetics::phenomenological::PhenomenologicalModel;
use crate::physics::energetics::probe::{ProbeInputs, ProbeMuscle};
use crate::physics::limb_params::MuscleParams;

/// One steady state.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SteadyPoint {
    /// Shortening velocity v_s, m/s (negative: lengthening).
    pub shortening_velocity_m_s: f64,
    /// Contractile force F_CE, N.
    pub force_n: f64,
    /// ATP rate, mol/s (phenomenological models: their power in ATP at e per molecule).
    pub atp_rate_mol_s: f64,
    /// Chemical (metabolic) power, W.
    pub chemical_w: f64,
    /// Heat rate, W.
    pub heat_w: f64,
    /// Work rate on the load, `F_CE v_s`, W.
    pub work_w: f64,
    /// Mechanical efficiency, work rate over chemical power (0 without chemical power).
    pub efficiency: f64,
}

/// `Ẇ / Ė`, 0 when `Ė` is not positive.
pub(crate) fn efficiency(work_w: f64, chemical_w: f64) -> f64 {
    if chemical_w > 0.0 {
        work_w / chemical_w
    } else {
        0.0
    }
}

/// The bridges' isometric chemical power at full activation (the scale of the activation
/// cost), full Huxley model: `e N_hs B (f1/2)(1 - N)`, W.
pub fn exact_isometric_bridge_w(scale: &CrossBridgeScale, e: &BridgeEnergyScale) -> f64 {
    e.chemical_power_w(steady_atp_flux(&scale.rates, 1.0, 0.0))
}

/// The same for the DM model, from its own isometric moments, W.
pub(crate) fn dm_isometric_bridge_w(scale: &CrossBridgeScale, e: &BridgeEnergyScale) -> f64 {
    e.chemical_power_w(gaussian_fluxes(&scale.rates, 1.0, &scale.q_iso).detachment[0])
}

/// A cross-bridge steady state from its fluxes, with the activation heat at full activation.
fn bridge_point(
    e: &BridgeEnergyScale,
    fluxes: &EnergyFluxes,
    force_n: f64,
    v_s: f64,
    isometric_bridge_w: f64,
) -> SteadyPoint {
    let p = bridge_powers(e, fluxes, force_n, -v_s);
    let act = activation_heat_w(1.0, e.activation_share, isometric_bridge_w);
    let chemical = p.chemical_w + act;
    SteadyPoint {
        shortening_velocity_m_s: v_s,
        force_n,
        atp_rate_mol_s: p.atp_rate_mol_s + act * e.atp_mol_per_j,
        chemical_w: chemical,
        heat_w: p.heat_w() + act,
        work_w: p.work_w,
        efficiency: efficiency(p.work_w, chemical),
    }
}

/// The full Huxley model's steady state at v_s, in closed form (`huxley_steady`,
/// `huxley_exact::steady_q1`).
pub fn exact_point(scale: &CrossBridgeScale, e: &BridgeEnergyScale, v_s: f64) -> SteadyPoint {
    let u = v_s / scale.l_h;
    let fluxes = steady_energy_fluxes(&scale.rates, 1.0, u);
    let force = scale.force(huxley_exact::steady_q1(&scale.rates, 1.0, u));
    bridge_point(e, &fluxes, force, v_s, exact_isometric_bridge_w(scale, e))
}

/// The DM model's steady state at v_s from its steady moments `q` there.
pub(crate) fn dm_point(
    scale: &CrossBridgeScale,
    e: &BridgeEnergyScale,
    q: &[f64; 3],
    v_s: f64,
) -> SteadyPoint {
    let fluxes = gaussian_fluxes(&scale.rates, 1.0, q).energy();
    let force = scale.force(q[1]);
    bridge_point(e, &fluxes, force, v_s, dm_isometric_bridge_w(scale, e))
}

/// DM steady moments at r = 1 for shortening rates `us` (h/s) in any order: each side of zero
/// by continuation from the isometric state (`distribution_moment::steady_curve`).
pub(crate) fn dm_moments(rates: &Rates, us: &[f64]) -> Result<Vec<[f64; 3]>, SteadyStateError> {
    let mut out = vec![[0.0; 3]; us.len()];
    for side in [1.0, -1.0] {
        let mut idx: Vec<usize> = (0..us.len())
            .filter(|&i| {
                if side > 0.0 {
                    us[i] >= 0.0
                } else {
                    us[i] < 0.0
                }
            })
            .collect();
        idx.sort_by(|&a, &b| us[a].abs().total_cmp(&us[b].abs()));
        let sorted: Vec<f64> = idx.iter().map(|&i| us[i]).collect();
        for (&i, q) in idx.iter().zip(dm::steady_curve(rates, &sorted)?) {
            out[i] = q;
        }
    }
    Ok(out)
}

/// The DM model's steady states at the shortening velocities `v_s` (m/s).
pub(crate) fn dm_curve(
    scale: &CrossBridgeScale,
    e: &BridgeEnergyScale,
    v_s: &[f64],
) -> Result<Vec<SteadyPoint>, SteadyStateError> {
    let us: Vec<f64> = v_s.iter().map(|v| v / scale.l_h).collect();
    let qs = dm_moments(&scale.rates, &us)?;
    Ok(qs
        .iter()
        .zip(v_s)
        .map(|(q, &v)| dm_point(scale, e, q, v))
        .collect())
}

/// A phenomenological model's steady state for a contractile force `force_n` at v_s, with
/// u = a = 1 at optimal length and no passive force.
pub(crate) fn probe_point(
    model: &PhenomenologicalModel,
    muscle: &ProbeMuscle,
    atp_free_energy_j: f64,
    force_n: f64,
    v_s: f64,
) -> SteadyPoint {
    let x = ProbeInputs {
        excitation: 1.0,
        activation: 1.0,
        fibre_length_norm: 1.0,
        force_length: 1.0,
        fibre_velocity_m_s: -v_s,
        active_force_n: force_n,
        passive_force_n: 0.0,
    };
    let r = model.rates(muscle, &x);
    SteadyPoint {
        shortening_velocity_m_s: v_s,
        force_n,
        atp_rate_mol_s: r.total_w() * atp_mol_per_j(atp_free_energy_j),
        chemical_w: r.total_w(),
        heat_w: r.heat_w(),
        work_w: r.work_w,
        efficiency: efficiency(r.work_w, r.total_w()),
    }
}

/// The Hill model's steady force at v_s: `Fmax g(v_s)` (docs/model.md §3), with the muscle's
/// curve set's g at a = 1 (§4b), N.
pub(crate) fn hill_steady_force(p: &MuscleParams, v_s: f64) -> f64 {
    hill_force(p.f_max, 1.0, 1.0, HillForceVelocity::new(p).at(-v_s, 1.0))
}
