//! One muscle–tendon unit (MODEL.md §5, paper eq. 8): the fibre carries the muscle mass; the
//! contractile element, parallel spring and damper act between the origin and the mass, the
//! tendon between the mass and the load.

use crate::physics::contractile::calibration::{self, CrossBridgeScale};
use crate::physics::contractile::crossbridge::Rates;
use crate::physics::contractile::distribution_moment;
use crate::physics::contractile::force_length::{force_length, force_length_slope};
use crate::physics::contractile::hill;
use crate::physics::model::ModelKind;
use crate::physics::parallel_element::{damper_force, parallel_spring};
use crate::physics::params::MuscleParams;
use crate::physics::spring::ExpLinearSpring;
use crate::physics::stiffness::{fibre_stiffness, series_stiffness};
use crate::physics::tendon::tendon;

/// The constants of one muscle–tendon unit, derived once from its parameters.
#[derive(Debug, Clone)]
pub struct Mtu {
    /// The parameters.
    pub params: MuscleParams,
    /// Series element.
    pub tendon: ExpLinearSpring,
    /// Parallel element.
    pub parallel: ExpLinearSpring,
    /// The contractile model.
    pub model: ModelKind,
    /// Cross-bridge scaling of the model in use (the DM calibration for Hill, whose short-range
    /// stiffness it defines).
    pub crossbridge: CrossBridgeScale,
    /// Hill short-range stiffness at full activation and optimal length, N/m.
    pub hill_k_iso: f64,
}

/// Everything observable about one MTU at one instant.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MtuOutputs {
    /// Tendon force, N.
    pub tendon_force: f64,
    /// Contractile-element force, N.
    pub ce_force: f64,
    /// Parallel spring force, N.
    pub pe_force: f64,
    /// Tendon length, m.
    pub tendon_length: f64,
    /// Contractile-element stiffness, N/m.
    pub ce_stiffness: f64,
    /// MTU stiffness (fibre in series with tendon), N/m.
    pub mtu_stiffness: f64,
    /// Tendon strain energy, J.
    pub tendon_energy: f64,
    /// Parallel-element strain energy, J.
    pub fibre_energy: f64,
    /// Cross-bridge elastic energy, J.
    pub crossbridge_energy: f64,
}

impl Mtu {
    /// Derives the constants (and runs the cross-bridge calibration for the Huxley models).
    pub fn new(params: &MuscleParams, model: ModelKind) -> Result<Self, String> {
        let dm = calibration::calibrate_distribution_moment(params).map_err(|e| e.to_string())?;
        let crossbridge = match model {
            ModelKind::Hill | ModelKind::Huxley => dm,
            ModelKind::HuxleyPde => calibration::calibrate_exact(params),
        };
        Ok(Self {
            params: params.clone(),
            tendon: tendon(params),
            parallel: parallel_spring(params),
            model,
            crossbridge,
            hill_k_iso: calibration::hill_isometric_stiffness(&dm),
        })
    }

    /// Number of contractile state variables (Q0, Q1, Q2 for the Huxley models).
    pub fn contractile_dim(&self) -> usize {
        match self.model {
            ModelKind::Hill => 0,
            ModelKind::Huxley | ModelKind::HuxleyPde => 3,
        }
    }

    /// Scaled cross-bridge rates, 1/s.
    pub fn rates(&self) -> &Rates {
        &self.crossbridge.rates
    }

    /// Filament-overlap factor λ(l_m) = f(l_m).
    pub fn overlap(&self, l_m: f64) -> f64 {
        force_length(
            l_m,
            self.params.l_opt,
            self.params.fl_width,
            self.params.fl_shape,
        )
    }

    /// Contractile force, N: Hill `Fmax a f(l) g(v_s)`, Huxley `Fmax Q1 / Q1_iso`.
    pub fn ce_force(&self, activation: f64, l_m: f64, v: f64, q: &[f64; 3]) -> f64 {
        match self.model {
            ModelKind::Hill => {
                let p = &self.params;
                let g = hill::force_velocity(-v, p.v_max, p.eccentric_asymptote);
                hill::hill_force(p.f_max, activation, self.overlap(l_m), g)
            }
            ModelKind::Huxley | ModelKind::HuxleyPde => self.crossbridge.force(q[1]),
        }
    }

    /// Fibre acceleration from eq. (8): `(F_SE - F_CE - F_P - B_m v) / M`, m/s².
    pub fn fibre_acceleration(&self, tendon_force: f64, ce_force: f64, l_m: f64, v: f64) -> f64 {
        let p = &self.params;
        (tendon_force - ce_force - self.parallel.force(l_m) - damper_force(p.b_m, v)) / p.mass
    }

    /// Moment rates of the DM model (eq. 12 with the Gaussian closure), or with a given closure
    /// φ (the full model's, taken from its grid).
    pub fn moment_rates(
        &self,
        activation: f64,
        l_m: f64,
        v: f64,
        q: &[f64; 3],
        closure: Option<&[f64; 3]>,
    ) -> [f64; 3] {
        let rates = &self.crossbridge.rates;
        let r = activation * self.overlap(l_m);
        let u = self.crossbridge.shortening_rate(v);
        match closure {
            None => distribution_moment::moment_rates(rates, q, r, u),
            Some(phi) => [
                r * rates.beta(0) - phi[0],
                r * rates.beta(1) - phi[1] - u * q[0],
                r * rates.beta(2) - phi[2] - 2.0 * u * q[1],
            ],
        }
    }

    /// Contractile stiffness k_CE, N/m: Hill `a f(l) k_iso`, Huxley `(Fmax/Q1_iso) Q0 / L_h`.
    pub fn ce_stiffness(&self, activation: f64, l_m: f64, q: &[f64; 3]) -> f64 {
        match self.model {
            ModelKind::Hill => activation * self.overlap(l_m) * self.hill_k_iso,
            ModelKind::Huxley | ModelKind::HuxleyPde => self.crossbridge.stiffness(q[0]),
        }
    }

    /// Slope of the overlap factor, 1/m (exposed for Jacobians and tests).
    pub fn overlap_slope(&self, l_m: f64) -> f64 {
        force_length_slope(
            l_m,
            self.params.l_opt,
            self.params.fl_width,
            self.params.fl_shape,
        )
    }

    /// All outputs at fibre state (l_m, v, Q), tendon length l_t and activation a.
    pub fn outputs(&self, activation: f64, l_m: f64, v: f64, q: &[f64; 3], l_t: f64) -> MtuOutputs {
        let ce_stiffness = self.ce_stiffness(activation, l_m, q);
        let k_m = fibre_stiffness(ce_stiffness, self.parallel.stiffness(l_m));
        MtuOutputs {
            tendon_force: self.tendon.force(l_t),
            ce_force: self.ce_force(activation, l_m, v, q),
            pe_force: self.parallel.force(l_m),
            tendon_length: l_t,
            ce_stiffness,
            mtu_stiffness: series_stiffness(k_m, self.tendon.stiffness(l_t)),
            tendon_energy: self.tendon.energy(l_t),
            fibre_energy: self.parallel.energy(l_m),
            crossbridge_energy: match self.model {
                ModelKind::Hill => 0.0,
                _ => self.crossbridge.energy(q[2]),
            },
        }
    }

    /// Fibre length at rest with the MTU held at total length `length` (a = 0, no bonds): where
    /// the tendon force equals the parallel force, by bisection (both are monotone).
    pub fn resting_fibre_length(&self, length: f64) -> f64 {
        let residual = |l_m: f64| self.tendon.force(length - l_m) - self.parallel.force(l_m);
        let (mut lo, mut hi) = (0.0, length);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if residual(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}
