//! ARK3(2)4L\[2\]SA, implicit part (Kennedy & Carpenter 2003, "Additive Runge–Kutta schemes for
//! convection–diffusion–reaction equations", Appl. Numer. Math. 44; SUNDIALS'
//! `ARKODE_ARK324L2SA_DIRK_4_2_3`).

use super::{Tableau, MAX_STAGES};

impl Tableau {
    /// ARK3(2)4L\[2\]SA, implicit part: third order, L-stable, stiffly accurate, three implicit
    /// stages, an embedded second-order solution.
    pub(crate) fn ark324() -> Self {
        let g = 1767732205903.0 / 4055673282236.0;
        let mut a = [[0.0; MAX_STAGES]; MAX_STAGES];
        a[1][0] = g;
        a[1][1] = g;
        a[2][0] = 2746238789719.0 / 10658868560708.0;
        a[2][1] = -640167445237.0 / 6845629431997.0;
        a[2][2] = g;
        a[3][0] = 1471266399579.0 / 7840856788654.0;
        a[3][1] = -4482444167858.0 / 7529755066697.0;
        a[3][2] = 11266239266428.0 / 11593286722821.0;
        a[3][3] = g;
        let b_hat = [
            2756255671327.0 / 12835298489170.0,
            -10771552573575.0 / 22201958757719.0,
            9247589265047.0 / 10645013368117.0,
            2193209047091.0 / 5459859503100.0,
        ];
        let mut e = [0.0; MAX_STAGES];
        for j in 0..4 {
            e[j] = a[3][j] - b_hat[j];
        }
        let mut c = [0.0; MAX_STAGES];
        c[1] = 1767732205903.0 / 2027836641118.0;
        c[2] = 3.0 / 5.0;
        c[3] = 1.0;
        Self::from_coefficients(4, g, c, a, e, 2)
    }
}

#[cfg(test)]
mod tests {
    use super::super::order_conditions::{assert_order, assert_row_sums, weights};
    use super::*;

    /// The tableau's order conditions: third order for the method, second for the embedding.
    #[test]
    fn ark324_meets_its_order_conditions() {
        let t = Tableau::ark324();
        assert_row_sums(&t, 1e-12);
        let (b, bh) = weights(&t);
        assert_order(&t, &b, 3, 1e-12);
        assert_order(&t, &bh, 2, 1e-12);
    }
}
