//! The interface every contractile-element model implements (docs/model.md §3, §6, §7).
//!
//! A model is one file in `physics/models/` plus one line in [`crate::physics::models::MODELS`].
//! It supplies, for one muscle:
//! - its calibration (the `build` function of its [`ModelSpec`], from the muscle's parameters);
//! - the size of its own state (0 for Hill, Q0..Q2 for the Huxley models) and their scales;
//! - the rates of that state, the contractile force F_CE, the stiffness k_CE and the
//!   cross-bridge energy, at a given activation, fibre length and velocity;
//! - for models with bonds, the fluxes that carry energy (docs/model.md §11);
//! - optional hooks around each implicit sub-step, for state that lives outside the ODE (the full
//!   Huxley model's bond distribution), and how it wants to be sub-stepped.
//!
//! The mechanics around it (fibre mass, springs, tendon, joints) are written once, in
//! `physics::mtu` and `physics::plant`.

use crate::physics::contractile::distribution_moment::SteadyStateError;
use crate::physics::energetics::bridge_flux::EnergyFluxes;
use crate::physics::energetics::metabolic::BridgeEnergetics;
use crate::physics::limb_params::MuscleParams;
use crate::physics::stepping::Stepping;
use crate::state_bytes::{StateError, StateReader, StateWriter};
use std::fmt;

/// What the contractile element sees at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CeInputs {
    /// Activation a, [0, 1].
    pub activation: f64,
    /// Fibre length l_m, m.
    pub fibre_length: f64,
    /// Fibre lengthening velocity v = dl_m/dt, m/s.
    pub fibre_velocity: f64,
    /// Filament overlap factor λ(l_m) = f(l_m) (the force–length curve), dimensionless.
    pub overlap: f64,
}

/// The motion of one fibre over a sub-step, for [`ContractileModel::after_substep`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SubstepMotion {
    /// Sub-step length, s.
    pub dt: f64,
    /// Activation at the sub-step's midpoint.
    pub(crate) activation_mid: f64,
    /// Overlap factor at the midpoint's fibre length.
    pub(crate) overlap_mid: f64,
    /// Fibre length change over the sub-step, m (negative when shortening).
    pub(crate) fibre_length_change: f64,
}

/// One muscle's contractile element.
pub(crate) trait ContractileModel: fmt::Debug + Send + Sync {
    /// Number of state variables of its own.
    fn state_dim(&self) -> usize;
    /// Typical magnitudes of those variables (tolerance units), written to `out`.
    fn state_scales(&self, out: &mut [f64]);
    /// Contractile force F_CE, N.
    fn force(&self, ce: &CeInputs, x: &[f64]) -> f64;
    /// `dx/dt` of its state; `t` is the time within the tick, s.
    fn rates(&self, t: f64, ce: &CeInputs, x: &[f64], dx: &mut [f64]);
    /// The fibre's lengthening velocity (m/s) at which this element and a parallel damper
    /// `damping` (N s/m) together carry `force` (N): an equilibrium fibre's balance (docs/model.md
    /// §5b); `ce.fibre_velocity` is not read. An element whose force does not depend on the
    /// velocity (the bridge models: theirs is in their state) leaves the yielding to the damper,
    /// `(force - F_CE)/B`, which needs B > 0 ([`ContractileModel::force_depends_on_velocity`]).
    fn balance_velocity(&self, ce: &CeInputs, x: &[f64], damping: f64, force: f64) -> f64 {
        (force - self.force(ce, x)) / damping
    }
    /// Whether F_CE depends on the fibre's velocity at the instant (Hill: through g(v)); if not,
    /// an equilibrium fibre on an elastic tendon needs a damper.
    fn force_depends_on_velocity(&self) -> bool {
        false
    }
    /// Contractile stiffness k_CE, N/m.
    fn stiffness(&self, ce: &CeInputs, x: &[f64]) -> f64;
    /// Cross-bridge elastic energy, J (0 for models without bonds).
    fn energy(&self, x: &[f64]) -> f64;
    /// The Distribution-Moment quantities Q0, Q1, Q2 it publishes (zeros for models without
    /// bonds).
    fn moments(&self, x: &[f64]) -> [f64; 3];
    /// The energy-carrying fluxes of its bonds at this state and the constants that turn them
    /// into watts (docs/model.md §11.1–11.2); `None` for a model without bonds.
    fn bridge_energy(
        &self,
        _ce: &CeInputs,
        _x: &[f64],
    ) -> Option<(EnergyFluxes, &BridgeEnergetics)> {
        None
    }
    /// Hook before a fixed sub-step starting at `t0` (time within the tick) of length `dt`.
    fn before_substep(&mut self, _t0: f64, _dt: f64) {}
    /// Hook after a fixed sub-step: may advance state outside the ODE and overwrite `x`.
    fn after_substep(&mut self, _motion: &SubstepMotion, _x: &mut [f64]) {}
    /// Forgets everything outside the ODE state (back to no bonds).
    fn reset(&mut self) {}
    /// Forgets what the sub-step hooks carry from one sub-step to the next (after a failed tick).
    fn forget_history(&mut self) {}
    /// Writes what it carries from tick to tick outside the ODE state (a saved state,
    /// `sim::saved`): nothing for a model without such state. Everything a later tick reads
    /// must be written, or a restored run departs from the original.
    fn save_state(&self, _out: &mut StateWriter) {}
    /// Reads back what [`ContractileModel::save_state`] wrote, into an element built from the
    /// same parameters; Err, naming the value, for bytes that do not fit it.
    fn restore_state(&mut self, _input: &mut StateReader) -> Result<(), StateError> {
        Ok(())
    }
    /// A copy behind a new box.
    fn clone_box(&self) -> Box<dyn ContractileModel>;
}

