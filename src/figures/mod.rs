//! The paper's figures reproduced (Figs. 4–6 of Jovanović et al. 2015, docs/model.md §9), plus the
//! steady force–velocity curves of the three models, as PNG and SVG, and a summary of the
//! numbers they show (`summary.md`).

pub mod plot;

use crate::config::ActuatorConfig;
use crate::physics::contractile::calibration::{calibrate_distribution_moment, calibrate_exact};
use crate::physics::contractile::distribution_moment::steady_curve;
use crate::physics::contractile::hill::force_velocity;
use crate::physics::contractile::huxley_exact::steady_q1;
use crate::physics::model::ModelKind;
use crate::sim::scenario::{Run, Scenario};
use crate::sim::simulation::default_stepping;
use plot::{write_chart, Chart, Series};
use plotters::style::RGBColor;
use std::fmt::Write as _;
use std::path::Path;

const HILL_COLOR: RGBColor = RGBColor(0xd6, 0x27, 0x28);
const DM_COLOR: RGBColor = RGBColor(0x1f, 0x77, 0xb4);
const PDE_COLOR: RGBColor = RGBColor(0x2c, 0xa0, 0x2c);

/// A colour per model, in the order of the model list.
const PALETTE: [RGBColor; 6] = [
    HILL_COLOR,
    DM_COLOR,
    PDE_COLOR,
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x8c, 0x56, 0x4b),
];

fn color(model: ModelKind) -> RGBColor {
    let i = ModelKind::all().position(|m| m == model).unwrap_or(0);
    PALETTE[i % PALETTE.len()]
}

fn label(model: ModelKind) -> &'static str {
    model.label()
}

fn run(name: &str, model: ModelKind, cfg: &ActuatorConfig) -> Result<Run, String> {
    let sc = Scenario::built_in(name, &cfg.muscles[0].params)?;
    sc.run(cfg, model, 1000.0, default_stepping(model))
}

fn series(run: &Run, f: impl Fn(&crate::sim::MuscleSnapshot) -> f64) -> Vec<(f64, f64)> {
    run.records
        .iter()
        .map(|r| (r.time, f(&r.muscles[0])))
        .collect()
}

/// Value of the first muscle's signal at time t (nearest tick).
fn at(run: &Run, t: f64, f: impl Fn(&crate::sim::MuscleSnapshot) -> f64) -> f64 {
    let i = ((t * run.rate_hz).round() as usize).min(run.records.len() - 1);
    f(&run.records[i].muscles[0])
}

/// Time from `start` until the force first reaches `frac` of its value at `plateau_t`, s.
fn rise_time(run: &Run, start: f64, plateau_t: f64, frac: f64) -> f64 {
    let target = frac * at(run, plateau_t, |m| m.ce_force);
    run.records
        .iter()
        .find(|r| r.time >= start && r.muscles[0].ce_force >= target)
        .map_or(f64::NAN, |r| r.time - start)
}

fn rms_and_max(a: &Run, b: &Run, f: impl Fn(&crate::sim::MuscleSnapshot) -> f64) -> (f64, f64) {
    let (mut sq, mut max, mut n) = (0.0, 0.0f64, 0usize);
    for (ra, rb) in a.records.iter().zip(&b.records) {
        let d = f(&ra.muscles[0]) - f(&rb.muscles[0]);
        sq += d * d;
        max = max.max(d.abs());
        n += 1;
    }
    ((sq / n.max(1) as f64).sqrt(), max)
}

/// Swing (max - min) of a signal over [t0, t1].
fn swing(run: &Run, t0: f64, t1: f64, f: impl Fn(&crate::sim::MuscleSnapshot) -> f64) -> f64 {
    let vals = run
        .records
        .iter()
        .filter(|r| r.time >= t0 && r.time <= t1)
        .map(|r| f(&r.muscles[0]));
    let (lo, hi) = vals.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    hi - lo
}

