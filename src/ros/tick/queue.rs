//! The bounded command queue from the DDS side to the tick loop: [`COMMAND_CAPACITY`] inputs plus
//! [`CONTROL_RESERVE`] control commands, a full queue drops (and counts) what it cannot hold.
//!
//! The rule: the loop never waits for a sender. The queue is a mutex-guarded ring that the loop
//! only ever `try_lock`s ([`CommandReceiver::try_drain`]): when a sender holds it (preempted
//! inside [`CommandSender::send`], e.g. by the tick thread itself under SCHED_FIFO on the same
//! core), the loop leaves the commands for the next tick ([`Drain::Busy`], counted as
//! `commands_deferred`). `std::sync::mpsc` does not keep that rule: its `try_recv` waits
//! (`Backoff::snooze`) for a sender that has claimed a slot to finish writing it (`start_recv` in
//! the Rust standard library's `library/std/src/sync/mpmc/array.rs`), so a preempted sender would
//! hold the loop for as long as it stays preempted.

use super::messages::Command;
use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, TryLockError};

/// Inputs (excitations, loads) the command queue holds before it drops new ones: a second of
/// commands at 1 kHz, far more than arrive between two ticks unless the loop is stopped.
pub const COMMAND_CAPACITY: usize = 1024;

/// Extra room for control commands (reset, actuator replacement, publish rate), so that a
/// flood of inputs never crowds them out; beyond it they are dropped (and counted) too.
pub const CONTROL_RESERVE: usize = 64;

/// The command queue shared by the senders and the loop.
pub(super) struct CommandQueue {
    pub(super) items: Mutex<VecDeque<Command>>,
    /// The loop's thread, when it sleeps until a command arrives (lockstep).
    waiter: OnceLock<std::thread::Thread>,
    /// Live senders; none left (and the queue empty) = disconnected.
    senders: AtomicUsize,
    dropped: AtomicU64,
    inputs_capacity: usize,
    capacity: usize,
}

impl CommandQueue {
    fn lock(&self) -> MutexGuard<'_, VecDeque<Command>> {
        // A panic while the lock was held cannot leave the deque inconsistent: use it.
        self.items.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The sending side of the command queue (the DDS side, any thread). Never waits for a tick:
/// only, briefly, for another sender's push or the loop's drain (a copy of the queued commands);
/// a full queue drops the command and counts it.
pub struct CommandSender {
    queue: Arc<CommandQueue>,
}

impl CommandSender {
    /// Queues `c` for the next tick; gives it back when the queue is full (it is then counted
    /// as dropped).
    pub fn send(&self, c: Command) -> Result<(), Command> {
        let q = &self.queue;
        let limit = match c {
            Command::Excitation(_) | Command::Load(_) => q.inputs_capacity,
            _ => q.capacity,
        };
        let mut items = q.lock();
        if items.len() >= limit {
            drop(items);
            q.dropped.fetch_add(1, Ordering::Relaxed);
            return Err(c);
        }
        items.push_back(c);
        drop(items);
        if let Some(t) = q.waiter.get() {
            t.unpark();
        }
        Ok(())
    }

    /// Commands dropped so far because the queue was full.
    #[cfg(test)]
    pub fn dropped(&self) -> u64 {
        self.queue.dropped.load(Ordering::Relaxed)
    }
}

impl Clone for CommandSender {
    fn clone(&self) -> Self {
        self.queue.senders.fetch_add(1, Ordering::AcqRel);
        Self {
            queue: self.queue.clone(),
        }
    }
}

impl Drop for CommandSender {
    fn drop(&mut self) {
        self.queue.senders.fetch_sub(1, Ordering::AcqRel);
    }
}

/// What [`CommandReceiver::try_drain`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Drain {
    /// The queued commands (maybe none) were moved to the buffer.
    Taken,
    /// A sender held the queue: nothing taken, try again at the next tick.
    Busy,
    /// Every sender is gone and nothing is left.
    Disconnected,
}

/// The loop's side of the command queue.
pub struct CommandReceiver {
    pub(super) queue: Arc<CommandQueue>,
}

impl CommandReceiver {
    /// A buffer for [`Self::try_drain`] that never has to grow (allocated once, before the
    /// loop starts).
    pub fn buffer(&self) -> Vec<Command> {
        Vec::with_capacity(self.queue.capacity)
    }

    /// Moves every queued command to `out`, in order, if the queue is free; never waits (a
    /// `try_lock`, never a blocking lock or a spin).
    pub fn try_drain(&self, out: &mut Vec<Command>) -> Drain {
        let mut items = match self.queue.items.try_lock() {
            Ok(g) => g,
            Err(TryLockError::Poisoned(e)) => e.into_inner(),
            Err(TryLockError::WouldBlock) => return Drain::Busy,
        };
        if items.is_empty() && self.queue.senders.load(Ordering::Acquire) == 0 {
            return Drain::Disconnected;
        }
        out.extend(items.drain(..));
        Drain::Taken
    }

    /// Commands dropped so far because the queue was full.
    pub fn dropped(&self) -> u64 {
        self.queue.dropped.load(Ordering::Relaxed)
    }

    /// From now on every command sent unparks the calling thread.
    pub fn wake_me(&self) {
        let _ = self.queue.waiter.set(std::thread::current());
    }
}

/// The command queue, bounded: [`COMMAND_CAPACITY`] inputs plus [`CONTROL_RESERVE`] for control
/// commands.
pub fn command_channel() -> (CommandSender, CommandReceiver) {
    command_channel_with(COMMAND_CAPACITY, CONTROL_RESERVE)
}

/// The command queue with room for `inputs` inputs and `reserve` more control commands.
pub fn command_channel_with(inputs: usize, reserve: usize) -> (CommandSender, CommandReceiver) {
    let capacity = inputs + reserve;
    let queue = Arc::new(CommandQueue {
        items: Mutex::new(VecDeque::with_capacity(capacity)),
        waiter: OnceLock::new(),
        senders: AtomicUsize::new(1),
        dropped: AtomicU64::new(0),
        inputs_capacity: inputs,
        capacity,
    });
    (
        CommandSender {
            queue: queue.clone(),
        },
        CommandReceiver { queue },
    )
}
