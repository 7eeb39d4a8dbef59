//! Calibration of a subject's units against measured joint moments (docs/emg.md
//! "Calibration"): a few bounded, physiological parameters chosen so that the units, driven
//! through some trials, reproduce the trials' inverse-dynamics moments.
//!
//! The parameters (each within its bounds, [`Bounds`], defaults after CEINMS's test
//! configuration and Lloyd & Besier 2003):
//! - Lloyd & Besier's C1 and C2, the shape factor A and the electromechanical delay, shared by
//!   every unit;
//! - with the Hill model, `max_velocity`: every unit's `v_max` in optimal lengths per second,
//!   between Lloyd & Besier's 10 and the effective 500 of CEINMS's toolbox code (its fibre
//!   velocity enters the force–velocity curve as `0.002 v / l_opt`), shared by every unit;
//! - per group of units, a strength (a multiplier of each unit's maximum isometric force), a
//!   slack fibre length λ̄ (each unit's tendon slack length set so that its fibre is λ̄ optimal
//!   lengths long at the unit's mean length over the trials with the tendon at slack) and a
//!   multiplier of its optimal fibre length. A group is the units the excitation map drives
//!   from the same EMG channels: their excitations are one signal, so nothing in the data tells
//!   their strengths apart but their moment arms.
//!
//! A changed optimal fibre length keeps CEINMS's maximum velocity of ten optimal lengths per
//! second and the damping's share of the force, so `v_max` scales with it and `b_m` with
//! strength over it.
//!
//! The objective is the mean over trials and degrees of freedom of `Σ(m − p)² / Σ(m − m̄)²`
//! (one minus the coefficient of determination R², the rating the calibration is judged by); a
//! candidate whose drive fails costs `FAILED_COST`.
//!
//! The strengths are solved, not searched (`strengths`): for each candidate of the other
//! parameters, the units are driven at strength 1 and the groups' strengths that minimise the
//! objective within their bounds follow by bounded linear least squares, since a unit's forces
//! scale with its strength. The search (`calibrate/search.rs`) moves the other parameters only.
//!
//! The optimiser is CMA-ES (Hansen 2016, arXiv:1604.00772; the `cmaes` crate): derivative-free,
//! invariant to the parameters' scales, robust to the objective's steps (the delay is a whole
//! number of ticks), and it evaluates a generation's candidates independently, on every core
//! (rayon), deterministically for a seed. It searches an unbounded space mapped into the bounds
//! by `lo + (hi − lo)(1 − cos πz)/2`, which keeps every candidate inside them without clipping.

use crate::measured::{Excitation, ExcitationMap};
pub use crate::subject::bounds::Bounds;
use crate::subject::drive::{DriveError, PreparedTrial};
use crate::subject::units::SubjectModel;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{MuscleParams, Stepping};
use strengths::{best_strengths, Term};

mod result;
mod search;
pub(crate) mod strengths;

pub use search::{CalibrateError, Outcome, Settings, MAX_EVALUATIONS, MIN_EVALUATIONS};

/// The cost of a candidate whose drive fails: above any mean of `1 − R²` a usable candidate
/// gives on real data.
pub(crate) const FAILED_COST: f64 = 1e3;

/// What a calibrated parameter sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// C1 of every unit.
    C1,
    /// C2 of every unit.
    C2,
    /// The shape factor of every unit.
    ShapeFactor,
    /// The delay of every unit, s.
    EmDelay,
    /// A group's strength.
    Strength,
    /// A group's slack fibre length λ̄: each unit's tendon slack length is the one that leaves
    /// its fibre at λ̄ optimal lengths when the unit is at its mean length over the trials and
    /// the tendon at slack.
    SlackFibreLength,
    /// A group's optimal fibre length multiplier.
    OptimalFibreLength,
    /// The Hill force–velocity curve's reach, optimal lengths per second: every unit's `v_max`
    /// is this many of its optimal lengths per second (Hill model only).
    MaxVelocity,
}

/// One calibrated parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Its name: `c1`, `c2`, `shape_factor`, `em_delay`, or `<quantity>.<group>`.
    pub name: String,
    /// What it sets.
    pub quantity: Quantity,
    /// The units it sets (indices into [`Problem::units`]).
    pub units: Vec<usize>,
    /// Its bounds.
    pub bounds: [f64; 2],
    /// Its starting value (the subject's, or 1 for a multiplier, inside the bounds).
    pub start: f64,
}

/// A calibration problem: trials prepared for the subject's units, the parameters.
#[derive(Debug, Clone)]
pub struct Problem {
    /// The trials.
    pub trials: Vec<PreparedTrial>,
    /// The units driven, in the subject's order.
    pub units: Vec<String>,
    /// The units' parameters before calibration.
    pub base: Vec<MuscleParams>,
    /// Each unit's mean length over the trials' ticks, m.
    pub mean_length: Vec<f64>,
    /// The calibrated parameters.
    pub parameters: Vec<Parameter>,
    /// The indices in `parameters` of those the search moves (all but the strengths).
    pub searched: Vec<usize>,
    /// The indices in `parameters` of the groups' strengths.
    pub strengths: Vec<usize>,
    /// The contractile model.
    pub model: ModelKind,
    /// Its stepping.
    pub stepping: Stepping,
}

