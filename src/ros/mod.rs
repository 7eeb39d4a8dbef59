//! The ROS 2 node (`muscle_actuator node`): docs/ros-interface.md.
//!
//! Thin wiring around [`muscle_actuator_core::sim::Actuator`], which knows nothing of DDS. Its public face is
//! [`run_node`]; the modules are the crate's own. Start-up:
//! - `args`: the standard ROS 2 command-line arguments, name expansion and remapping;
//! - `setup`: what the command line asks of the node, resolved before DDS starts;
//! - `params`: the parameters and their rules; `param_callbacks`: changes at run time;
//!   `node_state`: what the node's tasks share (parameters in force, names, the loop's queue);
//! - `clock`: wall, sim or lockstep time, or following `/clock`;
//! - `endpoints`: the node's topics and services, each declared once;
//! - `dds`: the participant and the node's endpoints.
//!
//! Running:
//! - `tick`: the fixed-rate loop on its own thread (queues in and out, never waits on DDS);
//! - `sample_messages`: a tick's sample as the published messages;
//! - `outputs`: the output topics, one producer each, and the publisher thread that writes them;
//! - `threads`: the tick loop, the publisher and the applied-inputs recorder, started and stopped
//!   together;
//! - `inputs`: the input topics, one handler each, served on the executor; `roles`: which
//!   handler or producer each endpoint has;
//! - `services`: `~/reset` and `~/step`; `events`: the tick loop's events as log lines;
//! - incoming commands are validated by [`muscle_actuator_core::sim::input`] (the core crate's rules, shared
//!   with the Python package);
//! - `diagnostics`: `/diagnostics`, once a second;
//! - `logging`: stderr, `/rosout` and the recording's log, at a `severity`;
//! - `record`: the node's MCAP recording (off the tick thread);
//! - `live`: the live view, a Foxglove WebSocket server (off the tick thread);
//!   `live_requests`: what its clients ask, answered on the executor;
//! - `signals`: SIGINT and SIGTERM;
//! - `error`: why the node cannot run ([`NodeError`]);
//! - `node`: the node's main, which wires these together.

pub(crate) mod args;
pub(crate) mod clock;
pub(crate) mod dds;
pub(crate) mod diagnostics;
pub(crate) mod endpoints;
mod error;
mod events;
pub(crate) mod inputs;
pub(crate) mod live;
mod live_requests;
pub(crate) mod logging;
#[cfg(test)]
mod markdown_table;
pub(crate) mod node;
mod node_state;
pub(crate) mod outputs;
mod param_callbacks;
pub(crate) mod params;
pub(crate) mod record;
mod roles;
mod sample_messages;
mod services;
pub(crate) mod setup;
pub(crate) mod severity;
mod signals;
mod threads;
pub(crate) mod tick;

pub use args::{ArgsError, FlowTooDeep, NameError, ParamsFileError, ValueError, DEFAULT_NODE_NAME};
pub use clock::UnknownClock;
pub use dds::DdsError;
pub use error::NodeError;
pub use params::{BuildError, ParameterError};
pub use setup::SetupError;
pub use signals::SignalError;
pub use threads::ThreadsError;

/// Runs the node until SIGINT/SIGTERM. `args` is everything after `node` on the command line
/// (`--ros-args ...`). Errors (bad argument, bad parameter, DDS set-up) come back as one line.
pub fn run_node(args: Vec<String>) -> Result<(), NodeError> {
    node::run(&args)
}