/// Writes every figure and `summary.md` into `dir`.
pub fn write_all(dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let cfg = ActuatorConfig::default();
    let mut summary = String::from("# Figures: the numbers they show\n\n");

    // Figs. 4 and 5: the pulse, three models.
    let pulse: Vec<(ModelKind, Run)> = ModelKind::all()
        .map(|m| run("pulse", m, &cfg).map(|r| (m, r)))
        .collect::<Result<_, _>>()?;
    let chart = |title, y_label, f: &dyn Fn(&crate::sim::MuscleSnapshot) -> f64| Chart {
        title,
        x_label: "time (s)",
        y_label,
        series: pulse
            .iter()
            .map(|(m, r)| Series {
                label: label(*m),
                color: color(*m),
                points: series(r, f),
                dashed: false,
            })
            .collect(),
    };
    write_chart(
        dir,
        "fig4_pulse_ce_force",
        &chart(
            "Fig. 4: contractile force, 1 s excitation pulse",
            "F_CE (N)",
            &|m| m.ce_force,
        ),
    )?;
    write_chart(
        dir,
        "fig5_pulse_fiber_length",
        &chart(
            "Fig. 5: fibre length, 1 s excitation pulse",
            "l_m (m)",
            &|m| m.fiber_length,
        ),
    )?;
    write_chart(
        dir,
        "pulse_stiffness",
        &chart(
            "Contractile stiffness k_CE, 1 s excitation pulse",
            "k_CE (N/m)",
            &|m| m.stiffness,
        ),
    )?;

    let _ = writeln!(
        summary,
        "## Pulse (Figs. 4-5): clamped MTU, excitation 1 from 1 s to 2 s\n"
    );
    let _ = writeln!(summary, "| model | F_CE at 1.9 s (N) | fibre shortening (mm) | 90% rise time (ms) | force 50 ms after release (N) |");
    let _ = writeln!(summary, "|---|---|---|---|---|");
    for (m, r) in &pulse {
        let _ = writeln!(
            summary,
            "| {} | {:.1} | {:.3} | {:.1} | {:.1} |",
            m.name(),
            at(r, 1.9, |s| s.ce_force),
            1e3 * (at(r, 0.5, |s| s.fiber_length) - at(r, 1.9, |s| s.fiber_length)),
            1e3 * rise_time(r, 1.0, 1.9, 0.9),
            at(r, 2.05, |s| s.ce_force),
        );
    }
    let by = |k: ModelKind| {
        &pulse
            .iter()
            .find(|(m, _)| *m == k)
            .expect("all models run")
            .1
    };
    let (rms, max) = rms_and_max(by(ModelKind::HUXLEY), by(ModelKind::HUXLEY_PDE), |s| {
        s.ce_force
    });
    let (rms_l, max_l) = rms_and_max(by(ModelKind::HUXLEY), by(ModelKind::HUXLEY_PDE), |s| {
        s.fiber_length
    });
    let _ = writeln!(summary, "\nDM vs full Huxley over the pulse: F_CE RMS {rms:.1} N, max {max:.1} N; l_m RMS {:.3} mm, max {:.3} mm.", rms_l * 1e3, max_l * 1e3);
    let (rms, max) = rms_and_max(by(ModelKind::HILL), by(ModelKind::HUXLEY), |s| s.ce_force);
    let _ = writeln!(
        summary,
        "Hill vs DM over the pulse: F_CE RMS {rms:.1} N, max {max:.1} N.\n"
    );

    // Fig. 6: energies under a sinusoidal pull, 10 Hz and 100 Hz.
    let _ = writeln!(
        summary,
        "## Energy (Fig. 6): passive muscle, tendon pulled by 150 + 150 sin(2πft) N\n"
    );
    let _ = writeln!(summary, "Swings (max - min) over the last 0.1 s; the tendon's share is its swing over the sum of both elements' swings.\n");
    let _ = writeln!(summary, "| f | tendon swing (J) | parallel element swing (J) | total (tendon + PE) swing (J) | tendon share |");
    let _ = writeln!(summary, "|---|---|---|---|---|");
    for (name, f) in [("energy-10hz", 10.0), ("energy-100hz", 100.0)] {
        let r = run(name, ModelKind::HILL, &cfg)?;
        write_chart(
            dir,
            &format!("fig6_{}", name.replace('-', "_")),
            &Chart {
                title: &format!("Fig. 6: strain energy, sinusoidal tendon force at {f} Hz"),
                x_label: "time (s)",
                y_label: "energy (J)",
                series: vec![
                    Series {
                        label: "tendon",
                        color: DM_COLOR,
                        points: series(&r, |m| m.tendon_energy),
                        dashed: false,
                    },
                    Series {
                        label: "tendon + parallel element",
                        color: HILL_COLOR,
                        points: series(&r, |m| m.tendon_energy + m.fiber_energy),
                        dashed: false,
                    },
                ],
            },
        )?;
        let t_swing = swing(&r, 0.1, 0.2, |m| m.tendon_energy);
        let pe_swing = swing(&r, 0.1, 0.2, |m| m.fiber_energy);
        let total = swing(&r, 0.1, 0.2, |m| m.tendon_energy + m.fiber_energy);
        let _ = writeln!(
            summary,
            "| {f} Hz | {t_swing:.4} | {pe_swing:.4} | {total:.4} | {:.1}% |",
            100.0 * t_swing / (t_swing + pe_swing)
        );
    }

    // Steady force–velocity curves.
    let p = &cfg.muscles[0].params;
    let dm = calibrate_distribution_moment(p).map_err(|e| e.to_string())?;
    let ex = calibrate_exact(p);
    let shortening: Vec<f64> = (0..=50).map(|i| i as f64 / 50.0).collect();
    let lengthening: Vec<f64> = (1..=50).map(|i| -(i as f64) / 50.0).collect();
    let dm_curve = |vs: &[f64]| -> Result<Vec<(f64, f64)>, String> {
        let us: Vec<f64> = vs.iter().map(|v| v * p.v_max / dm.l_h).collect();
        let q = steady_curve(&dm.rates, &us).map_err(|e| e.to_string())?;
        Ok(vs
            .iter()
            .zip(q)
            .map(|(v, q)| (*v, dm.force(q[1]) / p.f_max))
            .collect())
    };
    let mut dm_points = dm_curve(&lengthening)?;
    dm_points.reverse();
    dm_points.extend(dm_curve(&shortening)?);
    let grid: Vec<f64> = dm_points.iter().map(|(v, _)| *v).collect();
    let exact_points: Vec<(f64, f64)> = grid
        .iter()
        .map(|v| {
            (
                *v,
                ex.force(steady_q1(&ex.rates, 1.0, v * p.v_max / ex.l_h)) / p.f_max,
            )
        })
        .collect();
    let hill_points: Vec<(f64, f64)> = grid
        .iter()
        .map(|v| {
            (
                *v,
                force_velocity(v * p.v_max, p.v_max, p.eccentric_asymptote),
            )
        })
        .collect();
    write_chart(
        dir,
        "force_velocity",
        &Chart {
            title: "Steady force-velocity at full activation, optimal length",
            x_label: "shortening velocity v_s / vmax",
            y_label: "F / Fmax",
            series: vec![
                Series {
                    label: "Hill",
                    color: HILL_COLOR,
                    points: hill_points,
                    dashed: true,
                },
                Series {
                    label: "Huxley (DM)",
                    color: DM_COLOR,
                    points: dm_points.clone(),
                    dashed: false,
                },
                Series {
                    label: "Huxley (exact)",
                    color: PDE_COLOR,
                    points: exact_points.clone(),
                    dashed: false,
                },
            ],
        },
    )?;
    let dev = |lo: f64, hi: f64| {
        dm_points
            .iter()
            .zip(&exact_points)
            .filter(|((v, _), _)| *v >= lo && *v <= hi)
            .map(|((_, a), (_, b))| (a - b).abs())
            .fold(0.0, f64::max)
    };
    let _ = writeln!(
        summary,
        "\n## Steady force-velocity, DM vs exact Huxley\n\nLargest |F_DM - F_exact| / Fmax: {:.3} while shortening (0 < v_s <= vmax), {:.3} while lengthening (-vmax <= v_s < 0). Both are exact at v_s = 0 and at vmax by calibration.",
        dev(1e-9, 1.0),
        dev(-1.0, -1e-9)
    );
    std::fs::write(dir.join("summary.md"), &summary)
        .map_err(|e| format!("cannot write {}: {e}", dir.join("summary.md").display()))?;
    print!("{summary}");
    Ok(())
}
