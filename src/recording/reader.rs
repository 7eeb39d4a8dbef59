//! Reading a recording back: every message (raw CDR) with its topic and times, and the metadata
//! records.
//!
//! Nothing in the file is trusted. Only a regular file of at most [`MAX_RECORDING_BYTES`] is
//! read; every record's strings are checked to fit in it before the `mcap` crate parses it
//! ([`lengths`]); no record, and no chunk once decompressed, may be larger than the file; the
//! messages held may total at most [`MAX_MESSAGE_BYTES`] (a small file of compressed zeros
//! cannot fill the memory).

mod lengths;

use mcap::read::ChannelAccumulator;
use mcap::records::Record;
use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::path::Path;

/// Largest recording read, bytes (256 MiB: about 20 minutes of a 1 kHz elbow run recorded by
/// `simulate --out` with an excitation changing every tick, 12 MB a minute).
pub const MAX_RECORDING_BYTES: u64 = 256 << 20;

/// Most message bytes (decompressed) a recording may hold in memory (512 MiB: about 15 minutes
/// of that run, 0.6 kB of messages a tick).
pub const MAX_MESSAGE_BYTES: usize = 512 << 20;

/// One recorded message.
#[derive(Debug, Clone, PartialEq)]
pub struct RawMessage {
    pub topic: String,
    /// Schema name `pkg/msg/Type` ("" without a schema).
    pub type_name: String,
    /// The channel's message encoding (`cdr` for ROS 2).
    pub encoding: String,
    /// The schema's encoding (`ros2msg` for ROS 2; "" without a schema).
    pub schema_encoding: String,
    pub log_time: u64,
    pub publish_time: u64,
    /// CDR with its encapsulation header.
    pub data: Vec<u8>,
}

/// The content of a recording.
#[derive(Debug, Clone, Default)]
pub struct Recording {
    /// The header's profile (`ros2` for ours).
    pub profile: String,
    /// Metadata records by name.
    pub metadata: BTreeMap<String, BTreeMap<String, String>>,
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
}

/// Why reading stopped.
enum Stop {
    /// The file is damaged here (in recovery mode: the end of what is readable).
    Damaged(String),
    /// The file asks for more than a recording may hold.
    TooLarge(String),
}

/// Reads `path`. Strict (`recover` false): a truncated or corrupted file is an error naming the
/// file. Recovering: returns everything readable up to the damage (a file cut by a crash holds
/// every chunk flushed before it).
pub fn read_recording(path: &Path, recover: bool) -> Result<Recording, String> {
    let buf = crate::config::read_regular_file(path, MAX_RECORDING_BYTES)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    read_bytes(&buf, recover).map_err(|e| format!("{}: {e}", path.display()))
}

/// As [`read_recording`], from memory.
pub fn read_bytes(buf: &[u8], recover: bool) -> Result<Recording, String> {
    let mut rec = Recording::default();
    match read_into(buf, recover, &mut rec) {
        Ok(()) => Ok(rec),
        Err(Stop::Damaged(e)) if recover => {
            rec.stopped_early = Some(e);
            Ok(rec)
        }
        Err(Stop::Damaged(e)) => Err(format!(
            "not a complete MCAP file (truncated or corrupted): {e}"
        )),
        Err(Stop::TooLarge(e)) => Err(e),
    }
}

fn damaged(e: impl std::fmt::Display) -> Stop {
    Stop::Damaged(e.to_string())
}

/// Reads the records of `buf` in file order (chunks decompressed, CRCs checked) into `rec`.
fn read_into(buf: &[u8], recover: bool, rec: &mut Recording) -> Result<(), Stop> {
    let options = LinearReaderOptions::default()
        .with_skip_end_magic(recover)
        .with_validate_chunk_crcs(true)
        .with_record_length_limit(buf.len());
    let mut reader = LinearReader::new_with_options(options);
    let mut channels = ChannelAccumulator::default();
    let mut rest = buf;
    let mut held = 0usize;
    while let Some(event) = reader.next_event() {
        match event.map_err(damaged)? {
            LinearReadEvent::ReadRequest(need) => {
                let n = need.min(rest.len());
                reader.insert(n).copy_from_slice(&rest[..n]);
                reader.notify_read(n);
                rest = &rest[n..];
            }
            LinearReadEvent::Record { opcode, data } => {
                lengths::check(opcode, data).map_err(Stop::Damaged)?;
                let record = mcap::parse_record(opcode, data).map_err(damaged)?;
                take(record, &mut channels, rec, &mut held)?;
            }
        }
    }
    Ok(())
}

/// Keeps what a record brings: the profile, a metadata record, a schema or channel (linked as
/// the `mcap` crate's message stream links them), a message.
fn take(
    record: Record<'_>,
    channels: &mut ChannelAccumulator<'static>,
    rec: &mut Recording,
    held: &mut usize,
) -> Result<(), Stop> {
    match record {
        Record::Header(h) => rec.profile = h.profile,
        Record::Metadata(m) => {
            rec.metadata.insert(m.name, m.metadata);
        }
        Record::Schema { header, data } => channels
            .add_schema(header, Cow::Owned(data.into_owned()))
            .map_err(damaged)?,
        Record::Channel(c) => channels.add_channel(c).map_err(damaged)?,
        Record::Message { header, data } => {
            let ch = channels.get(header.channel_id).ok_or_else(|| {
                damaged(format!(
                    "a message on channel {} that no channel record defines",
                    header.channel_id
                ))
            })?;
            *held = held.saturating_add(data.len());
            if *held > MAX_MESSAGE_BYTES {
                return Err(Stop::TooLarge(format!(
                    "its messages hold more than {} MiB (decompressed), more than a recording \
                     may hold in memory",
                    MAX_MESSAGE_BYTES >> 20
                )));
            }
            let schema = ch.schema.as_ref();
            rec.messages.push(RawMessage {
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
