//! Huxley's two-state cross-bridge rates (docs/model.md §6), bridge position ξ in units of h.

/// Rate constants f1, g1, g2, g3 (1/s once scaled).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rates {
    /// Attachment slope on [0, 1].
    pub f1: f64,
    /// Detachment slope on [0, 1] (and beyond 1).
    pub g1: f64,
    /// Detachment rate for ξ < 0.
    pub g2: f64,
    /// Extra detachment slope beyond ξ = 1.
    pub g3: f64,
}

impl Rates {
    /// All rates multiplied by `s`.
    pub(crate) fn scaled(self, s: f64) -> Rates {
        Rates {
            f1: self.f1 * s,
            g1: self.g1 * s,
            g2: self.g2 * s,
            g3: self.g3 * s,
        }
    }

    /// Attachment rate `f(ξ) = f1 ξ` on [0, 1], else 0.
    pub(crate) fn attach(&self, xi: f64) -> f64 {
        if (0.0..=1.0).contains(&xi) {
            self.f1 * xi
        } else {
            0.0
        }
    }

    /// Detachment rate `g(ξ)`: g2 (ξ < 0); g1 ξ on [0, 1]; g1 ξ + g3 (ξ - 1) beyond 1.
    pub(crate) fn detach(&self, xi: f64) -> f64 {
        if xi < 0.0 {
            self.g2
        } else if xi <= 1.0 {
            self.g1 * xi
        } else {
            self.g1 * xi + self.g3 * (xi - 1.0)
        }
    }

    /// `β_k = ∫ ξ^k f(ξ) dξ = f1 / (k + 2)`.
    pub(crate) fn beta(&self, k: usize) -> f64 {
        self.f1 / (k as f64 + 2.0)
    }
}
