//! The ESDIRK stepper: stiffly accurate ESDIRK methods with an embedded error estimate (Kennedy &
//! Carpenter 2003; the tableaux in [`super::tableau`]). An explicit first stage, then implicit
//! stages that share the iteration matrix `I - hγ J`; the last stage is the step's result and its
//! derivative starts the next step. The error estimate is filtered through `(I - hγ J)⁻¹` for the
//! stiff components (Hosea & Shampine 1996).
//!
//! Which tableau: TR-BDF2 (second order) for fixed sub-steps; for adaptive sub-steps the
//! implicit part of ARK3(2)4L\[2\]SA (third order), whose sub-steps in the transients, where the
//! fibre mass rings on the tendon and cross-bridge springs, are longer than a second-order
//! method's at the same accuracy; and, for a call whose carried step is shorter than
//! `HIGH_BELOW` (1.5) times its span (the state moves fast), ESDIRK4(3)6L\[2\]SA (fourth order,
//! five implicit stages, Kennedy & Carpenter 2016; [`Esdirk::with_high_order`]), which takes
//! fewer sub-steps and evaluations there. Quiet ticks, one step each, stay on the three-stage
//! method (docs/integration.md, "Methods"; the work per tick in docs/benchmarks.md).
//!
//! The tick loop needs a stepper that is allocation-free and bit-deterministic, keeps its
//! Jacobian across ticks, and lets the linear algebra exploit the plant's structure (the
//! [`IterationMatrix`]); this one is written for it. The Jacobian and its factorisation are
//! refreshed only when the simplified Newton iteration converges slowly, the step size changes
//! by more than 20%, or it fails. `advance` chooses sub-steps by the embedded error estimate;
//! `step` takes one fixed step.

// Index loops over several parallel vectors read better than zipped iterators here.
#![allow(clippy::needless_range_loop)]

use super::tableau::{Tableau, MAX_STAGES};
use crate::integrator::{ConvergenceError, IterationMatrix, OdeSystem, Stats};
use std::sync::Arc;

mod saved;

/// Newton stops when the scaled error it estimates is left is below this fraction of the step's
/// tolerance (and never above `NEWTON_TOL_MAX`): small enough that the DM elbow's joint scenario
/// stays within crates/core/tests/reference_runs.rs's bound (1e-6 m) of the reference CSV; smaller fractions
/// add evaluations without a measurable gain.
const NEWTON_TOL_FRACTION: f64 = 0.03;
const NEWTON_TOL_MAX: f64 = 1e-5;
const NEWTON_MAX_ITER: usize = 10;
const SLOW_CONTRACTION: f64 = 0.3;
/// `advance` takes the higher-order tableau, when it has one, for a call whose carried step is
/// below this multiple of the call's span. Above 1: a tick that follows a step the error
/// estimate let grow only a little past the tick is about to need sub-steps. Below 2: steady
/// ticks, whose carried step is at most 2 spans, stay on the cheaper base tableau.
const HIGH_BELOW: f64 = 1.5;
/// Relative change of `hγ` up to which the iteration matrix is kept.
const REUSE: f64 = 0.2;

/// The error left after a Newton iteration that contracts at rate θ, per unit of its last
/// correction: `θ / (1 - θ)` (Hairer & Wanner 1996, IV.8, eq. 8.10).
fn error_factor(rate: f64) -> f64 {
    rate / (1.0 - rate)
}

/// The same factor for a stage's first iteration, before it has a rate of its own: the last
/// one's, raised to 0.8 towards 1 (Hairer & Wanner 1996, IV.8, after eq. 8.10), and at least
/// `ETA_MIN^0.8`. Raised, so that a stage's first correction is not taken for converged on the
/// strength of the previous stage's fast contraction (the DM pulse keeps its accuracy against the
/// reference solution).
fn first_error_factor(last: f64) -> f64 {
    last.max(ETA_MIN).powf(0.8)
}

