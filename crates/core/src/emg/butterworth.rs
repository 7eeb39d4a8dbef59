//! Digital Butterworth filters as zeros, poles and gain, designed as `scipy.signal.butter` does
//! (SciPy 1.17, `signal/_filter_design.py`): the analog prototype's poles on the left unit
//! half-circle (Butterworth 1930), moved to the pre-warped cut-off(s) by the low-pass, high-pass
//! or band-pass transform, then mapped to the z-plane by the bilinear transform (Oppenheim &
//! Schafer 2010, the bilinear transformation: `z = (2 fs' + s)/(2 fs' - s)` with fs' = 2 in SciPy's normalised
//! frequency, where the cut-off w (a fraction of Nyquist) pre-warps to `4 tan(π w / 2)`).
//! [`butterworth`] pairs them into second-order sections ([`crate::emg::sos`]).

use crate::emg::error::EmgError;
use crate::emg::sos::{zpk_to_sos, Sos, Zpk};
use nalgebra::Complex;
use std::f64::consts::PI;

/// Highest filter order accepted (a band-pass of order N has 2N poles). EMG practice uses 1 to 8;
/// past 10, second-order sections of narrow low cut-offs lose digits to rounding.
pub const MAX_ORDER: usize = 10;

/// The band a filter passes, cut-offs in Hz (−3 dB points of one causal pass).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Band {
    /// Passes below `cut_off_hz`.
    LowPass {
        /// Cut-off, Hz.
        cut_off_hz: f64,
    },
    /// Passes above `cut_off_hz`.
    HighPass {
        /// Cut-off, Hz.
        cut_off_hz: f64,
    },
    /// Passes between `low_hz` and `high_hz`.
    BandPass {
        /// Low cut-off, Hz.
        low_hz: f64,
        /// High cut-off, Hz.
        high_hz: f64,
    },
}

/// The Butterworth filter of `order` (N; a band-pass has 2N poles) passing `band` at
/// `sample_rate_hz`, as second-order sections: `scipy.signal.butter(N, cut-off(s), btype,
/// fs=sample_rate_hz, output='sos')`.
pub fn butterworth(order: usize, band: Band, sample_rate_hz: f64) -> Result<Sos, EmgError> {
    check_sample_rate(sample_rate_hz)?;
    check_order(order)?;
    check_band(band, sample_rate_hz)?;
    Ok(zpk_to_sos(&digital_zpk(order, band, sample_rate_hz)))
}

/// A sample rate that is finite and above zero, Hz.
pub(crate) fn check_sample_rate(sample_rate_hz: f64) -> Result<(), EmgError> {
    if sample_rate_hz.is_finite() && sample_rate_hz > 0.0 {
        Ok(())
    } else {
        Err(EmgError::SampleRate {
            value_hz: sample_rate_hz,
        })
    }
}

/// An order in 1..=[`MAX_ORDER`].
pub(crate) fn check_order(order: usize) -> Result<(), EmgError> {
    if (1..=MAX_ORDER).contains(&order) {
        Ok(())
    } else {
        Err(EmgError::Order {
            order,
            max: MAX_ORDER,
        })
    }
}

/// Cut-offs strictly between 0 Hz and Nyquist, a band's low below its high.
pub(crate) fn check_band(band: Band, sample_rate_hz: f64) -> Result<(), EmgError> {
    let nyquist_hz = sample_rate_hz / 2.0;
    let cut_off = |f: f64| {
        if f.is_finite() && f > 0.0 && f < nyquist_hz {
            Ok(())
        } else {
            Err(EmgError::CutOff {
                cut_off_hz: f,
                nyquist_hz,
            })
        }
    };
    match band {
        Band::LowPass { cut_off_hz } | Band::HighPass { cut_off_hz } => cut_off(cut_off_hz),
        Band::BandPass { low_hz, high_hz } => {
            cut_off(low_hz)?;
            cut_off(high_hz)?;
            if low_hz < high_hz {
                Ok(())
            } else {
                Err(EmgError::BandOrder { low_hz, high_hz })
            }
        }
    }
}

/// The digital filter's zeros, poles and gain (inputs already checked).
pub(crate) fn digital_zpk(order: usize, band: Band, sample_rate_hz: f64) -> Zpk {
    let proto = prototype(order);
    let analog = match band {
        Band::LowPass { cut_off_hz } => to_low_pass(proto, prewarp(cut_off_hz, sample_rate_hz)),
        Band::HighPass { cut_off_hz } => to_high_pass(proto, prewarp(cut_off_hz, sample_rate_hz)),
        Band::BandPass { low_hz, high_hz } => {
            let w1 = prewarp(low_hz, sample_rate_hz);
            let w2 = prewarp(high_hz, sample_rate_hz);
            to_band_pass(proto, (w1 * w2).sqrt(), w2 - w1)
        }
    };
    bilinear(analog)
}

