//! Why a value for one of the node's parameters is refused: its name, its type, its bounds.
//! The parameter services send the message as their reason, so it names the parameter and
//! quotes long values as excerpts.

use super::limits::{MAX_RATE_HZ, MAX_REAL_TIME_FACTOR};
use crate::ros::clock::UnknownClock;
use muscle_actuator_core::physics::models::UnknownModel;
use muscle_actuator_core::physics::UnknownEnergyModel;

/// Why a parameter value is refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ParameterError {
    /// The node declares no parameter of this name.
    #[error("unknown parameter {name:?} (known: {known})")]
    Unknown {
        /// The name, as an excerpt.
        name: String,
        /// Every parameter's name, joined.
        known: String,
    },
    /// A double parameter given another type.
    #[error("parameter {name:?} must be a double (e.g. 1000.0), got {got}")]
    NotDouble {
        /// The parameter.
        name: &'static str,
        /// The value given ([`super::Given::describe`]).
        got: String,
    },
    /// A string parameter given another type.
    #[error("parameter {name:?} must be a string, got {got}")]
    NotString {
        /// The parameter.
        name: &'static str,
        /// The value given ([`super::Given::describe`]).
        got: String,
    },
    /// A string longer than its parameter's kind allows.
    #[error("parameter {name:?} is too long ({bytes} bytes, at most {limit}): {excerpt}")]
    TooLong {
        /// The parameter.
        name: &'static str,
        /// The string's length, bytes.
        bytes: usize,
        /// The limit, with its unit ("64 characters", "4096 bytes").
        limit: &'static str,
        /// The string, as an excerpt.
        excerpt: String,
    },
    /// A bool parameter given another type.
    #[error("parameter {name:?} must be a bool, got {got}")]
    NotBool {
        /// The parameter.
        name: &'static str,
        /// The value given ([`super::Given::describe`]).
        got: String,
    },
    /// A count given something other than an integer of at least 1.
    #[error("parameter {name:?} must be an integer >= 1, got {got}")]
    NotCount {
        /// The parameter.
        name: &'static str,
        /// The value given ([`super::Given::describe`]).
        got: String,
    },
    /// A port given something other than an integer from 0 to 65535.
    #[error(
        "parameter {name:?} must be an integer from 0 (off) to {}, got {got}",
        u16::MAX
    )]
    NotPort {
        /// The parameter.
        name: &'static str,
        /// The value given ([`super::Given::describe`]).
        got: String,
    },
    /// `rate_hz` not finite, not positive or above [`MAX_RATE_HZ`].
    #[error("rate_hz = {0} is invalid: must be a finite number > 0 and <= {MAX_RATE_HZ}")]
    RateHz(f64),
    /// `publish_rate_hz` not finite or negative.
    #[error("publish_rate_hz = {0} is invalid: must be finite and >= 0 (0 = publish every tick)")]
    PublishRateHz(f64),
    /// `real_time_factor` outside 0 to [`MAX_REAL_TIME_FACTOR`].
    #[error(
        "real_time_factor = {0} is invalid: must be from 0 (as fast as possible) to \
         {MAX_REAL_TIME_FACTOR}"
    )]
    RealTimeFactor(f64),
    /// `clock_rate_hz` not finite or negative.
    #[error("clock_rate_hz = {0} is invalid: must be finite and >= 0 (0 = every tick)")]
    ClockRateHz(f64),
    /// `model` names no model.
    #[error(transparent)]
    Model(#[from] UnknownModel),
    /// `clock` names no clock mode.
    #[error(transparent)]
    Clock(#[from] UnknownClock),
    /// `energy_model` names no energy model (and is not empty).
    #[error("{0} (or empty: each muscle's from the configuration)")]
    EnergyModel(#[source] UnknownEnergyModel),
}
