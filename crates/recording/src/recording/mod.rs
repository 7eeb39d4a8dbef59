//! Recordings: rosbag2-compatible MCAP files (docs/recordings.md).
//!
//! This module knows ROS 2 message encodings and the MCAP container, nothing of the physics:
//! - [`schema`]: `ros2msg` schema texts with their dependencies appended;
//! - [`writer`]: the recorder thread (bounded channel, drops counted, chunks flushed on time);
//! - `reader`: reading a recording back (strictly, or recovering what a truncated file holds);
//! - [`rosbag2`]: rosbag2's YAML in a file (the QoS profiles, the bag's metadata);
//! - [`recover`]: rewriting a file cut by a crash as a complete, indexed one;
//! - `cdr`: [`encode_cdr`] / [`decode_cdr`], CDR with its 4-byte encapsulation header;
//! - `error`: what reading, recording and recovering a file report.

pub(crate) mod cdr;
pub(crate) mod error;
pub(crate) mod reader;
pub mod recover;
pub mod rosbag2;
pub mod schema;
pub mod writer;

pub use cdr::{decode_cdr, encode_cdr, CdrError, CDR_LE_HEADER};
pub use error::{Damage, LengthError, ReadError, RecordingError, RewriteError};
pub use reader::{read_recording, RawMessage, Recording};
pub use rosbag2::qos_yaml;
pub use writer::{ChannelSpec, RecordSender, Recorder, RecorderOptions, RecorderState};
