//! Reading a recording back: every message (raw CDR) with its topic and times, and the metadata
//! records.
//!
//! Nothing in the file is trusted. Only a regular file of at most `MAX_RECORDING_BYTES` is
//! read; every record's strings are checked to fit in it before the `mcap` crate parses it
//! (`lengths.rs`); no record, and no chunk once decompressed, may be larger than the file; the
//! messages held may total at most `MAX_MESSAGE_BYTES` (a small file of compressed zeros
//! cannot fill the memory).
//!
//! `read_run_file` is what `replay`, `compare` and `recover` use: a file that ends in the MCAP
//! magic is read strictly (damage is an error), any other (a recording cut by a crash, without
//! its summary) is read record by record up to the cut, under the same checks, and accepted if
//! it holds at least one message.

mod lengths;

use super::error::{Damage, ReadError, RecordingError};
use mcap::read::ChannelAccumulator;
use mcap::records::{Metadata, Record};
use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// The MCAP magic, at both ends of a complete file.
const MAGIC: &[u8; 8] = b"\x89MCAP0\r\n";

/// Largest recording read, bytes (256 MiB: about 20 minutes of a 1 kHz elbow run recorded by
/// `simulate --out` with an excitation changing every tick, 12 MB a minute).
pub(crate) const MAX_RECORDING_BYTES: u64 = 256 << 20;

/// Most message bytes (decompressed) a recording may hold in memory (512 MiB: about 15 minutes
/// of that run, 0.6 kB of messages a tick).
pub(crate) const MAX_MESSAGE_BYTES: usize = 512 << 20;

/// Largest chunk (decompressed) read from a file cut by a crash, bytes, if larger than the file:
/// such a chunk is decompressed whole and checked against its CRC before any of its records is
/// taken, and may well be larger than what is left of the file (the recorder closes chunks at
/// 1 MiB, rosbag2 at a few).
pub(crate) const MAX_RECOVERED_CHUNK_BYTES: usize = 64 << 20;

/// One recorded message.
#[derive(Debug, Clone, PartialEq)]
pub struct RawMessage {
    /// The channel's id in the file read (a key of [`Recording::channels`]).
    pub channel_id: u16,
    /// The message's sequence number as recorded.
    pub sequence: u32,
    /// The channel's topic.
    pub topic: String,
    /// Schema name `pkg/msg/Type` ("" without a schema).
    pub type_name: String,
    /// The channel's message encoding (`cdr` for ROS 2).
    pub encoding: String,
    /// The schema's encoding (`ros2msg` for ROS 2; "" without a schema).
    pub schema_encoding: String,
    /// Log time, ns (in the recording's time base).
    pub log_time: u64,
    /// Publish time, ns (in the recording's time base).
    pub publish_time: u64,
    /// CDR with its encapsulation header.
    pub data: Vec<u8>,
}

/// The content of a recording.
#[derive(Debug, Clone, Default)]
pub struct Recording {
    /// The header's profile (`ros2` for ours).
    pub profile: String,
    /// The header's library.
    pub library: String,
    /// Metadata records by name.
    pub metadata: BTreeMap<String, BTreeMap<String, String>>,
    /// The metadata records in file order, each with the number of messages read before it.
    pub metadata_records: Vec<(usize, Metadata)>,
    /// The channels (with their schemas and metadata) by id, as the file defines them.
    pub channels: BTreeMap<u16, Arc<mcap::Channel<'static>>>,
    /// Messages in file order.
    pub messages: Vec<RawMessage>,
    /// In recovery mode: why reading stopped early (a truncated file), if it did.
    pub stopped_early: Option<String>,
}

