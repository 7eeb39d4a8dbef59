//! The command line as the integration tests run it: the binary, a temporary directory per test
//! binary, a run that must succeed, a scenario recorded to MCAP, and the top-level records of the
//! files it writes. Included by path (`#[path = "common/cli.rs"] mod cli;`).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The program under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_muscle_actuator"))
}

/// `$TMPDIR/muscle_actuator_<tag>_<pid>`, created.
pub fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("muscle_actuator_{tag}_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Its standard error, as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A refusal: a non-zero exit that is not a panic (101), naming each of `needles` on stderr.
pub fn assert_clean_failure(o: &Output, needles: &[&str]) {
    let err = stderr(o);
    assert!(!o.status.success(), "should fail: {err}");
    assert_ne!(o.status.code(), Some(101), "panicked: {err}");
    assert!(!err.contains("panicked"), "panicked: {err}");
    for n in needles {
        assert!(err.contains(n), "expected {n:?} in: {err}");
    }
}

/// Runs `cmd`, which must succeed.
pub fn run_ok(cmd: &mut Command) -> Output {
    let o = cmd.output().unwrap();
    assert!(o.status.success(), "{cmd:?} failed: {}", stderr(&o));
    o
}

/// `simulate` (Hill model) of the scenario `text`, written as `dir/name.toml` and recorded to
/// `dir/name.mcap`.
pub fn record_scenario(dir: &Path, name: &str, text: &str) -> PathBuf {
    let scenario = dir.join(format!("{name}.toml"));
    std::fs::write(&scenario, text).unwrap();
    let out = dir.join(format!("{name}.mcap"));
    run_ok(
        bin()
            .arg("simulate")
            .arg(&scenario)
            .args(["--model", "hill", "--out"])
            .arg(&out),
    );
    out
}

/// Top-level records of an MCAP file up to its footer: (offset of the opcode, opcode, declared
/// body length). Written out here (nine bytes a record: opcode, u64 LE length) so that tests can
/// cut and damage files at exact places.
pub fn mcap_records(buf: &[u8]) -> Vec<(usize, u8, u64)> {
    let mut out = Vec::new();
    let mut at = 8; // the magic
    while at + 9 <= buf.len() {
        let op = buf[at];
        let len = u64::from_le_bytes(buf[at + 1..at + 9].try_into().unwrap());
        out.push((at, op, len));
        if op == 0x02 {
            break; // the footer
        }
        at = at.saturating_add(9).saturating_add(len as usize);
    }
    out
}

/// A CSV table read with the `csv` crate (RFC 4180 quoting): its header and its rows, every row
/// as long as the header (a ragged row fails the test).
pub fn read_csv(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::ReaderBuilder::new().from_reader(text.as_bytes());
    let header = r.headers().unwrap().iter().map(String::from).collect();
    let rows = r
        .records()
        .map(|row| row.unwrap().iter().map(String::from).collect())
        .collect();
    (header, rows)
}
