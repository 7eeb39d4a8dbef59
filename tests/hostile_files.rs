//! Hostile MCAP files for `replay` and `compare`: a corpus generated here, from a real recording
//! made by `simulate --out` (no binary blobs; every random choice seeded).
//!
//! Damage at the byte level (truncations, bit flips in record and chunk headers, records and
//! chunks declaring huge lengths), rebuilt files with lies inside (non-finite or out-of-range
//! metadata, ticks shifted by 1e12, non-monotone ticks, NaN values, names that do not match,
//! CDR payloads whose array lengths run past their end, foreign schemas and encodings, a
//! decompression bomb), and things that are not recordings at all (`/dev/zero`, a FIFO, a
//! directory, megabytes of zeros or random bytes, a sparse file over the size limit).
//!
//! Each file goes through `replay FILE` and `compare GOOD FILE --json`, each run as a child with
//! a time limit and a 1 GiB address-space limit. Every run must end cleanly: no panic, no signal
//! (a failed allocation aborts), no hang, an `error:` line whenever it fails. Files marked
//! [`Expect::Refuse`] must be refused; damage that may land where nothing is read (a bit flip in
//! the summary section) may also be accepted, but then with finite figures only; a file cut
//! short ([`Expect::Truncated`], as by a crash) may be accepted for what its whole chunks hold,
//! with finite figures and one warning. The summary
//! line (`cargo test --test hostile_files -- --nocapture`) gives the counts.

#[path = "common/child.rs"]
mod child;
#[path = "common/cli.rs"]
mod cli;

use child::{Ended, Rng};
use muscle_actuator_recording::msgs::muscle_actuator_msgs::{
    ActivationCommand, ActuatorState, ExternalLoad,
};
use muscle_actuator_recording::recording::{decode_cdr, encode_cdr, read_recording};
use std::collections::BTreeMap;
use std::ffi::OsString;
use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::time::Duration;

const TIME_LIMIT: Duration = Duration::from_secs(10);
const WORKERS: usize = 2;
const STATE_TOPIC: &str = "/muscle_actuator/state";
const STATE_TYPE: &str = "muscle_actuator_msgs/msg/ActuatorState";
const ACTIVATION_TYPE: &str = "muscle_actuator_msgs/msg/ActivationCommand";
const LOAD_TYPE: &str = "muscle_actuator_msgs/msg/ExternalLoad";
const JOINT_STATE_TYPE: &str = "sensor_msgs/msg/JointState";
const MAGIC: &[u8; 8] = b"\x89MCAP0\r\n";

/// What a file may end in.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Expect {
    /// A control: every command succeeds.
    Accept,
    /// An `error:` line and a non-zero exit from every command.
    Refuse,
    /// Damage that may land where nothing is read: refused, or accepted with finite figures.
    Either,
    /// A file cut short (a crash): refused, or accepted with finite figures and exactly one
    /// `warning:` line naming the file as truncated.
    Truncated,
}

struct Case {
    name: String,
    path: PathBuf,
    expect: Expect,
}

struct Corpus {
    dir: PathBuf,
    cases: Vec<Case>,
}

impl Corpus {
    fn add(&mut self, name: &str, bytes: &[u8], expect: Expect) {
        let path = self
            .dir
            .join(format!("{:03}_{name}.mcap", self.cases.len()));
        std::fs::write(&path, bytes).unwrap();
        self.add_path(name, path, expect);
    }

    fn add_path(&mut self, name: &str, path: PathBuf, expect: Expect) {
        self.cases.push(Case {
            name: name.into(),
            path,
            expect,
        });
    }
}

/// One message with everything about its channel, to rebuild files from.
#[derive(Clone)]
struct Msg {
    topic: String,
    schema_name: String,
    schema_encoding: String,
    schema_data: Vec<u8>,
    encoding: String,
    log_time: u64,
    publish_time: u64,
    data: Vec<u8>,
}

type Meta = Vec<(String, BTreeMap<String, String>)>;

/// A change to one recorded state.
type StateEdit = fn(&mut ActuatorState);

fn messages(buf: &[u8]) -> Vec<Msg> {
    mcap::MessageStream::new(buf)
        .unwrap()
        .map(|m| {
            let m = m.unwrap();
            let s = m.channel.schema.as_ref().unwrap();
            Msg {
                topic: m.channel.topic.clone(),
                schema_name: s.name.clone(),
                schema_encoding: s.encoding.clone(),
                schema_data: s.data.to_vec(),
                encoding: m.channel.message_encoding.clone(),
                log_time: m.log_time,
                publish_time: m.publish_time,
                data: m.data.into_owned(),
            }
        })
        .collect()
}

