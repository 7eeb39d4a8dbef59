//! The raw-EMG chain to a normalised linear envelope (Winter 2009; Lloyd & Besier 2003;
//! Pizzolato et al. 2015): the mean removed, a Butterworth band-pass (movement artefact and
//! high-frequency noise out), full-wave rectification, a Butterworth low-pass to the linear
//! envelope, then division by a normaliser, an MVC peak or the peak of the envelope(s) given.
//!
//! The filters run zero-phase (offline: forward and backward, no lag, the magnitude response
//! squared) or causal (online: one forward pass from rest, the envelope lagging by the filters'
//! group delay); see [`crate::emg::filter`]. Every option is a field of [`EnvelopeOptions`] with
//! its default and unit.

use crate::emg::butterworth::{butterworth, check_sample_rate, Band};
use crate::emg::error::{check_finite, EmgError};
use crate::emg::filter::{filter_causal, filter_zero_phase};

/// How the filters run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Phase {
    /// Forward and backward (offline): no lag, the magnitude response squared, so a cut-off is
    /// the -6 dB point rather than -3 dB (`scipy.signal.sosfiltfilt`). The default.
    #[default]
    ZeroPhase,
    /// One forward pass from rest (online): the output lags by the filters' group delay
    /// (`scipy.signal.sosfilt`).
    Causal,
}

/// A Butterworth band-pass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandPass {
    /// Low cut-off, Hz. Default 20 Hz (De Luca et al. 2010: movement artefact lies mostly below
    /// 20 Hz).
    pub low_hz: f64,
    /// High cut-off, Hz; must be below half the sample rate. Default 450 Hz (surface EMG holds
    /// little power above 400 to 500 Hz; De Luca et al. 2010).
    pub high_hz: f64,
    /// Order N of the design (2N poles, as `scipy.signal.butter(N, ..., 'bandpass')`). Default 4.
    pub order: usize,
}

impl Default for BandPass {
    fn default() -> Self {
        BandPass {
            low_hz: 20.0,
            high_hz: 450.0,
            order: 4,
        }
    }
}

/// A Butterworth low-pass, the linear envelope's filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LowPass {
    /// Cut-off, Hz. Default 6 Hz, common for gait (Lloyd & Besier 2003 use 6 Hz; 3 to 10 Hz is
    /// the usual range).
    pub cut_off_hz: f64,
    /// Order N of the design. Default 4.
    pub order: usize,
}

impl Default for LowPass {
    fn default() -> Self {
        LowPass {
            cut_off_hz: 6.0,
            order: 4,
        }
    }
}

/// What the envelope is divided by.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Normalisation {
    /// Not normalised: the envelope in the raw signal's unit.
    None,
    /// By a given peak, typically that of a maximal voluntary contraction's envelope processed
    /// with the same options, in the raw signal's unit; must be finite and above 0.
    MvcPeak(f64),
    /// By the largest value of the envelope(s) given (all of them together when several
    /// signals are processed at once). The default.
    #[default]
    SignalPeak,
}

/// The chain's options; `EnvelopeOptions::default()` is the chain of the module doc with the
/// defaults of each field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnvelopeOptions {
    /// Subtract the signal's mean first (the amplifier's offset). Default true.
    pub remove_mean: bool,
    /// The band-pass before rectification, or none (a signal already band-limited). Default
    /// 20-450 Hz, order 4.
    pub band_pass: Option<BandPass>,
    /// The low-pass after rectification. Default 6 Hz, order 4.
    pub low_pass: LowPass,
    /// Zero-phase (offline) or causal (online). Default zero-phase.
    pub phase: Phase,
    /// The normaliser. Default the peak of the signal(s) given.
    pub normalisation: Normalisation,
}

impl Default for EnvelopeOptions {
    fn default() -> Self {
        EnvelopeOptions {
            remove_mean: true,
            band_pass: Some(BandPass::default()),
            low_pass: LowPass::default(),
            phase: Phase::default(),
            normalisation: Normalisation::default(),
        }
    }
}

/// `x` less its mean.
pub(crate) fn remove_mean(x: &[f64]) -> Vec<f64> {
    let mean = x.iter().sum::<f64>() / x.len().max(1) as f64;
    x.iter().map(|v| v - mean).collect()
}

