//! `muscle_actuator steady` as a user runs it: the CSV (every row, the columns documented,
//! velocities exactly -vmax..vmax), the energy balance of every steady state, Huxley's (1957)
//! table for the full model, Hill's g(v), the muscle and its `[muscle.energetics]` from the
//! configuration; and the refusals: one clear line on stderr, a non-zero exit, never a panic.

use muscle_actuator_core::physics::contractile::force_velocity;
use muscle_actuator_core::physics::MuscleParams;
use std::path::{Path, PathBuf};
use std::process::Output;

#[path = "common/cli.rs"]
mod cli;
use cli::{assert_clean_failure, bin, read_csv, run_ok, stderr, temp_dir};

/// Avogadro's number, 1/mol (SI 2019, exact).
const AVOGADRO_PER_MOL: f64 = 6.022_140_76e23;

const COLUMNS: [&str; 11] = [
    "model",
    "source",
    "v_s_m_s",
    "v_s_over_vmax",
    "force_n",
    "atp_rate_mol_s",
    "chemical_w",
    "heat_w",
    "work_w",
    "efficiency",
    "chemical_w_kg",
];

/// One CSV row: model, source, and the nine numbers.
struct Row {
    model: String,
    source: String,
    v: [f64; 9],
}

impl Row {
    fn get(&self, column: &str) -> f64 {
        let i = COLUMNS.iter().position(|c| *c == column).unwrap();
        self.v[i - 2]
    }
}

fn parse_csv(text: &str) -> Vec<Row> {
    let (header, rows) = read_csv(text);
    assert_eq!(header, COLUMNS);
    rows.into_iter()
        .map(|f| {
            let v: Vec<f64> = f[2..].iter().map(|x| x.parse().unwrap()).collect();
            assert!(v.iter().all(|x| x.is_finite()), "{f:?}");
            Row {
                model: f[0].clone(),
                source: f[1].clone(),
                v: v.try_into().unwrap(),
            }
        })
        .collect()
}

/// `steady ARGS --csv -`: the rows.
fn steady_csv(args: &[&str]) -> Vec<Row> {
    let o = run_ok(bin().arg("steady").args(args).args(["--csv", "-"]));
    parse_csv(&String::from_utf8(o.stdout).unwrap())
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1.0)
}

/// (d) Every row, `points × sources`, each source's velocities ascending from exactly -vmax to
/// exactly vmax through 0, for each model; the CSV file and the table beside it.
#[test]
fn csv_holds_every_velocity_of_every_source() {
    let v_max = MuscleParams::default().v_max;
    for (model, sources) in [
        ("hill", &["umberger", "umberger2010", "bhargava"][..]),
        (
            "huxley",
            &["crossbridge", "umberger", "umberger2010", "bhargava"],
        ),
        (
            "huxley-pde",
            &["crossbridge", "umberger", "umberger2010", "bhargava"],
        ),
    ] {
        for points in [3usize, 41, 101] {
            let rows = steady_csv(&["--model", model, "--points", &points.to_string()]);
            assert_eq!(rows.len(), points * sources.len(), "{model}");
            for (k, set) in rows.chunks(points).enumerate() {
                assert!(set
                    .iter()
                    .all(|r| r.model == model && r.source == sources[k]));
                let v: Vec<f64> = set.iter().map(|r| r.get("v_s_m_s")).collect();
                assert_eq!((v[0], v[points / 2], v[points - 1]), (-v_max, 0.0, v_max));
                assert!(v.windows(2).all(|w| w[1] > w[0]), "{model} {v:?}");
                for (i, r) in set.iter().enumerate() {
                    let frac = -1.0 + 2.0 * i as f64 / (points - 1) as f64;
                    assert!((r.get("v_s_over_vmax") - frac).abs() < 1e-15);
                }
            }
        }
    }
    let dir = temp_dir("steady_csv");
    let file = dir.join("dm.csv");
    let o = run_ok(bin().args(["steady", "--csv"]).arg(&file));
    let table = String::from_utf8(o.stdout).unwrap();
    assert!(
        table.contains("model huxley") && table.contains("9 of 41 velocities"),
        "{table}"
    );
    assert_eq!(
        table
            .lines()
            .filter(|l| l.starts_with("crossbridge "))
            .count(),
        9
    );
    let rows = parse_csv(&std::fs::read_to_string(&file).unwrap());
    assert_eq!(rows.len(), 41 * 4);
}

/// (b) DM rows: chemical power = e N_A × ATP rate for the cross-bridges, and heat + work =
/// chemical power for every source within 1e-9 (no energy is stored in a steady state).
#[test]
fn dm_rows_balance_their_energy() {
    let e = MuscleParams::default().energetics.atp_free_energy;
    let rows = steady_csv(&["--model", "huxley", "--points", "201"]);
    for r in &rows {
        let chemical = r.get("chemical_w");
        let what = format!("{} at {} m/s", r.source, r.get("v_s_m_s"));
        let balance = r.get("heat_w") + r.get("work_w");
        assert!(
            rel(balance, chemical) < 1e-9,
            "{what}: {balance} vs {chemical}"
        );
        let atp = e * AVOGADRO_PER_MOL * r.get("atp_rate_mol_s");
        assert!(rel(atp, chemical) < 1e-9, "{what}: {atp} vs {chemical}");
    }
    assert_eq!(
        rows.iter().filter(|r| r.source == "crossbridge").count(),
        201
    );
}

