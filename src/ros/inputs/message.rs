//! The message types an input topic may carry.

use muscle_actuator_recording::msgs::muscle_actuator_msgs::{ActivationCommand, ExternalLoad};
use muscle_actuator_recording::msgs::{Clock, Float64, Float64MultiArray, Int64, JointState};
use serde::de::DeserializeOwned;
use serde::Serialize;

/// A message an input topic carries: read from DDS's CDR or a client's JSON (whose missing
/// fields take the type's defaults), written into the recording.
pub(crate) trait InputMessage: 'static + DeserializeOwned + Serialize + Default {
    /// Its header's stamp, ns, for types with a header: the recording's publish time.
    fn header_stamp_ns(&self) -> Option<i64> {
        None
    }
}

impl InputMessage for ActivationCommand {
    fn header_stamp_ns(&self) -> Option<i64> {
        Some(self.header.stamp.to_nanos())
    }
}

impl InputMessage for ExternalLoad {
    fn header_stamp_ns(&self) -> Option<i64> {
        Some(self.header.stamp.to_nanos())
    }
}

impl InputMessage for JointState {
    fn header_stamp_ns(&self) -> Option<i64> {
        Some(self.header.stamp.to_nanos())
    }
}

impl InputMessage for Float64 {}
impl InputMessage for Float64MultiArray {}
impl InputMessage for Int64 {}
impl InputMessage for Clock {}
