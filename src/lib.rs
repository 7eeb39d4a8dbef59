//! muscle_actuator: muscle actuators (Hill and Huxley models) driving any limb, for ROS 2.
//!
//! - [`physics`]: the mathematics of docs/model.md, no I/O.
//! - [`integrator`]: the fixed-tick implicit stepper and the adaptive reference solver.
//! - [`sim`]: the actuator stepped tick by tick (the facade the node and the CLI use).
//! - [`config`]: the configuration file.
//! - [`msgs`]: the ROS 2 message types and a tick's state as messages (no DDS).
//! - [`recording`]: rosbag2-compatible MCAP recordings (no physics).
//! - [`runs`]: runs as recordings: `simulate --out`, replay and compare.

pub mod cli;
pub mod config;
pub mod csv;
pub mod figures;
pub mod integrator;
pub mod msgs;
pub mod physics;
pub mod recording;
pub mod ros;
pub mod runs;
pub mod sim;
#[cfg(test)]
mod tests_fourth_model;
