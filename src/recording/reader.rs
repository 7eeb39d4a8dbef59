//! Reading a recording back: every message (raw CDR) with its topic and times, and the metadata
//! records.

use mcap::read::Options;
use mcap::records::Record;
use std::collections::BTreeMap;
use std::path::Path;

/// One recorded message.
#[derive(Debug, Clone, PartialEq)]
pub struct RawMessage {
    pub topic: String,
    /// Schema name `pkg/msg/Type` ("" without a schema).
    pub type_name: String,
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

/// Reads `path`. Strict (`recover` false): a truncated or corrupted file is an error naming the
/// file. Recovering: returns everything readable up to the damage (a file cut by a crash holds
/// every chunk flushed before it).
pub fn read_recording(path: &Path, recover: bool) -> Result<Recording, String> {
    let buf = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    read_bytes(&buf, recover).map_err(|e| format!("{}: {e}", path.display()))
}

/// As [`read_recording`], from memory.
pub fn read_bytes(buf: &[u8], recover: bool) -> Result<Recording, String> {
    let bad = |e: &dyn std::fmt::Display| {
        format!("not a complete MCAP file (truncated or corrupted): {e}")
    };
    let mut options: enumset::EnumSet<Options> = Options::ValidateChunkCrcs.into();
    if recover {
        options |= Options::IgnoreEndMagic;
    }
    let mut rec = Recording::default();
    let reader = mcap::read::LinearReader::new_with_options(buf, options).map_err(|e| bad(&e))?;
    for r in reader {
        match r {
            Ok(Record::Header(h)) => rec.profile = h.profile,
            Ok(Record::Metadata(m)) => {
                rec.metadata.insert(m.name, m.metadata);
            }
            Ok(_) => {}
            Err(e) => {
                if recover {
                    rec.stopped_early = Some(e.to_string());
                    break;
                }
                return Err(bad(&e));
            }
        }
    }
    let stream = mcap::MessageStream::new_with_options(buf, options).map_err(|e| bad(&e))?;
    for m in stream {
        match m {
            Ok(m) => rec.messages.push(RawMessage {
                topic: m.channel.topic.clone(),
                type_name: m
                    .channel
                    .schema
                    .as_ref()
                    .map(|s| s.name.clone())
                    .unwrap_or_default(),
                log_time: m.log_time,
                publish_time: m.publish_time,
                data: m.data.into_owned(),
            }),
            Err(e) => {
                if recover {
                    rec.stopped_early.get_or_insert(e.to_string());
                    break;
                }
                return Err(bad(&e));
            }
        }
    }
    Ok(rec)
}
