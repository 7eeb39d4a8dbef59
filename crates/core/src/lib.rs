//! muscle_actuator_core: the muscle actuator's engine, with no ROS, no files of recordings, no
//! plots and no command line in it. The `muscle_actuator` crate (the node, the CLI, the figures)
//! and the Python package build on it.
//!
//! - [`physics`]: the mathematics of docs/model.md, no I/O.
//! - `integrator`: the fixed-tick implicit stepper, its tableaux and iteration matrices (the
//!   crate's).
//! - [`sim`]: the actuator stepped tick by tick, its inputs checked by name, the offline
//!   scenarios, saved states, rollouts and steady states.
//! - [`emg`]: EMG to activation: Butterworth filters, the raw-EMG chain to a normalised linear
//!   envelope, neural activation and its nonlinearity (Lloyd & Besier 2003), no I/O.
//! - [`config`]: the configuration file: schema, the antagonistic-pair form, parsing, validation.
//! - [`csv`]: a run as CSV (`simulate --csv`, `export`).
//! - [`time`]: the time base of a run (ticks ↔ stamps), now, ISO 8601 dates (neutral).
//! - [`text`]: user text as messages quote it: excerpts, one-line messages (neutral).
//! - [`files`]: bounded reading of the files a user names, files written whole (neutral).
//! - [`state_bytes`]: the values of a saved state as bytes, every read checked (neutral).

#![warn(missing_docs)]
#![warn(unreachable_pub)]

pub mod config;
pub mod csv;
pub mod emg;
pub mod files;
pub(crate) mod integrator;
pub mod physics;
pub mod sim;
pub mod state_bytes;
pub mod text;
pub mod time;
