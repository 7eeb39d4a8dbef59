//! A person's muscle–tendon units driven by their measurements (docs/emg.md): the units of a
//! CEINMS subject as the project's muscles (`units`), each unit stepped along its measured
//! length under its EMG-driven excitation with its own fibre and tendon dynamics, and the joint
//! moments `Σ F r` they make ([`drive`]).
//!
//! - `units`: a CEINMS subject's units as the project's muscles; `mod@file`: the project's
//!   subject file; `bounds` and `record`: a calibration's bounds and its record.
//! - [`drive`]: a trial's units stepped (prepared in `prepare`, refused per `limits` with a
//!   `DriveError`).
//! - [`calibrate`]: the parameters fitted to measured moments.
//!
//! A unit here has no joint of a limb: its muscle–tendon length l_mt(t) is an input. The engine
//! drives it through a driven "length coordinate" of its own (a driven joint whose angle is the
//! length beyond l_opt + l_ts, spanned with a moment arm of −1 m: docs/model.md §8b, §8c), which
//! keeps every unit an independent part of the plant.

pub(crate) mod bounds;
pub mod calibrate;
pub(crate) mod calibration_record;
pub mod drive;
mod error;
pub(crate) mod file;
pub(crate) mod limits;
mod prepare;
pub(crate) mod units;

pub use drive::{DriveError, Prediction, PreparedTrial};
pub use file::SubjectFileError;
pub use units::{SubjectModel, UnitModel};
