//! The `muscle_actuator` metadata record of a run file: everything needed to rebuild the run
//! (model, rate, stepping, attachment, configuration, time base, the driven joints' initial
//! motion), as text and back, checked.

use super::limits::{self, LimitError};
use muscle_actuator_core::config::{ActuatorConfig, ConfigError};
use muscle_actuator_core::csv::SplitError;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{Inputs, Plant, PlantError, Stepping, Topology};
use muscle_actuator_core::sim::{SetupError, Simulation};
use muscle_actuator_core::text::excerpt;
use muscle_actuator_core::time::{iso8601, TimeBase};
use std::collections::BTreeMap;

/// Name of our metadata record.
pub const METADATA_NAME: &str = "muscle_actuator";

/// What is wrong with a `muscle_actuator` metadata record (or a run's metadata to write).
#[derive(Debug, thiserror::Error)]
pub enum MetadataError {
    /// The record lacks a key it must have.
    #[error("metadata record {METADATA_NAME:?} has no {key:?}")]
    Missing {
        /// The key.
        key: &'static str,
    },
    /// A key's value does not parse (or is not one of the values it may take).
    #[error("metadata {METADATA_NAME}.{key} = {:?} is invalid", excerpt(.value))]
    Invalid {
        /// The key.
        key: &'static str,
        /// Its value.
        value: String,
    },
    /// A list key (`muscles`, `joints`) is not one CSV record.
    #[error("metadata {METADATA_NAME}.{key} = {:?} is invalid: {reason}", excerpt(.value))]
    BadList {
        /// The key.
        key: &'static str,
        /// Its value.
        value: String,
        /// Why it does not parse.
        #[source]
        reason: SplitError,
    },
    /// The configuration recorded is not a valid one (its lines joined by `; `).
    #[error(
        "metadata {METADATA_NAME}.config_toml: {}",
        .0.to_string().replace('\n', "; ")
    )]
    Config(#[source] ConfigError),
    /// The configuration to record does not serialize as TOML.
    #[error("configuration as TOML: {0}")]
    ConfigToml(#[source] toml::ser::Error),
    /// The rate or stepping recorded is out of its limits.
    #[error(transparent)]
    Limit(#[from] LimitError),
    /// The clamped length recorded is not a finite number > 0.
    #[error("metadata {METADATA_NAME}.length = {length} is invalid: must be a finite number > 0")]
    Length {
        /// The length recorded, m.
        length: f64,
    },
    /// The initial tendon force recorded is not a finite number >= 0.
    #[error(
        "metadata {METADATA_NAME}.initial_force = {force} is invalid: must be a finite number >= 0"
    )]
    InitialForce {
        /// The force recorded, N.
        force: f64,
    },
    /// The driven joints' initial motion does not have one pair per driven joint.
    #[error(
        "metadata {METADATA_NAME}.initial_joint_motion has {pairs} (angle, velocity) pairs for \
         {driven} driven joints"
    )]
    InitialMotionCount {
        /// The pairs recorded.
        pairs: usize,
        /// The driven joints of the configuration.
        driven: usize,
    },
    /// The muscle or joint list recorded is not that of the configuration's topology.
    #[error(
        "metadata {METADATA_NAME}.{key} = {:?} does not match its configuration ({})",
        excerpt(&.listed.join(",")),
        excerpt(&.actual.join(","))
    )]
    Names {
        /// `muscles` or `joints`.
        key: &'static str,
        /// The names recorded.
        listed: Vec<String>,
        /// The configuration's names.
        actual: Vec<String>,
    },
}

/// How the muscles were attached in a run.
#[derive(Debug, Clone, PartialEq)]
pub enum AttachmentMeta {
    /// The configuration's whole limb.
    Joint,
    /// The configuration's first muscle alone, held at a total length.
    Clamped {
        /// The muscle–tendon unit's length, m.
        length: f64,
    },
    /// The configuration's first muscle alone, its tendon pulled by an external force.
    Force {
        /// The tendon force at the start, N.
        initial_force: f64,
    },
    /// The configuration's limb with driven joints (those marked in `config`), their motion
    /// from a scenario's schedules or a measured trial's lengths (`predict --out`), recorded as
    /// applied, on `~/applied/joint_motion`.
    Driven,
}

