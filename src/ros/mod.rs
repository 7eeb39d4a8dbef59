//! The ROS 2 node (`muscle_actuator node`): README, "The ROS interface".
//!
//! Thin wiring around [`crate::sim::Actuator`], which knows nothing of DDS:
//! - [`args`]: the standard ROS 2 command-line arguments, name expansion and remapping;
//! - [`params`]: the six parameters and their rules;
//! - [`input`]: validation of incoming commands;
//! - [`record`]: the node's MCAP recording (off the tick thread);
//! - [`tick`]: the fixed-rate loop on its own thread (channels in and out, never waits on DDS);
//! - [`msgs`]: the message types, field for field as in `msg/*.msg`;
//! - [`node`]: the DDS side (ros2-client on RustDDS): topics, services, parameters, diagnostics,
//!   logging, signals.

pub mod args;
pub mod diagnostics;
pub mod input;
pub mod logging;
pub mod msgs;
pub mod node;
pub mod params;
pub mod record;
pub mod tick;

/// The node's name unless remapped with `-r __node:=...`.
pub const DEFAULT_NODE_NAME: &str = "muscle_actuator";

/// Runs the node until SIGINT/SIGTERM. `args` is everything after `node` on the command line
/// (`--ros-args ...`). Errors (bad argument, bad parameter, DDS set-up) come back as one line.
pub fn run_node(args: Vec<String>) -> Result<(), String> {
    node::run(&args)
}