/// An MCAP file of these metadata records and messages (channels and schemas as the messages
/// name them), zstd-chunked or not.
fn write_mcap(meta: &Meta, msgs: &[Msg], chunked: bool) -> Vec<u8> {
    let mut w = mcap::WriteOptions::new()
        .profile("ros2")
        .use_chunks(chunked)
        .compression(chunked.then_some(mcap::Compression::Zstd))
        .create(Cursor::new(Vec::new()))
        .unwrap();
    for (name, map) in meta {
        w.write_metadata(&mcap::records::Metadata {
            name: name.clone(),
            metadata: map.clone(),
        })
        .unwrap();
    }
    let mut schemas = BTreeMap::new();
    let mut channels = BTreeMap::new();
    for (seq, m) in msgs.iter().enumerate() {
        let skey = (
            m.schema_name.clone(),
            m.schema_encoding.clone(),
            m.schema_data.clone(),
        );
        let sid = match schemas.get(&skey) {
            Some(&id) => id,
            None => {
                let id = w
                    .add_schema(&m.schema_name, &m.schema_encoding, &m.schema_data)
                    .unwrap();
                schemas.insert(skey, id);
                id
            }
        };
        let ckey = (m.topic.clone(), sid, m.encoding.clone());
        let cid = match channels.get(&ckey) {
            Some(&id) => id,
            None => {
                let id = w
                    .add_channel(sid, &m.topic, &m.encoding, &BTreeMap::new())
                    .unwrap();
                channels.insert(ckey, id);
                id
            }
        };
        w.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id: cid,
                sequence: seq as u32,
                log_time: m.log_time,
                publish_time: m.publish_time,
            },
            &m.data,
        )
        .unwrap();
    }
    w.finish().unwrap();
    w.into_inner().into_inner()
}

fn main_dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("muscle_actuator_hostile_{}", std::process::id()));
    std::fs::create_dir_all(d.join("out")).unwrap();
    d
}

/// `simulate` of a 0.1 s elbow run (excitation pulse, torque step) recorded to MCAP.
fn base_recording(dir: &Path) -> PathBuf {
    cli::record_scenario(
        dir,
        "base",
        "name = \"hostile-base\"\nduration = 0.1\nattachment = \"joint\"\n\
         [[input]]\nsignal = \"excitation\"\nmuscle = \"flexor\"\nkind = \"pulse\"\n\
         start = 0.02\nend = 0.06\nvalue = 0.5\n\
         [[input]]\nsignal = \"external_torque\"\nkind = \"step\"\nat = 0.05\nto = -1.0\n",
    )
}

use cli::mcap_records as records;

fn put_u64(buf: &mut [u8], at: usize, v: u64) {
    buf[at..at + 8].copy_from_slice(&v.to_le_bytes());
}

fn put_u32(buf: &mut [u8], at: usize, v: u32) {
    buf[at..at + 4].copy_from_slice(&v.to_le_bytes());
}

fn flip(buf: &[u8], byte: usize, bit: usize) -> Vec<u8> {
    let mut b = buf.to_vec();
    b[byte] ^= 1 << bit;
    b
}

/// Truncations: at the start, at every record boundary and just inside it, and at random.
fn truncations(c: &mut Corpus, base: &[u8], rng: &mut Rng) {
    let mut cuts = vec![0, 1, 7, 8, 9, 16, base.len() - 1, base.len() - 8];
    for (at, _, len) in records(base) {
        cuts.extend([at, at + 1, at + 9, at + 9 + (len as usize) / 2]);
    }
    for _ in 0..24 {
        cuts.push(rng.below(base.len()));
    }
    cuts.retain(|&n| n < base.len());
    cuts.sort();
    cuts.dedup();
    for n in cuts {
        c.add(&format!("truncated_at_{n}"), &base[..n], Expect::Truncated);
    }
}

/// Bit flips in each record's opcode and length, in each chunk header field, and anywhere.
fn bit_flips(c: &mut Corpus, base: &[u8], rng: &mut Rng) {
    for (at, op, _) in records(base) {
        for _ in 0..2 {
            let byte = at + rng.below(9);
            let bit = rng.below(8);
            c.add(
                &format!("flip_record_{op:02x}_at_{byte}_{bit}"),
                &flip(base, byte, bit),
                Expect::Either,
            );
        }
        if op == 0x06 {
            // Chunk: start, end, uncompressed size, CRC, compression (length, text), records
            // length.
            let b = at + 9;
            for (field, off, width) in [
                ("start", 0, 8),
                ("end", 8, 8),
                ("usize", 16, 8),
                ("crc", 24, 4),
                ("complen", 28, 4),
                ("comp", 32, 4),
                ("reclen", 36, 8),
            ] {
                let byte = b + off + rng.below(width);
                let bit = rng.below(8);
                c.add(
                    &format!("flip_chunk_{field}_{byte}_{bit}"),
                    &flip(base, byte, bit),
                    Expect::Either,
                );
            }
        }
    }
    for _ in 0..40 {
        let byte = rng.below(base.len());
        let bit = rng.below(8);
        c.add(
            &format!("flip_any_{byte}_{bit}"),
            &flip(base, byte, bit),
            Expect::Either,
        );
    }
}

