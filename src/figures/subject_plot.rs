//! `predict --plot`: a prediction drawn, as PNG and SVG. `OUT.png` (and `OUT.svg`): one panel per
//! degree of freedom, the predicted joint moment against the measured one, its R² and RMSE in
//! the panel's title; `OUT_forces.png` (and `.svg`): the units' tendon forces through the trial,
//! one line per unit, the legend beside the chart.

use super::error::{FigureError, PlotError};
use super::palette::{BLACK, BLUE};
use super::plot::{register_font, stage_panels, Chart, Panel, Series};
use muscle_actuator_core::files::AtomicFile;
use muscle_actuator_measured::measured::rating::Rating;
use muscle_actuator_measured::subject::Prediction;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// The forces chart's size without its legend, and the legend column's width, pixels.
const FORCES_PX: (u32, u32) = (1100, 640);
const LEGEND_PX: u32 = 260;
/// Height of a legend entry, pixels.
const ENTRY_PX: u32 = 18;

/// The units' colours: ten (Matplotlib's `tab10`), then again dashed, then dotted.
const COLORS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// The images `stage` draws for `out`: `OUT.png`, `OUT.svg`, `OUT_forces.png`,
/// `OUT_forces.svg` (beside `out`).
pub fn outputs(out: &Path) -> Result<[PathBuf; 4], FigureError> {
    let (dir, stem) = dir_and_stem(out)?;
    let forces = format!("{stem}_forces");
    Ok([
        dir.join(format!("{stem}.png")),
        dir.join(format!("{stem}.svg")),
        dir.join(format!("{forces}.png")),
        dir.join(format!("{forces}.svg")),
    ])
}

/// The directory and the file stem of `out`.
fn dir_and_stem(out: &Path) -> Result<(&Path, &str), FigureError> {
    let dir = (out.parent())
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let stem =
        (out.file_stem().and_then(|s| s.to_str())).ok_or_else(|| FigureError::PlotFileName {
            path: out.to_path_buf(),
        })?;
    Ok((dir, stem))
}

/// The figures of `p` for `out` ([`outputs`]) drawn under temporary names beside them, not yet
/// in place: the caller renames them ([`super::plot::commit_all`]) once all its outputs are
/// made, so that a failure leaves none.
pub fn stage(
    p: &Prediction,
    ratings: &[(String, Rating)],
    trial: &str,
    out: &Path,
) -> Result<Vec<AtomicFile>, FigureError> {
    let (dir, stem) = dir_and_stem(out)?;
    let mut staged = Vec::from(moments_figure(dir, stem, p, ratings)?);
    staged.extend(forces_figure(dir, &format!("{stem}_forces"), p, trial)?);
    Ok(staged)
}

/// One panel per degree of freedom: measured (black) and predicted (blue) moment, N m.
fn moments_figure(
    dir: &Path,
    stem: &str,
    p: &Prediction,
    ratings: &[(String, Rating)],
) -> Result<[AtomicFile; 2], FigureError> {
    let titles: Vec<String> = (p.dofs.iter().enumerate())
        .map(|(d, dof)| match ratings.get(d) {
            Some((_, r)) => format!("{dof}: R² {:.3}, RMSE {:.1} N m", r.r_squared, r.rmse),
            None => dof.clone(),
        })
        .collect();
    let curve = |label, color, values: &[f64]| Series {
        label,
        color,
        points: p
            .times
            .iter()
            .copied()
            .zip(values.iter().copied())
            .collect(),
        dashed: false,
    };
    let panels: Vec<Panel> = (titles.iter().enumerate())
        .map(|(d, title)| Panel {
            chart: Chart {
                title,
                x_label: "time (s)",
                y_label: "moment (N m)",
                series: vec![
                    curve("measured", BLACK, &p.measured[d]),
                    curve("predicted", BLUE, &p.moment[d]),
                ],
            },
            markers: vec![],
            legend: SeriesLabelPosition::UpperRight,
        })
        .collect();
    stage_panels(dir, stem, &panels)
}

