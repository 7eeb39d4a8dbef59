//! TR-BDF2 (Bank, Coughran, Fichtner, Grosse, Rose & Smith 1985, "Transient simulation of
//! silicon devices and circuits", IEEE Trans. CAD 4(4)) as an ESDIRK, with Hosea & Shampine's
//! error estimate (1996, "Analysis and implementation of TR-BDF2", Appl. Numer. Math. 20).

use super::{Tableau, MAX_STAGES};

impl Tableau {
    /// TR-BDF2 written as an ESDIRK: a trapezoidal stage to γ = 2 - √2, then BDF2 to 1; second
    /// order, L-stable, two implicit stages with diagonal γ/2. Its error estimate is Hosea &
    /// Shampine's: `2 C h [(F_2 - F_1)/(1 - γ) - (F_1 - F_0)/γ]`,
    /// `C = (-3γ² + 4γ - 2) / (12 (2 - γ))`.
    pub(crate) fn trbdf2() -> Self {
        let g = 2.0 - std::f64::consts::SQRT_2;
        let d = 0.5 * g;
        let w = 1.0 / (2.0 * (2.0 - g));
        let mut a = [[0.0; MAX_STAGES]; MAX_STAGES];
        a[1][0] = d;
        a[1][1] = d;
        a[2][0] = w;
        a[2][1] = w;
        a[2][2] = d;
        let k = 2.0 * (-3.0 * g * g + 4.0 * g - 2.0) / (12.0 * (2.0 - g));
        let mut e = [0.0; MAX_STAGES];
        e[0] = k / g;
        e[1] = -k * (1.0 / (1.0 - g) + 1.0 / g);
        e[2] = k / (1.0 - g);
        let mut c = [0.0; MAX_STAGES];
        c[1] = g;
        c[2] = 1.0;
        Self::from_coefficients(3, d, c, a, e, 2)
    }
}

#[cfg(test)]
mod tests {
    use super::super::order_conditions::{assert_order, assert_row_sums, dot, weights};
    use super::*;

    /// TR-BDF2's tableau: second order, and an error estimate that vanishes on polynomials of
    /// degree one in time.
    #[test]
    fn trbdf2_meets_its_order_conditions() {
        let t = Tableau::trbdf2();
        let s = t.stages;
        assert_row_sums(&t, 1e-15);
        let (b, _) = weights(&t);
        assert_order(&t, &b, 2, 1e-15);
        assert!(t.e[..s].iter().sum::<f64>().abs() < 1e-15);
        assert!(dot(&t.e[..s], &t.c[..s]).abs() < 1e-15);
        let c2: Vec<f64> = t.c[..s].iter().map(|x| x * x).collect();
        assert!(dot(&t.e[..s], &c2).abs() > 1e-3);
    }
}
