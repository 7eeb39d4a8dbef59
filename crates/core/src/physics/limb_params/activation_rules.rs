//! The rules of a muscle's activation keys (docs/model.md §2b, docs/configuration.md
//! "Activation"): Lloyd & Besier's constants only with `activation = "lloyd_besier"`, C1 and C2
//! then required, each within the range `crate::emg` accepts.

use super::formulation::ActivationKind;
use super::{Checker, MuscleParams};
use crate::emg::neural::MAX_DELAY_S;
use crate::emg::nonlinearity::{MAX_SHAPE_FACTOR, MIN_SHAPE_FACTOR};

impl MuscleParams {
    /// Appends one error per broken activation rule.
    pub(super) fn validate_activation(&self, c: &mut Checker<'_>) {
        if let Some(s) = self.optimal_length_shift {
            if !(s.is_finite() && (0.0..1.0).contains(&s)) {
                c.fail("optimal_length_shift", s, "must be >= 0 and < 1");
            }
        }
        let keys = [
            ("c1", self.c1),
            ("c2", self.c2),
            ("shape_factor", self.shape_factor),
            ("em_delay", self.em_delay),
            ("neural_rate_hz", self.neural_rate_hz),
        ];
        if self.activation == ActivationKind::FirstOrder {
            for (name, value) in keys {
                if let Some(v) = value {
                    c.fail(name, v, "applies to activation = \"lloyd_besier\" only");
                }
            }
            return;
        }
        for (name, value) in [("c1", self.c1), ("c2", self.c2)] {
            match value {
                None => c.fail(
                    name,
                    "(none)",
                    "is needed with activation = \"lloyd_besier\" (|C| < 1, at neural_rate_hz)",
                ),
                Some(v) if !(v.is_finite() && v.abs() < 1.0) => {
                    c.fail(name, v, "must be > -1 and < 1 (a stable recursion)")
                }
                Some(_) => {}
            }
        }
        if let Some(a) = self.shape_factor {
            if !(MIN_SHAPE_FACTOR..=MAX_SHAPE_FACTOR).contains(&a) {
                c.fail("shape_factor", a, "must be >= -3 and <= 3");
            }
        }
        if let Some(d) = self.em_delay {
            if !(0.0..=MAX_DELAY_S).contains(&d) {
                c.fail("em_delay", d, "must be >= 0 and <= 0.5 s");
            }
        }
        if let Some(r) = self.neural_rate_hz {
            c.positive("neural_rate_hz", r);
        }
    }
}
