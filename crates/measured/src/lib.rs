//! muscle_actuator_measured: measured data of people and the muscles made from them, on the
//! engine (`muscle_actuator_core`), with no ROS, no recordings, no plots and no command line.
//! The command line (`subject`, `predict`, `calibrate`), the Python package and the node's live
//! EMG estimator build on it.
//!
//! - [`measured`]: measured data of people as CEINMS lays it out (EMG, muscle–tendon lengths,
//!   moment arms, joint moments, the subject's parameters, the EMG-to-unit map), read and checked.
//! - [`subject`]: a person's muscle–tendon units (a CEINMS subject) driven by measured
//!   lengths and EMG, their joint moments, prediction and calibration.
//!
//! The EMG signal chain (filters, envelope, neural activation and its nonlinearity) is the
//! engine's (`muscle_actuator_core::emg`): a muscle's Lloyd & Besier activation steps it every
//! tick, so the engine cannot do without it; this crate reads and drives data through it.

#![warn(missing_docs)]
#![warn(unreachable_pub)]

pub mod measured;
pub mod subject;
