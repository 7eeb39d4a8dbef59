//! What this machine allows a 1 kHz loop, with no simulation and no DDS: a thread (SCHED_FIFO
//! when permitted, timer slack 1 ns) sleeping to absolute 1 ms deadlines, its wake-up lateness
//! measured. The node's tick lateness cannot be better than this.
//! `cargo run --release --example timer_baseline -- [seconds]`

use std::time::{Duration, Instant};

fn main() {
    let seconds: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(20);
    let param = libc::sched_param { sched_priority: 40 };
    // SAFETY: pid 0 is this thread; plain integer arguments.
    let rt = unsafe {
        libc::prctl(libc::PR_SET_TIMERSLACK, 1 as libc::c_ulong, 0, 0, 0);
        libc::sched_setscheduler(0, libc::SCHED_FIFO, &param) == 0
    };
    let n = (seconds * 1000) as usize;
    let mut late = Vec::with_capacity(n);
    let origin = Instant::now();
    for i in 1..=n {
        let deadline = origin + Duration::from_millis(i as u64);
        let now = Instant::now();
        if deadline > now {
            std::thread::sleep(deadline - now);
        }
        late.push(
            Instant::now()
                .saturating_duration_since(deadline)
                .as_secs_f64()
                * 1e6,
        );
    }
    late.sort_by(f64::total_cmp);
    let over = late.iter().filter(|&&l| l > 1000.0).count();
    println!(
        "1 kHz sleep loop for {seconds} s (SCHED_FIFO: {rt}): lateness p50 {:.1} us, p99 {:.1} us, max {:.1} us; later than one period: {over}",
        late[n / 2],
        late[n * 99 / 100],
        late[n - 1]
    );
}
