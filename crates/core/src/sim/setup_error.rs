//! Why a simulation cannot be set up: its configuration, its plant, its tick rate, its
//! sub-stepping, its inputs' sizes, its threads ([`crate::sim::Simulation::new`],
//! [`crate::sim::Actuator::new`], `set_threads`).

use crate::config::{ConfigError, StepperError};
use crate::physics::models::ModelKind;
use crate::physics::plant::PlantError;
use crate::physics::stepping::SteppingError;

/// Why a simulation cannot be set up.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// The configuration breaks its rules.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// The plant cannot be built (no muscle, a span over a missing joint, a model's calibration).
    #[error(transparent)]
    Plant(#[from] PlantError),
    /// A tick rate that is not a finite number > 0.
    #[error("invalid rate_hz = {0}: must be a finite number > 0")]
    Rate(
        /// The rate given, Hz.
        f64,
    ),
    /// A sub-stepping that breaks its rules.
    #[error(transparent)]
    Stepping(#[from] SteppingError),
    /// The configuration's `[stepper]` table with a stepping that has no tolerance.
    #[error(transparent)]
    Stepper(#[from] StepperError),
    /// Adaptive sub-steps for a model with state outside the ODE.
    #[error("the {0} model needs a fixed number of sub-steps")]
    NeedsFixedSubsteps(
        /// The model.
        ModelKind,
    ),
    /// Inputs sized for another plant.
    #[error(
        "inputs for {muscles} muscles and {joints} joints given to a plant of {plant_muscles} \
         muscles and {plant_joints} joints"
    )]
    InputSizes {
        /// Muscles of the inputs (their excitations).
        muscles: usize,
        /// Joints of the inputs (their external torques).
        joints: usize,
        /// Muscles of the plant.
        plant_muscles: usize,
        /// Joints of the plant.
        plant_joints: usize,
    },
    /// A muscle's Lloyd & Besier activation that cannot run at the tick rate (a positive C1 or
    /// C2 at another `neural_rate_hz`, a delay of too many ticks).
    #[error("muscle {muscle}'s activation: {source}")]
    Activation {
        /// The muscle's index.
        muscle: usize,
        /// Why.
        source: crate::emg::EmgError,
    },
    /// A number of threads outside 1 to the most a simulation takes
    /// (`simulation::MAX_THREADS`).
    #[error("invalid threads = {threads}: must be 1 to {max}")]
    Threads {
        /// The number given.
        threads: usize,
        /// The most allowed.
        max: usize,
    },
    /// The threads could not be started.
    #[error("cannot start {threads} threads: {source}")]
    ThreadPool {
        /// The number asked for.
        threads: usize,
        /// Why.
        source: rayon::ThreadPoolBuildError,
    },
}
