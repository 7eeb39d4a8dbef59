//! The command line on bad input: one clear line naming what is wrong, a non-zero exit, never a
//! panic (exit code 101). And the CSV it writes: header and rows as documented, the columns
//! those of the message definitions (`msg/msg/*.msg`).

use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::{JointSnapshot, MuscleSnapshot};
use std::path::PathBuf;
use std::process::Output;

#[path = "common/cli.rs"]
mod cli;
use cli::{assert_clean_failure, bin, read_csv, stderr};

fn tmp(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("muscle_actuator_cli_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// The fields of `msg/msg/NAME.msg`, (type, name) in order, constants left out.
fn msg_fields(name: &str) -> Vec<(String, String)> {
    let path = format!("{}/msg/msg/{name}.msg", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .filter(|l| !l.is_empty() && !l.contains('='))
        .map(|l| {
            let (ty, name) = l.split_once(char::is_whitespace).unwrap();
            (ty.to_string(), name.trim().to_string())
        })
        .collect()
}

fn simulate_with_config(config_text: &str) -> Output {
    let cfg = tmp(&format!("cfg_{}.toml", config_text.len()), config_text);
    bin()
        .args(["simulate", "pulse", "--model", "hill", "--config"])
        .arg(&cfg)
        .output()
        .unwrap()
}

#[test]
fn each_invalid_parameter_gets_its_own_error() {
    let cases: &[(&str, &[&str])] = &[
        (
            "[[muscle]]\nname = \"flexor\"\nf_max = -1.0\n[[muscle]]\nname = \"extensor\"\n",
            &["muscle.flexor.f_max", "must be > 0"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\n[muscle.energetics]\natp_free_energy = 1e-300\n[[muscle]]\nname = \"extensor\"\n",
            &["muscle.flexor.energetics.atp_free_energy", "from 1e-21 to 1e-17 J"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\n[muscle.energetics]\nactivation_share = 1.0\n[[muscle]]\nname = \"extensor\"\n",
            &["muscle.flexor.energetics.activation_share", "[0, 0.9]"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\n[[muscle]]\nname = \"extensor\"\n[muscle.energetics]\nmetabolic_mass = 1e300\n",
            &["muscle.extensor.energetics.metabolic_mass", "<= 1000 kg"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\n[muscle.energetics]\nenergy_model = \"heat\"\n[[muscle]]\nname = \"extensor\"\n",
            &["energy_model", "heat", "umberger2010"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\nmass = 0.0\n[[muscle]]\nname = \"extensor\"\n",
            &["muscle.flexor.mass", "must be > 0"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\n[[muscle]]\nname = \"extensor\"\nl_mc = 0.05\n",
            &["muscle.extensor.l_mc", "must be > l_ms"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\nt_act = nan\n[[muscle]]\nname = \"extensor\"\n",
            &["muscle.flexor.t_act", "finite"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\nfl_width = -0.5\n[[muscle]]\nname = \"extensor\"\n",
            &["muscle.flexor.fl_width"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\nl_opt = 0.0\n[[muscle]]\nname = \"extensor\"\n",
            &["muscle.flexor.l_opt"],
        ),
        (
            "[joint]\nradius = -0.03\n",
            &["joint.radius", "must be > 0"],
        ),
        (
            "[joint]\nmin_angle = 1.0\nmax_angle = 0.5\n",
            &["joint.elbow.max_angle", "must be > min_angle"],
        ),
        (
            "[[muscle]]\nname = \"flexor\"\nfmax = 10.0\n[[muscle]]\nname = \"extensor\"\n",
            &["fmax"],
        ),
        (
            "[[muscle]]\nname = \"biceps\"\n",
            &[
                "muscle.biceps",
                "replaces the default pair's muscle of the same name",
            ],
        ),
        (
            "[[muscle]]\nname = \"a\"\n[[muscle]]\nname = \"b\"\n[[muscle]]\nname = \"c\"\n",
            &["3 entries", "antagonistic pair"],
        ),
        (
            "[[muscle]]\nname = \"a\"\n[[muscle]]\nname = \"a\"\n",
            &["must be unique"],
        ),
        ("this is not toml", &["configuration file"]),
    ];
    for (text, needles) in cases {
        let o = simulate_with_config(text);
        assert_clean_failure(&o, needles);
    }
}

#[test]
fn several_bad_values_are_all_reported() {
    let o = simulate_with_config("[[muscle]]\nname = \"flexor\"\nf_max = -1.0\nv_max = 0.0\n[[muscle]]\nname = \"extensor\"\n");
    assert_clean_failure(&o, &["muscle.flexor.f_max", "muscle.flexor.v_max"]);
}

#[test]
fn discontinuous_l_tc_is_warned_about() {
    // The paper's table value l_tc = l_ts: a 200 N jump at slack length. The run may go through
    // or stop with a clear error at the jump; it must warn and must not panic.
    let o = simulate_with_config(
        "[[muscle]]\nname = \"flexor\"\nl_tc = 0.3185\n[[muscle]]\nname = \"extensor\"\n",
    );
    assert_ne!(o.status.code(), Some(101), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("breaks tendon force continuity"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("l_tc = 0.3194980"), "{}", stderr(&o));
}

#[test]
fn unknown_scenario_lists_the_valid_ones() {
    let o = bin().args(["simulate", "twitch"]).output().unwrap();
    assert_clean_failure(&o, &["twitch", "pulse", "energy-10hz", "energy-100hz"]);
}

#[test]
fn unknown_model_is_named() {
    let o = bin()
        .args(["simulate", "pulse", "--model", "hil"])
        .output()
        .unwrap();
    assert_clean_failure(&o, &["hil", &ModelKind::names()]);
}

#[test]
fn bad_files_and_rates_fail_cleanly() {
    let o = bin()
        .args(["simulate", "pulse", "--config", "/nonexistent/cfg.toml"])
        .output()
        .unwrap();
    assert_clean_failure(&o, &["/nonexistent/cfg.toml"]);
    let o = bin()
        .args(["simulate", "/nonexistent/s.toml"])
        .output()
        .unwrap();
    assert_clean_failure(&o, &["/nonexistent/s.toml"]);
    let o = bin()
        .args(["simulate", "pulse", "--rate-hz", "0"])
        .output()
        .unwrap();
    assert_clean_failure(&o, &["rate_hz"]);
    let o = bin()
        .args([
            "simulate",
            "pulse",
            "--model",
            "huxley-pde",
            "--substeps",
            "0",
        ])
        .output()
        .unwrap();
    assert_clean_failure(&o, &["substeps"]);
    let bad = tmp("bad_scenario.toml", "duration = 1.0\nattachment = \"joint\"\n[[input]]\nsignal = \"excitation\"\nmuscle = \"biceps\"\nkind = \"step\"\nat = 0.1\nto = 1.0\n");
    let o = bin().arg("simulate").arg(&bad).output().unwrap();
    assert_clean_failure(&o, &["biceps", "flexor"]);
    let bad = tmp("bad_ramp.toml", "duration = 1.0\nattachment = \"clamped\"\n[[input]]\nsignal = \"excitation\"\nkind = \"ramp\"\nstart = 0.5\nend = 0.2\nfrom = 0.0\nto = 1.0\n");
    let o = bin().arg("simulate").arg(&bad).output().unwrap();
    assert_clean_failure(&o, &["end = 0.2 must be > start = 0.5"]);
    let bad = tmp(
        "bad_duration.toml",
        "duration = -1.0\nattachment = \"joint\"\n",
    );
    let o = bin().arg("simulate").arg(&bad).output().unwrap();
    assert_clean_failure(&o, &["duration"]);
}

#[test]
fn csv_has_the_documented_columns_and_one_row_per_tick_per_muscle() {
    let out = std::env::temp_dir().join(format!("ma_cli_{}.csv", std::process::id()));
    let scenario = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/example.toml");
    let o = bin()
        .args(["simulate", scenario, "--model", "hill", "--csv"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&out).unwrap();
    let (header, rows) = read_csv(&text);
    // `time`, `name`, the muscle's fields after its name, then the per-joint arrays of the
    // joint (the stiffness matrix is not per joint).
    let mut columns = vec!["time".to_string(), "name".to_string()];
    columns.extend(
        msg_fields("MuscleState")
            .into_iter()
            .filter(|(ty, _)| ty == "float64")
            .map(|(_, name)| name),
    );
    columns.extend(
        msg_fields("ActuatorState")
            .into_iter()
            .filter(|(ty, name)| ty == "float64[]" && name != "stiffness_matrix")
            .map(|(_, name)| format!("elbow.{name}")),
    );
    assert_eq!(header, columns);
    let position = header.iter().position(|c| c == "elbow.position").unwrap();
    // 1.5 s at 1 kHz: the initial state and 1500 ticks, two muscles each.
    assert_eq!(rows.len(), 2 * 1501);
    assert!(rows.iter().all(|r| r.len() == columns.len()));
    assert_eq!(rows[0][1], "flexor");
    assert_eq!(rows[1][1], "extensor");
    // The flexor pulse flexes the joint: positive angle at 0.5 s.
    let at_half = rows
        .iter()
        .find(|r| r[0] == "0.5" && r[1] == "flexor")
        .unwrap();
    assert!(
        at_half[position].parse::<f64>().unwrap() > 0.01,
        "{at_half:?}"
    );
}

/// Names with a comma and quotes (which a configuration allows) are quoted in the CSV (RFC
/// 4180): read back with the `csv` crate, the header has its columns and every row as many;
/// the recording of the run exports to the same CSV.
#[test]
fn names_with_commas_and_quotes_keep_the_csv_columns() {
    let (muscle, joint) = (r#"a,"b""#, r#"el,"bow""#);
    let elbow = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/crates/core/configs/elbow.toml"
    ))
    .unwrap()
    .replace(r#"name = "flexor""#, &format!("name = '{muscle}'"))
    .replace(r#""elbow""#, &format!("'{joint}'"));
    assert_eq!(elbow.matches(joint).count(), 3, "{elbow}");
    let cfg = tmp("quoted_names.toml", &elbow);
    let scenario = tmp(
        "quoted_names_scenario.toml",
        "name = \"q\"\nduration = 0.01\nattachment = \"joint\"\n\
         [[input]]\nsignal = \"excitation\"\nkind = \"constant\"\nvalue = 0.5\n",
    );
    let (csv, mcap, export) = (
        scenario.with_file_name("quoted.csv"),
        scenario.with_file_name("quoted.mcap"),
        scenario.with_file_name("quoted_export.csv"),
    );
    let o = bin()
        .args(["simulate"])
        .arg(&scenario)
        .args(["--model", "hill", "--config"])
        .arg(&cfg)
        .arg("--csv")
        .arg(&csv)
        .arg("--out")
        .arg(&mcap)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.contains(r#""a,""b""""#), "{text}");
    let (header, rows) = read_csv(&text);
    let mut columns = vec!["time".to_string(), "name".to_string()];
    columns.extend(MuscleSnapshot::FIELDS.iter().map(|f| f.to_string()));
    columns.extend(JointSnapshot::FIELDS.iter().map(|f| format!("{joint}.{f}")));
    assert_eq!(header, columns);
    assert_eq!(rows.len(), 2 * 11);
    assert!(rows.iter().all(|r| r.len() == columns.len()));
    assert_eq!(
        (rows[0][1].as_str(), rows[1][1].as_str()),
        (muscle, "extensor")
    );
    let o = bin()
        .arg("export")
        .arg(&mcap)
        .arg("--csv")
        .arg(&export)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&export).unwrap(), text);
}

/// No command writes its output over a file it reads: `replay --out` over its recording,
/// `export --csv` over it, `compare --plot` over one of the runs, `simulate --csv`/`--out` over
/// its scenario or configuration or over each other, `steady --csv` over its configuration.
/// Each is refused before anything is written, the input left byte for byte as it was.
#[test]
fn no_output_is_written_over_an_input() {
    let dir = tmp("overwrite_marker", "").parent().unwrap().to_path_buf();
    let rec = dir.join("overwrite_run.mcap");
    let o = bin()
        .args(["simulate", "pulse", "--model", "hill", "--out"])
        .arg(&rec)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let before = std::fs::read(&rec).unwrap();
    // Another name for the same file: through `..` and through a symbolic link.
    let dotted = dir
        .join("..")
        .join(dir.file_name().unwrap())
        .join("overwrite_run.mcap");
    let link = dir.join("overwrite_link.mcap");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink(&rec, &link).unwrap();
    // A run named as the plot's SVG: `--plot X.png` writes X.png and X.svg.
    let as_svg = dir.join("overwrite_plot_run.svg");
    std::fs::copy(&rec, &as_svg).unwrap();
    let scenario = tmp(
        "overwrite_scenario.toml",
        "duration = 0.01\nattachment = \"clamped\"\n",
    );
    let config = tmp("overwrite_config.toml", "[[joint]]\nname = \"elbow\"\n");
    let s = |p: &PathBuf| p.to_string_lossy().into_owned();
    let cases: Vec<(Vec<String>, PathBuf)> = vec![
        (
            vec![
                "replay".into(),
                s(&rec),
                "--model".into(),
                "huxley".into(),
                "--out".into(),
                s(&rec),
            ],
            rec.clone(),
        ),
        (
            vec!["replay".into(), s(&rec), "--out".into(), s(&dotted)],
            rec.clone(),
        ),
        (
            vec!["replay".into(), s(&link), "--out".into(), s(&rec)],
            rec.clone(),
        ),
        (
            vec!["export".into(), s(&rec), "--csv".into(), s(&link)],
            rec.clone(),
        ),
        (
            vec![
                "compare".into(),
                s(&rec),
                s(&as_svg),
                "--plot".into(),
                s(&as_svg.with_extension("png")),
            ],
            as_svg.clone(),
        ),
        (
            vec![
                "simulate".into(),
                s(&scenario),
                "--csv".into(),
                s(&scenario),
            ],
            scenario.clone(),
        ),
        (
            vec![
                "simulate".into(),
                "pulse".into(),
                "--config".into(),
                s(&config),
                "--out".into(),
                s(&config),
            ],
            config.clone(),
        ),
        (
            vec![
                "simulate".into(),
                "pulse".into(),
                "--csv".into(),
                s(&rec),
                "--out".into(),
                s(&rec),
            ],
            rec.clone(),
        ),
        (
            vec![
                "steady".into(),
                "--config".into(),
                s(&config),
                "--csv".into(),
                s(&config),
            ],
            config.clone(),
        ),
    ];
    for (args, input) in cases {
        let kept = std::fs::read(&input).unwrap();
        let o = bin().args(&args).output().unwrap();
        assert_clean_failure(&o, &["would overwrite"]);
        assert_eq!(
            std::fs::read(&input).unwrap(),
            kept,
            "{args:?} changed its input"
        );
    }
    assert_eq!(std::fs::read(&rec).unwrap(), before);
    // A plot beside the run, not over it, is written.
    let o = bin()
        .args(["compare"])
        .arg(&rec)
        .arg(&rec)
        .arg("--plot")
        .arg(dir.join("overwrite_plot.png"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
}
