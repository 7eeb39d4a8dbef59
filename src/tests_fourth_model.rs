//! A model is one file plus its line in [`MODELS`](muscle_actuator_core::physics::models::MODELS): the fourth
//! model the tests register there ([`test_model`], the Hill element under the name `hill-copy`
//! with a stepping of its own) is reached by name from the command line (parser, help, listing),
//! the node's parameters (start-up arguments, validation, usage), CSV output, recordings
//! (written, read back, replayed) and the figures, with no other edit.

use crate::cli::{self, Cli};
use crate::ros::params::NodeParams;
use clap::{CommandFactory, Parser};
use muscle_actuator_core::physics::models::{test_model, ModelKind};
use muscle_actuator_core::physics::Stepping;
use ros2_client::ParameterValue;
use std::path::{Path, PathBuf};

fn fourth() -> ModelKind {
    "hill-copy".parse().expect("the fourth model is in MODELS")
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fourth_model_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The command's error as `main` prints it (clap's usage errors too): the tests match texts.
fn run_cli(args: &[&str]) -> Result<(), String> {
    let cli =
        Cli::try_parse_from(["muscle_actuator"].iter().chain(args)).map_err(|e| e.to_string())?;
    cli::run(cli).map_err(|e| e.to_string())
}

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn it_is_registered_with_its_own_spec() {
    assert_eq!(ModelKind::all().count(), 4);
    assert_eq!(fourth().spec().name, test_model::SPEC.name);
    assert!(std::ptr::eq(fourth().spec(), &test_model::SPEC));
    assert_eq!(
        muscle_actuator_core::sim::default_stepping(fourth()),
        test_model::SPEC.stepping
    );
}

#[test]
fn the_command_line_names_it() {
    let mut cmd = Cli::command();
    let help = cmd
        .find_subcommand_mut("simulate")
        .unwrap()
        .render_help()
        .to_string();
    assert!(
        help.contains("Contractile model: hill, huxley, huxley-pde or hill-copy"),
        "{help}"
    );
    assert!(
        help.contains("default: adaptive for hill, huxley and hill-copy, 20 for huxley-pde"),
        "{help}"
    );
    let listing = cli::models_listing();
    assert!(
        listing
            .lines()
            .any(|l| l.starts_with("hill-copy ") && l.ends_with(test_model::SPEC.summary)),
        "{listing}"
    );
    let e = run_cli(&["simulate", "pulse", "--model", "hill-cop"]).unwrap_err();
    assert!(e.contains("hill, huxley, huxley-pde, hill-copy"), "{e}");
}

/// `simulate --model hill-copy` writes the CSV of the Hill model (the same element, and its
/// sub-step bound is never reached in this run) and a recording of the fourth model with its
/// stepping, which loads and replays bit for bit.
#[test]
fn simulate_writes_csv_and_a_recording_that_replays() {
    let dir = temp_dir("simulate");
    for m in ["hill", "hill-copy"] {
        let (csv, mcap) = (dir.join(format!("{m}.csv")), dir.join(format!("{m}.mcap")));
        run_cli(&[
            "simulate",
            "pulse",
            "--model",
            m,
            "--csv",
            path(&csv),
            "--out",
            path(&mcap),
        ])
        .unwrap();
    }
    let csv = |m: &str| std::fs::read_to_string(dir.join(format!("{m}.csv"))).unwrap();
    assert_eq!(csv("hill-copy").lines().count(), 2 + 3000);
    assert_eq!(csv("hill-copy"), csv("hill"));

    let recorded = dir.join("hill-copy.mcap");
    let run = muscle_actuator_recording::runs::load_run(&recorded).unwrap();
    assert_eq!(run.meta.model, fourth());
    assert_eq!(
        run.meta.stepping,
        Stepping::Adaptive {
            tolerance: 5e-5,
            max_substeps: 48
        }
    );
    assert_eq!(run.states.len(), 3001);
    assert!(run.states.iter().all(|s| s.model == "hill-copy"));

    let replayed = dir.join("replayed.mcap");
    let s = muscle_actuator_recording::runs::replay(&recorded, None, &replayed).unwrap();
    assert_eq!(s.model, fourth());
    assert!(s.compared == 3001 && s.identical == s.compared, "{s:?}");
    run_cli(&["replay", path(&recorded), "--out", path(&replayed)]).unwrap();
    run_cli(&[
        "export",
        path(&replayed),
        "--csv",
        path(&dir.join("export.csv")),
    ])
    .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_node_takes_it_as_its_model_parameter() {
    let argv: Vec<String> = ["--ros-args", "-p", "model:=hill-copy"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let setup = crate::ros::setup::setup(&argv).unwrap().unwrap();
    assert_eq!(setup.params.model, fourth());
    let actuator = setup.params.build().unwrap();
    assert_eq!(actuator.model(), fourth());

    let mut p = NodeParams::default();
    p.set("model", &ParameterValue::String("hill-copy".into()), false)
        .unwrap();
    assert_eq!(p.model, fourth());
    assert_eq!(
        p.value("model"),
        Some(ParameterValue::String("hill-copy".into()))
    );
    let e = p
        .set("model", &ParameterValue::String("hill-cop".into()), false)
        .unwrap_err()
        .to_string();
    assert!(e.contains("hill-copy"), "{e}");
    let usage = crate::ros::args::usage();
    let words = usage.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        words.contains("model (contractile model; one of hill|huxley|huxley-pde|hill-copy;"),
        "{usage}"
    );
}

/// The pulse figures draw it in the colour of its position in the list, its row is in the
/// summary's table, and it is compared with its neighbour in the list.
#[test]
fn the_figures_show_it() {
    let dir = temp_dir("figures");
    crate::figures::write_all(&dir).unwrap();
    let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(summary.contains("\n| hill-copy | "), "{summary}");
    assert!(
        summary.contains("\nfull Huxley vs Hill copy over the pulse: F_CE RMS "),
        "{summary}"
    );
    let svg = std::fs::read_to_string(dir.join("fig4_pulse_ce_force.svg")).unwrap();
    assert!(svg.contains(test_model::SPEC.label), "no legend entry");
    // Its colour: the fourth of the palette.
    assert!(
        svg.contains("#9467BD") || svg.contains("#9467bd"),
        "no line in its colour"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
