//! Scenarios: an attachment, a duration and input schedules; the built-in ones reproduce the
//! paper's experiments (docs/model.md §9), others come from scenario files (TOML, see
//! `scenarios/example.toml`).

use crate::config::ActuatorConfig;
use crate::physics::models::ModelKind;
use crate::physics::params::MuscleParams;
use crate::physics::plant::{Inputs, Plant};
use crate::physics::topology::Topology;
use crate::sim::schedule::Schedule;
use crate::sim::simulation::{Simulation, Stepping};
use crate::sim::snapshot::StateSnapshot;
use serde::Deserialize;
use std::path::Path;

pub use crate::sim::run::{Record, Run};

/// The built-in scenarios' names.
pub const BUILT_IN: [&str; 3] = ["pulse", "energy-10hz", "energy-100hz"];

/// Most memory the records of a run may take, bytes (1 GiB): a run keeps one record per tick
/// (for the CSV and the summary), so duration × rate and the limb's size are bounded together.
pub const MAX_RUN_BYTES: f64 = (1u64 << 30) as f64;

/// Longest scenario name, characters (it names the run in reports and recordings).
pub const MAX_NAME_CHARS: usize = 200;

/// How the muscles are attached in a scenario.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SetupKind {
    /// The limb of the configuration: all its joints and muscles.
    Joint,
    /// The first muscle, clamped at a total length.
    Clamped,
    /// The first muscle, its tendon pulled by a scheduled force.
    Force,
    /// The limb of the configuration with some joints driven: each joint named by a
    /// `joint_angle` input (and each the configuration marks `driven`) follows its schedule.
    Driven,
}

