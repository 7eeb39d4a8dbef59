//! Why an EMG function refuses its input ([`EmgError`]): each variant names the value at fault,
//! and its message is one line; the check of a signal's samples shared by the filters, the chain
//! and the activation.

/// Why a filter, the envelope chain or the activation model refuses its input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EmgError {
    /// A sample rate that is not a finite number above zero.
    #[error("the sample rate must be a finite number above 0 Hz, not {value_hz}")]
    SampleRate {
        /// The rate given, Hz.
        value_hz: f64,
    },
    /// A sample period that is not a finite number above zero.
    #[error("the sample period must be a finite number above 0 s, not {value_s}")]
    SamplePeriod {
        /// The period given, s.
        value_s: f64,
    },
    /// A filter order outside 1..=[`MAX_ORDER`](crate::emg::butterworth::MAX_ORDER).
    #[error("the filter order must be 1 to {max}, not {order}")]
    Order {
        /// The order given.
        order: usize,
        /// The highest order accepted.
        max: usize,
    },
    /// A cut-off that is not strictly between 0 Hz and the Nyquist frequency.
    #[error("the cut-off {cut_off_hz} Hz must be above 0 Hz and below the Nyquist frequency {nyquist_hz} Hz")]
    CutOff {
        /// The cut-off given, Hz.
        cut_off_hz: f64,
        /// Half the sample rate, Hz.
        nyquist_hz: f64,
    },
    /// A band whose low cut-off is not below its high cut-off.
    #[error("the band's low cut-off {low_hz} Hz must be below its high cut-off {high_hz} Hz")]
    BandOrder {
        /// The low cut-off given, Hz.
        low_hz: f64,
        /// The high cut-off given, Hz.
        high_hz: f64,
    },
    /// A sample that is NaN or infinite.
    #[error("sample {index} is {value}: every sample must be a finite number")]
    NonFiniteSample {
        /// Its index in the signal.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A signal too short for the operation (the zero-phase filter's padding, or any signal at
    /// all).
    #[error("the signal has {len} samples; it needs at least {needed}")]
    TooShort {
        /// The samples given.
        len: usize,
        /// The fewest accepted.
        needed: usize,
    },
    /// A normaliser (an MVC peak) that is not a finite number above zero.
    #[error("the normaliser must be a finite number above 0, not {value}")]
    Normaliser {
        /// The value given.
        value: f64,
    },
    /// An envelope whose peak is not above zero, so it cannot normalise.
    #[error("the envelope's peak is {peak}, not above 0: it cannot normalise")]
    ZeroPeak {
        /// The peak found.
        peak: f64,
    },
    /// A recursion coefficient C1 or C2 outside the open interval (-1, 1).
    #[error("{name} must be a finite number in (-1, 1), not {value}")]
    Coefficient {
        /// `"C1"` or `"C2"`.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A coefficient above zero: its pole −C lies on the negative real axis, with no equivalent
    /// at another sample period.
    #[error(
        "{name} = {value} is above 0: its pole -{name} has no equivalent at another sample period"
    )]
    NoOtherPeriod {
        /// `"C1"` or `"C2"`.
        name: &'static str,
        /// The value.
        value: f64,
    },
    /// An electromechanical delay that is negative, not finite, or over the bound.
    #[error(
        "the electromechanical delay must be a finite number from 0 s to {max_s} s, not {value_s}"
    )]
    Delay {
        /// The delay given, s.
        value_s: f64,
        /// The longest accepted, s.
        max_s: f64,
    },
    /// A delay in samples over the bound of the delay line.
    #[error("the delay of {samples} samples is over the bound of {max} samples")]
    DelaySamples {
        /// The delay asked for, samples.
        samples: usize,
        /// The longest accepted, samples.
        max: usize,
    },
    /// A shape factor A outside the accepted range.
    #[error("the shape factor A must be a finite number from {min} to {max}, not {value}")]
    ShapeFactor {
        /// The value given.
        value: f64,
        /// The lowest accepted.
        min: f64,
        /// The highest accepted.
        max: f64,
    },
}

/// Every sample finite, or the first that is not.
pub(crate) fn check_finite(x: &[f64]) -> Result<(), EmgError> {
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(EmgError::NonFiniteSample {
            index,
            value: x[index],
        }),
        None => Ok(()),
    }
}
