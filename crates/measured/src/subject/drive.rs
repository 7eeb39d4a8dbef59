//! A subject's units stepped through a measured trial (docs/emg.md "Prediction"): each unit
//! along its measured muscle–tendon length under its EMG-driven excitation, with its own fibre
//! and tendon dynamics; the joint moments `M_j = Σ_i F_i r_ij` from the trial's moment arms.
//!
//! The time base:
//! - one tick per EMG sample (the EMG's own rate, 2 kHz in the CEINMS trials), tick 0 at the
//!   first EMG sample, so that Lloyd & Besier's C1 and C2 act per EMG sample as in CEINMS;
//! - the excitation of tick k is the map's excitation of EMG row k, clamped to at most 1
//!   (envelopes normalised to a maximum voluntary contraction may pass it; the clamped samples
//!   are counted in [`PreparedTrial::clamped_excitations`]); a negative one is refused;
//! - the unit's length at each tick's start is the trial's `lmt` interpolated linearly, and
//!   over the tick it moves at the slope to the next tick's (a piecewise-linear l_mt(t)); before
//!   the first kinematic sample (the EMG's lead, 130 ms in the CEINMS trials) the unit is held
//!   at its first length while its activation settles;
//! - the ticks run to the last kinematic sample; forces, activations and fibre lengths are
//!   read at the kinematic samples' times (linearly between the ticks' ends around them).

pub use super::error::DriveError;
use super::limits::{HELD_REACH_FRACTION, MAX_FIBRE_LOPT};
use muscle_actuator_core::config::{ActuatorConfig, ConfigError, MuscleConfig, SpanConfig};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{
    Inputs, JointParams, MomentArm, MuscleParams, Plant, Stepping,
};
use muscle_actuator_core::sim::Simulation;
use muscle_actuator_core::text::excerpt;

/// A unit's length coordinate is the joint named after it with this suffix.
pub(crate) const LENGTH_SUFFIX: &str = ".length";
/// A length coordinate's range, m: a unit's length within this of `l_opt + l_ts`.
pub(crate) const MAX_STRETCH_M: f64 = 1.0;

/// A trial's inputs, per tick, for the units of the asked degrees of freedom.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedTrial {
    /// The trial's name.
    pub name: String,
    /// The tick rate, Hz (the EMG's).
    pub rate_hz: f64,
    /// Time of tick 0's start, s (the first EMG sample).
    pub start_s: f64,
    /// The units driven (those spanning the degrees of freedom), in the subject's order.
    pub units: Vec<String>,
    /// Per unit, its excitation per tick, [0, 1].
    pub(super) excitation: Vec<Vec<f64>>,
    /// Per unit, its length at each tick's start and at the last tick's end, m.
    pub(super) length: Vec<Vec<f64>>,
    /// Excitation samples above 1 that were clamped to 1.
    pub clamped_excitations: usize,
    /// The kinematic samples' times, s: where the outputs are read.
    pub times: Vec<f64>,
    /// The degrees of freedom.
    pub dofs: Vec<String>,
    /// Per degree of freedom, its units (indices into `units`) and each one's moment arm, m,
    /// at every kinematic sample.
    pub(super) arms: Vec<Vec<(usize, Vec<f64>)>>,
    /// Per degree of freedom, its inverse-dynamics moment at every kinematic sample, N m.
    pub measured: Vec<Vec<f64>>,
    /// Per degree of freedom, the units of its moment-arm file with a moment arm (not zero
    /// throughout) that the subject does not give it: left out of its moment, for the caller to
    /// say.
    pub unused_arms: Vec<(String, Vec<String>)>,
}

/// Lengths a prediction held at their unit's reach ([`PreparedTrial::hold_within_reach`]).
#[derive(Debug, Clone, PartialEq)]
pub struct HeldLengths {
    /// Length samples held (one per tick and unit).
    pub samples: usize,
    /// The first unit held.
    pub unit: String,
    /// When it was first held, s.
    pub time_s: f64,
    /// The longest `(l_mt − l_ts) / l_opt` asked of a held unit.
    pub fibre_lopt: f64,
}

