//! Every refusal of the filters and the envelope chain, each with its own variant and a
//! one-line message, and no panic on hostile numbers.

use crate::emg::butterworth::{butterworth, Band, MAX_ORDER};
use crate::emg::envelope::{
    linear_envelope, linear_envelopes, BandPass, EnvelopeOptions, LowPass, Normalisation, Phase,
};
use crate::emg::error::EmgError;
use crate::emg::filter::{filter_causal, filter_zero_phase, pad_len};
use crate::emg::neural::{delay_samples, NeuralParams};
use crate::emg::nonlinearity::ShapeFactor;

const LOW: Band = Band::LowPass { cut_off_hz: 6.0 };

fn noise(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| ((k * 7919) % 101) as f64 / 50.0 - 1.0)
        .collect()
}

#[test]
fn filter_design_refusals() {
    for fs in [0.0, -1000.0, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(butterworth(2, LOW, fs), Err(EmgError::SampleRate { .. })),
            "{fs}"
        );
    }
    for order in [0, MAX_ORDER + 1] {
        assert_eq!(
            butterworth(order, LOW, 1000.0),
            Err(EmgError::Order {
                order,
                max: MAX_ORDER
            })
        );
    }
    for f in [0.0, -5.0, 500.0, 600.0, f64::NAN] {
        let r = butterworth(2, Band::HighPass { cut_off_hz: f }, 1000.0);
        assert!(
            matches!(r, Err(EmgError::CutOff { nyquist_hz, .. }) if nyquist_hz == 500.0),
            "{f}"
        );
    }
    let inverted = Band::BandPass {
        low_hz: 300.0,
        high_hz: 30.0,
    };
    assert_eq!(
        butterworth(2, inverted, 1000.0),
        Err(EmgError::BandOrder {
            low_hz: 300.0,
            high_hz: 30.0
        })
    );
    let equal = Band::BandPass {
        low_hz: 30.0,
        high_hz: 30.0,
    };
    assert!(matches!(
        butterworth(2, equal, 1000.0),
        Err(EmgError::BandOrder { .. })
    ));
    let above = Band::BandPass {
        low_hz: 30.0,
        high_hz: 450.0,
    };
    assert_eq!(
        butterworth(2, above, 800.0),
        Err(EmgError::CutOff {
            cut_off_hz: 450.0,
            nyquist_hz: 400.0
        })
    );
}

#[test]
fn filtering_refusals() {
    let sos = butterworth(
        4,
        Band::BandPass {
            low_hz: 20.0,
            high_hz: 450.0,
        },
        1000.0,
    )
    .unwrap();
    let edge = pad_len(&sos);
    assert_eq!(edge, 27);
    assert_eq!(
        filter_zero_phase(&sos, &noise(edge)),
        Err(EmgError::TooShort {
            len: edge,
            needed: edge + 1
        })
    );
    assert_eq!(
        filter_zero_phase(&sos, &[]),
        Err(EmgError::TooShort {
            len: 0,
            needed: edge + 1
        })
    );
    assert!(filter_zero_phase(&sos, &noise(edge + 1)).is_ok());
    let mut x = noise(100);
    x[42] = f64::INFINITY;
    assert!(matches!(
        filter_causal(&sos, &x),
        Err(EmgError::NonFiniteSample { index: 42, .. })
    ));
    assert!(matches!(
        filter_zero_phase(&sos, &x),
        Err(EmgError::NonFiniteSample { index: 42, .. })
    ));
    assert_eq!(filter_causal(&sos, &[]), Ok(Vec::new()));
}

#[test]
fn envelope_refusals() {
    let x = noise(2000);
    let with = |normalisation| EnvelopeOptions {
        normalisation,
        ..EnvelopeOptions::default()
    };
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let r = linear_envelope(&x, 1000.0, &with(Normalisation::MvcPeak(bad)));
        assert!(matches!(r, Err(EmgError::Normaliser { .. })), "{bad}");
    }
    let zeros = vec![3.0; 2000];
    assert!(matches!(
        linear_envelope(&zeros, 1000.0, &EnvelopeOptions::default()),
        Err(EmgError::ZeroPeak { .. })
    ));
    assert_eq!(
        linear_envelope(&[], 1000.0, &EnvelopeOptions::default()),
        Err(EmgError::TooShort { len: 0, needed: 1 })
    );
    let short = linear_envelope(&x[..20], 1000.0, &EnvelopeOptions::default());
    assert!(matches!(short, Err(EmgError::TooShort { len: 20, .. })));
    let causal = EnvelopeOptions {
        phase: Phase::Causal,
        ..EnvelopeOptions::default()
    };
    assert!(
        linear_envelope(&x[..20], 1000.0, &causal).is_ok(),
        "a causal chain needs no padding"
    );
    assert!(matches!(
        linear_envelope(&x, 800.0, &EnvelopeOptions::default()),
        Err(EmgError::CutOff { cut_off_hz, .. }) if cut_off_hz == 450.0
    ));
    let bad_low = EnvelopeOptions {
        low_pass: LowPass {
            cut_off_hz: 6.0,
            order: 0,
        },
        ..EnvelopeOptions::default()
    };
    assert!(matches!(
        linear_envelope(&x, 1000.0, &bad_low),
        Err(EmgError::Order { order: 0, .. })
    ));
    assert!(matches!(
        linear_envelope(&x, f64::NAN, &EnvelopeOptions::default()),
        Err(EmgError::SampleRate { .. })
    ));
    let mut y = x.clone();
    y[7] = f64::NAN;
    assert!(matches!(
        linear_envelopes(&[&x, &y], 1000.0, &EnvelopeOptions::default()),
        Err(EmgError::NonFiniteSample { index: 7, .. })
    ));
}