/// Records and chunks declaring lengths far beyond the file.
fn huge_lengths(c: &mut Corpus, base: &[u8]) {
    for (at, op, len) in records(base) {
        for v in [u64::MAX, 1 << 62, 1 << 40, base.len() as u64] {
            let mut b = base.to_vec();
            put_u64(&mut b, at + 1, v);
            c.add(&format!("len_{op:02x}_at_{at}_{v}"), &b, Expect::Refuse);
        }
        if op != 0x02 && len > 16 {
            let mut b = base.to_vec();
            put_u64(&mut b, at + 1, len / 2);
            c.add(&format!("len_halved_{op:02x}_at_{at}"), &b, Expect::Either);
        }
        if op == 0x06 {
            let b0 = at + 9;
            let comp_len = u32::from_le_bytes(base[b0 + 28..b0 + 32].try_into().unwrap()) as usize;
            let reclen_at = b0 + 32 + comp_len;
            let fields: [(&str, usize, u64, bool); 7] = [
                ("usize_max", b0 + 16, u64::MAX, true),
                ("usize_1t", b0 + 16, 1 << 40, true),
                ("usize_zero", b0 + 16, 0, true),
                ("reclen_max", reclen_at, u64::MAX, true),
                ("reclen_1t", reclen_at, 1 << 40, true),
                ("complen_max", b0 + 28, u32::MAX as u64, false),
                ("complen_big", b0 + 28, 1 << 30, false),
            ];
            for (name, off, v, wide) in fields {
                let mut b = base.to_vec();
                if wide {
                    put_u64(&mut b, off, v);
                } else {
                    put_u32(&mut b, off, v as u32);
                }
                c.add(&format!("chunk_{name}_at_{at}"), &b, Expect::Refuse);
            }
            let mut b = base.to_vec();
            b[b0 + 32..b0 + 32 + comp_len.min(4)].copy_from_slice(&b"lz5x"[..comp_len.min(4)]);
            c.add(
                &format!("chunk_unknown_compression_at_{at}"),
                &b,
                Expect::Refuse,
            );
        }
    }
}

/// Rebuilt files: `edit` changes the metadata and messages of the base run.
struct Rebuild<'a> {
    meta: &'a Meta,
    msgs: &'a [Msg],
}

impl Rebuild<'_> {
    fn with(&self, edit: impl FnOnce(&mut Meta, &mut Vec<Msg>)) -> Vec<u8> {
        let mut meta = self.meta.clone();
        let mut msgs = self.msgs.to_vec();
        edit(&mut meta, &mut msgs);
        write_mcap(&meta, &msgs, true)
    }

    fn ours(meta: &mut Meta) -> &mut BTreeMap<String, String> {
        &mut meta
            .iter_mut()
            .find(|(n, _)| n == "muscle_actuator")
            .unwrap()
            .1
    }
}

fn map_states(msgs: &mut [Msg], mut f: impl FnMut(usize, &mut ActuatorState)) {
    let states = msgs.iter_mut().filter(|m| m.schema_name == STATE_TYPE);
    for (k, m) in states.enumerate() {
        let mut s: ActuatorState = decode_cdr(&m.data).unwrap();
        f(k, &mut s);
        m.data = encode_cdr(&s).unwrap();
    }
}

