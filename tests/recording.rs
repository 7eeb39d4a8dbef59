//! Recordings: the MCAP file as rosbag2 readers expect it (read back with the `mcap` crate),
//! replay bit for bit, compare Hill vs Huxley, and clean errors on damaged files.

use muscle_actuator_recording::msgs::muscle_actuator_msgs::{ActivationCommand, ActuatorState};
use muscle_actuator_recording::recording::{self, decode_cdr, read_recording, schema::SEPARATOR};
use muscle_actuator_recording::runs::{self, compare, load_run};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

#[path = "common/cli.rs"]
mod cli;
use cli::{bin, run_ok};

fn dir() -> PathBuf {
    cli::temp_dir("rec")
}

/// `simulate pulse --model M --out` (once per model per test binary).
fn pulse(model: &str) -> PathBuf {
    static HILL: OnceLock<PathBuf> = OnceLock::new();
    static HUXLEY: OnceLock<PathBuf> = OnceLock::new();
    let cell = if model == "hill" { &HILL } else { &HUXLEY };
    cell.get_or_init(|| {
        let p = dir().join(format!("pulse_{model}.mcap"));
        run_ok(
            bin()
                .args(["simulate", "pulse", "--model", model, "--out"])
                .arg(&p),
        );
        p
    })
    .clone()
}

#[test]
fn file_is_rosbag2_mcap() {
    let path = pulse("hill");
    let buf = std::fs::read(&path).unwrap();
    let mut topics = std::collections::BTreeMap::new();
    for m in mcap::MessageStream::new(&buf).unwrap() {
        let m = m.unwrap();
        let ch = &m.channel;
        assert_eq!(ch.message_encoding, "cdr");
        assert!(ch.metadata["offered_qos_profiles"].contains("reliability: reliable"));
        let schema = ch.schema.as_ref().unwrap();
        assert_eq!(schema.encoding, "ros2msg");
        let text = std::str::from_utf8(&schema.data).unwrap();
        assert!(text.contains(&format!("{SEPARATOR}\nMSG: std_msgs/Header\n")));
        assert!(text.contains(&format!("{SEPARATOR}\nMSG: builtin_interfaces/Time\n")));
        if schema.name.ends_with("ActuatorState") {
            assert!(text.contains("MSG: muscle_actuator_msgs/MuscleState"));
        }
        assert_eq!(&m.data[..4], &recording::CDR_LE_HEADER);
        *topics.entry(ch.topic.clone()).or_insert(0) += 1;
    }
    assert_eq!(topics["/muscle_actuator/state"], 3001);
    // The pulse switches the excitation on and off: three commands (0, 1, 0).
    assert_eq!(topics["/muscle_actuator/activation"], 3);
    let rec = read_recording(&path, false).unwrap();
    assert_eq!(rec.profile, "ros2");
    assert!(rec.metadata["rosbag2"]["serialized_metadata"].contains("message_count: 3004"));
    let ours = &rec.metadata[runs::METADATA_NAME];
    assert_eq!(ours["model"], "hill");
    assert_eq!(ours["rate_hz"], "1000.0");
    assert!(ours.contains_key("config_toml") && ours.contains_key("program_version"));
    // Offline: log times and stamps are simulated time from zero, and the metadata says so.
    assert_eq!(ours["time_base"], "simulated");
    assert!(!ours.contains_key("tick_origin_ns"));
    // Values: the 1 s excitation step takes effect at tick 1000 (stamp 1.0 s).
    let acts: Vec<ActivationCommand> = rec
        .on("/muscle_actuator/activation")
        .map(|m| decode_cdr(&m.data).unwrap())
        .collect();
    assert_eq!(acts[1].excitation, vec![1.0]);
    assert_eq!(acts[1].header.stamp.to_nanos(), 1_000_000_000);
    let last: ActuatorState =
        decode_cdr(&rec.on("/muscle_actuator/state").last().unwrap().data).unwrap();
    assert_eq!(last.tick, 3000);
    assert_eq!(last.model, "hill");
}

