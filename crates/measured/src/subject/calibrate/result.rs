//! A calibrated subject: the problem's units set to the result, and the record of how.

use super::search::{Outcome, Settings};
use super::Problem;
use crate::subject::calibration_record::CalibrationRecord;
use crate::subject::units::SubjectModel;

impl Problem {
    /// `subject` with the units of this problem set to `outcome`'s values, and the record of
    /// how: the trials, degrees of freedom, model, optimiser, seed, costs and history. C1 and C2
    /// are stated at the trials' EMG rate (`neural_rate_hz`), the rate they were fitted at.
    pub fn calibrated(
        &self,
        subject: &SubjectModel,
        outcome: &Outcome,
        settings: &Settings,
    ) -> SubjectModel {
        let mut out = subject.clone();
        let params = self.params_at(&outcome.values);
        let rate = self.trials.first().map(|t| t.rate_hz);
        for (name, mut p) in self.units.iter().zip(params) {
            p.neural_rate_hz = rate;
            if let Some(u) = out.units.iter_mut().find(|u| &u.name == name) {
                u.params = p;
            }
        }
        out.calibration = Some(CalibrationRecord {
            trials: self.trials.iter().map(|t| t.name.clone()).collect(),
            dofs: self
                .trials
                .first()
                .map(|t| t.dofs.clone())
                .unwrap_or_default(),
            model: self.model.name().to_string(),
            optimiser: OPTIMISER.to_string(),
            seed: settings.seed,
            evaluations: outcome.evaluations,
            start_cost: outcome.start_cost,
            cost: outcome.cost,
            parameters: self
                .parameters
                .iter()
                .zip(&outcome.values)
                .map(|(p, &v)| (p.name.clone(), toml::Value::Float(v)))
                .collect(),
            history: outcome
                .history
                .iter()
                .map(|&(e, c)| [e as f64, c])
                .collect(),
            stopped: outcome.stopped,
        });
        out
    }
}

/// The optimiser, as a calibrated subject records it.
pub(crate) const OPTIMISER: &str = "CMA-ES (the cmaes crate, 0.2)";