/// (a) The full model's bridges, their activation cost `s Ė(0)` taken off: Huxley's (1957)
/// energy rates 3.7376, 4.4078 and 4.8314 times the isometric at 1/4, 1/2 and 1 vmax with the
/// project's rates (docs/model.md §11.3), Fmax isometric, no force at vmax.
#[test]
fn full_model_gives_huxleys_energy_rates() {
    let p = MuscleParams::default();
    let s = p.energetics.activation_share;
    let rows = steady_csv(&["--model", "huxley-pde", "--points", "41"]);
    let bridges: Vec<&Row> = rows.iter().filter(|r| r.source == "crossbridge").collect();
    let iso = bridges[20].get("chemical_w");
    for (i, want) in [(25, 3.7376), (30, 4.4078), (40, 4.8314)] {
        let ratio = (bridges[i].get("chemical_w") - s * iso) / ((1.0 - s) * iso);
        assert!(
            (ratio - want).abs() < 1e-4,
            "{} vmax: {ratio}",
            (i - 20) as f64 / 20.0
        );
    }
    assert!(rel(bridges[20].get("force_n"), p.f_max) < 1e-12);
    assert!(bridges[40].get("force_n").abs() < 1e-9 * p.f_max);
}

/// (c) Hill rows: force `Fmax g(v_s)` (its eccentric branch when lengthening), heat + work =
/// chemical power.
#[test]
fn hill_rows_take_fmax_g_and_balance() {
    let p = MuscleParams::default();
    for r in steady_csv(&["--model", "hill", "--points", "81"]) {
        let v = r.get("v_s_m_s");
        let g = force_velocity(v, p.v_max, p.eccentric_asymptote);
        assert!(rel(r.get("force_n"), p.f_max * g) < 1e-12, "{v}");
        let balance = r.get("heat_w") + r.get("work_w");
        assert!(
            rel(balance, r.get("chemical_w")) < 1e-12,
            "{} at {v}",
            r.source
        );
    }
}

fn write_config(name: &str, text: &str) -> PathBuf {
    let p = temp_dir("steady_config").join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// The muscle by name, with its own parameters and `[muscle.energetics]`: no activation cost
/// leaves the bridges' isometric 146.19 W (docs/model.md §11.3), per kg of the configured mass.
#[test]
fn the_named_muscle_with_its_energetics() {
    let cfg = write_config(
        "energetics.toml",
        "[[muscle]]\nname = \"flexor\"\nf_max = 2000.0\n\
         [[muscle]]\nname = \"extensor\"\n\
         [muscle.energetics]\nactivation_share = 0.0\nmetabolic_mass = 2.0\n",
    );
    let path = cfg.to_str().unwrap();
    let rows = steady_csv(&[
        "--config",
        path,
        "--muscle",
        "extensor",
        "--model",
        "huxley-pde",
    ]);
    let iso = &rows[20];
    assert_eq!(
        (iso.source.as_str(), iso.get("v_s_m_s")),
        ("crossbridge", 0.0)
    );
    assert!(
        (iso.get("chemical_w") - 146.19).abs() < 0.01,
        "{}",
        iso.get("chemical_w")
    );
    assert!(rel(iso.get("chemical_w_kg"), iso.get("chemical_w") / 2.0) < 1e-15);
    let flexor = steady_csv(&["--config", path, "--model", "hill", "--points", "3"]);
    assert_eq!(flexor[1].get("force_n"), 2000.0);
    let arm = steady_csv(&["--config", "arm", "--muscle", "TRIlong", "--points", "3"]);
    assert_eq!(arm[2].get("v_s_m_s"), 0.723656);
}

fn steady(args: &[&str]) -> Output {
    bin().arg("steady").args(args).output().unwrap()
}

/// (e) Refusals, each naming what is wrong.
#[test]
fn bad_arguments_are_refused_clearly() {
    let long = "m".repeat(500);
    let missing = Path::new("/nonexistent/steady/limb.toml");
    let cases: &[(&[&str], &[&str])] = &[
        (
            &["--model", "hill-cop"],
            &["unknown model", "hill, huxley, huxley-pde"],
        ),
        (
            &["--muscle", "biceps"],
            &["unknown muscle \"biceps\"", "flexor, extensor"],
        ),
        (&["--points", "2"], &["--points 2", "between 3 and 10001"]),
        (
            &["--points", "100000"],
            &["--points 100000", "between 3 and 10001"],
        ),
        (&["--points", "40"], &["--points 40", "odd"]),
        (&["--points", "-3"], &["'-3'"]),
        (&["--points=-3"], &["invalid value '-3' for '--points"]),
        (&["--points", "many"], &["--points"]),
        (
            &["--config", missing.to_str().unwrap()],
            &["/nonexistent/steady/limb.toml"],
        ),
        (
            &["--csv", "/nonexistent/steady/out.csv"],
            &["cannot create"],
        ),
        (&["--muscle", &long], &["unknown muscle"]),
    ];
    for (args, needles) in cases {
        let o = steady(args);
        assert_clean_failure(&o, needles);
        assert!(o.stdout.is_empty(), "{args:?}: output on failure");
    }
    let err = stderr(&steady(&["--muscle", &long]));
    assert!(
        !err.contains(&long) && err.contains(&"m".repeat(61)),
        "{err}"
    );
    let bad = write_config("bad.toml", "[[muscle]]\nname = \"flexor\"\n[muscle.energetics]\nactivation_share = 1.0\n[[muscle]]\nname = \"extensor\"\n");
    let o = steady(&["--config", bad.to_str().unwrap()]);
    assert_clean_failure(&o, &["muscle.flexor.energetics.activation_share"]);
}
