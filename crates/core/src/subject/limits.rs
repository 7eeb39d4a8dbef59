//! The bounds a drive holds its inputs to (docs/emg.md "Prediction").

/// The longest fibre a unit's length may ask, optimal lengths, with the tendon at slack:
/// CEINMS's own bound on a fibre (its equilibrium solve searches 0.2 to 2 l_opt,
/// lib/NMSmodel/Lloyd2003Muscle `integrateFiberLength`).
pub const MAX_FIBRE_LOPT: f64 = 2.0;

/// Largest relative deviation of an EMG sample step from the mean step: the EMG is one sample
/// per tick, so its samples must be evenly spaced.
pub const EMG_STEP_TOLERANCE: f64 = 1e-6;
