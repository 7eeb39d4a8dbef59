//! The Butterworth design and both filters against SciPy (crates/core/tests/reference/emg/, written by
//! scripts/scipy_emg_filters.py with SciPy 1.17.1): every section's coefficients, and the causal
//! (`sosfilt`) and zero-phase (`sosfiltfilt`) outputs of one seeded input, for low-, high- and
//! band-pass filters of orders 2 to 5. Tolerance 1e-10, relative to the largest coefficient of
//! the same polynomial, or to the largest value of the same output.

use crate::emg::butterworth::{butterworth, Band};
use crate::emg::filter::{filter_causal, filter_zero_phase, SosFilter};
use crate::emg::sos::Sos;

const SOS_TABLE: &str = include_str!("../../../tests/reference/emg/scipy_butter_sos.csv");
const FILTERED_TABLE: &str = include_str!("../../../tests/reference/emg/scipy_filtered.csv");
const TOLERANCE: f64 = 1e-10;

/// One filter of the table: its design and SciPy's sections (b0..a2 per row).
struct Case {
    name: String,
    order: usize,
    band: Band,
    fs_hz: f64,
    sections: Vec<[f64; 6]>,
}

/// The table's rows without its comment line and header, split at commas.
fn rows(table: &str) -> impl Iterator<Item = Vec<&str>> {
    table
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').collect())
}

fn num(s: &str) -> f64 {
    s.parse().unwrap()
}

fn cases() -> Vec<Case> {
    let mut out: Vec<Case> = Vec::new();
    for r in rows(SOS_TABLE) {
        let coefficients: Vec<f64> = r[7..13].iter().map(|s| num(s)).collect();
        let row: [f64; 6] = coefficients.try_into().unwrap();
        if out.last().map(|c| c.name != r[0]).unwrap_or(true) {
            let band = match r[1] {
                "lowpass" => Band::LowPass {
                    cut_off_hz: num(r[3]),
                },
                "highpass" => Band::HighPass {
                    cut_off_hz: num(r[3]),
                },
                _ => Band::BandPass {
                    low_hz: num(r[3]),
                    high_hz: num(r[4]),
                },
            };
            out.push(Case {
                name: r[0].to_string(),
                order: r[2].parse().unwrap(),
                band,
                fs_hz: num(r[5]),
                sections: Vec::new(),
            });
        }
        out.last_mut().unwrap().sections.push(row);
    }
    assert_eq!(out.len(), 8);
    out
}

/// The filtered table's column named `name`.
fn column(name: &str) -> Vec<f64> {
    let mut lines = FILTERED_TABLE.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let j = header.iter().position(|h| *h == name).unwrap();
    lines.map(|l| num(l.split(',').nth(j).unwrap())).collect()
}

fn design(case: &Case) -> Sos {
    butterworth(case.order, case.band, case.fs_hz).unwrap()
}

/// Largest |x - y| over the largest |y|.
fn relative_difference(x: &[f64], y: &[f64]) -> f64 {
    assert_eq!(x.len(), y.len());
    let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .zip(y)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale
}

#[test]
fn sections_match_scipy() {
    let mut worst = 0.0f64;
    for case in cases() {
        let sos = design(&case);
        assert_eq!(sos.sections().len(), case.sections.len(), "{}", case.name);
        for (ours, theirs) in sos.sections().iter().zip(&case.sections) {
            let db = relative_difference(&ours.b, &theirs[0..3]);
            let da = relative_difference(&ours.a, &theirs[3..6]);
            assert!(
                db <= TOLERANCE && da <= TOLERANCE,
                "{}: {ours:?} vs {theirs:?}",
                case.name
            );
            worst = worst.max(db).max(da);
        }
    }
    eprintln!("sections: largest relative difference from SciPy {worst:.2e}");
}

#[test]
fn causal_output_matches_scipy() {
    let x = column("input");
    let mut worst = 0.0f64;
    for case in cases() {
        let y = filter_causal(&design(&case), &x).unwrap();
        let d = relative_difference(&y, &column(&format!("{}_causal", case.name)));
        assert!(d <= TOLERANCE, "{}: {d:e}", case.name);
        worst = worst.max(d);
    }
    eprintln!("causal: largest relative difference from sosfilt {worst:.2e}");
}

#[test]
fn zero_phase_output_matches_scipy() {
    let x = column("input");
    let mut worst = 0.0f64;
    for case in cases() {
        let y = filter_zero_phase(&design(&case), &x).unwrap();
        let d = relative_difference(&y, &column(&format!("{}_zero_phase", case.name)));
        assert!(d <= TOLERANCE, "{}: {d:e}", case.name);
        worst = worst.max(d);
    }
    eprintln!("zero-phase: largest relative difference from sosfiltfilt {worst:.2e}");
}

#[test]
fn stepped_filter_equals_whole_signal() {
    let x = column("input");
    for case in cases() {
        let sos = design(&case);
        let whole = filter_causal(&sos, &x).unwrap();
        let mut f = SosFilter::new(sos);
        let stepped: Vec<f64> = x.iter().map(|&v| f.step(v)).collect();
        assert_eq!(stepped, whole, "{}", case.name);
        f.reset();
        assert_eq!(f.step(x[0]), whole[0], "{}", case.name);
    }
}

#[test]
fn settled_filter_holds_its_dc_output() {
    for case in cases() {
        let sos = design(&case);
        let dc: f64 = sos
            .sections()
            .iter()
            .map(|s| s.b.iter().sum::<f64>() / s.a.iter().sum::<f64>())
            .product();
        let mut f = SosFilter::new(sos);
        f.settle(0.7);
        for _ in 0..50 {
            assert!((f.step(0.7) - 0.7 * dc).abs() <= 1e-12, "{}", case.name);
        }
    }
}
