//! The tight-tolerance adaptive reference of the tests: Dormand–Prince 8(5,3) from the
//! `ode_solvers` crate (a dev-dependency), an explicit method entirely independent of the
//! implicit tick stepper. It integrates in scaled variables (y / scale) so that one tolerance
//! fits every component.

use ode_solvers::dop_shared::OutputType;
use ode_solvers::{DVector, Dop853, System};

struct Scaled<'a, F> {
    f: &'a F,
    scales: &'a [f64],
    y: std::cell::RefCell<Vec<f64>>,
    dy: std::cell::RefCell<Vec<f64>>,
}

impl<F: Fn(f64, &[f64], &mut [f64])> System<f64, DVector<f64>> for Scaled<'_, F> {
    fn system(&self, t: f64, ys: &DVector<f64>, dys: &mut DVector<f64>) {
        let mut y = self.y.borrow_mut();
        let mut dy = self.dy.borrow_mut();
        for i in 0..y.len() {
            y[i] = ys[i] * self.scales[i];
        }
        (self.f)(t, &y, &mut dy);
        for i in 0..y.len() {
            dys[i] = dy[i] / self.scales[i];
        }
    }
}

/// Integrates `dy/dt = f(t, y)` from t0 to t1 in place, with relative and absolute tolerance
/// `tol` on the scaled components.
pub fn integrate<F: Fn(f64, &[f64], &mut [f64])>(
    f: &F,
    t0: f64,
    t1: f64,
    y: &mut [f64],
    scales: &[f64],
    tol: f64,
) -> Result<(), String> {
    let n = y.len();
    let sys = Scaled {
        f,
        scales,
        y: std::cell::RefCell::new(vec![0.0; n]),
        dy: std::cell::RefCell::new(vec![0.0; n]),
    };
    let y0 = DVector::from_iterator(n, y.iter().zip(scales).map(|(v, s)| v / s));
    let mut solver = Dop853::from_param(
        sys,
        t0,
        t1,
        t1 - t0,
        y0,
        tol,
        tol,
        0.9,
        0.0,
        0.333,
        6.0,
        t1 - t0,
        0.0,
        10_000_000,
        u32::MAX,
        OutputType::Sparse,
    );
    solver
        .integrate()
        .map_err(|e| format!("reference solver failed: {e}"))?;
    let last = solver
        .y_out()
        .last()
        .ok_or("reference solver produced no output")?;
    for i in 0..n {
        y[i] = last[i] * scales[i];
    }
    Ok(())
}
