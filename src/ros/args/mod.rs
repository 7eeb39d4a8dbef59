//! The standard ROS 2 command-line arguments, as `rcl` reads them (rcl's `arguments.c`):
//! `--ros-args -r __ns:=/ns -r __node:=name -r from:=to -p name:=value --params-file f.yaml
//! --log-level [logger:=]level [--]`. Parameter values and files follow `params_file.rs`;
//! names, namespaces and remapping follow `names.rs`.

mod error;
mod names;
mod params_file;

pub use error::{ArgsError, FlowTooDeep, ParamsFileError, ValueError};
pub use names::{
    check_name, check_node_name, expand, normalise_namespace, resolve, NameError, Remap,
    DEFAULT_NODE_NAME,
};
pub use params_file::{parse_param_rule, read_params_file};

use super::severity::Severity;
use muscle_actuator_core::text::excerpt;
use ros2_client::ParameterValue;
use std::path::Path;

/// A parameter assignment from `-p` or a parameters file, in command-line order.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamAssignment {
    pub name: String,
    pub value: ParameterValue,
    /// Where it came from, for error messages (`-p` or the file name).
    pub source: String,
}

/// The parsed command line of `muscle_actuator node`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RosArgs {
    /// `-r __ns:=...`: the node's namespace (absolute, normalised).
    pub namespace: Option<String>,
    /// `-r __node:=...` (or `__name`): the node's name.
    pub node_name: Option<String>,
    /// Topic and service remaps, in order (the first match wins).
    pub remaps: Vec<Remap>,
    /// Parameter assignments in order (later ones win).
    pub params: Vec<ParamAssignment>,
    /// `--log-level`.
    pub log_level: Option<Severity>,
    /// `--disable-rosout-logs`.
    pub disable_rosout: bool,
    /// `--disable-stdout-logs`.
    pub disable_stdout: bool,
    /// `-h` / `--help` outside `--ros-args`.
    pub help: bool,
}

/// Width of `node --help`'s parameter lines, columns (as its widest fixed line).
const USAGE_WIDTH: usize = 92;

/// Usage text of `muscle_actuator node`: the parameters from
/// [`PARAMETERS`](super::params::PARAMETERS).
pub fn usage() -> String {
    format!(
        "\
usage: muscle_actuator node [--ros-args [-r __ns:=/NS] [-r __node:=NAME] [-r FROM:=TO]...
                             [-p NAME:=VALUE]... [--params-file FILE.yaml]...
                             [--log-level [LOGGER:=]LEVEL] [--]]

{parameters}
environment: ROS_DOMAIN_ID (default 0); ROS_AUTOMATIC_DISCOVERY_RANGE=SUBNET to discover
             beyond this host (default: loopback only)",
        parameters = super::params::table::usage(USAGE_WIDTH),
    )
}

impl RosArgs {
    /// Parses everything after `node` on the command line. Parameter files are read here.
    pub fn parse(args: &[String]) -> Result<Self, ArgsError> {
        let mut out = RosArgs::default();
        let mut i = 0;
        let mut in_ros = false;
        while i < args.len() {
            let a = args[i].as_str();
            if !in_ros {
                match a {
                    "--ros-args" => in_ros = true,
                    "-h" | "--help" => out.help = true,
                    other => {
                        return Err(ArgsError::Unexpected {
                            arg: excerpt(other),
                        })
                    }
                }
                i += 1;
                continue;
            }
            let mut value = |flag: &str| -> Result<String, ArgsError> {
                i += 1;
                args.get(i).cloned().ok_or_else(|| ArgsError::MissingValue {
                    flag: flag.to_string(),
                })
            };
            match a {
                "--" => in_ros = false,
                "--ros-args" => {}
                "-r" | "--remap" => {
                    let rule = value(a)?;
                    out.add_remap(&rule)?;
                }
                "-p" | "--param" => {
                    let rule = value(a)?;
                    out.params.push(parse_param_rule(&rule)?);
                }
                "--params-file" => {
                    let file = value(a)?;
                    out.params.push(ParamAssignment {
                        name: String::new(),
                        value: ParameterValue::String(file),
                        source: PARAMS_FILE_MARK.into(),
                    });
                }
                "--log-level" => out.log_level = Some(parse_log_level(&value(a)?)?),
                "-e" | "--enclave" => {
                    value(a)?;
                }
                "--disable-rosout-logs" => out.disable_rosout = true,
                "--enable-rosout-logs" => out.disable_rosout = false,
                "--disable-stdout-logs" => out.disable_stdout = true,
                "--enable-stdout-logs" => out.disable_stdout = false,
                "--disable-external-lib-logs" | "--enable-external-lib-logs" => {}
                other => {
                    return Err(ArgsError::Unknown {
                        arg: excerpt(other),
                    })
                }
            }
            i += 1;
        }
        Ok(out)
    }

