//! The force–length curve f(l_m) (paper eq. 3), shared by Hill (force factor) and Huxley
//! (filament-overlap factor λ that scales attachment).

use crate::physics::limb_params::ForceLengthShape;

/// `f(l) = max(0, 1 - ((l/lopt - 1)/w)^2)` (parabola) or `exp(-((l/lopt - 1)/w)^2)` (Gaussian).
pub fn force_length(l: f64, l_opt: f64, w: f64, shape: ForceLengthShape) -> f64 {
    let x = (l / l_opt - 1.0) / w;
    match shape {
        ForceLengthShape::Parabola => (1.0 - x * x).max(0.0),
        ForceLengthShape::Gaussian => (-x * x).exp(),
    }
}

/// df/dl, 1/m.
pub(crate) fn force_length_slope(l: f64, l_opt: f64, w: f64, shape: ForceLengthShape) -> f64 {
    let x = (l / l_opt - 1.0) / w;
    let dx_dl = 1.0 / (l_opt * w);
    match shape {
        ForceLengthShape::Parabola if x.abs() < 1.0 => -2.0 * x * dx_dl,
        ForceLengthShape::Parabola => 0.0,
        ForceLengthShape::Gaussian => -2.0 * x * (-x * x).exp() * dx_dl,
    }
}
