//! The paper's figures reproduced (Figs. 4–6 of Jovanović et al. 2015, docs/model.md §9), plus the
//! steady force–velocity curves of the three models, their steady-state energetics
//! ([`energetics`], §11) and what the muscles cost in runs ([`cost`]), as PNG and SVG, and a
//! summary of the numbers they show (`summary.md`). The colours are [`palette`]'s, the drawing
//! [`plot`]'s, the runs and samples [`samples`]'; [`compare_plot`] draws `compare --plot`.

pub mod compare_plot;
pub mod cost;
pub mod energetics;
pub mod error;
pub mod palette;
pub mod plot;
pub mod samples;
pub mod subject_plot;

pub use error::{FigureError, PlotError};
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::contractile::{
    calibrate_distribution_moment, calibrate_exact, force_velocity, steady_curve, steady_q1,
};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::MuscleParams;
use muscle_actuator_core::sim::{MuscleSnapshot, Run};
use palette::{color, BLUE, RED};
use plot::{write_chart, Chart, Series};
use samples::{at, run, series};
use std::fmt::Write as _;
use std::path::Path;

/// Time from `start` until the force first reaches `frac` of its value at `plateau_t`, s.
fn rise_time(run: &Run, start: f64, plateau_t: f64, frac: f64) -> f64 {
    let target = frac * at(run, plateau_t, |m| m.ce_force);
    run.records()
        .find(|r| r.time >= start && r.muscles[0].ce_force >= target)
        .map_or(f64::NAN, |r| r.time - start)
}

fn rms_and_max(a: &Run, b: &Run, f: impl Fn(&MuscleSnapshot) -> f64) -> (f64, f64) {
    let (mut sq, mut max, mut n) = (0.0, 0.0f64, 0usize);
    for (ra, rb) in a.records().zip(b.records()) {
        let d = f(&ra.muscles[0]) - f(&rb.muscles[0]);
        sq += d * d;
        max = max.max(d.abs());
        n += 1;
    }
    ((sq / n.max(1) as f64).sqrt(), max)
}

/// Swing (max - min) of a signal over [t0, t1].
fn swing(run: &Run, t0: f64, t1: f64, f: impl Fn(&MuscleSnapshot) -> f64) -> f64 {
    let vals = run
        .records()
        .filter(|r| r.time >= t0 && r.time <= t1)
        .map(|r| f(&r.muscles[0]));
    let (lo, hi) = vals.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    hi - lo
}

/// Writes every figure and `summary.md` into `dir`, each file whole or not at all
/// ([`muscle_actuator_core::files::AtomicFile`]).
pub fn write_all(dir: &Path) -> Result<(), FigureError> {
    std::fs::create_dir_all(dir).map_err(|source| FigureError::CreateDir {
        path: dir.to_path_buf(),
        source,
    })?;
    let cfg = ActuatorConfig::default();
    let mut summary = String::from("# Figures: the numbers they show\n\n");
    pulse_figures(dir, &cfg, &mut summary)?;
    energy_figures(dir, &cfg, &mut summary)?;
    force_velocity_figure(dir, &cfg, &mut summary)?;
    energetics::steady_energetics_figure(dir, &cfg.muscles[0].params, &mut summary)?;
    cost::stiffness_cost_figure(dir, &cfg, &mut summary)?;
    let path = dir.join("summary.md");
    muscle_actuator_core::files::write_atomically(&path, summary.as_bytes())
        .map_err(|source| FigureError::Write { path, source })?;
    print!("{summary}");
    Ok(())
}

