//! The MCAP recorder: a thread that owns the file; producers hand it serialized messages through
//! a bounded channel and never wait (a full channel drops the message and counts it).
//!
//! The file is rosbag2-compatible: profile `ros2`, one `ros2msg` schema per type, `cdr` channels
//! with `offered_qos_profiles` (and `topic_type_hash` when given), a `rosbag2` metadata record at
//! the end and the caller's metadata records at the start. Chunks are zstd-compressed and closed
//! at least every `flush_interval`, so a crash loses at most that much.
//!
//! A write error (full disk, file gone) stops the recording: the thread records the reason in
//! [`RecorderStats`] and exits; producers see their messages counted as dropped, nothing more.

use super::error::RecordingError;
use super::rosbag2::{metadata_yaml, Topic, ROS_DISTRO};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError, SyncSender, TrySendError};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// One channel (topic) of a recording.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelSpec {
    /// Topic name, e.g. `/joint_states`.
    pub topic: String,
    /// Type name `pkg/msg/Type`.
    pub type_name: String,
    /// The `ros2msg` schema text (see [`super::schema::ros2msg_schema`]).
    pub schema: String,
    /// `offered_qos_profiles` (rosbag2 YAML).
    pub(crate) qos_yaml: String,
    /// REP-2016 type hash (`RIHS01_...`), when known.
    pub type_hash: Option<String>,
}

/// Options of a recorder.
#[derive(Debug, Clone)]
pub struct RecorderOptions {
    /// Messages the channel holds before producers start dropping.
    pub capacity: usize,
    /// Message bytes the channel holds before producers start dropping (a flood of large
    /// messages must not pile up in memory while the disk catches up).
    pub(crate) capacity_bytes: usize,
    /// Longest time a written message may stay in an open (unreadable) chunk.
    pub(crate) flush_interval: Duration,
    /// Chunk size target, bytes.
    pub(crate) chunk_size: u64,
    /// zstd level.
    pub(crate) compression_level: u32,
}

impl Default for RecorderOptions {
    fn default() -> Self {
        Self {
            capacity: 8192,
            capacity_bytes: 32 << 20,
            flush_interval: Duration::from_millis(500),
            chunk_size: 1 << 20,
            compression_level: 3,
        }
    }
}

/// Where the recording stands.
#[derive(Debug, Clone, PartialEq)]
pub enum RecorderState {
    /// Writing.
    Recording,
    /// Finished cleanly.
    Finished,
    /// Stopped by an error (the file holds what was flushed before it).
    Failed(String),
}

/// Counters shared between the recorder thread and its handle.
#[derive(Debug)]
pub struct RecorderStats {
    /// The file recorded to.
    pub path: PathBuf,
    /// Messages handed to the writer.
    pub written: AtomicU64,
    /// Messages dropped: channel full, or the recording had stopped.
    pub dropped: AtomicU64,
    /// Serialized message bytes written (before compression).
    pub message_bytes: AtomicU64,
    /// Message bytes handed over but not yet written.
    queued_bytes: AtomicUsize,
    capacity_bytes: usize,
    state: Mutex<RecorderState>,
}

impl RecorderStats {
    /// Where the recording stands now.
    pub fn state(&self) -> RecorderState {
        self.state
            .lock()
            .map(|s| s.clone())
            .unwrap_or(RecorderState::Failed(
                "internal error: lock poisoned".into(),
            ))
    }
    fn set_state(&self, s: RecorderState) {
        if let Ok(mut g) = self.state.lock() {
            *g = s;
        }
    }
}

enum Item {
    Message {
        channel: usize,
        log_time: u64,
        publish_time: u64,
        data: Vec<u8>,
    },
    /// A metadata record learnt while recording (a reader keeps the last one of a name).
    Metadata(mcap::records::Metadata),
    Finish,
}

/// Handle of a running recorder. Dropping it finishes the file (as [`Recorder::finish`]).
pub struct Recorder {
    tx: Option<SyncSender<Item>>,
    stats: Arc<RecorderStats>,
    thread: Option<JoinHandle<()>>,
}

type McapWriter = mcap::Writer<BufWriter<File>>;

