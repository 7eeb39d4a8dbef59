//! Recordings cut by a crash (no summary): `replay` and `compare` read every whole chunk with one
//! warning naming the time range read, and `recover` rewrites them as complete, indexed MCAP
//! files holding exactly those messages, byte for byte. Files with nothing readable are refused
//! with one `error:` line.

use mcap::read::Options;
use std::path::{Path, PathBuf};
use std::process::Output;

#[path = "common/cli.rs"]
mod cli;
use cli::{bin, stderr};

fn dir() -> PathBuf {
    cli::temp_dir("recover")
}

/// A recording of several chunks: 8 s of a 1 kHz elbow run (about 1.2 MB, six chunks).
fn long_recording() -> PathBuf {
    static MADE: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    MADE.get_or_init(make_long_recording).clone()
}

fn make_long_recording() -> PathBuf {
    cli::record_scenario(
        &dir(),
        "long",
        "name = \"long\"\nduration = 8.0\nattachment = \"joint\"\n[[input]]\n\
         signal = \"excitation\"\nmuscle = \"flexor\"\nkind = \"pulse\"\nstart = 0.05\n\
         end = 4.0\nvalue = 0.5\n",
    )
}

/// Top-level records: (offset, opcode, end).
fn records(buf: &[u8]) -> Vec<(usize, u8, usize)> {
    cli::mcap_records(buf)
        .into_iter()
        .map(|(at, op, len)| (at, op, at + 9 + len as usize))
        .collect()
}

/// (topic, sequence, log time, publish time, data) of a message.
type Msg = (String, u32, u64, u64, Vec<u8>);

/// The messages the `mcap` crate's streaming reader yields before the first error.
fn stream(buf: &[u8], options: enumset::EnumSet<Options>) -> (Vec<Msg>, bool) {
    let mut out = Vec::new();
    for m in mcap::MessageStream::new_with_options(buf, options).unwrap() {
        match m {
            Ok(m) => out.push((
                m.channel.topic.clone(),
                m.sequence,
                m.log_time,
                m.publish_time,
                m.data.into_owned(),
            )),
            Err(_) => return (out, false),
        }
    }
    (out, true)
}

/// One line on stderr, an `error:` naming `path`, a failure that is not a panic.
fn assert_refused(o: &Output, path: &Path, what: &str) {
    let err = stderr(o);
    assert!(!o.status.success(), "{what} accepted: {err}");
    assert_ne!(o.status.code(), Some(101), "{what} panicked: {err}");
    assert_eq!(err.lines().count(), 1, "{what}: {err}");
    assert!(err.starts_with("error: "), "{what}: {err}");
    assert!(err.contains(path.to_str().unwrap()), "{what}: {err}");
}

