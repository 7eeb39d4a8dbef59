//! Every file an offline command writes is written whole or not at all: under a hidden temporary
//! name beside it (`.NAME.tmp-…`), renamed into place once complete. After success the output
//! holds what the command writes and no temporary is left; a command killed while writing leaves
//! no file under the output's name (and an output that existed byte for byte as it was); a write
//! that fails (directory missing, file-size limit reached mid-way) gives one `error:` line naming
//! the output and leaves neither the output nor a temporary.

use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::path::{Path, PathBuf};
use std::process::{Output, Stdio};
use std::time::{Duration, Instant};

#[path = "common/cli.rs"]
mod cli;
use cli::{bin, run_ok, stderr};

/// A fresh, empty directory for one test.
fn fresh(tag: &str) -> PathBuf {
    let d = cli::temp_dir("atomic").join(tag);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Removes a test's directory, and the one of this test binary once it is empty.
fn remove(dir: &Path) {
    std::fs::remove_dir_all(dir).unwrap();
    let _ = std::fs::remove_dir(dir.parent().unwrap());
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// The temporaries in `dir` (of any output).
fn temporaries(dir: &Path) -> Vec<String> {
    names(dir)
        .into_iter()
        .filter(|n| n.starts_with('.') && n.contains(".tmp-"))
        .collect()
}

/// The temporary of `target`, if one is in its directory.
fn temporary_of(target: &Path) -> Option<PathBuf> {
    let prefix = format!(".{}.tmp-", target.file_name()?.to_string_lossy());
    let dir = target.parent()?;
    names(dir)
        .into_iter()
        .find(|n| n.starts_with(&prefix))
        .map(|n| dir.join(n))
}

fn s(p: &Path) -> String {
    p.to_string_lossy().into_owned()
}

fn read(p: &Path) -> Vec<u8> {
    std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// A complete MCAP file: the magic at both ends.
fn assert_whole_mcap(p: &Path) {
    let b = read(p);
    let magic = b"\x89MCAP0\r\n";
    assert!(
        b.len() > 16 && b.starts_with(magic) && b.ends_with(magic),
        "{} is no complete MCAP file ({} bytes)",
        p.display(),
        b.len()
    );
}

/// A complete PNG (signature, IEND last) or SVG (closing tag last).
fn assert_whole_image(p: &Path) {
    let b = read(p);
    let whole = match p.extension().and_then(|e| e.to_str()) {
        Some("png") => b.starts_with(b"\x89PNG\r\n\x1a\n") && b.ends_with(b"IEND\xae\x42\x60\x82"),
        Some("svg") => String::from_utf8_lossy(&b).trim_end().ends_with("</svg>"),
        _ => false,
    };
    assert!(
        whole,
        "{} is not a complete image ({} bytes)",
        p.display(),
        b.len()
    );
}

/// `got` is `expected`, byte for byte (said with their sizes, not their bytes).
fn assert_same(got: &[u8], expected: &[u8], what: &str) {
    assert!(
        got == expected,
        "{what}: {} bytes, expected {} bytes{}",
        got.len(),
        expected.len(),
        match got.iter().zip(expected).position(|(a, b)| a != b) {
            Some(i) => format!(", first difference at byte {i}"),
            None => String::new(),
        }
    );
}

/// Standard output of a command that must succeed.
fn stdout_of(args: &[String]) -> Vec<u8> {
    run_ok(bin().args(args)).stdout
}

#[test]
fn every_command_writes_its_output_whole_and_leaves_no_temporary() {
    let d = fresh("success");
    let (sim_csv, sim_mcap) = (d.join("sim.csv"), d.join("sim.mcap"));
    // An output that exists is replaced.
    std::fs::write(&sim_csv, "an older run\n").unwrap();
    let pulse = ["simulate", "pulse", "--model", "hill"].map(String::from);
    let mut args = pulse.to_vec();
    args.extend(["--csv".into(), s(&sim_csv), "--out".into(), s(&sim_mcap)]);
    run_ok(bin().args(&args));
    let csv = stdout_of(&[&pulse[..], &["--csv".to_string(), "-".to_string()][..]].concat());
    assert!(csv.len() > 1000);
    assert_same(&read(&sim_csv), &csv, "simulate --csv");
    assert_whole_mcap(&sim_mcap);

    let export = d.join("export.csv");
    run_ok(bin().args(["export", &s(&sim_mcap), "--csv", &s(&export)]));
    assert_same(&read(&export), &csv, "export --csv");

    let replayed = d.join("replayed.mcap");
    run_ok(bin().args(["replay", &s(&sim_mcap), "--out", &s(&replayed)]));
    assert_whole_mcap(&replayed);
    let again = stdout_of(&["export".into(), s(&replayed), "--csv".into(), "-".into()]);
    assert_same(&again, &csv, "replay --out");

    let recovered = d.join("recovered.mcap");
    run_ok(bin().args(["recover", &s(&sim_mcap), &s(&recovered)]));
    assert_whole_mcap(&recovered);
    let again = stdout_of(&["export".into(), s(&recovered), "--csv".into(), "-".into()]);
    assert_same(&again, &csv, "recover");

    let plot = d.join("cmp.png");
    run_ok(bin().args(["compare", &s(&sim_mcap), &s(&replayed), "--plot", &s(&plot)]));
    assert_whole_image(&plot);
    assert_whole_image(&plot.with_extension("svg"));

    let steady = d.join("steady.csv");
    run_ok(bin().args(["steady", "--model", "hill", "--csv", &s(&steady)]));
    let expected = stdout_of(&["steady", "--model", "hill", "--csv", "-"].map(String::from));
    assert_same(&read(&steady), &expected, "steady --csv");

    let figures = d.join("figures");
    let o = run_ok(bin().args(["figures", "--out", &s(&figures)]));
    assert_same(
        &read(&figures.join("summary.md")),
        &o.stdout,
        "figures summary.md",
    );
    // Markdown: a blank line before every heading but the first.
    let md = String::from_utf8_lossy(&o.stdout);
    let lines: Vec<&str> = md.lines().collect();
    for (k, l) in lines.iter().enumerate().skip(1) {
        if l.starts_with('#') {
            assert_eq!(lines[k - 1], "", "no blank line before {l:?}");
        }
    }
    let images: Vec<String> = names(&figures)
        .into_iter()
        .filter(|n| n.ends_with(".png") || n.ends_with(".svg"))
        .collect();
    assert!(images.len() >= 16, "{images:?}");
    for n in &images {
        assert_whole_image(&figures.join(n));
    }
    assert_eq!(temporaries(&figures), Vec::<String>::new());
    assert_eq!(temporaries(&d), Vec::<String>::new());
    remove(&d);
}

/// Starts `args`, waits until the temporary of `target` holds at least `min_bytes` (the command
/// is writing it), kills the command with SIGKILL and checks that it was still running.
fn kill_while_writing(args: &[String], target: &Path, min_bytes: u64) {
    let mut child = bin()
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        let size = temporary_of(target)
            .and_then(|t| std::fs::metadata(t).ok())
            .map(|m| m.len());
        if size.is_some_and(|n| n >= min_bytes) {
            break;
        }
        if let Some(status) = child.try_wait().unwrap() {
            panic!(
                "{args:?} ended ({status}) before it was seen writing {}",
                target.display()
            );
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "{args:?}: no temporary of {}",
            target.display()
        );
        std::thread::sleep(Duration::from_millis(1));
    }
    child.kill().unwrap();
    let status = child.wait().unwrap();
    assert_eq!(
        status.signal(),
        Some(libc::SIGKILL),
        "{args:?} finished before the kill"
    );
}

#[test]
fn a_command_killed_while_writing_leaves_no_file_under_the_output_name() {
    let d = fresh("killed");
    // 200 s of a clamped Hill muscle at 1 kHz: long enough to be killed mid-way.
    let scenario = d.join("long.toml");
    std::fs::write(
        &scenario,
        "name = \"long\"\nduration = 200.0\nattachment = \"clamped\"\n[[input]]\n\
         signal = \"excitation\"\nkind = \"sine\"\namplitude = 0.4\nfrequency = 1.0\n\
         offset = 0.5\n",
    )
    .unwrap();
    let simulate = |flag: &str, out: &Path| {
        ["simulate", &s(&scenario), "--model", "hill", flag, &s(out)].map(String::from)
    };
    // The recording is written as the run goes; its temporary has the header at once.
    let fresh_mcap = d.join("fresh.mcap");
    kill_while_writing(&simulate("--out", &fresh_mcap), &fresh_mcap, 1);
    assert!(
        !fresh_mcap.exists(),
        "a killed run left {}",
        fresh_mcap.display()
    );
    // An output that existed is left as it was, byte for byte.
    let kept = b"an earlier, complete output\n".to_vec();
    let old_mcap = d.join("old.mcap");
    std::fs::write(&old_mcap, &kept).unwrap();
    kill_while_writing(&simulate("--out", &old_mcap), &old_mcap, 1);
    assert_same(
        &read(&old_mcap),
        &kept,
        "the killed run's existing recording",
    );
    // The CSV is written after the run: killed with a megabyte of it written.
    let old_csv = d.join("old.csv");
    std::fs::write(&old_csv, &kept).unwrap();
    kill_while_writing(&simulate("--csv", &old_csv), &old_csv, 1 << 20);
    assert_same(&read(&old_csv), &kept, "the killed run's existing CSV");
    // `figures`, killed while it draws Fig. 6 (after the pulse's figures): that figure is not
    // there, whatever is under a figure's name is complete, and summary.md (written last) is
    // not there.
    let figures = d.join("figures");
    let drawn = figures.join("fig6_energy_10hz.png");
    std::fs::create_dir_all(&figures).unwrap();
    kill_while_writing(&["figures".into(), "--out".into(), s(&figures)], &drawn, 0);
    assert!(!drawn.exists());
    let written: Vec<String> = names(&figures)
        .into_iter()
        .filter(|n| !n.starts_with('.'))
        .collect();
    assert!(
        written.contains(&"fig4_pulse_ce_force.png".to_string()),
        "{written:?}"
    );
    for n in &written {
        assert_whole_image(&figures.join(n));
    }
    remove(&d);
}

/// Largest file the commands below may write, bytes (RLIMIT_FSIZE): each of their outputs is
/// larger, so each write fails part-way (EFBIG, SIGXFSZ ignored).
const FILE_SIZE_LIMIT: u64 = 16 << 10;

/// `args` run with files limited to [`FILE_SIZE_LIMIT`] bytes.
fn run_limited(args: &[String]) -> Output {
    let mut cmd = bin();
    cmd.args(args);
    // SAFETY: setrlimit and signal are async-signal-safe and touch no memory of the parent.
    unsafe {
        cmd.pre_exec(|| {
            let lim = libc::rlimit {
                rlim_cur: FILE_SIZE_LIMIT as libc::rlim_t,
                rlim_max: FILE_SIZE_LIMIT as libc::rlim_t,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            // Ignored: a write past the limit fails with EFBIG instead of killing the process.
            libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
            Ok(())
        });
    }
    cmd.output().unwrap()
}

/// The command line `words` followed by `target`, and `target`.
fn case(words: &[&str], target: &Path) -> (Vec<String>, PathBuf) {
    let mut args: Vec<String> = words.iter().map(|w| w.to_string()).collect();
    args.push(s(target));
    (args, target.to_path_buf())
}

/// A clean failure: not a panic, exactly one `error:` line, naming `target` and no temporary.
fn assert_one_error_line(args: &[String], o: &Output, target: &Path) {
    let err = stderr(o);
    assert!(!o.status.success(), "{args:?} should fail: {err}");
    assert_ne!(o.status.code(), Some(101), "{args:?} panicked: {err}");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    let errors: Vec<&str> = err.lines().filter(|l| l.starts_with("error: ")).collect();
    assert_eq!(errors.len(), 1, "{args:?}: {err}");
    assert!(errors[0].contains(&s(target)), "{args:?}: {err}");
    assert!(
        !err.contains(".tmp-"),
        "{args:?} names its temporary: {err}"
    );
}

#[test]
fn a_failing_write_gives_one_error_line_and_leaves_nothing() {
    let d = fresh("failing");
    let input = d.join("input.mcap");
    run_ok(bin().args(["simulate", "pulse", "--model", "hill", "--out", &s(&input)]));
    let other = d.join("other.mcap");
    std::fs::copy(&input, &other).unwrap();
    assert!(std::fs::metadata(&input).unwrap().len() > FILE_SIZE_LIMIT);

    // The output's directory missing (or a file): nothing is created.
    let missing = d.join("missing");
    let not_a_dir = d.join("input.mcap").join("sub");
    let (input, other) = (s(&input), s(&other));
    let cases = [
        case(
            &["simulate", "pulse", "--model", "hill", "--csv"],
            &missing.join("a.csv"),
        ),
        case(
            &["simulate", "pulse", "--model", "hill", "--out"],
            &not_a_dir.join("a.mcap"),
        ),
        case(&["replay", &input, "--out"], &not_a_dir.join("r.mcap")),
        case(&["export", &input, "--csv"], &missing.join("e.csv")),
        case(&["recover", &input], &missing.join("r.mcap")),
        case(
            &["compare", &input, &other, "--plot"],
            &missing.join("p.png"),
        ),
        case(&["steady", "--csv"], &missing.join("s.csv")),
        case(&["figures", "--out"], &not_a_dir),
    ];
    for (args, target) in &cases {
        let o = bin().args(args).output().unwrap();
        assert_one_error_line(args, &o, target);
        assert!(!missing.exists(), "{args:?} created {}", missing.display());
    }

    // The write failing part-way (the file-size limit): neither output nor temporary is left,
    // and an output that existed is as it was.
    let kept = b"an earlier, complete output\n".to_vec();
    let existing = d.join("existing.csv");
    std::fs::write(&existing, &kept).unwrap();
    let figures = d.join("figures");
    let mut cases = vec![
        case(
            &["simulate", "pulse", "--model", "hill", "--csv"],
            &d.join("sim.csv"),
        ),
        case(
            &["simulate", "pulse", "--model", "hill", "--csv"],
            &existing,
        ),
        case(
            &["simulate", "pulse", "--model", "hill", "--out"],
            &d.join("sim.mcap"),
        ),
        case(&["replay", &input, "--out"], &d.join("replay.mcap")),
        case(&["export", &input, "--csv"], &d.join("export.csv")),
        case(&["recover", &input], &d.join("recovered.mcap")),
        case(&["compare", &input, &other, "--plot"], &d.join("cmp.png")),
        case(
            &["steady", "--model", "hill", "--points", "10001", "--csv"],
            &d.join("steady.csv"),
        ),
    ];
    // The first file `figures` writes is Fig. 4's PNG.
    let (args, _) = case(&["figures", "--out"], &figures);
    cases.push((args, figures.join("fig4_pulse_ce_force.png")));
    for (args, target) in &cases {
        let o = run_limited(args);
        assert_one_error_line(args, &o, target);
        assert_eq!(temporaries(&d), Vec::<String>::new(), "{args:?}");
    }
    assert_same(
        &read(&existing),
        &kept,
        "the existing output of a failed write",
    );
    assert_eq!(
        names(&d),
        ["existing.csv", "figures", "input.mcap", "other.mcap"]
    );
    assert_eq!(names(&figures), Vec::<String>::new(), "figures wrote files");
    remove(&d);
}
