//! The tick thread's real-time set-up (Linux): a timer slack of 1 ns, so that its sleeps end
//! close to their deadline (prctl(2), `PR_SET_TIMERSLACK`: the kernel may otherwise defer a
//! timer's expiry by the default 50 µs to coalesce wake-ups), and, for a loop with deadlines to
//! meet, a request for `SCHED_FIFO` (sched(7)), granted to root or with CAP_SYS_NICE or an
//! `RLIMIT_RTPRIO` limit. Only the wall clock asks for it: a simulated clock running flat out
//! under SCHED_FIFO would starve the node's other threads (docs/time.md).

/// Lowers this thread's timer slack so that sleeps end close to their deadline (Linux).
pub(super) fn tighten_timer_slack() {
    #[cfg(target_os = "linux")]
    // SAFETY: prctl(PR_SET_TIMERSLACK) takes an integer argument and affects only this thread.
    unsafe {
        libc::prctl(libc::PR_SET_TIMERSLACK, 1 as libc::c_ulong, 0, 0, 0);
    }
}

/// Priority of the tick thread under SCHED_FIFO, when the process may use it (root or
/// CAP_SYS_NICE / an rtprio limit): the loop then preempts the DDS and publisher threads and other
/// processes' ordinary threads, which is what holds the period on a loaded machine.
const REALTIME_PRIORITY: libc::c_int = 40;

/// Asks for real-time (SCHED_FIFO) scheduling for this thread; returns whether it was granted.
/// Without the privilege the loop runs at normal priority, which is only slower to wake.
pub(super) fn request_realtime_priority() -> bool {
    #[cfg(target_os = "linux")]
    {
        let param = libc::sched_param {
            sched_priority: REALTIME_PRIORITY,
        };
        // SAFETY: pid 0 is the calling thread; `param` is a valid sched_param for the call.
        unsafe { libc::sched_setscheduler(0, libc::SCHED_FIFO, &param) == 0 }
    }
    #[cfg(not(target_os = "linux"))]
    false
}