impl Recording {
    /// The messages on `topic`.
    pub fn on<'a>(&'a self, topic: &'a str) -> impl Iterator<Item = &'a RawMessage> + 'a {
        self.messages.iter().filter(move |m| m.topic == topic)
    }

    /// For a recording read up to a cut ([`Recording::stopped_early`]): the warning naming what
    /// was recovered, one line.
    pub(crate) fn truncation_warning(&self, path: &Path) -> Option<String> {
        self.stopped_early.as_ref()?;
        let (t0, t1) = self.log_time_range_s().unwrap_or_default();
        Some(format!(
            "{} is truncated (no summary): read {} messages from {t0:.3} to {t1:.3} s; the rest \
             is lost",
            path.display(),
            self.messages.len()
        ))
    }

    /// The first and last log times of the messages, s.
    pub(crate) fn log_time_range_s(&self) -> Option<(f64, f64)> {
        let times = self.messages.iter().map(|m| m.log_time);
        Some((
            times.clone().min()? as f64 * 1e-9,
            times.max()? as f64 * 1e-9,
        ))
    }
}

/// Reads a run file as `replay`, `compare` and `recover` do: strictly if it ends in the MCAP
/// magic (a complete file, whose damage is an error); otherwise (a file cut by a crash) every
/// message up to the cut, with [`Recording::stopped_early`] set. A cut file with no message is
/// an error.
pub(crate) fn read_run_file(path: &Path) -> Result<Recording, RecordingError> {
    let buf = read_file(path)?;
    let complete = buf.ends_with(MAGIC) && buf.len() >= 2 * MAGIC.len();
    let rec = read_bytes(&buf, !complete).map_err(|source| RecordingError::Invalid {
        path: path.to_path_buf(),
        source,
    })?;
    match rec.stopped_early {
        Some(reason) if rec.messages.is_empty() => Err(RecordingError::NothingReadable {
            path: path.to_path_buf(),
            reason,
        }),
        _ => Ok(rec),
    }
}

/// The bytes of `path`, a regular file of at most [`MAX_RECORDING_BYTES`].
fn read_file(path: &Path) -> Result<Vec<u8>, RecordingError> {
    muscle_actuator_core::files::read_regular_file(path, MAX_RECORDING_BYTES).map_err(|source| {
        RecordingError::Unreadable {
            path: path.to_path_buf(),
            source,
        }
    })
}

/// Reads `path`. Strict (`recover` false): a truncated or corrupted file is an error naming the
/// file. Recovering: returns everything readable up to the damage (a file cut by a crash holds
/// every chunk flushed before it).
pub fn read_recording(path: &Path, recover: bool) -> Result<Recording, RecordingError> {
    let buf = read_file(path)?;
    read_bytes(&buf, recover).map_err(|source| RecordingError::Invalid {
        path: path.to_path_buf(),
        source,
    })
}

/// As [`read_recording`], from memory.
pub(crate) fn read_bytes(buf: &[u8], recover: bool) -> Result<Recording, ReadError> {
    let mut rec = Recording::default();
    match read_into(buf, recover, &mut rec) {
        Ok(()) => Ok(rec),
        Err(ReadError::Damaged(e)) if recover => {
            rec.stopped_early = Some(e.to_string());
            Ok(rec)
        }
        Err(e) => Err(e),
    }
}

/// Damage stops reading (in recovery mode: where what is readable ends).
fn damaged(e: impl Into<Damage>) -> ReadError {
    ReadError::Damaged(e.into())
}

