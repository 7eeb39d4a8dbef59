//! `scripts/check-structure.py` (file sizes, function lengths, import cycles) on the two fixture
//! trees of tests/structure_fixtures/ (README.md there): it fails on `tangled/` and names each
//! problem, and passes on `clean/`. Needs python3 (as the ROS tests do).

use std::path::Path;
use std::process::Command;

/// Runs the check on one fixture with the fixtures' limits; (exit code, stdout).
fn check(fixture: &str, extra: &[&str]) -> (i32, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = root.join("tests/structure_fixtures").join(fixture);
    let out = Command::new("python3")
        .arg(root.join("scripts/check-structure.py"))
        .arg("--src")
        .arg(dir.join("src"))
        .args(["--max-file-lines", "40", "--max-fn-lines", "20"])
        .args(extra)
        .output()
        .expect("python3 runs scripts/check-structure.py");
    let stdout = String::from_utf8(out.stdout).unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.is_empty(), "stderr: {stderr}");
    (out.status.code().expect("an exit code"), stdout)
}

#[test]
fn a_tangled_tree_fails_with_each_problem_named() {
    let (code, out) = check("tangled", &["--graph"]);
    assert_eq!(code, 1, "{out}");
    for expected in [
        "FAIL src/big.rs: 42 lines of non-test code (limit 40)",
        "FAIL src/parts/right.rs:13: fn long_function is 21 lines (limit 20)",
        "FAIL import cycle within crate: feeder -> store -> feeder",
        "    feeder -> store: src/feeder.rs:4: use crate::store::Shelf",
        "    store -> feeder: src/store.rs:6: crate::feeder::Feed",
        "FAIL import cycle within parts: parts::left -> parts::right -> parts::left",
        "    parts::right -> parts::left: src/parts/right.rs:3: use crate::parts::Left",
        "module graph within crate:\n  feeder -> big, store\n  store -> feeder\n",
        "check-structure: 4 problem(s) in 7 files",
    ] {
        assert!(out.contains(expected), "missing {expected:?} in:\n{out}");
    }
    // Test code counts for nothing: not its length, not its imports (big's tests use feeder).
    assert!(!out.contains("a_long_test_function"), "{out}");
    assert!(!out.contains("big ->"), "{out}");
}

#[test]
fn a_clean_tree_passes_and_names_its_exceptions() {
    let exceptions =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/structure_fixtures/clean/exceptions.txt");
    let (code, out) = check("clean", &["--exceptions", exceptions.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}");
    for expected in [
        "excepted: src/table.rs:4: fn long_but_excepted, 24 lines (a table of 20 steps that \
         reads best as one list)",
        "note: exception src/table.rs::gone is not needed any more",
        "check-structure: 7 files of ",
    ] {
        assert!(out.contains(expected), "missing {expected:?} in:\n{out}");
    }
    assert!(!out.contains("FAIL"), "{out}");
}

#[test]
fn without_its_exception_the_long_function_fails() {
    let (code, out) = check("clean", &[]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("FAIL src/table.rs:4: fn long_but_excepted is 24 lines (limit 20)"),
        "{out}"
    );
}

#[test]
fn an_exception_needs_a_reason() {
    let path =
        std::env::temp_dir().join(format!("structure-exceptions-{}.txt", std::process::id()));
    std::fs::write(&path, "src/table.rs::long_but_excepted\n").unwrap();
    let (code, out) = check("clean", &["--exceptions", path.to_str().unwrap()]);
    std::fs::remove_file(&path).unwrap();
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("an exception needs a reason"), "{out}");
    assert!(out.contains("fn long_but_excepted is 24 lines"), "{out}");
}
