//! The work–precision diagram (docs/benchmarks.md "Work and precision"): for each contractile
//! model (Hill, DM) and formulation (docs/model.md §5b: the fibre with mass, the equilibrium
//! fibre, the rigid tendon), the stepper's tolerance swept from 1e-2 to 1e-8 (and each model's
//! default), the cost of a tick against its error from the tight reference solver (Dop853 at
//! 1e-10, tests/common/reference.rs), under three loads of the default elbow at 1 kHz:
//!
//! - co-contraction: both muscles from rest to 0.6 / 0.3, 0.5 s;
//! - step: a full flexor excitation step from rest, the 0.1 s after it;
//! - realistic: both muscles' excitations drawn anew every 100 ms (fixed seeds), 1 s.
//!
//! `cargo bench --bench work_precision [-- DIR]` prints a Markdown table (µs per tick, the median
//! of 5 runs; worst force error over Fmax and worst fibre-length error, m, at any tick) and
//! draws `work_precision_hill` and `work_precision_huxley` (PNG, SVG) into DIR (default
//! `target/work-precision`): a panel per load, a curve per formulation, log10 of the error
//! against log10 of the µs per tick, the model's default tolerance marked.

#[path = "../crates/core/tests/common/mod.rs"]
mod common;

use muscle_actuator::figures::palette::{BLACK, BLUE, RED};
use muscle_actuator::figures::plot::{write_panels, Chart, Markers, Panel, Series};
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{FibreKind, Stepping, TendonKind};
use muscle_actuator_core::sim::{
    default_stepping, Scenario, Schedule, ScheduledInput, SetupKind, Signal,
};
use plotters::chart::SeriesLabelPosition;
use std::path::PathBuf;
use std::time::Instant;

const RATE: f64 = 1000.0;
/// The tolerances swept; `None` is the model's default.
const TOLERANCES: [Option<f64>; 8] = [
    Some(1e-2),
    Some(1e-3),
    Some(1e-4),
    None,
    Some(1e-5),
    Some(1e-6),
    Some(1e-7),
    Some(1e-8),
];
const FORMULATIONS: [(&str, FibreKind, TendonKind); 3] = [
    ("massed fibre", FibreKind::Massed, TendonKind::Elastic),
    (
        "equilibrium fibre",
        FibreKind::Equilibrium,
        TendonKind::Elastic,
    ),
    ("rigid tendon", FibreKind::Equilibrium, TendonKind::Rigid),
];
const REPS: usize = 5;

fn excitation(muscle: &str, schedule: Schedule) -> ScheduledInput {
    ScheduledInput {
        signal: Signal::Excitation,
        muscle: Some(muscle.into()),
        joint: None,
        schedule,
    }
}

/// A piecewise-constant excitation drawn anew every 100 ms from a fixed-seed generator.
fn random_levels(seed: u64, duration: f64) -> Schedule {
    let mut state = seed;
    let mut points = Vec::new();
    let mut t = 0.0;
    while t < duration {
        // 64-bit LCG (Knuth's MMIX constants): fixed draws without a dependency.
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let level = (state >> 11) as f64 / (1u64 << 53) as f64;
        points.push([t, level]);
        points.push([t + 0.0999, level]);
        t += 0.1;
    }
    Schedule::Piecewise { points }
}

fn loads() -> Vec<(&'static str, Scenario)> {
    let scenario = |name: &str, duration: f64, inputs| Scenario {
        name: name.into(),
        duration,
        attachment: SetupKind::Joint,
        length: None,
        initial_force: 0.0,
        inputs,
    };
    vec![
        (
            "co-contraction",
            scenario(
                "co-contraction",
                0.5,
                vec![
                    excitation("flexor", Schedule::Constant { value: 0.6 }),
                    excitation("extensor", Schedule::Constant { value: 0.3 }),
                ],
            ),
        ),
        (
            "step",
            scenario(
                "step",
                0.1,
                vec![excitation("flexor", Schedule::Constant { value: 1.0 })],
            ),
        ),
        (
            "realistic",
            scenario(
                "realistic",
                1.0,
                vec![
                    excitation("flexor", random_levels(1, 1.0)),
                    excitation("extensor", random_levels(2, 1.0)),
                ],
            ),
        ),
    ]
}

fn stepping(model: ModelKind, tolerance: Option<f64>) -> Stepping {
    match tolerance {
        Some(tolerance) => Stepping::Adaptive {
            tolerance,
            max_substeps: 10_000,
        },
        None => default_stepping(model),
    }
}

