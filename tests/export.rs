//! `export`: a recording's states as the CSV of `simulate --csv`, byte for byte, and one
//! `error:` line for input that is not a sound recording.

use std::path::{Path, PathBuf};

#[path = "common/cli.rs"]
mod cli;
use cli::{bin, run_ok};

fn dir() -> PathBuf {
    cli::temp_dir("export")
}

/// `simulate ARGS --csv A --out R`, then `export R --csv B`: (A, B) as text.
fn simulate_and_export(tag: &str, args: &[&str]) -> (String, String) {
    let d = dir();
    let (a, r, b) = (
        d.join(format!("{tag}_simulate.csv")),
        d.join(format!("{tag}.mcap")),
        d.join(format!("{tag}_export.csv")),
    );
    run_ok(
        bin()
            .arg("simulate")
            .args(args)
            .arg("--csv")
            .arg(&a)
            .arg("--out")
            .arg(&r),
    );
    run_ok(bin().arg("export").arg(&r).arg("--csv").arg(&b));
    (
        std::fs::read_to_string(a).unwrap(),
        std::fs::read_to_string(b).unwrap(),
    )
}

/// The first line that differs, for a readable failure.
fn assert_same_text(a: &str, b: &str) {
    assert_eq!(a.lines().count(), b.lines().count(), "row counts differ");
    for (i, (x, y)) in a.lines().zip(b.lines()).enumerate() {
        assert_eq!(x, y, "line {} differs", i + 1);
    }
    assert_eq!(a, b);
}

#[test]
fn export_of_a_joint_run_is_simulates_csv() {
    // Six muscles over two joints (the arm), some spanning one joint only: filled and empty
    // joint columns, joint inputs, adaptive sub-steps.
    let scenario = dir().join("export_arm.toml");
    std::fs::write(
        &scenario,
        "name = \"export-arm\"\nduration = 0.2\nattachment = \"joint\"\n\
         [[input]]\nsignal = \"excitation\"\nmuscle = \"BIClong\"\nkind = \"pulse\"\n\
         start = 0.02\nend = 0.12\nvalue = 0.6\n\
         [[input]]\nsignal = \"external_torque\"\nkind = \"step\"\nat = 0.05\nto = 0.3\n",
    )
    .unwrap();
    let (a, b) = simulate_and_export(
        "arm",
        &[
            scenario.to_str().unwrap(),
            "--config",
            "arm",
            "--model",
            "hill",
        ],
    );
    assert_same_text(&a, &b);
    // The comparison covers what it should: the header with both joints' columns, the initial
    // state and 200 ticks for 6 muscles, rows with and without joint values, moving numbers.
    let header = a.lines().next().unwrap();
    assert!(header.starts_with("time,name,excitation,activation,force,"));
    assert!(header.ends_with(",elbow.external_torque,elbow.stiffness"));
    assert!(header.contains(",shoulder.position,"));
    assert_eq!(a.lines().count(), 1 + 201 * 6);
    assert!(a.lines().skip(1).any(|l| l.contains(",,,,,")));
    assert!(a.lines().skip(1).any(|l| !l.contains(",,")));
    let last = a.lines().last().unwrap();
    assert!(last.starts_with("0.2,"), "{last}");
    assert_ne!(
        a.lines().nth(1).unwrap(),
        a.lines().nth(1 + 6 * 100).unwrap()
    );
}

#[test]
fn export_of_a_clamped_run_is_simulates_csv() {
    let (a, b) = simulate_and_export("pulse", &["pulse", "--model", "huxley"]);
    assert_same_text(&a, &b);
    assert_eq!(a.lines().count(), 1 + 3001);
    assert!(a
        .lines()
        .next()
        .unwrap()
        .ends_with(",phenomenological_energy"));
}

/// `export` of `input`: fails with one `error:` line naming the problem, writes no CSV.
fn refused(input: &Path, what: &str) {
    let out = dir().join(format!("refused_{what}.csv"));
    let o = bin()
        .arg("export")
        .arg(input)
        .arg("--csv")
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{what}: accepted: {err}");
    assert_eq!(err.lines().count(), 1, "{what}: {err}");
    assert!(err.starts_with("error: "), "{what}: {err}");
    assert!(o.stdout.is_empty(), "{what}");
    assert!(!out.exists(), "{what}: a CSV was written");
}

#[test]
fn export_refuses_what_is_not_a_sound_recording() {
    let d = dir();
    let text = d.join("not_mcap.mcap");
    std::fs::write(&text, "time,name\n0,flexor\n").unwrap();
    refused(&text, "text");
    refused(&d.join("missing.mcap"), "missing");

    // A recording cut short before its first whole chunk: nothing is readable, so refused (cut
    // later, it is read up to the cut with one warning: tests/hostile_files.rs).
    let r = d.join("to_cut.mcap");
    run_ok(
        bin()
            .args(["simulate", "pulse", "--model", "hill", "--out"])
            .arg(&r),
    );
    let bytes = std::fs::read(&r).unwrap();
    let cut = d.join("cut.mcap");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    refused(&cut, "truncated");
}
