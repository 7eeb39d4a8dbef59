//! What a recorded run must satisfy before it is replayed or compared, whoever wrote the file:
//! states whose ticks only grow, within a run of bounded length consistent with the time the
//! recording spans (replay simulates every tick up to the last); finite values; states naming
//! the run's muscles and joints; inputs in tick order with one value per name.

use super::channels::STATE_TYPE;
use super::limits::MAX_RECORDED_TICKS;
use super::RunMeta;
use crate::msgs::muscle_actuator_msgs::ActuatorState;
use crate::recording::schema::field_names;
use crate::recording::Recording;
use muscle_actuator_core::sim::snapshot::{JointSnapshot, MuscleSnapshot};
use muscle_actuator_core::text::excerpt;

/// Slack of the simulated span over the recorded one: a node's tick loop keeps to the wall
/// clock its log times follow, within jitter; offline runs log simulated time exactly.
const SPAN_SLACK_FACTOR: f64 = 1.25;
const SPAN_SLACK_S: f64 = 1.0;

/// States whose ticks only grow, finite, naming the run's muscles and joints.
pub(super) fn check_states(meta: &RunMeta, states: &[ActuatorState]) -> Result<(), String> {
    for w in states.windows(2) {
        if w[1].tick <= w[0].tick {
            return Err(format!(
                "the run was reset or rebuilt, or its ticks are out of order (tick {} followed \
                 by {}); replay and compare cover runs without resets or parameter changes",
                w[0].tick, w[1].tick
            ));
        }
    }
    for s in states {
        let at = |what: String| format!("state at tick {}: {what}", s.tick);
        let muscles: Vec<&String> = s.muscles.iter().map(|m| &m.name).collect();
        if muscles.len() != meta.muscles.len()
            || muscles.iter().zip(&meta.muscles).any(|(a, b)| *a != b)
        {
            return Err(at(format!(
                "muscles [{}] are not the run's [{}]",
                excerpt(
                    &s.muscles
                        .iter()
                        .map(|m| m.name.as_str())
                        .collect::<Vec<_>>()
                        .join(",")
                ),
                excerpt(&meta.muscles.join(","))
            )));
        }
        if s.joint != meta.joints {
            return Err(at(format!(
                "joints [{}] are not the run's [{}]",
                excerpt(&s.joint.join(",")),
                excerpt(&meta.joints.join(","))
            )));
        }
        for m in &s.muscles {
            for (f, v) in MuscleSnapshot::FIELDS.iter().zip(m.state.values()) {
                finite(v).map_err(|v| at(format!("{}.{f} = {v}", excerpt(&m.name))))?;
            }
        }
        for (name, j) in s.joint.iter().zip(&s.joints) {
            for (f, v) in JointSnapshot::FIELDS.iter().zip(j.values()) {
                finite(v).map_err(|v| at(format!("{}.{f} = {v}", excerpt(name))))?;
            }
        }
        for v in &s.stiffness_matrix {
            finite(*v).map_err(|v| at(format!("stiffness_matrix holds {v}")))?;
        }
    }
    Ok(())
}

/// `Err(v)` for a value that is not finite.
fn finite(v: f64) -> Result<(), String> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(format!("{v} (not a finite number)"))
    }
}

/// Inputs in tick order with one value per name.
pub(super) fn check_inputs(
    what: &str,
    inputs: &[(u64, Vec<String>, Vec<f64>)],
) -> Result<(), String> {
    for w in inputs.windows(2) {
        if w[1].0 < w[0].0 {
            return Err(format!(
                "{what} inputs out of tick order (tick {} after {})",
                w[1].0, w[0].0
            ));
        }
    }
    for (tick, names, values) in inputs {
        if names.len() != values.len() {
            return Err(format!(
                "{what} input at tick {tick}: {} names for {} values",
                names.len(),
                values.len()
            ));
        }
        for (n, v) in names.iter().zip(values) {
            finite(*v).map_err(|v| format!("{what} input at tick {tick}: {} = {v}", excerpt(n)))?;
        }
    }
    Ok(())
}

