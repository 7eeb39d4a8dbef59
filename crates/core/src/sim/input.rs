//! Validation of incoming commands (docs/robustness.md): a command with unknown names,
//! mismatched array lengths, or NaN/infinite values is rejected whole; excitations outside
//! [0, 1] are clamped and reported. Pure functions: no DDS here.

use std::fmt;

/// A command that passed validation, ready for the tick loop.
#[derive(Debug, Clone, PartialEq)]
pub struct Accepted {
    /// (index into the actuator's names, value), in the command's order.
    pub values: Vec<(usize, f64)>,
    /// Names whose value was clamped, with the value received.
    pub clamped: Vec<(String, f64)>,
}

/// Why a command was rejected. Names from the command are kept as short excerpts
/// ([`quote`]): a rejection is logged, counted and shown in `/diagnostics`, and a hostile name may
/// be megabytes long.
#[derive(Debug, Clone, PartialEq)]
pub enum Rejection {
    /// The two arrays differ in length.
    LengthMismatch {
        /// Length of the names array.
        names: usize,
        /// Length of the values array.
        values: usize,
    },
    /// A name that the actuator does not have (quoted).
    UnknownName {
        /// The name, quoted.
        name: String,
        /// The actuator's names.
        known: Vec<String>,
    },
    /// The same name twice in one command.
    DuplicateName(String),
    /// A NaN or infinite value.
    NonFinite {
        /// The name the value was sent for, quoted.
        name: String,
        /// The value received.
        value: f64,
    },
    /// No entries at all.
    Empty,
}

impl Rejection {
    /// A short key for counting rejections by kind.
    pub fn kind(&self) -> &'static str {
        match self {
            Rejection::LengthMismatch { .. } => "length_mismatch",
            Rejection::UnknownName { .. } => "unknown_name",
            Rejection::DuplicateName(_) => "duplicate_name",
            Rejection::NonFinite { .. } => "non_finite",
            Rejection::Empty => "empty",
        }
    }
}

impl fmt::Display for Rejection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rejection::LengthMismatch { names, values } => write!(
                f,
                "{names} names but {values} values: the arrays must have the same length"
            ),
            Rejection::UnknownName { name, known } => {
                const SHOWN: usize = 16;
                write!(f, "unknown name {name} (known: ")?;
                write!(f, "{}", known[..known.len().min(SHOWN)].join(", "))?;
                if known.len() > SHOWN {
                    write!(f, " and {} more", known.len() - SHOWN)?;
                }
                write!(f, ")")
            }
            Rejection::DuplicateName(n) => write!(f, "name {n} given twice"),
            Rejection::NonFinite { name, value } => {
                write!(f, "value for {name} is {value}: must be finite")
            }
            Rejection::Empty => write!(f, "no names given"),
        }
    }
}

/// A user-supplied name as the log and the diagnostics show it: quoted, at most 64 characters,
/// with its length when it was cut.
pub fn quote(name: &str) -> String {
    let e = crate::text::excerpt(name);
    if e.len() == name.len() {
        format!("{name:?}")
    } else {
        format!("{e:?} ({} bytes)", name.len())
    }
}

fn common(names: &[String], values: &[f64], known: &[String]) -> Result<Vec<usize>, Rejection> {
    if names.len() != values.len() {
        return Err(Rejection::LengthMismatch {
            names: names.len(),
            values: values.len(),
        });
    }
    if names.is_empty() {
        return Err(Rejection::Empty);
    }
    let mut idx = Vec::with_capacity(names.len());
    for (n, v) in names.iter().zip(values) {
        let i = known
            .iter()
            .position(|k| k == n)
            .ok_or_else(|| Rejection::UnknownName {
                name: quote(n),
                known: known.to_vec(),
            })?;
        if idx.contains(&i) {
            return Err(Rejection::DuplicateName(quote(n)));
        }
        if !v.is_finite() {
            return Err(Rejection::NonFinite {
                name: quote(n),
                value: *v,
            });
        }
        idx.push(i);
    }
    Ok(idx)
}