impl Problem {
    /// The problem of calibrating `subject`'s units on `trials` (prepared for the same degrees
    /// of freedom) under `model`, the groups from `map`.
    pub fn new(
        subject: &SubjectModel,
        map: &ExcitationMap,
        trials: Vec<PreparedTrial>,
        model: ModelKind,
        stepping: Stepping,
    ) -> Result<Problem, DriveError> {
        let bounds = &subject.bounds;
        let units = trials.first().ok_or(DriveError::NoDof)?.units.clone();
        let base = subject.params_of(&units)?;
        let mean_length: Vec<f64> = (0..units.len())
            .map(|i| trials.iter().map(|t| t.mean_length(i)).sum::<f64>() / trials.len() as f64)
            .collect();
        let first = &base[0];
        let inside = |v: f64, b: [f64; 2]| v.clamp(b[0], b[1]);
        let all: Vec<usize> = (0..units.len()).collect();
        let global = |name: &str, quantity, b: [f64; 2], v: Option<f64>| Parameter {
            name: name.into(),
            quantity,
            units: all.clone(),
            bounds: b,
            start: inside(v.unwrap_or(0.5 * (b[0] + b[1])), b),
        };
        let mut parameters = vec![
            global("c1", Quantity::C1, bounds.c1, first.c1),
            global("c2", Quantity::C2, bounds.c2, first.c2),
            global(
                "shape_factor",
                Quantity::ShapeFactor,
                bounds.shape_factor,
                first.shape_factor,
            ),
            global(
                "em_delay",
                Quantity::EmDelay,
                bounds.em_delay,
                first.em_delay,
            ),
        ];
        if model == ModelKind::HILL {
            let start = first.v_max / first.l_opt;
            parameters.push(global(
                "max_velocity",
                Quantity::MaxVelocity,
                bounds.max_velocity,
                Some(start),
            ));
        }
        for (group, members) in groups(map, &units) {
            parameters.push(Parameter {
                name: format!("strength.{group}"),
                quantity: Quantity::Strength,
                units: members.clone(),
                bounds: bounds.strength,
                start: inside(1.0, bounds.strength),
            });
        }
        for (group, members) in groups(map, &units) {
            for (quantity, prefix, b) in [
                (
                    Quantity::SlackFibreLength,
                    "slack_fibre_length",
                    bounds.slack_fibre_length,
                ),
                (
                    Quantity::OptimalFibreLength,
                    "optimal_fibre_length",
                    bounds.optimal_fibre_length,
                ),
            ] {
                let start = match quantity {
                    Quantity::SlackFibreLength => {
                        members
                            .iter()
                            .map(|&i| slack_fibre_length(&base[i], mean_length[i]))
                            .sum::<f64>()
                            / members.len() as f64
                    }
                    _ => 1.0,
                };
                parameters.push(Parameter {
                    name: format!("{prefix}.{group}"),
                    quantity,
                    units: members.clone(),
                    bounds: b,
                    start: inside(start, b),
                });
            }
        }
        let (strengths, searched): (Vec<usize>, Vec<usize>) =
            (0..parameters.len()).partition(|&k| parameters[k].quantity == Quantity::Strength);
        Ok(Problem {
            trials,
            units,
            base,
            mean_length,
            parameters,
            searched,
            strengths,
            model,
            stepping,
        })
    }

    /// The starting values.
    pub fn start(&self) -> Vec<f64> {
        self.parameters.iter().map(|p| p.start).collect()
    }

    /// The units' parameters at `values` (one per parameter).
    pub fn params_at(&self, values: &[f64]) -> Vec<MuscleParams> {
        let mut out = self.base.clone();
        for (p, &v) in self.parameters.iter().zip(values) {
            for &i in &p.units {
                let m = &mut out[i];
                match p.quantity {
                    Quantity::C1 => m.c1 = Some(v),
                    Quantity::C2 => m.c2 = Some(v),
                    Quantity::ShapeFactor => m.shape_factor = Some(v),
                    Quantity::EmDelay => m.em_delay = Some(v),
                    Quantity::Strength => {
                        m.f_max *= v;
                        m.b_m *= v;
                    }
                    Quantity::SlackFibreLength | Quantity::MaxVelocity => {}
                    Quantity::OptimalFibreLength => {
                        m.l_opt *= v;
                        m.v_max *= v;
                        m.b_m /= v;
                    }
                }
            }
        }
        // The tendon slack lengths and maximum velocities last: they follow the optimal fibre
        // lengths.
        for (p, &v) in self.parameters.iter().zip(values) {
            for &i in &p.units {
                let m = &mut out[i];
                match p.quantity {
                    Quantity::SlackFibreLength => {
                        m.l_ts = self.mean_length[i] - fibre_along_tendon(m, v);
                    }
                    Quantity::MaxVelocity => {
                        // The damping keeps its share of force at a given v / v_max.
                        let v_max = v * m.l_opt;
                        m.b_m *= m.v_max / v_max;
                        m.v_max = v_max;
                    }
                    _ => {}
                }
            }
        }
        out
    }

