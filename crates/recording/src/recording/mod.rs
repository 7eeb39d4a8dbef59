//! Recordings: rosbag2-compatible MCAP files (docs/recordings.md).
//!
//! This module knows ROS 2 message encodings and the MCAP container, nothing of the physics:
//! - [`schema`]: `ros2msg` schema texts with their dependencies appended;
//! - [`writer`]: the recorder thread (bounded channel, drops counted, chunks flushed on time);
//! - [`reader`]: reading a recording back (strictly, or recovering what a truncated file holds);
//! - [`rosbag2`]: rosbag2's YAML in a file (the QoS profiles, the bag's metadata);
//! - [`recover`]: rewriting a file cut by a crash as a complete, indexed one;
//! - [`encode_cdr`] / [`decode_cdr`]: CDR with its 4-byte encapsulation header.

pub mod reader;
pub mod recover;
pub mod rosbag2;
pub mod schema;
pub mod writer;

pub use reader::{read_recording, RawMessage, Recording};
pub use rosbag2::qos_yaml;
pub use writer::{ChannelSpec, RecordSender, Recorder, RecorderOptions, RecorderState};

use byteorder::LittleEndian;
use serde::{de::DeserializeOwned, Serialize};

/// The encapsulation header of plain CDR (XCDR1), little-endian.
pub const CDR_LE_HEADER: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// Serializes a message as ROS 2 does on the wire: encapsulation header + XCDR1 LE body.
pub fn encode_cdr<T: Serialize>(msg: &T) -> Result<Vec<u8>, String> {
    let body = cdr_encoding::to_vec::<T, LittleEndian>(msg).map_err(|e| e.to_string())?;
    let mut out = Vec::with_capacity(body.len() + 4);
    out.extend_from_slice(&CDR_LE_HEADER);
    out.extend_from_slice(&body);
    Ok(out)
}

/// Reads a message written by [`encode_cdr`] (or by any ROS 2 node: CDR LE or BE).
pub fn decode_cdr<T: DeserializeOwned>(data: &[u8]) -> Result<T, String> {
    if data.len() < 4 {
        return Err(format!("message of {} bytes has no CDR header", data.len()));
    }
    let body = &data[4..];
    let r = match (data[0], data[1]) {
        (0x00, 0x01) => cdr_encoding::from_bytes::<T, LittleEndian>(body),
        (0x00, 0x00) => cdr_encoding::from_bytes::<T, byteorder::BigEndian>(body),
        (a, b) => return Err(format!("unsupported CDR encapsulation {a:02x} {b:02x}")),
    };
    r.map(|(v, _)| v)
        .map_err(|e| format!("bad CDR message: {e}"))
}
