//! The full Huxley (1957) model (docs/model.md §7): eq. (9) itself, the bond distribution on a
//! grid that rides with the actin, advanced exactly along the characteristics after each fixed
//! sub-step. Its moments Q0, Q1, Q2 are the ODE state; within a sub-step their rates use the
//! grid's closure φ taken at the sub-step's start and extrapolated linearly with the previous
//! sub-step's slope (second order, no extra pass over the grid). Calibrated from its exact
//! steady states.

use crate::physics::contractile::crossbridge_scale::{self, CrossBridgeScale};
use crate::physics::contractile::huxley_grid::CrossBridgeGrid;
use crate::physics::energetics::bridge_flux::{grid_fluxes, EnergyFluxes};
use crate::physics::energetics::bridge_power::BridgeEnergyScale;
use crate::physics::energetics::isovelocity::exact_isometric_bridge_w;
use crate::physics::energetics::metabolic::BridgeEnergetics;
use crate::physics::limb_params::MuscleParams;
use crate::physics::models::contractile_model::{
    CeInputs, ContractileModel, ModelBuildError, ModelSpec, SubstepMotion,
};
use crate::physics::stepping::Stepping;
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};

/// The model's entry in [`crate::physics::models::MODELS`].
pub(crate) static SPEC: ModelSpec = ModelSpec {
    name: "huxley-pde",
    label: "Huxley (full)",
    short_label: "full Huxley",
    summary: "the full Huxley model, solved by characteristics (the reference)",
    stepping: Stepping::Fixed(20),
    fourth_order_transients: false,
    build,
};

/// Room of the grid, in units of ξ (long tails after fast lengthening).
const GRID_EXTENT: f64 = 64.0;

/// The closure over a sub-step: `φ(t) = φ0 + slope (t - t0)`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct HeldClosure {
    /// φ_k at t0, 1/s.
    pub(crate) phi: [f64; 3],
    /// dφ_k/dt, 1/s².
    pub slope: [f64; 3],
    /// Start of the sub-step, s (time within the tick).
    pub t0: f64,
}

impl HeldClosure {
    /// φ at time t.
    pub(crate) fn at(&self, t: f64) -> [f64; 3] {
        let dt = t - self.t0;
        [
            self.phi[0] + self.slope[0] * dt,
            self.phi[1] + self.slope[1] * dt,
            self.phi[2] + self.slope[2] * dt,
        ]
    }
}

/// One muscle's full Huxley element: its calibration, its grid, the closure over the sub-step.
#[derive(Debug, Clone)]
pub(crate) struct HuxleyPde {
    /// Its calibration (from the exact steady states).
    pub scale: CrossBridgeScale,
    /// The bond distribution.
    pub grid: CrossBridgeGrid,
    /// Its bridges' energetics (docs/model.md §11.2).
    pub energetics: BridgeEnergetics,
    held: HeldClosure,
    previous: Option<[f64; 3]>,
}

fn build(p: &MuscleParams) -> Result<Box<dyn ContractileModel>, ModelBuildError> {
    let scale = crossbridge_scale::calibrate_exact(p);
    let e = BridgeEnergyScale::new(&scale, p, &p.energetics.bridge());
    let energetics = BridgeEnergetics::new(e, exact_isometric_bridge_w(&scale, &e));
    Ok(Box::new(HuxleyPde {
        scale,
        energetics,
        grid: CrossBridgeGrid::new(p.crossbridge.pde_cells, GRID_EXTENT),
        held: HeldClosure::default(),
        previous: None,
    }))
}

impl ContractileModel for HuxleyPde {
    fn state_dim(&self) -> usize {
        3
    }
    fn state_scales(&self, out: &mut [f64]) {
        out[..3].fill(self.scale.q_iso[0]);
    }
    fn force(&self, _ce: &CeInputs, x: &[f64]) -> f64 {
        self.scale.force(x[1])
    }
    fn rates(&self, t: f64, ce: &CeInputs, x: &[f64], dx: &mut [f64]) {
        let rates = &self.scale.rates;
        let r = ce.activation * ce.overlap;
        let u = self.scale.shortening_rate(ce.fibre_velocity);
        let phi = self.held.at(t);
        dx[0] = r * rates.beta(0) - phi[0];
        dx[1] = r * rates.beta(1) - phi[1] - u * x[0];
        dx[2] = r * rates.beta(2) - phi[2] - 2.0 * u * x[1];
    }
    fn stiffness(&self, _ce: &CeInputs, x: &[f64]) -> f64 {
        self.scale.stiffness(x[0])
    }
    fn energy(&self, x: &[f64]) -> f64 {
        self.scale.energy(x[2])
    }
    fn moments(&self, x: &[f64]) -> [f64; 3] {
        [x[0], x[1], x[2]]
    }
    /// The grid's own quadrature of the fluxes (docs/model.md §11.1); the grid is in step with
    /// `x` after every sub-step.
    fn bridge_energy(
        &self,
        ce: &CeInputs,
        _x: &[f64],
    ) -> Option<(EnergyFluxes, &BridgeEnergetics)> {
        let r = ce.activation * ce.overlap;
        let fluxes = grid_fluxes(&self.grid, &self.scale.rates, r).energy();
        Some((fluxes, &self.energetics))
    }
    fn before_substep(&mut self, t0: f64, dt: f64) {
        let phi = self.grid.closure(&self.scale.rates);
        let slope = match self.previous {
            Some(prev) => [0, 1, 2].map(|k| (phi[k] - prev[k]) / dt),
            None => [0.0; 3],
        };
        self.held = HeldClosure { phi, slope, t0 };
        self.previous = Some(phi);
    }
    fn after_substep(&mut self, m: &SubstepMotion, x: &mut [f64]) {
        let shift = m.fibre_length_change / self.scale.l_h;
        let r = m.activation_mid * m.overlap_mid;
        self.grid.advance(&self.scale.rates, r, m.dt, shift);
        x[..3].copy_from_slice(&self.grid.moments());
    }
    fn reset(&mut self) {
        self.grid.reset();
        self.previous = None;
    }
    fn forget_history(&mut self) {
        self.previous = None;
    }
    /// The grid, the closure held over the sub-step and the previous sub-step's closure.
    fn save_state(&self, out: &mut StateWriter) {
        self.grid.save_state(out);
        let HeldClosure { phi, slope, t0 } = self.held;
        for v in phi.into_iter().chain(slope).chain([t0]) {
            out.f64(v);
        }
        out.bool(self.previous.is_some());
        for v in self.previous.unwrap_or_default() {
            out.f64(v);
        }
    }
    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        self.grid.restore_state(input)?;
        let three = |input: &mut StateReader, what: &str| -> Result<[f64; 3], StateError> {
            Ok([input.f64(what)?, input.f64(what)?, input.f64(what)?])
        };
        let phi = three(input, "held closure")?;
        let slope = three(input, "held closure slope")?;
        let t0 = input.f64("held closure start")?;
        self.held = HeldClosure { phi, slope, t0 };
        let has_previous = input.bool("previous closure flag")?;
        let previous = three(input, "previous closure")?;
        self.previous = has_previous.then_some(previous);
        Ok(())
    }
    fn clone_box(&self) -> Box<dyn ContractileModel> {
        Box::new(self.clone())
    }
}
