//! `compare A B`: the differences between two recorded runs, per muscle and joint.

use super::error::{CompareError, RunError};
use super::{load_run, LoadedRun};
use serde::Serialize;
use std::path::Path;

/// Differences of one signal.
#[derive(Debug, Clone, Serialize)]
pub struct SignalDiff {
    /// `muscle.force`, `joint.position`, ...
    pub signal: String,
    /// Root mean square of B − A over the compared samples, in the signal's unit.
    pub rms_diff: f64,
    /// Largest |B − A|, in the signal's unit.
    pub max_abs_diff: f64,
    /// Time of the largest difference, s.
    pub(crate) max_diff_time: f64,
    /// Run A's peak: its value of largest magnitude (signed), in the signal's unit.
    pub peak_a: f64,
    pub(crate) peak_b: f64,
    /// Time of the peak (largest absolute value), s.
    pub(crate) peak_time_a: f64,
    pub(crate) peak_time_b: f64,
    /// 10 %–90 % rise time of the first rise towards the peak, s (None: no rise).
    pub rise_time_a: Option<f64>,
    /// The same in run B, s.
    pub rise_time_b: Option<f64>,
}

/// What one muscle spent over the compared span, in each run (docs/model.md §11.6).
#[derive(Debug, Clone, Serialize)]
pub struct EnergyFigures {
    /// The muscle's name.
    pub muscle: String,
    /// Metabolic energy over the span (the rise of `metabolic_energy`), J.
    pub energy_a_j: f64,
    /// The same in run B, J.
    pub energy_b_j: f64,
    /// Root mean square of `metabolic_power` over the span's samples, W.
    pub rms_power_a_w: f64,
    /// The same in run B, W.
    pub rms_power_b_w: f64,
    /// The phenomenological model's energy over the span, J.
    pub(crate) phenomenological_energy_a_j: f64,
    pub(crate) phenomenological_energy_b_j: f64,
}

/// The comparison.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// Run A's model (`hill`, `huxley`, `huxley-pde`).
    pub model_a: String,
    /// Run B's model.
    pub model_b: String,
    /// Start of the compared time span, s.
    pub start: f64,
    /// End of the compared time span, s.
    pub end: f64,
    /// Samples compared.
    pub samples: usize,
    /// Differences of each signal of every muscle and joint.
    pub signals: Vec<SignalDiff>,
    /// What each muscle spent in the common span, in each run.
    pub energies: Vec<EnergyFigures>,
    /// Warnings on the files read (one per file cut by a crash, read up to the cut).
    #[serde(skip)]
    pub warnings: Vec<String>,
}

/// The muscle fields compared, by their names in the one field list
/// ([`muscle_actuator_core::sim::MuscleSnapshot::FIELDS`]).
pub(crate) const MUSCLE_SIGNALS: [&str; 6] = [
    "force",
    "fiber_length",
    "stiffness",
    "metabolic_power",
    "metabolic_energy",
    "phenomenological_energy",
];
/// The joint fields compared ([`muscle_actuator_core::sim::JointSnapshot::FIELDS`]).
pub(crate) const JOINT_SIGNALS: [&str; 3] = ["position", "torque", "stiffness"];

/// (time, value) series of every compared signal of a run.
pub fn series(run: &LoadedRun) -> Vec<(String, Vec<(f64, f64)>)> {
    let rate = run.meta.rate_hz;
    let mut out: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    let mut push = |name: String, t: f64, v: f64| {
        if let Some(s) = out.iter_mut().find(|(n, _)| *n == name) {
            s.1.push((t, v));
        } else {
            out.push((name, vec![(t, v)]));
        }
    };
    for s in &run.states {
        let t = s.tick as f64 / rate;
        for m in &s.muscles {
            for f in MUSCLE_SIGNALS {
                let v = m.state.get(f).unwrap_or(f64::NAN);
                push(format!("{}.{f}", m.name), t, v);
            }
        }
        for (j, name) in s.joints.iter().zip(&s.joint) {
            for f in JOINT_SIGNALS {
                push(format!("{name}.{f}"), t, j.get(f).unwrap_or(f64::NAN));
            }
        }
    }
    out
}

