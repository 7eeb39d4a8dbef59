//! The simulation: a plant stepped tick by tick with inputs held over each tick, the actuator
//! facade the node uses, and the offline scenarios. It knows nothing of ROS, files or threads.

pub mod actuator;
pub mod jacobian;
pub mod part;
pub mod scenario;
pub mod schedule;
pub mod simulation;
pub mod snapshot;

pub use actuator::Actuator;
pub use simulation::{Simulation, StepError};
pub use snapshot::{JointSnapshot, MuscleSnapshot, StateSnapshot};
