//! `compare --plot`: the overlay of two recorded runs' muscle forces (A solid, B dashed).

use super::error::FigureError;
use super::plot::{write_chart, Chart, Series};
use muscle_actuator_recording::runs::compare::series;
use muscle_actuator_recording::runs::LoadedRun;
use plotters::style::RGBColor;
use std::path::Path;

/// [`draw`] as the recording crate's `compare_files` takes it: its `PlotFn` signature wants the
/// error as text.
pub fn plot(a: &LoadedRun, b: &LoadedRun, out: &Path) -> Result<(), String> {
    draw(a, b, out).map_err(|e| e.to_string())
}

/// Overlay plot of the muscles' forces (A solid, B dashed) as `out` (PNG; an SVG beside it).
pub fn draw(a: &LoadedRun, b: &LoadedRun, out: &Path) -> Result<(), FigureError> {
    let colors = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
    ];
    let sa = series(a);
    let sb = series(b);
    let mut labels = Vec::new();
    let mut data = Vec::new();
    for (i, m) in a.meta.muscles.iter().enumerate() {
        let key = format!("{m}.force");
        for (run, s, dashed) in [(a, &sa, false), (b, &sb, true)] {
            if let Some((_, pts)) = s.iter().find(|(n, _)| *n == key) {
                labels.push(format!("{m} ({})", run.meta.model.name()));
                data.push((colors[i % colors.len()], pts.clone(), dashed));
            }
        }
    }
    let lines: Vec<Series> = data
        .into_iter()
        .zip(&labels)
        .map(|((color, points, dashed), label)| Series {
            label,
            color,
            points,
            dashed,
        })
        .collect();
    let dir = out
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let stem =
        out.file_stem()
            .and_then(|s| s.to_str())
            .ok_or_else(|| FigureError::PlotFileName {
                path: out.to_path_buf(),
            })?;
    let title = format!(
        "Tendon force: {} (solid) vs {} (dashed)",
        a.meta.model.name(),
        b.meta.model.name()
    );
    write_chart(
        dir,
        stem,
        &Chart {
            title: &title,
            x_label: "time (s)",
            y_label: "force (N)",
            series: lines,
        },
    )
}