/// What the `muscle_actuator` metadata record holds: everything needed to rebuild the run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunMeta {
    /// What made the run (`simulate pulse`, `node /muscle_actuator`, `replay ...`).
    pub source: String,
    /// The contractile-element model.
    pub model: ModelKind,
    /// The tick rate, Hz.
    pub rate_hz: f64,
    /// How each tick was divided into sub-steps.
    pub stepping: Stepping,
    /// How the muscles were attached.
    pub attachment: AttachmentMeta,
    /// The actuator's configuration.
    pub config: ActuatorConfig,
    /// The node's parameters (JSON), for node runs.
    pub parameters_json: Option<String>,
    /// Wall-clock start, ns since the Unix epoch.
    pub start_time_ns: i64,
    /// What the log times and header stamps count.
    pub time_base: TimeBase,
    /// The driven joints' motion the run started from, (angle rad, velocity rad/s) per driven
    /// joint in configuration order; empty: their initial angles, at rest (as the node starts).
    pub initial_joint_motion: Vec<(f64, f64)>,
    /// The run's muscle names, in the order of every recorded state's muscles.
    pub muscles: Vec<String>,
    /// The run's joint names, in the order of every recorded state's joints.
    pub joints: Vec<String>,
}

fn stepping_text(s: Stepping) -> String {
    match s {
        Stepping::Adaptive {
            tolerance,
            max_substeps,
        } => format!("adaptive {tolerance:e} {max_substeps}"),
        Stepping::Fixed(n) => format!("fixed {n}"),
    }
}

fn parse_stepping(s: &str) -> Option<Stepping> {
    let parts: Vec<&str> = s.split_whitespace().collect();
    match parts.as_slice() {
        ["adaptive", t, m] => Some(Stepping::Adaptive {
            tolerance: t.parse().ok()?,
            max_substeps: m.parse().ok()?,
        }),
        ["fixed", n] => Some(Stepping::Fixed(n.parse().ok()?)),
        _ => None,
    }
}

/// Why the simulation a run describes could not be built.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// The run's configuration is not valid.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// The plant refuses the run's topology or model.
    #[error(transparent)]
    Plant(#[from] PlantError),
    /// The simulation could not be set up.
    #[error(transparent)]
    Setup(#[from] SetupError),
}

/// The record's value of `k`, or the error naming the missing key.
fn get<'a>(m: &'a BTreeMap<String, String>, k: &'static str) -> Result<&'a String, MetadataError> {
    m.get(k).ok_or(MetadataError::Missing { key: k })
}

/// The error of key `k` holding the invalid `v`.
fn bad(k: &'static str, v: &str) -> MetadataError {
    MetadataError::Invalid {
        key: k,
        value: v.into(),
    }
}

/// The time base the record names; a record without the key is simulated time (offline runs
/// stamp inputs from zero).
fn time_base_from(m: &BTreeMap<String, String>) -> Result<TimeBase, MetadataError> {
    Ok(match m.get("time_base").map(String::as_str) {
        None | Some("simulated") => TimeBase::Simulated,
        Some("wall") => {
            let v = get(m, "tick_origin_ns")?;
            TimeBase::WallOrigin {
                tick_origin_ns: v.parse().map_err(|_| bad("tick_origin_ns", v))?,
            }
        }
        Some("ros_clock") => TimeBase::RosClock {
            tick_origin_ns: match m.get("tick_origin_ns") {
                Some(v) => Some(v.parse().map_err(|_| bad("tick_origin_ns", v))?),
                None => None,
            },
        },
        Some(other) => return Err(bad("time_base", other)),
    })
}

/// The driven joints' initial motion: finite (angle, velocity) pairs, none without the key.
fn initial_motion_from(m: &BTreeMap<String, String>) -> Result<Vec<(f64, f64)>, MetadataError> {
    let Some(v) = m.get("initial_joint_motion") else {
        return Ok(vec![]);
    };
    let x: Vec<f64> = (v.split_whitespace())
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| bad("initial_joint_motion", v))?;
    if !x.len().is_multiple_of(2) || x.iter().any(|x| !x.is_finite()) {
        return Err(bad("initial_joint_motion", v));
    }
    Ok(x.chunks(2).map(|p| (p[0], p[1])).collect())
}

