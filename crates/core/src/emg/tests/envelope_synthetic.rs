//! The raw-EMG chain on a synthetic signal of known envelope: a seeded carrier of random
//! frequency (60 to 200 Hz, a new target every 40 ms, so band-limited and inside the default
//! 20-450 Hz band) times the envelope `0.5 + 0.4 sin(2π 1.5 t)`, plus a DC offset of 0.2, at
//! 4 kHz for 12 s, through the default chain.
//!
//! The carrier is a sine of unit amplitude whose frequency wanders, so its rectified value has
//! the same local mean (2/π) throughout: what the 6 Hz low-pass keeps of `env |sin φ|` is
//! `(2/π) env`, the harmonics of `|sin φ|` lying at 2k times the carrier frequency, where the
//! filter passes less than 1e-10 of them, except where sampling folds one back near 0 Hz
//! (2kf near a multiple of the sample rate). At 4 kHz and f ≤ 200 Hz the first that can fold is
//! the 10th (k = 10), of amplitude (4/π)/(4k² - 1), i.e. 2/(4k² - 1) = 5.0e-3 of the mean: the
//! bound on the error, relative to the peak, away from the first and last 0.5 s (where the
//! zero-phase filter's odd extension of a rectified signal starts from one sample's value). A
//! Gaussian-noise carrier would leave a ripple of about 0.755 sqrt(6 Hz / 430 Hz) ≈ 9 % of the
//! envelope, which would swamp the comparison. The rest, the low-pass's gain at 1.5 Hz (1 - 2e-5
//! zero-phase) and the band-pass's across 60-200 Hz (within 2e-4 of 1
//! zero-phase), is far smaller.
//!
//! The causal chain's lag, measured by cross-correlation with the known envelope after the
//! first 2 s, must equal the low-pass's group delay at 1.5 Hz plus the band-pass's mean group
//! delay over 60-200 Hz, within the band-pass's spread over that band plus 1 ms; the
//! zero-phase chain's lag must be zero within 0.05 sample.

use crate::emg::butterworth::{butterworth, Band};
use crate::emg::envelope::{linear_envelope, BandPass, EnvelopeOptions, LowPass, Phase};
use crate::emg::sos::Sos;
use nalgebra::Complex;
use std::f64::consts::PI;

const FS_HZ: f64 = 4000.0;
const SECONDS: f64 = 12.0;

/// xorshift64 (Marsaglia 2003), uniform in [0, 1).
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The known envelope at time `t`, s.
fn envelope_at(t: f64) -> f64 {
    0.5 + 0.4 * (2.0 * PI * 1.5 * t).sin()
}

/// The raw signal and its envelope, sample by sample.
fn synthetic() -> (Vec<f64>, Vec<f64>) {
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    let n = (SECONDS * FS_HZ) as usize;
    let hold = (0.040 * FS_HZ) as usize;
    let mut target = 60.0 + 140.0 * rng.next();
    let mut previous = target;
    let mut phase = 0.0;
    let mut raw = Vec::with_capacity(n);
    let mut env = Vec::with_capacity(n);
    for k in 0..n {
        if k % hold == 0 {
            previous = target;
            target = 60.0 + 140.0 * rng.next();
        }
        let frequency = previous + (target - previous) * (k % hold) as f64 / hold as f64;
        phase += 2.0 * PI * frequency / FS_HZ;
        let t = k as f64 / FS_HZ;
        env.push(envelope_at(t));
        raw.push(0.2 + envelope_at(t) * phase.sin());
    }
    (raw, env)
}

/// The filter's frequency response at `f_hz`.
fn response(sos: &Sos, f_hz: f64) -> Complex<f64> {
    let z1 = Complex::new(0.0, -2.0 * PI * f_hz / FS_HZ).exp();
    let z2 = z1 * z1;
    sos.sections().iter().fold(Complex::new(1.0, 0.0), |h, s| {
        h * (s.b[0] + z1 * s.b[1] + z2 * s.b[2]) / (s.a[0] + z1 * s.a[1] + z2 * s.a[2])
    })
}

/// Group delay `-dφ/dΩ` at `f_hz`, s, by central difference.
fn group_delay_s(sos: &Sos, f_hz: f64) -> f64 {
    let h = 1e-3;
    -(response(sos, f_hz + h) / response(sos, f_hz - h)).arg() / (2.0 * PI * 2.0 * h)
}

