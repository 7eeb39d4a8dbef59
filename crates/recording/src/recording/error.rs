//! What reading, recording and recovering an MCAP file report: [`RecordingError`] names the file;
//! [`ReadError`], [`Damage`] and [`LengthError`] say what is wrong with its bytes (the reader's),
//! [`RewriteError`] what failed writing a recovered file (`recover`'s).

use std::io;
use std::path::{Path, PathBuf};

/// A length prefix of a record that asks for more than the record holds.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "record 0x{opcode:02x}: a {field} of {declared} bytes where only {remaining} remain in its \
     record"
)]
pub struct LengthError {
    /// The record's opcode.
    pub opcode: u8,
    /// What the prefix measures (`string`, `map`, `string length`, ...).
    pub field: &'static str,
    /// The bytes it asks for.
    pub declared: usize,
    /// The bytes left in the record (or in its enclosing map).
    pub remaining: usize,
}

/// Why the recovered file could not be written.
#[derive(Debug, thiserror::Error)]
pub enum RewriteError {
    /// Creating or flushing the file failed.
    #[error(transparent)]
    Io(#[from] io::Error),
    /// The MCAP writer refused a record or failed to write it.
    #[error(transparent)]
    Mcap(#[from] mcap::McapError),
    /// A message read names a channel the recording read does not hold.
    #[error("message on unknown channel {channel}")]
    UnknownChannel {
        /// The channel id the message names.
        channel: u16,
    },
}

/// Where a file's bytes stop being a readable MCAP recording.
#[derive(Debug, thiserror::Error)]
pub enum Damage {
    /// The `mcap` crate refuses a record (bad CRC, bad opcode, a record cut short, ...).
    #[error(transparent)]
    Mcap(#[from] mcap::McapError),
    /// A record's length prefix asks for more than the record holds.
    #[error(transparent)]
    Length(#[from] LengthError),
    /// The file ends inside a record (the crash cut it).
    #[error("the file ends in a record begun at byte {at}")]
    CutRecord {
        /// Offset of the record's opcode, bytes.
        at: usize,
    },
    /// The file ends at a record boundary but before its footer.
    #[error("the file ends before its footer")]
    NoFooter,
    /// The footer is there but not the closing magic.
    #[error("the file does not end in the MCAP magic")]
    NoEndMagic,
    /// A message names a channel that no channel record before it defines.
    #[error("a message on channel {channel} that no channel record defines")]
    UnknownChannel {
        /// The channel id the message names.
        channel: u16,
    },
}

/// Why the bytes of a recording were refused (the file is named by [`RecordingError`]).
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// A truncated or corrupted file, read strictly.
    #[error("not a complete MCAP file (truncated or corrupted): {0}")]
    Damaged(#[source] Damage),
    /// The messages, decompressed, exceed what a recording may hold in memory.
    #[error(
        "its messages hold more than {limit_mib} MiB (decompressed), more than a recording may \
         hold in memory"
    )]
    TooLarge {
        /// The limit, MiB (`reader::MAX_MESSAGE_BYTES`).
        limit_mib: usize,
    },
}

/// A recording file that could not be read, recorded or recovered, named.
#[derive(Debug, thiserror::Error)]
pub enum RecordingError {
    /// The file could not be read: missing, not a regular file, too large, not permitted.
    #[error("cannot read {}: {source}", path.display())]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// The reason, with its [`io::ErrorKind`] (`NotFound` for a missing file).
        #[source]
        source: io::Error,
    },
    /// The file was read but is not a readable recording (damaged, or too large in memory).
    #[error("{}: {source}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong with its bytes.
        #[source]
        source: ReadError,
    },
    /// A file without its summary (cut by a crash, or not MCAP at all) in which no message is
    /// readable.
    #[error(
        "{}: not a complete MCAP file (truncated or corrupted), and no message in it is \
         readable: {reason}",
        path.display()
    )]
    NothingReadable {
        /// The file.
        path: PathBuf,
        /// Where reading stopped ([`Damage`]'s text, as [`super::Recording::stopped_early`]).
        reason: String,
    },
    /// `recover` was asked to write its output over its input.
    #[error("{}: the output would overwrite the input; give another path", out.display())]
    OverwritesInput {
        /// The output named.
        out: PathBuf,
    },
    /// `recover` found a complete file without any message: nothing to write.
    #[error("{}: no message in it is readable; nothing to recover", input.display())]
    NoMessages {
        /// The input.
        input: PathBuf,
    },
    /// `recover` could not write its output (the temporary beside it).
    #[error("recovering into {}: {source}", out.display())]
    Rewrite {
        /// The output.
        out: PathBuf,
        /// What failed.
        #[source]
        source: RewriteError,
    },
    /// `recover` wrote its output but could not rename it into place.
    #[error("cannot create {}: {source}", out.display())]
    Commit {
        /// The output.
        out: PathBuf,
        /// The rename's error.
        #[source]
        source: io::Error,
    },
    /// The recorder could not create the file or its directory.
    #[error("recording {}: {source}", path.display())]
    Create {
        /// The file (or, for its directory, still the file).
        path: PathBuf,
        /// The reason, with its [`io::ErrorKind`].
        #[source]
        source: io::Error,
    },
    /// The recorder could not write the file's first records (header, schemas, channels,
    /// metadata).
    #[error("recording {}: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The writer's error.
        #[source]
        source: mcap::McapError,
    },
    /// The recorder's thread could not be started.
    #[error("cannot start the recorder thread: {0}")]
    Thread(#[source] io::Error),
}

impl RecordingError {
    /// The [`io::ErrorKind`] of a file that could not be read or created.
    pub fn io_kind(&self) -> Option<io::ErrorKind> {
        match self {
            Self::Unreadable { source, .. } | Self::Create { source, .. } => Some(source.kind()),
            _ => None,
        }
    }

    /// Whether the file read does not exist.
    pub fn is_not_found(&self) -> bool {
        matches!(self, Self::Unreadable { source, .. } if source.kind() == io::ErrorKind::NotFound)
    }

    /// Whether the file was read but is damaged or not MCAP (or holds more than memory allows).
    pub fn is_damaged(&self) -> bool {
        matches!(self, Self::Invalid { .. } | Self::NothingReadable { .. })
    }

    /// The file the error is about (none for the recorder's thread).
    pub fn path(&self) -> Option<&Path> {
        match self {
            Self::Unreadable { path, .. }
            | Self::Invalid { path, .. }
            | Self::NothingReadable { path, .. }
            | Self::Create { path, .. }
            | Self::Write { path, .. } => Some(path),
            Self::OverwritesInput { out }
            | Self::Rewrite { out, .. }
            | Self::Commit { out, .. } => Some(out),
            Self::NoMessages { input } => Some(input),
            Self::Thread(_) => None,
        }
    }

    /// The same error naming `to` where it names `from` (a temporary named as its target).
    pub(crate) fn renamed(mut self, from: &Path, to: &Path) -> Self {
        let path = match &mut self {
            Self::Unreadable { path, .. }
            | Self::Invalid { path, .. }
            | Self::NothingReadable { path, .. }
            | Self::Create { path, .. }
            | Self::Write { path, .. } => path,
            Self::OverwritesInput { out }
            | Self::Rewrite { out, .. }
            | Self::Commit { out, .. } => out,
            Self::NoMessages { input } => input,
            Self::Thread(_) => return self,
        };
        if path == from {
            *path = to.to_path_buf();
        }
        self
    }
}
