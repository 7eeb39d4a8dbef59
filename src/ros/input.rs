//! Validation of incoming commands (SPEC.md "Bad input"): a command with unknown names,
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

/// Why a command was rejected.
#[derive(Debug, Clone, PartialEq)]
pub enum Rejection {
    /// The two arrays differ in length.
    LengthMismatch { names: usize, values: usize },
    /// A name that the actuator does not have.
    UnknownName { name: String, known: Vec<String> },
    /// The same name twice in one command.
    DuplicateName(String),
    /// A NaN or infinite value.
    NonFinite { name: String, value: f64 },
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
                write!(f, "unknown name {name:?} (known: {})", known.join(", "))
            }
            Rejection::DuplicateName(n) => write!(f, "name {n:?} given twice"),
            Rejection::NonFinite { name, value } => {
                write!(f, "value for {name:?} is {value}: must be finite")
            }
            Rejection::Empty => write!(f, "no names given"),
        }
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
                name: n.clone(),
                known: known.to_vec(),
            })?;
        if idx.contains(&i) {
            return Err(Rejection::DuplicateName(n.clone()));
        }
        if !v.is_finite() {
            return Err(Rejection::NonFinite {
                name: n.clone(),
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

    #[test]
    fn load_rules() {
        let known = s(&["elbow"]);
        let ok = validate_load(&s(&["elbow"]), &[-3.0], &known).unwrap();
        assert_eq!(ok.values, vec![(0, -3.0)]);
        assert!(validate_load(&s(&["knee"]), &[1.0], &known).is_err());
        assert!(validate_load(&s(&["elbow"]), &[f64::NEG_INFINITY], &known).is_err());
    }
}
