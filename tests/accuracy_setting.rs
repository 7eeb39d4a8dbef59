//! The accuracy setting (docs/configuration.md, `[stepper]`) on its way through files: the
//! tolerance reaches the simulation from a configuration file and the recording's metadata
//! (replay reproduces the run); with fixed sub-steps it is refused on one line. Against the
//! reference solver and through saved states: crates/core/tests/accuracy_setting.rs.

#[path = "common/cli.rs"]
mod cli;

use cli::{assert_clean_failure, bin, run_ok};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{Stepping, DEFAULT_MAX_SUBSTEPS};
use muscle_actuator_recording::runs::{self, load_run};
use std::path::PathBuf;

/// A configuration file of the default elbow with `[stepper] tolerance = 1e-7`.
fn tight_config_file(dir: &std::path::Path) -> PathBuf {
    let p = dir.join("elbow_tight.toml");
    std::fs::write(
        &p,
        "[[muscle]]\nname = \"flexor\"\n\n[[muscle]]\nname = \"extensor\"\n\n\
         [stepper]\ntolerance = 1e-7\n",
    )
    .unwrap();
    p
}

/// `simulate --config` with `[stepper]` records the tolerance (in the configuration and the
/// stepping of the metadata); replay reproduces the run bit for bit, and replaying with another
/// model keeps the tolerance. The run differs from the default stepping's.
#[test]
fn the_tolerance_survives_a_recordings_round_trip() {
    let dir = cli::temp_dir("tolerance");
    let config = tight_config_file(&dir);
    let (tight, default) = (dir.join("tight.mcap"), dir.join("default.mcap"));
    run_ok(
        bin()
            .args(["simulate", "pulse", "--model", "hill", "--config"])
            .arg(&config)
            .arg("--out")
            .arg(&tight),
    );
    run_ok(
        bin()
            .args(["simulate", "pulse", "--model", "hill", "--out"])
            .arg(&default),
    );
    let run = load_run(&tight).unwrap();
    assert_eq!(run.meta.config.stepper.tolerance, Some(1e-7));
    let expected = Stepping::Adaptive {
        tolerance: 1e-7,
        max_substeps: DEFAULT_MAX_SUBSTEPS,
    };
    assert_eq!(run.meta.stepping, expected);
    assert_ne!(run.states, load_run(&default).unwrap().states);

    let again = dir.join("tight_again.mcap");
    let s = runs::replay(&tight, None, &again).unwrap();
    assert_eq!((s.compared, s.identical), (3001, 3001), "{s:?}");
    let replayed = load_run(&again).unwrap();
    assert_eq!(replayed.meta.stepping, expected);
    assert_eq!(replayed.meta.config, run.meta.config);

    let as_dm = dir.join("tight_as_huxley.mcap");
    runs::replay(&tight, Some(ModelKind::HUXLEY), &as_dm).unwrap();
    assert_eq!(load_run(&as_dm).unwrap().meta.stepping, expected);
    // The full model steps with fixed sub-steps only: the recorded tolerance is refused.
    let e = runs::replay(&tight, Some(ModelKind::HUXLEY_PDE), &dir.join("pde.mcap")).unwrap_err();
    assert!(e.to_string().starts_with("stepper.tolerance"), "{e}");
}

/// A tolerance with `--substeps`, a bad tolerance, and a tolerance for the full model are
/// refused on one line naming `stepper.tolerance`.
#[test]
fn the_command_line_refuses_what_it_cannot_honour() {
    let dir = cli::temp_dir("tolerance_cli");
    let config = tight_config_file(&dir);
    let simulate = |extra: &[&str], config: &std::path::Path| {
        bin()
            .args(["simulate", "pulse", "--csv", "-", "--config"])
            .arg(config)
            .args(extra)
            .output()
            .unwrap()
    };
    for extra in [
        &["--model", "hill", "--substeps", "8"][..],
        &["--model", "huxley-pde"][..],
    ] {
        let o = simulate(extra, &config);
        assert_clean_failure(&o, &["stepper.tolerance applies to adaptive sub-steps"]);
        assert_eq!(
            cli::stderr(&o).trim().lines().count(),
            1,
            "{}",
            cli::stderr(&o)
        );
    }
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[stepper]\ntolerance = 0.5\n").unwrap();
    let o = simulate(&["--model", "hill"], &bad);
    assert_clean_failure(&o, &["stepper.tolerance = 0.5"]);
    assert_eq!(
        cli::stderr(&o).trim().lines().count(),
        1,
        "{}",
        cli::stderr(&o)
    );
}
