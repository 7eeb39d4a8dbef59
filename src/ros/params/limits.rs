//! The bounds on the parameters' values.

/// The live view's port unless set: Foxglove's own default for a WebSocket connection
/// (`ws://localhost:8765`), so that a first-time user connects without looking it up.
pub const DEFAULT_FOXGLOVE_PORT: u16 = 8765;
/// Highest `real_time_factor` (beyond it, 0 = as fast as possible is the honest value).
pub const MAX_REAL_TIME_FACTOR: f64 = 1e6;

/// Upper bound on the tick rate (the simulation's).
pub use muscle_actuator_core::sim::MAX_RATE_HZ;
/// Longest `model` value, characters (a model name).
pub const MAX_NAME_CHARS: usize = 64;
/// Longest `config` and `record_dir` values, bytes (PATH_MAX).
pub const MAX_PATH_BYTES: usize = 4096;
