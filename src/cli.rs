//! The `muscle_actuator` command line: the offline commands (simulate, replay, compare, recover,
//! export, figures, models, [`steady`](mod@steady)) and the node. Model names, the default model
//! and the default sub-stepping in its help come from [`MODELS`](muscle_actuator_core::physics::models::MODELS).

mod error;
mod prediction_run;
pub mod steady;
pub mod subject;

pub use error::CliError;

use clap::{Parser, Subcommand};
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::{join, ModelKind};
use muscle_actuator_core::physics::params::EnergyModel;
use muscle_actuator_core::physics::stepping::Stepping;
use muscle_actuator_core::sim::steady::{DEFAULT_POINTS, MAX_POINTS, MIN_POINTS};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "muscle_actuator",
    version,
    about = "Muscle actuators driving any limb: Hill and Huxley (Distribution-Moment) models, as a ROS 2 node and offline"
)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// Run a scenario offline (no DDS); record it to MCAP (--out) and/or CSV (--csv).
    Simulate {
        /// A built-in scenario (pulse, energy-10hz, energy-100hz) or a scenario file (.toml).
        scenario: String,
        #[arg(long, default_value = ModelKind::DEFAULT.name(), help = model_help())]
        model: String,
        /// Limb configuration: a built-in name (elbow, arm) or a file (TOML); default: elbow.
        #[arg(long)]
        config: Option<PathBuf>,
        #[arg(long, help = energy_model_help())]
        energy_model: Option<String>,
        /// Tick rate, Hz.
        #[arg(long, default_value_t = 1000.0)]
        rate_hz: f64,
        #[arg(long, help = substeps_help())]
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
    /// List the contractile models: name and what it is, one a line.
    Models,
    /// A subject's muscle-tendon units (CEINMS's subject XML, or the project's TOML) written as
    /// the project's TOML subject file (docs/emg.md).
    Subject {
        /// The subject file (.xml or .toml).
        file: PathBuf,
        /// The TOML subject file to write.
        #[arg(long)]
        out: PathBuf,
    },
    /// Drive a subject's units through a measured trial (EMG, muscle-tendon lengths, moment
    /// arms) and rate the predicted joint moments against the measured ones: R2, r2, RMSE.
    Predict {
        #[command(flatten)]
        args: subject::PredictArgs,
        #[arg(long, default_value = "hill", help = model_help())]
        model: String,
    },
    /// Calibrate a subject's units on trials: bounded parameters fitted by CMA-ES so that the
    /// predicted moments of the degrees of freedom match the measured ones (docs/emg.md).
    Calibrate {
        /// The subject file (CEINMS XML or the project's TOML).
        #[arg(long)]
        subject: PathBuf,
        /// The EMG-to-unit map (CEINMS's excitation generator XML).
        #[arg(long)]
        excitations: PathBuf,
        /// The trials' folders.
        #[arg(long, num_args = 1.., required = true)]
        trials: Vec<PathBuf>,
        /// The degrees of freedom whose moments are matched, comma-separated (R_knee_fe,...).
        #[arg(long)]
        dofs: String,
        #[arg(long, default_value = "hill", help = model_help())]
        model: String,
        /// The calibrated subject's TOML file.
        #[arg(long)]
        out: PathBuf,
        /// The optimiser's seed (the same seed, the same result).
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Most objective evaluations.
        #[arg(long, default_value_t = DEFAULT_EVALUATIONS)]
        evaluations: usize,
        /// Threads the candidates are evaluated on (default: every core).
        #[arg(long)]
        threads: Option<usize>,
    },
    /// One muscle's steady states at full activation and optimal length, shortening velocities
    /// from -vmax to vmax: force, ATP rate, chemical power, heat, work, efficiency, from the
    /// cross-bridges (Huxley models) and each phenomenological energy model.
    Steady {
        #[arg(long, default_value = ModelKind::DEFAULT.name(), help = model_help())]
        model: String,
        /// Limb configuration: a built-in name (elbow, arm) or a file (TOML); default: elbow.
        #[arg(long)]
        config: Option<PathBuf>,
        /// The muscle, by name; default: the configuration's first.
        #[arg(long)]
        muscle: Option<String>,
        #[arg(long, default_value_t = DEFAULT_POINTS, help = points_help())]
        points: usize,
        /// CSV of every row ('-' for standard output, and no table).
        #[arg(long)]
        csv: Option<PathBuf>,
    },
}

