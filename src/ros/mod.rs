//! The ROS 2 node (`muscle_actuator node`): README, "The ROS interface".
//!
//! Thin wiring around [`crate::sim::Actuator`], which knows nothing of DDS:
//! - [`args`]: the standard ROS 2 command-line arguments, name expansion and remapping;
//! - [`params`]: the parameters and their rules; [`clock`]: wall, sim or lockstep time;
//! - [`input`]: validation of incoming commands;
//! - [`record`]: the node's MCAP recording (off the tick thread);
//! - [`tick`]: the fixed-rate loop on its own thread (channels in and out, never waits on DDS);
//! - [`node`]: the DDS side (ros2-client on RustDDS): topics, services, parameters, diagnostics,
//!   logging, signals.

pub mod args;
pub mod clock;
pub mod dds;
pub mod diagnostics;
pub mod input;
pub mod logging;
pub mod node;
mod param_callbacks;
pub mod params;
pub mod record;
pub(crate) mod setup;
mod signals;
mod tasks;
mod threads;
pub mod tick;

/// The node's name unless remapped with `-r __node:=...`.
pub const DEFAULT_NODE_NAME: &str = "muscle_actuator";

/// Runs the node until SIGINT/SIGTERM. `args` is everything after `node` on the command line
/// (`--ros-args ...`). Errors (bad argument, bad parameter, DDS set-up) come back as one line.
pub fn run_node(args: Vec<String>) -> Result<(), String> {
    node::run(&args)
}
