//! The ROS 2 node (`muscle_actuator node`): docs/ros-interface.md.
//!
//! Thin wiring around [`crate::sim::Actuator`], which knows nothing of DDS. Start-up:
//! - [`args`]: the standard ROS 2 command-line arguments, name expansion and remapping;
//! - `setup`: what the command line asks of the node, resolved before DDS starts;
//! - [`params`]: the parameters and their rules; `param_callbacks`: changes at run time;
//! - [`clock`]: wall, sim or lockstep time, or following `/clock`;
//! - `endpoints`: the node's topics and services, each declared once;
//! - [`dds`]: the participant and the node's endpoints.
//!
//! Running:
//! - [`tick`]: the fixed-rate loop on its own thread (queues in and out, never waits on DDS);
//! - `threads`: the tick loop, the publisher and the applied-inputs recorder, started and stopped
//!   together;
//! - `tasks`: the executor's tasks: the input topics, the services, the loop's events;
//! - incoming commands are validated by [`crate::sim::input`] (the core crate's rules, shared
//!   with the Python package);
//! - [`diagnostics`]: `/diagnostics`, once a second;
//! - [`logging`]: stderr, `/rosout` and the recording's log;
//! - [`record`]: the node's MCAP recording (off the tick thread);
//! - `live`: the live view, a Foxglove WebSocket server (off the tick thread);
//!   `live_requests`: what its clients ask, answered on the executor;
//! - `signals`: SIGINT and SIGTERM;
//! - [`node`]: the node's main, which wires these together.

pub mod args;
pub mod clock;
pub mod dds;
pub mod diagnostics;
pub(crate) mod endpoints;
pub(crate) mod live;
mod live_requests;
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

pub use args::DEFAULT_NODE_NAME;

/// Runs the node until SIGINT/SIGTERM. `args` is everything after `node` on the command line
/// (`--ros-args ...`). Errors (bad argument, bad parameter, DDS set-up) come back as one line.
pub fn run_node(args: Vec<String>) -> Result<(), String> {
    node::run(&args)
}