fn hostile_metadata(c: &mut Corpus, r: &Rebuild) {
    let set = |k: &'static str, v: String| {
        r.with(move |meta, _| {
            Rebuild::ours(meta).insert(k.into(), v);
        })
    };
    let long_digits = "9".repeat(400);
    for v in [
        "NaN",
        "nan",
        "inf",
        "-inf",
        "-1000.0",
        "0",
        "0.0",
        "-0.0",
        "1e12",
        "1e308",
        "1e-300",
        "100001",
        "abc",
        "",
        "1000.0 Hz",
        "0x3e8",
        &long_digits,
    ] {
        c.add(
            &format!("meta_rate_{}", v.len().min(12)),
            &set("rate_hz", v.into()),
            Expect::Refuse,
        );
    }
    for (k, v) in [
        ("model", "bogus"),
        ("model", ""),
        ("stepping", "fixed 0"),
        ("stepping", "fixed 10001"),
        ("stepping", "fixed 18446744073709551615"),
        ("stepping", "adaptive nan 64"),
        ("stepping", "adaptive -1e-5 64"),
        ("stepping", "adaptive 1e-5 0"),
        ("stepping", "adaptive 1e-5 99999999999"),
        ("stepping", "sometimes"),
        ("attachment", "glued"),
        ("config_toml", "this is = not [ toml"),
        (
            "config_toml",
            "[[muscle]]\nname = \"flexor\"\nf_max = nan\n",
        ),
        ("muscles", "a,b,c"),
        ("muscles", ""),
        ("joints", "knee"),
        ("joints", "elbow,elbow"),
    ] {
        c.add(
            &format!("meta_{k}_{}", v.len()),
            &set(k, v.into()),
            Expect::Refuse,
        );
    }
    for k in ["rate_hz", "model", "stepping", "attachment", "config_toml"] {
        let b = r.with(|meta, _| {
            Rebuild::ours(meta).remove(k);
        });
        c.add(&format!("meta_without_{k}"), &b, Expect::Refuse);
    }
    let b = r.with(|meta, _| meta.retain(|(n, _)| n != "muscle_actuator"));
    c.add("meta_record_missing", &b, Expect::Refuse);
    // Plausible or harmless lies: a different but valid rate, a long source, a bad start time.
    c.add(
        "meta_rate_500",
        &set("rate_hz", "500.0".into()),
        Expect::Either,
    );
    c.add(
        "meta_long_source",
        &set("source", "x".repeat(100_000)),
        Expect::Either,
    );
    c.add(
        "meta_bad_start_time",
        &set("start_time_ns", "-99999999999999999999999".into()),
        Expect::Either,
    );
}