impl Clone for Box<dyn ContractileModel> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// Why a model cannot be built for a muscle's parameters.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelBuildError {
    /// Its calibration from its own steady states failed.
    #[error(transparent)]
    Calibration(#[from] SteadyStateError),
    /// An equilibrium fibre on an elastic tendon whose force does not depend on velocity, with
    /// no damper: nothing sets the fibre's velocity (docs/model.md §5b).
    #[error(
        "the {model} model's force does not depend on the fibre's velocity, so an equilibrium \
         fibre on an elastic tendon needs a damper: b_m must be > 0"
    )]
    EquilibriumWithoutDamper {
        /// The model's name.
        model: &'static str,
    },
}

/// A model as the program names it: its name, what it is, how it is built and stepped.
#[derive(Debug)]
pub struct ModelSpec {
    /// The name on the command line, in parameters and in messages (`hill`, `huxley`, ...).
    pub name: &'static str,
    /// A label for plots and tables.
    pub label: &'static str,
    /// Its name within a sentence (figure summaries: "DM vs full Huxley").
    pub short_label: &'static str,
    /// One line on what it is.
    pub summary: &'static str,
    /// How its ticks are sub-stepped by default; [`Stepping::Fixed`] for models with state
    /// outside the ODE.
    pub stepping: Stepping,
    /// Whether, with adaptive sub-steps, the ticks whose state moves fast (a carried sub-step
    /// shorter than 1.5 ticks, `HIGH_BELOW` in `integrator/esdirk.rs`) take the fourth-order
    /// method rather than the third-order one (docs/model.md §10, docs/integration.md
    /// "Methods"; the work per tick is printed by `cargo bench --bench limb`).
    pub(crate) fourth_order_transients: bool,
    /// Its calibration: the model for one muscle with these parameters.
    pub(crate) build: fn(&MuscleParams) -> Result<Box<dyn ContractileModel>, ModelBuildError>,
}

/// A model: a reference to its entry in [`crate::physics::models::MODELS`]. Compared by name.
#[derive(Clone, Copy)]
pub struct ModelKind(pub &'static ModelSpec);

impl ModelKind {
    /// The name used on the command line, in parameters and in messages.
    pub fn name(self) -> &'static str {
        self.0.name
    }
    /// The label for plots.
    pub fn label(self) -> &'static str {
        self.0.label
    }
    /// The model's entry.
    pub fn spec(self) -> &'static ModelSpec {
        self.0
    }
    /// Whether its whole state is an ODE (adaptive sub-steps, an ODE reference solution exists).
    pub fn is_ode(self) -> bool {
        self.0.stepping.is_adaptive()
    }
    /// Builds the contractile element of one muscle.
    pub(crate) fn build(
        self,
        params: &MuscleParams,
    ) -> Result<Box<dyn ContractileModel>, ModelBuildError> {
        (self.0.build)(params)
    }
}

impl PartialEq for ModelKind {
    fn eq(&self, other: &Self) -> bool {
        self.0.name == other.0.name
    }
}
impl Eq for ModelKind {}
impl std::hash::Hash for ModelKind {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.0.name.hash(state)
    }
}
impl fmt::Debug for ModelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "ModelKind({})", self.0.name)
    }
}
impl fmt::Display for ModelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.name)
    }
}