/// The lag of `y` behind `x` that maximises their cross-correlation over `from..to`, samples,
/// refined by a parabola through the three best.
fn lag_samples(x: &[f64], y: &[f64], from: usize, to: usize, max_lag: usize) -> f64 {
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let (mx, my) = (mean(&x[from..to]), mean(&y[from..to]));
    let corr = |lag: usize| {
        (from..to)
            .map(|k| (x[k] - mx) * (y[k + lag] - my))
            .sum::<f64>()
    };
    let c: Vec<f64> = (0..=max_lag).map(corr).collect();
    let best = (0..c.len()).max_by(|&i, &j| c[i].total_cmp(&c[j])).unwrap();
    if best == 0 || best == max_lag {
        return best as f64;
    }
    let (a, b, d) = (c[best - 1], c[best], c[best + 1]);
    best as f64 + 0.5 * (a - d) / (a - 2.0 * b + d)
}

/// Largest |x - y| over `range`.
fn max_error(x: &[f64], y: &[f64], range: std::ops::Range<usize>) -> f64 {
    range.map(|k| (x[k] - y[k]).abs()).fold(0.0, f64::max)
}

#[test]
fn zero_phase_envelope_matches_the_known_one_without_lag() {
    let (raw, env) = synthetic();
    let peak = env.iter().fold(0.0f64, |m, &v| m.max(v));
    let expected: Vec<f64> = env.iter().map(|v| v / peak).collect();
    let out = linear_envelope(&raw, FS_HZ, &EnvelopeOptions::default()).unwrap();
    let n = out.len();
    let margin = (0.5 * FS_HZ) as usize;
    let interior = max_error(&out, &expected, margin..n - margin);
    let whole = max_error(&out, &expected, 0..n);
    // The known envelope leads and lags nothing: compare it with the output both ways.
    let lag_out = lag_samples(&expected, &out, margin, n - margin - 50, 50);
    let lag_env = lag_samples(&out, &expected, margin, n - margin - 50, 50);
    eprintln!(
        "zero-phase: max error {interior:.2e} inside, {whole:.2e} overall; lag {lag_out:.3} / {lag_env:.3} samples"
    );
    assert!(interior <= 5e-3, "{interior}");
    assert!(
        lag_out.abs() <= 0.05 && lag_env.abs() <= 0.05,
        "{lag_out} {lag_env}"
    );
}

#[test]
fn causal_envelope_lags_by_the_group_delay() {
    let (raw, env) = synthetic();
    let options = EnvelopeOptions {
        phase: Phase::Causal,
        ..EnvelopeOptions::default()
    };
    let out = linear_envelope(&raw, FS_HZ, &options).unwrap();
    let n = out.len();
    let from = (2.0 * FS_HZ) as usize;
    let lag = lag_samples(&env, &out, from, n - 800, 800) / FS_HZ;

    let lp = LowPass::default();
    let bp = BandPass::default();
    let low = butterworth(
        lp.order,
        Band::LowPass {
            cut_off_hz: lp.cut_off_hz,
        },
        FS_HZ,
    )
    .unwrap();
    let band = Band::BandPass {
        low_hz: bp.low_hz,
        high_hz: bp.high_hz,
    };
    let band = butterworth(bp.order, band, FS_HZ).unwrap();
    let band_delays: Vec<f64> = (60..=200).map(|f| group_delay_s(&band, f as f64)).collect();
    let band_mean = band_delays.iter().sum::<f64>() / band_delays.len() as f64;
    let band_spread = band_delays
        .iter()
        .map(|d| (d - band_mean).abs())
        .fold(0.0, f64::max);
    let expected = group_delay_s(&low, 1.5) + band_mean;

    let shifted = (lag * FS_HZ).round() as usize;
    let peak = out.iter().fold(0.0f64, |m, &v| m.max(v));
    let env_peak = env.iter().fold(0.0f64, |m, &v| m.max(v));
    let aligned = (from..n - shifted).map(|k| (out[k + shifted] / peak - env[k] / env_peak).abs());
    let aligned = aligned.fold(0.0, f64::max);
    eprintln!(
        "causal: lag {:.2} ms; group delay {:.2} ms (low-pass at 1.5 Hz {:.2} ms, band-pass {:.2} ± {:.2} ms over 60-200 Hz); error once aligned {aligned:.2e}",
        lag * 1e3,
        expected * 1e3,
        group_delay_s(&low, 1.5) * 1e3,
        band_mean * 1e3,
        band_spread * 1e3
    );
    assert!(lag > 0.03, "{lag}");
    assert!(
        (lag - expected).abs() <= band_spread + 1e-3,
        "{lag} vs {expected}"
    );
}