fn hostile_ticks_and_values(c: &mut Corpus, r: &Rebuild) {
    const SHIFT: u64 = 1_000_000_000_000;
    let b = r.with(|_, msgs| map_states(msgs, |_, s| s.tick += SHIFT));
    c.add("ticks_all_shifted_1e12", &b, Expect::Refuse);
    let n = r
        .msgs
        .iter()
        .filter(|m| m.schema_name == STATE_TYPE)
        .count();
    let b = r.with(|_, msgs| {
        map_states(msgs, |k, s| {
            if k == n - 1 {
                s.tick += SHIFT
            }
        })
    });
    c.add("ticks_last_shifted_1e12", &b, Expect::Refuse);
    let b = r.with(|_, msgs| {
        map_states(msgs, |k, s| {
            if k == n - 1 {
                s.tick = u64::MAX
            }
        })
    });
    c.add("ticks_last_max", &b, Expect::Refuse);
    // A consistent lie: ticks, stamps and log times all 1e12 ticks (1e9 s) later, with one
    // message left at time 0 so the recorded time span matches.
    let b = r.with(|_, msgs| {
        map_states(msgs, |_, s| {
            s.tick += SHIFT;
            s.header.stamp = muscle_actuator_recording::msgs::Time::from_nanos(
                s.header.stamp.to_nanos() + 1_000_000_000_000_000_000,
            );
        });
        for m in msgs.iter_mut().skip(1) {
            m.log_time += 1_000_000_000_000_000_000;
            m.publish_time += 1_000_000_000_000_000_000;
        }
    });
    c.add("ticks_consistently_shifted_1e12", &b, Expect::Refuse);
    let b = r.with(|_, msgs| map_states(msgs, |k, s| s.tick = (n - k) as u64));
    c.add("ticks_reversed", &b, Expect::Refuse);
    let b = r.with(|_, msgs| {
        let dup = msgs
            .iter()
            .rposition(|m| m.schema_name == STATE_TYPE)
            .unwrap();
        let m = msgs[dup].clone();
        msgs.push(m);
    });
    c.add("ticks_duplicated_state", &b, Expect::Refuse);
    // Inputs out of tick order, or stamped before the epoch.
    let b = r.with(|_, msgs| {
        let acts: Vec<usize> = (0..msgs.len())
            .filter(|&i| msgs[i].schema_name == ACTIVATION_TYPE)
            .collect();
        let (first, last) = (acts[0], acts[acts.len() - 1]);
        let tmp = msgs[first].data.clone();
        msgs[first].data = msgs[last].data.clone();
        msgs[last].data = tmp;
    });
    c.add("inputs_out_of_order", &b, Expect::Refuse);
    let b = r.with(|_, msgs| {
        for m in msgs.iter_mut().filter(|m| m.schema_name == ACTIVATION_TYPE) {
            let mut a: ActivationCommand = decode_cdr(&m.data).unwrap();
            a.header.stamp = muscle_actuator_recording::msgs::Time::from_nanos(-5_000_000_000);
            m.data = encode_cdr(&a).unwrap();
        }
    });
    c.add("inputs_negative_stamp", &b, Expect::Refuse);
    // Non-finite values, in states and inputs.
    let values: [(&str, StateEdit); 4] = [
        ("nan_force", |s| s.muscles[0].state.force = f64::NAN),
        ("inf_position", |s| s.joints[0].position = f64::INFINITY),
        ("nan_stiffness_matrix", |s| s.stiffness_matrix[0] = f64::NAN),
        ("neg_inf_fiber", |s| {
            s.muscles[1].state.fiber_length = f64::NEG_INFINITY
        }),
    ];
    for (name, f) in values {
        let b = r.with(|_, msgs| {
            map_states(msgs, |k, s| {
                if k == n / 2 {
                    f(s)
                }
            })
        });
        c.add(&format!("value_{name}"), &b, Expect::Refuse);
    }
    let b = r.with(|_, msgs| {
        map_states(msgs, |k, s| {
            if k == n / 2 {
                s.muscles[0].state.force = 1e300
            }
        })
    });
    c.add("value_1e300_force", &b, Expect::Either);
    let b = r.with(|_, msgs| {
        for m in msgs.iter_mut().filter(|m| m.schema_name == ACTIVATION_TYPE) {
            let mut a: ActivationCommand = decode_cdr(&m.data).unwrap();
            a.excitation.iter_mut().for_each(|u| *u = f64::NAN);
            m.data = encode_cdr(&a).unwrap();
        }
    });
    c.add("value_nan_excitation", &b, Expect::Refuse);
    let b = r.with(|_, msgs| {
        for m in msgs.iter_mut().filter(|m| m.schema_name == LOAD_TYPE) {
            let mut l: ExternalLoad = decode_cdr(&m.data).unwrap();
            l.torque.iter_mut().for_each(|t| *t = f64::INFINITY);
            m.data = encode_cdr(&l).unwrap();
        }
    });
    c.add("value_inf_torque", &b, Expect::Refuse);
    // States that do not match the metadata's muscles and joints.
    let names: [(&str, StateEdit); 4] = [
        ("muscle_renamed", |s| s.muscles[0].name = "intruder".into()),
        ("muscle_dropped", |s| {
            s.muscles.pop();
        }),
        ("joint_renamed", |s| s.joint[0] = "knee".into()),
        ("model_renamed", |s| s.model = "x".repeat(5000)),
    ];
    for (name, f) in names {
        let b = r.with(|_, msgs| map_states(msgs, |_, s| f(s)));
        let expect = if name == "model_renamed" {
            Expect::Either
        } else {
            Expect::Refuse
        };
        c.add(&format!("names_{name}"), &b, expect);
    }
}

/// Offsets of the u32 length prefixes of a CDR message found by what follows them (strings
/// whose text is known).
fn string_prefixes(data: &[u8], texts: &[&str]) -> Vec<usize> {
    let mut out = Vec::new();
    for t in texts {
        let mut needle = ((t.len() + 1) as u32).to_le_bytes().to_vec();
        needle.extend_from_slice(t.as_bytes());
        needle.push(0);
        if let Some(i) = data
            .windows(needle.len())
            .position(|w| w == needle.as_slice())
        {
            out.push(i);
            // A sequence of strings: its element count (small) precedes the first string.
            let count = (i >= 4).then(|| u32::from_le_bytes(data[i - 4..i].try_into().unwrap()));
            if count.is_some_and(|n| (1..=16).contains(&n)) {
                out.push(i - 4);
            }
        }
    }
    out
}