impl RunMeta {
    /// The metadata record's map.
    pub fn to_map(&self) -> Result<BTreeMap<String, String>, MetadataError> {
        let mut m = BTreeMap::new();
        let mut put = |k: &str, v: String| {
            m.insert(k.to_string(), v);
        };
        put("source", self.source.clone());
        put("model", self.model.name().into());
        put("rate_hz", format!("{:?}", self.rate_hz));
        put("stepping", stepping_text(self.stepping));
        match &self.attachment {
            AttachmentMeta::Joint => put("attachment", "joint".into()),
            AttachmentMeta::Driven => put("attachment", "driven".into()),
            AttachmentMeta::Clamped { length } => {
                put("attachment", "clamped".into());
                put("length", format!("{length:?}"));
            }
            AttachmentMeta::Force { initial_force } => {
                put("attachment", "force".into());
                put("initial_force", format!("{initial_force:?}"));
            }
        }
        put(
            "config_toml",
            toml::to_string(&self.config).map_err(MetadataError::ConfigToml)?,
        );
        if let Some(p) = &self.parameters_json {
            put("parameters_json", p.clone());
        }
        put("start_time_ns", self.start_time_ns.to_string());
        put("start_time", iso8601(self.start_time_ns));
        match self.time_base {
            TimeBase::Simulated => put("time_base", "simulated".into()),
            TimeBase::WallOrigin { tick_origin_ns } => {
                put("time_base", "wall".into());
                put("tick_origin_ns", tick_origin_ns.to_string());
            }
            TimeBase::RosClock { tick_origin_ns } => {
                put("time_base", "ros_clock".into());
                if let Some(t) = tick_origin_ns {
                    put("tick_origin_ns", t.to_string());
                }
            }
        }
        if !self.initial_joint_motion.is_empty() {
            // `{:?}` prints the shortest text that parses back to the same f64.
            let v: Vec<String> = (self.initial_joint_motion.iter())
                .map(|(a, w)| format!("{a:?} {w:?}"))
                .collect();
            put("initial_joint_motion", v.join(" "));
        }
        // One CSV record each: a name with a comma or a quote is quoted.
        put(
            "muscles",
            muscle_actuator_core::csv::join_record(&self.muscles),
        );
        put(
            "joints",
            muscle_actuator_core::csv::join_record(&self.joints),
        );
        put("program_version", env!("CARGO_PKG_VERSION").into());
        put("program", "muscle_actuator".into());
        Ok(m)
    }

