//! The kinds a scenario names: how its muscles are attached ([`SetupKind`]) and the input each
//! of its schedules drives ([`Signal`]).

use serde::Deserialize;

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