fn hostile_cdr(c: &mut Corpus, r: &Rebuild) {
    for ty in [STATE_TYPE, ACTIVATION_TYPE, LOAD_TYPE, JOINT_STATE_TYPE] {
        let short = ty.rsplit('/').next().unwrap();
        let target = r.msgs.iter().position(|m| m.schema_name == ty).unwrap();
        let data = r.msgs[target].data.clone();
        let prefixes = string_prefixes(&data, &["hill", "elbow", "flexor", "extensor"]);
        for (i, &at) in prefixes.iter().enumerate() {
            for v in [u32::MAX, 0x7fff_ffff, 0x0010_0000] {
                let b = r.with(|_, msgs| put_u32(&mut msgs[target].data, at, v));
                c.add(&format!("cdr_{short}_len{i}_{v:x}"), &b, Expect::Refuse);
            }
        }
        for keep in [0, 2, 4, 8, data.len() / 2, data.len() - 1] {
            let b = r.with(|_, msgs| msgs[target].data.truncate(keep));
            c.add(&format!("cdr_{short}_cut_{keep}"), &b, Expect::Refuse);
        }
        for header in [[0u8, 2, 0, 0], [1, 1, 0, 0], [0xff; 4]] {
            let b = r.with(|_, msgs| msgs[target].data[..4].copy_from_slice(&header));
            c.add(
                &format!("cdr_{short}_encapsulation_{:x}", header[1]),
                &b,
                Expect::Refuse,
            );
        }
    }
}

fn foreign(c: &mut Corpus, r: &Rebuild) {
    let retype = |ty: &'static str, to: &'static str| {
        r.with(move |_, msgs| {
            for m in msgs.iter_mut().filter(|m| m.schema_name == ty) {
                m.schema_name = to.into();
            }
        })
    };
    c.add(
        "schema_state_foreign",
        &retype(STATE_TYPE, "std_msgs/msg/String"),
        Expect::Refuse,
    );
    c.add(
        "schema_state_as_activation",
        &retype(STATE_TYPE, ACTIVATION_TYPE),
        Expect::Refuse,
    );
    c.add(
        "schema_activation_as_state",
        &retype(ACTIVATION_TYPE, STATE_TYPE),
        Expect::Refuse,
    );
    c.add(
        "schema_joint_states_as_state",
        &retype(JOINT_STATE_TYPE, STATE_TYPE),
        Expect::Refuse,
    );
    c.add(
        "schema_activation_foreign",
        &retype(ACTIVATION_TYPE, "geometry_msgs/msg/Twist"),
        Expect::Either,
    );
    let b = r.with(|_, msgs| {
        for m in msgs.iter_mut().filter(|m| m.schema_name == STATE_TYPE) {
            m.encoding = "json".into();
        }
    });
    c.add("encoding_state_json", &b, Expect::Refuse);
    let b = r.with(|_, msgs| {
        for m in msgs.iter_mut() {
            m.schema_encoding = "protobuf".into();
        }
    });
    c.add("encoding_schema_protobuf", &b, Expect::Refuse);
    let chatter = |with_meta: bool| {
        r.with(move |meta, msgs| {
            if !with_meta {
                meta.clear();
            }
            let mut data = vec![0, 1, 0, 0, 6, 0, 0, 0];
            data.extend_from_slice(b"hello\0");
            *msgs = (0..50)
                .map(|i| Msg {
                    topic: "/chatter".into(),
                    schema_name: "std_msgs/msg/String".into(),
                    schema_encoding: "ros2msg".into(),
                    schema_data: b"string data\n".to_vec(),
                    encoding: "cdr".into(),
                    log_time: i * 1_000_000,
                    publish_time: i * 1_000_000,
                    data: data.clone(),
                })
                .collect();
        })
    };
    c.add("foreign_chatter", &chatter(false), Expect::Refuse);
    c.add(
        "foreign_chatter_our_metadata",
        &chatter(true),
        Expect::Refuse,
    );
    c.add(
        "empty_mcap",
        &write_mcap(&vec![], &[], true),
        Expect::Refuse,
    );
    c.add(
        "metadata_only",
        &r.with(|_, msgs| msgs.clear()),
        Expect::Refuse,
    );
}

/// A decompression bomb: 900 MiB of zeros as state messages of 64 KiB, zstd-compressed into
/// chunks of under 1 MiB each, in a file of about 2 MiB (a metadata record of 1 MiB of text
/// keeps every chunk smaller than the file, as a reader may demand).
fn bomb(c: &mut Corpus, r: &Rebuild, rng: &mut Rng) {
    let state = r
        .msgs
        .iter()
        .find(|m| m.schema_name == STATE_TYPE)
        .unwrap()
        .clone();
    let mut w = mcap::WriteOptions::new()
        .profile("ros2")
        .compression(Some(mcap::Compression::Zstd))
        .create(Cursor::new(Vec::new()))
        .unwrap();
    for (name, map) in r.meta {
        w.write_metadata(&mcap::records::Metadata {
            name: name.clone(),
            metadata: map.clone(),
        })
        .unwrap();
    }
    let padding: String = rng
        .bytes(1 << 20)
        .into_iter()
        .map(|b| char::from(b'a' + b % 26))
        .collect();
    w.write_metadata(&mcap::records::Metadata {
        name: "padding".into(),
        metadata: BTreeMap::from([("text".to_string(), padding)]),
    })
    .unwrap();
    let sid = w
        .add_schema(
            &state.schema_name,
            &state.schema_encoding,
            &state.schema_data,
        )
        .unwrap();
    let cid = w
        .add_channel(sid, STATE_TOPIC, "cdr", &BTreeMap::new())
        .unwrap();
    let zeros = vec![0u8; 64 << 10];
    for i in 0..(900u32 << 4) {
        w.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id: cid,
                sequence: i,
                log_time: i as u64 * 1_000_000,
                publish_time: i as u64 * 1_000_000,
            },
            &zeros,
        )
        .unwrap();
    }
    w.finish().unwrap();
    let bytes = w.into_inner().into_inner();
    assert!(
        bytes.len() < 4 << 20,
        "the bomb is small: {} bytes",
        bytes.len()
    );
    c.add("decompression_bomb", &bytes, Expect::Refuse);
}

