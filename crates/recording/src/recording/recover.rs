//! `recover IN OUT`: rewrites a recording cut by a crash (no summary, no index) as a complete,
//! indexed MCAP file: the same header (profile and library), the schemas and channels (with
//! their metadata), the metadata records written, and every readable message, each with its
//! sequence number, times and bytes unchanged, in file order.
//!
//! The input is read as `replay` and `compare` read it (`reader::read_run_file`), under every
//! check of the reader; a file with no readable message is refused. The output is written beside
//! `OUT` under a temporary name and renamed into place once complete
//! ([`muscle_actuator_core::files::AtomicFile`]), so a failure leaves no partial file; `OUT` may
//! not be `IN`.

use super::error::{RecordingError, RewriteError};
use super::reader::{read_run_file, Recording};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

/// What `recover` wrote.
#[derive(Debug, Clone)]
pub struct Recovered {
    /// Messages written.
    pub messages: usize,
    /// Channels written.
    pub channels: usize,
    /// Metadata records written.
    pub metadata_records: usize,
    /// First and last log times of the messages, s.
    pub(crate) range_s: (f64, f64),
    /// Why reading stopped early (`None`: the input was complete).
    pub stopped_early: Option<String>,
}

impl Recovered {
    /// One line for the command line.
    pub fn line(&self, input: &Path, out: &Path) -> String {
        let (t0, t1) = self.range_s;
        let how = match &self.stopped_early {
            Some(_) => "truncated",
            None => "complete",
        };
        format!(
            "recovered {} messages on {} channels from {t0:.3} to {t1:.3} s and {} metadata \
             records of {} ({how}) into {}",
            self.messages,
            self.channels,
            self.metadata_records,
            input.display(),
            out.display()
        )
    }
}

/// Reads `input` (complete, or cut by a crash) and writes everything readable to `out` as a
/// complete MCAP file.
pub fn recover(input: &Path, out: &Path) -> Result<Recovered, RecordingError> {
    if muscle_actuator_core::files::same_file(input, out) {
        return Err(RecordingError::OverwritesInput {
            out: out.to_path_buf(),
        });
    }
    let rec = read_run_file(input)?;
    if rec.messages.is_empty() {
        return Err(RecordingError::NoMessages {
            input: input.to_path_buf(),
        });
    }
    let into = |e: RewriteError| RecordingError::Rewrite {
        out: out.to_path_buf(),
        source: e,
    };
    let mut file = muscle_actuator_core::files::AtomicFile::create(out)
        .map_err(|e| into(RewriteError::Io(e)))?;
    write(&rec, file.file()).map_err(into)?;
    file.commit().map_err(|source| RecordingError::Commit {
        out: out.to_path_buf(),
        source,
    })?;
    Ok(Recovered {
        messages: rec.messages.len(),
        channels: rec.channels.len(),
        metadata_records: rec.metadata_records.len(),
        range_s: rec.log_time_range_s().unwrap_or_default(),
        stopped_early: rec.stopped_early,
    })
}

/// Writes `rec` into `file` as the recorder does (zstd chunks, indexed summary).
fn write(rec: &Recording, file: &mut File) -> Result<(), RewriteError> {
    let options = super::writer::RecorderOptions::default();
    let mut w = mcap::WriteOptions::new()
        .profile(rec.profile.clone())
        .library(rec.library.clone())
        .compression(Some(mcap::Compression::Zstd))
        .compression_level(options.compression_level)
        .chunk_size(Some(options.chunk_size))
        .create(BufWriter::with_capacity(1 << 16, file))?;
    // Schemas and channels keep their ids (the message records are then the same).
    let mut ids: BTreeMap<u16, u16> = BTreeMap::new();
    for (&old, ch) in &rec.channels {
        let schema_id = match &ch.schema {
            Some(s) => w.add_schema_with_id(s.id, &s.name, &s.encoding, &s.data)?,
            None => 0,
        };
        let id = w.add_channel_with_id(
            old,
            schema_id,
            &ch.topic,
            &ch.message_encoding,
            &ch.metadata,
        )?;
        ids.insert(old, id);
    }
    let mut metadata = rec.metadata_records.iter().peekable();
    for (i, m) in rec.messages.iter().enumerate() {
        while let Some((_, md)) = metadata.next_if(|(before, _)| *before <= i) {
            w.write_metadata(md)?;
        }
        let channel_id = *ids.get(&m.channel_id).ok_or(RewriteError::UnknownChannel {
            channel: m.channel_id,
        })?;
        w.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id,
                sequence: m.sequence,
                log_time: m.log_time,
                publish_time: m.publish_time,
            },
            &m.data,
        )?;
    }
    for (_, md) in metadata {
        w.write_metadata(md)?;
    }
    w.finish()?;
    w.into_inner().into_inner().map_err(|e| e.into_error())?;
    Ok(())
}