/// The forces figure drawn as `stem.png` and `stem.svg` in `dir` under temporary names, not
/// yet committed.
fn forces_figure(
    dir: &Path,
    stem: &str,
    p: &Prediction,
    trial: &str,
) -> Result<[AtomicFile; 2], FigureError> {
    register_font();
    let rows = u32::try_from(p.units.len()).unwrap_or(u32::MAX);
    let height = FORCES_PX
        .1
        .max(rows.saturating_mul(ENTRY_PX).saturating_add(80));
    let size = (FORCES_PX.0 + LEGEND_PX, height);
    let create = |ext: &str| {
        let path = dir.join(format!("{stem}.{ext}"));
        AtomicFile::create(&path).map_err(|source| FigureError::CreateFile { path, source })
    };
    let (png, svg) = (create("png")?, create("svg")?);
    let drawn = |out: &AtomicFile| {
        let path = out.target().to_path_buf();
        move |source| FigureError::Draw { path, source }
    };
    let title = format!("Tendon forces of the units, {trial}");
    let png_area = BitMapBackend::new(png.path(), size).into_drawing_area();
    draw_forces(png_area, p, &title).map_err(drawn(&png))?;
    let svg_area = SVGBackend::new(svg.path(), size).into_drawing_area();
    draw_forces(svg_area, p, &title).map_err(drawn(&svg))?;
    Ok([png, svg])
}

/// Unit `i`'s line: its colour and whether dashed (`Some((dash, gap))`, pixels).
fn unit_style(i: usize) -> (RGBColor, Option<(u32, u32)>) {
    let dash = match (i / COLORS.len()) % 3 {
        0 => None,
        1 => Some((8, 5)),
        _ => Some((2, 4)),
    };
    (COLORS[i % COLORS.len()], dash)
}

/// The backend's error as [`PlotError`].
fn err<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> PlotError {
    PlotError(e.to_string())
}

/// The forces chart on the left of `root`, its legend in a column on the right.
fn draw_forces<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    p: &Prediction,
    title: &str,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    let (chart_area, legend_area) = root.split_horizontally(FORCES_PX.0);
    let (t0, t1) = (p.times.first().copied(), p.times.last().copied());
    let (t0, t1) = (t0.unwrap_or(0.0), t1.unwrap_or(1.0));
    let finite = p.force.iter().flatten().copied().filter(|f| f.is_finite());
    let top = finite.fold(0.0f64, f64::max);
    let mut c = ChartBuilder::on(&chart_area)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(t0..t1.max(t0 + 1e-9), 0.0..(1.05 * top).max(1.0))
        .map_err(err)?;
    c.configure_mesh()
        .x_desc("time (s)")
        .y_desc("tendon force (N)")
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .draw()
        .map_err(err)?;
    for (i, force) in p.force.iter().enumerate() {
        let (color, dash) = unit_style(i);
        let style = ShapeStyle::from(&color).stroke_width(2);
        let points = (p.times.iter().copied().zip(force.iter().copied()))
            .filter(|(t, f)| t.is_finite() && f.is_finite());
        match dash {
            None => c.draw_series(LineSeries::new(points, style)),
            Some((d, g)) => c.draw_series(DashedLineSeries::new(points, d, g, style)),
        }
        .map_err(err)?;
    }
    draw_legend(&legend_area, p)?;
    root.present().map_err(err)
}

/// One entry per unit down `area`: a sample of its line, its name.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: &Prediction,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    for (i, unit) in p.units.iter().enumerate() {
        let (color, dash) = unit_style(i);
        let style = ShapeStyle::from(&color).stroke_width(2);
        let y = 60 + (i as i32) * ENTRY_PX as i32;
        let segments: Vec<(i32, i32)> = match dash {
            None => vec![(0, 28)],
            Some((d, g)) => {
                let (d, g) = (d as i32, g as i32);
                (0..)
                    .map(|k| (k * (d + g), k * (d + g) + d))
                    .take_while(|s| s.0 < 28)
                    .collect()
            }
        };
        for (a, b) in segments {
            let path = PathElement::new(vec![(10 + a, y), (10 + b.min(28), y)], style);
            area.draw(&path).map_err(err)?;
        }
        let text = Text::new(unit.as_str(), (46, y - 7), ("sans-serif", 14).into_font());
        area.draw(&text).map_err(err)?;
    }
    Ok(())
}
