//! A line chart written as PNG and SVG (plotters), with axes, units and a legend; several side
//! by side as the panels of one figure, with markers over their curves.

use super::error::{FigureError, PlotError};
use muscle_actuator_core::files::AtomicFile;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// One curve: legend label, colour and points.
pub struct Series<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Line colour.
    pub color: RGBColor,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Dashed line.
    pub dashed: bool,
}

/// A chart: title, axis labels (with units) and curves.
pub struct Chart<'a> {
    /// Title above the plot.
    pub title: &'a str,
    /// x-axis label.
    pub x_label: &'a str,
    /// y-axis label.
    pub y_label: &'a str,
    /// The curves.
    pub series: Vec<Series<'a>>,
}

static FONT: Once = Once::new();

/// The embedded font (DejaVu Sans) for PNG text: no system fonts are needed.
pub(super) fn register_font() {
    FONT.call_once(|| {
        // The bytes are a valid TrueType font shipped by the `dejavu` crate.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

/// Points drawn as circles over a panel's curves, with a legend entry.
pub struct Markers<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Colour.
    pub color: RGBColor,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
}

/// One panel of a figure: a chart (curves with an empty label stay out of the legend), markers
/// over it, and the corner of its legend.
pub struct Panel<'a> {
    /// The curves, axes and title.
    pub chart: Chart<'a>,
    /// Points over the curves.
    pub markers: Vec<Markers<'a>>,
    /// Where the legend goes.
    pub legend: SeriesLabelPosition,
}

/// Size of one panel, pixels.
const PANEL_PX: (u32, u32) = (640, 560);

fn bounds<'a>(points: impl Iterator<Item = &'a [(f64, f64)]>) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for s in points {
        for &(x, y) in s {
            if x.is_finite() && y.is_finite() {
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
    }
    if x0 > x1 {
        return ((0.0, 1.0), (0.0, 1.0));
    }
    let pad = ((y1 - y0) * 0.05).max(1e-12 * y1.abs().max(1.0));
    ((x0, x1.max(x0 + 1e-12)), (y0 - pad, y1 + pad))
}

/// The backend's error as [`PlotError`].
fn err<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> PlotError {
    PlotError(e.to_string())
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    chart: &Chart,
    legend: SeriesLabelPosition,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    draw_panel(&root, chart, &[], legend)?;
    root.present().map_err(err)?;
    Ok(())
}

/// Draws `chart` and `markers` on `area`, the legend at `legend`.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    chart: &Chart,
    markers: &[Markers],
    legend: SeriesLabelPosition,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let curves = chart.series.iter().map(|s| &s.points[..]);
    let ((x0, x1), (y0, y1)) = bounds(curves.chain(markers.iter().map(|m| &m.points[..])));
    let mut c = ChartBuilder::on(area)
        .caption(chart.title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    c.configure_mesh()
        .x_desc(chart.x_label)
        .y_desc(chart.y_label)
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .draw()
        .map_err(err)?;
    for s in &chart.series {
        draw_curve(&mut c, s)?;
    }
    for m in markers {
        let style = ShapeStyle::from(&m.color).stroke_width(2);
        let pts = m.points.iter().copied();
        c.draw_series(pts.map(|p| Circle::new(p, 5, style)))
            .map_err(err)?
            .label(m.label)
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, style));
    }
    if chart.series.iter().any(|s| !s.label.is_empty()) || !markers.is_empty() {
        c.configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .position(legend)
            .draw()
            .map_err(err)?;
    }
    Ok(())
}

/// Draws one curve, solid or dashed, with its legend entry (none for an empty label).
fn draw_curve<'a, DB: DrawingBackend + 'a>(
    c: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    s: &Series,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let style = ShapeStyle::from(&s.color).stroke_width(2);
    let pts = s
        .points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite());
    let anno = if s.dashed {
        c.draw_series(DashedLineSeries::new(pts, 8, 5, style))
            .map_err(err)?
    } else {
        c.draw_series(LineSeries::new(pts, style)).map_err(err)?
    };
    if s.label.is_empty() {
        return Ok(());
    }
    // A dashed curve's legend entry is two dashes, a solid one's one line.
    let anno = anno.label(s.label);
    if s.dashed {
        anno.legend(move |(x, y)| {
            EmptyElement::at((x, y))
                + PathElement::new(vec![(0, 0), (8, 0)], style)
                + PathElement::new(vec![(12, 0), (20, 0)], style)
        });
    } else {
        anno.legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
    }
    Ok(())
}

