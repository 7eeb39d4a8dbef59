//! The Hill-type contractile element (docs/model.md §3, paper eqs. 1–3):
//! `F_CE = Fmax a f(l_m) g(v_s)`, no state of its own; f and g from the muscle's curve set
//! (§4b). Its short-range stiffness is that of the
//! attached bridges implied by the Distribution-Moment calibration, `k_CE = a f(l_m) k_iso`
//! (§8).

use crate::physics::contractile::crossbridge_scale;
use crate::physics::contractile::hill_equation::hill_force;
use crate::physics::curves::force_velocity::HillForceVelocity;
use crate::physics::limb_params::MuscleParams;
use crate::physics::models::contractile_model::{
    CeInputs, ContractileModel, ModelBuildError, ModelSpec,
};
use crate::physics::stepping::{Stepping, DEFAULT_MAX_SUBSTEPS};

/// The model's entry in [`crate::physics::models::MODELS`].
pub(crate) static SPEC: ModelSpec = ModelSpec {
    name: "hill",
    label: "Hill",
    short_label: "Hill",
    summary: "Hill-type: Fmax · a · f(l) · g(v)",
    // Chosen so that 1 kHz ticks (third-order ESDIRK sub-steps) meet the accuracy bounds against
    // the reference solver with a margin of at least 2 on every scenario (tests/integrator_accuracy.rs
    // and tests/limb.rs print them).
    // Its transients take few sub-steps per tick, too few for the fourth-order method's longer
    // sub-steps to pay for its extra stages (docs/integration.md).
    stepping: Stepping::Adaptive {
        tolerance: 5e-5,
        max_substeps: DEFAULT_MAX_SUBSTEPS,
    },
    fourth_order_transients: false,
    build,
};

/// One muscle's Hill element.
#[derive(Debug, Clone)]
pub(crate) struct Hill {
    f_max: f64,
    /// The force–velocity relation of its curve set.
    force_velocity: HillForceVelocity,
    /// Short-range stiffness at full activation and optimal length, N/m.
    k_iso: f64,
}

fn build(p: &MuscleParams) -> Result<Box<dyn ContractileModel>, ModelBuildError> {
    let dm = crossbridge_scale::calibrate_distribution_moment(p)?;
    Ok(Box::new(Hill {
        f_max: p.f_max,
        force_velocity: HillForceVelocity::new(p),
        k_iso: crossbridge_scale::hill_isometric_stiffness(&dm),
    }))
}

impl ContractileModel for Hill {
    fn state_dim(&self) -> usize {
        0
    }
    fn state_scales(&self, _out: &mut [f64]) {}
    fn force(&self, ce: &CeInputs, _x: &[f64]) -> f64 {
        let g = self.force_velocity.at(ce.fibre_velocity, ce.activation);
        hill_force(self.f_max, ce.activation, ce.overlap, g)
    }
    fn balance_velocity(&self, ce: &CeInputs, _x: &[f64], damping: f64, force: f64) -> f64 {
        let active = self.f_max * ce.activation * ce.overlap;
        self.force_velocity
            .balance_velocity(active, ce.activation, damping, force)
    }
    fn force_depends_on_velocity(&self) -> bool {
        true
    }
    fn rates(&self, _t: f64, _ce: &CeInputs, _x: &[f64], _dx: &mut [f64]) {}
    fn stiffness(&self, ce: &CeInputs, _x: &[f64]) -> f64 {
        ce.activation * ce.overlap * self.k_iso
    }
    fn energy(&self, _x: &[f64]) -> f64 {
        0.0
    }
    fn moments(&self, _x: &[f64]) -> [f64; 3] {
        [0.0; 3]
    }
    fn clone_box(&self) -> Box<dyn ContractileModel> {
        Box::new(self.clone())
    }
}