/// Which input a schedule drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Signal {
    /// A muscle's excitation (clamped to [0, 1] when applied).
    Excitation,
    /// The pull on a force-driven tendon, N.
    TendonForce,
    /// The external torque on a joint, N m.
    ExternalTorque,
    /// A driven joint's angle, rad; its velocity is the schedule's derivative.
    JointAngle,
}

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
    pub fn built_in(name: &str, params: &MuscleParams) -> Result<Self, String> {
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
            _ => Err(format!(
                "unknown scenario {name:?}: expected one of {} or a scenario file (.toml)",
                BUILT_IN.join(", ")
            )),
        }
    }

    /// A scenario from a TOML file (a regular file of at most 1 MiB).
    pub fn from_file(path: &Path) -> Result<Self, String> {
        let cannot = |e: &dyn std::fmt::Display| {
            format!("cannot read scenario file {}: {e}", path.display())
        };
        let bytes = crate::files::read_regular_file(path, crate::files::MAX_FILE_BYTES)
            .map_err(|e| cannot(&e))?;
        let text = String::from_utf8(bytes).map_err(|e| cannot(&e))?;
        let s: Scenario = toml::from_str(&text).map_err(|e| {
            format!(
                "scenario file {}: {}",
                path.display(),
                crate::text::toml_error(&e, &text)
            )
        })?;
        s.check()
            .map_err(|e| format!("scenario file {}: {e}", path.display()))?;
        Ok(s)
    }

    /// A built-in name, or else a path to a scenario file.
    pub fn resolve(name_or_path: &str, params: &MuscleParams) -> Result<Self, String> {
        if BUILT_IN.contains(&name_or_path) || !Path::new(name_or_path).exists() {
            if !BUILT_IN.contains(&name_or_path) && name_or_path.ends_with(".toml") {
                return Err(format!("scenario file {name_or_path} does not exist"));
            }
            Self::built_in(name_or_path, params)
        } else {
            Self::from_file(Path::new(name_or_path))
        }
    }

    fn check(&self) -> Result<(), String> {
        if self.name.chars().count() > MAX_NAME_CHARS {
            return Err(format!(
                "name {:?} is longer than {MAX_NAME_CHARS} characters",
                crate::text::excerpt(&self.name)
            ));
        }
        if !(self.duration.is_finite() && self.duration > 0.0 && self.duration <= 3600.0) {
            return Err(format!(
                "duration = {} must be in (0, 3600] s",
                self.duration
            ));
        }
        if let Some(l) = self.length {
            if !(l.is_finite() && l > 0.0) {
                return Err(format!("length = {l} must be a finite number > 0"));
            }
        }
        if !self.initial_force.is_finite() || self.initial_force < 0.0 {
            return Err(format!(
                "initial_force = {} must be a finite number >= 0",
                self.initial_force
            ));
        }
        for (i, input) in self.inputs.iter().enumerate() {
            input
                .schedule
                .check()
                .map_err(|e| format!("input[{i}]: {e}"))?;
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
                return Err(format!(
                    "input[{i}]: signal {:?} does not apply to attachment {:?}",
                    input.signal, self.attachment
                ));
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
    ) -> Result<Run, String> {
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
    ) -> Result<ScenarioRunner, String> {
        config.validate().map_err(|e| e.to_string())?;
        let topology = self.topology(config);
        let names = topology.muscle_names();
        let joint_names = topology.joint_names();
        self.check_size(rate_hz, names.len(), joint_names.len())?;
        let mut muscle_index = Vec::with_capacity(self.inputs.len());
        for (i, input) in self.inputs.iter().enumerate() {
            let lookup = |want: &Option<String>, names: &[String], what: &str| match want {
                None => Ok(0),
                Some(m) => names.iter().position(|n| n == m).ok_or_else(|| {
                    format!(
                        "input[{i}]: unknown {what} {:?} (this scenario has {})",
                        crate::text::excerpt(m),
                        if names.is_empty() {
                            "none".to_string()
                        } else {
                            crate::text::one_line(&names.join(", "))
                        }
                    )
                }),
            };
            let idx = match input.signal {
                Signal::ExternalTorque | Signal::JointAngle => {
                    if joint_names.is_empty() {
                        return Err(format!("input[{i}]: this scenario has no joint"));
                    }
                    lookup(&input.joint, &joint_names, "joint")?
                }
                _ => lookup(&input.muscle, &names, "muscle")?,
            };
            muscle_index.push(idx);
        }
        self.check_driven(&topology, &muscle_index)?;
        let plant = Plant::new(&topology, model)?;
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
    fn check_size(&self, rate_hz: f64, muscles: usize, joints: usize) -> Result<(), String> {
        if !(rate_hz.is_finite() && rate_hz > 0.0) {
            return Ok(());
        }
        let ticks = (self.duration * rate_hz).round();
        let bytes = (ticks + 1.0) * Run::record_bytes(muscles, joints);
        if !bytes.is_finite() || bytes > MAX_RUN_BYTES {
            return Err(format!(
                "a run of {} s at {rate_hz} Hz is {ticks} ticks, whose records ({muscles} \
                 muscles, {joints} joints) take about {:.0} MiB, more than the {} MiB a run may \
                 hold: shorten the duration or lower the rate",
                self.duration,
                bytes / (1u64 << 20) as f64,
                MAX_RUN_BYTES / (1u64 << 20) as f64
            ));
        }
        Ok(())
    }

    /// Every driven joint has a `joint_angle` schedule and no external torque (the attachment
    /// `joint` has no driven joint); `index` is each input's muscle or joint.
    fn check_driven(&self, topology: &Topology, index: &[usize]) -> Result<(), String> {
        for (j, joint) in topology.joints.iter().enumerate() {
            let scheduled = |signal| {
                (self.inputs.iter().zip(index)).any(|(i, &k)| i.signal == signal && k == j)
            };
            if joint.driven && !scheduled(Signal::JointAngle) {
                return Err(format!(
                    "joint {:?} is driven: the scenario needs attachment = \"driven\" and a \
                     joint_angle input for it",
                    crate::text::excerpt(&joint.name)
                ));
            }
            if joint.driven && scheduled(Signal::ExternalTorque) {
                return Err(format!(
                    "joint {:?} is driven: an external torque on it has no effect",
                    crate::text::excerpt(&joint.name)
                ));
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
    pub fn topology(&self, config: &ActuatorConfig) -> Topology {
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
    pub fn fill_inputs(&self, t: f64, inputs: &mut Inputs) {
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
    pub fn step(&mut self) -> Result<(), String> {
        self.apply_inputs();
        self.sim.step().map_err(|e| e.to_string())
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
    pub fn keep_record(&mut self, run: &mut Run) -> Result<(), String> {
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
    pub fn muscle_joints(&self) -> Vec<Vec<usize>> {
        let plant = self.sim.plant();
        (0..plant.muscle_count())
            .map(|i| plant.spans(i).iter().map(|s| s.joint).collect())
            .collect()
    }
}
