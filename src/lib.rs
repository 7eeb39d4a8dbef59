//! muscle_actuator: muscle actuators (Hill and Huxley models) driving any limb, for ROS 2.
//!
//! The layers are crates: [`muscle_actuator_core`] (the engine: physics, stepper, simulation,
//! configuration; no ROS), [`muscle_actuator_measured`] (measured data of people: CEINMS readers,
//! subjects, prediction, calibration), [`muscle_actuator_recording`] (MCAP recordings and runs;
//! no DDS) and this one, the node, the command line and the figures, which names the crate of
//! every item it uses from below.
//!
//! - [`figures`]: the paper's figures reproduced (`figures`), and `compare --plot`.
//! - [`ros`]: the ROS 2 node (`node`).
//! - [`cli`]: the command line (`src/main.rs` calls [`cli::main`]).

pub mod cli;
pub mod figures;
pub mod ros;

#[cfg(all(test, feature = "test-model"))]
mod tests_fourth_model;
#[cfg(all(test, feature = "test-topic"))]
mod tests_topic;
