//! The steady-state energetics figure (docs/model.md §11.3, §11.5): steady force, metabolic
//! (chemical) power and efficiency against v_s / vmax at full activation and optimal length, for
//! the Hill model with Umberger (the default energy model) and with Bhargava, and for the
//! cross-bridge energetics of the DM and the full Huxley model ([`muscle_actuator_core::sim::steady`]). Over the
//! full model: Hill's (1938) heat coefficient, the line of slope `P0 + a` through its isometric
//! rate, and Huxley's (1957) closed form `Ė/Ė0 = 1 + (f1/g1)(1 - e^{-φ})/φ` at 1/4, 1/2 and
//! 1 vmax. Its key numbers go to the summary.

use super::error::FigureError;
use super::palette::{color, BLACK, ORANGE};
use super::plot::{write_panels, Chart, Markers, Panel, Series};
use muscle_actuator_core::physics::contractile::calibrate_exact;
use muscle_actuator_core::physics::energetics::{
    activation_heat_w, energy_rate_ratio, exact_isometric_bridge_w, exact_point, BridgeEnergyScale,
};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{EnergyModel, MuscleParams};
use muscle_actuator_core::sim::steady::{steady_table, EnergySource, SteadyRow};
use plotters::prelude::SeriesLabelPosition;
use plotters::style::RGBColor;
use std::fmt::Write as _;
use std::path::Path;

/// Velocities from -vmax to vmax: a step of 0.002 vmax.
const GRID_POINTS: usize = 1001;
/// Where Huxley (1957) tabulated his energy rate, v_s / vmax.
const HUXLEY_FRACTIONS: [f64; 3] = [0.25, 0.5, 1.0];
/// Hill's heat-coefficient line is drawn from v_s = 0 to this fraction of vmax.
const HILL_LINE_END: f64 = 0.15;

/// One curve: its label, colour, dash and its steady states from -vmax to vmax.
struct Curve {
    label: String,
    color: RGBColor,
    dashed: bool,
    rows: Vec<SteadyRow>,
}

impl Curve {
    /// (v_s / vmax, y) over the rows with v_s / vmax ≥ `from`.
    fn points(&self, from: f64, y: impl Fn(&SteadyRow) -> f64) -> Vec<(f64, f64)> {
        let rows = self.rows.iter().filter(|r| r.v_over_vmax >= from);
        rows.map(|r| (r.v_over_vmax, y(r))).collect()
    }
    fn isometric(&self) -> &SteadyRow {
        &self.rows[self.rows.len() / 2]
    }
    /// The highest efficiency while shortening: (v_s / vmax, efficiency).
    fn efficiency_peak(&self) -> (f64, f64) {
        self.points(0.0, |r| r.point.efficiency)
            .into_iter()
            .fold((0.0, 0.0), |best, x| if x.1 > best.1 { x } else { best })
    }
}

/// The four curves: Hill + Umberger, Hill + Bhargava, DM and the full model by cross-bridges.
fn curves(p: &MuscleParams) -> Result<Vec<Curve>, FigureError> {
    let curve =
        |model: ModelKind, source: EnergySource, color, dashed| -> Result<Curve, FigureError> {
            let label = match source {
                EnergySource::CrossBridge => format!("{}, cross-bridges", model.spec().short_label),
                EnergySource::Phenomenological(m) => format!("{} + {}", model.label(), m.label()),
            };
            let table = steady_table(p, model, GRID_POINTS)?;
            let rows = table.into_iter().filter(|r| r.source == source).collect();
            Ok(Curve {
                label,
                color,
                dashed,
                rows,
            })
        };
    let phen = EnergySource::Phenomenological;
    Ok(vec![
        curve(
            ModelKind::HILL,
            phen(EnergyModel::Umberger),
            color(ModelKind::HILL),
            false,
        )?,
        curve(ModelKind::HILL, phen(EnergyModel::Bhargava), ORANGE, true)?,
        curve(
            ModelKind::HUXLEY,
            EnergySource::CrossBridge,
            color(ModelKind::HUXLEY),
            false,
        )?,
        curve(
            ModelKind::HUXLEY_PDE,
            EnergySource::CrossBridge,
            color(ModelKind::HUXLEY_PDE),
            false,
        )?,
    ])
}