/// Creates the file (and its directory) with its channels and `metadata` records written and
/// flushed: the MCAP writer and the channel ids, in the order of `channels`.
fn open_writer(
    path: &Path,
    channels: &[ChannelSpec],
    metadata: &[(String, BTreeMap<String, String>)],
    options: &RecorderOptions,
) -> Result<(McapWriter, Vec<u16>), RecordingError> {
    let create = |source| RecordingError::Create {
        path: path.to_path_buf(),
        source,
    };
    let what = |source| RecordingError::Write {
        path: path.to_path_buf(),
        source,
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(create)?;
    }
    let file = File::create(path).map_err(create)?;
    let mut writer = mcap::WriteOptions::new()
        .profile("ros2")
        .library(format!("muscle_actuator {}", env!("CARGO_PKG_VERSION")))
        .compression(Some(mcap::Compression::Zstd))
        .compression_level(options.compression_level)
        .chunk_size(Some(options.chunk_size))
        .create(BufWriter::with_capacity(1 << 16, file))
        .map_err(what)?;
    let mut ids = Vec::with_capacity(channels.len());
    for c in channels {
        let schema_id = writer
            .add_schema(&c.type_name, "ros2msg", c.schema.as_bytes())
            .map_err(what)?;
        let mut meta = BTreeMap::new();
        meta.insert("offered_qos_profiles".to_string(), c.qos_yaml.clone());
        if let Some(h) = &c.type_hash {
            meta.insert("topic_type_hash".to_string(), h.clone());
        }
        let id = writer
            .add_channel(schema_id, &c.topic, "cdr", &meta)
            .map_err(what)?;
        ids.push(id);
    }
    for (name, map) in metadata {
        writer
            .write_metadata(&mcap::records::Metadata {
                name: name.clone(),
                metadata: map.clone(),
            })
            .map_err(what)?;
    }
    writer.flush().map_err(what)?;
    Ok((writer, ids))
}

impl Recorder {
    /// Creates the file (and its directory) and starts the writer thread. `metadata` records are
    /// written first (so that a crash keeps them). Errors (cannot create, cannot write) come back
    /// as one line naming the path.
    pub fn start(
        path: &Path,
        channels: Vec<ChannelSpec>,
        metadata: Vec<(String, BTreeMap<String, String>)>,
        options: RecorderOptions,
    ) -> Result<Recorder, RecordingError> {
        let (writer, ids) = open_writer(path, &channels, &metadata, &options)?;
        let stats = Arc::new(RecorderStats {
            path: path.to_path_buf(),
            written: AtomicU64::new(0),
            dropped: AtomicU64::new(0),
            message_bytes: AtomicU64::new(0),
            queued_bytes: AtomicUsize::new(0),
            capacity_bytes: options.capacity_bytes.max(1),
            state: Mutex::new(RecorderState::Recording),
        });
        let (tx, rx) = mpsc::sync_channel::<Item>(options.capacity.max(1));
        let st = stats.clone();
        let thread = std::thread::Builder::new()
            .name("recorder".into())
            .spawn(move || {
                let counts = vec![0; channels.len()];
                Worker {
                    writer: Some(writer),
                    ids,
                    channels,
                    counts,
                    first: u64::MAX,
                    last: 0,
                    stats: st,
                }
                .run(rx, options.flush_interval)
            })
            .map_err(RecordingError::Thread)?;
        Ok(Recorder {
            tx: Some(tx),
            stats,
            thread: Some(thread),
        })
    }

    /// The shared counters and state.
    pub fn stats(&self) -> &Arc<RecorderStats> {
        &self.stats
    }

    /// A cloneable producer end (for another thread).
    pub fn sender(&self) -> RecordSender {
        RecordSender {
            tx: self.tx.clone(),
            stats: self.stats.clone(),
        }
    }

    /// Hands a message over without waiting; false (and counted) if it was dropped.
    pub fn record(&self, channel: usize, log_time: u64, publish_time: u64, data: Vec<u8>) -> bool {
        self.sender().record(channel, log_time, publish_time, data)
    }

    /// Hands a message over, waiting for room (offline use: nothing is dropped while the
    /// recording runs). False if the recording has stopped.
    pub fn record_blocking(
        &self,
        channel: usize,
        log_time: u64,
        publish_time: u64,
        data: Vec<u8>,
    ) -> bool {
        let Some(tx) = &self.tx else { return false };
        let len = data.len();
        self.stats.queued_bytes.fetch_add(len, Ordering::Relaxed);
        let sent = tx
            .send(Item::Message {
                channel,
                log_time,
                publish_time,
                data,
            })
            .is_ok();
        if !sent {
            self.stats.queued_bytes.fetch_sub(len, Ordering::Relaxed);
        }
        let ok = sent && self.stats.state() == RecorderState::Recording;
        if !ok {
            self.stats.dropped.fetch_add(1, Ordering::Relaxed);
        }
        ok
    }

