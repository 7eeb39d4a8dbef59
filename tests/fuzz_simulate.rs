//! `simulate` on fuzzed scenario and configuration files and on hostile command-line arguments.
//!
//! The scenario and configuration files of `scenarios/` and `configs/` (durations cut to 0.1 s)
//! are mutated with seeded choices: lines dropped, duplicated or swapped, numbers replaced by
//! NaN, infinities, -1, 0, 1e308, 5e-324 or integers beyond 64 bits, the text truncated or
//! spliced with random bytes, tables and arrays nested ten thousand deep, strings of 100 000
//! characters. Directed cases add the command-line arguments that size memory or loops
//! (`--rate-hz 1e9`, `1e12`, `nan`, `--substeps 18446744073709551615`, ...), runs too long to
//! hold, limbs too large, and paths that are not regular files.
//!
//! Every run is a child with a time limit and a 1 GiB address-space limit; each must end
//! cleanly (no panic, no signal, no hang, an `error:` line for every refusal) and a CSV it
//! writes must hold finite numbers only. The summary line
//! (`cargo test --test fuzz_simulate -- --nocapture`) gives the counts.

#[path = "common/child.rs"]
mod child;

use child::Rng;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::time::Duration;

const TIME_LIMIT: Duration = Duration::from_secs(20);
const WORKERS: usize = 2;
const SCENARIO_VARIANTS: usize = 40;
const CONFIG_VARIANTS: usize = 30;

const HOSTILE_NUMBERS: [&str; 17] = [
    "nan",
    "+nan",
    "inf",
    "-inf",
    "-1",
    "0",
    "0.0",
    "-0.0",
    "1e308",
    "-1e308",
    "5e-324",
    "1e-308",
    "1e30",
    "18446744073709551615",
    "9223372036854775807",
    "-9223372036854775808",
    "99999999999999999999999",
];

