//! Why the node's command line cannot be read: an argument, a remap rule, a `-p` value or a
//! parameters file. Quoted user text is an excerpt ([`muscle_actuator_core::text::excerpt`]), so that every
//! message stays one short line.

use super::names::NameError;
use muscle_actuator_core::physics::models::MODELS;

/// Why a command-line argument of `muscle_actuator node` is refused.
#[derive(Debug, thiserror::Error)]
pub enum ArgsError {
    /// An argument before `--ros-args` other than `-h`/`--help`.
    #[error(
        "unexpected argument {arg:?}: ROS arguments go after --ros-args \
         (try `muscle_actuator node --help`)"
    )]
    Unexpected {
        /// The argument, as an excerpt.
        arg: String,
    },
    /// A flag at the end of the line, without its value.
    #[error("{flag} needs a value")]
    MissingValue {
        /// The flag as written (`-r`, `--param`, ...).
        flag: String,
    },
    /// An argument after `--ros-args` that ROS does not define.
    #[error("unknown ROS argument {arg:?} (expected -r, -p, --params-file, --log-level, --)")]
    Unknown {
        /// The argument, as an excerpt.
        arg: String,
    },
    /// A `-r` rule without `:=`.
    #[error("-r {rule:?}: expected FROM:=TO")]
    RemapSyntax {
        /// The rule, as an excerpt.
        rule: String,
    },
    /// A `-r` rule with an empty side.
    #[error("-r {rule:?}: empty name")]
    RemapEmpty {
        /// The rule, as an excerpt.
        rule: String,
    },
    /// A `-r __ns:=...` whose namespace breaks the rules.
    #[error("-r {rule:?}: bad namespace: {source}")]
    BadNamespace {
        /// The rule, as an excerpt.
        rule: String,
        /// The rule broken.
        source: NameError,
    },
    /// A `-r __node:=...` whose node name breaks the rules.
    #[error("-r {rule:?}: bad node name: {source}")]
    BadNodeName {
        /// The rule, as an excerpt.
        rule: String,
        /// The rule broken.
        source: NameError,
    },
    /// A topic or service remap with a side that breaks the rules.
    #[error("-r {rule:?}: bad name: {source}")]
    BadName {
        /// The rule, as an excerpt.
        rule: String,
        /// The rule broken.
        source: NameError,
    },
    /// A `--log-level` that names no severity.
    #[error("--log-level {spec:?}: unknown level (debug, info, warn, error, fatal)")]
    LogLevel {
        /// The level as given, as an excerpt.
        spec: String,
    },
    /// A `-p` rule without `:=`.
    #[error("-p {rule:?}: expected NAME:=VALUE (e.g. -p model:={})", MODELS[0].name)]
    ParamSyntax {
        /// The rule, as an excerpt.
        rule: String,
    },
    /// A `-p` rule with nothing before `:=`.
    #[error("-p {rule:?}: empty parameter name")]
    ParamEmptyName {
        /// The rule, as an excerpt.
        rule: String,
    },
    /// A `-p` value nested too deep to be parsed.
    #[error("-p {rule:?}: {source}")]
    ParamTooDeep {
        /// The rule, as an excerpt.
        rule: String,
        /// The limit.
        source: FlowTooDeep,
    },
    /// A `-p` value that is no parameter value.
    #[error("-p {rule:?}: {source}")]
    ParamValue {
        /// The rule, as an excerpt.
        rule: String,
        /// Why the value is none.
        source: ValueError,
    },
    /// A `--params-file` that cannot be read.
    #[error(transparent)]
    ParamsFile(#[from] ParamsFileError),
}

/// Why a parameters file cannot be used; `file` is its path as an excerpt.
#[derive(Debug, thiserror::Error)]
pub enum ParamsFileError {
    /// Not a regular file of at most 1 MiB, or unreadable.
    #[error("cannot read parameters file {file} (a regular file of at most 1 MiB): {source}")]
    Read {
        /// The file.
        file: String,
        /// Why.
        source: std::io::Error,
    },
    /// Not UTF-8.
    #[error("parameters file {file}: not UTF-8 text")]
    NotUtf8 {
        /// The file.
        file: String,
    },
    /// Nested too deep to be parsed.
    #[error("parameters file {file}: {source}")]
    TooDeep {
        /// The file.
        file: String,
        /// The limit.
        source: FlowTooDeep,
    },
    /// Not YAML.
    #[error("parameters file {file}: not valid YAML: {source}")]
    Yaml {
        /// The file.
        file: String,
        /// The parser's error.
        source: serde_norway::Error,
    },
    /// The document is not a mapping of node names.
    #[error("parameters file {file}: expected `node_name: {{ros__parameters: {{...}}}}`")]
    NotNodeSections {
        /// The file.
        file: String,
    },
    /// A `ros__parameters` at the top, under no node name.
    #[error("parameters file {file}: `ros__parameters` needs a node name above it")]
    NoNodeName {
        /// The file.
        file: String,
    },
    /// A node key that is not a string.
    #[error("parameters file {file}: node keys must be strings")]
    NodeKeyNotString {
        /// The file.
        file: String,
    },
    /// An empty node key.
    #[error("parameters file {file}: empty node key")]
    EmptyNodeKey {
        /// The file.
        file: String,
    },
    /// A plain value where a node's section was expected.
    #[error(
        "parameters file {file}: {name:?} holds a value before any `ros__parameters` \
         (expected `node_name: {{ros__parameters: {{...}}}}`)"
    )]
    ValueBeforeParameters {
        /// The file.
        file: String,
        /// The node name so far, as an excerpt.
        name: String,
    },
    /// A `ros__parameters` that is not a mapping.
    #[error("parameters file {file}: `ros__parameters` must be a mapping")]
    ParametersNotMapping {
        /// The file.
        file: String,
    },
    /// A parameter whose value is no parameter value.
    #[error("parameters file {file}: parameter {name:?}: {source}")]
    Value {
        /// The file.
        file: String,
        /// The parameter's (dotted) name, as an excerpt.
        name: String,
        /// Why the value is none.
        source: ValueError,
    },
}

/// Why a YAML value is no ROS 2 parameter value.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ValueError {
    /// A number neither an `i64` nor an `f64`.
    #[error("number {0} out of range")]
    OutOfRange(String),
    /// `~` or nothing.
    #[error("empty value")]
    Empty,
    /// A sequence of mixed types.
    #[error("an array must hold values of one type")]
    MixedArray,
    /// A mapping.
    #[error("a mapping is not a parameter value")]
    Mapping,
}

/// YAML flow collections nested deeper than the limit, refused before parsing.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("nested deeper than {max} levels of [ ] or {{ }}")]
pub struct FlowTooDeep {
    /// The deepest nesting allowed (`params_file::MAX_FLOW_DEPTH`).
    pub max: usize,
}
