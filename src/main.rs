//! The `muscle_actuator` command line.

use clap::{Parser, Subcommand};
use muscle_actuator::config::ActuatorConfig;
use muscle_actuator::physics::model::ModelKind;
use muscle_actuator::runs::limits;
use muscle_actuator::sim::scenario::Scenario;
use muscle_actuator::sim::simulation::{default_stepping, Stepping};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "muscle_actuator",
    version,
    about = "Muscle actuators driving any limb: Hill and Huxley (Distribution-Moment) models, as a ROS 2 node and offline"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scenario offline (no DDS); record it to MCAP (--out) and/or CSV (--csv).
    Simulate {
        /// A built-in scenario (pulse, energy-10hz, energy-100hz) or a scenario file (.toml).
        scenario: String,
        /// Contractile model: hill, huxley or huxley-pde.
        #[arg(long, default_value = "huxley")]
        model: String,
        /// Limb configuration: a built-in name (elbow, arm) or a file (TOML); default: elbow.
        #[arg(long)]
        config: Option<PathBuf>,
        /// Tick rate, Hz.
        #[arg(long, default_value_t = 1000.0)]
        rate_hz: f64,
        /// Fixed number of implicit (TR-BDF2) sub-steps per tick (default: adaptive for hill and
        /// huxley, 20 for huxley-pde).
        #[arg(long)]
        substeps: Option<usize>,
        /// CSV output file ('-' for standard output).
        #[arg(long)]
        csv: Option<PathBuf>,
        /// MCAP recording (rosbag2-compatible) of the run.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Feed the recorded inputs of a run through a model, tick by tick, and record the result.
    Replay {
        /// The recording (.mcap).
        input: PathBuf,
        /// Contractile model (default: the recorded one).
        #[arg(long)]
        model: Option<String>,
        /// Output recording (.mcap).
        #[arg(long)]
        out: PathBuf,
    },
    /// Compare two recorded runs: RMS and max differences, peak timing, rise times.
    Compare {
        a: PathBuf,
        b: PathBuf,
        /// Overlay plot of the forces (PNG; an SVG is written beside it).
        #[arg(long)]
        plot: Option<PathBuf>,
        /// JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Rewrite a recording cut by a crash (no summary) as a complete, indexed MCAP file holding
    /// everything readable in it.
    Recover {
        /// The damaged recording (.mcap).
        input: PathBuf,
        /// The recovered recording (.mcap; not the input).
        output: PathBuf,
    },
    /// Write a recording's states as CSV: the columns of `simulate --csv`, one row per recorded
    /// state per muscle.
    Export {
        /// The recording (.mcap).
        input: PathBuf,
        /// CSV output file ('-' for standard output).
        #[arg(long)]
        csv: PathBuf,
    },
    /// Run the ROS 2 node; everything after `node` goes to it (`--ros-args ...`, see `node --help`).
    #[command(disable_help_flag = true)]
    Node {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Reproduce the paper's Figs. 4-6 and the force-velocity comparison as PNG and SVG.
    Figures {
        /// Output directory.
        #[arg(long, default_value = "figures")]
        out: PathBuf,
    },
}

fn load_config(path: &Option<PathBuf>) -> Result<ActuatorConfig, String> {
    let cfg = match path {
        Some(p) => ActuatorConfig::resolve(&p.to_string_lossy()).map_err(|e| e.to_string())?,
        None => ActuatorConfig::default(),
    };
    for w in cfg.warnings() {
        eprintln!("warning: {w}");
    }
    Ok(cfg)
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Simulate {
            scenario,
            model,
            config,
            rate_hz,
            substeps,
            csv,
            out,
        } => {
            limits::check_rate_hz("--rate-hz", rate_hz)?;
            if let Some(n) = substeps {
                limits::check_substeps("--substeps", n)?;
            }
            let model: ModelKind = model
                .parse()
                .map_err(|e: muscle_actuator::physics::model::UnknownModel| e.to_string())?;
            let cfg = load_config(&config)?;
            let sc = Scenario::resolve(&scenario, &cfg.muscles[0].params)?;
            let stepping = substeps
                .map(Stepping::Fixed)
                .unwrap_or(default_stepping(model));
            let run = match &out {
                Some(path) => muscle_actuator::runs::simulate_to_mcap(
                    &sc, &cfg, model, rate_hz, stepping, path,
                )?,
                None => sc.run(&cfg, model, rate_hz, stepping)?,
            };
            if let Some(path) = csv {
                let write = |out: &mut dyn std::io::Write| {
                    let mut buf = std::io::BufWriter::new(out);
                    muscle_actuator::csv::write_csv(&run, &mut buf)
                };
                if path.as_os_str() == "-" {
                    write(&mut std::io::stdout().lock())
                } else {
                    let mut f = std::fs::File::create(&path)
                        .map_err(|e| format!("cannot create {}: {e}", path.display()))?;
                    write(&mut f)
                }
                .map_err(|e| format!("cannot write CSV {}: {e}", path.display()))?;
            }
            let last = run.records.last().ok_or("the scenario produced no ticks")?;
            eprintln!(
                "{}: {} ticks of {} at {} Hz; final tendon force {:.3} N, fibre length {:.6} m",
                run.scenario,
                run.records.len() - 1,
                run.model,
                run.rate_hz,
                last.muscles[0].force,
                last.muscles[0].fiber_length
            );
            Ok(())
        }
        Command::Replay { input, model, out } => {
            let model = model
                .map(|m| {
                    m.parse::<ModelKind>()
                        .map_err(|e: muscle_actuator::physics::model::UnknownModel| e.to_string())
                })
                .transpose()?;
            let s = muscle_actuator::runs::replay(&input, model, &out)?;
            if let Some(w) = &s.warning {
                eprintln!("warning: {w}");
            }
            if s.compared > 0 {
                eprintln!(
                    "replayed {} ticks with {}: {} of {} recorded states reproduced bit for bit{}",
                    s.ticks,
                    s.model,
                    s.identical,
                    s.compared,
                    s.first_difference
                        .map(|t| format!(" (first difference at tick {t})"))
                        .unwrap_or_default()
                );
            } else {
                eprintln!(
                    "replayed {} ticks with {} into {}",
                    s.ticks,
                    s.model,
                    out.display()
                );
            }
            if s.identical < s.compared {
                return Err("the replay did not reproduce the recorded states".into());
            }
            Ok(())
        }
        Command::Compare { a, b, plot, json } => {
            let c = muscle_actuator::runs::compare::compare_files(&a, &b, plot.as_deref())?;
            for w in &c.warnings {
                eprintln!("warning: {w}");
            }
            if json {
                println!(
                    "{}",
                    serde_json::to_string_pretty(&c).map_err(|e| e.to_string())?
                );
            } else {
                print!("{}", c.table());
            }
            Ok(())
        }
        Command::Recover { input, output } => {
            let r = muscle_actuator::recording::recover::recover(&input, &output)?;
            if let Some(w) = &r.stopped_early {
                eprintln!(
                    "warning: {} is truncated (no summary); reading stopped: {}",
                    input.display(),
                    muscle_actuator::config::excerpt(w)
                );
            }
            eprintln!("{}", r.line(&input, &output));
            Ok(())
        }
        Command::Export { input, csv } => {
            let s = muscle_actuator::runs::export::export_csv(&input, &csv)?;
            eprintln!(
                "exported {} states of {} muscles from {}",
                s.states,
                s.muscles,
                input.display()
            );
            Ok(())
        }
        Command::Figures { out } => muscle_actuator::figures::write_all(&out),
        Command::Node { args } => muscle_actuator::ros::run_node(args),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
