//! SIGINT and SIGTERM: the first asks for a clean stop; one more, well after the first while
//! the stop is stuck, finishes the recording at once and exits with status 130.

use muscle_actuator_recording::recording::RecordSender;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// A second SIGINT/SIGTERM sooner than this after the first is part of the same stop request.
const SIGNAL_INSIST_AFTER: Duration = Duration::from_secs(2);

/// Longest the recording may take to finish on an insisted stop.
const EMERGENCY_FINISH: Duration = Duration::from_secs(2);

/// Why the stop signals cannot be handled.
#[derive(Debug, thiserror::Error)]
pub enum SignalError {
    /// The handlers cannot be registered.
    #[error("cannot install signal handlers: {0}")]
    Handlers(#[source] std::io::Error),
    /// The thread that waits for them cannot start.
    #[error("cannot start the signal thread: {0}")]
    Thread(#[source] std::io::Error),
}

/// The installed handlers.
pub(crate) struct StopSignals {
    /// Receives one `()` on the first signal.
    pub(crate) requested: smol::channel::Receiver<()>,
    /// The recording to finish if a stop is insisted on (set once it has started).
    pub(crate) recording: Arc<Mutex<Option<RecordSender>>>,
    handle: signal_hook::iterator::Handle,
}

impl StopSignals {
    /// Installs the handlers first thing, so that an early Ctrl-C is not lost.
    pub(crate) fn install() -> Result<Self, SignalError> {
        let (tx, requested) = smol::channel::bounded::<()>(1);
        let mut signals = signal_hook::iterator::Signals::new([
            signal_hook::consts::SIGINT,
            signal_hook::consts::SIGTERM,
        ])
        .map_err(SignalError::Handlers)?;
        let handle = signals.handle();
        let recording: Arc<Mutex<Option<RecordSender>>> = Arc::new(Mutex::new(None));
        let rec = recording.clone();
        std::thread::Builder::new()
            .name("signals".into())
            .spawn(move || {
                let mut first: Option<Instant> = None;
                for _ in signals.forever() {
                    match first {
                        None => {
                            first = Some(Instant::now());
                            let _ = tx.try_send(());
                        }
                        // A terminal's Ctrl-C through a wrapper, or `timeout`, delivers the
                        // signal to the process group too: a second one in the same instant is
                        // the same request. Only one well after the first, while the shutdown
                        // is stuck, cuts it short, and even then the recording is finished
                        // first.
                        Some(t) if t.elapsed() >= SIGNAL_INSIST_AFTER => {
                            if let Some(tx) = rec.lock().ok().and_then(|g| g.clone()) {
                                tx.finish_now(EMERGENCY_FINISH);
                            }
                            std::process::exit(130);
                        }
                        Some(_) => {}
                    }
                }
            })
            .map_err(SignalError::Thread)?;
        Ok(Self {
            requested,
            recording,
            handle,
        })
    }

    /// Names the recording an insisted stop must finish.
    pub(crate) fn guard_recording(&self, tx: Option<RecordSender>) {
        if let Ok(mut g) = self.recording.lock() {
            *g = tx;
        }
    }

    /// Ends the signal thread.
    pub(crate) fn close(&self) {
        self.handle.close();
    }
}
