//! `steady`: one muscle's isovelocity steady states at full activation and optimal length
//! ([`muscle_actuator_core::sim::steady`], docs/model.md §11.5), a table of selected velocities on standard
//! output and, with `--csv`, every row as CSV (columns [`SteadyRow::FIELDS`], units in the
//! names).

use super::common::{
    check_not_an_input, default_model, load_config, model_help, parse_model, read_files,
};
use super::{CliError, SteadyError};
use muscle_actuator_core::config::{ActuatorConfig, MuscleConfig};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::steady::{
    steady_table, SteadyRow, DEFAULT_POINTS, MAX_POINTS, MIN_POINTS,
};
use muscle_actuator_core::text::excerpt;
use std::io::Write;
use std::path::{Path, PathBuf};

/// What `steady` is asked.
#[derive(clap::Args)]
pub struct Args {
    #[arg(long, default_value = default_model(), help = model_help())]
    model: String,
    /// Limb configuration: a built-in name (elbow, arm) or a file (TOML); default: elbow.
    #[arg(long)]
    config: Option<PathBuf>,
    /// The muscle, by name; default: the configuration's first.
    #[arg(long)]
    muscle: Option<String>,
    #[arg(long, default_value_t = DEFAULT_POINTS, help = points_help(), allow_negative_numbers = true)]
    points: usize,
    /// CSV of every row ('-' for standard output, and no table).
    #[arg(long)]
    csv: Option<PathBuf>,
}

/// Help of `steady --points`.
fn points_help() -> String {
    format!(
        "Shortening velocities, evenly from -vmax to vmax through 0: an odd number from \
         {MIN_POINTS} to {MAX_POINTS}"
    )
}

/// Runs `steady`.
pub(super) fn run(a: Args) -> Result<(), CliError> {
    muscle_actuator_core::sim::steady::check_points(a.points)?;
    if let Some(c) = &a.csv {
        check_not_an_input(c, &read_files(&[a.config.as_deref()]))?;
    }
    let model = parse_model(&a.model)?;
    let cfg = load_config(&a.config)?;
    Ok(steady(
        model,
        &cfg,
        a.muscle.as_deref(),
        a.points,
        a.csv.as_deref(),
    )?)
}

/// Fractions of vmax the table shows when the grid has more than [`SHOW_ALL`] velocities: the
/// grid's nearest to each.
const SHOWN_FRACTIONS: [f64; 9] = [-1.0, -0.5, -0.25, 0.0, 0.1, 0.25, 0.5, 0.75, 1.0];
/// Grids of at most this many velocities are shown whole.
const SHOW_ALL: usize = 11;

/// Runs `steady` for the muscle named `muscle` (default: the first) of `cfg`: computes the rows,
/// writes the CSV and the table (no table when the CSV goes to standard output).
pub fn steady(
    model: ModelKind,
    cfg: &ActuatorConfig,
    muscle: Option<&str>,
    points: usize,
    csv: Option<&Path>,
) -> Result<(), SteadyError> {
    let m = select_muscle(cfg, muscle)?;
    let rows = steady_table(&m.params, model, points).map_err(|reason| SteadyError::Table {
        muscle: excerpt(&m.name),
        reason,
    })?;
    let to_stdout = csv.is_some_and(|p| p.as_os_str() == "-");
    if let Some(path) = csv {
        write_csv_to(&rows, path)?;
    }
    if !to_stdout {
        print!("{}", table(m, &rows, points));
    }
    if let Some(path) = csv.filter(|_| !to_stdout) {
        eprintln!("wrote {} rows to {}", rows.len(), path.display());
    }
    Ok(())
}

/// The muscle named `name`, or the configuration's first.
fn select_muscle<'a>(
    cfg: &'a ActuatorConfig,
    name: Option<&str>,
) -> Result<&'a MuscleConfig, SteadyError> {
    let Some(name) = name else {
        return cfg.muscles.first().ok_or(SteadyError::NoMuscle);
    };
    cfg.muscles.iter().find(|m| m.name == name).ok_or_else(|| {
        let names: Vec<String> = cfg.muscles.iter().map(|m| excerpt(&m.name)).collect();
        SteadyError::UnknownMuscle {
            name: excerpt(name),
            known: names.join(", "),
        }
    })
}

/// Indices into one source's rows (ascending velocities) that the table shows.
fn shown(points: usize) -> Vec<usize> {
    if points <= SHOW_ALL {
        return (0..points).collect();
    }
    let step = 2.0 / (points - 1) as f64;
    let mut idx: Vec<usize> = SHOWN_FRACTIONS
        .iter()
        .map(|f| (((f + 1.0) / step).round() as usize).min(points - 1))
        .collect();
    idx.dedup();
    idx
}