impl std::fmt::Display for HeldLengths {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} length samples beyond their fibre's reach ({MAX_FIBRE_LOPT} optimal lengths with the tendon at slack, asked up to {:.3}) were held at it, the first of unit {:?} at {} s",
            self.samples, self.fibre_lopt, self.unit, self.time_s
        )
    }
}

/// The longest unit length a fibre of `p` reaches with its tendon at slack, m.
fn reach(p: &MuscleParams) -> f64 {
    p.l_ts + MAX_FIBRE_LOPT * p.l_opt
}

/// What a drive gives at the kinematic samples' times.
#[derive(Debug, Clone, PartialEq)]
pub struct Prediction {
    /// The times, s.
    pub times: Vec<f64>,
    /// The units, as in the prepared trial.
    pub units: Vec<String>,
    /// Per unit, its tendon force, N.
    pub force: Vec<Vec<f64>>,
    /// Per unit, its activation.
    pub activation: Vec<Vec<f64>>,
    /// Per unit, its fibre length, m.
    pub fibre_length: Vec<Vec<f64>>,
    /// The degrees of freedom.
    pub dofs: Vec<String>,
    /// Per degree of freedom, the predicted moment `Σ F r`, N m.
    pub moment: Vec<Vec<f64>>,
    /// Per degree of freedom, the measured moment, N m.
    pub measured: Vec<Vec<f64>>,
}

impl PreparedTrial {
    /// The moment arms of degree of freedom `dof` (an index into [`Self::dofs`]): per unit that
    /// spans it, its index into [`Self::units`] and its arm at every kinematic sample, m.
    pub(crate) fn arms(&self, dof: usize) -> &[(usize, Vec<f64>)] {
        self.arms.get(dof).map_or(&[], Vec::as_slice)
    }

    /// Every unit's every length within its fibre's reach ([`DriveError::OutOfReach`]).
    fn check_reach(&self, params: &[MuscleParams]) -> Result<(), DriveError> {
        self.beyond_reach(params, 0.0).map(|_| ())
    }

    /// Holds at the reach of its fibre every length of a unit that passes it by at most
    /// `HELD_REACH_FRACTION` of the unit's resting length, for a prediction (docs/emg.md
    /// "Prediction"); a length further beyond is refused ([`DriveError::OutOfReach`]) and
    /// nothing is changed. The samples held, if any.
    pub fn hold_within_reach(
        &mut self,
        params: &[MuscleParams],
    ) -> Result<Option<HeldLengths>, DriveError> {
        let held = self.beyond_reach(params, HELD_REACH_FRACTION)?;
        for (lengths, p) in self.length.iter_mut().zip(params) {
            let reach = reach(p);
            for l in lengths.iter_mut() {
                *l = l.min(reach);
            }
        }
        Ok(held)
    }

    /// The lengths beyond their unit's reach, refused if any passes it by more than `margin`
    /// of the unit's resting length.
    fn beyond_reach(
        &self,
        params: &[MuscleParams],
        margin: f64,
    ) -> Result<Option<HeldLengths>, DriveError> {
        if params.len() != self.units.len() {
            return Err(DriveError::Plant(format!(
                "{} parameter sets for {} units",
                params.len(),
                self.units.len()
            )));
        }
        let mut held: Option<HeldLengths> = None;
        for (i, p) in params.iter().enumerate() {
            let reach = reach(p);
            let limit = reach + margin * (p.l_opt + p.l_ts);
            for (k, &length_m) in self.length[i].iter().enumerate() {
                if length_m <= reach {
                    continue;
                }
                let time_s = self.start_s + k as f64 / self.rate_hz;
                if length_m > limit {
                    return Err(DriveError::OutOfReach {
                        trial: self.name.clone(),
                        unit: excerpt(&self.units[i]),
                        time_s,
                        length_m,
                        fibre_lopt: (length_m - p.l_ts) / p.l_opt,
                    });
                }
                let h = held.get_or_insert_with(|| HeldLengths {
                    samples: 0,
                    unit: excerpt(&self.units[i]),
                    time_s,
                    fibre_lopt: 0.0,
                });
                h.samples += 1;
                h.fibre_lopt = h.fibre_lopt.max((length_m - p.l_ts) / p.l_opt);
            }
        }
        Ok(held)
    }

