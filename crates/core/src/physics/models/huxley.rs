//! The model `huxley`: the Huxley-type contractile element reduced by Zahalak's
//! Distribution-Moment approximation (docs/model.md §6, paper eqs. 9–12): state Q0, Q1, Q2, rates
//! from eq. (12) with the Gaussian closure, calibrated from its own steady states. Its equations
//! are `physics::contractile::distribution_moment`'s.

use crate::physics::contractile::closure_limits::ClosureLimits;
use crate::physics::contractile::crossbridge_scale::{self, CrossBridgeScale};
use crate::physics::contractile::distribution_moment::moment_rates_keeping;
use crate::physics::energetics::bridge_flux::{gaussian_fluxes_near, EnergyFluxes};
use crate::physics::energetics::bridge_power::BridgeEnergyScale;
use crate::physics::energetics::isovelocity::dm_isometric_bridge_w;
use crate::physics::energetics::metabolic::BridgeEnergetics;
use crate::physics::limb_params::MuscleParams;
use crate::physics::models::contractile_model::{
    CeInputs, ContractileModel, ModelBuildError, ModelSpec,
};
use crate::physics::stepping::{Stepping, DEFAULT_MAX_SUBSTEPS};

/// The model's entry in [`crate::physics::models::MODELS`].
pub(crate) static SPEC: ModelSpec = ModelSpec {
    name: "huxley",
    label: "Huxley (DM)",
    short_label: "DM",
    summary: "Huxley cross-bridges, Distribution-Moment approximation (Q0, Q1, Q2)",
    // The stiff cross-bridge spring needs a tighter tolerance than Hill for the same margin of at
    // least 2 against the reference solver (tests/integrator_accuracy.rs, tests/limb.rs).
    // Its transients ring on the cross-bridge and tendon springs and take several sub-steps per
    // tick: the fourth-order method makes them longer and fewer (docs/integration.md; the sub-steps
    // per tick are in the `cargo bench --bench limb` table).
    stepping: Stepping::Adaptive {
        tolerance: 2e-5,
        max_substeps: DEFAULT_MAX_SUBSTEPS,
    },
    fourth_order_transients: true,
    build,
};

/// One muscle's DM element.
#[derive(Debug, Clone)]
pub(crate) struct DistributionMoment {
    /// Its calibration.
    pub scale: CrossBridgeScale,
    /// Its bridges' energetics (docs/model.md §11.2).
    pub energetics: BridgeEnergetics,
    /// Φ and ϕ at the closure's limits in its last evaluation, for the fluxes (not state).
    limits: ClosureLimits,
}

fn build(p: &MuscleParams) -> Result<Box<dyn ContractileModel>, ModelBuildError> {
    let scale = crossbridge_scale::calibrate_distribution_moment(p)?;
    let e = BridgeEnergyScale::new(&scale, p, &p.energetics.bridge());
    let energetics = BridgeEnergetics::new(e, dm_isometric_bridge_w(&scale, &e));
    Ok(Box::new(DistributionMoment {
        scale,
        energetics,
        limits: ClosureLimits::default(),
    }))
}

fn q(x: &[f64]) -> [f64; 3] {
    [x[0], x[1], x[2]]
}

impl ContractileModel for DistributionMoment {
    fn state_dim(&self) -> usize {
        3
    }
    fn state_scales(&self, out: &mut [f64]) {
        out[..3].fill(self.scale.q_iso[0]);
    }
    fn force(&self, _ce: &CeInputs, x: &[f64]) -> f64 {
        self.scale.force(x[1])
    }
    fn rates(&self, _t: f64, ce: &CeInputs, x: &[f64], dx: &mut [f64]) {
        let r = ce.activation * ce.overlap;
        let u = self.scale.shortening_rate(ce.fibre_velocity);
        let kept = Some(&self.limits);
        dx[..3].copy_from_slice(&moment_rates_keeping(&self.scale.rates, &q(x), r, u, kept));
    }
    fn stiffness(&self, _ce: &CeInputs, x: &[f64]) -> f64 {
        self.scale.stiffness(x[0])
    }
    fn energy(&self, x: &[f64]) -> f64 {
        self.scale.energy(x[2])
    }
    fn moments(&self, x: &[f64]) -> [f64; 3] {
        q(x)
    }
    /// The Gaussian closure's fluxes in closed form (docs/model.md §11.1), with the error
    /// function and exponential at its limits carried from the last closure evaluation where
    /// that was near (at a tick's end, the stepper's last Newton iterate).
    fn bridge_energy(&self, ce: &CeInputs, x: &[f64]) -> Option<(EnergyFluxes, &BridgeEnergetics)> {
        let r = ce.activation * ce.overlap;
        let fluxes = gaussian_fluxes_near(&self.scale.rates, r, &q(x), Some(&self.limits));
        let fluxes = fluxes.energy();
        Some((fluxes, &self.energetics))
    }
    fn clone_box(&self) -> Box<dyn ContractileModel> {
        Box::new(self.clone())
    }
}
