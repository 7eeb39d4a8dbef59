//! The bytes of a saved state (neutral): a writer of little-endian values and a reader whose
//! every read is checked, against what is left of the bytes and against the size the reader
//! expects, with errors on one line that name the value. `sim::saved` frames these bytes (magic,
//! version, checksum); each part of the state writes and reads its own values (`SavedState`).
//!
//! Values: `u8`; flags as one byte 0 or 1; `u64` and sizes as 8 bytes little-endian; `f64` as its
//! bits (`to_bits`, 8 bytes little-endian: every value comes back bit for bit, −0 and NaNs too);
//! a run of `f64` or a string as its length (8 bytes) then its items.

/// Why saved bytes do not fit the structure read into them: one line that names the value
/// (docs/robustness.md).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum StateError {
    /// Fewer bytes left than the value needs.
    #[error("the bytes end inside {what} (at byte {at} of {len}, {needed} more needed)")]
    Truncated {
        /// The value being read.
        what: String,
        /// Offset of the value's first byte.
        at: usize,
        /// Length of all the bytes.
        len: usize,
        /// Bytes the value needs from `at`.
        needed: usize,
    },
    /// A count of items whose bytes cannot all be there (refused before any allocation).
    #[error("the bytes end inside {what} ({count} items announced, {left} bytes left)")]
    CountTooLarge {
        /// The value being read.
        what: String,
        /// The count of items announced.
        count: usize,
        /// Bytes left for the items.
        left: usize,
    },
    /// A flag byte other than 0 or 1.
    #[error("{what}: {value} is not a flag (0 or 1)")]
    NotAFlag {
        /// The value being read.
        what: String,
        /// The byte read.
        value: u8,
    },
    /// A size or index over the bound the reader set.
    #[error("{what}: {value} is over its bound {max}")]
    OverBound {
        /// The value being read.
        what: String,
        /// The size or index read.
        value: u64,
        /// The largest value allowed.
        max: usize,
    },
    /// A length other than the structure's.
    #[error("{what}: {saved} saved, this structure has {expected}")]
    Length {
        /// The value being read.
        what: String,
        /// The length saved.
        saved: u64,
        /// The structure's length.
        expected: usize,
    },
    /// Text that is not UTF-8.
    #[error("{what} is not UTF-8 text")]
    NotUtf8 {
        /// The value being read.
        what: String,
    },
    /// Bytes after the last value.
    #[error("{0} bytes left over after the state")]
    LeftOver(usize),
    /// A value that reads but does not fit the structure (a repeated row of a permutation, an
    /// unknown kind, a flag the structure cannot have).
    #[error("{0}")]
    Invalid(String),
    /// An error in one part of the state, named (`muscle 1: …`).
    #[error("{part}: {error}")]
    In {
        /// The part of the state (`muscle 1`).
        part: String,
        /// The error inside it.
        error: Box<StateError>,
    },
}

impl StateError {
    /// This error as one inside `part`.
    pub(crate) fn in_part(self, part: impl Into<String>) -> Self {
        StateError::In {
            part: part.into(),
            error: Box::new(self),
        }
    }
}

/// Something whose state is written to saved bytes and read back into a value of the same
/// structure (built anew from the same configuration).
pub(crate) trait SavedState {
    /// Writes the state.
    fn save_state(&self, out: &mut StateWriter);
    /// Reads back what `save_state` wrote; Err, naming the value, for bytes that do not fit
    /// this value's structure (the value may then be partly overwritten: discard it).
    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError>;
}

/// Writes values to a growing byte vector.
#[derive(Debug, Default)]
pub(crate) struct StateWriter {
    bytes: Vec<u8>,
}

impl StateWriter {
    /// An empty writer.
    pub(crate) fn new() -> Self {
        Self::default()
    }
    /// One byte.
    pub(crate) fn u8(&mut self, v: u8) {
        self.bytes.push(v);
    }
    /// A flag, as 0 or 1.
    pub(crate) fn bool(&mut self, v: bool) {
        self.u8(u8::from(v));
    }
    /// 8 bytes, little-endian.
    pub(crate) fn u64(&mut self, v: u64) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    /// A size or an index, as a `u64`.
    pub(crate) fn usize(&mut self, v: usize) {
        self.u64(v as u64);
    }
    /// The bits of `v`.
    pub(crate) fn f64(&mut self, v: f64) {
        self.u64(v.to_bits());
    }
    /// The length, then each value.
    pub(crate) fn f64s(&mut self, v: &[f64]) {
        self.usize(v.len());
        for &x in v {
            self.f64(x);
        }
    }
    /// The length in bytes, then the UTF-8 text.
    pub(crate) fn str(&mut self, s: &str) {
        self.usize(s.len());
        self.bytes.extend_from_slice(s.as_bytes());
    }
    /// Raw bytes, as they are (no length).
    pub(crate) fn raw(&mut self, b: &[u8]) {
        self.bytes.extend_from_slice(b);
    }
    /// What was written.
    pub(crate) fn bytes(&self) -> &[u8] {
        &self.bytes
    }
    /// What was written, taken.
    pub(crate) fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }
}

