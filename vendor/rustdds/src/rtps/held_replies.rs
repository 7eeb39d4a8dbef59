//! Replies held for a requester whose reader this Writer has not matched yet.
//!
//! A reply (a sample whose write options carry a `related_sample_identity`, as
//! a server of the DDS-RPC enhanced service mapping writes it) goes to the readers the
//! Writer has matched when it is written. The requester's reply reader may
//! still be unknown then: the requester has matched us (it sent the request
//! after it saw our endpoints), but its reader's SEDP announcement has not
//! reached us yet. A volatile Writer sends a newly matched reader nothing that
//! was written before the match (RTPS 2.5 §8.7.2.2.1, DURABILITY VOLATILE): the
//! reader is told by GAP that those samples are not for it, and the reply is
//! lost.
//!
//! So the Writer notes such a reply (its sequence number, whom it is for and
//! until when) and, when the reader it is for matches within
//! [`HOLD_DURATION`], sends that reader the reply from its history instead of
//! a GAP. A reply that waits longer, that does not fit the bounded queue, or
//! that has left the history meanwhile, is dropped and counted.
//!
//! Whom a reply is for: the `related_sample_identity` names a GUID. Fast DDS
//! (rmw_fastrtps) puts there the requester's reply *reader* GUID; then it is
//! that reader. Other implementations put the request *writer* GUID there;
//! then it is any reader of that participant (the requester filters replies
//! by the identity).

use std::{
  collections::VecDeque,
  sync::{
    atomic::{AtomicU64, Ordering},
    Arc,
  },
  time::{Duration, Instant},
};

use crate::structure::{
  cache_change::CacheChange,
  guid::{GuidPrefix, GUID},
  sequence_number::SequenceNumber,
};

/// How long a reply waits for its reader to match.
pub(crate) const HOLD_DURATION: Duration = Duration::from_secs(1);

/// At most this many replies wait per Writer; a further one drops the oldest.
pub(crate) const MAX_HELD_REPLIES: usize = 64;

/// Counts of the replies held by the Writers of one DomainParticipant, since
/// its creation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HeldReplyCounts {
  /// Replies written while the reader they are for was not matched.
  pub held: u64,
  /// Held replies sent when their reader matched.
  pub delivered: u64,
  /// Held replies given up: their reader did not match within the hold time,
  /// the queue was full, or the reply had left the Writer's history.
  pub dropped: u64,
}

/// The participant-wide counters behind [`HeldReplyCounts`], shared by its
/// Writers.
#[derive(Debug, Default)]
pub(crate) struct HeldReplyStats {
  held: AtomicU64,
  delivered: AtomicU64,
  dropped: AtomicU64,
}

impl HeldReplyStats {
  pub fn counts(&self) -> HeldReplyCounts {
    HeldReplyCounts {
      held: self.held.load(Ordering::Relaxed),
      delivered: self.delivered.load(Ordering::Relaxed),
      dropped: self.dropped.load(Ordering::Relaxed),
    }
  }
}

/// Whom a held reply is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum HoldTarget {
  Reader(GUID),
  Participant(GuidPrefix),
}

impl HoldTarget {
  /// The target named by a reply's related sample identity.
  pub fn of(identity_guid: GUID) -> Self {
    if identity_guid.entity_id.kind().is_reader() {
      Self::Reader(identity_guid)
    } else {
      Self::Participant(identity_guid.prefix)
    }
  }

  pub fn is(&self, reader: GUID) -> bool {
    match self {
      Self::Reader(g) => *g == reader,
      Self::Participant(p) => *p == reader.prefix,
    }
  }
}

#[derive(Debug)]
struct Held {
  seq: SequenceNumber,
  target: HoldTarget,
  deadline: Instant,
}

/// One Writer's held replies, oldest first.
#[derive(Debug)]
pub(crate) struct HeldReplies {
  entries: VecDeque<Held>,
  stats: Arc<HeldReplyStats>,
  /// Samples up to this one have been considered (a sample whose
  /// transmission is interrupted is pushed again from its start).
  considered_up_to: SequenceNumber,
  /// An expiry timer is pending.
  timer_set: bool,
}