/// The last tick within [`MAX_RECORDED_TICKS`], and its simulated time (from tick 0) within the
/// time the recording's messages span.
pub(super) fn check_length(
    meta: &RunMeta,
    states: &[ActuatorState],
    recorded_span_s: f64,
) -> Result<(), String> {
    let Some(last) = states.last().map(|s| s.tick) else {
        return Ok(());
    };
    if last > MAX_RECORDED_TICKS {
        return Err(format!(
            "its last state is at tick {last}: a run may span at most {MAX_RECORDED_TICKS} ticks"
        ));
    }
    let simulated = last as f64 / meta.rate_hz;
    let allowed = recorded_span_s * SPAN_SLACK_FACTOR + SPAN_SLACK_S;
    if simulated > allowed {
        return Err(format!(
            "its last state is at tick {last} ({simulated:.6e} s at {} Hz), but its messages \
             span only {recorded_span_s:.6e} s",
            meta.rate_hz
        ));
    }
    Ok(())
}

/// The `MuscleState` of every recorded `ActuatorState` schema has this version's fields: an
/// older recording (one made before the energetics fields, say) is refused with the fields it
/// lacks, not decoded into garbage.
pub(super) fn check_state_schema(rec: &Recording) -> Result<(), String> {
    const MUSCLE_TYPE: &str = "muscle_actuator_msgs/MuscleState";
    let want: Vec<&str> = std::iter::once("name")
        .chain(MuscleSnapshot::FIELDS)
        .collect();
    for ch in rec.channels.values() {
        let Some(schema) = ch.schema.as_ref().filter(|s| s.name == STATE_TYPE) else {
            continue;
        };
        let text = String::from_utf8_lossy(&schema.data);
        let have = field_names(&text, MUSCLE_TYPE, false).unwrap_or_default();
        if have != want {
            let missing: Vec<&str> = want
                .iter()
                .copied()
                .filter(|f| !have.iter().any(|h| h == f))
                .collect();
            return Err(format!(
                "channel {}: its {MUSCLE_TYPE} has {} fields where this version's has {}{}; \
                 the recording was made by another version of muscle_actuator, and replay, \
                 compare and export read this version's recordings only",
                excerpt(&ch.topic),
                have.len(),
                want.len(),
                if missing.is_empty() {
                    String::new()
                } else {
                    format!(" (it lacks {})", excerpt(&missing.join(", ")))
                }
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::msgs::definition;
    use crate::recording::schema::ros2msg_schema;
    use std::borrow::Cow;
    use std::sync::Arc;

    /// A recording with one `~/state` channel whose schema is `text`.
    fn with_state_schema(text: &str) -> Recording {
        let schema = mcap::Schema {
            id: 1,
            name: STATE_TYPE.into(),
            encoding: "ros2msg".into(),
            data: Cow::Owned(text.as_bytes().to_vec()),
        };
        let channel = mcap::Channel {
            id: 1,
            topic: "/muscle_actuator/state".into(),
            schema: Some(Arc::new(schema)),
            message_encoding: "cdr".into(),
            metadata: Default::default(),
        };
        let mut rec = Recording::default();
        rec.channels.insert(1, Arc::new(channel));
        rec
    }

    #[test]
    fn a_recording_of_this_version_passes_an_older_one_is_refused_by_name() {
        let current = ros2msg_schema(STATE_TYPE, &definition).unwrap();
        assert_eq!(check_state_schema(&with_state_schema(&current)), Ok(()));
        // The schema of a recording made before the energetics fields.
        let older: String = current
            .lines()
            .take_while(|l| !l.starts_with("# Energetics"))
            .chain(
                current
                    .lines()
                    .skip_while(|l| !l.starts_with("float64 phenomenological_energy"))
                    .skip(1),
            )
            .map(|l| format!("{l}\n"))
            .collect();
        assert!(older.contains("crossbridge_energy") && !older.contains("metabolic_power"));
        let e = check_state_schema(&with_state_schema(&older)).unwrap_err();
        assert!(
            e.contains("lacks metabolic_power, activation_heat_rate"),
            "{e}"
        );
        assert!(e.contains("another version"), "{e}");
        // A schema without the MuscleState section at all.
        let e = check_state_schema(&with_state_schema("float64 x\n")).unwrap_err();
        assert!(e.contains("has 0 fields"), "{e}");
    }
}
