//! The length-prefixed strings of an MCAP record checked against the record, before the `mcap`
//! crate parses it: its parser (binrw, `McapString`) allocates a string's declared length before
//! reading it, so a single corrupt prefix asks for up to 4 GiB. Written out here because the
//! crate offers no bounded parse; the layouts are those of the MCAP specification
//! (<https://mcap.dev/spec>), for every record whose parser reads a string. Chunk headers are
//! bounded by the crate's own reader (against the record's length) and need no check here.

use crate::recording::error::LengthError;
use mcap::records::op;

/// The unread rest of a record's body, and the record's opcode (named in errors).
struct Body<'a> {
    rest: &'a [u8],
    opcode: u8,
}

impl<'a> Body<'a> {
    fn take(&mut self, n: usize, field: &'static str) -> Result<&'a [u8], LengthError> {
        if n > self.rest.len() {
            return Err(LengthError {
                opcode: self.opcode,
                field,
                declared: n,
                remaining: self.rest.len(),
            });
        }
        let (head, rest) = self.rest.split_at(n);
        self.rest = rest;
        Ok(head)
    }

    fn u32(&mut self, field: &'static str) -> Result<usize, LengthError> {
        let b = self.take(4, field)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    }

    fn skip(&mut self, n: usize) -> Result<(), LengthError> {
        self.take(n, "field").map(|_| ())
    }

    fn string(&mut self) -> Result<(), LengthError> {
        let n = self.u32("string length")?;
        self.take(n, "string").map(|_| ())
    }

    /// A map of strings to strings: its length in bytes, then key and value strings.
    fn string_map(&mut self) -> Result<(), LengthError> {
        let n = self.u32("map length")?;
        let mut map = Body {
            rest: self.take(n, "map")?,
            opcode: self.opcode,
        };
        while !map.rest.is_empty() {
            map.string()?;
            map.string()?;
        }
        Ok(())
    }

    /// A map or array of fixed-size entries: only its length in bytes needs to fit.
    fn block(&mut self) -> Result<(), LengthError> {
        let n = self.u32("map length")?;
        self.take(n, "map").map(|_| ())
    }
}

/// Whether every string, map and block that record `opcode`'s parser reads fits in `body`.
pub(crate) fn check(opcode: u8, body: &[u8]) -> Result<(), LengthError> {
    let mut b = Body { rest: body, opcode };
    match opcode {
        // profile, library
        op::HEADER => b.string().and_then(|_| b.string()),
        // id u16, name, encoding (the data's own length the crate checks)
        op::SCHEMA => b.skip(2).and_then(|_| b.string()).and_then(|_| b.string()),
        // id u16, schema id u16, topic, message encoding, metadata
        op::CHANNEL => b
            .skip(4)
            .and_then(|_| b.string())
            .and_then(|_| b.string())
            .and_then(|_| b.string_map()),
        // times, chunk offset and length (4 × u64), message index offsets, message index
        // length u64, compression
        op::CHUNK_INDEX => b
            .skip(32)
            .and_then(|_| b.block())
            .and_then(|_| b.skip(8))
            .and_then(|_| b.string()),
        // log and create times (2 × u64), name, media type
        op::ATTACHMENT => b.skip(16).and_then(|_| b.string()).and_then(|_| b.string()),
        // offset, length, log and create times, data size (5 × u64), name, media type
        op::ATTACHMENT_INDEX => b.skip(40).and_then(|_| b.string()).and_then(|_| b.string()),
        // name, metadata
        op::METADATA => b.string().and_then(|_| b.string_map()),
        // offset, length (2 × u64), name
        op::METADATA_INDEX => b.skip(16).and_then(|_| b.string()),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings_must_fit_their_record() {
        let mut md = Vec::new();
        md.extend(4u32.to_le_bytes());
        md.extend(b"name");
        md.extend(12u32.to_le_bytes());
        md.extend(1u32.to_le_bytes());
        md.extend(b"k");
        md.extend(3u32.to_le_bytes());
        md.extend(b"val");
        assert_eq!(check(op::METADATA, &md), Ok(()));
        let mut huge = md.clone();
        huge[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        let e = check(op::METADATA, &huge).unwrap_err();
        assert_eq!(
            (e.field, e.declared, e.remaining),
            ("string", u32::MAX as usize, 8)
        );
        assert!(e.to_string().contains("4294967295"), "{e}");
        assert!(check(op::METADATA, &md[..md.len() - 1]).is_err());
        assert!(check(op::HEADER, &[0xff, 0xff, 0xff, 0xff]).is_err());
        assert_eq!(check(op::MESSAGE, &[1, 2, 3]), Ok(()));
    }
}
