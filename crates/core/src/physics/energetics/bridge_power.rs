//! Cross-bridge powers from the fluxes (docs/model.md §11.2): ATP rate, chemical power, the
//! two heat sources, work and stored strain energy, plus the activation (calcium-handling) cost.
//!
//! The calibration of docs/model.md §6 fixes the force per unit Q1, `C = Fmax / Q1_iso`, and
//! the length per unit ξ, `L_h = lopt h / s_hs`. A bridge of stiffness k at ξ pulls with
//! `k h ξ`, so with B bridges per unit ξ in one half-sarcomere `C = B k h`, and the
//! `N_hs = lopt / s_hs` half-sarcomeres in series store `½ C L_h Q2`. B and k are fixed apart
//! by the energy per ATP: Huxley (1957) chose the ratio `ε = e / (½ k h²)` so that the rise of
//! the energy rate with shortening velocity matches Hill's (1938) heat coefficient,
//! `dĖ/dV (V = 0) = P0 + a`, which gives `ε = (1 + a/P0) (f1 + g1) / f1`.

use crate::physics::contractile::crossbridge_scale::CrossBridgeScale;
use crate::physics::energetics::bridge_flux::EnergyFluxes;
use crate::physics::limb_params::MuscleParams;

/// Avogadro's number, 1/mol (SI 2019, exact).
pub(crate) const AVOGADRO_PER_MOL: f64 = 6.022_140_76e23;

/// Parameters of the cross-bridge energetics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BridgeEnergyParams {
    /// Free energy of ATP hydrolysis e, J per molecule: 100 zJ (≈ 60 kJ/mol) in working muscle
    /// (Barclay 2015, Compr Physiol 5:961).
    pub(crate) atp_free_energy_j: f64,
    /// Hill's (1938) heat coefficient a / P0 (0.25), which sets `ε = e / (½ k h²)`.
    pub hill_a_over_p0: f64,
    /// Share of the isometric ATP turnover at full activation spent on calcium handling (ion
    /// pumps), not on bridges: 0.35, the middle of the 30–40 % of Barclay (2015).
    pub activation_share: f64,
}

impl Default for BridgeEnergyParams {
    fn default() -> Self {
        Self {
            atp_free_energy_j: 1.0e-19,
            hill_a_over_p0: 0.25,
            activation_share: 0.35,
        }
    }
}

/// Energy per ATP over the strain energy of a bridge at ξ = 1,
/// `ε = e / (½ k h²) = (1 + a/P0) (f1 + g1) / f1` (Huxley 1957; 1.5387 with his rates).
pub(crate) fn energy_ratio(f1: f64, g1: f64, hill_a_over_p0: f64) -> f64 {
    (1.0 + hill_a_over_p0) * (f1 + g1) / f1
}

/// Bridge stiffness `k = 2 e / (ε h²)`, N/m per bridge.
pub(crate) fn bridge_stiffness_n_m(atp_free_energy_j: f64, energy_ratio: f64, h_m: f64) -> f64 {
    2.0 * atp_free_energy_j / (energy_ratio * h_m * h_m)
}

/// Bridges per unit ξ in one half-sarcomere, `B = C / (k h)` (C = Fmax / Q1_iso, N).
pub(crate) fn bridges_per_xi_half_sarcomere(
    force_per_q1_n: f64,
    stiffness_n_m: f64,
    h_m: f64,
) -> f64 {
    force_per_q1_n / (stiffness_n_m * h_m)
}

/// Moles of ATP whose free energy is one joule at e J per molecule, `1 / (e N_A)`, mol/J.
pub(crate) fn atp_mol_per_j(atp_free_energy_j: f64) -> f64 {
    1.0 / (atp_free_energy_j * AVOGADRO_PER_MOL)
}

/// Half-sarcomeres in series along the fibre, `N_hs = lopt / s_hs`.
pub(crate) fn half_sarcomeres(l_opt_m: f64, s_hs_m: f64) -> f64 {
    l_opt_m / s_hs_m
}

/// The constants that turn one muscle's fluxes into powers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BridgeEnergyScale {
    /// Energy per ATP e, J.
    pub(crate) atp_free_energy_j: f64,
    /// Bridges per unit ξ in the whole muscle, `N_hs B` (a count): a flux of 1/s in the units
    /// of the moments is this many molecules of ATP per second.
    pub(crate) bridges_per_xi: f64,
    /// Strain energy per unit of the ξ² moment, `½ C L_h`, J (docs/model.md §6's E_CE / Q2).
    pub(crate) strain_j: f64,
    /// Stiffness of one bridge k, N/m.
    pub(crate) bridge_stiffness_n_m: f64,
    /// Share of the isometric turnover spent on calcium handling.
    pub activation_share: f64,
    /// Moles of ATP per unit flux, `N_hs B / N_A`, mol (a tick's products instead of
    /// divisions: [`BridgeEnergyScale::new`] derives it).
    pub(crate) atp_mol_per_flux: f64,
    /// [`atp_mol_per_j`] of e, mol/J.
    pub(crate) atp_mol_per_j: f64,
}

