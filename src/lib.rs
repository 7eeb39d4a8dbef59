//! muscle_actuator: muscle actuators (Hill and Huxley models) driving any limb, for ROS 2.
//!
//! The layers are crates: [`muscle_actuator_core`] (the engine: physics, stepper, simulation,
//! configuration; no ROS), [`muscle_actuator_recording`] (MCAP recordings and runs; no DDS) and
//! this one, the node, the command line and the figures. Their modules are re-exported here, so
//! `muscle_actuator::physics` is `muscle_actuator_core::physics`.
//!
//! - [`physics`], [`integrator`], [`sim`], [`config`], [`csv`], [`emg`], [`measured`], [`time`],
//!   [`text`], [`files`], [`state_bytes`]: from [`muscle_actuator_core`].
//! - [`msgs`], [`recording`], [`runs`]: from [`muscle_actuator_recording`].
//! - [`figures`]: the paper's figures reproduced (`figures`), and `compare --plot`.
//! - [`ros`]: the ROS 2 node (`node`).
//! - [`cli`]: the command line (`src/main.rs` calls [`cli::main`]).

pub use muscle_actuator_core::{
    config, csv, emg, files, integrator, measured, physics, sim, state_bytes, subject, text, time,
};
pub use muscle_actuator_recording::{msgs, recording, runs};

pub mod cli;
pub mod figures;
pub mod ros;

#[cfg(all(test, feature = "test-model"))]
mod tests_fourth_model;
