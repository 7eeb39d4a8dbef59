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
use muscle_actuator_core::sim::{JointSnapshot, MuscleSnapshot};
use muscle_actuator_core::text::excerpt;

/// Slack of the simulated span over the recorded one: a node's tick loop keeps to the wall
/// clock its log times follow, within jitter; offline runs log simulated time exactly.
const SPAN_SLACK_FACTOR: f64 = 1.25;
const SPAN_SLACK_S: f64 = 1.0;

/// What makes a recorded run unfit for replay, compare or export.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CheckError {
    /// A state's tick does not follow the one before it (a reset, a rebuild, a shuffle).
    #[error(
        "the run was reset or rebuilt, or its ticks are out of order (tick {before} followed by \
         {after}); replay and compare cover runs without resets or parameter changes"
    )]
    TicksOutOfOrder {
        /// The earlier state's tick.
        before: u64,
        /// The tick of the state after it.
        after: u64,
    },
    /// A state's muscles are not the run's (names and order).
    #[error(
        "state at tick {tick}: muscles [{}] are not the run's [{}]",
        excerpt(&.found.join(",")),
        excerpt(&.expected.join(","))
    )]
    StateMuscles {
        /// The state's tick.
        tick: u64,
        /// The muscles the state names.
        found: Vec<String>,
        /// The run's muscles.
        expected: Vec<String>,
    },
    /// A state's joints are not the run's (names and order).
    #[error(
        "state at tick {tick}: joints [{}] are not the run's [{}]",
        excerpt(&.found.join(",")),
        excerpt(&.expected.join(","))
    )]
    StateJoints {
        /// The state's tick.
        tick: u64,
        /// The joints the state names.
        found: Vec<String>,
        /// The run's joints.
        expected: Vec<String>,
    },
    /// A muscle's or joint's field in a state is not a finite number.
    #[error(
        "state at tick {tick}: {}.{field} = {value} (not a finite number)",
        excerpt(.name)
    )]
    StateNotFinite {
        /// The state's tick.
        tick: u64,
        /// The muscle or joint.
        name: String,
        /// The field.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// A state's stiffness matrix holds a value that is not a finite number.
    #[error("state at tick {tick}: stiffness_matrix holds {value} (not a finite number)")]
    StiffnessNotFinite {
        /// The state's tick.
        tick: u64,
        /// The value.
        value: f64,
    },
    /// Inputs recorded out of tick order.
    #[error("{what} inputs out of tick order (tick {tick} after {before})")]
    InputsOutOfOrder {
        /// `activation` or `external load`.
        what: &'static str,
        /// The later input's tick.
        tick: u64,
        /// The tick of the input before it.
        before: u64,
    },
    /// An input with not as many values as names.
    #[error("{what} input at tick {tick}: {names} names for {values} values")]
    InputLengths {
        /// `activation` or `external load`.
        what: &'static str,
        /// The input's tick.
        tick: u64,
        /// Names given.
        names: usize,
        /// Values given.
        values: usize,
    },
    /// An input value that is not a finite number.
    #[error(
        "{what} input at tick {tick}: {} = {value} (not a finite number)",
        excerpt(.name)
    )]
    InputNotFinite {
        /// `activation` or `external load`.
        what: &'static str,
        /// The input's tick.
        tick: u64,
        /// The muscle or joint named.
        name: String,
        /// The value.
        value: f64,
    },
    /// The last state lies beyond `MAX_RECORDED_TICKS`.
    #[error("its last state is at tick {last}: a run may span at most {MAX_RECORDED_TICKS} ticks")]
    TooManyTicks {
        /// The last state's tick.
        last: u64,
    },
    /// The last state's simulated time exceeds the time the messages span (with slack).
    #[error(
        "its last state is at tick {last} ({simulated_s:.6e} s at {rate_hz} Hz), but its \
         messages span only {recorded_s:.6e} s"
    )]
    LongerThanRecorded {
        /// The last state's tick.
        last: u64,
        /// Its simulated time from tick 0, s.
        simulated_s: f64,
        /// The run's rate, Hz.
        rate_hz: f64,
        /// The time the messages span, s.
        recorded_s: f64,
    },
    /// The recorded `MuscleState` has other fields than this version's: a recording made by
    /// another version of the program.
    #[error(
        "channel {}: its {MUSCLE_TYPE} has {have} fields where this version's has {want}{}; the \
         recording was made by another version of muscle_actuator, and replay, compare and \
         export read this version's recordings only",
        excerpt(.topic),
        lacking(.missing)
    )]
    OtherVersion {
        /// The `~/state` channel's topic.
        topic: String,
        /// Fields the recorded `MuscleState` has.
        have: usize,
        /// Fields this version's has.
        want: usize,
        /// This version's fields the recorded one lacks.
        missing: Vec<String>,
    },
}

