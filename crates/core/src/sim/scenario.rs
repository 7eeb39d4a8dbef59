//! Scenarios: an attachment, a duration and input schedules; the built-in ones reproduce the
//! paper's experiments (docs/model.md §9), others come from scenario files (TOML, see
//! `scenarios/example.toml`).

use crate::config::ActuatorConfig;
use crate::physics::limb_params::MuscleParams;
use crate::physics::models::ModelKind;
use crate::physics::plant::{Inputs, Plant};
use crate::physics::stepping::Stepping;
use crate::physics::topology::Topology;
use crate::sim::schedule::Schedule;
use crate::sim::setup_error::SetupError;
use crate::sim::simulation::{Simulation, StepError};
use crate::sim::snapshot::StateSnapshot;
use serde::Deserialize;
use std::path::Path;

use crate::sim::records::{Record, RecordMismatch, Run};
use crate::sim::scenario_error::{BadScenario, ScenarioError, ScenarioRunError};
use crate::sim::scenario_kinds::{SetupKind, Signal};

/// The built-in scenarios' names.
pub(crate) const BUILT_IN: [&str; 3] = ["pulse", "energy-10hz", "energy-100hz"];

/// Most memory the records of a run may take, bytes (1 GiB): a run keeps one record per tick
/// (for the CSV and the summary), so duration × rate and the limb's size are bounded together.
pub(crate) const MAX_RUN_BYTES: f64 = (1u64 << 30) as f64;

/// Longest scenario name, characters (it names the run in reports and recordings).
pub(crate) const MAX_NAME_CHARS: usize = 200;

/// One scheduled input; schedules on the same input add up.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct ScheduledInput {
    /// The input driven.
    pub signal: Signal,
    /// The muscle, for excitations (default: the first).
    #[serde(default)]
    pub muscle: Option<String>,
    /// The joint, for external torques and joint angles (default: the first).
    #[serde(default)]
    pub joint: Option<String>,
    /// The schedule.
    #[serde(flatten)]
    pub schedule: Schedule,
}

/// A complete scenario.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Name, for reports.
    #[serde(default = "default_name")]
    pub name: String,
    /// Simulated time, s.
    pub duration: f64,
    /// The attachment.
    pub attachment: SetupKind,
    /// Clamped: total MTU length, m (default lopt + l_ts).
    #[serde(default)]
    pub length: Option<f64>,
    /// Force-driven: tendon force of the initial static equilibrium, N.
    #[serde(default)]
    pub initial_force: f64,
    /// The inputs.
    #[serde(default, rename = "input")]
    pub inputs: Vec<ScheduledInput>,
}

fn default_name() -> String {
    "scenario".into()
}

impl Scenario {
    /// A built-in scenario by name (docs/model.md §9).
    pub fn built_in(name: &str, params: &MuscleParams) -> Result<Self, ScenarioError> {
        let excitation = |schedule| ScheduledInput {
            signal: Signal::Excitation,
            muscle: None,
            joint: None,
            schedule,
        };
        let energy = |f: f64| Scenario {
            name: name.into(),
            duration: 0.2,
            attachment: SetupKind::Force,
            length: None,
            initial_force: 150.0,
            inputs: vec![ScheduledInput {
                signal: Signal::TendonForce,
                muscle: None,
                joint: None,
                schedule: Schedule::Sine {
                    offset: 150.0,
                    amplitude: 150.0,
                    frequency: f,
                    phase: 0.0,
                },
            }],
        };
        match name {
            "pulse" => Ok(Scenario {
                name: name.into(),
                duration: 3.0,
                attachment: SetupKind::Clamped,
                length: Some(params.l_opt + params.l_ts),
                initial_force: 0.0,
                inputs: vec![excitation(Schedule::Pulse {
                    start: 1.0,
                    end: 2.0,
                    value: 1.0,
                    base: 0.0,
                })],
            }),
            "energy-10hz" => Ok(energy(10.0)),
            "energy-100hz" => Ok(energy(100.0)),
            _ => Err(ScenarioError::Unknown {
                name: name.into(),
                built_in: &BUILT_IN,
            }),
        }
    }

