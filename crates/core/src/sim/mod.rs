//! The simulation: a plant stepped tick by tick with inputs held over each tick, the actuator
//! facade the node uses, and the offline scenarios. It knows nothing of ROS, files or threads.
//! The files are the crate's modules; what other crates use of them is re-exported here, and
//! [`input`] and [`steady`] are namespaces of their own.
//!
//! - `simulation`: a plant stepped at a fixed tick, inputs held over each tick ([`Simulation`]);
//!   `setup_error`: why a simulation or an actuator cannot be set up ([`SetupError`]);
//! - `part`: one independent part of a limb with its own stepper; `jacobian`: the plant's
//!   Jacobian by blocks for the block-arrowhead iteration matrix (docs/model.md §8b);
//! - `actuator`: [`Actuator`], the facade the node and the CLI step;
//! - `snapshot`: what is observable after a tick ([`StateSnapshot`], [`MuscleSnapshot`],
//!   [`JointSnapshot`]); `energy`: the energy spent since start;
//! - `saved`: an actuator's complete state as bytes and back (`Actuator::to_bytes`,
//!   `Actuator::from_bytes`), for a copy that continues bit for bit;
//! - `scenario`: the paper's experiments and scenario files ([`Scenario`]); `scenario_kinds`:
//!   their attachments and signals; `schedule`: their input schedules ([`Schedule`]);
//!   `scenario_error`: why one cannot be read or run; `records`: a run's records, tick after
//!   tick ([`Run`], [`Record`]).
//! - `rollout`: an actuator stepped over per-tick inputs, chosen outputs into flat buffers
//!   (the Python package's rollouts, [`rollout()`]).
//! - [`input`]: commands by name checked against the actuator's names (unknown names,
//!   mismatched lengths, NaN rejected whole; excitations clamped to [0, 1]).
//! - [`steady`]: isovelocity steady states at full activation and optimal length, with their
//!   energetics (the `steady` command, the steady-state energetics figure).

pub mod input;
pub mod steady;

pub(crate) mod actuator;
pub(crate) mod energy;
pub(crate) mod jacobian;
pub(crate) mod neural_drive;
pub(crate) mod part;
pub(crate) mod records;
pub(crate) mod rollout;
pub(crate) mod saved;
pub(crate) mod scenario;
pub(crate) mod scenario_error;
pub(crate) mod scenario_kinds;
pub(crate) mod schedule;
pub(crate) mod setup_error;
pub(crate) mod simulation;
pub(crate) mod snapshot;

pub use self::{
    actuator::Actuator,
    records::{Record, RecordMismatch, Run},
    rollout::{rollout, write_tick, Outputs, OutputsError, Source},
    saved::SavedStateError,
    scenario::{Scenario, ScenarioRunner, ScheduledInput},
    scenario_error::{BadScenario, ScenarioError, ScenarioRunError},
    scenario_kinds::{SetupKind, Signal},
    schedule::{Schedule, ScheduleError},
    setup_error::SetupError,
    simulation::{default_stepping, Simulation, StepError, MAX_RATE_HZ},
    snapshot::StateSnapshot,
};
/// Defined below the simulation: the stepper's work counters ([`Simulation::stats`]) and what is
/// observable about a muscle and a joint (the physics' `observables`).
pub use crate::{
    integrator::Stats,
    physics::observables::{
        EnergeticsOutputs, JointSnapshot, MuscleSnapshot, JOINT_FIELD_COUNT, MUSCLE_FIELD_COUNT,
    },
};