/// The analog prototype of order N (cut-off 1 rad/s, no zeros, gain 1): poles
/// `-exp(iπ m / 2N)` for m = -N+1, -N+3, …, N-1 (`scipy.signal.buttap`).
pub(crate) fn prototype(order: usize) -> Zpk {
    let n = order as f64;
    let p = (0..order)
        .map(|j| {
            let m = 2.0 * j as f64 - n + 1.0;
            -Complex::new(0.0, PI * m / (2.0 * n)).exp()
        })
        .collect();
    Zpk {
        z: Vec::new(),
        p,
        k: 1.0,
    }
}

/// The analog cut-off, in SciPy's normalised units, whose bilinear image is `cut_off_hz`:
/// `4 tan(π w / 2)` with `w = 2 f / fs` (Oppenheim & Schafer 2010, frequency pre-warping of the bilinear
/// transformation).
pub(crate) fn prewarp(cut_off_hz: f64, sample_rate_hz: f64) -> f64 {
    let w = 2.0 * cut_off_hz / sample_rate_hz;
    4.0 * (PI * w / 2.0).tan()
}

/// Poles minus zeros.
fn degree(zpk: &Zpk) -> usize {
    zpk.p.len().saturating_sub(zpk.z.len())
}

/// Low-pass to low-pass at `wo`: s → s/wo (`scipy.signal.lp2lp_zpk`).
fn to_low_pass(zpk: Zpk, wo: f64) -> Zpk {
    let d = degree(&zpk) as i32;
    Zpk {
        z: zpk.z.iter().map(|z| z * wo).collect(),
        p: zpk.p.iter().map(|p| p * wo).collect(),
        k: zpk.k * wo.powi(d),
    }
}

/// Low-pass to high-pass at `wo`: s → wo/s, the extra zeros at the origin
/// (`scipy.signal.lp2hp_zpk`).
fn to_high_pass(zpk: Zpk, wo: f64) -> Zpk {
    let d = degree(&zpk);
    let prod = |v: &[Complex<f64>]| v.iter().fold(Complex::new(1.0, 0.0), |acc, x| acc * -x);
    let k = zpk.k * (prod(&zpk.z) / prod(&zpk.p)).re;
    let mut z: Vec<_> = zpk.z.iter().map(|z| wo / z).collect();
    z.extend(std::iter::repeat_n(Complex::new(0.0, 0.0), d));
    Zpk {
        z,
        p: zpk.p.iter().map(|p| wo / p).collect(),
        k,
    }
}

/// Low-pass to band-pass of centre `wo` and width `bw`: s → (s² + wo²)/(s bw), each root r
/// becoming `r bw/2 ± sqrt((r bw/2)² - wo²)`, the extra zeros at the origin
/// (`scipy.signal.lp2bp_zpk`).
fn to_band_pass(zpk: Zpk, wo: f64, bw: f64) -> Zpk {
    let d = degree(&zpk);
    let split = |roots: &[Complex<f64>]| -> Vec<Complex<f64>> {
        let scaled: Vec<_> = roots.iter().map(|r| r * (bw / 2.0)).collect();
        let root = |r: &Complex<f64>| (r * r - wo * wo).sqrt();
        let plus = scaled.iter().map(|r| r + root(r));
        let minus = scaled.iter().map(|r| r - root(r));
        plus.chain(minus).collect()
    };
    let mut z = split(&zpk.z);
    z.extend(std::iter::repeat_n(Complex::new(0.0, 0.0), d));
    Zpk {
        z,
        p: split(&zpk.p),
        k: zpk.k * bw.powi(d as i32),
    }
}

/// The bilinear transform with fs' = 2: `z = (4 + s)/(4 - s)`, the zeros at infinity moved to
/// z = -1, the gain `k Π(4 - z)/Π(4 - p)` (`scipy.signal.bilinear_zpk`).
fn bilinear(zpk: Zpk) -> Zpk {
    const FS2: f64 = 4.0;
    let d = degree(&zpk);
    let map = |s: &Complex<f64>| (FS2 + s) / (FS2 - s);
    let prod = |v: &[Complex<f64>]| {
        v.iter()
            .fold(Complex::new(1.0, 0.0), |acc, x| acc * (FS2 - x))
    };
    let k = zpk.k * (prod(&zpk.z) / prod(&zpk.p)).re;
    let mut z: Vec<_> = zpk.z.iter().map(map).collect();
    z.extend(std::iter::repeat_n(Complex::new(-1.0, 0.0), d));
    Zpk {
        z,
        p: zpk.p.iter().map(map).collect(),
        k,
    }
}