#[test]
fn truncated_recordings_are_read_and_recovered() {
    let intact_path = long_recording();
    let intact = std::fs::read(&intact_path).unwrap();
    let (all, complete) = stream(&intact, Options::ValidateChunkCrcs.into());
    assert!(complete && all.len() > 1000);
    let recs = records(&intact);
    let chunks: Vec<(usize, usize)> = recs
        .iter()
        .filter(|r| r.1 == mcap::records::op::CHUNK)
        .map(|r| (r.0, r.2))
        .collect();
    assert!(chunks.len() >= 5, "{chunks:?}");
    let data_end = recs
        .iter()
        .find(|r| r.1 == mcap::records::op::DATA_END)
        .unwrap()
        .0;
    let mid = |c: (usize, usize)| (c.0 + c.1) / 2;
    let cuts = [
        (20, "in the header"),
        (mid(chunks[1]), "in the first chunk of messages"),
        (chunks[3].0, "after a few chunks"),
        (mid(chunks[3]), "mid-chunk"),
        (mid(chunks[chunks.len() - 1]), "in the last chunk"),
        (data_end, "before the summary"),
        ((data_end + intact.len()) / 2, "in the summary"),
        (intact.len() - 8, "before the end magic"),
    ];
    let mut readable = 0;
    for (i, (cut, what)) in cuts.iter().enumerate() {
        let what = format!("cut at {cut} ({what})");
        let bytes = &intact[..*cut];
        let truncated = dir().join(format!("cut_{i}.mcap"));
        std::fs::write(&truncated, bytes).unwrap();
        // What the crate's streaming reader yields from the whole records before the cut (on
        // the cut file itself it also yields the first messages of the chunk cut short, which
        // no CRC vouches for: those are not recovered).
        let whole = records(bytes)
            .iter()
            .take_while(|r| r.2 <= bytes.len())
            .last()
            .map_or(8.min(bytes.len()), |r| r.2);
        let (expected, _) = stream(
            &bytes[..whole],
            Options::IgnoreEndMagic | Options::ValidateChunkCrcs,
        );
        let (partial, _) = stream(bytes, Options::IgnoreEndMagic.into());
        assert!(partial.len() >= expected.len() && partial[..expected.len()] == expected[..]);
        assert!(!matches!(mcap::Summary::read(bytes), Ok(Some(_))), "{what}");
        let replay = bin()
            .arg("replay")
            .arg(&truncated)
            .arg("--out")
            .arg(dir().join(format!("replayed_{i}.mcap")))
            .output()
            .unwrap();
        let compare = bin()
            .arg("compare")
            .arg(&intact_path)
            .arg(&truncated)
            .output()
            .unwrap();
        let recovered = dir().join(format!("recovered_{i}.mcap"));
        let recover = bin()
            .arg("recover")
            .arg(&truncated)
            .arg(&recovered)
            .output()
            .unwrap();
        if expected.is_empty() {
            assert_refused(&replay, &truncated, &format!("replay, {what}"));
            assert_refused(&compare, &truncated, &format!("compare, {what}"));
            assert_refused(&recover, &truncated, &format!("recover, {what}"));
            assert!(!recovered.exists(), "{what}");
            continue;
        }
        readable += 1;
        let n = expected.len();
        assert_eq!(expected[..], all[..n], "{what}");
        let t1 = expected.iter().map(|m| m.2).max().unwrap() as f64 * 1e-9;
        let range = format!("read {n} messages from 0.000 to {t1:.3} s");
        for (o, cmd) in [(&replay, "replay"), (&compare, "compare")] {
            let err = stderr(o);
            assert!(o.status.success(), "{cmd}, {what}: {err}");
            let warnings: Vec<&str> = err.lines().filter(|l| l.starts_with("warning:")).collect();
            assert_eq!(warnings.len(), 1, "{cmd}, {what}: {err}");
            assert!(
                warnings[0].contains(truncated.to_str().unwrap())
                    && warnings[0].contains("truncated")
                    && warnings[0].contains(&range),
                "{cmd}, {what}: {err} (expected {range:?})"
            );
            assert!(!err.contains("error"), "{cmd}, {what}: {err}");
        }
        let err = stderr(&recover);
        assert!(recover.status.success(), "recover, {what}: {err}");
        assert!(err.contains(&format!("recovered {n} messages")), "{err}");
        // The strict reader: a summary, every message, the first n of the intact file.
        let out = std::fs::read(&recovered).unwrap();
        let summary = mcap::Summary::read(&out)
            .unwrap()
            .expect("a summary in the recovered file");
        assert_eq!(summary.stats.as_ref().unwrap().message_count, n as u64);
        assert!(!summary.chunk_indexes.is_empty());
        let (got, complete) = stream(&out, Options::ValidateChunkCrcs.into());
        assert!(complete, "{what}: the recovered file does not read whole");
        assert_eq!(got.len(), n, "{what}");
        assert!(
            got == all[..n],
            "{what}: messages differ from the intact file's"
        );
        // Channels (with their metadata) and schemas as in the intact file.
        let intact_summary = mcap::Summary::read(&intact).unwrap().unwrap();
        assert_eq!(summary.channels.len(), intact_summary.channels.len());
        for (id, c) in &intact_summary.channels {
            let r = &summary.channels[id];
            assert_eq!(
                (&r.topic, &r.message_encoding, &r.metadata),
                (&c.topic, &c.message_encoding, &c.metadata)
            );
            let (rs, cs) = (r.schema.as_ref().unwrap(), c.schema.as_ref().unwrap());
            assert_eq!(
                (&rs.name, &rs.encoding, &rs.data),
                (&cs.name, &cs.encoding, &cs.data)
            );
        }
        // Header profile and the metadata records that were written.
        let back = muscle_actuator_recording::recording::read_recording(&recovered, false).unwrap();
        let cut_rec =
            muscle_actuator_recording::recording::read_recording(&truncated, true).unwrap();
        assert_eq!(back.profile, "ros2");
        assert_eq!(back.library, cut_rec.library);
        assert!(
            back.metadata.contains_key("muscle_actuator"),
            "{:?}",
            back.metadata.keys()
        );
        assert_eq!(back.metadata, cut_rec.metadata);
        assert_eq!(
            summary.metadata_indexes.len(),
            cut_rec.metadata_records.len()
        );
    }
    assert!(readable >= 5, "{readable}");

    // The recovered file of a complete recording is the same recording.
    let whole = dir().join("whole_recovered.mcap");
    let o = bin()
        .arg("recover")
        .arg(&intact_path)
        .arg(&whole)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    let (got, complete) = stream(
        &std::fs::read(&whole).unwrap(),
        Options::ValidateChunkCrcs.into(),
    );
    assert!(complete && got == all);
    let back = muscle_actuator_recording::recording::read_recording(&whole, false).unwrap();
    assert!(back.metadata.contains_key("rosbag2"));
}

#[test]
fn recover_refuses_what_it_cannot_recover() {
    let d = dir();
    let garbage = d.join("garbage.mcap");
    std::fs::write(&garbage, b"not an mcap file at all, not even its magic").unwrap();
    let empty = d.join("empty.mcap");
    std::fs::write(&empty, b"").unwrap();
    let magic = d.join("magic_only.mcap");
    std::fs::write(&magic, b"\x89MCAP0\r\n").unwrap();
    for bad in [&garbage, &empty, &magic, &d.join("missing.mcap")] {
        let out = d.join("out.mcap");
        let o = bin().arg("recover").arg(bad).arg(&out).output().unwrap();
        assert_refused(&o, bad, "recover");
        assert!(!out.exists());
    }
    // Never over the input, by any name.
    let intact = long_recording();
    let before = std::fs::read(&intact).unwrap();
    let cut = d.join("cut.mcap");
    std::fs::write(&cut, &before[..before.len() / 2]).unwrap();
    let same = d.join(".").join("cut.mcap");
    for out in [&cut, &same] {
        let o = bin().arg("recover").arg(&cut).arg(out).output().unwrap();
        let err = stderr(&o);
        assert!(!o.status.success() && err.starts_with("error: "), "{err}");
        assert!(err.contains("overwrite"), "{err}");
    }
    assert_eq!(std::fs::read(&cut).unwrap(), before[..before.len() / 2]);
}
