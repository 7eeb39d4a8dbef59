//! The stepper's state as a saved state's bytes (`sim::saved`): what it carries from call to
//! call, read back into a stepper rebuilt with the same tableaux and sizes.

use super::Esdirk;
use crate::integrator::Stats;
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};

/// What a stepper carries from call to call: the iteration matrix (its Jacobian and
/// factorisation) and whether they are valid, Newton's carried error factor and threshold, the
/// last step's end and derivative (the next step's first stage), every work vector, the
/// counters. The tableaux are the rebuilt stepper's.
impl<M: SavedState> SavedState for Esdirk<M> {
    fn save_state(&self, out: &mut StateWriter) {
        for flag in [
            self.high_active,
            self.jac_valid,
            self.lu_valid,
            self.refresh_next,
        ] {
            out.bool(flag);
        }
        for v in [self.lu_d, self.newton_tol, self.eta] {
            out.f64(v);
        }
        let wk = &self.work;
        out.usize(wk.f.len());
        for f in &wk.f {
            out.f64s(f);
        }
        for v in [
            &wk.rhs,
            &wk.z,
            &wk.fz,
            &wk.delta,
            &wk.est,
            &wk.inv_scale,
            &wk.inv_w,
        ] {
            out.f64s(v);
        }
        out.f64(wk.end_t);
        out.f64s(&wk.end_y);
        out.f64s(&wk.end_f);
        out.bool(wk.end_valid);
        let Stats {
            rhs_evals,
            jacobians,
            factorisations,
            solves,
            substeps,
            rejected,
        } = self.stats;
        for v in [
            rhs_evals,
            jacobians,
            factorisations,
            solves,
            substeps,
            rejected,
        ] {
            out.u64(v);
        }
        self.matrix.save_state(out);
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        self.high_active = input.bool("stepper's fourth-order flag")?;
        if self.high_active && self.high.is_none() {
            return Err(StateError::Invalid(
                "the stepper's fourth-order flag is set for a stepper without it".into(),
            ));
        }
        self.jac_valid = input.bool("stepper's Jacobian flag")?;
        self.lu_valid = input.bool("stepper's factorisation flag")?;
        self.refresh_next = input.bool("stepper's refresh flag")?;
        self.lu_d = input.f64("stepper's factorised h gamma")?;
        self.newton_tol = input.f64("stepper's Newton threshold")?;
        self.eta = input.f64("stepper's Newton error factor")?;
        let wk = &mut self.work;
        input.expect_len("stepper's stage slots", wk.f.len())?;
        for f in wk.f.iter_mut() {
            input.f64s_into("stepper's stage derivative", f)?;
        }
        for v in [
            &mut wk.rhs,
            &mut wk.z,
            &mut wk.fz,
            &mut wk.delta,
            &mut wk.est,
            &mut wk.inv_scale,
            &mut wk.inv_w,
        ] {
            input.f64s_into("stepper's work vector", v)?;
        }
        wk.end_t = input.f64("stepper's last step end")?;
        input.f64s_into("stepper's last step state", &mut wk.end_y)?;
        input.f64s_into("stepper's last step derivative", &mut wk.end_f)?;
        wk.end_valid = input.bool("stepper's last step flag")?;
        let mut counter = || input.u64("stepper's work counters");
        self.stats = Stats {
            rhs_evals: counter()?,
            jacobians: counter()?,
            factorisations: counter()?,
            solves: counter()?,
            substeps: counter()?,
            rejected: counter()?,
        };
        self.matrix.restore_state(input)
    }
}