/// Things that are not recordings at all.
fn not_recordings(c: &mut Corpus, rng: &mut Rng) {
    let dir = c.dir.clone();
    for dev in ["/dev/zero", "/dev/urandom", "/dev/null"] {
        if Path::new(dev).exists() {
            c.add_path(dev, PathBuf::from(dev), Expect::Refuse);
        }
    }
    let fifo = dir.join("fifo.mcap");
    let cpath = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    if unsafe { libc::mkfifo(cpath.as_ptr(), 0o600) } == 0 {
        c.add_path("fifo", fifo, Expect::Refuse);
    }
    c.add_path("directory", dir.join("out"), Expect::Refuse);
    c.add_path("missing", dir.join("no_such_file.mcap"), Expect::Refuse);
    let mb = 4 << 20;
    c.add("zeros_4mb", &vec![0u8; mb], Expect::Refuse);
    c.add("random_4mb", &rng.bytes(mb), Expect::Refuse);
    let mut magic_zeros = MAGIC.to_vec();
    magic_zeros.resize(mb, 0);
    c.add("magic_then_zeros", &magic_zeros, Expect::Refuse);
    let mut magic_random = MAGIC.to_vec();
    magic_random.extend(rng.bytes(mb));
    c.add("magic_then_random", &magic_random, Expect::Refuse);
    c.add("magic_only", MAGIC, Expect::Refuse);
    c.add(
        "magic_twice",
        &[&MAGIC[..], &MAGIC[..]].concat(),
        Expect::Refuse,
    );
    c.add("empty", b"", Expect::Refuse);
    c.add("one_byte", b"\x89", Expect::Refuse);
    // Over the size limit, without writing it: a sparse file (a hole after the magic).
    let sparse = dir.join("sparse_300mb.mcap");
    let f = std::fs::File::create(&sparse).unwrap();
    std::io::Write::write_all(&mut &f, MAGIC).unwrap();
    f.set_len(300 << 20).unwrap();
    c.add_path("sparse_300mb", sparse, Expect::Refuse);
}

/// Whether an accepted run's output is sound: finite figures from `compare --json`, a summary
/// line from `replay`.
/// The commands each hostile file goes through (`compare` against the sound run).
const COMMANDS: [&str; 3] = ["replay", "compare", "export"];

fn accepted_soundly(e: &Ended, command: &str) -> Result<(), String> {
    if command != "compare" {
        let summary = if command == "replay" {
            "replayed "
        } else {
            "exported "
        };
        return if e.stderr.contains(summary) {
            Ok(())
        } else {
            Err(format!(
                "{command} accepted without its summary: {}",
                e.stderr
            ))
        };
    }
    let v: serde_json::Value =
        serde_json::from_str(&e.stdout).map_err(|err| format!("compare output: {err}"))?;
    fn walk(v: &serde_json::Value, key: &str, bad: &mut Vec<String>) {
        match v {
            serde_json::Value::Null if !key.starts_with("rise_time") => bad.push(key.into()),
            serde_json::Value::Number(n) if !n.as_f64().is_some_and(f64::is_finite) => {
                bad.push(key.into())
            }
            serde_json::Value::Array(a) => a.iter().for_each(|x| walk(x, key, bad)),
            serde_json::Value::Object(o) => o.iter().for_each(|(k, x)| walk(x, k, bad)),
            _ => {}
        }
    }
    let mut bad = Vec::new();
    walk(&v, "", &mut bad);
    if bad.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "compare accepted with non-finite figures in {bad:?}"
        ))
    }
}

