//! Why a configuration's TOML does not fit the schema ([`super::parse`], [`super::pair`]): the
//! reason inside [`super::ConfigError::Parse`], which names the file.

use crate::text::excerpt;

/// What is wrong with a configuration's TOML; reasons quoted from the parser are kept as text.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ParseError {
    /// The text is not TOML.
    #[error("{0}")]
    Toml(
        /// The parser's message, with its line and column.
        String,
    ),
    /// A top-level key other than `joint`, `muscle` and `stepper`.
    #[error("unknown key {:?}: expected `joint`, `muscle` and `stepper`", excerpt(.0))]
    UnknownKey(
        /// The key.
        String,
    ),
    /// The `[stepper]` table does not read (not a table, an unknown key, a value of the wrong
    /// type).
    #[error("stepper: {reason}")]
    Stepper {
        /// The parser's reason.
        reason: String,
    },
    /// An entry of the `[[joint]]` array is not a joint.
    #[error("joint[{index}]: {reason}")]
    Joint {
        /// Its index.
        index: usize,
        /// The parser's reason.
        reason: String,
    },
    /// `joint` is neither a table nor an array of tables.
    #[error("`joint` must be a table or an array of tables")]
    JointNotATable,
    /// The single `[joint]` table is not a joint.
    #[error("joint: {reason}")]
    PairJoint {
        /// The parser's reason.
        reason: String,
    },
    /// A number of the single `[joint]` table (`radius`, `path_length`) is not a number.
    #[error("joint.{key}: {reason}")]
    PairValue {
        /// The key.
        key: &'static str,
        /// The parser's reason.
        reason: String,
    },
    /// A pulley radius or common path length with muscles that have spans.
    #[error(
        "joint.radius and joint.path_length belong to the antagonistic pair \
         (muscles without spans); with [[muscle.span]] give each muscle its \
         moment arms and path_length"
    )]
    PairKeysWithSpans,
    /// `muscle` is not an array of tables.
    #[error("`muscle` must be an array of tables ([[muscle]])")]
    MusclesNotAnArray,
    /// An entry of the `[[muscle]]` array is not a table.
    #[error("muscle[{index}] must be a table")]
    MuscleNotATable {
        /// Its index.
        index: usize,
    },
    /// A muscle's `name` is not a string.
    #[error("muscle[{index}].name must be a string, found {}", excerpt(.found))]
    MuscleNameNotAString {
        /// The muscle's index.
        index: usize,
        /// The value found, as TOML.
        found: String,
    },
    /// A muscle without `name`.
    #[error("muscle[{index}] has no name")]
    MuscleWithoutName {
        /// Its index.
        index: usize,
    },
    /// A value of a named muscle does not read: its `path_length`, its `span` array, or its
    /// parameters (`key` None).
    #[error("muscle {:?}: {}{reason}", excerpt(.muscle), key_prefix(*.key))]
    MuscleValue {
        /// The muscle's name.
        muscle: String,
        /// The key (`path_length`, `span`), None for the parameters.
        key: Option<&'static str>,
        /// The parser's reason.
        reason: String,
    },
}

/// `KEY: `, or nothing.
fn key_prefix(key: Option<&str>) -> String {
    key.map_or_else(String::new, |k| format!("{k}: "))
}

#[cfg(test)]
mod tests {
    use crate::config::{ActuatorConfig, ConfigError, ParseError};
    use std::path::Path;

    /// A shape error keeps its variant and the message its text, named by the file.
    #[test]
    fn shape_errors_are_typed_with_the_same_text() {
        let e = ActuatorConfig::from_toml_str("[[muscle]]\nf_max = 1.0\n").unwrap_err();
        assert!(matches!(
            e,
            ConfigError::Parse {
                error: ParseError::MuscleWithoutName { index: 0 },
                ..
            }
        ));
        assert_eq!(
            e.to_string(),
            "configuration file <text>: muscle[0] has no name"
        );
        let e = ActuatorConfig::from_toml_str("[[muscle]]\nname = \"m\"\nf_max = \"x\"\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("configuration file <text>: muscle \"m\": "),
            "{e}"
        );
        let e = ActuatorConfig::from_toml_str("[joint]\nradius = \"r\"\n").unwrap_err();
        assert!(matches!(
            e,
            ConfigError::Parse {
                error: ParseError::PairValue { key: "radius", .. },
                ..
            }
        ));
    }

    /// A missing file is told apart from one that does not read.
    #[test]
    fn a_missing_file_is_not_found() {
        let e = ActuatorConfig::from_file(Path::new("/nonexistent/actuator.toml")).unwrap_err();
        assert!(e.is_not_found(), "{e}");
        assert!(e.to_string().contains("(built-in configurations: "), "{e}");
        let e = ActuatorConfig::from_file(Path::new("/")).unwrap_err();
        assert!(
            matches!(e, ConfigError::Io { .. }) && !e.is_not_found(),
            "{e}"
        );
    }
}
