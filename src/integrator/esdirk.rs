//! Stiffly accurate ESDIRK methods with an embedded error estimate (Kennedy & Carpenter 2003):
//! an explicit first stage, then implicit stages that share the iteration matrix `I - hγ J`;
//! the last stage is the step's result and its derivative starts the next step.
//!
//! Three tableaux: TR-BDF2 (second order; for fixed sub-steps) and, for adaptive sub-steps, the
//! implicit part of ARK3(2)4L[2]SA: third order, L-stable, three
//! implicit stages, an embedded second-order solution for the error estimate, filtered through
//! `(I - hγ J)⁻¹` for the stiff components (Hosea & Shampine 1996). In the transients, where the
//! fibre mass rings on the tendon and cross-bridge springs, its sub-steps are much longer than a
//! second-order method's (TR-BDF2, which this project used before) at the same accuracy. While
//! the state moves so fast that one step barely covers a call's span, `advance` switches to
//! ESDIRK4(3)6L[2]SA (fourth order, five implicit stages): after a full excitation step it takes
//! 2.6 sub-steps per tick instead of 6.2, and about 30% fewer evaluations; quiet ticks, one
//! step each, stay on the three-stage method.
//!
//! Written by hand: on a stiff toy problem measured for this project, diffsol's ESDIRK/BDF cost
//! about 1 µs per 1 ms tick against about 0.5 µs for a hand-written TR-BDF2 (this project's
//! earlier stepper), and the tick loop needs one that is
//! allocation-free and bit-deterministic, keeps its Jacobian across ticks, and lets the linear
//! algebra exploit the plant's structure (the [`IterationMatrix`]). The Jacobian and its
//! factorisation are refreshed only when the simplified Newton iteration converges slowly, the
//! step size changes by more than 20%, or it fails. `advance` chooses sub-steps by the embedded
//! error estimate; `step` takes one fixed step.

// Index loops over several parallel vectors read better than zipped iterators here.
#![allow(clippy::needless_range_loop)]

use crate::integrator::{ConvergenceError, IterationMatrix, OdeSystem, Stats};
use std::sync::Arc;

