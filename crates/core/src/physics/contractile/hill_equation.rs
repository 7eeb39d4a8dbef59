//! Hill-type contractile element (paper eqs. 1–2, docs/model.md §3).

/// Force–velocity factor g(v_s) with `v' = v_s / vmax` (v_s: shortening velocity):
/// paper eq. (2) `(1 - v')/(1 + 4 v')` for 0 <= v' <= 1, 0 beyond vmax; for lengthening our C1
/// continuation `N - (N - 1)/(1 - c v')`, `c = 5/(N - 1)` (slope -5 at v' = 0 on both sides).
pub fn force_velocity(v_shortening: f64, v_max: f64, eccentric_asymptote: f64) -> f64 {
    let vr = v_shortening / v_max;
    if vr >= 1.0 {
        0.0
    } else if vr >= 0.0 {
        (1.0 - vr) / (1.0 + 4.0 * vr)
    } else {
        let n = eccentric_asymptote;
        let c = 5.0 / (n - 1.0);
        n - (n - 1.0) / (1.0 - c * vr)
    }
}

/// `F_CE = Fmax a f(l_m) g(v_s)`, N (paper eq. 1).
/// `dg/dv_s` of [`force_velocity`] (per m/s of shortening velocity): `-5/(1 + 4 v_r)²/vmax`
/// shortening, 0 beyond vmax, `-(N - 1) c/(1 - c v_r)²/vmax` lengthening (`c = 5/(N - 1)`: both
/// branches have slope -5/vmax at 0).
pub(crate) fn force_velocity_derivative(
    v_shortening: f64,
    v_max: f64,
    eccentric_asymptote: f64,
) -> f64 {
    let vr = v_shortening / v_max;
    if vr >= 1.0 {
        0.0
    } else if vr >= 0.0 {
        let d = 1.0 + 4.0 * vr;
        -5.0 / (d * d) / v_max
    } else {
        let n = eccentric_asymptote;
        let c = 5.0 / (n - 1.0);
        let d = 1.0 - c * vr;
        -(n - 1.0) * c / (d * d) / v_max
    }
}

pub(crate) fn hill_force(
    f_max: f64,
    activation: f64,
    force_length: f64,
    force_velocity: f64,
) -> f64 {
    f_max * activation * force_length * force_velocity
}