    /// Back from the record (fails with the missing or bad key).
    pub(crate) fn from_map(m: &BTreeMap<String, String>) -> Result<Self, MetadataError> {
        let f64_of = |k: &'static str| -> Result<f64, MetadataError> {
            let v = get(m, k)?;
            v.parse::<f64>().map_err(|_| bad(k, v))
        };
        let model: ModelKind = get(m, "model")?
            .parse()
            .map_err(|_| bad("model", &m["model"]))?;
        let stepping =
            parse_stepping(get(m, "stepping")?).ok_or_else(|| bad("stepping", &m["stepping"]))?;
        let attachment = match get(m, "attachment")?.as_str() {
            "joint" => AttachmentMeta::Joint,
            "driven" => AttachmentMeta::Driven,
            "clamped" => AttachmentMeta::Clamped {
                length: f64_of("length")?,
            },
            "force" => AttachmentMeta::Force {
                initial_force: f64_of("initial_force")?,
            },
            other => return Err(bad("attachment", other)),
        };
        let config =
            ActuatorConfig::from_toml_str(get(m, "config_toml")?).map_err(MetadataError::Config)?;
        let list = |k: &'static str| -> Result<Vec<String>, MetadataError> {
            m.get(k).map_or(Ok(Vec::new()), |s| {
                muscle_actuator_core::csv::split_record(s)
                    .map(|v| v.into_iter().filter(|x| !x.is_empty()).collect())
                    .map_err(|reason| MetadataError::BadList {
                        key: k,
                        value: s.clone(),
                        reason,
                    })
            })
        };
        let time_base = time_base_from(m)?;
        let meta = RunMeta {
            source: m.get("source").cloned().unwrap_or_default(),
            model,
            rate_hz: f64_of("rate_hz")?,
            stepping,
            attachment,
            config,
            parameters_json: m.get("parameters_json").cloned(),
            start_time_ns: m
                .get("start_time_ns")
                .and_then(|s| s.parse().ok())
                .unwrap_or(0),
            time_base,
            initial_joint_motion: initial_motion_from(m)?,
            muscles: list("muscles")?,
            joints: list("joints")?,
        };
        meta.check()?;
        Ok(meta)
    }

    /// The numbers within their limits (a rate the node would accept, sub-steps the simulation
    /// would), the attachment's numbers finite, the muscle and joint lists those of the
    /// configuration's topology.
    fn check(&self) -> Result<(), MetadataError> {
        let key = |k: &str| format!("metadata {METADATA_NAME}.{k}");
        limits::check_rate_hz(&key("rate_hz"), self.rate_hz)?;
        limits::check_stepping(&key("stepping"), self.stepping)?;
        match self.attachment {
            AttachmentMeta::Clamped { length } if !(length.is_finite() && length > 0.0) => {
                return Err(MetadataError::Length { length });
            }
            AttachmentMeta::Force { initial_force }
                if !(initial_force.is_finite() && initial_force >= 0.0) =>
            {
                return Err(MetadataError::InitialForce {
                    force: initial_force,
                });
            }
            _ => {}
        }
        let driven = self.config.joints.iter().filter(|j| j.driven).count();
        if !self.initial_joint_motion.is_empty() && self.initial_joint_motion.len() != driven {
            return Err(MetadataError::InitialMotionCount {
                pairs: self.initial_joint_motion.len(),
                driven,
            });
        }
        let topology = self.topology();
        for (k, listed, actual) in [
            ("muscles", &self.muscles, topology.muscle_names()),
            ("joints", &self.joints, topology.joint_names()),
        ] {
            if *listed != actual {
                return Err(MetadataError::Names {
                    key: k,
                    listed: listed.clone(),
                    actual,
                });
            }
        }
        Ok(())
    }

    /// The topology of the run.
    pub(crate) fn topology(&self) -> Topology {
        let first = &self.config.muscles[0];
        match &self.attachment {
            AttachmentMeta::Joint | AttachmentMeta::Driven => self.config.topology(),
            AttachmentMeta::Clamped { length } => {
                Topology::clamped(&first.name, first.params.clone(), *length)
            }
            AttachmentMeta::Force { .. } => {
                Topology::force_driven(&first.name, first.params.clone())
            }
        }
    }

    /// The simulation this run describes, in its initial state (with model `model`).
    pub(crate) fn build(
        &self,
        model: ModelKind,
        stepping: Stepping,
    ) -> Result<Simulation, BuildError> {
        self.config.validate()?;
        let plant = Plant::new(&self.topology(), model)?;
        let mut initial = Inputs::zeros(plant.muscle_count(), plant.joint_count());
        if let AttachmentMeta::Force { initial_force } = self.attachment {
            initial.tendon_force.fill(initial_force);
        }
        let driven = (plant.joints.iter().enumerate()).filter(|(_, j)| j.driven);
        for (n, (j, p)) in driven.enumerate() {
            let (angle, velocity) =
                (self.initial_joint_motion.get(n).copied()).unwrap_or((p.initial_angle, 0.0));
            initial.joint_angle[j] = angle;
            initial.joint_velocity[j] = velocity;
        }
        Ok(Simulation::new(plant, self.rate_hz, stepping, initial)?)
    }
}

