//! ESDIRK4(3)6L\[2\]SA (Kennedy & Carpenter 2016, NASA/TM-2016-219173, "Diagonally implicit
//! Runge–Kutta methods for ordinary differential equations. A review"; SUNDIALS'
//! `ARKODE_ESDIRK436L2SA_6_3_4`).

use super::{Tableau, MAX_STAGES};

impl Tableau {
    /// ESDIRK4(3)6L\[2\]SA (Kennedy & Carpenter 2016, table of the method of that name): fourth
    /// order, L-stable, stiffly accurate, five implicit stages with γ = 1/4, an embedded
    /// third-order solution. The coefficients as SUNDIALS gives them
    /// (`src/arkode/arkode_butcher_dirk.def`, `ARKODE_ESDIRK436L2SA_6_3_4`): a_i0 from the row
    /// sums c_i, the last row the weights b.
    pub(crate) fn esdirk436() -> Self {
        let r2 = std::f64::consts::SQRT_2;
        let g = 0.25;
        let mut c = [0.0; MAX_STAGES];
        c[1] = 0.5;
        c[2] = (2.0 - r2) / 4.0;
        c[3] = 5.0 / 8.0;
        c[4] = 26.0 / 25.0;
        c[5] = 1.0;
        let b = [
            (1181.0 - 987.0 * r2) / 13782.0,
            (1181.0 - 987.0 * r2) / 13782.0,
            47.0 * (-267.0 + 1783.0 * r2) / 273343.0,
            -16.0 * (-22922.0 + 3525.0 * r2) / 571953.0,
            -15625.0 * (97.0 + 376.0 * r2) / 90749876.0,
            0.25,
        ];
        let b_hat = [
            -480923228411.0 / 4982971448372.0,
            -480923228411.0 / 4982971448372.0,
            6709447293961.0 / 12833189095359.0,
            3513175791894.0 / 6748737351361.0,
            -498863281070.0 / 6042575550617.0,
            2077005547802.0 / 8945017530137.0,
        ];
        let mut a = [[0.0; MAX_STAGES]; MAX_STAGES];
        a[2][1] = (1.0 - r2) / 8.0;
        a[3][1] = (5.0 - 7.0 * r2) / 64.0;
        a[3][2] = 7.0 * (1.0 + r2) / 32.0;
        a[4][1] = -(13796.0 + 54539.0 * r2) / 125000.0;
        a[4][2] = (506605.0 + 132109.0 * r2) / 437500.0;
        a[4][3] = 166.0 * (-97.0 + 376.0 * r2) / 109375.0;
        for i in 1..5 {
            a[i][i] = g;
            a[i][0] = c[i] - (1..=i).map(|j| a[i][j]).sum::<f64>();
        }
        a[5][..6].copy_from_slice(&b);
        let mut e = [0.0; MAX_STAGES];
        for j in 0..6 {
            e[j] = b[j] - b_hat[j];
        }
        Self::from_coefficients(6, g, c, a, e, 3)
    }
}

#[cfg(test)]
mod tests {
    use super::super::order_conditions::{a_times, assert_order, assert_row_sums, dot, weights};
    use super::*;

    /// ESDIRK4(3)6L\[2\]SA's order conditions: fourth order for the method (all eight trees),
    /// third for the embedding, and the stages' row sums.
    #[test]
    fn esdirk436_meets_its_order_conditions() {
        let t = Tableau::esdirk436();
        let s = t.stages;
        assert_row_sums(&t, 1e-12);
        let (b, bh) = weights(&t);
        assert_order(&t, &b, 4, 1e-12);
        assert_order(&t, &bh, 3, 1e-12);
        // The embedding is of order three, not four: its error estimate does not vanish.
        let c: Vec<f64> = t.c[..s].to_vec();
        let c3: Vec<f64> = c.iter().map(|x| x.powi(3)).collect();
        let aac = a_times(&t, &a_times(&t, &c));
        assert!((dot(&bh, &c3) - 0.25).abs() > 1e-6 || (dot(&bh, &aac) - 1.0 / 24.0).abs() > 1e-6);
    }
}