fn repo(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("muscle_actuator_fuzz_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `text` with every `duration = ...` line set to 0.1 s.
fn short(text: &str) -> String {
    text.lines()
        .map(|l| {
            if l.trim_start().starts_with("duration") {
                "duration = 0.1".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
        + "\n"
}

/// Byte ranges of the number literals of a TOML text (outside strings and comments; a plain
/// scan, enough to find where numbers are).
fn numbers(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let (mut i, mut in_str, mut in_comment) = (0, false, false);
    while i < b.len() {
        let c = b[i];
        match c {
            b'\n' => in_comment = false,
            b'#' if !in_str => in_comment = true,
            b'"' if !in_comment => in_str = !in_str,
            _ => {}
        }
        let starts = !in_str
            && !in_comment
            && (c.is_ascii_digit() || (c == b'-' && b.get(i + 1).is_some_and(u8::is_ascii_digit)))
            && (i == 0
                || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_' || b[i - 1] == b'.'));
        if starts {
            let mut j = i + 1;
            while j < b.len() && (b[j].is_ascii_alphanumeric() || b"._+-".contains(&b[j])) {
                j += 1;
            }
            out.push((i, j));
            i = j;
            continue;
        }
        i += 1;
    }
    out
}

/// One seeded mutation of a TOML text (bytes: some mutations break UTF-8 on purpose).
fn mutate(text: &str, rng: &mut Rng) -> Vec<u8> {
    let lines: Vec<&str> = text.lines().collect();
    let line = rng.below(lines.len().max(1));
    let rebuild = |ls: Vec<String>| (ls.join("\n") + "\n").into_bytes();
    let owned = || lines.iter().map(|l| l.to_string()).collect::<Vec<_>>();
    match rng.below(10) {
        0 => {
            let mut ls = owned();
            ls.remove(line);
            rebuild(ls)
        }
        1 => {
            let mut ls = owned();
            ls.insert(line, lines[line].to_string());
            rebuild(ls)
        }
        2 => {
            let mut ls = owned();
            let other = rng.below(ls.len());
            ls.swap(line, other);
            rebuild(ls)
        }
        3..=5 => {
            // Numbers replaced: one, or several at once.
            let spans = numbers(text);
            if spans.is_empty() {
                return text.as_bytes().to_vec();
            }
            let mut chosen: Vec<(usize, usize)> =
                (0..1 + rng.below(3)).map(|_| *rng.pick(&spans)).collect();
            chosen.sort();
            chosen.dedup();
            let mut out = text.to_string();
            for (a, b) in chosen.into_iter().rev() {
                let value: &str = rng.pick::<&str>(&HOSTILE_NUMBERS);
                out.replace_range(a..b, value);
            }
            out.into_bytes()
        }
        6 => text.as_bytes()[..rng.below(text.len())].to_vec(),
        7 => {
            let mut b = text.as_bytes().to_vec();
            let at = rng.below(b.len());
            let n = 1 + rng.below(64);
            let junk = rng.bytes(n);
            b.splice(at..at, junk);
            b
        }
        8 => {
            // Deep nesting: an array or an inline table ten thousand levels deep.
            let depth = 10_000;
            let nested = if rng.below(2) == 0 {
                format!("deep = {}1{}\n", "[".repeat(depth), "]".repeat(depth))
            } else {
                format!("deep = {}1{}\n", "{a = ".repeat(depth), "}".repeat(depth))
            };
            let mut ls = owned();
            ls.insert(line, nested);
            rebuild(ls)
        }
        _ => {
            // A string of 100 000 characters in place of the first string on a line.
            let long = "x".repeat(100_000);
            let mut ls = owned();
            let l = &mut ls[line];
            match (l.find('"'), l.rfind('"')) {
                (Some(a), Some(b)) if b > a => l.replace_range(a + 1..b, &long),
                _ => l.push_str(&format!(" # {long}")),
            }
            rebuild(ls)
        }
    }
}

/// A run to make: the arguments, and the CSV it writes if it succeeds.
struct Case {
    name: String,
    args: Vec<OsString>,
    csv: PathBuf,
}

fn simulate(name: &str, scenario: &Path, config: Option<&str>, extra: &[&str], d: &Path) -> Case {
    let csv = d.join(format!("{name}.csv"));
    let mut args: Vec<OsString> = vec![
        "simulate".into(),
        scenario.into(),
        "--model".into(),
        "hill".into(),
    ];
    if let Some(c) = config {
        args.push("--config".into());
        args.push(c.into());
    }
    args.extend(extra.iter().map(OsString::from));
    args.push("--csv".into());
    args.push(csv.clone().into());
    Case {
        name: name.into(),
        args,
        csv,
    }
}

/// Whether a CSV holds finite numbers only (the `name` column aside).
fn csv_finite(path: &Path) -> Result<(), String> {
    let mut reader =
        csv::Reader::from_path(path).map_err(|e| format!("CSV {}: {e}", path.display()))?;
    if reader
        .headers()
        .map_err(|e| format!("CSV {}: {e}", path.display()))?
        .is_empty()
    {
        return Err("an empty CSV".into());
    }
    for (r, row) in reader.records().enumerate() {
        let row = row.map_err(|e| format!("CSV {}: {e}", path.display()))?;
        for (k, field) in row.iter().enumerate() {
            if k == 1 || field.is_empty() {
                continue;
            }
            match field.parse::<f64>() {
                Ok(v) if v.is_finite() => {}
                _ => return Err(format!("CSV row {r} column {k}: {field:?}")),
            }
        }
    }
    Ok(())
}

/// The scenario files with the configuration each runs on.
const SCENARIOS: [(&str, Option<&str>); 4] = [
    ("scenarios/example.toml", None),
    ("scenarios/arm_biceps.toml", Some("arm")),
    ("scenarios/arm_cocontraction.toml", Some("arm")),
    (
        "scenarios/four_joints.toml",
        Some("configs/four_joints.toml"),
    ),
];

/// The configuration files with a (short) scenario that runs on each.
const CONFIGS: [(&str, &str); 3] = [
    ("crates/core/configs/elbow.toml", "scenarios/example.toml"),
    ("crates/core/configs/arm.toml", "scenarios/arm_biceps.toml"),
    ("configs/four_joints.toml", "scenarios/four_joints.toml"),
];

fn fuzzed_cases(d: &Path, rng: &mut Rng) -> Vec<Case> {
    let mut cases = Vec::new();
    let config_arg = |c: Option<&str>| {
        c.map(|c| {
            if c.contains('/') {
                repo(c).display().to_string()
            } else {
                c.to_string()
            }
        })
    };
    for (s, cfg) in SCENARIOS {
        let text = short(&std::fs::read_to_string(repo(s)).unwrap());
        let stem = Path::new(s)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .to_string();
        let base = d.join(format!("{stem}_short.toml"));
        std::fs::write(&base, &text).unwrap();
        cases.push(simulate(
            &format!("{stem}_short"),
            &base,
            config_arg(cfg).as_deref(),
            &[],
            d,
        ));
        for v in 0..SCENARIO_VARIANTS {
            let mut bytes = mutate(&text, rng);
            if rng.below(4) == 0 {
                // A second mutation on top (on what is still text).
                bytes = mutate(&String::from_utf8_lossy(&bytes), rng);
            }
            let p = d.join(format!("{stem}_{v:02}.toml"));
            std::fs::write(&p, &bytes).unwrap();
            cases.push(simulate(
                &format!("{stem}_{v:02}"),
                &p,
                config_arg(cfg).as_deref(),
                &[],
                d,
            ));
        }
    }
    for (c, s) in CONFIGS {
        let text = std::fs::read_to_string(repo(c)).unwrap();
        let stem = Path::new(c)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .to_string();
        let scenario = d.join(format!("{stem}_scenario.toml"));
        std::fs::write(&scenario, short(&std::fs::read_to_string(repo(s)).unwrap())).unwrap();
        for v in 0..CONFIG_VARIANTS {
            let bytes = mutate(&text, rng);
            let p = d.join(format!("cfg_{stem}_{v:02}.toml"));
            std::fs::write(&p, &bytes).unwrap();
            let cfg = p.display().to_string();
            cases.push(simulate(
                &format!("cfg_{stem}_{v:02}"),
                &scenario,
                Some(&cfg),
                &[],
                d,
            ));
        }
    }
    cases
}

/// A configuration of `joints` joints in a chain, each spanned by one muscle.
fn big_limb(joints: usize) -> String {
    let mut t = String::new();
    for j in 0..joints {
        t.push_str(&format!("[[joint]]\nname = \"j{j}\"\n"));
    }
    for j in 0..joints {
        t.push_str(&format!(
            "[[muscle]]\nname = \"m{j}\"\n[[muscle.span]]\njoint = \"j{j}\"\nmoment_arm = 0.03\n"
        ));
    }
    t
}

/// Directed cases, each with whether it must be refused (None: a clean refusal or a run).
fn directed_cases(d: &Path, rng: &mut Rng) -> Vec<(Case, Option<bool>)> {
    let mut cases = Vec::new();
    let pulse = Path::new("pulse");
    for (i, rate) in [
        "1e9", "1e12", "nan", "inf", "-inf", "-1", "0", "100001", "1e308",
    ]
    .iter()
    .enumerate()
    {
        let arg = format!("--rate-hz={rate}");
        cases.push((
            simulate(&format!("rate_{i}"), pulse, None, &[&arg], d),
            Some(true),
        ));
    }
    for (i, n) in [
        "18446744073709551615",
        "18446744073709551616",
        "0",
        "10001",
        "-1",
    ]
    .iter()
    .enumerate()
    {
        let arg = format!("--substeps={n}");
        cases.push((
            simulate(&format!("substeps_{i}"), pulse, None, &[&arg], d),
            Some(true),
        ));
    }
    cases.push((
        simulate("model_bogus", pulse, None, &["--model", "bogus"], d),
        Some(true),
    ));
    // Valid extremes that run quickly: a tiny rate (no tick), one sub-step.
    cases.push((
        simulate("rate_tiny", pulse, None, &["--rate-hz=1e-300"], d),
        Some(false),
    ));
    // One tick a second: the solver may refuse such a step, cleanly.
    cases.push((simulate("rate_one", pulse, None, &["--rate-hz=1"], d), None));
    let short_joint = d.join("joint_short.toml");
    std::fs::write(&short_joint, "duration = 0.05\nattachment = \"joint\"\n").unwrap();
    cases.push((
        simulate("substeps_one", &short_joint, None, &["--substeps=1"], d),
        Some(false),
    ));
    // Runs too long, limbs too large to hold.
    let hour = d.join("hour.toml");
    std::fs::write(&hour, "duration = 3600\nattachment = \"joint\"\n").unwrap();
    cases.push((
        simulate("hour_at_100khz", &hour, None, &["--rate-hz=100000"], d),
        Some(true),
    ));
    cases.push((simulate("hour_at_1khz", &hour, None, &[], d), Some(true)));
    let big = d.join("big_limb.toml");
    std::fs::write(&big, big_limb(3000)).unwrap();
    let big_cfg = big.display().to_string();
    cases.push((
        simulate("limb_3000_joints", &short_joint, Some(&big_cfg), &[], d),
        Some(true),
    ));
    // Paths that are not regular files, and files of bytes.
    let fifo = d.join("fifo.toml");
    let cpath = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(cpath.as_ptr(), 0o600) }, 0);
    let random = d.join("random.toml");
    std::fs::write(&random, rng.bytes(4096)).unwrap();
    let zeros = d.join("zeros.toml");
    std::fs::write(&zeros, vec![0u8; 2 << 20]).unwrap();
    let fifo_s = fifo.display().to_string();
    let dir_s = d.display().to_string();
    let random_s = random.display().to_string();
    let zeros_s = zeros.display().to_string();
    for (i, p) in ["/dev/zero", &fifo_s, &dir_s, &random_s, &zeros_s]
        .iter()
        .enumerate()
    {
        cases.push((
            simulate(&format!("scenario_path_{i}"), Path::new(p), None, &[], d),
            Some(true),
        ));
        cases.push((
            simulate(&format!("config_path_{i}"), pulse, Some(p), &[], d),
            Some(true),
        ));
    }
    cases.push((
        simulate("scenario_missing", &d.join("missing.toml"), None, &[], d),
        Some(true),
    ));
    cases
}

#[test]
fn fuzzed_simulate_inputs_end_cleanly() {
    let d = dir();
    let mut rng = Rng(0x7369_6d75_6c61);
    let fuzzed = fuzzed_cases(&d, &mut rng);
    let directed = directed_cases(&d, &mut rng);
    let n_fuzzed = fuzzed.len();
    let mut all: Vec<(Case, Option<bool>)> = fuzzed.into_iter().map(|c| (c, None)).collect();
    all.extend(directed);
    let args: Vec<Vec<OsString>> = all.iter().map(|(c, _)| c.args.clone()).collect();
    let ended = child::run_all(&args, TIME_LIMIT, WORKERS);
    let (mut refused, mut accepted) = (0, 0);
    let mut problems = Vec::new();
    for ((case, must_refuse), e) in all.iter().zip(&ended) {
        if let Some(p) = e.problem() {
            problems.push(format!("{}: {p}", case.name));
            continue;
        }
        if e.accepted() {
            accepted += 1;
            if *must_refuse == Some(true) {
                problems.push(format!("{}: accepted; stderr: {}", case.name, e.stderr));
            } else if let Err(why) = csv_finite(&case.csv) {
                problems.push(format!("{}: {why}", case.name));
            }
        } else {
            refused += 1;
            if *must_refuse == Some(false) {
                problems.push(format!("{}: refused: {}", case.name, e.stderr));
            }
        }
        if std::env::var_os("FUZZ_VERBOSE").is_some() {
            let line = e
                .stderr
                .lines()
                .last()
                .unwrap_or("")
                .chars()
                .take(250)
                .collect::<String>();
            println!("{} ({:?}): {line}", case.name, e.elapsed);
        }
    }
    let slowest = ended.iter().map(|e| e.elapsed).max().unwrap_or_default();
    println!(
        "fuzzed simulate: {} runs ({n_fuzzed} fuzzed scenario/configuration files, {} directed \
         cases): {refused} refused with an `error:` line, {accepted} accepted with finite CSVs, \
         {} with problems; slowest run {slowest:?}",
        ended.len(),
        ended.len() - n_fuzzed,
        problems.len()
    );
    child::assert_no_problems(&problems, 30, 600);
    let _ = std::fs::remove_dir_all(&d);
}
