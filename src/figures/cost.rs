//! What the muscles cost (docs/model.md §11.6): metabolic power through the paper's pulse
//! beside its force, and the cost of stiffness, joint stiffness against metabolic power for
//! isometric co-contraction of the elbow from rest to full excitation, per model.

use super::error::FigureError;
use super::palette::color;
use super::plot::{write_chart, write_chart_with_legend, Chart, Series};
use super::samples::{at, run, series};
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::EnergyModel;
use muscle_actuator_core::sim::{
    default_stepping, MuscleSnapshot, Run, Scenario, Schedule, ScheduledInput, SetupKind, Signal,
};
use plotters::chart::SeriesLabelPosition;
use plotters::style::RGBColor;
use std::fmt::Write as _;
use std::path::Path;

/// Co-contraction levels of the cost-of-stiffness curve (both muscles' excitation).
pub const LEVELS: [f64; 12] = [0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0];
/// How long each level is held before it is read, s (activation and force settle in ~0.1 s).
pub const HOLD_S: f64 = 0.3;
const GREY: RGBColor = RGBColor(0x7f, 0x7f, 0x7f);

/// One co-contraction level, read at the end of its hold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CocontractionPoint {
    /// Both muscles' excitation.
    pub level: f64,
    /// The first joint's stiffness K_00, N m/rad.
    pub joint_stiffness: f64,
    /// Metabolic power of all muscles, W.
    pub metabolic_w: f64,
    /// Their phenomenological models' power, W.
    pub phenomenological_w: f64,
}

/// Every muscle of `cfg` held at excitation `level` for [`HOLD_S`], the limb free.
pub fn cocontraction(
    cfg: &ActuatorConfig,
    model: ModelKind,
    level: f64,
) -> Result<CocontractionPoint, FigureError> {
    let inputs = cfg
        .muscles
        .iter()
        .map(|m| ScheduledInput {
            signal: Signal::Excitation,
            muscle: Some(m.name.clone()),
            joint: None,
            schedule: Schedule::Constant { value: level },
        })
        .collect();
    let sc = Scenario {
        name: format!("cocontraction-{level}"),
        duration: HOLD_S,
        attachment: SetupKind::Joint,
        length: None,
        initial_force: 0.0,
        inputs,
    };
    let r = sc.run(cfg, model, 1000.0, default_stepping(model))?;
    let last = r.last().ok_or(FigureError::NoTicks)?;
    let sum = |f: fn(&MuscleSnapshot) -> f64| last.muscles.iter().map(f).sum::<f64>();
    Ok(CocontractionPoint {
        level,
        joint_stiffness: last.stiffness_matrix.first().copied().unwrap_or(0.0),
        metabolic_w: sum(|m| m.metabolic_power),
        phenomenological_w: sum(|m| m.phenomenological_power),
    })
}

/// The pulse's metabolic power, every model (and Hill with Bhargava's model, dashed), and its
/// numbers: the energy of the pulse and the power on its plateau.
pub(super) fn pulse_power_figure(
    dir: &Path,
    cfg: &ActuatorConfig,
    pulse: &[(ModelKind, Run)],
    summary: &mut String,
) -> Result<(), FigureError> {
    let bhargava = run(
        "pulse",
        ModelKind::HILL,
        &cfg.clone().with_energy_model(EnergyModel::Bhargava),
    )?;
    let mut lines: Vec<Series> = pulse
        .iter()
        .map(|(m, r)| Series {
            label: m.label(),
            color: color(*m),
            points: series(r, |s| s.metabolic_power),
            dashed: false,
        })
        .collect();
    lines.push(Series {
        label: "Hill (Bhargava 2004)",
        color: GREY,
        points: series(&bhargava, |s| s.metabolic_power),
        dashed: true,
    });
    write_chart(
        dir,
        "pulse_metabolic_power",
        &Chart {
            title: "Metabolic power, 1 s excitation pulse (beside Fig. 4's force)",
            x_label: "time (s)",
            y_label: "metabolic power (W)",
            series: lines,
        },
    )?;
    let _ = writeln!(summary, "## Metabolic power through the pulse\n");
    let _ = writeln!(summary, "Huxley models: the bridges' ATP and the calcium handling; Hill: Umberger (2010) with Uchida's (2016) options, and Bhargava (2004).\n");
    let _ = writeln!(
        summary,
        "| model | power at 1.9 s (W) | energy over the run (J) | phenomenological energy (J) |"
    );
    let _ = writeln!(summary, "|---|---|---|---|");
    let rows = pulse.iter().map(|(m, r)| (m.name().to_string(), r));
    for (name, r) in rows.chain(std::iter::once(("hill + bhargava".to_string(), &bhargava))) {
        let end = &r.last().ok_or(FigureError::NoTicks)?.muscles[0];
        let _ = writeln!(
            summary,
            "| {name} | {:.1} | {:.2} | {:.2} |",
            at(r, 1.9, |s| s.metabolic_power),
            end.metabolic_energy,
            end.phenomenological_energy
        );
    }
    summary.push('\n');
    Ok(())
}

/// The cost of stiffness: joint stiffness against metabolic power at each co-contraction level,
/// every model (and Hill with Bhargava's model, dashed), and its table.
pub(super) fn stiffness_cost_figure(
    dir: &Path,
    cfg: &ActuatorConfig,
    summary: &mut String,
) -> Result<(), FigureError> {
    let curve =
        |cfg: &ActuatorConfig, m: ModelKind| -> Result<Vec<CocontractionPoint>, FigureError> {
            LEVELS.iter().map(|&c| cocontraction(cfg, m, c)).collect()
        };
    let mut curves = Vec::new();
    for m in ModelKind::all() {
        curves.push((m.label().to_string(), color(m), false, curve(cfg, m)?));
    }
    let bhargava = cfg.clone().with_energy_model(EnergyModel::Bhargava);
    curves.push((
        "Hill (Bhargava 2004)".into(),
        GREY,
        true,
        curve(&bhargava, ModelKind::HILL)?,
    ));
    let lines = curves
        .iter()
        .map(|(label, color, dashed, pts)| Series {
            label,
            color: *color,
            points: pts
                .iter()
                .map(|p| (p.metabolic_w, p.joint_stiffness))
                .collect(),
            dashed: *dashed,
        })
        .collect();
    // The curves rise steeply and end in the upper right: the legend goes below them.
    write_chart_with_legend(
        dir,
        "cost_of_stiffness",
        &Chart {
            title: "The cost of stiffness: elbow co-contraction from rest to full excitation",
            x_label: "metabolic power of both muscles (W)",
            y_label: "joint stiffness (N m/rad)",
            series: lines,
        },
        SeriesLabelPosition::LowerRight,
    )?;
    let _ = writeln!(
        summary,
        "\n## The cost of stiffness: isometric co-contraction of the elbow\n"
    );
    let _ = writeln!(summary, "Both muscles at the same excitation for {HOLD_S} s; joint stiffness (N m/rad) and metabolic power of both (W).\n");
    let _ = write!(summary, "| excitation |");
    for (label, ..) in &curves {
        let _ = write!(summary, " {label}: K, P |");
    }
    let _ = writeln!(summary, "\n|---|{}", "---|".repeat(curves.len()));
    for (k, level) in LEVELS.iter().enumerate() {
        let _ = write!(summary, "| {level} |");
        for (.., pts) in &curves {
            let _ = write!(
                summary,
                " {:.0}, {:.1} |",
                pts[k].joint_stiffness, pts[k].metabolic_w
            );
        }
        summary.push('\n');
    }
    summary.push('\n');
    Ok(())
}