/// Linear interpolation of a time-sorted series at t (inside its span).
fn interp(s: &[(f64, f64)], t: f64) -> Option<f64> {
    let i = s.partition_point(|p| p.0 < t);
    if i < s.len() && s[i].0 == t {
        return Some(s[i].1);
    }
    if i == 0 || i >= s.len() {
        return None;
    }
    let (t0, v0) = s[i - 1];
    let (t1, v1) = s[i];
    Some(v0 + (v1 - v0) * (t - t0) / (t1 - t0))
}

fn peak(s: &[(f64, f64)]) -> (f64, f64) {
    s.iter()
        .copied()
        .fold((f64::NAN, 0.0), |(bt, bv): (f64, f64), (t, v)| {
            if bt.is_nan() || v.abs() > bv.abs() {
                (t, v)
            } else {
                (bt, bv)
            }
        })
}

/// 10 %–90 % rise time from the series' start value towards its peak.
fn rise_time(s: &[(f64, f64)]) -> Option<f64> {
    let (tp, vp) = peak(s);
    let v0 = s.first()?.1;
    let span = vp - v0;
    if span.abs() < 1e-12 * vp.abs().max(1e-300) || span == 0.0 {
        return None;
    }
    let crossing = |frac: f64| {
        s.iter()
            .take_while(|p| p.0 <= tp)
            .find(|p| (p.1 - v0) / span >= frac)
            .map(|p| p.0)
    };
    Some(crossing(0.9)? - crossing(0.1)?)
}

fn sorted_names(run: &LoadedRun, joints: bool) -> Vec<String> {
    let mut v = if joints {
        run.meta.joints.clone()
    } else {
        run.meta.muscles.clone()
    };
    v.sort();
    v
}

/// Compares two runs. Refuses runs with different muscles or joints, or without common time.
pub(crate) fn compare_runs(a: &LoadedRun, b: &LoadedRun) -> Result<Comparison, CompareError> {
    if sorted_names(a, false) != sorted_names(b, false) {
        return Err(CompareError::DifferentMuscles {
            a: a.meta.muscles.clone(),
            b: b.meta.muscles.clone(),
        });
    }
    if sorted_names(a, true) != sorted_names(b, true) {
        return Err(CompareError::DifferentJoints {
            a: a.meta.joints.clone(),
            b: b.meta.joints.clone(),
        });
    }
    let sa = series(a);
    let sb = series(b);
    let span = |s: &[(String, Vec<(f64, f64)>)]| {
        s.first()
            .and_then(|(_, v)| Some((v.first()?.0, v.last()?.0)))
    };
    let (Some((a0, a1)), Some((b0, b1))) = (span(&sa), span(&sb)) else {
        return Err(CompareError::NoStates);
    };
    let (start, end) = (a0.max(b0), a1.min(b1));
    if start >= end {
        return Err(CompareError::NoOverlap {
            a: (a0, a1),
            b: (b0, b1),
        });
    }
    let mut signals = Vec::new();
    let mut samples = 0;
    for (name, va) in &sa {
        let Some((_, vb)) = sb.iter().find(|(n, _)| n == name) else {
            continue;
        };
        let va: Vec<(f64, f64)> = va
            .iter()
            .copied()
            .filter(|p| p.0 >= start && p.0 <= end)
            .collect();
        let vb: Vec<(f64, f64)> = vb
            .iter()
            .copied()
            .filter(|p| p.0 >= start && p.0 <= end)
            .collect();
        let (mut sum2, mut n, mut max, mut tmax) = (0.0, 0usize, 0.0f64, start);
        for &(t, x) in &va {
            if let Some(y) = interp(&vb, t) {
                let d = x - y;
                sum2 += d * d;
                n += 1;
                if d.abs() > max {
                    max = d.abs();
                    tmax = t;
                }
            }
        }
        samples = samples.max(n);
        let (pta, pa) = peak(&va);
        let (ptb, pb) = peak(&vb);
        signals.push(SignalDiff {
            signal: name.clone(),
            rms_diff: if n > 0 {
                (sum2 / n as f64).sqrt()
            } else {
                f64::NAN
            },
            max_abs_diff: max,
            max_diff_time: tmax,
            peak_a: pa,
            peak_b: pb,
            peak_time_a: pta,
            peak_time_b: ptb,
            rise_time_a: rise_time(&va),
            rise_time_b: rise_time(&vb),
        });
    }
    let energies = a
        .meta
        .muscles
        .iter()
        .map(|m| energy_figures(m, &sa, &sb, start, end))
        .collect();
    let c = Comparison {
        model_a: a.meta.model.name().into(),
        model_b: b.meta.model.name().into(),
        start,
        end,
        samples,
        signals,
        energies,
        warnings: Vec::new(),
    };
    c.check_finite()?;
    Ok(c)
}