/// `calibrate --evaluations` by default.
const DEFAULT_EVALUATIONS: usize = 1000;

/// Help of `simulate --model`.
fn model_help() -> String {
    format!(
        "Contractile model: {}",
        ModelKind::names_joined(", ", " or ")
    )
}

/// Help of `steady --points`.
fn points_help() -> String {
    format!(
        "Shortening velocities, evenly from -vmax to vmax through 0: an odd number from \
         {MIN_POINTS} to {MAX_POINTS}"
    )
}

/// Help of `simulate --substeps`: each model's default stepping.
fn substeps_help() -> String {
    let adaptive = ModelKind::all().filter(|m| m.spec().stepping.is_adaptive());
    let mut defaults = vec![format!(
        "adaptive for {}",
        join(adaptive.map(|m| m.name()), ", ", " and ")
    )];
    for m in ModelKind::all() {
        if let Stepping::Fixed(n) = m.spec().stepping {
            defaults.push(format!("{n} for {m}"));
        }
    }
    format!(
        "Fixed number of implicit (TR-BDF2) sub-steps per tick (default: {}; a configuration's \
         [stepper] table sets the adaptive ones' tolerance, and is refused with --substeps)",
        defaults.join(", ")
    )
}

/// The `models` listing: each model's name and summary, the default marked.
pub fn models_listing() -> String {
    let width = ModelKind::all().map(|m| m.name().len()).max().unwrap_or(0);
    let mut out = String::new();
    for m in ModelKind::all() {
        let mark = if m == ModelKind::DEFAULT {
            " [default]"
        } else {
            ""
        };
        out.push_str(&format!(
            "{:width$}  {}{mark}\n",
            m.name(),
            m.spec().summary
        ));
    }
    out
}

fn parse_model(name: &str) -> Result<ModelKind, CliError> {
    Ok(name.parse()?)
}

fn load_config(path: &Option<PathBuf>) -> Result<ActuatorConfig, CliError> {
    let cfg = match path {
        Some(p) => ActuatorConfig::resolve(&p.to_string_lossy())?,
        None => ActuatorConfig::default(),
    };
    for w in cfg.warnings() {
        eprintln!("warning: {w}");
    }
    Ok(cfg)
}

/// The help of `--energy-model`, from the list of energy models.
fn energy_model_help() -> String {
    format!(
        "Phenomenological energy model of every muscle: {} (default: each muscle's \
         energetics.energy_model in the configuration, umberger unless set)",
        EnergyModel::names()
    )
}

/// `cfg` with every muscle's energy model set to `name`, if one is given.
fn with_energy_model(cfg: ActuatorConfig, name: Option<&str>) -> Result<ActuatorConfig, CliError> {
    match name {
        Some(n) => Ok(cfg.with_energy_model(n.parse()?)),
        None => Ok(cfg),
    }
}

/// Refuses an output that would overwrite one of `inputs` ([`muscle_actuator_core::files::check_not_an_input`]).
fn check_not_an_input(out: &Path, inputs: &[&Path]) -> Result<(), CliError> {
    muscle_actuator_core::files::check_not_an_input(out, inputs).map_err(CliError::from)
}