#[test]
fn recorder_round_trip_and_errors() {
    use muscle_actuator_recording::recording::{Recorder, RecorderOptions, RecorderState};
    let path = dir().join("round_trip.mcap");
    let ch = runs::channel("/x", runs::ACTIVATION_TYPE).unwrap();
    let rec = Recorder::start(&path, vec![ch.clone()], vec![], RecorderOptions::default()).unwrap();
    let mut sent = Vec::new();
    for i in 0..100u64 {
        let msg = ActivationCommand {
            header: Default::default(),
            muscle: vec!["flexor".into()],
            excitation: vec![i as f64 / 100.0],
        };
        assert!(rec.record_blocking(0, i, i, recording::encode_cdr(&msg).unwrap()));
        sent.push(msg);
    }
    // A metadata record learnt while recording (a node following /clock learns its tick
    // origin at the first clock message): written after what was queued before it; a reader
    // keeps the last record of a name, a recovery keeps both where they were.
    let tagged = |v: &str| std::collections::BTreeMap::from([("k".to_string(), v.to_string())]);
    let rec = {
        let rec = rec;
        let sender = rec.sender();
        assert!(sender.metadata("late", tagged("1")));
        assert!(sender.metadata("late", tagged("2")));
        rec
    };
    assert_eq!(rec.finish(), RecorderState::Finished);
    let back = read_recording(&path, false).unwrap();
    assert_eq!(back.metadata["late"], tagged("2"));
    let late: Vec<(usize, &str)> = (back.metadata_records.iter())
        .filter(|(_, m)| m.name == "late")
        .map(|(before, m)| (*before, m.metadata["k"].as_str()))
        .collect();
    assert_eq!(late, vec![(100, "1"), (100, "2")]);
    let recovered = dir().join("round_trip_recovered.mcap");
    recording::recover::recover(&path, &recovered).unwrap();
    assert_eq!(
        read_recording(&recovered, false).unwrap().metadata["late"],
        tagged("2")
    );
    let got: Vec<ActivationCommand> = back
        .messages
        .iter()
        .map(|m| decode_cdr(&m.data).unwrap())
        .collect();
    assert_eq!(got, sent);

    // Unwritable places: the error names the path; nothing panics.
    let file = dir().join("a_file");
    std::fs::write(&file, "x").unwrap();
    let e = Recorder::start(
        &file.join("sub/run.mcap"),
        vec![ch.clone()],
        vec![],
        RecorderOptions::default(),
    )
    .err()
    .unwrap();
    assert!(e.to_string().contains("a_file"), "{e}");
    // A full device: the start fails or the recording stops with a report.
    if Path::new("/dev/full").exists() {
        match Recorder::start(
            Path::new("/dev/full"),
            vec![ch],
            vec![],
            RecorderOptions::default(),
        ) {
            Err(e) => assert!(e.to_string().contains("/dev/full"), "{e}"),
            Ok(r) => {
                for i in 0..10_000u64 {
                    r.record(0, i, i, vec![0, 1, 0, 0, 0, 0, 0, 0]);
                }
                assert!(matches!(r.finish(), RecorderState::Failed(_)));
            }
        }
    }
}

#[test]
fn replay_is_bit_identical() {
    let src = pulse("hill");
    let out = dir().join("replay_hill.mcap");
    let o = run_ok(bin().arg("replay").arg(&src).arg("--out").arg(&out));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("3001 of 3001 recorded states reproduced bit for bit"),
        "{err}"
    );
    let a = load_run(&src).unwrap();
    let b = load_run(&out).unwrap();
    assert_eq!(
        b.meta.time_base,
        muscle_actuator_core::time::TimeBase::Simulated
    );
    assert_eq!(a.states, b.states);
    assert_eq!(a.activations, b.activations);

    // Replaying the Hill run with Huxley gives a valid, different run.
    let hux = dir().join("replay_hill_as_huxley.mcap");
    run_ok(
        bin()
            .arg("replay")
            .arg(&src)
            .args(["--model", "huxley", "--out"])
            .arg(&hux),
    );
    let c = compare::compare_files(&src, &hux, None).unwrap();
    let force = c
        .signals
        .iter()
        .find(|s| s.signal == "flexor.force")
        .unwrap();
    assert!(force.max_abs_diff > 1.0 && force.rms_diff.is_finite());
}