/// Muscle `m`'s energy figures over [start, end] from the two runs' series.
fn energy_figures(
    m: &str,
    sa: &[(String, Vec<(f64, f64)>)],
    sb: &[(String, Vec<(f64, f64)>)],
    start: f64,
    end: f64,
) -> EnergyFigures {
    let within = |s: &[(String, Vec<(f64, f64)>)], f: &str| -> Vec<(f64, f64)> {
        let key = format!("{m}.{f}");
        s.iter()
            .find(|(n, _)| *n == key)
            .map(|(_, v)| {
                v.iter()
                    .copied()
                    .filter(|p| p.0 >= start && p.0 <= end)
                    .collect()
            })
            .unwrap_or_default()
    };
    let rise = |v: &[(f64, f64)]| match (v.first(), v.last()) {
        (Some(a), Some(b)) => b.1 - a.1,
        _ => f64::NAN,
    };
    let rms = |v: &[(f64, f64)]| (v.iter().map(|p| p.1 * p.1).sum::<f64>() / v.len() as f64).sqrt();
    EnergyFigures {
        muscle: m.to_string(),
        energy_a_j: rise(&within(sa, "metabolic_energy")),
        energy_b_j: rise(&within(sb, "metabolic_energy")),
        rms_power_a_w: rms(&within(sa, "metabolic_power")),
        rms_power_b_w: rms(&within(sb, "metabolic_power")),
        phenomenological_energy_a_j: rise(&within(sa, "phenomenological_energy")),
        phenomenological_energy_b_j: rise(&within(sb, "phenomenological_energy")),
    }
}

impl Comparison {
    /// Refuses a comparison with a figure that is not finite: values too large to difference,
    /// or a signal without a sample of A inside the common span.
    fn check_finite(&self) -> Result<(), CompareError> {
        for d in &self.signals {
            let figures = [
                ("rms diff", Some(d.rms_diff)),
                ("max diff", Some(d.max_abs_diff)),
                ("time of the max diff", Some(d.max_diff_time)),
                ("peak A", Some(d.peak_a)),
                ("peak B", Some(d.peak_b)),
                ("time of peak A", Some(d.peak_time_a)),
                ("time of peak B", Some(d.peak_time_b)),
                ("rise time A", d.rise_time_a),
                ("rise time B", d.rise_time_b),
            ];
            for (name, v) in figures {
                if let Some(value) = v.filter(|v| !v.is_finite()) {
                    return Err(CompareError::NotFinite {
                        signal: d.signal.clone(),
                        figure: name,
                        value,
                    });
                }
            }
        }
        Ok(())
    }