/// Figs. 4 and 5 and the stiffness under the pulse, every model; their table and the
/// differences between neighbours in the model list.
fn pulse_figures(
    dir: &Path,
    cfg: &ActuatorConfig,
    summary: &mut String,
) -> Result<(), FigureError> {
    let pulse: Vec<(ModelKind, Run)> = ModelKind::all()
        .map(|m| run("pulse", m, cfg).map(|r| (m, r)))
        .collect::<Result<_, _>>()?;
    let chart = |title, y_label, f: &dyn Fn(&MuscleSnapshot) -> f64| Chart {
        title,
        x_label: "time (s)",
        y_label,
        series: pulse
            .iter()
            .map(|(m, r)| Series {
                label: m.label(),
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
    pulse_table(&pulse, summary);
    pulse_differences(&pulse, summary);
    cost::pulse_power_figure(dir, cfg, &pulse, summary)
}

/// The pulse's numbers per model.
fn pulse_table(pulse: &[(ModelKind, Run)], summary: &mut String) {
    let _ = writeln!(
        summary,
        "## Pulse (Figs. 4-5): clamped MTU, excitation 1 from 1 s to 2 s\n"
    );
    let _ = writeln!(summary, "| model | F_CE at 1.9 s (N) | fibre shortening (mm) | 90% rise time (ms) | force 50 ms after release (N) |");
    let _ = writeln!(summary, "|---|---|---|---|---|");
    for (m, r) in pulse {
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
}

/// Each model against the next one in the list (from the simplest to the reference), the pair
/// that ends at the reference first: the contractile force, and for that pair the fibre length
/// too.
fn pulse_differences(pulse: &[(ModelKind, Run)], summary: &mut String) {
    summary.push('\n');
    for (k, pair) in pulse.windows(2).rev().enumerate() {
        let [(ma, a), (mb, b)] = pair else {
            continue;
        };
        let (sa, sb) = (ma.spec().short_label, mb.spec().short_label);
        let (rms, max) = rms_and_max(a, b, |s| s.ce_force);
        let _ = write!(
            summary,
            "{sa} vs {sb} over the pulse: F_CE RMS {rms:.1} N, max {max:.1} N"
        );
        if k == 0 {
            let (rms, max) = rms_and_max(a, b, |s| s.fiber_length);
            let _ = write!(
                summary,
                "; l_m RMS {:.3} mm, max {:.3} mm",
                rms * 1e3,
                max * 1e3
            );
        }
        summary.push_str(".\n");
    }
    summary.push('\n');
}

/// Fig. 6: the energies under a sinusoidal pull at 10 Hz and 100 Hz (the Hill model: the
/// passive muscle is the same in every model).
fn energy_figures(
    dir: &Path,
    cfg: &ActuatorConfig,
    summary: &mut String,
) -> Result<(), FigureError> {
    let _ = writeln!(
        summary,
        "## Energy (Fig. 6): passive muscle, tendon pulled by 150 + 150 sin(2πft) N\n"
    );
    let _ = writeln!(summary, "Swings (max - min) over the last 0.1 s; the tendon's share is its swing over the sum of both elements' swings.\n");
    let _ = writeln!(summary, "| f | tendon swing (J) | parallel element swing (J) | total (tendon + PE) swing (J) | tendon share |");
    let _ = writeln!(summary, "|---|---|---|---|---|");
    for (name, f) in [("energy-10hz", 10.0), ("energy-100hz", 100.0)] {
        let r = run(name, ModelKind::HILL, cfg)?;
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
                        color: BLUE,
                        points: series(&r, |m| m.tendon_energy),
                        dashed: false,
                    },
                    Series {
                        label: "tendon + parallel element",
                        color: RED,
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
    Ok(())
}

/// The steady force–velocity curves at full activation and optimal length, F / Fmax against
/// v_s / vmax from -1 to 1: Hill's g(v) (docs/model.md §3), the Distribution-Moment steady states
/// (§6) and the exact Huxley ones (§7), on one grid.
fn steady_curves(p: &MuscleParams) -> Result<[Vec<(f64, f64)>; 3], FigureError> {
    let dm = calibrate_distribution_moment(p)?;
    let ex = calibrate_exact(p);
    let shortening: Vec<f64> = (0..=50).map(|i| i as f64 / 50.0).collect();
    let lengthening: Vec<f64> = (1..=50).map(|i| -(i as f64) / 50.0).collect();
    let dm_curve = |vs: &[f64]| -> Result<Vec<(f64, f64)>, FigureError> {
        let us: Vec<f64> = vs.iter().map(|v| v * p.v_max / dm.l_h).collect();
        let q = steady_curve(&dm.rates, &us)?;
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
    Ok([hill_points, dm_points, exact_points])
}

/// The steady force–velocity figure ([`steady_curves`]), each curve in its model's colour, and
/// how far the Distribution-Moment curve is from the exact one.
fn force_velocity_figure(
    dir: &Path,
    cfg: &ActuatorConfig,
    summary: &mut String,
) -> Result<(), FigureError> {
    let [hill_points, dm_points, exact_points] = steady_curves(&cfg.muscles[0].params)?;
    write_chart(
        dir,
        "force_velocity",
        &Chart {
            title: "Steady force-velocity at full activation, optimal length",
            x_label: "shortening velocity v_s / vmax",
            y_label: "F / Fmax",
            series: vec![
                Series {
                    label: ModelKind::HILL.label(),
                    color: color(ModelKind::HILL),
                    points: hill_points,
                    dashed: true,
                },
                Series {
                    label: ModelKind::HUXLEY.label(),
                    color: color(ModelKind::HUXLEY),
                    points: dm_points.clone(),
                    dashed: false,
                },
                Series {
                    label: "Huxley (exact)",
                    color: color(ModelKind::HUXLEY_PDE),
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
    Ok(())
}
