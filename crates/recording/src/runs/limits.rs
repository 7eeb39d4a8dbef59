//! The limits a run keeps wherever its numbers come from (the command line, a recording's
//! metadata): the tick rate and sub-steps as the node's parameters and the simulation allow
//! them, and the length of a recorded run that replay may simulate.

use muscle_actuator_core::physics::{Stepping, SteppingError};
use muscle_actuator_core::sim::MAX_RATE_HZ;

/// Most sub-steps per tick, fixed or as the adaptive maximum (as `Simulation::new` allows).
pub(crate) use muscle_actuator_core::physics::MAX_SUBSTEPS;

/// Most ticks a recorded run may span: replay simulates every one of them (10^8: a day at
/// 1 kHz).
pub(crate) const MAX_RECORDED_TICKS: u64 = 100_000_000;

/// A number out of its limits, named as where it came from (`--rate-hz`,
/// `metadata muscle_actuator.rate_hz`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LimitError {
    /// A tick rate that is not finite, not > 0 or above [`MAX_RATE_HZ`].
    #[error(
        "{name} = {} is invalid: must be a finite number > 0 and <= {MAX_RATE_HZ} (the node's \
         limit for rate_hz)",
        shown(*.value)
    )]
    RateHz {
        /// Where the rate came from.
        name: String,
        /// The rate given, Hz.
        value: f64,
    },
    /// A number of sub-steps per tick outside 1 to [`MAX_SUBSTEPS`].
    #[error("{name} = {value} is invalid: must be between 1 and {MAX_SUBSTEPS}")]
    Substeps {
        /// Where the number came from.
        name: String,
        /// The number given.
        value: usize,
    },
    /// A stepping that breaks its rules ([`Stepping::check`]).
    #[error("{name}: {reason}")]
    Stepping {
        /// Where the stepping came from.
        name: String,
        /// The rule broken.
        #[source]
        reason: SteppingError,
    },
}

/// A tick rate, Hz: finite, > 0 and at most the node's [`MAX_RATE_HZ`]. `name` says where it
/// came from (`--rate-hz`, `metadata muscle_actuator.rate_hz`).
pub fn check_rate_hz(name: &str, r: f64) -> Result<(), LimitError> {
    if r.is_finite() && r > 0.0 && r <= MAX_RATE_HZ {
        Ok(())
    } else {
        Err(LimitError::RateHz {
            name: name.into(),
            value: r,
        })
    }
}

/// A number as written in messages: plainly, or in scientific notation if that is long.
fn shown(v: f64) -> String {
    let plain = v.to_string();
    if plain.len() <= 20 {
        plain
    } else {
        format!("{v:e}")
    }
}

/// A number of sub-steps per tick: 1 to [`MAX_SUBSTEPS`].
pub fn check_substeps(name: &str, n: usize) -> Result<(), LimitError> {
    if (1..=MAX_SUBSTEPS).contains(&n) {
        Ok(())
    } else {
        Err(LimitError::Substeps {
            name: name.into(),
            value: n,
        })
    }
}

/// A stepping within its rules ([`Stepping::check`]), named in the error.
pub(crate) fn check_stepping(name: &str, s: Stepping) -> Result<(), LimitError> {
    s.check().map_err(|reason| LimitError::Stepping {
        name: name.into(),
        reason,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_and_substeps_within_the_node_limits() {
        for ok in [1e-3, 1000.0, MAX_RATE_HZ] {
            assert!(check_rate_hz("r", ok).is_ok(), "{ok}");
        }
        for bad in [
            f64::NAN,
            f64::INFINITY,
            -1.0,
            0.0,
            1e9,
            MAX_RATE_HZ * 1.0001,
        ] {
            let e = check_rate_hz("--rate-hz", bad).unwrap_err().to_string();
            assert!(
                e.starts_with("--rate-hz = ") && e.contains("<= 100000"),
                "{e}"
            );
        }
        assert!(check_substeps("s", 1).is_ok() && check_substeps("s", MAX_SUBSTEPS).is_ok());
        assert!(check_substeps("s", 0).is_err() && check_substeps("s", usize::MAX).is_err());
        let adaptive = |tolerance, max_substeps| Stepping::Adaptive {
            tolerance,
            max_substeps,
        };
        assert!(check_stepping("x", adaptive(1e-5, 64)).is_ok());
        assert!(check_stepping("x", adaptive(f64::NAN, 64)).is_err());
        assert!(check_stepping("x", adaptive(1e-5, 0)).is_err());
        assert!(check_stepping("x", Stepping::Fixed(10_001)).is_err());
    }
}