#[test]
fn compare_hill_and_huxley_pulse() {
    let (hill, hux) = (pulse("hill"), pulse("huxley"));
    let plot = dir().join("cmp.png");
    let o = run_ok(
        bin()
            .arg("compare")
            .arg(&hill)
            .arg(&hux)
            .arg("--plot")
            .arg(&plot),
    );
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(table.contains("flexor.force"), "{table}");
    assert!(plot.exists());
    // Both tables' rows as long as their header, the longest name included: the columns line
    // up.
    let mut tables = table.lines().skip(1).collect::<Vec<_>>();
    tables.retain(|l| !l.is_empty());
    assert!(tables
        .iter()
        .any(|l| l.starts_with("flexor.phenomenological_energy ")));
    let (signals, energies) =
        tables.split_at(tables.iter().position(|l| l.starts_with("energy")).unwrap());
    for rows in [signals, energies] {
        let len = rows[0].chars().count();
        assert!(rows.iter().all(|l| l.chars().count() == len), "{table}");
    }
    let o = run_ok(bin().arg("compare").arg(&hill).arg(&hux).arg("--json"));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["model_b"], "huxley");

    // Plateau force at t = 1.9 s within 1 %; a different rise.
    let at = |p: &Path| {
        load_run(p)
            .unwrap()
            .states
            .iter()
            .find(|s| s.tick == 1900)
            .unwrap()
            .muscles[0]
            .state
            .force
    };
    let (fa, fb) = (at(&hill), at(&hux));
    assert!((fa - fb).abs() < 0.01 * fa.abs(), "{fa} vs {fb}");
    let c = compare::compare_files(&hill, &hux, None).unwrap();
    let f = c
        .signals
        .iter()
        .find(|s| s.signal == "flexor.force")
        .unwrap();
    let (ra, rb) = (f.rise_time_a.unwrap(), f.rise_time_b.unwrap());
    assert!((ra - rb).abs() > 0.005, "rise {ra} vs {rb}");
    assert!(f.rms_diff > 1.0);

    // What each run spent: the rise of its recorded energy over the span, and the RMS of its
    // recorded power, computed here from the states.
    let spent = |p: &Path| {
        let run = load_run(p).unwrap();
        let m = |i: usize| run.states[i].muscles[0].state;
        let n = run.states.len();
        let rms = (run
            .states
            .iter()
            .map(|s| s.muscles[0].state.metabolic_power.powi(2))
            .sum::<f64>()
            / n as f64)
            .sqrt();
        (m(n - 1).metabolic_energy - m(0).metabolic_energy, rms)
    };
    let (e, json_e) = (&c.energies[0], &json["energies"][0]);
    assert_eq!(e.muscle, "flexor");
    for (got, (energy, rms)) in [
        ((e.energy_a_j, e.rms_power_a_w), spent(&hill)),
        ((e.energy_b_j, e.rms_power_b_w), spent(&hux)),
    ] {
        assert!(energy > 100.0, "{energy} J");
        assert!(
            (got.0 - energy).abs() <= 1e-9 * energy,
            "{} J against {energy} J",
            got.0
        );
        assert!(
            (got.1 - rms).abs() <= 1e-9 * rms,
            "{} W against {rms} W",
            got.1
        );
    }
    assert_eq!(json_e["energy_b_j"].as_f64(), Some(e.energy_b_j));
    assert!(table.contains("energy over the span"), "{table}");

    // Incomparable: different muscles (a joint run has two).
    let joint = dir().join("joint.toml");
    std::fs::write(
        &joint,
        "name = \"j\"\nduration = 0.05\nattachment = \"joint\"\n",
    )
    .unwrap();
    let jrun = dir().join("joint.mcap");
    run_ok(
        bin()
            .arg("simulate")
            .arg(&joint)
            .args(["--model", "hill", "--out"])
            .arg(&jrun),
    );
    let o = bin().arg("compare").arg(&hill).arg(&jrun).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("different muscles"),
        "{err}"
    );
}