#[test]
fn hostile_recordings_are_refused_cleanly() {
    let dir = main_dir();
    let base_path = base_recording(&dir);
    let base = std::fs::read(&base_path).unwrap();
    let meta: Meta = read_recording(&base_path, false)
        .unwrap()
        .metadata
        .into_iter()
        .collect();
    let msgs = messages(&base);
    let r = Rebuild {
        meta: &meta,
        msgs: &msgs,
    };
    let mut c = Corpus {
        dir: dir.clone(),
        cases: Vec::new(),
    };
    let mut rng = Rng(0x6d75_7363_6c65);
    c.add_path("control_original", base_path.clone(), Expect::Accept);
    c.add("control_rebuilt", &r.with(|_, _| {}), Expect::Accept);
    c.add(
        "control_unchunked",
        &write_mcap(&meta, &msgs, false),
        Expect::Accept,
    );
    truncations(&mut c, &base, &mut rng);
    bit_flips(&mut c, &base, &mut rng);
    huge_lengths(&mut c, &base);
    hostile_metadata(&mut c, &r);
    hostile_ticks_and_values(&mut c, &r);
    hostile_cdr(&mut c, &r);
    foreign(&mut c, &r);
    bomb(&mut c, &r, &mut rng);
    not_recordings(&mut c, &mut rng);

    let mut runs: Vec<Vec<OsString>> = Vec::new();
    for (i, case) in c.cases.iter().enumerate() {
        let out = dir.join("out").join(format!("{i:03}.mcap"));
        let csv = out.with_extension("csv");
        runs.push(vec![
            "replay".into(),
            case.path.clone().into(),
            "--out".into(),
            out.into(),
        ]);
        runs.push(vec![
            "compare".into(),
            base_path.clone().into(),
            case.path.clone().into(),
            "--json".into(),
        ]);
        runs.push(vec![
            "export".into(),
            case.path.clone().into(),
            "--csv".into(),
            csv.into(),
        ]);
    }
    let ended = child::run_all(&runs, TIME_LIMIT, WORKERS);
    let mut problems = Vec::new();
    let (mut refused, mut accepted) = (0, 0);
    let mut by_expect: BTreeMap<String, (usize, usize)> = BTreeMap::new();
    for (k, e) in ended.iter().enumerate() {
        let case = &c.cases[k / COMMANDS.len()];
        let command = COMMANDS[k % COMMANDS.len()];
        let tally = by_expect.entry(format!("{:?}", case.expect)).or_default();
        if let Some(p) = e.problem() {
            problems.push(format!("{}: {p}", case.name));
            continue;
        }
        if e.accepted() {
            accepted += 1;
            tally.1 += 1;
            if case.expect == Expect::Refuse {
                problems.push(format!(
                    "{}: {} accepted a file it must refuse; stderr: {}",
                    case.name, command, e.stderr
                ));
            } else if let Err(why) = accepted_soundly(e, command) {
                problems.push(format!("{}: {why}", case.name));
            } else if case.expect == Expect::Truncated {
                let warnings: Vec<&str> = e
                    .stderr
                    .lines()
                    .filter(|l| l.starts_with("warning:"))
                    .collect();
                if warnings.len() != 1 || !warnings[0].contains("is truncated (no summary)") {
                    problems.push(format!(
                        "{}: accepted without one truncation warning: {}",
                        case.name, e.stderr
                    ));
                }
            }
        } else {
            refused += 1;
            tally.0 += 1;
            if case.expect == Expect::Accept {
                problems.push(format!("{}: control refused: {}", case.name, e.stderr));
            }
        }
    }
    if std::env::var_os("HOSTILE_VERBOSE").is_some() {
        for (k, e) in ended.iter().enumerate() {
            let verdict = match e.stderr.lines().find(|l| l.starts_with("error: ")) {
                Some(l) if !e.accepted() => l.chars().take(300).collect::<String>(),
                _ => "accepted".into(),
            };
            println!(
                "{} {}: {verdict}",
                c.cases[k / COMMANDS.len()].name,
                COMMANDS[k % COMMANDS.len()]
            );
        }
    }
    let slowest = ended.iter().map(|e| e.elapsed).max().unwrap_or_default();
    println!(
        "hostile MCAP corpus: {} files, {} runs (replay + compare + export): {refused} refused with an \
         `error:` line, {accepted} accepted, {} with problems; by expectation (refused, accepted): \
         {by_expect:?}; slowest run {slowest:?}",
        c.cases.len(),
        ended.len(),
        problems.len()
    );
    child::assert_no_problems(&problems, 40, 700);
    let _ = std::fs::remove_dir_all(&dir);
}