/// Hill's (1938) heat coefficient through the full model's isometric rate: `Ė(0) + (P0 + a)
/// v_s` (a/P0 the muscle's, 0.25 by default), from 0 to [`HILL_LINE_END`] vmax, W.
fn hill_heat_line(p: &MuscleParams, full: &Curve) -> Vec<(f64, f64)> {
    let e0 = full.isometric().point.chemical_w;
    let slope_w_per_m_s = (1.0 + p.energetics.hill_a_over_p0) * p.f_max;
    [0.0, HILL_LINE_END]
        .map(|f| (f, e0 + slope_w_per_m_s * f * p.v_max))
        .to_vec()
}

/// Huxley's (1957) closed form at [`HUXLEY_FRACTIONS`]: the full model's isometric bridge
/// rate times `Ė/Ė0`, plus its activation cost, W.
fn huxley_points(p: &MuscleParams) -> Vec<(f64, f64)> {
    let scale = calibrate_exact(p);
    let e = BridgeEnergyScale::new(&scale, p, &p.energetics.bridge());
    let iso = exact_isometric_bridge_w(&scale, &e);
    let act = activation_heat_w(1.0, e.activation_share, iso);
    let ratio = |f: f64| energy_rate_ratio(&scale.rates, f * p.v_max / scale.l_h);
    HUXLEY_FRACTIONS.map(|f| (f, act + iso * ratio(f))).to_vec()
}

/// One panel: each curve's `y` while shortening (v_s / vmax from 0 to 1; lengthening is in the
/// summary: its forces reach 1.7 to 4.8 Fmax and would flatten the rest), labelled in the
/// legend if `legend`.
fn panel<'a>(
    curves: &'a [Curve],
    (title, y_label): (&'a str, &'a str),
    legend: bool,
    y: impl Fn(&SteadyRow) -> f64,
) -> Panel<'a> {
    let series = curves.iter().map(|c| Series {
        label: if legend { &c.label } else { "" },
        color: c.color,
        points: c.points(0.0, &y),
        dashed: c.dashed,
    });
    Panel {
        chart: Chart {
            title,
            x_label: "shortening velocity v_s / vmax",
            y_label,
            series: series.collect(),
        },
        markers: Vec::new(),
        legend: SeriesLabelPosition::UpperRight,
    }
}

/// Writes `steady_energetics.png` (and `.svg`) for the muscle `p` and appends its numbers to
/// `summary`.
pub fn steady_energetics_figure(
    dir: &Path,
    p: &MuscleParams,
    summary: &mut String,
) -> Result<(), FigureError> {
    let curves = curves(p)?;
    let force_axis = ("Steady force", "F / Fmax");
    let force = panel(&curves, force_axis, true, |r| r.point.force_n / p.f_max);
    let power_axis = ("Metabolic power", "chemical power (W)");
    let mut power = panel(&curves, power_axis, false, |r| r.point.chemical_w);
    power.chart.series.push(Series {
        label: "Hill (1938): slope P0 + a at v_s = 0",
        color: BLACK,
        points: hill_heat_line(p, &curves[3]),
        dashed: true,
    });
    power.markers.push(Markers {
        label: "Huxley (1957) closed form",
        color: BLACK,
        points: huxley_points(p),
    });
    power.legend = SeriesLabelPosition::LowerRight;
    let efficiency_axis = ("Efficiency", "work / chemical power");
    let efficiency = panel(&curves, efficiency_axis, false, |r| r.point.efficiency);
    write_panels(dir, "steady_energetics", &[force, power, efficiency])?;
    summarise(p, &curves, summary);
    Ok(())
}

/// The figure's numbers: per curve the isometric power (W, W/kg), its ratio at vmax and at
/// -vmax (with the force there), the peak efficiency and where; the full model against
/// Huxley's closed form and Hill's coefficient.
fn summarise(p: &MuscleParams, curves: &[Curve], out: &mut String) {
    let mass = p.energetics.mass_kg(p.f_max, p.l_opt);
    let _ = writeln!(
        out,
        "\n## Steady-state energetics (steady_energetics.png)\n"
    );
    let _ = writeln!(out, "Full activation, optimal length, v_s / vmax every 0.002; per kg of the metabolic mass {mass:.4} kg. Ė: chemical power; -vmax: lengthening at vmax.\n");
    let _ = writeln!(out, "| model, energy | isometric Ė (W) | isometric Ė (W/kg) | Ė(vmax) / Ė(0) | peak efficiency | at v_s / vmax | Ė(-vmax) / Ė(0) | F(-vmax) / Fmax |");
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|");
    for c in curves {
        let (iso, first, last) = (c.isometric(), &c.rows[0], &c.rows[c.rows.len() - 1]);
        let (at, peak) = c.efficiency_peak();
        let _ = writeln!(
            out,
            "| {} | {:.1} | {:.1} | {:.3} | {peak:.3} | {at:.3} | {:.3} | {:.3} |",
            c.label,
            iso.point.chemical_w,
            iso.chemical_w_kg,
            last.point.chemical_w / iso.point.chemical_w,
            first.point.chemical_w / iso.point.chemical_w,
            first.point.force_n / p.f_max,
        );
    }
    full_model_checks(p, &curves[3], &curves[2], out);
}