/// Reads values back, each read checked.
#[derive(Debug)]
pub(crate) struct StateReader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> StateReader<'a> {
    /// A reader at the start of `bytes`.
    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        Self { bytes, at: 0 }
    }

    /// A reader of the same bytes at byte `at` (the tests' way to read one place twice).
    #[cfg(test)]
    fn clone_at(&self, at: usize) -> Self {
        Self {
            bytes: self.bytes,
            at,
        }
    }

    /// Bytes not read yet.
    pub(crate) fn remaining(&self) -> usize {
        self.bytes.len() - self.at
    }

    /// The next `n` bytes.
    pub(crate) fn raw(&mut self, n: usize, what: &str) -> Result<&'a [u8], StateError> {
        if n > self.remaining() {
            return Err(StateError::Truncated {
                what: what.into(),
                at: self.at,
                len: self.bytes.len(),
                needed: n,
            });
        }
        let b = &self.bytes[self.at..self.at + n];
        self.at += n;
        Ok(b)
    }

    /// One byte.
    pub(crate) fn u8(&mut self, what: &str) -> Result<u8, StateError> {
        Ok(self.raw(1, what)?[0])
    }

    /// A flag (0 or 1).
    pub(crate) fn bool(&mut self, what: &str) -> Result<bool, StateError> {
        match self.u8(what)? {
            0 => Ok(false),
            1 => Ok(true),
            value => Err(StateError::NotAFlag {
                what: what.into(),
                value,
            }),
        }
    }

    /// 8 bytes, little-endian.
    pub(crate) fn u64(&mut self, what: &str) -> Result<u64, StateError> {
        let b = self.raw(8, what)?;
        Ok(u64::from_le_bytes(b.try_into().expect("8 bytes")))
    }

    /// A size or an index of at most `max`.
    pub(crate) fn usize(&mut self, what: &str, max: usize) -> Result<usize, StateError> {
        let v = self.u64(what)?;
        match usize::try_from(v) {
            Ok(v) if v <= max => Ok(v),
            _ => Err(StateError::OverBound {
                what: what.into(),
                value: v,
                max,
            }),
        }
    }

    /// A value from its bits.
    pub(crate) fn f64(&mut self, what: &str) -> Result<f64, StateError> {
        Ok(f64::from_bits(self.u64(what)?))
    }

    /// A length that must be `expected` (the size of the structure read into).
    pub(crate) fn expect_len(&mut self, what: &str, expected: usize) -> Result<(), StateError> {
        let n = self.u64(what)?;
        if n != expected as u64 {
            return Err(StateError::Length {
                what: what.into(),
                saved: n,
                expected,
            });
        }
        Ok(())
    }

    /// A run of values into `out`, whose length the saved one must equal.
    pub(crate) fn f64s_into(&mut self, what: &str, out: &mut [f64]) -> Result<(), StateError> {
        self.expect_len(what, out.len())?;
        self.check_room(out.len(), 8, what)?;
        for v in out.iter_mut() {
            *v = self.f64(what)?;
        }
        Ok(())
    }

    /// A run of values of any length up to `max`, appended to `out`.
    pub(crate) fn f64s_extend(
        &mut self,
        what: &str,
        max: usize,
        out: &mut impl Extend<f64>,
    ) -> Result<usize, StateError> {
        let n = self.usize(what, max)?;
        self.check_room(n, 8, what)?;
        for _ in 0..n {
            out.extend([self.f64(what)?]);
        }
        Ok(n)
    }

    /// A string of at most `max` bytes.
    pub(crate) fn str(&mut self, what: &str, max: usize) -> Result<&'a str, StateError> {
        let n = self.usize(what, max)?;
        let b = self.raw(n, what)?;
        std::str::from_utf8(b).map_err(|_| StateError::NotUtf8 { what: what.into() })
    }

    /// A count of items of `item_bytes` bytes each that must fit in what is left (so that a
    /// damaged count is refused before anything is allocated for it).
    pub(crate) fn check_room(
        &self,
        count: usize,
        item_bytes: usize,
        what: &str,
    ) -> Result<(), StateError> {
        match count.checked_mul(item_bytes) {
            Some(n) if n <= self.remaining() => Ok(()),
            _ => Err(StateError::CountTooLarge {
                what: what.into(),
                count,
                left: self.remaining(),
            }),
        }
    }

    /// Err unless every byte was read.
    pub(crate) fn finish(&self) -> Result<(), StateError> {
        match self.remaining() {
            0 => Ok(()),
            n => Err(StateError::LeftOver(n)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each refusal is its own kind, and reads as the one line the command line prints.
    #[test]
    fn refusals_are_typed_and_read_as_one_line() {
        let mut w = StateWriter::new();
        w.u8(2);
        w.u64(5);
        let bytes = w.into_bytes();
        let mut r = StateReader::new(&bytes);
        let e = r.bool("flag").unwrap_err();
        assert_eq!(
            e,
            StateError::NotAFlag {
                what: "flag".into(),
                value: 2
            }
        );
        assert_eq!(e.to_string(), "flag: 2 is not a flag (0 or 1)");
        let e = r.clone_at(1).usize("count", 4).unwrap_err();
        assert!(
            matches!(
                e,
                StateError::OverBound {
                    value: 5,
                    max: 4,
                    ..
                }
            ),
            "{e:?}"
        );
        let e = r
            .clone_at(1)
            .f64s_extend("run", 10, &mut Vec::new())
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "the bytes end inside run (5 items announced, 0 bytes left)"
        );
        let e = r.clone_at(5).u64("tail").unwrap_err().in_part("muscle 1");
        assert_eq!(
            e.to_string(),
            "muscle 1: the bytes end inside tail (at byte 5 of 9, 8 more needed)"
        );
        assert_eq!(r.clone_at(0).finish(), Err(StateError::LeftOver(9)));
    }

    #[test]
    fn values_come_back_bit_for_bit() {
        let mut w = StateWriter::new();
        let odd = [
            -0.0,
            f64::NAN,
            f64::from_bits(0x7ff8_0000_dead_beef),
            1e-310,
            f64::MAX,
        ];
        w.f64s(&odd);
        w.bool(true);
        w.str("huxley");
        w.u64(u64::MAX);
        let bytes = w.into_bytes();
        let mut r = StateReader::new(&bytes);
        let mut back = [0.0; 5];
        r.f64s_into("odd", &mut back).unwrap();
        for (a, b) in odd.iter().zip(&back) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
        assert!(r.bool("flag").unwrap());
        assert_eq!(r.str("name", 64).unwrap(), "huxley");
        assert_eq!(r.u64("big").unwrap(), u64::MAX);
        r.finish().unwrap();
    }

    #[test]
    fn damaged_reads_are_refused_by_name() {
        let mut w = StateWriter::new();
        w.f64s(&[1.0, 2.0]);
        w.u8(7);
        let bytes = w.into_bytes();
        let e = StateReader::new(&bytes)
            .f64s_into("the y", &mut [0.0; 3])
            .unwrap_err()
            .to_string();
        assert!(e.contains("the y") && e.contains("2 saved"), "{e}");
        let e = StateReader::new(&bytes[..12])
            .f64s_into("the y", &mut [0.0; 2])
            .unwrap_err()
            .to_string();
        assert!(e.contains("end inside the y"), "{e}");
        let mut r = StateReader::new(&bytes[16..]);
        let e = r.usize("a count", 1 << 40).unwrap_err().to_string();
        assert!(e.contains("a count"), "{e}");
        let mut r = StateReader::new(&bytes[8..]);
        r.f64("x").unwrap();
        r.f64("y").unwrap();
        let e = r.bool("flag").unwrap_err().to_string();
        assert!(e.contains("not a flag"), "{e}");
        let mut huge = StateWriter::new();
        huge.u64(u64::MAX / 2);
        let e = StateReader::new(huge.bytes())
            .f64s_extend("the grid", usize::MAX, &mut Vec::new())
            .unwrap_err()
            .to_string();
        assert!(e.contains("the grid"), "{e}");
    }
}