/// The aligned table: a heading, then per energy source the shown velocities.
fn table(m: &MuscleConfig, rows: &[SteadyRow], points: usize) -> String {
    let p = &m.params;
    let mut out = format!(
        "steady states of muscle {}, model {} ({}), full activation, optimal length \
         (Fmax {} N, vmax {} m/s, metabolic mass {:.4} kg)\n",
        excerpt(&m.name),
        rows.first().map_or("", |r| r.model.name()),
        rows.first().map_or("", |r| r.model.label()),
        p.f_max,
        p.v_max,
        p.energetics.mass_kg(p.f_max, p.l_opt),
    );
    let idx = shown(points);
    if idx.len() < points {
        out.push_str(&format!(
            "{} of {points} velocities; --csv FILE for all\n",
            idx.len()
        ));
    }
    out.push_str(&format!(
        "\n{:<13}{:>9}{:>11}{:>11}{:>14}{:>11}{:>10}{:>10}{:>8}{:>9}\n",
        "source",
        "v_s/vmax",
        "v_s (m/s)",
        "force (N)",
        "ATP (mmol/s)",
        "chem. (W)",
        "heat (W)",
        "work (W)",
        "effic.",
        "W/kg"
    ));
    for (k, set) in rows.chunks(points).enumerate() {
        if k > 0 {
            out.push('\n');
        }
        for r in idx.iter().filter_map(|&i| set.get(i)) {
            out.push_str(&table_line(r));
        }
    }
    out
}

/// One row of the table.
fn table_line(r: &SteadyRow) -> String {
    let x = &r.point;
    format!(
        "{:<13}{:>9.3}{:>11.4}{:>11.1}{:>14.4}{:>11.1}{:>10.1}{:>10.1}{:>8.3}{:>9.1}\n",
        r.source.name(),
        r.v_over_vmax,
        x.shortening_velocity_m_s,
        unsigned_zero(x.force_n, 1),
        1e3 * x.atp_rate_mol_s,
        x.chemical_w,
        x.heat_w,
        unsigned_zero(x.work_w, 1),
        unsigned_zero(x.efficiency, 3),
        r.chemical_w_kg,
    )
}

/// `x`, or 0 when it shows as zero at `decimals` places: no `-0.0` in the table for a rounding
/// residue (the full model's force at vmax is zero to 1e-12 N, either side).
fn unsigned_zero(x: f64, decimals: i32) -> f64 {
    if x.abs() < 0.5 * 10f64.powi(-decimals) {
        0.0
    } else {
        x
    }
}

/// Every row as CSV: a header of [`SteadyRow::FIELDS`], then the names and the values
/// ([`csv_number`]).
pub fn write_csv(rows: &[SteadyRow], out: &mut impl Write) -> std::io::Result<()> {
    let mut w = muscle_actuator_core::csv::writer(out);
    w.write_record(SteadyRow::FIELDS)?;
    for r in rows {
        w.write_field(r.model.name())?;
        w.write_field(r.source.name())?;
        for x in r.values() {
            w.write_field(csv_number(x))?;
        }
        w.write_record(None::<&[u8]>)?;
    }
    w.flush()
}

/// A number in the shortest form that reads back exactly: positional, or with an exponent
/// below 1e-3 in magnitude (a rounding residue such as the full model's force at vmax would
/// otherwise take 30 digits).
pub fn csv_number(x: f64) -> String {
    if x != 0.0 && x.abs() < 1e-3 {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The CSV to the file `path` (`-`: standard output).
fn write_csv_to(rows: &[SteadyRow], path: &Path) -> Result<(), SteadyError> {
    muscle_actuator_core::csv::write_text_to(path, |out| write_csv(rows, out))
        .map_err(SteadyError::from)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Large grids show the velocities nearest to [`SHOWN_FRACTIONS`]; small ones all.
    #[test]
    fn the_table_shows_selected_velocities_of_large_grids() {
        assert_eq!(shown(11), (0..11).collect::<Vec<_>>());
        assert_eq!(shown(41), [0, 10, 15, 20, 22, 25, 30, 35, 40]);
        assert_eq!(shown(13), [0, 3, 5, 6, 7, 8, 9, 11, 12]);
    }

    #[test]
    fn csv_numbers_read_back_exactly() {
        for x in [
            0.0,
            -0.5179,
            3913.0,
            1.0 / 3.0,
            -3.8e-13,
            2.5e-6,
            0.001,
            1e300,
        ] {
            assert_eq!(
                csv_number(x).parse::<f64>().unwrap(),
                x,
                "{}",
                csv_number(x)
            );
        }
        assert_eq!(csv_number(-3.8e-13), "-3.8e-13");
    }

    /// The tests' fourth model is reached by name and taken as Hill's.
    #[cfg(feature = "test-model")]
    #[test]
    fn the_fourth_model_runs() {
        use crate::cli::{run, Cli};
        use clap::Parser;
        let dir = std::env::temp_dir().join(format!("steady_fourth_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let csv = dir.join("copy.csv");
        let args = [
            "muscle_actuator",
            "steady",
            "--model",
            "hill-copy",
            "--points",
            "5",
        ];
        let cli = Cli::try_parse_from(args.iter().copied().chain(["--csv", csv.to_str().unwrap()]));
        run(cli.unwrap()).unwrap();
        let text = std::fs::read_to_string(&csv).unwrap();
        assert_eq!(text.lines().count(), 1 + 5 * 3);
        assert!(text.lines().skip(1).all(|l| l.starts_with("hill-copy,")));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