/// Validates an activation command against the actuator's muscle names.
pub fn validate_activation(
    muscles: &[String],
    excitation: &[f64],
    known: &[String],
) -> Result<Accepted, Rejection> {
    let idx = common(muscles, excitation, known)?;
    let mut values = Vec::with_capacity(idx.len());
    let mut clamped = Vec::new();
    for ((i, u), name) in idx.into_iter().zip(excitation).zip(muscles) {
        let c = u.clamp(0.0, 1.0);
        if c != *u {
            clamped.push((name.clone(), *u));
        }
        values.push((i, c));
    }
    Ok(Accepted { values, clamped })
}

/// Validates an external load against the actuator's joint names.
pub fn validate_load(
    joints: &[String],
    torque: &[f64],
    known: &[String],
) -> Result<Accepted, Rejection> {
    let idx = common(joints, torque, known)?;
    Ok(Accepted {
        values: idx.into_iter().zip(torque.iter().copied()).collect(),
        clamped: vec![],
    })
}

/// A `JointState` for the driven joints, checked: `(joint index, angle rad, velocity rad/s)` for
/// each driven joint it names, in the message's order. `driven` is (joint index, name) of every
/// driven joint. Other joints in the message (a robot simulator publishes all of its own) are
/// ignored; `Ok(vec![])` when it names none of the driven joints. Refused whole: arrays whose
/// lengths do not match the names (`velocity` may be empty: 0 rad/s), a name twice, a non-finite
/// angle or velocity of a driven joint.
pub fn validate_joint_motion(
    names: &[String],
    position: &[f64],
    velocity: &[f64],
    driven: &[(usize, String)],
) -> Result<Vec<(usize, f64, f64)>, Rejection> {
    if position.len() != names.len() {
        return Err(Rejection::LengthMismatch {
            names: names.len(),
            values: position.len(),
        });
    }
    if !velocity.is_empty() && velocity.len() != names.len() {
        return Err(Rejection::LengthMismatch {
            names: names.len(),
            values: velocity.len(),
        });
    }
    let mut out = Vec::new();
    for (k, name) in names.iter().enumerate() {
        if names[..k].contains(name) {
            return Err(Rejection::DuplicateName(quote(name)));
        }
        let Some((j, _)) = driven.iter().find(|(_, n)| n == name) else {
            continue;
        };
        let (angle, speed) = (position[k], velocity.get(k).copied().unwrap_or(0.0));
        for v in [angle, speed] {
            if !v.is_finite() {
                return Err(Rejection::NonFinite {
                    name: quote(name),
                    value: v,
                });
            }
        }
        out.push((*j, angle, speed));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(v: &[&str]) -> Vec<String> {
        v.iter().map(|x| x.to_string()).collect()
    }

    #[test]
    fn activation_rules() {
        let known = s(&["flexor", "extensor"]);
        let ok = validate_activation(&s(&["extensor", "flexor"]), &[0.25, 1.0], &known).unwrap();
        assert_eq!(ok.values, vec![(1, 0.25), (0, 1.0)]);
        assert!(ok.clamped.is_empty());

        let c = validate_activation(&s(&["flexor", "extensor"]), &[1.5, -0.1], &known).unwrap();
        assert_eq!(c.values, vec![(0, 1.0), (1, 0.0)]);
        assert_eq!(c.clamped.len(), 2);

        let e = validate_activation(&s(&["flexor"]), &[0.1, 0.2], &known).unwrap_err();
        assert_eq!(e.kind(), "length_mismatch");
        let e = validate_activation(&s(&["biceps"]), &[0.1], &known).unwrap_err();
        assert_eq!(e.kind(), "unknown_name");
        assert!(e.to_string().contains("biceps"));
        let e = validate_activation(&s(&["flexor"]), &[f64::NAN], &known).unwrap_err();
        assert_eq!(e.kind(), "non_finite");
        let e = validate_activation(&s(&["flexor"]), &[f64::INFINITY], &known).unwrap_err();
        assert_eq!(e.kind(), "non_finite");
        let e = validate_activation(&s(&["flexor", "flexor"]), &[0.1, 0.2], &known).unwrap_err();
        assert_eq!(e.kind(), "duplicate_name");
        let e = validate_activation(&[], &[], &known).unwrap_err();
        assert_eq!(e.kind(), "empty");
        // Rejected whole: a bad entry after a good one still rejects.
        let e = validate_activation(&s(&["flexor", "x"]), &[0.5, 0.5], &known).unwrap_err();
        assert_eq!(e.kind(), "unknown_name");
    }

    /// A hostile name is quoted as a short excerpt with its length, never whole.
    #[test]
    fn rejections_quote_names_briefly() {
        let known = s(&["flexor", "extensor"]);
        let huge = "x".repeat(1 << 20);
        for e in [
            validate_activation(std::slice::from_ref(&huge), &[0.5], &known).unwrap_err(),
            validate_activation(&s(&["flexor"]), &[0.5, 0.1], &known).unwrap_err(),
        ] {
            assert!(e.to_string().len() < 200, "{} bytes", e.to_string().len());
        }
        let e = validate_activation(&[huge], &[0.5], &known).unwrap_err();
        assert!(e.to_string().contains("(1048576 bytes)"), "{e}");
        let many: Vec<String> = (0..100).map(|i| format!("m{i}")).collect();
        let e = validate_load(&s(&["knee"]), &[1.0], &many).unwrap_err();
        assert!(e.to_string().ends_with("m15 and 84 more)"), "{e}");
    }

    #[test]
    fn load_rules() {
        let known = s(&["elbow"]);
        let ok = validate_load(&s(&["elbow"]), &[-3.0], &known).unwrap();
        assert_eq!(ok.values, vec![(0, -3.0)]);
        assert!(validate_load(&s(&["knee"]), &[1.0], &known).is_err());
        assert!(validate_load(&s(&["elbow"]), &[f64::NEG_INFINITY], &known).is_err());
    }

    #[test]
    fn joint_states_for_driven_joints() {
        let names = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let driven = vec![(1, "elbow".to_string())];
        // Other joints are ignored; the driven one is taken by name.
        let ok = validate_joint_motion(
            &names(&["shoulder", "elbow"]),
            &[0.3, -0.2],
            &[1.0, 2.0],
            &driven,
        )
        .unwrap();
        assert_eq!(ok, vec![(1, -0.2, 2.0)]);
        // No velocity: at rest.
        let ok = validate_joint_motion(&names(&["elbow"]), &[0.1], &[], &driven).unwrap();
        assert_eq!(ok, vec![(1, 0.1, 0.0)]);
        // None of ours: nothing.
        assert!(
            validate_joint_motion(&names(&["knee"]), &[0.1], &[0.0], &driven)
                .unwrap()
                .is_empty()
        );
        for (n, p, v, kind) in [
            (names(&["elbow"]), vec![f64::NAN], vec![0.0], "non_finite"),
            (
                names(&["elbow"]),
                vec![0.0],
                vec![f64::INFINITY],
                "non_finite",
            ),
            (names(&["elbow", "x"]), vec![0.0], vec![], "length_mismatch"),
            (
                names(&["elbow"]),
                vec![0.0],
                vec![1.0, 2.0],
                "length_mismatch",
            ),
            (
                names(&["elbow", "elbow"]),
                vec![0.0, 0.1],
                vec![],
                "duplicate_name",
            ),
        ] {
            assert_eq!(
                validate_joint_motion(&n, &p, &v, &driven)
                    .unwrap_err()
                    .kind(),
                kind
            );
        }
        // A NaN on a joint that is not driven is not ours to judge.
        assert!(validate_joint_motion(&names(&["knee"]), &[f64::NAN], &[], &driven).is_ok());
    }
}
