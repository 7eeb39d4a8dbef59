//! A value given for a parameter (by `-p`, a parameters file, the parameter services or the live
//! view), read as its type: the checks every parameter of a type shares, with their one-line
//! errors.

use super::error::ParameterError;
use super::limits::{MAX_NAME_CHARS, MAX_PATH_BYTES};
use muscle_actuator_core::text::excerpt;
use ros2_client::ParameterValue;

/// A parameter's ROS type; strings are limited by what they hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Bool,
    Integer,
    Double,
    /// A name (a model, a clock mode): at most [`MAX_NAME_CHARS`] characters.
    Name,
    /// A path: at most [`MAX_PATH_BYTES`] bytes.
    Path,
}

impl Kind {
    /// The type as docs/ros-interface.md writes it.
    #[cfg(test)]
    pub fn doc_name(self) -> &'static str {
        match self {
            Kind::Bool => "bool",
            Kind::Integer => "integer",
            Kind::Double => "double",
            Kind::Name | Kind::Path => "string",
        }
    }
}

/// A value for parameter `name` of type `kind`; `lenient` (start-up values from `-p` and files) also accepts an
/// integer for a double.
pub struct Given<'a> {
    pub name: &'static str,
    pub kind: Kind,
    pub value: &'a ParameterValue,
    pub lenient: bool,
}

impl Given<'_> {
    /// A double parameter's value.
    pub fn double(&self) -> Result<f64, ParameterError> {
        match self.value {
            ParameterValue::Double(d) => Ok(*d),
            ParameterValue::Integer(i) if self.lenient => Ok(*i as f64),
            other => Err(ParameterError::NotDouble {
                name: self.name,
                got: Self::describe(other),
            }),
        }
    }

    /// A string parameter's value: a name ([`Kind::Name`]) of at most [`MAX_NAME_CHARS`]
    /// characters, a path of at most [`MAX_PATH_BYTES`] bytes.
    pub fn string(&self) -> Result<String, ParameterError> {
        let name = self.name;
        match self.value {
            ParameterValue::String(s) => {
                let (limit, too_long) = if self.kind == Kind::Name {
                    ("64 characters", s.chars().count() > MAX_NAME_CHARS)
                } else {
                    ("4096 bytes", s.len() > MAX_PATH_BYTES)
                };
                if too_long {
                    return Err(ParameterError::TooLong {
                        name,
                        bytes: s.len(),
                        limit,
                        excerpt: excerpt(s),
                    });
                }
                Ok(s.clone())
            }
            other => Err(ParameterError::NotString {
                name,
                got: Self::describe(other),
            }),
        }
    }

    /// A value as an error message names it (long strings as excerpts).
    pub fn describe(v: &ParameterValue) -> String {
        match v {
            ParameterValue::NotSet => "nothing (not set)".into(),
            ParameterValue::Boolean(b) => format!("bool {b}"),
            ParameterValue::Integer(i) => format!("integer {i}"),
            ParameterValue::Double(d) => format!("double {d}"),
            ParameterValue::String(s) => format!("string {:?}", excerpt(s)),
            other => excerpt(&format!("{other:?}")),
        }
    }
}