    fn add_remap(&mut self, rule: &str) -> Result<(), ArgsError> {
        let quoted = || excerpt(rule);
        let (lhs, to) = rule
            .split_once(":=")
            .ok_or_else(|| ArgsError::RemapSyntax { rule: quoted() })?;
        // An optional `node:` prefix (a name has no ':' otherwise).
        let (node, from) = match lhs.split_once(':') {
            Some((n, f)) => (Some(n.to_string()), f),
            None => (None, lhs),
        };
        if from.is_empty() || to.is_empty() {
            return Err(ArgsError::RemapEmpty { rule: quoted() });
        }
        let bad_name = |source| ArgsError::BadName {
            rule: quoted(),
            source,
        };
        match from {
            "__ns" => {
                let ns = normalise_namespace(to).map_err(|source| ArgsError::BadNamespace {
                    rule: quoted(),
                    source,
                })?;
                self.push_node_rule(node, |s| s.namespace = Some(ns));
            }
            "__node" | "__name" => {
                check_node_name(to).map_err(|source| ArgsError::BadNodeName {
                    rule: quoted(),
                    source,
                })?;
                let name = to.to_string();
                self.push_node_rule(node, |s| s.node_name = Some(name));
            }
            _ => {
                check_name(from).map_err(bad_name)?;
                check_name(to).map_err(bad_name)?;
                self.remaps.push(Remap {
                    node,
                    from: from.into(),
                    to: to.into(),
                });
            }
        }
        Ok(())
    }

    fn push_node_rule(&mut self, node: Option<String>, apply: impl FnOnce(&mut Self)) {
        // A node-prefixed __ns/__node rule applies only to a node of that name; ours is the
        // default name unless renamed, so compare with the default.
        match node {
            Some(n) if n != DEFAULT_NODE_NAME => {}
            _ => apply(self),
        }
    }

    /// The parameter assignments with every `--params-file` expanded for the node `fqn`
    /// (its fully qualified name) in command-line order.
    pub fn resolved_params(&self, fqn: &str) -> Result<Vec<ParamAssignment>, ParamsFileError> {
        let mut out = Vec::new();
        for p in &self.params {
            if p.source == PARAMS_FILE_MARK {
                if let ParameterValue::String(file) = &p.value {
                    out.extend(read_params_file(Path::new(file), fqn)?);
                }
            } else {
                out.push(p.clone());
            }
        }
        Ok(out)
    }
}

/// The `source` of a `--params-file` entry in [`RosArgs::params`] (its value is the file name).
const PARAMS_FILE_MARK: &str = "\u{0}params-file";

/// `--log-level level` or `--log-level logger:=level`; every logger of this process is the
/// node's.
fn parse_log_level(spec: &str) -> Result<Severity, ArgsError> {
    let level = spec.rsplit_once(":=").map(|(_, l)| l).unwrap_or(spec);
    Severity::parse(level).ok_or_else(|| ArgsError::LogLevel {
        spec: excerpt(spec),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn parses_the_standard_arguments() {
        let a = RosArgs::parse(&args(
            "--ros-args -r __ns:=/lab/arm -r __node:=elbow_sim -r ~/state:=/st \
             -p model:=hill -p rate_hz:=500 -p publish_rate_hz:=100.0 -p record:=false \
             --log-level WARN --",
        ))
        .unwrap();
        assert_eq!(a.namespace.as_deref(), Some("/lab/arm"));
        assert_eq!(a.node_name.as_deref(), Some("elbow_sim"));
        assert_eq!(a.remaps.len(), 1);
        assert_eq!(a.params.len(), 4);
        assert_eq!(a.params[0].value, ParameterValue::String("hill".into()));
        assert_eq!(a.params[1].value, ParameterValue::Integer(500));
        assert_eq!(a.params[2].value, ParameterValue::Double(100.0));
        assert_eq!(a.params[3].value, ParameterValue::Boolean(false));
        assert_eq!(a.log_level, Some(Severity::Warn));
    }

    #[test]
    fn rejects_bad_arguments_with_a_reason() {
        for bad in [
            "--bogus",
            "--ros-args -r nothing",
            "--ros-args -p novalue",
            "--ros-args -p",
            "--ros-args --log-level loud",
            "--ros-args -r __ns:=/bad-name",
            "--ros-args -r __node:=9x",
            "--ros-args --frobnicate",
        ] {
            let e = RosArgs::parse(&args(bad)).unwrap_err().to_string();
            assert!(!e.is_empty(), "{bad}");
        }
    }

    /// Oversized arguments are refused with the rule they break, quoted as short excerpts.
    #[test]
    fn oversized_arguments_are_refused_briefly() {
        let long = |prefix: &str, n: usize| {
            vec![
                "--ros-args".to_string(),
                "-r".into(),
                format!("{prefix}{}", "n".repeat(n)),
            ]
        };
        let e = RosArgs::parse(&long("__node:=", 10_000))
            .unwrap_err()
            .to_string();
        assert!(e.contains("at most 255") && e.len() < 300, "{e}");
        assert!(RosArgs::parse(&long("__node:=", 255)).is_ok());
        let e = RosArgs::parse(&long("__ns:=/", 300))
            .unwrap_err()
            .to_string();
        assert!(e.contains("at most 245") && e.len() < 300, "{e}");
        let e = RosArgs::parse(&long("state:=", 300))
            .unwrap_err()
            .to_string();
        assert!(e.contains("at most 247") && e.len() < 300, "{e}");
        let deep = format!("x:={}{}", "[".repeat(100_000), "]".repeat(100_000));
        let e = RosArgs::parse(&["--ros-args".into(), "-p".into(), deep])
            .unwrap_err()
            .to_string();
        assert!(e.contains("nested deeper than 64") && e.len() < 300, "{e}");
        let e = RosArgs::parse(&["--ros-args".into(), "--bogus".into(), "b".repeat(1 << 20)])
            .unwrap_err()
            .to_string();
        assert!(e.len() < 300, "{e}");
    }
}