    /// A scenario from a TOML file (a regular file of at most 1 MiB).
    pub fn from_file(path: &Path) -> Result<Self, ScenarioError> {
        let path_buf = || path.to_path_buf();
        let bytes = crate::files::read_regular_file(path, crate::files::MAX_FILE_BYTES).map_err(
            |source| ScenarioError::Read {
                path: path_buf(),
                source,
            },
        )?;
        let text = String::from_utf8(bytes).map_err(|source| ScenarioError::NotUtf8 {
            path: path_buf(),
            source,
        })?;
        let s: Scenario = toml::from_str(&text).map_err(|e| ScenarioError::Parse {
            path: path_buf(),
            message: crate::text::toml_error(&e, &text),
        })?;
        s.check().map_err(|error| ScenarioError::Invalid {
            path: path_buf(),
            error,
        })?;
        Ok(s)
    }

    /// A built-in name, or else a path to a scenario file.
    pub fn resolve(name_or_path: &str, params: &MuscleParams) -> Result<Self, ScenarioError> {
        if BUILT_IN.contains(&name_or_path) || !Path::new(name_or_path).exists() {
            if !BUILT_IN.contains(&name_or_path) && name_or_path.ends_with(".toml") {
                return Err(ScenarioError::FileMissing {
                    path: name_or_path.into(),
                });
            }
            Self::built_in(name_or_path, params)
        } else {
            Self::from_file(Path::new(name_or_path))
        }
    }

    fn check(&self) -> Result<(), BadScenario> {
        if self.name.chars().count() > MAX_NAME_CHARS {
            return Err(BadScenario::NameTooLong {
                name: self.name.clone(),
                max_chars: MAX_NAME_CHARS,
            });
        }
        if !(self.duration.is_finite() && self.duration > 0.0 && self.duration <= 3600.0) {
            return Err(BadScenario::Duration(self.duration));
        }
        if let Some(l) = self.length {
            if !(l.is_finite() && l > 0.0) {
                return Err(BadScenario::Length(l));
            }
        }
        if !self.initial_force.is_finite() || self.initial_force < 0.0 {
            return Err(BadScenario::InitialForce(self.initial_force));
        }
        for (i, input) in self.inputs.iter().enumerate() {
            input
                .schedule
                .check()
                .map_err(|error| BadScenario::Schedule { index: i, error })?;
            let allowed = match self.attachment {
                SetupKind::Joint => {
                    !matches!(input.signal, Signal::TendonForce | Signal::JointAngle)
                }
                SetupKind::Driven => input.signal != Signal::TendonForce,
                SetupKind::Clamped => input.signal == Signal::Excitation,
                SetupKind::Force => {
                    !matches!(input.signal, Signal::ExternalTorque | Signal::JointAngle)
                }
            };
            if !allowed {
                return Err(BadScenario::SignalNotForAttachment {
                    index: i,
                    signal: input.signal,
                    attachment: self.attachment.clone(),
                });
            }
        }
        Ok(())
    }

    /// Runs the scenario with `model` at `rate_hz` with the given sub-stepping.
    pub fn run(
        &self,
        config: &ActuatorConfig,
        model: ModelKind,
        rate_hz: f64,
        stepping: Stepping,
    ) -> Result<Run, ScenarioRunError> {
        let mut runner = self.runner(config, model, rate_hz, stepping)?;
        let ticks = (self.duration * rate_hz).round() as usize;
        let mut run = runner.empty_run(ticks + 1);
        runner.keep_record(&mut run)?;
        for _ in 0..ticks {
            runner.step()?;
            runner.keep_record(&mut run)?;
        }
        Ok(run)
    }