/// Full-wave rectification, `|x|`.
pub(crate) fn rectify(x: &[f64]) -> Vec<f64> {
    x.iter().map(|v| v.abs()).collect()
}

/// The largest value of all the signals, or -∞ if there is none.
pub(crate) fn peak(signals: &[Vec<f64>]) -> f64 {
    signals
        .iter()
        .flatten()
        .fold(f64::NEG_INFINITY, |m, &v| m.max(v))
}

/// `x / by`, in place.
fn divide(x: &mut [f64], by: f64) {
    x.iter_mut().for_each(|v| *v /= by);
}

/// The filter of `band` and `order`, run as `phase` asks.
fn filtered(
    x: &[f64],
    order: usize,
    band: Band,
    fs: f64,
    phase: Phase,
) -> Result<Vec<f64>, EmgError> {
    let sos = butterworth(order, band, fs)?;
    match phase {
        Phase::ZeroPhase => filter_zero_phase(&sos, x),
        Phase::Causal => filter_causal(&sos, x),
    }
}

/// The linear envelope of `raw` sampled at `sample_rate_hz`, not normalised.
fn unnormalised(
    raw: &[f64],
    sample_rate_hz: f64,
    options: &EnvelopeOptions,
) -> Result<Vec<f64>, EmgError> {
    check_finite(raw)?;
    if raw.is_empty() {
        return Err(EmgError::TooShort { len: 0, needed: 1 });
    }
    let centred = if options.remove_mean {
        remove_mean(raw)
    } else {
        raw.to_vec()
    };
    let band_limited = match options.band_pass {
        Some(bp) => {
            let band = Band::BandPass {
                low_hz: bp.low_hz,
                high_hz: bp.high_hz,
            };
            filtered(&centred, bp.order, band, sample_rate_hz, options.phase)?
        }
        None => centred,
    };
    let lp = options.low_pass;
    let band = Band::LowPass {
        cut_off_hz: lp.cut_off_hz,
    };
    filtered(
        &rectify(&band_limited),
        lp.order,
        band,
        sample_rate_hz,
        options.phase,
    )
}

/// The normaliser `normalisation` asks for, given the envelopes; `None` for no division.
fn normaliser(
    normalisation: Normalisation,
    envelopes: &[Vec<f64>],
) -> Result<Option<f64>, EmgError> {
    match normalisation {
        Normalisation::None => Ok(None),
        Normalisation::MvcPeak(value) if value.is_finite() && value > 0.0 => Ok(Some(value)),
        Normalisation::MvcPeak(value) => Err(EmgError::Normaliser { value }),
        Normalisation::SignalPeak => {
            let p = peak(envelopes);
            if p > 0.0 {
                Ok(Some(p))
            } else {
                Err(EmgError::ZeroPeak { peak: p })
            }
        }
    }
}

/// The normalised linear envelopes of several raw signals sampled at `sample_rate_hz`, each
/// through the same chain; [`Normalisation::SignalPeak`] divides them all by their common peak.
/// Refuses a bad rate, cut-off or order, an empty signal, a non-finite sample, a signal too
/// short for the zero-phase padding, and a normaliser not above zero.
pub fn linear_envelopes(
    raws: &[&[f64]],
    sample_rate_hz: f64,
    options: &EnvelopeOptions,
) -> Result<Vec<Vec<f64>>, EmgError> {
    check_sample_rate(sample_rate_hz)?;
    if let Normalisation::MvcPeak(value) = options.normalisation {
        normaliser(Normalisation::MvcPeak(value), &[])?;
    }
    let mut envelopes = raws
        .iter()
        .map(|raw| unnormalised(raw, sample_rate_hz, options))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(by) = normaliser(options.normalisation, &envelopes)? {
        envelopes.iter_mut().for_each(|e| divide(e, by));
    }
    Ok(envelopes)
}

/// The normalised linear envelope of one raw signal ([`linear_envelopes`] of one).
pub fn linear_envelope(
    raw: &[f64],
    sample_rate_hz: f64,
    options: &EnvelopeOptions,
) -> Result<Vec<f64>, EmgError> {
    let mut out = linear_envelopes(&[raw], sample_rate_hz, options)?;
    Ok(out.pop().unwrap_or_default())
}
