use super::*;
use std::path::PathBuf;

/// Uneven times from 0 to about 1 s: steps between 0.6 h and 1.4 h.
fn uneven_times(h: f64) -> Vec<f64> {
    let n = (1.0 / h).round() as usize;
    let mut t = vec![0.0];
    for i in 0..n {
        let step = h * (1.0 + 0.4 * (1.7 * i as f64).sin());
        t.push(t[i] + step);
    }
    t
}

/// Uniform times from 0 to 1 s on the step `h` (1/h whole).
fn uniform_times(h: f64) -> Vec<f64> {
    let n = (1.0 / h).round() as usize;
    (0..=n).map(|i| i as f64 * h).collect()
}

/// Times strictly between samples of `times`: a third of each step in.
fn between(times: &[f64]) -> Vec<f64> {
    times
        .windows(2)
        .map(|w| w[0] + (w[1] - w[0]) / 3.0)
        .collect()
}

/// The largest |a − b|.
fn max_error(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn linear_data_is_interpolated_and_differentiated_exactly() {
    let times = uneven_times(0.01);
    let line = |t: f64| 3.0 - 2.0 * t;
    let values: Vec<f64> = times.iter().map(|&t| line(t)).collect();
    let at = between(&times);
    let got = interpolate(&times, &values, &at).unwrap();
    let exact: Vec<f64> = at.iter().map(|&t| line(t)).collect();
    assert!(
        max_error(&got, &exact) < 4e-15,
        "{}",
        max_error(&got, &exact)
    );
    let rates = derivative_at_samples(&times, &values).unwrap();
    assert!(max_error(&rates, &vec![-2.0; rates.len()]) < 1e-12);
    let rates = derivative_at(&times, &values, &at).unwrap();
    assert!(max_error(&rates, &vec![-2.0; rates.len()]) < 1e-12);
    // Two samples: their one slope.
    assert_eq!(
        derivative_at(&[1.0, 1.5], &[2.0, 3.0], &[1.0, 1.2, 1.5]).unwrap(),
        [2.0; 3]
    );
}

#[test]
fn a_series_at_its_own_times_is_itself_bit_for_bit() {
    let times = uneven_times(0.01);
    let values: Vec<f64> = times.iter().map(|t| (7.0 * t).sin() * 40.0 + 0.1).collect();
    assert_eq!(interpolate(&times, &values, &times).unwrap(), values);
    // In any order, with repeats.
    let at = [times[5], times[0], times[5], *times.last().unwrap()];
    let expected = [values[5], values[0], values[5], *values.last().unwrap()];
    assert_eq!(interpolate(&times, &values, &at).unwrap(), expected);
    // One sample: its value at its time.
    assert_eq!(interpolate(&[2.0], &[7.0], &[2.0]).unwrap(), [7.0]);
    // Halfway, the mean of the two neighbours.
    let mid = interpolate(&[0.0, 0.5], &[1.0, 3.0], &[0.25]).unwrap();
    assert_eq!(mid, [2.0]);
}

#[test]
fn a_parabola_s_derivative_is_exact_at_and_between_samples_ends_included() {
    let times = uneven_times(0.02);
    let v = |t: f64| 0.3 + 0.5 * t - 1.5 * t * t;
    let dv = |t: f64| 0.5 - 3.0 * t;
    let values: Vec<f64> = times.iter().map(|&t| v(t)).collect();
    let at_samples = derivative_at_samples(&times, &values).unwrap();
    let exact: Vec<f64> = times.iter().map(|&t| dv(t)).collect();
    let e = max_error(&at_samples, &exact);
    let at = between(&times);
    let exact_between: Vec<f64> = at.iter().map(|&t| dv(t)).collect();
    let e_between = max_error(
        &derivative_at(&times, &values, &at).unwrap(),
        &exact_between,
    );
    println!(
        "parabola on uneven steps: derivative error {e:.1e} at samples, {e_between:.1e} between"
    );
    assert!(e < 1e-12 && e_between < 1e-12);
}

/// The largest errors of the derivative of `v` (derivative `dv`) on uniform steps `h`: inside
/// at samples, at the two ends, and at mid-steps inside.
fn errors(h: f64, v: impl Fn(f64) -> f64, dv: impl Fn(f64) -> f64) -> (f64, f64, f64) {
    let times = uniform_times(h);
    let values: Vec<f64> = times.iter().map(|&t| v(t)).collect();
    let d = derivative_at_samples(&times, &values).unwrap();
    let n = times.len();
    let inner = (1..n - 1)
        .map(|i| (d[i] - dv(times[i])).abs())
        .fold(0.0, f64::max);
    let ends = (d[0] - dv(times[0]))
        .abs()
        .max((d[n - 1] - dv(times[n - 1])).abs());
    let mids: Vec<f64> = times[1..n - 2].iter().map(|t| t + h / 2.0).collect();
    let dm = derivative_at(&times, &values, &mids).unwrap();
    let exact: Vec<f64> = mids.iter().map(|&t| dv(t)).collect();
    (inner, ends, max_error(&dm, &exact))
}

#[test]
fn a_cubic_s_derivative_errs_as_predicted_and_quarters_when_the_step_halves() {
    // v = t³, v''' = 6: central error h² v'''/6 = h²; one-sided −h² v'''/3 = −2h²; at a
    // mid-step the central error plus the interpolation's, h² + (h/2)² · 3 = 7h²/4.
    let cube = |t: f64| t * t * t;
    let d_cube = |t: f64| 3.0 * t * t;
    for h in [0.02, 0.01] {
        let (inner, ends, mids) = errors(h, cube, d_cube);
        assert!((inner / (h * h) - 1.0).abs() < 1e-9, "{h}: {inner}");
        assert!((ends / (h * h) - 2.0).abs() < 1e-9, "{h}: {ends}");
        assert!((mids / (h * h) - 1.75).abs() < 1e-9, "{h}: {mids}");
    }
    let (a, b) = (errors(0.02, cube, d_cube), errors(0.01, cube, d_cube));
    println!(
        "t³: errors at h = 0.02 s {:.3e} inside, {:.3e} at the ends, {:.3e} mid-step; at \
         h = 0.01 s {:.3e}, {:.3e}, {:.3e}; ratios {:.4}, {:.4}, {:.4}",
        a.0,
        a.1,
        a.2,
        b.0,
        b.1,
        b.2,
        a.0 / b.0,
        a.1 / b.1,
        a.2 / b.2
    );
    assert!((a.0 / b.0 - 4.0).abs() < 1e-6);
    assert!((a.1 / b.1 - 4.0).abs() < 1e-6);
    assert!((a.2 / b.2 - 4.0).abs() < 1e-6);
}

#[test]
fn a_smooth_series_derivative_is_second_order_everywhere() {
    let v = |t: f64| (5.0 * t).sin();
    let dv = |t: f64| 5.0 * (5.0 * t).cos();
    let (a, b) = (errors(0.004, v, dv), errors(0.002, v, dv));
    println!(
        "sin 5t: errors at h = 4 ms {:.3e} inside, {:.3e} at the ends, {:.3e} mid-step; ratios \
         on halving {:.3}, {:.3}, {:.3}",
        a.0,
        a.1,
        a.2,
        a.0 / b.0,
        a.1 / b.1,
        a.2 / b.2
    );
    for ratio in [a.0 / b.0, a.1 / b.1, a.2 / b.2] {
        assert!((ratio - 4.0).abs() < 0.05, "{ratio}");
    }
}

#[test]
fn times_outside_the_samples_are_refused() {
    let times = [1.0, 1.1, 1.2];
    let values = [0.0, 1.0, 4.0];
    let e = interpolate(&times, &values, &[1.05, 1.2 + 2e-9]).unwrap_err();
    assert_eq!(
        e,
        ResampleError::OutOfRange {
            index: 1,
            time_s: 1.2 + 2e-9,
            start_s: 1.0,
            end_s: 1.2
        }
    );
    assert_eq!(
        e.to_string(),
        "requested time 1 (1.200000002 s) is outside the samples' 1 s to 1.2 s (no \
         extrapolation)"
    );
    assert!(matches!(
        derivative_at(&times, &values, &[0.9]),
        Err(ResampleError::OutOfRange { index: 0, .. })
    ));
    // Within the tolerance of an end: that end.
    let near = interpolate(&times, &values, &[1.0 - 0.5e-9, 1.2 + 0.5e-9]).unwrap();
    assert_eq!(near, [0.0, 4.0]);
}

#[test]
fn bad_series_and_times_are_refused_with_one_line_messages() {
    let e = interpolate(&[0.0, 1.0], &[1.0], &[0.5]).unwrap_err();
    assert_eq!(e.to_string(), "2 sample times but 1 values");
    assert_eq!(
        interpolate(&[], &[], &[0.0]).unwrap_err(),
        ResampleError::TooFewSamples {
            found: 0,
            needed: 1
        }
    );
    assert_eq!(
        derivative_at_samples(&[0.0], &[1.0])
            .unwrap_err()
            .to_string(),
        "1 samples, at least 2 needed"
    );
    let e = interpolate(&[0.0, 1.0, 1.0], &[1.0, 2.0, 3.0], &[0.5]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "sample time 2 (1 s) is not after the previous one (1 s)"
    );
    let e = interpolate(&[0.0, f64::NAN], &[1.0, 2.0], &[0.0]).unwrap_err();
    assert_eq!(e.to_string(), "sample time 1 is NaN, not a finite number");
    let e = derivative_at(&[0.0, 1.0], &[1.0, f64::INFINITY], &[0.0]).unwrap_err();
    assert_eq!(e.to_string(), "sample value 1 is inf, not a finite number");
    let e = interpolate(&[0.0, 1.0], &[1.0, 2.0], &[0.5, f64::NAN]).unwrap_err();
    assert!(matches!(
        e,
        ResampleError::NotFinite {
            quantity: Quantity::RequestedTime,
            index: 1,
            ..
        }
    ));
    let e = derivative_at_samples(&[0.0, 1e-300], &[-f64::MAX, f64::MAX]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "the derivative at sample 0 is inf, not a finite number"
    );
    // No times asked for: no values.
    assert!(interpolate(&[0.0], &[1.0], &[]).unwrap().is_empty());
    let table = Table::parse("datacolumns 2\ndatarows 2\ntime\ta\n0\t1\n1\t2\n").unwrap();
    assert_eq!(column_at(&table, "a", &[0.25]).unwrap(), [1.25]);
    assert_eq!(
        column_at(&table, "b", &[0.25]).unwrap_err().to_string(),
        "the table has no column \"b\""
    );
}

fn trial(name: &str) -> Trial {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/ceinms")
        .join(name);
    Trial::read(&dir).unwrap_or_else(|e| panic!("{e}"))
}

fn fast_walking() -> Trial {
    trial("_FastWalking_")
}

#[test]
fn every_trial_s_moments_share_the_kinematics_times_bit_for_bit() {
    for name in [
        "_CrossOvers1_",
        "_CrossOvers6_",
        "_CrossOvers7_",
        "_FastWalking1_",
        "_FastWalking9_",
        "_FastWalking_",
    ] {
        let t = trial(name);
        let moments = moments_at_kinematics(&t).unwrap();
        for (dof, table) in &t.moments {
            assert_eq!(table.times(), t.lmt.times(), "{name} {dof}");
            assert_eq!(moments[dof], t.moment(dof).unwrap(), "{name} {dof}");
        }
    }
}

#[test]
fn fast_walking_s_moments_at_the_kinematics_times_are_its_tables() {
    let trial = fast_walking();
    let moments = moments_at_kinematics(&trial).unwrap();
    assert_eq!(
        moments.keys().collect::<Vec<_>>(),
        ["R_ankle_fe", "R_hip_aa", "R_hip_fe", "R_knee_fe"]
    );
    for (dof, table) in &trial.moments {
        // The same times, bit for bit, so the same values.
        assert_eq!(table.times(), trial.lmt.times(), "{dof}");
        assert_eq!(moments[dof], trial.moment(dof).unwrap(), "{dof}");
    }
    let knee = &trial.moments["R_knee_fe"];
    let own = column_at(knee, "R_knee_fe", knee.times()).unwrap();
    assert_eq!(own, trial.moment("R_knee_fe").unwrap());
    assert_eq!(own[0], 8.56730199053);
    // Between the first two rows (2.32 s, 8.567 N m; 2.324 s, 2.578 N m): on the line.
    let quarter = column_at(knee, "R_knee_fe", &[2.321]).unwrap()[0];
    assert!((quarter - (0.75 * 8.56730199053 + 0.25 * 2.57765157044)).abs() < 1e-12);
    // The EMG starts 130 ms before the kinematics: its times are not all within them.
    assert!(matches!(
        unit_length(&trial, "vaslat_r", trial.emg.times()),
        Err(ResampleError::OutOfRange { index: 0, .. })
    ));
    let lengths = unit_length(&trial, "vaslat_r", trial.lmt.times()).unwrap();
    assert_eq!(lengths, trial.lmt.column_named("vaslat_r").unwrap());
    assert!(matches!(
        unit_length(&trial, "vastus", &[2.5]),
        Err(ResampleError::NoColumn { .. })
    ));
}

#[test]
fn fast_walking_s_lengthening_rates_at_mid_stance_lie_within_the_data_s() {
    let trial = fast_walking();
    let times = trial.lmt.times();
    // Stance from 2.320 s to 3.032 s: mid-stance 2.676 s; and 1.3 ms after it, between rows.
    let mid = (times[0] + times[times.len() - 1]) / 2.0;
    for unit in [
        "vaslat_r",
        "recfem_r",
        "semimem_r",
        "gasmed_r",
        "sol_r",
        "tibant_r",
    ] {
        let length = trial.lmt.column_named(unit).unwrap();
        // The slopes between consecutive rows, m/s.
        let slopes: Vec<f64> = length
            .windows(2)
            .zip(times.windows(2))
            .map(|(l, t)| (l[1] - l[0]) / (t[1] - t[0]))
            .collect();
        let low = slopes.iter().copied().fold(f64::INFINITY, f64::min);
        let high = slopes.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let rates = unit_lengthening_rate(&trial, unit, &[mid, mid + 0.0013]).unwrap();
        let at = unit_length(&trial, unit, &[mid]).unwrap()[0];
        println!(
            "{unit}: at {mid:.3} s length {at:.4} m, rate {:+.4} m/s ({:+.4} m/s 1.3 ms later); \
             slopes in the trial {low:+.4} to {high:+.4} m/s",
            rates[0], rates[1]
        );
        for &rate in &rates {
            assert!((low..=high).contains(&rate), "{unit}: {rate}");
        }
        // At a row, the central difference of its neighbours.
        let row = times.iter().position(|&t| t == mid).unwrap();
        let central = (length[row + 1] - length[row - 1]) / (times[row + 1] - times[row - 1]);
        assert!((rates[0] - central).abs() < 1e-12, "{unit}");
    }
}