/// The recorded type whose fields [`check_state_schema`] compares.
const MUSCLE_TYPE: &str = "muscle_actuator_msgs/MuscleState";

/// ` (it lacks a, b)`, or nothing when no field is missing.
fn lacking(missing: &[String]) -> String {
    if missing.is_empty() {
        String::new()
    } else {
        format!(" (it lacks {})", excerpt(&missing.join(", ")))
    }
}

/// States whose ticks only grow, finite, naming the run's muscles and joints.
pub(super) fn check_states(meta: &RunMeta, states: &[ActuatorState]) -> Result<(), CheckError> {
    for w in states.windows(2) {
        if w[1].tick <= w[0].tick {
            return Err(CheckError::TicksOutOfOrder {
                before: w[0].tick,
                after: w[1].tick,
            });
        }
    }
    for s in states {
        let tick = s.tick;
        let muscles: Vec<&String> = s.muscles.iter().map(|m| &m.name).collect();
        if muscles.len() != meta.muscles.len()
            || muscles.iter().zip(&meta.muscles).any(|(a, b)| *a != b)
        {
            return Err(CheckError::StateMuscles {
                tick,
                found: s.muscles.iter().map(|m| m.name.clone()).collect(),
                expected: meta.muscles.clone(),
            });
        }
        if s.joint != meta.joints {
            return Err(CheckError::StateJoints {
                tick,
                found: s.joint.clone(),
                expected: meta.joints.clone(),
            });
        }
        let not_finite =
            |name: &String, field: &'static str, value: f64| CheckError::StateNotFinite {
                tick,
                name: name.clone(),
                field,
                value,
            };
        for m in &s.muscles {
            for (f, v) in MuscleSnapshot::FIELDS.iter().zip(m.state.values()) {
                if !v.is_finite() {
                    return Err(not_finite(&m.name, f, v));
                }
            }
        }
        for (name, j) in s.joint.iter().zip(&s.joints) {
            for (f, v) in JointSnapshot::FIELDS.iter().zip(j.values()) {
                if !v.is_finite() {
                    return Err(not_finite(name, f, v));
                }
            }
        }
        if let Some(&value) = s.stiffness_matrix.iter().find(|v| !v.is_finite()) {
            return Err(CheckError::StiffnessNotFinite { tick, value });
        }
    }
    Ok(())
}

/// Inputs in tick order with one value per name.
pub(super) fn check_inputs(
    what: &'static str,
    inputs: &[(u64, Vec<String>, Vec<f64>)],
) -> Result<(), CheckError> {
    for w in inputs.windows(2) {
        if w[1].0 < w[0].0 {
            return Err(CheckError::InputsOutOfOrder {
                what,
                tick: w[1].0,
                before: w[0].0,
            });
        }
    }
    for (tick, names, values) in inputs {
        if names.len() != values.len() {
            return Err(CheckError::InputLengths {
                what,
                tick: *tick,
                names: names.len(),
                values: values.len(),
            });
        }
        if let Some((n, v)) = names.iter().zip(values).find(|(_, v)| !v.is_finite()) {
            return Err(CheckError::InputNotFinite {
                what,
                tick: *tick,
                name: n.clone(),
                value: *v,
            });
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
) -> Result<(), CheckError> {
    let Some(last) = states.last().map(|s| s.tick) else {
        return Ok(());
    };
    if last > MAX_RECORDED_TICKS {
        return Err(CheckError::TooManyTicks { last });
    }
    let simulated = last as f64 / meta.rate_hz;
    let allowed = recorded_span_s * SPAN_SLACK_FACTOR + SPAN_SLACK_S;
    if simulated > allowed {
        return Err(CheckError::LongerThanRecorded {
            last,
            simulated_s: simulated,
            rate_hz: meta.rate_hz,
            recorded_s: recorded_span_s,
        });
    }
    Ok(())
}

/// The `MuscleState` of every recorded `ActuatorState` schema has this version's fields: an
/// older recording (one made before the energetics fields, say) is refused with the fields it
/// lacks, not decoded into garbage.
pub(super) fn check_state_schema(rec: &Recording) -> Result<(), CheckError> {
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
            let missing = (want.iter())
                .filter(|f| !have.iter().any(|h| h == *f))
                .map(|f| f.to_string())
                .collect();
            return Err(CheckError::OtherVersion {
                topic: ch.topic.clone(),
                have: have.len(),
                want: want.len(),
                missing,
            });
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
        let e = check_state_schema(&with_state_schema(&older))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("lacks metabolic_power, activation_heat_rate"),
            "{e}"
        );
        assert!(e.contains("another version"), "{e}");
        // A schema without the MuscleState section at all.
        let e = check_state_schema(&with_state_schema("float64 x\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("has 0 fields"), "{e}");
    }
}
