//! Why the node cannot run: its set-up from the command line, the actuator its parameters
//! describe, DDS, the stop signals, its threads. Each message is one line; the command line
//! prints it after `error: `.

use super::dds::DdsError;
use super::params::BuildError;
use super::setup::SetupError;
use super::signals::SignalError;
use super::threads::ThreadsError;

/// Why the node stopped with an error.
#[derive(Debug, thiserror::Error)]
pub enum NodeError {
    /// The command line gives no set-up.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The parameters give no actuator.
    #[error(transparent)]
    Build(#[from] BuildError),
    /// SIGINT and SIGTERM cannot be handled.
    #[error(transparent)]
    Signals(#[from] SignalError),
    /// The participant, the node or an endpoint cannot be created.
    #[error(transparent)]
    Dds(#[from] DdsError),
    /// A thread cannot start, or the tick loop did not stop.
    #[error(transparent)]
    Threads(#[from] ThreadsError),
}