    /// The first unit that, driven alone, fails by tick `tick` (the diagnosis of a failed drive).
    fn failing_unit(
        &self,
        params: &[MuscleParams],
        model: ModelKind,
        stepping: Stepping,
        tick: usize,
    ) -> Option<usize> {
        if self.units.len() == 1 {
            return Some(0);
        }
        (0..self.units.len()).find(|&i| {
            let mut alone = self.only(i);
            for l in &mut alone.length {
                l.truncate(tick + 2);
            }
            for e in &mut alone.excitation {
                e.truncate(tick + 1);
            }
            alone
                .times
                .retain(|&t| t <= self.start_s + (tick + 1) as f64 / self.rate_hz);
            alone.times.truncate(alone.times.len().max(1));
            alone.run(&params[i..=i], model, stepping).is_err()
        })
    }

    /// This trial for unit `i` alone (no degree of freedom).
    fn only(&self, i: usize) -> PreparedTrial {
        PreparedTrial {
            name: self.name.clone(),
            rate_hz: self.rate_hz,
            start_s: self.start_s,
            units: vec![self.units[i].clone()],
            excitation: vec![self.excitation[i].clone()],
            length: vec![self.length[i].clone()],
            clamped_excitations: 0,
            times: self.times.clone(),
            dofs: Vec::new(),
            arms: Vec::new(),
            measured: Vec::new(),
            unused_arms: Vec::new(),
        }
    }

    /// The mean length of unit `i` (an index into [`Self::units`]) over the ticks, m.
    pub(crate) fn mean_length(&self, i: usize) -> f64 {
        let l = &self.length[i];
        l.iter().sum::<f64>() / l.len().max(1) as f64
    }

    /// The number of ticks.
    pub fn ticks(&self) -> usize {
        self.excitation.first().map_or(0, Vec::len)
    }

    /// The units with `params` (one per unit, in order) as a configuration: each unit on a
    /// driven length coordinate of its own, the joint `<unit>.length`, whose angle is the unit's
    /// length beyond `l_opt + l_ts` (its path length at 0), m, spanned with a moment arm of
    /// −1 m (so that `L = l_opt + l_ts + θ`, docs/model.md §8b, §8c).
    pub fn config(&self, params: &[MuscleParams]) -> ActuatorConfig {
        let mut cfg = ActuatorConfig {
            joints: Vec::with_capacity(params.len()),
            muscles: Vec::with_capacity(params.len()),
            stepper: Default::default(),
        };
        for ((u, p), l) in self.units.iter().zip(params).zip(&self.length) {
            let joint = format!("{u}{LENGTH_SUFFIX}");
            let nominal = p.l_opt + p.l_ts;
            // Every field named: a new one must be decided here. A driven joint's inertia,
            // damping and limit law are never used; they keep the defaults.
            let d = JointParams::default();
            cfg.joints.push(JointParams {
                name: joint.clone(),
                driven: true,
                initial_angle: l[0] - nominal,
                min_angle: -MAX_STRETCH_M,
                max_angle: MAX_STRETCH_M,
                inertia: d.inertia,
                damping: d.damping,
                limit_stiffness: d.limit_stiffness,
                limit_damping: d.limit_damping,
            });
            cfg.muscles.push(MuscleConfig {
                name: u.clone(),
                params: p.clone(),
                path_length: Some(nominal),
                spans: vec![SpanConfig {
                    joint,
                    moment_arm: MomentArm::Constant(-1.0),
                    changes_sign: false,
                }],
            });
        }
        cfg
    }

    /// The units with `params` (one per unit, in order) under `model`, stepped through the
    /// trial (the module's time base).
    pub fn run(
        &self,
        params: &[MuscleParams],
        model: ModelKind,
        stepping: Stepping,
    ) -> Result<Prediction, DriveError> {
        self.run_observed(params, model, stepping, |_, _| {})
    }

