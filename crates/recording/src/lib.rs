//! muscle_actuator_recording: runs as rosbag2-compatible MCAP recordings, with no DDS in it.
//! The node records through it, and the offline commands and the Python package read and
//! write through it.
//!
//! - [`msgs`]: the ROS 2 message types and a tick's state as messages, their type hashes (with
//!   the `ros2` feature they are also `ros2_client` messages, for the node).
//! - [`recording`]: MCAP: writer thread, schemas, CDR, reader, recover (knows nothing of physics).
//! - [`runs`]: runs as recordings: channels, metadata, `simulate --out`, loading, replay,
//!   compare, export, limits.

#![warn(missing_docs)]
#![warn(unreachable_pub)]

pub mod msgs;
pub mod recording;
pub mod runs;
