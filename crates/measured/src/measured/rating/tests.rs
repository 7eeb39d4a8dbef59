use super::*;

/// `|a − b|` within `tol` times `|b|` (or `tol` itself near 0).
fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

/// A knee-like moment, N m: 200 samples of a stance-phase shape.
fn moment() -> Vec<f64> {
    (0..200)
        .map(|i| {
            let t = i as f64 / 199.0;
            40.0 * (std::f64::consts::PI * t).sin() - 25.0 * (3.0 * t).cos() + 5.0 * t
        })
        .collect()
}

#[test]
fn a_perfect_prediction_scores_one_and_no_error() {
    let m = moment();
    let r = rate(&m, &m).unwrap();
    assert_eq!(r.r_squared, 1.0);
    assert_eq!(r.pearson_r_squared, 1.0);
    assert_eq!(r.rmse, 0.0);
    assert_eq!(r.rmse_over_peak, 0.0);
    assert_eq!(pearson_r(&m, &m).unwrap(), 1.0);
}

#[test]
fn an_offset_keeps_r2_of_pearson_at_one_but_lowers_the_coefficient_of_determination() {
    let m = moment();
    let c = 7.5;
    let p: Vec<f64> = m.iter().map(|x| x + c).collect();
    let r = rate(&m, &p).unwrap();
    let mean = m.iter().sum::<f64>() / m.len() as f64;
    let ss_tot: f64 = m.iter().map(|x| (x - mean) * (x - mean)).sum();
    let expected = 1.0 - m.len() as f64 * c * c / ss_tot;
    println!(
        "p = m + {c} N m: R² = {} (closed form {expected}), r² = {}, RMSE = {} N m",
        r.r_squared, r.pearson_r_squared, r.rmse
    );
    assert!(close(r.r_squared, expected, 1e-13), "{}", r.r_squared);
    assert!(r.r_squared < 1.0);
    assert!(close(r.pearson_r_squared, 1.0, 1e-14));
    assert!(close(r.rmse, c, 1e-13));
    let peak = m.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
    assert!(close(r.rmse_over_peak, c / peak, 1e-13));
}

#[test]
fn the_opposite_sign_scores_r2_of_pearson_one_and_r2_minus_three() {
    // Zero mean: Σ(m − (−m))² = 4 Σm² = 4 SS_tot, so R² = 1 − 4 = −3.
    let m = [-3.0, -1.0, 0.0, 1.0, 3.0, 2.5, -2.5];
    let p: Vec<f64> = m.iter().map(|x| -x).collect();
    let r = rate(&m, &p).unwrap();
    assert_eq!(r.r_squared, -3.0);
    assert_eq!(r.pearson_r_squared, 1.0);
    assert_eq!(pearson_r(&m, &p).unwrap(), -1.0);
    assert_eq!(coefficient_of_determination(&m, &p).unwrap(), -3.0);
}

#[test]
fn a_five_point_example_matches_the_hand_computation() {
    // m̄ = 6, SS_tot = 16 + 4 + 0 + 4 + 16 = 40; m − p = (−1, 0.5, 0, −1.5, 1), SS_res = 4.5;
    // p̄ = 6.2, p − p̄ = (−3.2, −2.7, −0.2, 3.3, 2.8): Σ(m − m̄)(p − p̄) = 36, Σ(p − p̄)² = 36.3.
    // R² = 1 − 4.5/40 = 0.8875; r² = 36²/(40 · 36.3) = 108/121; r = 6√3/11;
    // RMSE = √(4.5/5) = √0.9; over the peak 10.
    let m = [2.0, 4.0, 6.0, 8.0, 10.0];
    let p = [3.0, 3.5, 6.0, 9.5, 9.0];
    let r = rate(&m, &p).unwrap();
    println!("{r:?}");
    assert_eq!(r.r_squared, 0.8875);
    assert!(close(r.pearson_r_squared, 108.0 / 121.0, 2e-16));
    assert!(close(r.pearson_r_squared, 0.892_561_983_471_074_4, 2e-16));
    assert!(close(r.rmse, 0.948_683_298_050_513_8, 2e-16));
    assert!(close(r.rmse, 0.9_f64.sqrt(), 2e-16));
    assert!(close(r.rmse_over_peak, 0.094_868_329_805_051_38, 2e-16));
    let r = pearson_r(&m, &p).unwrap();
    assert!(close(r, 6.0 * 3.0_f64.sqrt() / 11.0, 2e-16), "{r}");
    assert!(close(r, 0.944_754_985_946_660_4, 2e-16), "{r}");
    assert_eq!(rmse(&m, &p).unwrap(), rate(&m, &p).unwrap().rmse);
}

