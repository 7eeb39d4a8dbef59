//! muscle_actuator: muscle actuators (Hill and Huxley models) driving any limb, for ROS 2.
//!
//! - [`physics`]: the mathematics of docs/model.md, no I/O.
//! - [`integrator`]: the fixed-tick implicit stepper, its tableaux and iteration matrices.
//! - [`sim`]: the actuator stepped tick by tick (the facade the node and the CLI use).
//! - [`config`]: the configuration file: schema, the antagonistic-pair form, parsing, validation.
//! - [`msgs`]: the ROS 2 message types and a tick's state as messages (no DDS).
//! - [`recording`]: rosbag2-compatible MCAP recordings (no physics).
//! - [`runs`]: runs as recordings: metadata, `simulate --out`, loading, replay, compare, export.
//! - [`csv`]: a run as CSV (`simulate --csv`, `export`).
//! - [`figures`]: the paper's figures reproduced (`figures`).
//! - [`ros`]: the ROS 2 node (`node`).
//! - [`cli`]: the command line (`src/main.rs` calls [`cli::main`]).
//! - [`time`]: the time base of a run (ticks ↔ stamps), now, ISO 8601 dates (neutral).
//! - [`text`]: user text as messages quote it: excerpts, one-line messages (neutral).
//! - [`files`]: bounded reading of the files a user names (neutral).
//! - [`state_bytes`]: the values of a saved state as bytes, every read checked (neutral).

pub mod cli;
pub mod config;
pub mod csv;
pub mod figures;
pub mod files;
pub mod integrator;
pub mod msgs;
pub mod physics;
pub mod recording;
pub mod ros;
pub mod runs;
pub mod sim;
pub mod state_bytes;
pub mod text;
pub mod time;

#[cfg(test)]
mod tests_fourth_model;