    /// A tick-by-tick runner of the scenario (for tests and benchmarks).
    pub fn runner(
        &self,
        config: &ActuatorConfig,
        model: ModelKind,
        rate_hz: f64,
        stepping: Stepping,
    ) -> Result<ScenarioRunner, ScenarioRunError> {
        config.validate().map_err(SetupError::from)?;
        let topology = self.topology(config);
        let names = topology.muscle_names();
        let joint_names = topology.joint_names();
        self.check_size(rate_hz, names.len(), joint_names.len())?;
        let mut muscle_index = Vec::with_capacity(self.inputs.len());
        for (i, input) in self.inputs.iter().enumerate() {
            let lookup =
                |want: &Option<String>, names: &[String], what: &'static str| match want {
                    None => Ok(0),
                    Some(m) => names.iter().position(|n| n == m).ok_or_else(|| {
                        ScenarioRunError::UnknownName {
                            index: i,
                            what,
                            name: m.clone(),
                            names: names.to_vec(),
                        }
                    }),
                };
            let idx = match input.signal {
                Signal::ExternalTorque | Signal::JointAngle => {
                    if joint_names.is_empty() {
                        return Err(ScenarioRunError::NoJoint { index: i });
                    }
                    lookup(&input.joint, &joint_names, "joint")?
                }
                _ => lookup(&input.muscle, &names, "muscle")?,
            };
            muscle_index.push(idx);
        }
        self.check_driven(&topology, &muscle_index)?;
        let plant = Plant::new(&topology, model).map_err(SetupError::from)?;
        let mut initial = Inputs::zeros(plant.muscle_count(), plant.joint_count());
        initial.tendon_force.fill(self.initial_force);
        // Driven joints start at rest where their schedules start.
        for (input, &k) in self.inputs.iter().zip(&muscle_index) {
            if input.signal == Signal::JointAngle {
                initial.joint_angle[k] += input.schedule.value(0.0);
                initial.joint_velocity[k] += input.schedule.slope(0.0);
            }
        }
        let sim = Simulation::new(plant, rate_hz, stepping, initial)?;
        let mut runner = ScenarioRunner {
            scenario: self.clone(),
            sim,
            names,
            joint_names,
            muscle_index,
            snapshot: StateSnapshot::default(),
        };
        runner.apply_inputs();
        Ok(runner)
    }

    /// The memory its records take at `rate_hz` with this many muscles and joints, within
    /// [`MAX_RUN_BYTES`]. (A rate that is not a finite number > 0 is left to the simulation to
    /// refuse.)
    fn check_size(
        &self,
        rate_hz: f64,
        muscles: usize,
        joints: usize,
    ) -> Result<(), ScenarioRunError> {
        if !(rate_hz.is_finite() && rate_hz > 0.0) {
            return Ok(());
        }
        let ticks = (self.duration * rate_hz).round();
        let bytes = (ticks + 1.0) * Run::record_bytes(muscles, joints);
        if !bytes.is_finite() || bytes > MAX_RUN_BYTES {
            return Err(ScenarioRunError::TooLarge {
                duration: self.duration,
                rate_hz,
                ticks,
                muscles,
                joints,
                bytes,
                max_bytes: MAX_RUN_BYTES,
            });
        }
        Ok(())
    }

    /// Every driven joint has a `joint_angle` schedule and no external torque (the attachment
    /// `joint` has no driven joint); `index` is each input's muscle or joint.
    fn check_driven(&self, topology: &Topology, index: &[usize]) -> Result<(), ScenarioRunError> {
        for (j, joint) in topology.joints.iter().enumerate() {
            let scheduled = |signal| {
                (self.inputs.iter().zip(index)).any(|(i, &k)| i.signal == signal && k == j)
            };
            if joint.driven && !scheduled(Signal::JointAngle) {
                return Err(ScenarioRunError::DrivenWithoutSchedule {
                    joint: joint.name.clone(),
                });
            }
            if joint.driven && scheduled(Signal::ExternalTorque) {
                return Err(ScenarioRunError::DrivenWithTorque {
                    joint: joint.name.clone(),
                });
            }
        }
        Ok(())
    }

    /// The configuration's limb as this scenario runs it: with attachment `driven`, every joint
    /// named by a `joint_angle` input is driven (as well as those the configuration marks).
    pub fn limb_config(&self, config: &ActuatorConfig) -> ActuatorConfig {
        let mut limb = config.clone();
        if self.attachment == SetupKind::Driven {
            for input in self
                .inputs
                .iter()
                .filter(|i| i.signal == Signal::JointAngle)
            {
                let name = input
                    .joint
                    .as_ref()
                    .or(limb.joints.first().map(|j| &j.name));
                if let Some(name) = name.cloned() {
                    if let Some(j) = limb.joints.iter_mut().find(|j| j.name == name) {
                        j.driven = true;
                    }
                }
            }
        }
        limb
    }

    /// The topology this scenario runs: the configuration's limb, or its first muscle alone.
    pub(crate) fn topology(&self, config: &ActuatorConfig) -> Topology {
        let first = &config.muscles[0];
        match self.attachment {
            SetupKind::Joint => config.topology(),
            SetupKind::Driven => self.limb_config(config).topology(),
            SetupKind::Clamped => Topology::clamped(
                &first.name,
                first.params.clone(),
                self.length
                    .unwrap_or(first.params.l_opt + first.params.l_ts),
            ),
            SetupKind::Force => Topology::force_driven(&first.name, first.params.clone()),
        }
    }
}