impl HeldReplies {
  pub fn new(stats: Arc<HeldReplyStats>) -> Self {
    Self {
      entries: VecDeque::new(),
      stats,
      considered_up_to: SequenceNumber::zero(),
      timer_set: false,
    }
  }

  /// Called with each sample as the Writer first pushes it. Holds it if it is
  /// a reply and `matched` says its reader is not matched. Returns the time a
  /// timer must fire to expire it when no expiry timer is pending (the pending
  /// one comes back through [`Self::on_timer`]).
  pub fn consider(
    &mut self,
    cc: &CacheChange,
    matched: impl Fn(&HoldTarget) -> bool,
    now: Instant,
  ) -> Option<Instant> {
    if cc.sequence_number <= self.considered_up_to {
      return None;
    }
    self.considered_up_to = cc.sequence_number;
    let identity = cc.write_options.related_sample_identity()?;
    let target = HoldTarget::of(identity.writer_guid);
    if matched(&target) {
      return None;
    }
    if self.entries.len() >= MAX_HELD_REPLIES {
      self.entries.pop_front();
      self.stats.dropped.fetch_add(1, Ordering::Relaxed);
    }
    let deadline = now + HOLD_DURATION;
    self.entries.push_back(Held {
      seq: cc.sequence_number,
      target,
      deadline,
    });
    self.stats.held.fetch_add(1, Ordering::Relaxed);
    if self.timer_set {
      None
    } else {
      self.timer_set = true;
      Some(deadline)
    }
  }

  /// The expiry timer fired: expires what is due. Returns when to fire again,
  /// if anything is left.
  pub fn on_timer(&mut self, now: Instant) -> Option<Instant> {
    let next = self.expire(now);
    self.timer_set = next.is_some();
    next
  }

  /// A reader has matched: the sequence numbers of the replies held for it,
  /// taken out of the queue. The caller sends each one still in its history
  /// ([`Self::delivered`]) and reports the others ([`Self::lost`]).
  pub fn release_for(&mut self, reader: GUID, now: Instant) -> Vec<SequenceNumber> {
    self.expire(now);
    let mut released = Vec::new();
    self.entries.retain(|h| {
      if h.target.is(reader) {
        released.push(h.seq);
        false
      } else {
        true
      }
    });
    released
  }

  pub fn delivered(&self, n: usize) {
    self.stats.delivered.fetch_add(n as u64, Ordering::Relaxed);
  }

  pub fn lost(&self, n: usize) {
    self.stats.dropped.fetch_add(n as u64, Ordering::Relaxed);
  }

  /// Drops (and counts) the replies whose hold time is over. Returns when the
  /// next one's is, if any is left.
  pub fn expire(&mut self, now: Instant) -> Option<Instant> {
    let before = self.entries.len();
    // Deadlines are in insertion order: HOLD_DURATION is constant.
    while self.entries.front().is_some_and(|h| h.deadline <= now) {
      self.entries.pop_front();
    }
    self.lost(before - self.entries.len());
    self.entries.front().map(|h| h.deadline)
  }

  #[cfg(test)]
  pub fn len(&self) -> usize {
    self.entries.len()
  }
}

#[cfg(test)]
mod tests {
  use super::*;
  use crate::{
    dds::{ddsdata::DDSData, with_key::WriteOptionsBuilder},
    messages::submessages::elements::serialized_payload::SerializedPayload,
    structure::{guid::EntityId, rpc::SampleIdentity},
    RepresentationIdentifier,
  };

  fn reply(seq: i64, to: GUID) -> CacheChange {
    let opts = WriteOptionsBuilder::new()
      .related_sample_identity(SampleIdentity {
        writer_guid: to,
        sequence_number: SequenceNumber::new(1),
      })
      .build();
    CacheChange::new(
      GUID::dummy_test_guid(crate::structure::guid::EntityKind::WRITER_NO_KEY_USER_DEFINED),
      SequenceNumber::new(seq),
      opts,
      DDSData::new(SerializedPayload::new(
        RepresentationIdentifier::CDR_LE,
        vec![0, 0, 0, 0],
      )),
    )
  }

