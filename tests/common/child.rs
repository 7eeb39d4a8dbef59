//! The command line run as a child under limits, for the hostile-input tests: a wall-clock limit
//! (the child is killed after it: a hang fails the test instead of stalling it), an address-space
//! limit (RLIMIT_AS, so an attempt to allocate gigabytes shows up as a failed allocation) and a
//! verdict on how it ended. Included by path (`#[path = "common/child.rs"] mod child;`).
#![allow(dead_code)]

use std::ffi::OsString;
use std::io::Read;
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Address space a child may map, bytes (1 GiB).
pub const MEMORY_LIMIT: u64 = 1 << 30;

/// The longest error line accepted: user strings must be quoted as excerpts, not whole.
pub const MAX_ERROR_LINE: usize = 2000;

/// How a child ended.
#[derive(Debug)]
pub struct Ended {
    /// The arguments it ran with (for messages).
    pub args: Vec<OsString>,
    /// Exit code (None: killed by a signal, or by us on the time limit).
    pub code: Option<i32>,
    /// The signal that ended it, if one did.
    pub signal: Option<i32>,
    /// Killed on the time limit.
    pub timed_out: bool,
    pub stdout: String,
    pub stderr: String,
    pub elapsed: Duration,
}

impl Ended {
    /// Exit 0.
    pub fn accepted(&self) -> bool {
        self.code == Some(0)
    }

    /// What is wrong with how it ended, if anything: a hang, a signal (an abort on a failed
    /// allocation included), a panic, a refusal without an `error:` line, an error line that
    /// quotes too much.
    pub fn problem(&self) -> Option<String> {
        let what = if self.timed_out {
            format!("did not finish within the time limit ({:?})", self.elapsed)
        } else if let Some(s) = self.signal {
            format!("killed by signal {s}")
        } else if self.code == Some(101) || self.stderr.contains("panicked") {
            "panicked".into()
        } else if self.code != Some(0) && !self.stderr.lines().any(|l| l.starts_with("error: ")) {
            format!("exit {:?} without an `error:` line", self.code)
        } else if let Some(l) = self.stderr.lines().find(|l| l.len() > MAX_ERROR_LINE) {
            format!("a stderr line of {} bytes", l.len())
        } else {
            return None;
        };
        let tail: String = self.stderr.chars().take(600).collect();
        Some(format!("{:?}: {what}; stderr: {tail}", self.args))
    }
}

/// Runs the CLI with `args` under the limits.
pub fn run(args: &[OsString], time_limit: Duration) -> Ended {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_muscle_actuator"));
    cmd.args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    // SAFETY: setrlimit is async-signal-safe and touches no memory of the parent.
    unsafe {
        cmd.pre_exec(|| {
            let lim = libc::rlimit {
                rlim_cur: MEMORY_LIMIT as libc::rlim_t,
                rlim_max: MEMORY_LIMIT as libc::rlim_t,
            };
            if libc::setrlimit(libc::RLIMIT_AS, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let start = Instant::now();
    let mut child = cmd.spawn().expect("the CLI starts");
    // Both pipes drained on their own threads, so a chatty child cannot block on a full pipe.
    let drain = |pipe: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            if let Some(mut p) = pipe {
                let _ = p.read_to_end(&mut v);
            }
            String::from_utf8_lossy(&v).into_owned()
        })
    };
    let out = drain(
        child
            .stdout
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let err = drain(
        child
            .stderr
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let mut timed_out = false;
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break s;
        }
        if start.elapsed() > time_limit {
            timed_out = true;
            let _ = child.kill();
            break child.wait().expect("wait");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let elapsed = start.elapsed();
    Ended {
        args: args.to_vec(),
        code: status.code(),
        signal: if timed_out { None } else { status.signal() },
        timed_out,
        stdout: out.join().unwrap_or_default(),
        stderr: err.join().unwrap_or_default(),
        elapsed,
    }
}

/// Runs every argument list (on `workers` threads), results in order.
pub fn run_all(cases: &[Vec<OsString>], time_limit: Duration, workers: usize) -> Vec<Ended> {
    let next = AtomicUsize::new(0);
    let mut results: Vec<Option<Ended>> = (0..cases.len()).map(|_| None).collect();
    let slots = std::sync::Mutex::new(&mut results);
    std::thread::scope(|s| {
        for _ in 0..workers.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(args) = cases.get(i) else { break };
                let e = run(args, time_limit);
                slots.lock().unwrap()[i] = Some(e);
            });
        }
    });
    results
        .into_iter()
        .map(|e| e.expect("every case ran"))
        .collect()
}

/// A small deterministic generator (SplitMix64; a few lines, so no crate for it), so every
/// generated case reproduces from its seed.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    pub fn bytes(&mut self, n: usize) -> Vec<u8> {
        (0..n).map(|_| self.next_u64() as u8).collect()
    }

    pub fn pick<'a, T>(&mut self, v: &'a [T]) -> &'a T {
        &v[self.below(v.len())]
    }
}

/// Fails with the first `shown` problems (each cut to `width` characters) if there are any.
pub fn assert_no_problems(problems: &[String], shown: usize, width: usize) {
    assert!(
        problems.is_empty(),
        "{} problems:\n{}",
        problems.len(),
        problems
            .iter()
            .take(shown)
            .map(|p| p.chars().take(width).collect::<String>())
            .collect::<Vec<_>>()
            .join("\n")
    );
}
