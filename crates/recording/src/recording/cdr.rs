//! CDR as ROS 2 puts it on the wire: a 4-byte encapsulation header, then the XCDR1 body.

use byteorder::LittleEndian;
use serde::{de::DeserializeOwned, Serialize};

/// The encapsulation header of plain CDR (XCDR1), little-endian.
pub const CDR_LE_HEADER: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// Why a message could not be serialized or read back as CDR.
#[derive(Debug, thiserror::Error)]
pub enum CdrError {
    /// The message does not serialize (a sequence of unknown length, say).
    #[error(transparent)]
    Encode(cdr_encoding::Error),
    /// The bytes are too short to hold the encapsulation header.
    #[error("message of {len} bytes has no CDR header")]
    NoHeader {
        /// The message's length, bytes.
        len: usize,
    },
    /// The encapsulation header names neither plain CDR little-endian nor big-endian.
    #[error("unsupported CDR encapsulation {:02x} {:02x}", .header[0], .header[1])]
    UnsupportedEncapsulation {
        /// The header's first two bytes (the representation identifier).
        header: [u8; 2],
    },
    /// The body does not decode as the expected type.
    #[error("bad CDR message: {0}")]
    Decode(#[source] cdr_encoding::Error),
}

/// Serializes a message as ROS 2 does on the wire: encapsulation header + XCDR1 LE body.
pub fn encode_cdr<T: Serialize>(msg: &T) -> Result<Vec<u8>, CdrError> {
    let body = cdr_encoding::to_vec::<T, LittleEndian>(msg).map_err(CdrError::Encode)?;
    let mut out = Vec::with_capacity(body.len() + 4);
    out.extend_from_slice(&CDR_LE_HEADER);
    out.extend_from_slice(&body);
    Ok(out)
}

/// Reads a message written by [`encode_cdr`] (or by any ROS 2 node: CDR LE or BE).
pub fn decode_cdr<T: DeserializeOwned>(data: &[u8]) -> Result<T, CdrError> {
    if data.len() < 4 {
        return Err(CdrError::NoHeader { len: data.len() });
    }
    let body = &data[4..];
    let r = match (data[0], data[1]) {
        (0x00, 0x01) => cdr_encoding::from_bytes::<T, LittleEndian>(body),
        (0x00, 0x00) => cdr_encoding::from_bytes::<T, byteorder::BigEndian>(body),
        (a, b) => return Err(CdrError::UnsupportedEncapsulation { header: [a, b] }),
    };
    r.map(|(v, _)| v).map_err(CdrError::Decode)
}