/// Whether `first_error_factor(last) * norm < tol`, where bounds decide it without the power:
/// for `l = max(last, ETA_MIN)`, `l^0.8` lies in `[l, 1]` when `l <= 1` and in `(1, l)` above
/// (a correctly rounded power keeps these bounds, and rounding keeps their products in order).
/// None where only the power decides.
fn raised_bounds(last: f64, norm: f64, tol: f64) -> Option<bool> {
    let l = last.max(ETA_MIN);
    let (low, high) = if l <= 1.0 { (l, 1.0) } else { (1.0, l) };
    if low * norm >= tol {
        Some(false)
    } else if high * norm < tol {
        Some(true)
    } else {
        None
    }
}

/// The step-size factor from a scaled error estimate of order k: `0.9 err^(-1/k)` within
/// [0.2, 2]. An estimate at most `0.9 × 0.45^k` gives 2 without the root, as the root would
/// (`0.9 (0.9 × 0.45^k)^(-1/k) = 2 × 0.9^(-1/k)`, above 2 by far more than rounding): the
/// steady ticks' case, whose estimates are far below the tolerance.
fn step_factor(err: f64, k: u32) -> f64 {
    if err <= 0.9 * 0.45f64.powi(k as i32) {
        2.0
    } else {
        (0.9 * inverse_root(err, k)).clamp(0.2, 2.0)
    }
}

/// `x^(-1/k)`, the step-size factor's root of the error estimate: `cbrt` for k = 3, two square
/// roots for k = 4, cheaper than `powf`.
fn inverse_root(x: f64, k: u32) -> f64 {
    match k {
        3 => 1.0 / x.cbrt(),
        4 => 1.0 / x.sqrt().sqrt(),
        _ => x.powf(-1.0 / k as f64),
    }
}

/// Floor of the carried error factor.
const ETA_MIN: f64 = 1e-16;

#[derive(Debug, Clone)]
struct Work {
    /// Stage derivatives F_j.
    f: Vec<Vec<f64>>,
    rhs: Vec<f64>,
    z: Vec<f64>,
    fz: Vec<f64>,
    delta: Vec<f64>,
    est: Vec<f64>,
    /// 1 / the system's scales: Newton's norm.
    inv_scale: Vec<f64>,
    /// 1 / (tolerance × scales): the error estimate's norm.
    inv_w: Vec<f64>,
    end_t: f64,
    end_y: Vec<f64>,
    end_f: Vec<f64>,
    end_valid: bool,
}

/// An ESDIRK stepper with its iteration matrix kept across steps.
#[derive(Debug, Clone)]
pub(crate) struct Esdirk<M> {
    n: usize,
    /// Shared, so that a step borrows it while the stages borrow the rest of `self` (no copy of
    /// the tableau per step).
    tableau: Arc<Tableau>,
    /// A higher-order tableau `advance` uses while the carried step is shorter than its span.
    high: Option<Arc<Tableau>>,
    /// Whether the sub-steps being taken use `high`.
    high_active: bool,
    matrix: M,
    jac_valid: bool,
    lu_valid: bool,
    lu_d: f64,
    refresh_next: bool,
    /// Newton's stopping threshold on the scaled error left after an iteration.
    newton_tol: f64,
    /// `θ/(1 - θ)` of the last contraction rate θ Newton observed: the factor from the last
    /// correction to the error left (Hairer & Wanner 1996, IV.8, eq. 8.10).
    eta: f64,
    work: Work,
    /// Work counters.
    pub stats: Stats,
}

impl<M> Esdirk<M> {
    /// A stepper for an n-dimensional system.
    pub(crate) fn new(n: usize, matrix: M, tableau: Tableau) -> Self {
        let v = || vec![0.0; n];
        Self {
            n,
            matrix,
            jac_valid: false,
            lu_valid: false,
            lu_d: 0.0,
            refresh_next: true,
            newton_tol: 1e-6,
            eta: 1.0,
            work: Work {
                f: (0..tableau.stages).map(|_| v()).collect(),
                rhs: v(),
                z: v(),
                fz: v(),
                delta: v(),
                est: v(),
                inv_scale: v(),
                inv_w: v(),
                end_t: f64::NAN,
                end_y: v(),
                end_f: v(),
                end_valid: false,
            },
            tableau: Arc::new(tableau),
            high: None,
            high_active: false,
            stats: Stats::default(),
        }
    }

