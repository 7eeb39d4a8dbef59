//! The bounds a drive holds its inputs to (docs/emg.md "Prediction").

/// The longest fibre a unit's length may ask, optimal lengths, with the tendon at slack:
/// CEINMS's own bound on a fibre (its equilibrium solve searches 0.2 to 2 l_opt,
/// lib/NMSmodel/Lloyd2003Muscle `integrateFiberLength`).
pub(crate) const MAX_FIBRE_LOPT: f64 = 2.0;

/// How far beyond its fibre's reach a prediction holds a unit's length at the reach (a counted
/// warning) rather than refusing it, as a fraction of the unit's resting length `l_opt + l_ts`:
/// a calibrated subject driven through a task it was not calibrated on may ask a few
/// millimetres more than its fibres reach (its geometry and lengths come from a scaled model),
/// while a length beyond this is an error in the data. Beyond 1.6 `l_opt` a CEINMS subject's
/// tabulated curves are flat (passive force at its ceiling, no active force), so a held length
/// changes the unit's force little.
pub(crate) const HELD_REACH_FRACTION: f64 = 0.1;

/// Largest relative deviation of an EMG sample step from the mean step: the EMG is one sample
/// per tick, so its samples must be evenly spaced.
pub(crate) const EMG_STEP_TOLERANCE: f64 = 1e-6;