    /// As [`Self::run`], `observe` shown the simulation at rest (with the inputs it was set up
    /// with) and after every tick (with the inputs the tick applied: the simulation's own have
    /// moved on, each driven angle to where the tick's motion ended).
    pub fn run_observed(
        &self,
        params: &[MuscleParams],
        model: ModelKind,
        stepping: Stepping,
        mut observe: impl FnMut(&Simulation, &Inputs),
    ) -> Result<Prediction, DriveError> {
        let n = self.units.len();
        if params.len() != n {
            return Err(DriveError::Plant(format!(
                "{} parameter sets for {n} units",
                params.len()
            )));
        }
        self.check_reach(params)?;
        let cfg = self.config(params);
        match cfg.validate() {
            Err(ConfigError::Invalid(errors)) => return Err(DriveError::Params(errors)),
            Err(other) => return Err(DriveError::Plant(other.to_string())),
            Ok(()) => {}
        }
        let nominal: Vec<f64> = params.iter().map(|p| p.l_opt + p.l_ts).collect();
        let plant = Plant::new(&cfg.topology(), model)?;
        let mut inputs = Inputs::zeros(n, n);
        for (j, l) in self.length.iter().enumerate() {
            inputs.joint_angle[j] = l[0] - nominal[j];
        }
        let mut sim = Simulation::new(plant, self.rate_hz, stepping, inputs)?;
        let ticks = self.ticks();
        let mut force = vec![Vec::with_capacity(ticks + 1); n];
        let mut activation = vec![Vec::with_capacity(ticks + 1); n];
        let mut fibre = vec![Vec::with_capacity(ticks + 1); n];
        let record = |sim: &Simulation,
                      force: &mut [Vec<f64>],
                      act: &mut [Vec<f64>],
                      fib: &mut [Vec<f64>]| {
            let (plant, y, a, inp) = (sim.plant(), sim.state(), sim.activations(), sim.inputs());
            for i in 0..n {
                force[i].push(plant.tendon_force(y, i, a[i], inp));
                act[i].push(a[i]);
                fib[i].push(plant.fibre_length(y, i, inp));
            }
        };
        record(&sim, &mut force, &mut activation, &mut fibre);
        let mut applied = sim.inputs().clone();
        observe(&sim, &applied);
        for k in 0..ticks {
            let inputs = sim.inputs_mut();
            for (i, l) in self.length.iter().enumerate() {
                inputs.excitation[i] = self.excitation[i][k];
                inputs.joint_angle[i] = l[k] - nominal[i];
                inputs.joint_velocity[i] = (l[k + 1] - l[k]) * self.rate_hz;
            }
            applied.clone_from(sim.inputs());
            if let Err(error) = sim.step() {
                let unit = self.failing_unit(params, model, stepping, k);
                return Err(DriveError::Step {
                    trial: self.name.clone(),
                    unit: unit.map(|i| excerpt(&self.units[i])),
                    time_s: self.start_s + k as f64 / self.rate_hz,
                    length_m: unit.map_or(f64::NAN, |i| self.length[i][k]),
                    error,
                });
            }
            record(&sim, &mut force, &mut activation, &mut fibre);
            observe(&sim, &applied);
        }
        let at: Vec<f64> = self
            .times
            .iter()
            .map(|t| (t - self.start_s) * self.rate_hz)
            .collect();
        let sample = |series: &[f64]| at.iter().map(|&x| at_index(series, x)).collect::<Vec<_>>();
        let force: Vec<Vec<f64>> = force.iter().map(|f| sample(f)).collect();
        let moment = self
            .arms
            .iter()
            .map(|of_dof| {
                (0..self.times.len())
                    .map(|s| of_dof.iter().map(|(i, r)| force[*i][s] * r[s]).sum())
                    .collect()
            })
            .collect();
        Ok(Prediction {
            times: self.times.clone(),
            units: self.units.clone(),
            activation: activation.iter().map(|a| sample(a)).collect(),
            fibre_length: fibre.iter().map(|l| sample(l)).collect(),
            force,
            dofs: self.dofs.clone(),
            moment,
            measured: self.measured.clone(),
        })
    }
}

/// `series[x]` for a fractional index x within it, linearly between its neighbours.
fn at_index(series: &[f64], x: f64) -> f64 {
    let last = series.len().saturating_sub(1);
    let k = (x.floor().max(0.0) as usize).min(last);
    let next = (k + 1).min(last);
    let w = (x - k as f64).clamp(0.0, 1.0);
    series[k] + w * (series[next] - series[k])
}
