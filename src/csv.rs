//! CSV output of a scenario run: one row per tick per muscle.

use crate::sim::scenario::Run;
use std::io::Write;

/// The `MuscleState.msg` field names after `name`, in message order.
pub const MUSCLE_FIELDS: [&str; 16] = [
    "excitation",
    "activation",
    "force",
    "ce_force",
    "pe_force",
    "fiber_length",
    "fiber_velocity",
    "tendon_length",
    "stiffness",
    "mtu_stiffness",
    "q0",
    "q1",
    "q2",
    "tendon_energy",
    "fiber_energy",
    "crossbridge_energy",
];

/// Writes `time,name,<MuscleState fields>[,joint_position,joint_velocity,joint_stiffness]`.
pub fn write_csv(run: &Run, out: &mut impl Write) -> std::io::Result<()> {
    let has_joint = run.records.first().is_some_and(|r| r.joint.is_some());
    write!(out, "time,name,{}", MUSCLE_FIELDS.join(","))?;
    if has_joint {
        write!(out, ",joint_position,joint_velocity,joint_stiffness")?;
    }
    writeln!(out)?;
    for rec in &run.records {
        for (m, name) in rec.muscles.iter().zip(&run.muscle_names) {
            let v = [
                m.excitation,
                m.activation,
                m.force,
                m.ce_force,
                m.pe_force,
                m.fiber_length,
                m.fiber_velocity,
                m.tendon_length,
                m.stiffness,
                m.mtu_stiffness,
                m.q0,
                m.q1,
                m.q2,
                m.tendon_energy,
                m.fiber_energy,
                m.crossbridge_energy,
            ];
            write!(out, "{},{}", rec.time, name)?;
            for x in v {
                write!(out, ",{x}")?;
            }
            if let Some(j) = &rec.joint {
                write!(out, ",{},{},{}", j.position, j.velocity, j.stiffness)?;
            }
            writeln!(out)?;
        }
    }
    Ok(())
}
