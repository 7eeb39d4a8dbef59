//! The "exponential, then linear" spring of Winters & Stark (docs/model.md §4), used by both the
//! tendon (series element) and the parallel element. Pure closed forms: force, stiffness,
//! inverse (length from force) and strain energy.

/// An exponential-then-linear tension spring, slack below `l_s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExpLinearSpring {
    /// Spring constant of the exponential part k_l, N/m.
    pub k_l: f64,
    /// Exponential shape k_e, 1/m.
    pub k_e: f64,
    /// Slack length l_s, m.
    pub l_s: f64,
    /// Length where the spring turns linear l_c, m.
    pub l_c: f64,
    /// Force at l_c where the linear part starts, F_c, N.
    pub(crate) f_c: f64,
    /// Spring constant of the linear part k, N/m.
    pub k: f64,
}

impl ExpLinearSpring {
    /// Tension, N (docs/model.md §4):
    /// 0 below slack; `(k_l/k_e)(exp(k_e (l - l_s)) - 1)` up to l_c; `F_c + k (l - l_c)` beyond.
    pub fn force(&self, l: f64) -> f64 {
        if l < self.l_s {
            0.0
        } else if l <= self.l_c {
            self.k_l / self.k_e * (self.k_e * (l - self.l_s)).exp_m1()
        } else {
            self.f_c + self.k * (l - self.l_c)
        }
    }

    /// Stiffness dF/dl, N/m: 0, `k_l exp(k_e (l - l_s))`, or k.
    pub fn stiffness(&self, l: f64) -> f64 {
        if l < self.l_s {
            0.0
        } else if l <= self.l_c {
            self.k_l * (self.k_e * (l - self.l_s)).exp()
        } else {
            self.k
        }
    }

    /// Force at the end of the exponential part, N (equals f_c when the spring is continuous).
    fn exp_force_at_l_c(&self) -> f64 {
        self.k_l / self.k_e * (self.k_e * (self.l_c - self.l_s)).exp_m1()
    }

    /// Length at which the spring carries `force` (the inverse of `force`), m. A force <= 0
    /// gives the slack length.
    pub fn length_at_force(&self, force: f64) -> f64 {
        if force <= 0.0 {
            self.l_s
        } else if force <= self.exp_force_at_l_c() {
            self.l_s + (force * self.k_e / self.k_l).ln_1p() / self.k_e
        } else {
            self.l_c + (force - self.f_c) / self.k
        }
    }

    /// Strain energy `E(l) = ∫_{l_s}^{l} F(x) dx`, J (paper eqs. 13–14):
    /// `(k_l/k_e)((exp(k_e d) - 1)/k_e - d)` with `d = min(l, l_c) - l_s`, plus
    /// `F_c y + k y²/2` with `y = l - l_c` beyond l_c.
    pub fn energy(&self, l: f64) -> f64 {
        if l <= self.l_s {
            return 0.0;
        }
        let d = l.min(self.l_c) - self.l_s;
        let exp_part = self.k_l / self.k_e * ((self.k_e * d).exp_m1() / self.k_e - d);
        if l <= self.l_c {
            exp_part
        } else {
            let y = l - self.l_c;
            exp_part + self.f_c * y + 0.5 * self.k * y * y
        }
    }
}