    /// With a second, higher-order tableau for `advance`'s sub-steps while the state moves
    /// fast: `advance` takes it for a call whose carried step is shorter than `HIGH_BELOW`
    /// times the call's span, and the base tableau for the others.
    pub(crate) fn with_high_order(mut self, high: Tableau) -> Self {
        while self.work.f.len() < high.stages {
            self.work.f.push(vec![0.0; self.n]);
        }
        self.high = Some(Arc::new(high));
        self
    }

    fn active(&self) -> &Arc<Tableau> {
        match (&self.high, self.high_active) {
            (Some(t), true) => t,
            _ => &self.tableau,
        }
    }

    /// Forgets the Jacobian (after a discontinuous change of the system).
    pub(crate) fn invalidate(&mut self) {
        self.jac_valid = false;
        self.lu_valid = false;
        self.refresh_next = true;
        self.work.end_valid = false;
    }

    fn newton<S: OdeSystem + ?Sized>(&mut self, sys: &S, t: f64, d: f64) -> Option<bool>
    where
        M: IterationMatrix<S>,
    {
        if !self.lu_valid {
            return None;
        }
        let wk = &mut self.work;
        let mut prev_norm = f64::INFINITY;
        let mut slow = false;
        // The first iteration's factor, `first_error_factor(eta)`, is computed only where
        // its bounds do not decide the stopping test (`raised_bounds`); until it is, `eta`
        // holds the factor it is computed from.
        let mut raise_pending = false;
        for iter in 0..NEWTON_MAX_ITER {
            sys.rhs(t, &wk.z, &mut wk.fz);
            self.stats.rhs_evals += 1;
            for i in 0..self.n {
                wk.delta[i] = wk.rhs[i] - wk.z[i] + wk.fz[i] * d;
            }
            self.matrix.solve(&mut wk.delta);
            self.stats.solves += 1;
            let mut norm = 0.0f64;
            for i in 0..self.n {
                wk.z[i] += wk.delta[i];
                norm = norm.max(wk.delta[i].abs() * wk.inv_scale[i]);
            }
            if !norm.is_finite() {
                if raise_pending {
                    self.eta = first_error_factor(self.eta);
                }
                return None;
            }
            if iter > 0 {
                let rate = norm / prev_norm;
                if rate > 1.0 {
                    if raise_pending {
                        self.eta = first_error_factor(self.eta);
                    }
                    return None;
                }
                raise_pending = false;
                slow |= rate > SLOW_CONTRACTION;
                self.eta = error_factor(rate);
            } else if raised_bounds(self.eta, norm, self.newton_tol) == Some(false) {
                // Not converged whatever the factor: the next iteration replaces it.
                raise_pending = true;
                prev_norm = norm;
                continue;
            } else {
                self.eta = first_error_factor(self.eta);
            }
            if self.eta * norm < self.newton_tol {
                return Some(slow || iter >= 4);
            }
            prev_norm = norm;
        }
        None
    }