    /// The objective at `values`: the mean over trials and degrees of freedom of `1 − R²`.
    pub(crate) fn cost(&self, values: &[f64]) -> f64 {
        let params = self.params_at(values);
        let mut sum = 0.0;
        let mut count = 0usize;
        for trial in &self.trials {
            let Ok(p) = trial.run(&params, self.model, self.stepping) else {
                return FAILED_COST;
            };
            for (m, q) in p.measured.iter().zip(&p.moment) {
                let mean = m.iter().sum::<f64>() / m.len() as f64;
                let sst: f64 = m.iter().map(|x| (x - mean).powi(2)).sum();
                let sse: f64 = m.iter().zip(q).map(|(x, y)| (x - y).powi(2)).sum();
                sum += sse / sst.max(f64::MIN_POSITIVE);
                count += 1;
            }
        }
        let c = sum / count.max(1) as f64;
        if c.is_finite() {
            c.min(FAILED_COST)
        } else {
            FAILED_COST
        }
    }

    /// The objective at the searched parameters' `values` (one per [`Problem::searched`]) with
    /// the best strengths ([`strengths`]), and every parameter's value.
    pub(crate) fn evaluate(&self, values: &[f64]) -> (f64, Vec<f64>) {
        let mut full = self.start();
        for (&k, &v) in self.searched.iter().zip(values) {
            full[k] = v;
        }
        for &k in &self.strengths {
            full[k] = 1.0;
        }
        let params = self.params_at(&full);
        let mut terms = Vec::new();
        for trial in &self.trials {
            let Ok(p) = trial.run(&params, self.model, self.stepping) else {
                return (FAILED_COST, full);
            };
            for (d, m) in p.measured.iter().enumerate() {
                let mean = m.iter().sum::<f64>() / m.len() as f64;
                let sst: f64 = m.iter().map(|x| (x - mean).powi(2)).sum();
                let mut columns = vec![vec![0.0; m.len()]; self.strengths.len()];
                for (unit, arm) in trial.arms(d) {
                    let Some(g) = self
                        .strengths
                        .iter()
                        .position(|&k| self.parameters[k].units.contains(unit))
                    else {
                        continue;
                    };
                    for (c, (f, r)) in columns[g].iter_mut().zip(p.force[*unit].iter().zip(arm)) {
                        *c += f * r;
                    }
                }
                terms.push(Term {
                    weight: 1.0 / sst.max(f64::MIN_POSITIVE),
                    measured: m.clone(),
                    columns,
                });
            }
        }
        let start: Vec<f64> = self
            .strengths
            .iter()
            .map(|&k| self.parameters[k].start)
            .collect();
        let bounds = self
            .strengths
            .first()
            .map_or([1.0, 1.0], |&k| self.parameters[k].bounds);
        let (s, cost) = best_strengths(&terms, bounds, &start);
        for (&k, v) in self.strengths.iter().zip(s) {
            full[k] = v;
        }
        (
            if cost.is_finite() {
                cost.min(FAILED_COST)
            } else {
                FAILED_COST
            },
            full,
        )
    }
}

/// The length along the tendon of a fibre `lambda` optimal lengths long, m (constant
/// thickness, docs/model.md §5b).
fn fibre_along_tendon(m: &MuscleParams, lambda: f64) -> f64 {
    let thickness = m.l_opt * m.pennation.sin();
    ((lambda * m.l_opt).powi(2) - thickness * thickness)
        .max(0.0)
        .sqrt()
}

/// The slack fibre length λ̄ that `m`'s tendon slack length leaves at the unit length
/// `mean_length` (0 when the tendon alone is longer).
fn slack_fibre_length(m: &MuscleParams, mean_length: f64) -> f64 {
    let along = mean_length - m.l_ts;
    if along <= 0.0 {
        return 0.0;
    }
    let thickness = m.l_opt * m.pennation.sin();
    (along * along + thickness * thickness).sqrt() / m.l_opt
}

/// The units' groups: units the map drives from the same channels, named after the first unit
/// of each; indices into `units`.
fn groups(map: &ExcitationMap, units: &[String]) -> Vec<(String, Vec<usize>)> {
    let mut out: Vec<(Vec<String>, String, Vec<usize>)> = Vec::new();
    for (i, u) in units.iter().enumerate() {
        let mut source: Vec<String> = map
            .unit(u)
            .map(Excitation::channels)
            .unwrap_or_default()
            .to_vec();
        source.sort();
        match out
            .iter_mut()
            .find(|(s, _, _)| *s == source && !source.is_empty())
        {
            Some((_, _, members)) => members.push(i),
            None => out.push((source, u.clone(), vec![i])),
        }
    }
    out.into_iter()
        .map(|(_, name, members)| (name, members))
        .collect()
}