  fn reader_guid(prefix_byte: u8) -> GUID {
    GUID::new(
      GuidPrefix::new(&[prefix_byte; 12]),
      EntityId::new(
        [0, 0, 1],
        crate::structure::guid::EntityKind::READER_NO_KEY_USER_DEFINED,
      ),
    )
  }

  #[test]
  fn reply_for_an_unmatched_reader_is_held_and_released_when_it_matches() {
    let stats = Arc::new(HeldReplyStats::default());
    let mut h = HeldReplies::new(stats.clone());
    let now = Instant::now();
    let r = reader_guid(7);
    assert!(h.consider(&reply(1, r), |_| false, now).is_some());
    // Pushed again after an interrupted send: not held twice.
    assert!(h.consider(&reply(1, r), |_| false, now).is_none());
    assert_eq!(h.len(), 1);
    assert!(h.release_for(reader_guid(8), now).is_empty());
    assert_eq!(h.release_for(r, now), vec![SequenceNumber::new(1)]);
    h.delivered(1);
    assert_eq!(
      stats.counts(),
      HeldReplyCounts {
        held: 1,
        delivered: 1,
        dropped: 0
      }
    );
  }

  #[test]
  fn reply_for_a_matched_reader_is_not_held() {
    let stats = Arc::new(HeldReplyStats::default());
    let mut h = HeldReplies::new(stats.clone());
    assert!(h
      .consider(&reply(1, reader_guid(7)), |_| true, Instant::now())
      .is_none());
    assert_eq!(h.len(), 0);
    assert_eq!(stats.counts().held, 0);
  }

  #[test]
  fn reply_named_by_a_writer_guid_waits_for_any_reader_of_its_participant() {
    let mut h = HeldReplies::new(Arc::new(HeldReplyStats::default()));
    let now = Instant::now();
    let request_writer = GUID::new(
      GuidPrefix::new(&[7; 12]),
      EntityId::new(
        [0, 0, 2],
        crate::structure::guid::EntityKind::WRITER_NO_KEY_USER_DEFINED,
      ),
    );
    h.consider(&reply(1, request_writer), |_| false, now);
    assert_eq!(
      h.release_for(reader_guid(7), now),
      vec![SequenceNumber::new(1)]
    );
  }

  #[test]
  fn held_replies_expire_and_are_counted() {
    let stats = Arc::new(HeldReplyStats::default());
    let mut h = HeldReplies::new(stats.clone());
    let now = Instant::now();
    h.consider(&reply(1, reader_guid(7)), |_| false, now);
    // One timer at a time.
    assert!(h
      .consider(
        &reply(2, reader_guid(7)),
        |_| false,
        now + HOLD_DURATION / 2
      )
      .is_none());
    assert_eq!(
      h.on_timer(now + HOLD_DURATION),
      Some(now + HOLD_DURATION * 3 / 2)
    );
    assert_eq!(h.len(), 1);
    assert!(h
      .release_for(reader_guid(7), now + HOLD_DURATION * 2)
      .is_empty());
    assert_eq!(stats.counts().dropped, 2);
  }

  #[test]
  fn the_queue_is_bounded() {
    let stats = Arc::new(HeldReplyStats::default());
    let mut h = HeldReplies::new(stats.clone());
    let now = Instant::now();
    for seq in 1..=(MAX_HELD_REPLIES as i64 + 3) {
      h.consider(&reply(seq, reader_guid(7)), |_| false, now);
    }
    assert_eq!(h.len(), MAX_HELD_REPLIES);
    assert_eq!(stats.counts().dropped, 3);
    assert_eq!(
      h.release_for(reader_guid(7), now)[0],
      SequenceNumber::new(4)
    );
  }
}
