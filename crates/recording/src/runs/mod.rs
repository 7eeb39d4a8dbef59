//! Runs as recordings: the channels of a run file ([`channels`]), its `muscle_actuator` metadata
//! record ([`metadata`]), `simulate --out` (`simulate`, written by `writer`), reading a run
//! back ([`load`], checked by [`checks`] within [`limits`]), [`replay`](mod@replay), [`compare`] and
//! [`export`]; what they report ([`error`]).
//!
//! One time base per recording, named in the metadata ([`muscle_actuator_core::time`]). Offline runs carry
//! their inputs on the input topics themselves, stamped with the tick at which they take effect;
//! the node records inputs as received on the input topics and, as applied by the tick loop, on
//! `<node>/applied/activation` and `<node>/applied/external_load`.

pub mod channels;
pub mod checks;
pub mod compare;
pub mod error;
pub mod export;
pub mod limits;
pub mod load;
pub mod metadata;
pub mod observed;
pub mod replay;
pub(crate) mod simulate;
pub(crate) mod writer;

/// The channels of a run, for the node (`muscle_actuator::ros`) and the tests, which name them
/// from here; the time base is [`muscle_actuator_core::time`]'s.
pub use channels::{
    channel, Channel, Layout, NodeTopic, ACTIVATION, ACTIVATION_TYPE, APPLIED_ACTIVATION,
    APPLIED_JOINT_MOTION, APPLIED_LOAD, DIAGNOSTICS_TYPE, FLOAT64_ARRAY_TYPE, FLOAT64_TYPE,
    JOINT_STATES, JOINT_STATE_TYPE, LOAD, LOAD_TYPE, LOG_TYPE, OFFLINE_NODE, STATE, STATE_TYPE,
};
pub use error::{CompareError, ExportError, RunError};
pub use load::{load_run, InputsAt, InvalidRun, JointMotionAt, LoadError, LoadedRun};
pub use metadata::{
    driven_motion, AttachmentMeta, BuildError, MetadataError, RunMeta, METADATA_NAME,
};
pub use observed::ObservedRun;
pub use replay::{replay, ReplaySummary};
pub use simulate::{run_scenario, simulate_to_mcap};
pub use writer::joint_motion_msg;
