//! The stepper's tests: order, stiff accuracy and step-size control on problems with known
//! solutions.

use super::*;
use crate::integrator::dense::DenseMatrix;

/// Prothero–Robinson: y' = λ (y - cos t) - sin t, exact solution y = cos t for any λ.
struct ProtheroRobinson(f64);
impl OdeSystem for ProtheroRobinson {
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = self.0 * (y[0] - t.cos()) - t.sin();
    }
    fn scales(&self, out: &mut [f64]) {
        out[0] = 1.0;
    }
}

/// The error at t = 1 of 100 fixed steps of `tableau` on Prothero–Robinson with this λ.
fn prothero_robinson_error(tableau: fn() -> Tableau, lambda: f64) -> f64 {
    let sys = ProtheroRobinson(lambda);
    let mut st = Esdirk::new(1, DenseMatrix::new(1), tableau());
    let mut y = [1.0];
    let h = 1e-2;
    for k in 0..100 {
        st.step(&sys, k as f64 * h, h, &mut y).unwrap();
    }
    (y[0] - 1f64.cos()).abs()
}

/// Stiffly accurate: no order reduction on the stiff problem.
#[test]
fn stiff_problem_is_solved_at_the_smooth_solution_accuracy() {
    for lambda in [-1.0, -1e3, -1e6] {
        let err = prothero_robinson_error(Tableau::ark324, lambda);
        assert!(err < 1e-5, "λ = {lambda}: error {err}");
    }
}

#[test]
fn adaptive_advance_meets_its_tolerance_and_adapts() {
    let mut steps_before = 0;
    for tol in [1e-4, 1e-6, 1e-8] {
        let mut st = Esdirk::new(1, DenseMatrix::new(1), Tableau::ark324());
        let mut y = [1.0];
        let mut h = 0.0;
        let mut steps = 0;
        for k in 0..10 {
            steps += st
                .advance(
                    &Decay(-5.0),
                    k as f64 * 0.1,
                    (k + 1) as f64 * 0.1,
                    &mut y,
                    &mut h,
                    tol,
                    10_000,
                )
                .unwrap();
        }
        let err = (y[0] - (-5.0f64).exp()).abs();
        assert!(
            err < 50.0 * tol,
            "tol {tol}: error {err} after {steps} steps"
        );
        assert!(steps > steps_before, "tighter tolerances need more steps");
        steps_before = steps;
    }
}

struct Decay(f64);
impl OdeSystem for Decay {
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = self.0 * y[0];
    }
    fn scales(&self, out: &mut [f64]) {
        out[0] = 1.0;
    }
}

/// The order `tableau` shows on y' = -2y over [0, 1] from n to 2n fixed steps.
fn observed_order(tableau: fn() -> Tableau, n: usize) -> f64 {
    let err = |n: usize| {
        let mut st = Esdirk::new(1, DenseMatrix::new(1), tableau());
        let mut y = [1.0];
        let h = 1.0 / n as f64;
        for k in 0..n {
            st.step(&Decay(-2.0), k as f64 * h, h, &mut y).unwrap();
        }
        (y[0] - (-2.0f64).exp()).abs()
    };
    (err(n) / err(2 * n)).log2()
}

/// One step of length 1 on y' = -1e9 y from 1: what an L-stable method leaves of it.
fn stiff_decay(tableau: fn() -> Tableau) -> f64 {
    let mut st = Esdirk::new(1, DenseMatrix::new(1), tableau());
    let mut y = [1.0];
    st.step(&Decay(-1e9), 0.0, 1.0, &mut y).unwrap();
    y[0]
}

#[test]
fn converges_at_third_order_and_damps_stiff_modes() {
    let order = observed_order(Tableau::ark324, 20);
    assert!((2.7..3.4).contains(&order), "observed order {order}");
    let r = stiff_decay(Tableau::ark324);
    assert!(r.abs() < 1e-6, "R(-1e9) = {r}");
}

#[test]
fn esdirk436_converges_at_fourth_order_and_damps_stiff_modes() {
    let order = observed_order(Tableau::esdirk436, 10);
    assert!((3.7..4.4).contains(&order), "observed order {order}");
    let r = stiff_decay(Tableau::esdirk436);
    assert!(r.abs() < 1e-6, "R(-1e9) = {r}");
    for lambda in [-1.0, -1e3, -1e6] {
        let err = prothero_robinson_error(Tableau::esdirk436, lambda);
        assert!(err < 1e-7, "λ = {lambda}: error {err}");
    }
}

/// Values spread over many decades, with the edges of the bounds (1, ETA_MIN) among them.
fn spread() -> Vec<f64> {
    let mut v: Vec<f64> = (-400..=100).map(|k| 10f64.powf(k as f64 / 20.0)).collect();
    v.extend([
        0.0,
        ETA_MIN,
        1.0,
        1.0 - 1e-16,
        1.0 + 1e-15,
        0.9 * 0.45f64.powi(3),
        f64::INFINITY,
    ]);
    v
}

/// `x` and its neighbouring doubles, two either side.
fn around(x: f64) -> [f64; 5] {
    let (d1, u1) = (x.next_down(), x.next_up());
    [d1.next_down(), d1, x, u1, u1.next_up()]
}

#[test]
fn the_bounds_decide_as_the_power_does() {
    let tol = 1.5e-6;
    let mut decided = 0;
    for &last in &spread() {
        // The grid's norms, and those at each bound's edge, where rounding decides.
        let l = last.max(ETA_MIN);
        let mut norms = spread();
        for edge in [tol / l, tol, tol / first_error_factor(last)] {
            norms.extend(around(edge));
        }
        for &norm in &norms {
            let by_power = first_error_factor(last) * norm < tol;
            if let Some(d) = raised_bounds(last, norm, tol) {
                assert_eq!(d, by_power, "last {last:e}, norm {norm:e}");
                decided += 1;
            }
        }
    }
    // Most pairs are decided by the bounds: the test covers them.
    assert!(decided > 150_000, "{decided}");
}

#[test]
fn the_step_factor_is_the_roots_to_the_bit() {
    for k in 2..=5 {
        // The grid, and a fine one either side of the threshold and of 0.45^k (factor 2).
        let mut errs = spread();
        for x in [0.9 * 0.45f64.powi(k as i32), 0.45f64.powi(k as i32)] {
            errs.extend(around(x));
            errs.extend((-40..=40).map(|i| x * (1.0 + 0.002 * i as f64)));
        }
        for &err in &errs {
            let by_root = if err > 0.0 {
                (0.9 * inverse_root(err, k)).clamp(0.2, 2.0)
            } else {
                2.0
            };
            assert_eq!(
                step_factor(err, k).to_bits(),
                by_root.to_bits(),
                "k {k}, err {err:e}"
            );
        }
    }
}