    /// Writes the summary and closes the file; returns the final state.
    pub fn finish(mut self) -> RecorderState {
        self.close();
        self.stats.state()
    }

    fn close(&mut self) {
        if let Some(tx) = self.tx.take() {
            let _ = tx.send(Item::Finish);
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for Recorder {
    fn drop(&mut self) {
        self.close();
    }
}

/// A producer end of a recorder (cloneable, for other threads).
#[derive(Clone)]
pub struct RecordSender {
    tx: Option<SyncSender<Item>>,
    stats: Arc<RecorderStats>,
}

impl RecordSender {
    /// Hands a message over without waiting; false (and counted) if it was dropped: the channel
    /// is full, or holds its budget of bytes already.
    pub fn record(&self, channel: usize, log_time: u64, publish_time: u64, data: Vec<u8>) -> bool {
        let Some(tx) = &self.tx else { return false };
        let len = data.len();
        let queued = self.stats.queued_bytes.fetch_add(len, Ordering::Relaxed);
        if queued + len > self.stats.capacity_bytes {
            self.stats.queued_bytes.fetch_sub(len, Ordering::Relaxed);
            self.stats.dropped.fetch_add(1, Ordering::Relaxed);
            return false;
        }
        match tx.try_send(Item::Message {
            channel,
            log_time,
            publish_time,
            data,
        }) {
            Ok(()) => true,
            Err(TrySendError::Full(_)) | Err(TrySendError::Disconnected(_)) => {
                self.stats.queued_bytes.fetch_sub(len, Ordering::Relaxed);
                self.stats.dropped.fetch_add(1, Ordering::Relaxed);
                false
            }
        }
    }

    /// The recorder's counters.
    pub fn stats(&self) -> &Arc<RecorderStats> {
        &self.stats
    }

    /// Hands a metadata record over (written after what is queued before it); false (and
    /// counted as dropped) when the channel is full or closed.
    pub fn metadata(&self, name: &str, metadata: BTreeMap<String, String>) -> bool {
        let Some(tx) = &self.tx else { return false };
        let item = Item::Metadata(mcap::records::Metadata {
            name: name.into(),
            metadata,
        });
        if tx.try_send(item).is_ok() {
            true
        } else {
            self.stats.dropped.fetch_add(1, Ordering::Relaxed);
            false
        }
    }

    /// Asks the recorder to finish the file now (what is queued before this request is written,
    /// then the summary) and waits up to `timeout` for it: for a process that must exit before
    /// its owner of the [`Recorder`] gets to finish it. True if the file is finished.
    pub fn finish_now(&self, timeout: Duration) -> bool {
        let deadline = Instant::now() + timeout;
        let Some(tx) = &self.tx else { return false };
        let mut sent = false;
        while Instant::now() < deadline {
            if !sent {
                sent = match tx.try_send(Item::Finish) {
                    Ok(()) => true,
                    Err(TrySendError::Full(_)) => false,
                    Err(TrySendError::Disconnected(_)) => true,
                };
            }
            if self.stats.state() != RecorderState::Recording {
                return self.stats.state() == RecorderState::Finished;
            }
            std::thread::sleep(Duration::from_millis(2));
        }
        false
    }
}

struct Worker {
    writer: Option<McapWriter>,
    ids: Vec<u16>,
    channels: Vec<ChannelSpec>,
    counts: Vec<u64>,
    first: u64,
    last: u64,
    stats: Arc<RecorderStats>,
}

impl Worker {
    /// Writes what arrives on `rx`, flushing at most every `flush_interval`, until the handle
    /// finishes or goes away; after a failed write, drains and counts what still arrives.
    fn run(mut self, rx: mpsc::Receiver<Item>, flush_interval: Duration) {
        let mut last_flush = Instant::now();
        let mut dirty = false;
        loop {
            let wait = flush_interval.saturating_sub(last_flush.elapsed());
            match rx.recv_timeout(wait) {
                Ok(Item::Message {
                    channel,
                    log_time,
                    publish_time,
                    data,
                }) => {
                    self.stats
                        .queued_bytes
                        .fetch_sub(data.len(), Ordering::Relaxed);
                    if self.write(channel, log_time, publish_time, &data).is_err() {
                        break;
                    }
                    dirty = true;
                }
                Ok(Item::Metadata(m)) => {
                    if self.write_metadata(&m).is_err() {
                        break;
                    }
                    dirty = true;
                }
                Ok(Item::Finish) | Err(RecvTimeoutError::Disconnected) => {
                    self.finish();
                    return;
                }
                Err(RecvTimeoutError::Timeout) => {}
            }
            if dirty && last_flush.elapsed() >= flush_interval {
                if self.flush().is_err() {
                    break;
                }
                dirty = false;
                last_flush = Instant::now();
            } else if !dirty {
                last_flush = Instant::now();
            }
        }
        // Failed: drain and count what still arrives until the handle goes away.
        while let Ok(item) = rx.recv() {
            match item {
                Item::Message { .. } | Item::Metadata(_) => {
                    self.stats.dropped.fetch_add(1, Ordering::Relaxed);
                }
                Item::Finish => return,
            }
        }
    }

    fn fail(&mut self, what: &str, e: impl std::error::Error) {
        // The whole chain: the mcap error alone hides the OS reason (e.g. "No space left").
        let mut text = e.to_string();
        let mut source = e.source();
        while let Some(s) = source {
            text.push_str(&format!(": {s}"));
            source = s.source();
        }
        let msg = format!(
            "recording {} stopped: {what}: {text}",
            self.stats.path.display()
        );
        self.stats.set_state(RecorderState::Failed(msg));
        // Whatever the writer still buffers cannot be written either: close it without the
        // summary (dropping the mcap writer would try to finish the file again).
        if let Some(w) = self.writer.take() {
            drop(w.into_inner());
        }
    }

    fn write_metadata(&mut self, m: &mcap::records::Metadata) -> Result<(), ()> {
        let Some(w) = self.writer.as_mut() else {
            return Err(());
        };
        if let Err(e) = w.write_metadata(m) {
            self.fail("writing a metadata record", e);
            return Err(());
        }
        Ok(())
    }

    fn write(
        &mut self,
        channel: usize,
        log_time: u64,
        publish_time: u64,
        data: &[u8],
    ) -> Result<(), ()> {
        let Some(&id) = self.ids.get(channel) else {
            self.stats.dropped.fetch_add(1, Ordering::Relaxed);
            return Ok(());
        };
        let Some(w) = self.writer.as_mut() else {
            return Err(());
        };
        let seq = self.counts[channel] as u32;
        let r = w.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id: id,
                sequence: seq,
                log_time,
                publish_time,
            },
            data,
        );
        match r {
            Ok(()) => {
                self.counts[channel] += 1;
                self.first = self.first.min(log_time);
                self.last = self.last.max(log_time);
                self.stats.written.fetch_add(1, Ordering::Relaxed);
                self.stats
                    .message_bytes
                    .fetch_add(data.len() as u64, Ordering::Relaxed);
                Ok(())
            }
            Err(e) => {
                self.stats.dropped.fetch_add(1, Ordering::Relaxed);
                self.fail("write failed", e);
                Err(())
            }
        }
    }

    fn flush(&mut self) -> Result<(), ()> {
        let Some(w) = self.writer.as_mut() else {
            return Err(());
        };
        if let Err(e) = w.flush() {
            self.fail("flush failed", e);
            return Err(());
        }
        Ok(())
    }

    fn finish(&mut self) {
        let meta = match self.rosbag2_metadata() {
            Ok(meta) => meta,
            Err(e) => return self.fail("cannot write the rosbag2 metadata", e),
        };
        let Some(w) = self.writer.as_mut() else {
            return;
        };
        let r = w
            .write_metadata(&mcap::records::Metadata {
                name: "rosbag2".into(),
                metadata: meta,
            })
            .and_then(|_| w.finish().map(|_| ()));
        match r {
            Ok(()) => {
                self.writer.take();
                self.stats.set_state(RecorderState::Finished);
            }
            Err(e) => self.fail("cannot finish the file", e),
        }
    }

    /// The `rosbag2` metadata record: the bag's `metadata.yaml` content as rosbag2_storage_mcap
    /// writes it (key `serialized_metadata`).
    fn rosbag2_metadata(&self) -> Result<BTreeMap<String, String>, serde_norway::Error> {
        let topics: Vec<Topic> = (self.channels.iter().zip(&self.counts))
            .map(|(c, &n)| Topic {
                name: &c.topic,
                type_name: &c.type_name,
                qos_yaml: &c.qos_yaml,
                type_hash: c.type_hash.as_deref(),
                message_count: n,
            })
            .collect();
        let y = metadata_yaml(&topics, self.first, self.last)?;
        let mut m = BTreeMap::new();
        m.insert("serialized_metadata".to_string(), y);
        m.insert("ROS_DISTRO".to_string(), ROS_DISTRO.to_string());
        Ok(m)
    }
}