    /// A readable table; the name column as wide as its longest name, so that the numbers
    /// stay in their columns.
    pub fn table(&self) -> String {
        let opt = |v: Option<f64>| v.map(|x| format!("{x:.4}")).unwrap_or_else(|| "-".into());
        const SIGNAL: &str = "signal";
        const ENERGY: &str = "energy over the span";
        let w = (self.signals.iter().map(|d| d.signal.chars().count()))
            .chain(self.energies.iter().map(|e| e.muscle.chars().count()))
            .chain([SIGNAL.len(), ENERGY.len()])
            .max()
            .unwrap_or(0);
        let mut s = format!(
            "A: {}   B: {}   compared {:.4}..{:.4} s ({} samples)\n",
            self.model_a, self.model_b, self.start, self.end, self.samples
        );
        s.push_str(&format!(
            "{:<w$} {:>12} {:>12} {:>9} {:>12} {:>12} {:>9} {:>9} {:>9} {:>9}\n",
            SIGNAL,
            "rms diff",
            "max diff",
            "at s",
            "peak A",
            "peak B",
            "t peak A",
            "t peak B",
            "rise A",
            "rise B"
        ));
        for d in &self.signals {
            s.push_str(&format!(
                "{:<w$} {:>12.5e} {:>12.5e} {:>9.4} {:>12.5e} {:>12.5e} {:>9.4} {:>9.4} {:>9} {:>9}\n",
                d.signal,
                d.rms_diff,
                d.max_abs_diff,
                d.max_diff_time,
                d.peak_a,
                d.peak_b,
                d.peak_time_a,
                d.peak_time_b,
                opt(d.rise_time_a),
                opt(d.rise_time_b)
            ));
        }
        s.push_str(&format!(
            "\n{:<w$} {:>12} {:>12} {:>12} {:>12} {:>14} {:>14}\n",
            ENERGY,
            "A (J)",
            "B (J)",
            "rms P A (W)",
            "rms P B (W)",
            "phenom. A (J)",
            "phenom. B (J)"
        ));
        for e in &self.energies {
            s.push_str(&format!(
                "{:<w$} {:>12.5e} {:>12.5e} {:>12.5e} {:>12.5e} {:>14.5e} {:>14.5e}\n",
                e.muscle,
                e.energy_a_j,
                e.energy_b_j,
                e.rms_power_a_w,
                e.rms_power_b_w,
                e.phenomenological_energy_a_j,
                e.phenomenological_energy_b_j
            ));
        }
        s
    }
}

/// Draws the overlay of two runs' muscle forces as a file (the `muscle_actuator` crate's
/// `figures::compare_plot::plot`; plots are not this crate's business).
// A String error: the figures layer's own error text, carried as [`RunError::Plot`].
pub type PlotFn = fn(&LoadedRun, &LoadedRun, &Path) -> Result<(), String>;

/// `compare A B`: loads both (a file cut by a crash up to the cut, with a warning), compares,
/// optionally plots (to the path, with the function given).
pub fn compare_files(
    a: &Path,
    b: &Path,
    plot_out: Option<(&Path, PlotFn)>,
) -> Result<Comparison, RunError> {
    if let Some((p, _)) = plot_out {
        for written in [p.with_extension("png"), p.with_extension("svg")] {
            muscle_actuator_core::files::check_not_an_input(&written, &[a, b])?;
        }
    }
    let ra = load_run(a)?;
    let rb = load_run(b)?;
    for (run, path) in [(&ra, a), (&rb, b)] {
        if run.states.is_empty() {
            return Err(RunError::NoStates {
                path: path.to_path_buf(),
            });
        }
    }
    let mut c = compare_runs(&ra, &rb)?;
    c.warnings = [&ra, &rb]
        .iter()
        .filter_map(|r| r.warning.clone())
        .collect();
    if let Some((p, plot)) = plot_out {
        plot(&ra, &rb, p).map_err(RunError::Plot)?;
    }
    Ok(c)
}
