//! How a tick is divided into implicit sub-steps (docs/model.md §10): each model's default
//! (`ModelSpec::stepping`) and a run's
//! choice are values of this one type.

/// Most adaptive sub-steps per tick by default.
pub const DEFAULT_MAX_SUBSTEPS: usize = 64;
/// Most sub-steps per tick, fixed or adaptive (a sanity bound).
pub const MAX_SUBSTEPS: usize = 10_000;

/// A stepping that breaks its rules ([`Stepping::check`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SteppingError {
    /// An adaptive tolerance that is not a finite number > 0.
    #[error("invalid tolerance = {0}: must be a finite number > 0")]
    Tolerance(
        /// The tolerance.
        f64,
    ),
    /// A number of sub-steps outside 1 to [`MAX_SUBSTEPS`].
    #[error("invalid {name} = {count}: must be between 1 and {MAX_SUBSTEPS}")]
    Substeps {
        /// `substeps` (fixed) or `max_substeps` (adaptive).
        name: &'static str,
        /// The number given.
        count: usize,
    },
}

/// How a tick is divided into implicit sub-steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stepping {
    /// Sub-steps chosen by the local error estimate: each below `tolerance` times the state's
    /// scales, at most `max_substeps` per tick.
    Adaptive {
        /// Relative local error tolerance.
        tolerance: f64,
        /// Most sub-steps per tick.
        max_substeps: usize,
    },
    /// A fixed number of equal sub-steps per tick (models with state outside the ODE).
    Fixed(usize),
}

impl Stepping {
    /// Its rules: 1 to [`MAX_SUBSTEPS`] sub-steps, an adaptive tolerance finite and > 0.
    pub fn check(&self) -> Result<(), SteppingError> {
        let (what, n) = match *self {
            Stepping::Fixed(n) => ("substeps", n),
            Stepping::Adaptive {
                tolerance,
                max_substeps,
            } => {
                if !(tolerance.is_finite() && tolerance > 0.0) {
                    return Err(SteppingError::Tolerance(tolerance));
                }
                ("max_substeps", max_substeps)
            }
        };
        if (1..=MAX_SUBSTEPS).contains(&n) {
            Ok(())
        } else {
            Err(SteppingError::Substeps {
                name: what,
                count: n,
            })
        }
    }

    /// Whether the sub-steps follow the local error estimate.
    pub fn is_adaptive(&self) -> bool {
        matches!(self, Stepping::Adaptive { .. })
    }
}