/// Most stages of a tableau.
const MAX_STAGES: usize = 6;
/// Newton stops when the scaled error it estimates is left is below this fraction of the step's
/// tolerance (and never above `NEWTON_TOL_MAX`). At 0.1 the elbow's joint scenario (DM) drifted
/// 1.2e-6 m from the reference CSV of the earlier program (bound 1e-6 m, tests/reference_runs.rs);
/// at 0.03 it stays at 8e-7 m, at 0.01 it costs 10% more evaluations for nothing measurable.
const NEWTON_TOL_FRACTION: f64 = 0.03;
const NEWTON_TOL_MAX: f64 = 1e-5;
const NEWTON_MAX_ITER: usize = 10;
const SLOW_CONTRACTION: f64 = 0.3;
/// `advance` takes the higher-order tableau, when it has one, for a call whose carried step is
/// below this multiple of the call's span. 1.5 rather than 1: a tick that follows a step the
/// error estimate let grow only a little past the tick is about to need sub-steps (DM under the
/// realistic load of benches/limb.rs: 4.25 → 3.93 µs per tick at 1.5, 3.90 at 2; at 2.5 the
/// steady ticks, whose carried step is at most 2 spans, take it too and cost 1.4× more).
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
/// `ETA_MIN^0.8`. (Taking the last one as it is saves a third of the iterations, and put the DM
/// pulse 2e-5 m off the reference solution.)
fn first_error_factor(last: f64) -> f64 {
    last.max(ETA_MIN).powf(0.8)
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

/// A stiffly accurate ESDIRK tableau with an embedded method.
#[derive(Debug, Clone, PartialEq)]
pub struct Tableau {
    /// Number of stages (the first explicit).
    pub stages: usize,
    /// The diagonal γ.
    pub gamma: f64,
    /// Stage times c_i.
    pub c: [f64; MAX_STAGES],
    /// Coefficients a_ij, row-major, `stages × stages` in a `MAX_STAGES²` array.
    pub a: [[f64; MAX_STAGES]; MAX_STAGES],
    /// `b - b̂`: the weights of the error estimate.
    pub e: [f64; MAX_STAGES],
    /// Order of the embedded method (the error estimate is O(h^(order + 1))).
    pub embedded_order: u32,
    /// Stage predictor weights: `F_s ≈ Σ_j p_sj F_j`, the polynomial through the earlier
    /// stages' (c_j, F_j) evaluated at c_s.
    pub predictor: [[f64; MAX_STAGES]; MAX_STAGES],
}

/// Lagrange weights at each stage time of the polynomial through the earlier stages.
fn predictor_weights(c: &[f64; MAX_STAGES], stages: usize) -> [[f64; MAX_STAGES]; MAX_STAGES] {
    let mut p = [[0.0; MAX_STAGES]; MAX_STAGES];
    for s in 1..stages {
        for j in 0..s {
            p[s][j] = (0..s)
                .filter(|&k| k != j)
                .map(|k| (c[s] - c[k]) / (c[j] - c[k]))
                .product();
        }
    }
    p
}

impl Tableau {
    /// TR-BDF2 (Bank et al. 1985) written as an ESDIRK: a trapezoidal stage to γ = 2 - √2, then
    /// BDF2 to 1; second order, L-stable, two implicit stages with diagonal γ/2. Its error
    /// estimate is Hosea & Shampine's (1996): `2 C h [(F_2 - F_1)/(1 - γ) - (F_1 - F_0)/γ]`,
    /// `C = (-3γ² + 4γ - 2) / (12 (2 - γ))`.
    pub fn trbdf2() -> Self {
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
        Self {
            stages: 3,
            gamma: d,
            predictor: predictor_weights(&c, 3),
            c,
            a,
            e,
            embedded_order: 2,
        }
    }

    /// ARK3(2)4L[2]SA, implicit part (Kennedy & Carpenter 2003).
    pub fn ark324() -> Self {
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
        Self {
            stages: 4,
            gamma: g,
            predictor: predictor_weights(&c, 4),
            c,
            a,
            e,
            embedded_order: 2,
        }
    }
}

impl Tableau {
    /// ESDIRK4(3)6L[2]SA (Kennedy & Carpenter 2016, NASA/TM-2016-219173, "Diagonally implicit
    /// Runge–Kutta methods for ordinary differential equations. A review", table of the method
    /// of that name): fourth order, L-stable, stiffly accurate, five implicit stages with
    /// γ = 1/4, an embedded third-order solution. The coefficients as SUNDIALS gives them
    /// (`src/arkode/arkode_butcher_dirk.def`, `ARKODE_ESDIRK436L2SA_6_3_4`): a_i0 from the row
    /// sums c_i, the last row the weights b.
    pub fn esdirk436() -> Self {
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
        Self {
            stages: 6,
            gamma: g,
            predictor: predictor_weights(&c, 6),
            c,
            a,
            e,
            embedded_order: 3,
        }
    }
}

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
pub struct Esdirk<M> {
    n: usize,
    /// Shared, so that a step borrows it while the stages borrow the rest of `self` (a copy per
    /// step was a measurable memmove).
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
    pub fn new(n: usize, matrix: M, tableau: Tableau) -> Self {
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
    pub fn with_high_order(mut self, high: Tableau) -> Self {
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
    pub fn invalidate(&mut self) {
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
                return None;
            }
            if iter > 0 {
                let rate = norm / prev_norm;
                if rate > 1.0 {
                    return None;
                }
                slow |= rate > SLOW_CONTRACTION;
                self.eta = error_factor(rate);
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
        true
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
    pub fn step<S: OdeSystem + ?Sized>(
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
    pub fn advance<S: OdeSystem + ?Sized>(
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
            let err = self
                .work
                .est
                .iter()
                .zip(&self.work.inv_w)
                .map(|(x, w)| (x * w).abs())
                .fold(0.0, f64::max);
            let err = if err.is_finite() { err } else { f64::INFINITY };
            let factor = if err > 0.0 {
                (0.9 * inverse_root(err, order + 1)).clamp(0.2, 2.0)
            } else {
                2.0
            };
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
mod tests {
    use super::*;
    use crate::integrator::dense::DenseMatrix;

    /// TR-BDF2's tableau: second order, and an error estimate that vanishes on polynomials of
    /// degree one in time.
    #[test]
    fn trbdf2_meets_its_order_conditions() {
        let t = Tableau::trbdf2();
        let s = t.stages;
        let b: Vec<f64> = (0..s).map(|j| t.a[s - 1][j]).collect();
        for i in 0..s {
            let row: f64 = (0..s).map(|j| t.a[i][j]).sum();
            assert!((row - t.c[i]).abs() < 1e-15, "row {i}");
        }
        let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
        assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!((dot(&b, &t.c[..s]) - 0.5).abs() < 1e-15);
        assert!(t.e[..s].iter().sum::<f64>().abs() < 1e-15);
        assert!(dot(&t.e[..s], &t.c[..s]).abs() < 1e-15);
        let c2: Vec<f64> = t.c[..s].iter().map(|x| x * x).collect();
        assert!(dot(&t.e[..s], &c2).abs() > 1e-3);
    }

    /// The tableau's order conditions: third order for the method, second for the embedding.
    #[test]
    fn ark324_meets_its_order_conditions() {
        let t = Tableau::ark324();
        let s = t.stages;
        let b: Vec<f64> = (0..s).map(|j| t.a[s - 1][j]).collect();
        let bh: Vec<f64> = (0..s).map(|j| b[j] - t.e[j]).collect();
        for i in 0..s {
            let row: f64 = (0..s).map(|j| t.a[i][j]).sum();
            assert!((row - t.c[i]).abs() < 1e-12, "row {i}");
        }
        let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
        let c: Vec<f64> = t.c[..s].to_vec();
        let c2: Vec<f64> = c.iter().map(|x| x * x).collect();
        let ac: Vec<f64> = (0..s)
            .map(|i| (0..s).map(|j| t.a[i][j] * c[j]).sum())
            .collect();
        assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        assert!((dot(&b, &c) - 0.5).abs() < 1e-12);
        assert!((dot(&b, &c2) - 1.0 / 3.0).abs() < 1e-12);
        assert!((dot(&b, &ac) - 1.0 / 6.0).abs() < 1e-12);
        assert!((bh.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        assert!((dot(&bh, &c) - 0.5).abs() < 1e-12);
    }

    /// Prothero–Robinson: y' = λ (y - cos t) - sin t, exact solution y = cos t for any λ.
    struct ProtheroRobinson(f64);
    impl OdeSystem for ProtheroRobinson {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = self.0 * (y[0] - t.cos()) - t.sin();
        }
        fn scales(&self, out: &mut [f64]) {
            out[0] = 1.0;
        }
    }

    /// Stiffly accurate: no order reduction on the stiff problem.
    #[test]
    fn stiff_problem_is_solved_at_the_smooth_solution_accuracy() {
        for lambda in [-1.0, -1e3, -1e6] {
            let sys = ProtheroRobinson(lambda);
            let mut st = Esdirk::new(1, DenseMatrix::new(1), Tableau::ark324());
            let mut y = [1.0];
            let h = 1e-2;
            for k in 0..100 {
                st.step(&sys, k as f64 * h, h, &mut y).unwrap();
            }
            let err = (y[0] - 1f64.cos()).abs();
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
        fn dim(&self) -> usize {
            1
        }
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

    /// ESDIRK4(3)6L[2]SA's order conditions: fourth order for the method (all eight trees),
    /// third for the embedding, and the stages' row sums.
    #[test]
    fn esdirk436_meets_its_order_conditions() {
        let t = Tableau::esdirk436();
        let s = t.stages;
        let b: Vec<f64> = (0..s).map(|j| t.a[s - 1][j]).collect();
        let bh: Vec<f64> = (0..s).map(|j| b[j] - t.e[j]).collect();
        for i in 0..s {
            let row: f64 = (0..s).map(|j| t.a[i][j]).sum();
            assert!((row - t.c[i]).abs() < 1e-12, "row {i}");
        }
        let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
        let c: Vec<f64> = t.c[..s].to_vec();
        let pw = |k: i32| c.iter().map(|x| x.powi(k)).collect::<Vec<f64>>();
        let am = |v: &[f64]| -> Vec<f64> {
            (0..s)
                .map(|i| (0..s).map(|j| t.a[i][j] * v[j]).sum())
                .collect()
        };
        let ac = am(&c);
        let ac2 = am(&pw(2));
        let aac = am(&ac);
        let cac: Vec<f64> = (0..s).map(|i| c[i] * ac[i]).collect();
        let conditions = |w: &[f64], order: usize| {
            let mut list = vec![
                (w.iter().sum::<f64>(), 1.0),
                (dot(w, &c), 0.5),
                (dot(w, &pw(2)), 1.0 / 3.0),
                (dot(w, &ac), 1.0 / 6.0),
                (dot(w, &pw(3)), 0.25),
                (dot(w, &cac), 1.0 / 8.0),
                (dot(w, &ac2), 1.0 / 12.0),
                (dot(w, &aac), 1.0 / 24.0),
            ];
            list.truncate(if order == 4 { 8 } else { 4 });
            for (k, (got, want)) in list.into_iter().enumerate() {
                assert!(
                    (got - want).abs() < 1e-12,
                    "order {order}, condition {k}: {got}"
                );
            }
        };
        conditions(&b, 4);
        conditions(&bh, 3);
        // The embedding is of order three, not four: its error estimate does not vanish.
        assert!(
            (dot(&bh, &pw(3)) - 0.25).abs() > 1e-6 || (dot(&bh, &aac) - 1.0 / 24.0).abs() > 1e-6
        );
    }

    #[test]
    fn esdirk436_converges_at_fourth_order_and_damps_stiff_modes() {
        let order = observed_order(Tableau::esdirk436, 10);
        assert!((3.7..4.4).contains(&order), "observed order {order}");
        let r = stiff_decay(Tableau::esdirk436);
        assert!(r.abs() < 1e-6, "R(-1e9) = {r}");
        for lambda in [-1.0, -1e3, -1e6] {
            let sys = ProtheroRobinson(lambda);
            let mut st = Esdirk::new(1, DenseMatrix::new(1), Tableau::esdirk436());
            let mut y = [1.0];
            let h = 1e-2;
            for k in 0..100 {
                st.step(&sys, k as f64 * h, h, &mut y).unwrap();
            }
            let err = (y[0] - 1f64.cos()).abs();
            assert!(err < 1e-7, "λ = {lambda}: error {err}");
        }
    }
}