/// µs per tick of a whole run of the scenario, the median of [`REPS`].
fn us_per_tick(sc: &Scenario, cfg: &ActuatorConfig, model: ModelKind, s: Stepping) -> f64 {
    let ticks = (sc.duration * RATE).round();
    let mut times: Vec<f64> = (0..REPS)
        .map(|_| {
            let t0 = Instant::now();
            std::hint::black_box(sc.run(cfg, model, RATE, s).unwrap());
            t0.elapsed().as_secs_f64() * 1e6 / ticks
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[REPS / 2]
}

/// One point of a curve.
struct Point {
    tolerance: Option<f64>,
    us: f64,
    force: f64,
    length: f64,
}

fn main() {
    let dir = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .map_or_else(
            || {
                // Cargo's target directory wherever it is (`CARGO_TARGET_DIR`), else ./target.
                let target =
                    std::env::var_os("CARGO_TARGET_DIR").unwrap_or_else(|| "target".into());
                PathBuf::from(target).join("work-precision")
            },
            PathBuf::from,
        );
    println!(
        "| model | formulation | load | tolerance | µs per tick | worst ΔF / Fmax | worst Δl_m (m) |"
    );
    println!("|---|---|---|---|---|---|---|");
    // WORK_PRECISION_MODELS=hill and WORK_PRECISION_FORMULATIONS=equilibrium restrict the
    // table (the figures are drawn only for the full sweep).
    let only = |var: &str, name: &str| {
        std::env::var(var).map_or(true, |v| v.split(',').any(|x| name.starts_with(x)))
    };
    let full = std::env::var("WORK_PRECISION_MODELS").is_err()
        && std::env::var("WORK_PRECISION_FORMULATIONS").is_err();
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        if !only("WORK_PRECISION_MODELS", model.name()) {
            continue;
        }
        let mut panels = Vec::new();
        for (load, sc) in loads() {
            let mut series = Vec::new();
            let mut markers = Vec::new();
            for (label, fibre, tendon) in FORMULATIONS {
                if !only("WORK_PRECISION_FORMULATIONS", label) {
                    continue;
                }
                let mut cfg = ActuatorConfig::default();
                for m in &mut cfg.muscles {
                    (m.params.fibre, m.params.tendon) = (fibre, tendon);
                }
                let f_max = cfg.muscles[0].params.f_max;
                let points: Vec<Point> = TOLERANCES
                    .iter()
                    .map(|&tolerance| {
                        let s = stepping(model, tolerance);
                        let us = us_per_tick(&sc, &cfg, model, s);
                        let (force, length) =
                            common::worst_deviation_from_reference(&sc, &cfg, model, RATE, s);
                        Point {
                            tolerance,
                            us,
                            force: force / f_max,
                            length,
                        }
                    })
                    .collect();
                for p in &points {
                    let tol = p.tolerance.map_or("default".into(), |t| format!("{t:.0e}"));
                    println!(
                        "| {model} | {label} | {load} | {tol} | {:.2} | {:.2e} | {:.2e} |",
                        p.us, p.force, p.length
                    );
                }
                let log = |p: &Point| (p.us.log10(), p.force.max(1e-16).log10());
                let color = match fibre {
                    FibreKind::Massed => BLACK,
                    FibreKind::Equilibrium if tendon == TendonKind::Elastic => BLUE,
                    FibreKind::Equilibrium => RED,
                };
                let mut curve: Vec<(f64, f64)> = points
                    .iter()
                    .filter(|p| p.tolerance.is_some())
                    .map(log)
                    .collect();
                curve.sort_by(|a, b| a.0.total_cmp(&b.0));
                series.push((label, color, curve));
                let default: Vec<(f64, f64)> = points
                    .iter()
                    .filter(|p| p.tolerance.is_none())
                    .map(log)
                    .collect();
                markers.push((format!("{label}, default tolerance"), color, default));
            }
            panels.push((load, series, markers));
        }
        let titles: Vec<String> = panels
            .iter()
            .map(|(load, ..)| format!("{} model, {load}", model.label()))
            .collect();
        let panels: Vec<Panel> = panels
            .iter()
            .zip(&titles)
            .map(|((_, series, markers), title)| Panel {
                chart: Chart {
                    title,
                    x_label: "log10 µs per tick",
                    y_label: "log10 worst |ΔF| / Fmax",
                    series: series
                        .iter()
                        .map(|(label, color, points)| Series {
                            label,
                            color: *color,
                            points: points.clone(),
                            dashed: false,
                        })
                        .collect(),
                },
                markers: markers
                    .iter()
                    .map(|(label, color, points)| Markers {
                        label,
                        color: *color,
                        points: points.clone(),
                    })
                    .collect(),
                legend: SeriesLabelPosition::UpperRight,
            })
            .collect();
        if !full {
            continue;
        }
        std::fs::create_dir_all(&dir).unwrap();
        let stem = format!("work_precision_{}", model.name());
        write_panels(&dir, &stem, &panels).unwrap();
        eprintln!("wrote {}/{stem}.png and .svg", dir.display());
    }
}