/// Runs one parsed command.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Simulate {
            scenario,
            model,
            config,
            energy_model,
            rate_hz,
            substeps,
            csv,
            out,
        } => {
            let mut inputs = read_files(&[Some(Path::new(&scenario)), config.as_deref()]);
            for o in [&csv, &out].into_iter().flatten() {
                check_not_an_input(o, &inputs)?;
                inputs.push(o);
            }
            simulate(
                &scenario,
                &model,
                &with_energy_model(load_config(&config)?, energy_model.as_deref())?,
                rate_hz,
                substeps,
                csv.as_deref(),
                out.as_deref(),
            )
        }
        Command::Replay { input, model, out } => {
            let model = model.as_deref().map(parse_model).transpose()?;
            replay(&input, model, &out)
        }
        Command::Compare { a, b, plot, json } => compare(&a, &b, plot.as_deref(), json),
        Command::Recover { input, output } => {
            let r = muscle_actuator_recording::recording::recover::recover(&input, &output)?;
            if let Some(w) = &r.stopped_early {
                eprintln!(
                    "warning: {} is truncated (no summary); reading stopped: {}",
                    input.display(),
                    muscle_actuator_core::text::excerpt(w)
                );
            }
            eprintln!("{}", r.line(&input, &output));
            Ok(())
        }
        Command::Export { input, csv } => {
            let s = muscle_actuator_recording::runs::export::export_csv(&input, &csv)?;
            eprintln!(
                "exported {} states of {} muscles from {}",
                s.states,
                s.muscles,
                input.display()
            );
            Ok(())
        }
        Command::Figures { out } => Ok(crate::figures::write_all(&out)?),
        Command::Models => {
            print!("{}", models_listing());
            Ok(())
        }
        Command::Node { args } => Ok(crate::ros::run_node(args)?),
        Command::Subject { file, out } => Ok(subject::convert(&file, &out)?),
        Command::Predict { args, model } => {
            let ratings = subject::predict(&args, parse_model(&model)?)?;
            let trial = args.trial.display().to_string();
            print!("{}", subject::ratings_table(&trial, &ratings));
            Ok(())
        }
        Command::Calibrate {
            subject: s,
            excitations,
            trials,
            dofs,
            model,
            out,
            seed,
            evaluations,
            threads,
        } => {
            let dofs = subject::parse_dofs(&dofs)?;
            Ok(subject::calibrate(&subject::CalibrateArgs {
                subject: &s,
                excitations: &excitations,
                trials: &trials,
                dofs: &dofs,
                model: parse_model(&model)?,
                out: &out,
                settings: muscle_actuator_measured::subject::calibrate::Settings {
                    seed,
                    max_evaluations: evaluations,
                    threads: threads.unwrap_or_else(rayon::current_num_threads),
                    ..Default::default()
                },
                progress: true,
            })?)
        }
        Command::Steady {
            model,
            config,
            muscle,
            points,
            csv,
        } => {
            muscle_actuator_core::sim::steady::check_points(points)?;
            if let Some(c) = &csv {
                check_not_an_input(c, &read_files(&[config.as_deref()]))?;
            }
            let model = parse_model(&model)?;
            let cfg = load_config(&config)?;
            Ok(steady::steady(
                model,
                &cfg,
                muscle.as_deref(),
                points,
                csv.as_deref(),
            )?)
        }
    }
}

/// The files among `paths` that exist (a scenario or configuration named by path rather than
/// as a built-in), which no output may overwrite.
fn read_files<'a>(paths: &[Option<&'a Path>]) -> Vec<&'a Path> {
    paths
        .iter()
        .flatten()
        .copied()
        .filter(|p| p.is_file())
        .collect()
}

/// `simulate`: the scenario run offline, recorded to MCAP and/or written as CSV.
fn simulate(
    scenario: &str,
    model: &str,
    cfg: &ActuatorConfig,
    rate_hz: f64,
    substeps: Option<usize>,
    csv: Option<&Path>,
    out: Option<&Path>,
) -> Result<(), CliError> {
    let model = parse_model(model)?;
    let run = muscle_actuator_recording::runs::run_scenario(
        scenario, cfg, model, rate_hz, substeps, out,
    )?;
    if let Some(path) = csv {
        muscle_actuator_core::csv::write_csv_to(&run, path)?;
    }
    let last = run.last().ok_or(CliError::NoTicks)?;
    eprintln!(
        "{}: {} ticks of {} at {} Hz; final tendon force {:.3} N, fibre length {:.6} m",
        run.scenario,
        run.len() - 1,
        run.model,
        run.rate_hz,
        last.muscles[0].force,
        last.muscles[0].fiber_length
    );
    Ok(())
}

/// `replay`: the recorded inputs through a model (the recorded one unless named).
fn replay(input: &Path, model: Option<ModelKind>, out: &Path) -> Result<(), CliError> {
    let s = muscle_actuator_recording::runs::replay(input, model, out)?;
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
        return Err(CliError::ReplayDiffers);
    }
    Ok(())
}

/// `compare`: two recordings as a table or JSON, with an optional overlay plot.
fn compare(a: &Path, b: &Path, plot: Option<&Path>, json: bool) -> Result<(), CliError> {
    let plot_to = plot.map(|p| {
        (
            p,
            crate::figures::compare_plot::plot as muscle_actuator_recording::runs::compare::PlotFn,
        )
    });
    let c = muscle_actuator_recording::runs::compare::compare_files(a, b, plot_to)?;
    for w in &c.warnings {
        eprintln!("warning: {w}");
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&c)?);
    } else {
        print!("{}", c.table());
    }
    Ok(())
}

/// Parses the command line, runs the command, reports an error as one line.
pub fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