/// Draws the panels side by side on `root`.
fn draw_panels<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    panels: &[Panel],
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    for (area, panel) in root.split_evenly((1, panels.len())).iter().zip(panels) {
        draw_panel(area, &panel.chart, &panel.markers, panel.legend.clone())?;
    }
    root.present().map_err(err)?;
    Ok(())
}

/// Writes `stem.png` and `stem.svg` in `dir`, the legend in the upper right corner.
pub fn write_chart(dir: &Path, stem: &str, chart: &Chart) -> Result<(), FigureError> {
    write_chart_with_legend(dir, stem, chart, SeriesLabelPosition::UpperRight)
}

/// Writes `stem.png` and `stem.svg` in `dir`, the legend at `legend` (a corner the curves
/// leave free).
pub fn write_chart_with_legend(
    dir: &Path,
    stem: &str,
    chart: &Chart,
    legend: SeriesLabelPosition,
) -> Result<(), FigureError> {
    write_png_svg(
        dir,
        stem,
        (1000, 600),
        |area| draw(area, chart, legend.clone()),
        |area| draw(area, chart, legend.clone()),
    )
}

/// Writes `stem.png` and `stem.svg` in `dir`: the panels side by side, each `PANEL_PX` (pixels).
pub fn write_panels(dir: &Path, stem: &str, panels: &[Panel]) -> Result<(), FigureError> {
    commit_all(stage_panels(dir, stem, panels)?)
}

/// As [`write_panels`], the two files left under their temporary names for the caller to commit
/// ([`commit_all`]).
pub fn stage_panels(
    dir: &Path,
    stem: &str,
    panels: &[Panel],
) -> Result<[AtomicFile; 2], FigureError> {
    let size = (PANEL_PX.0 * panels.len().max(1) as u32, PANEL_PX.1);
    stage_png_svg(
        dir,
        stem,
        size,
        |area| draw_panels(area, panels),
        |area| draw_panels(area, panels),
    )
}

/// Draws `stem.png` by `png` and `stem.svg` by `svg` in `dir`, each under a temporary name
/// beside it ([`AtomicFile`]: the backends pick the format by the extension, which it keeps),
/// and renames both into place once both are drawn: a failure leaves neither.
fn write_png_svg(
    dir: &Path,
    stem: &str,
    size: (u32, u32),
    png: impl FnOnce(DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), PlotError>,
    svg: impl FnOnce(DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), PlotError>,
) -> Result<(), FigureError> {
    commit_all(stage_png_svg(dir, stem, size, png, svg)?)
}

/// Renames drawn figures into place ([`AtomicFile::commit`]).
pub fn commit_all(staged: impl IntoIterator<Item = AtomicFile>) -> Result<(), FigureError> {
    for out in staged {
        let path = out.target().to_path_buf();
        out.commit()
            .map_err(|source| FigureError::Write { path, source })?;
    }
    Ok(())
}

/// As [`write_png_svg`], the two files left under their temporary names for the caller to
/// commit.
fn stage_png_svg(
    dir: &Path,
    stem: &str,
    size: (u32, u32),
    png: impl FnOnce(DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), PlotError>,
    svg: impl FnOnce(DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), PlotError>,
) -> Result<[AtomicFile; 2], FigureError> {
    register_font();
    let create = |ext: &str| {
        let path = dir.join(format!("{stem}.{ext}"));
        AtomicFile::create(&path).map_err(|source| FigureError::CreateFile { path, source })
    };
    let (png_out, svg_out) = (create("png")?, create("svg")?);
    let drawn = |out: &AtomicFile| {
        let path = out.target().to_path_buf();
        move |source| FigureError::Draw { path, source }
    };
    png(BitMapBackend::new(png_out.path(), size).into_drawing_area()).map_err(drawn(&png_out))?;
    svg(SVGBackend::new(svg_out.path(), size).into_drawing_area()).map_err(drawn(&svg_out))?;
    Ok([png_out, svg_out])
}