/// The full model's bridges over their isometric rate at Huxley's velocities, against his
/// closed form; its slope at v_s = 0 against Hill's `P0 + a`; the DM's first step.
fn full_model_checks(p: &MuscleParams, full: &Curve, dm: &Curve, out: &mut String) {
    let s = p.energetics.activation_share;
    let e0 = full.isometric().point.chemical_w;
    let bridges = |w: f64| format!("{:.4}", (w - s * e0) / ((1.0 - s) * e0));
    let at = |f: f64| full.rows.iter().find(|r| (r.v_over_vmax - f).abs() < 1e-9);
    let rows = HUXLEY_FRACTIONS.iter().filter_map(|&f| at(f));
    let ratios: Vec<String> = rows.map(|r| bridges(r.point.chemical_w)).collect();
    let closed: Vec<String> = huxley_points(p).iter().map(|(_, w)| bridges(*w)).collect();
    let scale = calibrate_exact(p);
    let e = BridgeEnergyScale::new(&scale, p, &p.energetics.bridge());
    let dv = 1e-7 * p.v_max;
    let rise = exact_point(&scale, &e, dv).chemical_w - exact_point(&scale, &e, 0.0).chemical_w;
    let slope = rise / dv / p.f_max;
    let dm_iso = dm.isometric().point.chemical_w;
    let dm_step = dm.rows[dm.rows.len() / 2 + 1].point.chemical_w / dm_iso;
    let _ = writeln!(
        out,
        "\nFull model, bridges over their isometric rate at 1/4, 1/2, 1 vmax: {} (Huxley's closed form: {}; his table, with his rate fractions: 3.739, 4.410, 4.834). \
         Its slope at v_s = 0: {slope:.4} Fmax (Hill 1938: P0 + a = {:.2} Fmax). \
         DM at 0.002 vmax: {dm_step:.4} of its isometric rate (its closure dips before it rises).",
        ratios.join(", "),
        closed.join(", "),
        1.0 + p.energetics.hill_a_over_p0,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The figure is written, PNG and SVG, with the four curves and both marks; the summary
    /// holds the documented numbers (docs/model.md §11.3) and Huxley's closed form.
    #[test]
    fn the_figure_and_its_numbers() {
        let dir = std::env::temp_dir().join(format!("steady_figure_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut summary = String::new();
        steady_energetics_figure(&dir, &MuscleParams::default(), &mut summary).unwrap();
        let png = std::fs::read(dir.join("steady_energetics.png")).unwrap();
        assert!(png.starts_with(b"\x89PNG") && png.len() > 10_000);
        let svg = std::fs::read_to_string(dir.join("steady_energetics.svg")).unwrap();
        for label in [
            "full Huxley, cross-bridges",
            "Hill + Bhargava 2004",
            "Huxley (1957)",
        ] {
            assert!(svg.contains(label), "{label}");
        }
        for row in [
            "| DM, cross-bridges | 216.6 | 136.2 | 2.942 | 0.307 | 0.090 |",
            "| full Huxley, cross-bridges | 224.9 | 141.4 | 3.490 | 0.288 | 0.166 |",
            "| Hill + Bhargava 2004 | 284.7 | 179.0 |",
            "isometric rate at 1/4, 1/2, 1 vmax: 3.7376, 4.4078, 4.8314 (Huxley's closed form: \
             3.7376, 4.4078, 4.8314;",
            "Its slope at v_s = 0: 1.2500 Fmax",
        ] {
            assert!(summary.contains(row), "{row} not in {summary}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