impl BridgeEnergyScale {
    /// The scale of a muscle calibrated as `scale`, with the energy parameters `e`.
    pub fn new(scale: &CrossBridgeScale, p: &MuscleParams, e: &BridgeEnergyParams) -> Self {
        let h = p.crossbridge.h;
        let eps = energy_ratio(scale.rates.f1, scale.rates.g1, e.hill_a_over_p0);
        let k = bridge_stiffness_n_m(e.atp_free_energy_j, eps, h);
        let b = bridges_per_xi_half_sarcomere(scale.force_per_q1, k, h);
        let bridges_per_xi = half_sarcomeres(p.l_opt, p.crossbridge.s_hs) * b;
        Self {
            atp_free_energy_j: e.atp_free_energy_j,
            bridges_per_xi,
            strain_j: 0.5 * scale.force_per_q1 * scale.l_h,
            bridge_stiffness_n_m: k,
            activation_share: e.activation_share,
            atp_mol_per_flux: bridges_per_xi / AVOGADRO_PER_MOL,
            atp_mol_per_j: atp_mol_per_j(e.atp_free_energy_j),
        }
    }

    /// ATP rate of a flux `d0` (1/s, moment units), mol/s.
    pub(crate) fn atp_rate_mol_s(&self, d0: f64) -> f64 {
        self.atp_mol_per_flux * d0
    }

    /// Chemical power of a cycle flux `d0` (1/s, moment units): `e N_hs B d0`, W.
    pub fn chemical_power_w(&self, d0: f64) -> f64 {
        self.atp_free_energy_j * self.bridges_per_xi * d0
    }

    /// Strain energy carried by a ξ² flux `d2` (1/s): `½ C L_h d2`, W.
    pub(crate) fn strain_power_w(&self, d2: f64) -> f64 {
        self.strain_j * d2
    }
}

/// Mechanical work rate of the contractile element on its load, `F_CE v_s = -F_CE v`, W
/// (positive when shortening).
pub(crate) fn work_rate_w(force_n: f64, lengthening_velocity_m_s: f64) -> f64 {
    -force_n * lengthening_velocity_m_s
}

/// Activation (calcium-handling) heat, `a s/(1 - s) Ė_iso` with s the activation share and
/// `Ė_iso` the bridges' own isometric chemical power at full activation and optimal length, W.
/// Independent of filament overlap and velocity: the pumps serve the calcium released.
pub fn activation_heat_w(activation: f64, activation_share: f64, isometric_bridge_w: f64) -> f64 {
    activation * activation_share / (1.0 - activation_share) * isometric_bridge_w
}

/// The bridges' powers at one instant, W (ATP rate in mol/s).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct BridgePowers {
    /// ATP split by detachments, mol/s.
    pub atp_rate_mol_s: f64,
    /// Chemical power of the detachments, `e N_hs B D_0`.
    pub chemical_w: f64,
    /// Chemical power counted at attachment, `e N_hs B A_0`: the above plus e times the rate of
    /// change of the number of bound bridges.
    pub(crate) chemical_at_attachment_w: f64,
    /// Heat at attachment: free energy not stored as strain, `e N_hs B A_0 - ½ C L_h A_2`.
    pub(crate) attachment_heat_w: f64,
    /// Heat at detachment: the strain a bridge still holds, `½ C L_h D_2`.
    pub(crate) detachment_heat_w: f64,
    /// Work on the load, `F_CE v_s`.
    pub work_w: f64,
    /// Rate of change of the stored strain energy, `½ C L_h (A_2 - D_2) - F_CE v_s`
    /// (`= ½ C L_h dQ2/dt` by eq. 12).
    pub(crate) stored_rate_w: f64,
}

impl BridgePowers {
    /// Total heat of the bridges, attachment plus detachment.
    pub(crate) fn heat_w(&self) -> f64 {
        self.attachment_heat_w + self.detachment_heat_w
    }
}

/// The bridges' powers from the fluxes, the force `F_CE = C Q1` (N) and the fibre's lengthening
/// velocity v (m/s).
pub(crate) fn bridge_powers(
    s: &BridgeEnergyScale,
    x: &EnergyFluxes,
    force_n: f64,
    lengthening_velocity_m_s: f64,
) -> BridgePowers {
    let work = work_rate_w(force_n, lengthening_velocity_m_s);
    BridgePowers {
        atp_rate_mol_s: s.atp_rate_mol_s(x.detachment),
        chemical_w: s.chemical_power_w(x.detachment),
        chemical_at_attachment_w: s.chemical_power_w(x.attachment),
        attachment_heat_w: s.chemical_power_w(x.attachment) - s.strain_power_w(x.strain_in),
        detachment_heat_w: s.strain_power_w(x.strain_out),
        work_w: work,
        stored_rate_w: s.strain_power_w(x.strain_in - x.strain_out) - work,
    }
}
