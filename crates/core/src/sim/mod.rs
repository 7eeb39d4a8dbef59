//! The simulation: a plant stepped tick by tick with inputs held over each tick, the actuator
//! facade the node uses, and the offline scenarios. It knows nothing of ROS, files or threads.
//!
//! - [`simulation`]: a plant stepped at a fixed tick, inputs held over each tick;
//!   `setup_error`: why a simulation or an actuator cannot be set up;
//! - `part`: one independent part of a limb with its own stepper; [`jacobian`]: the plant's
//!   Jacobian by blocks for the block-arrowhead iteration matrix (docs/model.md §8b);
//! - `actuator`: [`Actuator`], the facade the node and the CLI step;
//! - [`snapshot`]: what is observable after a tick; `energy`: the energy spent since start;
//! - [`saved`]: an actuator's complete state as bytes and back (`Actuator::to_bytes`,
//!   `Actuator::from_bytes`), for a copy that continues bit for bit;
//! - [`scenario`]: the paper's experiments and scenario files; `scenario_kinds`: their
//!   attachments and signals; [`schedule`]: their input schedules; [`scenario_error`]: why one
//!   cannot be read or run; [`records`]: a run's records, tick after tick.
//! - [`rollout`]: an actuator stepped over per-tick inputs, chosen outputs into flat buffers
//!   (the Python package's rollouts).
//! - [`input`]: commands by name checked against the actuator's names (unknown names,
//!   mismatched lengths, NaN rejected whole; excitations clamped to [0, 1]).
//! - [`steady`]: isovelocity steady states at full activation and optimal length, with their
//!   energetics (the `steady` command, the steady-state energetics figure).

pub(crate) mod actuator;
pub(crate) mod energy;
pub mod input;
pub mod jacobian;
pub(crate) mod neural_drive;
pub(crate) mod part;
pub mod records;
pub mod rollout;
pub mod saved;
pub mod scenario;
pub mod scenario_error;
pub(crate) mod scenario_kinds;
pub mod schedule;
pub(crate) mod setup_error;
pub mod simulation;
pub mod snapshot;
pub mod steady;

pub use actuator::Actuator;
pub use setup_error::SetupError;
pub use simulation::{Simulation, StepError};
pub use snapshot::{JointSnapshot, MuscleSnapshot, StateSnapshot};