#[test]
fn damaged_files_are_clean_errors() {
    let src = std::fs::read(pulse("huxley")).unwrap();
    let truncated = dir().join("truncated.mcap");
    std::fs::write(&truncated, &src[..src.len() * 2 / 3]).unwrap();
    let mut corrupt = src.clone();
    let mid = corrupt.len() / 2;
    for b in &mut corrupt[mid..mid + 64] {
        *b ^= 0x5a;
    }
    let corrupted = dir().join("corrupted.mcap");
    std::fs::write(&corrupted, &corrupt).unwrap();
    let garbage = dir().join("garbage.mcap");
    std::fs::write(&garbage, b"not an mcap file at all").unwrap();
    let good = pulse("huxley");
    // A complete file damaged inside, no MCAP file at all, or a file cut inside its one chunk of
    // messages (nothing whole to read) is refused.
    for bad in [&truncated, &corrupted, &garbage] {
        for args in [
            vec![
                "replay".into(),
                bad.clone(),
                "--out".into(),
                dir().join("x.mcap"),
            ],
            vec!["compare".into(), good.clone(), bad.clone()],
        ] {
            let o = bin().args(&args).output().unwrap();
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(!o.status.success(), "{args:?} should fail");
            assert_ne!(o.status.code(), Some(101), "panicked: {err}");
            assert!(err.contains(bad.to_str().unwrap()), "{err}");
            assert_eq!(err.lines().count(), 1, "{err}");
        }
    }
    // A file cut in its summary (a crash) is read up to the cut, with one warning.
    let cut_late = dir().join("cut_late.mcap");
    std::fs::write(&cut_late, &src[..src.len() - 1000]).unwrap();
    let o = bin()
        .arg("replay")
        .arg(&cut_late)
        .arg("--out")
        .arg(dir().join("x.mcap"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert_eq!(
        err.lines().filter(|l| l.starts_with("warning:")).count(),
        1,
        "{err}"
    );
    assert!(err.contains(cut_late.to_str().unwrap()), "{err}");
    // A truncated file still yields the whole chunks flushed before the cut, and no more.
    let rec = read_recording(&cut_late, true).unwrap();
    assert!(rec.stopped_early.is_some());
    assert!(!rec.messages.is_empty());
    assert!(read_recording(&cut_late, false).is_err());
    let rec = read_recording(&truncated, true).unwrap();
    assert!(rec.stopped_early.is_some() && rec.messages.is_empty());
}

/// A whole limb records, replays bit for bit, replays with another model, and compares per
/// muscle and per joint; its metadata carries the configuration (moment-arm polynomials
/// included) that replay rebuilds it from.
#[test]
fn limb_runs_record_replay_and_compare() {
    let scenario = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/arm_biceps.toml");
    let arm = dir().join("arm_hill.mcap");
    run_ok(
        bin()
            .args([
                "simulate", scenario, "--config", "arm", "--model", "hill", "--out",
            ])
            .arg(&arm),
    );
    let run = load_run(&arm).unwrap();
    assert_eq!(run.meta.joints, ["shoulder", "elbow"]);
    assert_eq!(run.meta.muscles.len(), 6);
    assert_eq!(
        run.meta.config,
        muscle_actuator_core::config::ActuatorConfig::resolve("arm").unwrap()
    );
    let last = run.states.last().unwrap();
    assert_eq!(last.joints.len(), 2);
    assert_eq!(last.stiffness_matrix.len(), 4);
    assert!(
        last.joints[1].position > 0.01,
        "the biceps flexes the elbow"
    );

    let again = dir().join("arm_again.mcap");
    let s = runs::replay(&arm, None, &again).unwrap();
    assert_eq!((s.compared, s.identical), (601, 601), "{s:?}");
    let as_dm = dir().join("arm_as_huxley.mcap");
    runs::replay(
        &arm,
        Some(muscle_actuator_core::physics::models::ModelKind::HUXLEY),
        &as_dm,
    )
    .unwrap();
    let c = compare::compare_files(&arm, &as_dm, None).unwrap();
    for signal in [
        "BIClong.force",
        "TRIlong.fiber_length",
        "shoulder.position",
        "elbow.stiffness",
    ] {
        assert!(
            c.signals.iter().any(|d| d.signal == signal),
            "{signal} missing from the comparison"
        );
    }
    let elbow = c
        .signals
        .iter()
        .find(|d| d.signal == "elbow.position")
        .unwrap();
    // The models differ, but not by more than a fifth of the elbow's swing.
    assert!(
        elbow.max_abs_diff > 0.0 && elbow.max_abs_diff < 0.2 * elbow.peak_a.abs(),
        "{elbow:?}"
    );
}