/// The driven joints' motion that `sim` holds for its next tick: (angle rad, velocity rad/s) per
/// driven joint, in configuration order ([`RunMeta::initial_joint_motion`] at tick 0).
pub fn driven_motion(sim: &Simulation) -> Vec<(f64, f64)> {
    let inputs = sim.inputs();
    (sim.plant().joints.iter().enumerate())
        .filter(|(_, j)| j.driven)
        .map(|(j, _)| (inputs.joint_angle[j], inputs.joint_velocity[j]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use muscle_actuator_core::sim::default_stepping;

    /// The time base survives the metadata record, and a record without one is simulated time;
    /// so does the driven joints' initial motion, which must fit them.
    #[test]
    fn time_base_and_initial_motion_round_trip_the_record() {
        let wall = TimeBase::WallOrigin {
            tick_origin_ns: 1_763_800_000_000_000_123,
        };
        let cfg = ActuatorConfig::default();
        let mut meta = RunMeta {
            source: "test".into(),
            model: "hill".parse().unwrap(),
            rate_hz: 1000.0,
            stepping: default_stepping("hill".parse().unwrap()),
            attachment: AttachmentMeta::Joint,
            config: cfg.clone(),
            parameters_json: None,
            start_time_ns: 5,
            time_base: wall,
            initial_joint_motion: vec![],
            muscles: cfg.topology().muscle_names(),
            joints: cfg.topology().joint_names(),
        };
        let mut map = meta.to_map().unwrap();
        assert_eq!(map["time_base"], "wall");
        assert_eq!(RunMeta::from_map(&map).unwrap(), meta);
        map.remove("time_base");
        map.remove("tick_origin_ns");
        meta.time_base = TimeBase::Simulated;
        assert_eq!(RunMeta::from_map(&map).unwrap(), meta);
        map.insert("time_base".into(), "sundial".into());
        assert!(matches!(
            RunMeta::from_map(&map),
            Err(MetadataError::Invalid {
                key: "time_base",
                ..
            })
        ));
        map.insert("time_base".into(), "wall".into());
        assert!(matches!(
            RunMeta::from_map(&map),
            Err(MetadataError::Missing {
                key: "tick_origin_ns"
            })
        ));
        // Following /clock: no origin until the first clock message, then the one it gave.
        for origin in [None, Some(5_000_000_000_000)] {
            meta.time_base = TimeBase::RosClock {
                tick_origin_ns: origin,
            };
            assert_eq!(RunMeta::from_map(&meta.to_map().unwrap()).unwrap(), meta);
        }
        // The driven joints' initial motion round-trips exactly, and must fit them.
        let mut cfg = ActuatorConfig::default();
        cfg.joints[0].driven = true;
        meta.config = cfg;
        meta.initial_joint_motion = vec![(0.1 + 0.2, std::f64::consts::PI / 3.0)];
        assert_eq!(RunMeta::from_map(&meta.to_map().unwrap()).unwrap(), meta);
        meta.initial_joint_motion.push((0.0, 0.0));
        let e = RunMeta::from_map(&meta.to_map().unwrap()).unwrap_err();
        assert!(e.to_string().contains("initial_joint_motion"), "{e}");
        assert!(matches!(
            e,
            MetadataError::InitialMotionCount {
                pairs: 2,
                driven: 1
            }
        ));
    }
}
