//! The fixed-rate tick loop, on its own thread (docs/ros-interface.md, docs/time.md). It owns
//! the actuator; everything else talks to it through queues, so it never waits for DDS: commands
//! queue in a bounded [`command_channel`] and are applied at the next tick boundary, samples go
//! out through a bounded channel (dropped and counted when the publisher falls behind), events
//! for the log through another (likewise).
//!
//! - `messages`: what goes in and out ([`Command`], [`Output`], [`Sample`], [`Applied`],
//!   [`Event`]);
//! - `queue`: the command queue, which the loop never waits for;
//! - `stamped_inputs`: inputs stamped ahead, waiting for their tick (simulated clocks);
//! - `stats`: the counters shared with `/diagnostics`, the lateness histogram, the run summary;
//! - `realtime`: the tick thread's timer slack and SCHED_FIFO request;
//! - `pacing`: deadlines and the stamps' wall clock;
//! - `tick_loop`: the loop, a `TickLoop` whose steps are named methods; `apply`: the commands
//!   it applies and its resets.

mod apply;
mod messages;
mod pacing;
mod queue;
mod realtime;
mod stamped_inputs;
mod stats;
mod tick_loop;

#[cfg(test)]
mod tests;

pub use messages::{Applied, AppliedInput, Command, Event, Output, Sample};
pub use pacing::Pacing;
pub use queue::{command_channel, CommandReceiver, CommandSender};
pub use stats::{RunSummary, TickStats};
pub use tick_loop::LoopIo;

use muscle_actuator_core::sim::Actuator;
use tick_loop::TickLoop;

/// Runs the loop on the calling thread until `io.stop` is set (or the command channel closes).
/// Ticks at the actuator's rate against absolute deadlines; a tick that starts more than one
/// period late is an overrun.
pub fn run(actuator: Actuator, publish_every: u64, io: LoopIo) -> RunSummary {
    TickLoop::start(actuator, publish_every, io).run()
}

/// Starts the loop on its own thread.
pub fn spawn(
    actuator: Actuator,
    publish_every: u64,
    io: LoopIo,
) -> std::io::Result<std::thread::JoinHandle<RunSummary>> {
    std::thread::Builder::new()
        .name("tick".into())
        .spawn(move || run(actuator, publish_every, io))
}
