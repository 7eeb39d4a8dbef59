//! DATA that a reliable Reader received from a Writer it had not matched yet.
//!
//! A remote Writer may match our Reader, and send it DATA, before our
//! discovery has processed that Writer's SEDP announcement. The Reader cannot
//! take such a sample (it has no WriterProxy and so does not know the Writer's
//! QoS, RTPS 2.5 §8.4.10), and drops it. The Writer, believing it sent, repeats
//! it only when the Reader asks for it: after its next HEARTBEAT, whose period
//! is the Writer's choice (3 s by default in Fast DDS).
//!
//! So the Reader notes the sequence numbers it dropped, per Writer, and when
//! the Writer matches it asks for them at once with an ACKNACK that lists
//! them as missing (§8.3.7.1), and again every 20 ms (10 times at most) for
//! what has still not come: a Writer that has only just pushed a sample may not
//! act on a request for it yet (Fast DDS resends only samples it counts as
//! unacknowledged). The notes are bounded in number and in age.

use std::{
  collections::{BTreeMap, BTreeSet},
  time::{Duration, Instant},
};

use crate::structure::{guid::GUID, sequence_number::SequenceNumber};

/// Notes older than this are forgotten: a Writer announced that late is not a
/// discovery race.
pub(crate) const EARLY_DATA_MAX_AGE: Duration = Duration::from_secs(10);
/// At most this many Writers are noted per Reader (the oldest note goes).
pub(crate) const EARLY_DATA_MAX_WRITERS: usize = 32;
/// DATA asked for but not come is asked for again after this, ...
pub(crate) const EARLY_DATA_RETRY_INTERVAL: Duration = Duration::from_millis(20);
/// ... up to this many times in all.
pub(crate) const EARLY_DATA_RETRIES: u8 = 10;
/// At most this many sequence numbers per Writer (the lowest ones are kept:
/// one ACKNACK can list 256 from its base, §8.3.5.5).
pub(crate) const EARLY_DATA_MAX_PER_WRITER: usize = 64;

#[derive(Debug, Default)]
pub(crate) struct EarlyData {
  writers: BTreeMap<GUID, (Instant, BTreeSet<SequenceNumber>)>,
}

impl EarlyData {
  /// DATA `sn` from the unmatched `writer` was dropped at `now`.
  pub fn note(&mut self, writer: GUID, sn: SequenceNumber, now: Instant) {
    self
      .writers
      .retain(|_, (since, _)| now.duration_since(*since) < EARLY_DATA_MAX_AGE);
    if !self.writers.contains_key(&writer) && self.writers.len() >= EARLY_DATA_MAX_WRITERS {
      if let Some(oldest) = self
        .writers
        .iter()
        .min_by_key(|(_, (since, _))| *since)
        .map(|(g, _)| *g)
      {
        self.writers.remove(&oldest);
      }
    }
    let (_, sns) = self
      .writers
      .entry(writer)
      .or_insert_with(|| (now, BTreeSet::new()));
    sns.insert(sn);
    while sns.len() > EARLY_DATA_MAX_PER_WRITER {
      sns.pop_last();
    }
  }

  /// `writer` has matched: what was dropped from it (recent enough), lowest
  /// first, at most 256 from the lowest.
  pub fn take(&mut self, writer: GUID, now: Instant) -> Option<Vec<SequenceNumber>> {
    let (since, sns) = self.writers.remove(&writer)?;
    if now.duration_since(since) >= EARLY_DATA_MAX_AGE {
      return None;
    }
    let first = *sns.first()?;
    Some(
      sns
        .into_iter()
        .take_while(|sn| *sn < first + SequenceNumber::new(256))
        .collect(),
    )
  }
}

#[cfg(test)]
mod tests {
  use super::*;
  use crate::structure::guid::{EntityId, EntityKind, GuidPrefix};

  #[test]
  fn dropped_data_is_asked_for_when_its_writer_matches() {
    let mut e = EarlyData::default();
    let w = GUID::dummy_test_guid(EntityKind::WRITER_NO_KEY_USER_DEFINED);
    let now = Instant::now();
    e.note(w, SequenceNumber::new(3), now);
    e.note(w, SequenceNumber::new(1), now);
    e.note(w, SequenceNumber::new(300), now);
    assert_eq!(
      e.take(w, now),
      Some(vec![SequenceNumber::new(1), SequenceNumber::new(3)])
    );
    assert_eq!(e.take(w, now), None);
  }

  #[test]
  fn old_notes_are_forgotten() {
    let mut e = EarlyData::default();
    let w = GUID::dummy_test_guid(EntityKind::WRITER_NO_KEY_USER_DEFINED);
    let now = Instant::now();
    e.note(w, SequenceNumber::new(1), now);
    assert_eq!(e.take(w, now + EARLY_DATA_MAX_AGE), None);
  }

  #[test]
  fn notes_are_bounded() {
    let mut e = EarlyData::default();
    let now = Instant::now();
    let mut first = None;
    for i in 0..(EARLY_DATA_MAX_WRITERS + 5) {
      let w = GUID::new(
        GuidPrefix::new(&[i as u8; 12]),
        EntityId::new([0, 0, 2], EntityKind::WRITER_NO_KEY_USER_DEFINED),
      );
      first.get_or_insert(w);
      for sn in 1..=(EARLY_DATA_MAX_PER_WRITER as i64 + 10) {
        e.note(
          w,
          SequenceNumber::new(sn),
          now + Duration::from_millis(i as u64),
        );
      }
    }
    assert_eq!(e.writers.len(), EARLY_DATA_MAX_WRITERS);
    assert!(e
      .writers
      .values()
      .all(|(_, s)| s.len() == EARLY_DATA_MAX_PER_WRITER));
    assert_eq!(e.take(first.unwrap(), now), None);
  }
}