/// Steps a scenario tick by tick, sampling its schedules at each tick's start.
#[derive(Debug, Clone)]
pub struct ScenarioRunner {
    scenario: Scenario,
    sim: Simulation,
    names: Vec<String>,
    joint_names: Vec<String>,
    /// Per input: the muscle (excitation, tendon force) or joint (torque) it drives.
    muscle_index: Vec<usize>,
    snapshot: StateSnapshot,
}

impl ScenarioRunner {
    /// Writes the inputs the schedules give at time t into `inputs` (sized for the plant).
    pub(crate) fn fill_inputs(&self, t: f64, inputs: &mut Inputs) {
        inputs.clear();
        let mut tendon_force_scheduled = false;
        for (input, &k) in self.scenario.inputs.iter().zip(&self.muscle_index) {
            let v = input.schedule.value(t);
            match input.signal {
                Signal::Excitation => inputs.excitation[k] += v,
                Signal::TendonForce => {
                    tendon_force_scheduled = true;
                    inputs.tendon_force[k] += v
                }
                Signal::ExternalTorque => inputs.external_torque[k] += v,
                Signal::JointAngle => {
                    inputs.joint_angle[k] += v;
                    inputs.joint_velocity[k] += input.schedule.slope(t);
                }
            }
        }
        if !tendon_force_scheduled {
            inputs.tendon_force.fill(self.scenario.initial_force);
        }
        for u in &mut inputs.excitation {
            *u = u.clamp(0.0, 1.0);
        }
    }

    /// The inputs the schedules give at time t.
    pub fn inputs_at(&self, t: f64) -> Inputs {
        let mut inputs = self.sim.inputs().clone();
        self.fill_inputs(t, &mut inputs);
        inputs
    }

    /// The schedules at the tick's start into the simulation's inputs, in place (taken out and
    /// put back, so that nothing is allocated).
    fn apply_inputs(&mut self) {
        let t = self.sim.time();
        let mut inputs = std::mem::take(self.sim.inputs_mut());
        self.fill_inputs(t, &mut inputs);
        *self.sim.inputs_mut() = inputs;
    }

    /// Advances one tick (inputs sampled at its start).
    pub fn step(&mut self) -> Result<(), StepError> {
        self.apply_inputs();
        self.sim.step()
    }

    /// The current state as a record.
    pub fn record(&mut self) -> Record<'_> {
        self.sim.fill_snapshot(&mut self.snapshot);
        Record::of(self.sim.time(), &self.snapshot)
    }

    /// The state the last [`ScenarioRunner::record`] or [`ScenarioRunner::keep_record`] filled.
    pub fn snapshot(&self) -> &StateSnapshot {
        &self.snapshot
    }

    /// A run of this runner's scenario, model, rate, muscles and joints without records, with
    /// room for `capacity`.
    pub fn empty_run(&self, capacity: usize) -> Run {
        Run::new(
            self.scenario.name.clone(),
            self.sim.plant().model,
            self.sim.rate_hz(),
            self.names.clone(),
            self.joint_names.clone(),
            self.muscle_joints(),
            capacity,
        )
    }

    /// Appends the current state's record to `run` (which has this runner's muscles and
    /// joints).
    pub fn keep_record(&mut self, run: &mut Run) -> Result<(), RecordMismatch> {
        self.sim.fill_snapshot(&mut self.snapshot);
        run.push(self.sim.time(), &self.snapshot)
    }

    /// The simulation.
    pub fn simulation(&self) -> &Simulation {
        &self.sim
    }

    /// Muscle names, in order.
    pub fn muscle_names(&self) -> &[String] {
        &self.names
    }

    /// Joint names, in order.
    pub fn joint_names(&self) -> &[String] {
        &self.joint_names
    }

    /// Per muscle, the indices of the joints it spans.
    pub(crate) fn muscle_joints(&self) -> Vec<Vec<usize>> {
        let plant = self.sim.plant();
        (0..plant.muscle_count())
            .map(|i| plant.spans(i).iter().map(|s| s.joint).collect())
            .collect()
    }
}
