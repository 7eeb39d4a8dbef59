//! The simulation facade: an actuator stepped tick by tick, with inputs held over each tick.
//! It knows nothing of ROS, files or threads.

pub mod actuator;
pub mod snapshot;

pub use actuator::{Actuator, StepError};
pub use snapshot::{JointSnapshot, MuscleSnapshot};