#[test]
fn the_figures_do_not_depend_on_the_series_scale() {
    let m = [2.0, 4.0, 6.0, 8.0, 10.0];
    let p = [3.0, 3.5, 6.0, 9.5, 9.0];
    let r = rate(&m, &p).unwrap();
    for k in [1e-300, 1e-3, 3.0, 1e300] {
        let (mk, pk): (Vec<f64>, Vec<f64>) = m.iter().zip(&p).map(|(a, b)| (a * k, b * k)).unzip();
        let rk = rate(&mk, &pk).unwrap();
        assert!(close(rk.r_squared, r.r_squared, 1e-15), "{k}: {rk:?}");
        assert!(
            close(rk.pearson_r_squared, r.pearson_r_squared, 1e-15),
            "{k}"
        );
        assert!(close(rk.rmse / k, r.rmse, 1e-15), "{k}");
        assert!(close(rk.rmse_over_peak, r.rmse_over_peak, 1e-15), "{k}");
    }
    // Near the largest double, squares of the raw values would overflow.
    let big = [f64::MAX, -f64::MAX / 2.0, 0.0];
    let rb = rate(&big, &[f64::MAX / 2.0, -f64::MAX, 0.0]).unwrap();
    assert!(
        rb.r_squared.is_finite() && rb.pearson_r_squared.is_finite(),
        "{rb:?}"
    );
}

#[test]
fn the_coefficient_of_determination_is_negative_when_p_is_worse_than_the_mean() {
    let m = moment();
    let mean = m.iter().sum::<f64>() / m.len() as f64;
    let flat = vec![mean; m.len()];
    // The mean itself: R² = 0 (to rounding); Pearson's r is undefined for it.
    assert!(close(
        coefficient_of_determination(&m, &flat).unwrap(),
        0.0,
        1e-14
    ));
    assert!(matches!(
        rate(&m, &flat),
        Err(RatingError::NoSpread {
            series: Series::Predicted,
            ..
        })
    ));
    let shifted: Vec<f64> = m.iter().map(|x| x + 60.0).collect();
    let r = rate(&m, &shifted).unwrap();
    println!("p = m + 60 N m: {r:?}");
    assert!(
        r.r_squared < 0.0 && close(r.pearson_r_squared, 1.0, 1e-14),
        "{r:?}"
    );
}

#[test]
fn bad_series_are_refused_with_one_line_messages() {
    let m = [1.0, 2.0, 3.0];
    let e = rate(&m, &[1.0, 2.0]).unwrap_err();
    assert_eq!(
        e,
        RatingError::LengthMismatch {
            measured: 3,
            predicted: 2
        }
    );
    assert_eq!(
        e.to_string(),
        "3 measured samples but 2 predicted: they must be sample for sample"
    );
    assert_eq!(rate(&[], &[]).unwrap_err(), RatingError::Empty);
    assert_eq!(rmse(&[], &[]).unwrap_err(), RatingError::Empty);
    let e = rate(&[1.0, f64::NAN, 3.0], &m).unwrap_err();
    assert!(matches!(
        e,
        RatingError::NotFinite {
            series: Series::Measured,
            index: 1,
            ..
        }
    ));
    assert_eq!(
        e.to_string(),
        "measured sample 1 is NaN, not a finite number"
    );
    let e = rmse(&m, &[1.0, 2.0, f64::NEG_INFINITY]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "predicted sample 2 is -inf, not a finite number"
    );
    let e = rate(&[4.0; 3], &m).unwrap_err();
    assert_eq!(
        e,
        RatingError::NoSpread {
            series: Series::Measured,
            first: 4.0
        }
    );
    assert!(!e.to_string().contains('\n'));
    assert_eq!(
        coefficient_of_determination(&[4.0; 3], &[4.0; 3]).unwrap_err(),
        e
    );
    assert!(matches!(
        pearson_r(&m, &[0.0; 3]),
        Err(RatingError::NoSpread {
            series: Series::Predicted,
            ..
        })
    ));
    // A single sample has no spread.
    assert!(matches!(
        rate(&[1.0], &[1.0]),
        Err(RatingError::NoSpread { .. })
    ));
    // A spread of 1e-120 beside a peak of 1 leaves the doubles' range in R²: refused.
    let tiny = [1.0, 1.0 + f64::EPSILON, 1.0];
    assert!(rate(&tiny, &[0.0, 1.0, 2.0]).is_ok());
    let flat = [1e-120, 2e-120, 0.0];
    assert!(matches!(
        rate(&flat, &[0.0, 1.0, 2.0]),
        Err(RatingError::NoSpread {
            series: Series::Measured,
            ..
        })
    ));
    // A constant predicted series still has an RMSE and a coefficient of determination.
    assert_eq!(rmse(&m, &[2.0; 3]).unwrap(), (2.0_f64 / 3.0).sqrt());
    assert_eq!(coefficient_of_determination(&m, &[2.0; 3]).unwrap(), 0.0);
}
