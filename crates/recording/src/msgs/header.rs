//! `std_msgs/msg/Header`, the stamp and frame of a message.

use super::Time;
use serde::{Deserialize, Serialize};

/// `std_msgs/msg/Header`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// The time the data refers to, on the node's clock (docs/time.md).
    pub stamp: Time,
    /// The coordinate frame of the data (empty: none).
    pub frame_id: String,
}
ros2_message!(Header);

impl Default for Header {
    fn default() -> Self {
        Self {
            stamp: Time::ZERO,
            frame_id: String::new(),
        }
    }
}