/// Reads the records of `buf` in file order (chunks decompressed, CRCs checked) into `rec`.
fn read_into(buf: &[u8], recover: bool, rec: &mut Recording) -> Result<(), ReadError> {
    // Recovering: only whole records (a chunk cut by a crash is not read in part), and each
    // chunk checked against its CRC before any of its records is taken.
    let (buf, cut) = if recover {
        whole_records(buf)
    } else {
        (buf, None)
    };
    let options = LinearReaderOptions::default()
        .with_skip_end_magic(recover)
        .with_validate_chunk_crcs(true)
        .with_prevalidate_chunk_crcs(recover)
        .with_record_length_limit(if recover {
            buf.len().max(MAX_RECOVERED_CHUNK_BYTES)
        } else {
            buf.len()
        });
    let mut reader = LinearReader::new_with_options(options);
    let mut channels = ChannelAccumulator::default();
    let mut rest = buf;
    let mut held = 0usize;
    let mut footer = false;
    while let Some(event) = reader.next_event() {
        match event.map_err(damaged)? {
            LinearReadEvent::ReadRequest(need) => {
                let n = need.min(rest.len());
                reader.insert(n).copy_from_slice(&rest[..n]);
                reader.notify_read(n);
                rest = &rest[n..];
            }
            LinearReadEvent::Record { opcode, data } => {
                lengths::check(opcode, data).map_err(damaged)?;
                let record = mcap::parse_record(opcode, data).map_err(damaged)?;
                footer |= matches!(record, Record::Footer(_));
                take(record, &mut channels, rec, &mut held)?;
            }
        }
    }
    match cut {
        Some(at) => Err(damaged(Damage::CutRecord { at })),
        None if !footer => Err(damaged(Damage::NoFooter)),
        None if recover => Err(damaged(Damage::NoEndMagic)),
        None => Ok(()),
    }
}

/// The longest prefix of `buf` made of the magic and whole top-level records, and where the
/// record cut short begins (`None`: `buf` ends at a record boundary).
fn whole_records(buf: &[u8]) -> (&[u8], Option<usize>) {
    if buf.len() < MAGIC.len() {
        return (buf, None);
    }
    let mut at = MAGIC.len();
    while at < buf.len() {
        let Some(len) = buf
            .get(at + 1..at + 9)
            .map(|b| u64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
        else {
            return (&buf[..at], Some(at));
        };
        match usize::try_from(len)
            .ok()
            .and_then(|n| n.checked_add(at + 9))
        {
            Some(end) if end <= buf.len() => at = end,
            // The end magic, or a record longer than what remains.
            _ if buf[at..] == MAGIC[..] => return (buf, None),
            _ => return (&buf[..at], Some(at)),
        }
    }
    (buf, None)
}

/// Keeps what a record brings: the profile, a metadata record, a schema or channel (linked as
/// the `mcap` crate's message stream links them), a message.
fn take(
    record: Record<'_>,
    channels: &mut ChannelAccumulator<'static>,
    rec: &mut Recording,
    held: &mut usize,
) -> Result<(), ReadError> {
    match record {
        Record::Header(h) => {
            rec.profile = h.profile;
            rec.library = h.library;
        }
        Record::Metadata(m) => {
            rec.metadata.insert(m.name.clone(), m.metadata.clone());
            rec.metadata_records.push((rec.messages.len(), m));
        }
        Record::Schema { header, data } => channels
            .add_schema(header, Cow::Owned(data.into_owned()))
            .map_err(damaged)?,
        Record::Channel(c) => {
            let id = c.id;
            channels.add_channel(c).map_err(damaged)?;
            if let Some(ch) = channels.get(id) {
                rec.channels.entry(id).or_insert(ch);
            }
        }
        Record::Message { header, data } => {
            let ch = channels.get(header.channel_id).ok_or_else(|| {
                damaged(Damage::UnknownChannel {
                    channel: header.channel_id,
                })
            })?;
            *held = held.saturating_add(data.len());
            if *held > MAX_MESSAGE_BYTES {
                return Err(ReadError::TooLarge {
                    limit_mib: MAX_MESSAGE_BYTES >> 20,
                });
            }
            let schema = ch.schema.as_ref();
            rec.messages.push(RawMessage {
                channel_id: header.channel_id,
                sequence: header.sequence,
                topic: ch.topic.clone(),
                type_name: schema.map(|s| s.name.clone()).unwrap_or_default(),
                encoding: ch.message_encoding.clone(),
                schema_encoding: schema.map(|s| s.encoding.clone()).unwrap_or_default(),
                log_time: header.log_time,
                publish_time: header.publish_time,
                data: data.into_owned(),
            });
        }
        _ => {}
    }
    Ok(())
}