    /// One attempt from (t, y) with step h: on success the result is in `work.end_y` and the error
    /// estimate in `work.est`.
    fn try_step<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        y: &[f64],
        force_refresh: bool,
    ) -> bool
    where
        M: IterationMatrix<S>,
    {
        let n = self.n;
        // A second handle on the tableau frees `self` for the stages.
        let tb = self.active().clone();
        let d = tb.gamma * h;
        {
            let wk = &mut self.work;
            if wk.end_valid && (wk.end_t - t).abs() <= 1e-9 * h && wk.end_y == y && !force_refresh {
                // Taken, not copied (buffers swap): it is no longer there to take again.
                std::mem::swap(&mut wk.f[0], &mut wk.end_f);
                wk.end_valid = false;
            } else {
                sys.rhs(t, y, &mut wk.f[0]);
                self.stats.rhs_evals += 1;
            }
        }
        if force_refresh || self.refresh_next || !self.jac_valid {
            self.stats.rhs_evals += self.matrix.update_jacobian(sys, t, y, &self.work.f[0]);
            self.stats.jacobians += 1;
            self.jac_valid = true;
            self.lu_valid = false;
            self.refresh_next = false;
        }
        if !self.lu_valid || (self.lu_d - d).abs() > REUSE * d {
            self.lu_valid = self.matrix.factorise(d);
            self.lu_d = d;
            self.stats.factorisations += 1;
        }
        let mut slow = false;
        for s in 1..tb.stages {
            // rhs = y + h Σ_j a_sj F_j; Newton starts from rhs + d F̂_s, the stage's slope F̂_s
            // predicted by the polynomial through the earlier stages.
            {
                // One pass over the components (no copies), the sums in the order of j.
                let wk = &mut self.work;
                let mut ha = [0.0; MAX_STAGES];
                let mut dp = [0.0; MAX_STAGES];
                for j in 0..s {
                    (ha[j], dp[j]) = (h * tb.a[s][j], d * tb.predictor[s][j]);
                }
                let f = &wk.f[..s];
                for i in 0..n {
                    let (mut r, mut p) = (y[i], 0.0);
                    for (j, fj) in f.iter().enumerate() {
                        r += ha[j] * fj[i];
                        p += dp[j] * fj[i];
                    }
                    wk.rhs[i] = r;
                    wk.z[i] = r + p;
                }
            }
            let Some(sl) = self.newton(sys, t + tb.c[s] * h, d) else {
                return false;
            };
            slow |= sl;
            let wk = &mut self.work;
            for i in 0..n {
                wk.f[s][i] = (wk.z[i] - wk.rhs[i]) / d;
            }
        }
        self.refresh_next = slow;
        self.finish_step::<S>(&tb, t, h);
        true
    }

    /// After the stages of a step from t of size h: the error estimate `h Σ_j e_j F_j`, filtered
    /// through `(I - hγ J)⁻¹`, in `work.est`; the result in `work.end_y` and its derivative in
    /// `work.end_f`, for the next step's first stage.
    #[inline]
    fn finish_step<S: OdeSystem + ?Sized>(&mut self, tb: &Tableau, t: f64, h: f64)
    where
        M: IterationMatrix<S>,
    {
        let wk = &mut self.work;
        let mut he = [0.0; MAX_STAGES];
        for j in 0..tb.stages {
            he[j] = h * tb.e[j];
        }
        let f = &wk.f[..tb.stages];
        for (i, e) in wk.est.iter_mut().enumerate() {
            *e = f
                .iter()
                .enumerate()
                .fold(0.0, |acc, (j, fj)| acc + he[j] * fj[i]);
        }
        wk.end_t = t + h;
        // Buffers swap rather than copy (a copy of a few numbers is a call to memcpy): the result
        // is in `end_y` from here; `z` and the last stage's slot are overwritten by the next step
        // before they are read.
        std::mem::swap(&mut wk.end_y, &mut wk.z);
        std::mem::swap(&mut wk.end_f, &mut wk.f[tb.stages - 1]);
        wk.end_valid = true;
        self.matrix.solve(&mut wk.est);
        self.stats.solves += 1;
    }

    /// The error estimate of the last step in units of the tolerance (max norm; infinite when
    /// it is not finite).
    #[inline]
    fn scaled_error(&self) -> f64 {
        let err = self
            .work
            .est
            .iter()
            .zip(&self.work.inv_w)
            .map(|(x, w)| (x * w).abs())
            .fold(0.0, f64::max);
        if err.is_finite() {
            err
        } else {
            f64::INFINITY
        }
    }

    fn end_is_finite(&self) -> bool {
        self.work.end_y.iter().all(|v| v.is_finite())
    }

    fn step_split<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        y: &mut [f64],
        depth: u32,
    ) -> Result<(), ConvergenceError>
    where
        M: IterationMatrix<S>,
    {
        for attempt in 0..2 {
            if self.try_step(sys, t, h, y, attempt == 1) && self.end_is_finite() {
                y.copy_from_slice(&self.work.end_y);
                self.stats.substeps += 1;
                return Ok(());
            }
        }
        if depth >= 6 {
            return Err(ConvergenceError { t });
        }
        self.stats.rejected += 1;
        let half = 0.5 * h;
        self.step_split(sys, t, half, y, depth + 1)?;
        self.step_split(sys, t + half, half, y, depth + 1)
    }

    /// One step of size h from (t, y); `y` is updated in place. On failure it refreshes the
    /// Jacobian and retries, then splits the step in halves (up to 2^6 pieces).
    pub(crate) fn step<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        y: &mut [f64],
    ) -> Result<(), ConvergenceError>
    where
        M: IterationMatrix<S>,
    {
        self.high_active = false;
        self.load_scales(sys);
        self.step_split(sys, t, h, y, 0)
    }

    /// Newton's weights from the system's scales, once per call (the scales are constants of
    /// the system; the scales themselves are left in `inv_w`).
    fn load_scales<S: OdeSystem + ?Sized>(&mut self, sys: &S) {
        let wk = &mut self.work;
        sys.scales(&mut wk.inv_w);
        for (i, s) in wk.inv_scale.iter_mut().zip(&wk.inv_w) {
            *i = 1.0 / s;
        }
    }

    /// Integrates from t0 to t1 with sub-steps chosen by the local error estimate, so that each
    /// sub-step's error is below `tol` times the system's scales (max norm). `h` carries the
    /// step size from call to call (deterministic: it depends only on the history of states).
    /// Steps are at most `t1 - t0` and at least `(t1 - t0) / max_substeps`; a step at the
    /// minimum size is accepted whatever its estimate.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(crate) fn advance<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &S,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        h: &mut f64,
        tol: f64,
        max_substeps: usize,
    ) -> Result<usize, ConvergenceError>
    where
        M: IterationMatrix<S>,
    {
        let span = t1 - t0;
        let h_min = span / max_substeps as f64;
        self.high_active = self.high.is_some() && *h > 0.0 && *h < HIGH_BELOW * span;
        let order = self.active().embedded_order;
        self.newton_tol = (NEWTON_TOL_FRACTION * tol).min(NEWTON_TOL_MAX);
        // The scales, left in inv_w, become its weights.
        self.load_scales(sys);
        for s in self.work.inv_w.iter_mut() {
            *s = 1.0 / (tol * *s);
        }
        let mut t = t0;
        let mut taken = 0;
        if !(*h > 0.0 && h.is_finite()) {
            *h = span;
        }
        if !(span > 0.0 && span.is_finite()) || y.iter().any(|v| !v.is_finite()) {
            return Err(ConvergenceError { t: t0 });
        }
        while t1 - t > 1e-12 * span {
            let remaining = t1 - t;
            let mut step = h.clamp(h_min, span);
            if remaining <= step {
                step = remaining;
            } else if remaining < 2.0 * step {
                step = 0.5 * remaining;
            }
            let mut ok = self.try_step(sys, t, step, y, false) && self.end_is_finite();
            if !ok {
                self.stats.rejected += 1;
                ok = self.try_step(sys, t, step, y, true) && self.end_is_finite();
            }
            if !ok {
                if step > h_min * (1.0 + 1e-9) {
                    *h = (0.25 * step).max(h_min);
                    continue;
                }
                self.step_split(sys, t, step, y, 0)?;
                t += step;
                taken += 1;
                continue;
            }
            let err = self.scaled_error();
            let factor = step_factor(err, order + 1);
            if err <= 1.0 || step <= h_min * (1.0 + 1e-9) {
                let clipped = step < *h;
                y.copy_from_slice(&self.work.end_y);
                t += step;
                taken += 1;
                self.stats.substeps += 1;
                let proposed = if (1.0..=1.25).contains(&factor) {
                    step
                } else {
                    step * factor
                };
                *h = if clipped && factor >= 1.0 {
                    h.max(proposed)
                } else {
                    proposed
                };
            } else {
                self.stats.rejected += 1;
                self.work.end_valid = false;
                *h = step * factor;
            }
        }
        Ok(taken)
    }
}

#[cfg(test)]
mod tests;
