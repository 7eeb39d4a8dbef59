//! The search: CMA-ES over the parameters the strengths do not solve ([`Problem::searched`]),
//! each in its bounds through the cosine map of the module above, candidates evaluated on a
//! pool of `threads` (rayon), deterministic for a seed.

use super::{Problem, FAILED_COST};
use cmaes::{CMAESOptions, DVector};
use std::ops::ControlFlow;

/// Fewest evaluations a calibration may be given: a CMA-ES generation samples two points at
/// least.
pub const MIN_EVALUATIONS: usize = 2;

/// Most evaluations a calibration may be given.
pub const MAX_EVALUATIONS: usize = 1_000_000;

/// The optimiser's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The seed of CMA-ES's sampling.
    pub seed: u64,
    /// Most objective evaluations of the search (whole generations of CMA-ES that fit in it,
    /// from [`MIN_EVALUATIONS`] to [`MAX_EVALUATIONS`]).
    pub max_evaluations: usize,
    /// Threads the candidates are evaluated on.
    pub threads: usize,
    /// CMA-ES's initial step in the search space (the bounds span π there).
    pub initial_step: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            seed: 1,
            max_evaluations: 1000,
            threads: 1,
            initial_step: 0.5,
        }
    }
}

/// A calibration's result.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// The best parameter values found, one per [`Problem::parameters`] (the start's if nothing
    /// found beats it).
    pub values: Vec<f64>,
    /// Their cost (`Problem::cost`, each trial driven with them).
    pub cost: f64,
    /// The cost of the starting values.
    pub start_cost: f64,
    /// Objective evaluations made.
    pub evaluations: usize,
    /// After each generation: evaluations so far and the best cost so far.
    pub history: Vec<(usize, f64)>,
    /// Whether the progress callback stopped the search before its evaluations were spent:
    /// then `values` are the best found so far.
    pub stopped: bool,
}

impl Problem {
    /// A point of the search space to the searched parameters' values (the cosine map).
    pub(crate) fn values_of(&self, z: &[f64]) -> Vec<f64> {
        self.searched
            .iter()
            .map(|&k| &self.parameters[k])
            .zip(z)
            .map(|(p, &z)| {
                let [lo, hi] = p.bounds;
                lo + (hi - lo) * 0.5 * (1.0 - (std::f64::consts::PI * z).cos())
            })
            .collect()
    }

    /// The point of the search space in [0, 1] that maps to the searched parameters' `values`.
    fn point_of(&self, values: &[f64]) -> Vec<f64> {
        self.searched
            .iter()
            .map(|&k| &self.parameters[k])
            .zip(values)
            .map(|(p, &v)| {
                let [lo, hi] = p.bounds;
                let u = if hi > lo { (v - lo) / (hi - lo) } else { 0.5 };
                (1.0 - 2.0 * u.clamp(0.0, 1.0)).acos() / std::f64::consts::PI
            })
            .collect()
    }

    /// Calibrates: CMA-ES from the starting values under `settings`, `progress` told the
    /// evaluations so far and the best cost after each generation; a `Break` from it stops the
    /// calibration after that generation ([`CalibrateError::Stopped`], carrying the best found so
    /// far, re-driven).
    pub fn calibrate(
        &self,
        settings: &Settings,
        mut progress: impl FnMut(usize, f64) -> ControlFlow<()>,
    ) -> Result<Outcome, CalibrateError> {
        let start = self.start();
        let start_cost = self.cost(&start);
        let searched_start: Vec<f64> = self.searched.iter().map(|&k| start[k]).collect();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(settings.threads.max(1))
            .build()
            .map_err(|e| CalibrateError::Threads(e.to_string()))?;
        let objective = |z: &DVector<f64>| self.evaluate(&self.values_of(z.as_slice())).0;
        let budget = settings.max_evaluations;
        let mut options = CMAESOptions::new(self.point_of(&searched_start), settings.initial_step)
            .seed(settings.seed)
            .max_function_evals(budget);
        // Never more evaluations than asked: a budget below CMA-ES's population (Hansen 2016,
        // λ = 4 + ⌊3 ln n⌋) makes the one generation that small, and the search ends before a
        // generation that would not fit.
        if budget < options.population_size {
            options = options.population_size(budget.max(MIN_EVALUATIONS));
        }
        let lambda = options.population_size;
        let mut cmaes = options
            .build(objective)
            .map_err(|e| CalibrateError::Options(format!("{e:?}")))?;
        let mut history = Vec::new();
        let (mut best_z, mut best) = (self.point_of(&searched_start), FAILED_COST);
        let mut stopped = false;
        loop {
            let done = pool.install(|| cmaes.next_parallel());
            if let Some(b) = cmaes.overall_best_individual() {
                if b.value < best {
                    best = b.value;
                    best_z = b.point.as_slice().to_vec();
                }
            }
            history.push((cmaes.function_evals(), best));
            if progress(cmaes.function_evals(), best).is_break() {
                stopped = true;
                break;
            }
            if done.is_some() || cmaes.function_evals() + lambda > budget {
                break;
            }
        }
        let (_, values) = self.evaluate(&self.values_of(&best_z));
        let cost = self.cost(&values);
        let (values, cost) = if cost <= start_cost {
            (values, cost)
        } else {
            (start, start_cost)
        };
        if cost >= FAILED_COST {
            return Err(self.why_nothing_drives(&values));
        }
        let outcome = Outcome {
            values,
            cost,
            start_cost,
            evaluations: cmaes.function_evals(),
            history,
            stopped,
        };
        if stopped {
            return Err(CalibrateError::Stopped {
                evaluations: outcome.evaluations,
                of: settings.max_evaluations,
                best: Box::new(outcome),
            });
        }
        Ok(outcome)
    }
}

impl Problem {
    /// Why neither the start nor any candidate could be driven through every trial: the
    /// reason the first trial that refuses `values` gives (it names the trial).
    fn why_nothing_drives(&self, values: &[f64]) -> CalibrateError {
        let params = self.params_at(values);
        for trial in &self.trials {
            if let Err(e) = trial.run(&params, self.model, self.stepping) {
                return CalibrateError::NothingDrives(e.to_string());
            }
        }
        CalibrateError::NothingDrives(format!(
            "the moments' mean 1 - R2 is at least {FAILED_COST} or not finite"
        ))
    }
}

/// Why a calibration cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibrateError {
    /// The thread pool cannot be built.
    #[error("cannot start the calibration's threads: {0}")]
    Threads(String),
    /// CMA-ES refuses its options.
    #[error("the optimiser refuses its options: {0}")]
    Options(String),
    /// Neither the start nor any candidate could be driven through the trials: nothing to
    /// calibrate from (lengths beyond the fibres' reach, say).
    #[error("no parameters tried could drive the trials: {0}")]
    NothingDrives(String),
    /// The progress callback asked to stop.
    #[error("calibration stopped after {evaluations} of {of} evaluations")]
    Stopped {
        /// Evaluations made.
        evaluations: usize,
        /// Evaluations it would have made at most.
        of: usize,
        /// The best found so far, re-driven (the start's if nothing beat it), marked stopped.
        best: Box<Outcome>,
    },
}