#[test]
fn envelopes_share_one_peak_and_mvc_divides() {
    let x = noise(3000);
    let half: Vec<f64> = x.iter().map(|v| v / 2.0).collect();
    let both = linear_envelopes(&[&x, &half], 1000.0, &EnvelopeOptions::default()).unwrap();
    let peak = |v: &[f64]| v.iter().fold(f64::NEG_INFINITY, |m, &a| m.max(a));
    assert!((peak(&both[0]) - 1.0).abs() <= 1e-15);
    assert!((peak(&both[1]) - 0.5).abs() <= 1e-12);
    let raw = EnvelopeOptions {
        normalisation: Normalisation::None,
        ..EnvelopeOptions::default()
    };
    let unscaled = linear_envelope(&x, 1000.0, &raw).unwrap();
    let mvc = EnvelopeOptions {
        normalisation: Normalisation::MvcPeak(2.0),
        ..EnvelopeOptions::default()
    };
    let scaled = linear_envelope(&x, 1000.0, &mvc).unwrap();
    assert!(unscaled
        .iter()
        .zip(&scaled)
        .all(|(u, s)| (u / 2.0 - s).abs() <= 1e-15));
    let no_band = EnvelopeOptions {
        band_pass: None,
        remove_mean: false,
        ..EnvelopeOptions::default()
    };
    assert!(
        linear_envelope(&x, 100.0, &no_band).is_ok(),
        "no band-pass, no 450 Hz limit"
    );
}

#[test]
fn messages_are_one_line() {
    let errors = [
        butterworth(2, LOW, f64::NAN).unwrap_err(),
        butterworth(0, LOW, 1000.0).unwrap_err(),
        butterworth(2, Band::LowPass { cut_off_hz: 900.0 }, 1000.0).unwrap_err(),
        butterworth(
            2,
            Band::BandPass {
                low_hz: 50.0,
                high_hz: 10.0,
            },
            1000.0,
        )
        .unwrap_err(),
        filter_causal(&butterworth(2, LOW, 1000.0).unwrap(), &[f64::NAN]).unwrap_err(),
        filter_zero_phase(&butterworth(2, LOW, 1000.0).unwrap(), &[1.0]).unwrap_err(),
        linear_envelope(
            &noise(100),
            1000.0,
            &EnvelopeOptions {
                normalisation: Normalisation::MvcPeak(0.0),
                ..EnvelopeOptions::default()
            },
        )
        .unwrap_err(),
        linear_envelope(&[0.0; 100], 1000.0, &EnvelopeOptions::default()).unwrap_err(),
        NeuralParams::new(1.0, 0.0).unwrap_err(),
        NeuralParams::new(0.5, -0.5)
            .unwrap()
            .at_period(0.001, 0.002)
            .unwrap_err(),
        delay_samples(-1.0, 0.001).unwrap_err(),
        delay_samples(0.5, 1e-9).unwrap_err(),
        delay_samples(0.01, 0.0).unwrap_err(),
        ShapeFactor::new(4.0).unwrap_err(),
    ];
    for e in errors {
        let m = e.to_string();
        assert!(!m.contains('\n') && !m.is_empty(), "{m:?}");
    }
}

#[test]
fn hostile_numbers_never_panic() {
    let values = [
        0.0,
        -0.0,
        1e-310,
        -1e-310,
        1e-300,
        1.0,
        1e300,
        f64::MAX,
        f64::MIN,
        f64::NAN,
        f64::INFINITY,
        -1.0,
    ];
    let x = noise(200);
    for &fs in &values {
        for &f in &values {
            for order in [0, 1, 3, MAX_ORDER, MAX_ORDER + 1, usize::MAX] {
                for band in [
                    Band::LowPass { cut_off_hz: f },
                    Band::HighPass { cut_off_hz: f },
                    Band::BandPass {
                        low_hz: f,
                        high_hz: fs / 3.0,
                    },
                ] {
                    if let Ok(sos) = butterworth(order, band, fs) {
                        let _ = filter_causal(&sos, &x);
                        let _ = filter_zero_phase(&sos, &x);
                    }
                }
            }
            let options = EnvelopeOptions {
                band_pass: Some(BandPass {
                    low_hz: f,
                    high_hz: fs / 3.0,
                    order: 2,
                }),
                normalisation: Normalisation::MvcPeak(f),
                ..EnvelopeOptions::default()
            };
            let _ = linear_envelope(&x, fs, &options);
            let _ = delay_samples(f, fs);
            let _ = NeuralParams::new(f, fs).and_then(|p| p.at_period(f, fs));
            let _ = ShapeFactor::new(f);
        }
    }
    let huge: Vec<f64> = x.iter().map(|v| v * 1e307).collect();
    let _ = linear_envelope(&huge, 1000.0, &EnvelopeOptions::default());
}
