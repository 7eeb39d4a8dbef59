//! What the command line asks of the node, resolved before DDS starts: name, namespace, the
//! parameters (defaults, then `--params-file`, then `-p`, as rcl applies them) and the other ROS
//! arguments.

use super::args::DEFAULT_NODE_NAME;
use super::args::{self, ArgsError, RosArgs};
use super::params::{self, NodeParams, ParameterError};

/// Why the command line gives no set-up.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// An argument, a remap rule, a `-p` value or a parameters file is refused.
    #[error(transparent)]
    Args(#[from] ArgsError),
    /// `use_sim_time` given a value other than a bool.
    #[error("{from}: use_sim_time must be a bool")]
    UseSimTimeNotBool {
        /// Where the value came from (`-p ...` or the file).
        from: String,
    },
    /// A declared parameter given a value it refuses.
    #[error("{from}: {source}")]
    Parameter {
        /// Where the value came from (`-p ...` or the file).
        from: String,
        /// Why it is refused.
        source: ParameterError,
    },
}

/// Everything the node needs, resolved from the command line before DDS starts.
#[derive(Debug)]
pub(crate) struct Setup {
    pub(crate) namespace: String,
    pub(crate) name: String,
    pub(crate) fqn: String,
    pub(crate) params: NodeParams,
    /// The standard `use_sim_time` (start-up value): with `clock` wall, follow `/clock`.
    pub(crate) use_sim_time: bool,
    pub(crate) ros_args: RosArgs,
    /// Notes on the undeclared parameters ignored, logged at debug level once the logger
    /// exists.
    pub(crate) ignored: Vec<String>,
}

/// The set-up `argv` asks for; `None` after printing the usage for `--help`.
pub(crate) fn setup(argv: &[String]) -> Result<Option<Setup>, SetupError> {
    let ros_args = RosArgs::parse(argv)?;
    if ros_args.help {
        println!("{}", args::usage());
        return Ok(None);
    }
    let namespace = ros_args.namespace.clone().unwrap_or_else(|| "/".into());
    let name = ros_args
        .node_name
        .clone()
        .unwrap_or_else(|| DEFAULT_NODE_NAME.into());
    let fqn = args::expand("~", &namespace, &name);
    let mut p = NodeParams::default();
    let mut ignored = Vec::new();
    let mut use_sim_time = false;
    for a in ros_args.resolved_params(&fqn).map_err(ArgsError::from)? {
        // As rclcpp and rclpy do (without `allow_undeclared_parameters`), a parameter this
        // node does not declare is ignored: a shared file holds other nodes' parameters.
        if a.name != params::table::USE_SIM_TIME && params::spec(&a.name).is_none() {
            ignored.push(format!(
                "ignoring undeclared parameter {:?} (from {})",
                muscle_actuator_core::text::excerpt(&a.name),
                a.source
            ));
            continue;
        }
        if a.name == params::table::USE_SIM_TIME {
            match a.value {
                ros2_client::ParameterValue::Boolean(b) => use_sim_time = b,
                _ => return Err(SetupError::UseSimTimeNotBool { from: a.source }),
            }
            continue;
        }
        p.set(&a.name, &a.value, true)
            .map_err(|source| SetupError::Parameter {
                from: a.source.clone(),
                source,
            })?;
    }
    Ok(Some(Setup {
        namespace,
        name,
        fqn,
        params: p,
        use_sim_time,
        ros_args,
        ignored,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn setup_applies_arguments_in_order() {
        let argv: Vec<String> =
            "--ros-args -r __ns:=/lab -p model:=hill -p rate_hz:=250 -p model:=huxley"
                .split_whitespace()
                .map(String::from)
                .collect();
        let s = setup(&argv).unwrap().unwrap();
        assert_eq!(s.fqn, "/lab/muscle_actuator");
        assert_eq!(s.params.model.name(), "huxley");
        assert_eq!(s.params.rate_hz, 250.0);
        let bad: Vec<String> = "--ros-args -p rate_hz:=-1"
            .split_whitespace()
            .map(String::from)
            .collect();
        assert!(setup(&bad).unwrap_err().to_string().contains("rate_hz"));
        // An undeclared parameter is ignored with a note; a declared one keeps its checks.
        let unknown: Vec<String> = "--ros-args -p colour:=red -p model:=hill"
            .split_whitespace()
            .map(String::from)
            .collect();
        let s = setup(&unknown).unwrap().unwrap();
        assert_eq!(s.params.model.name(), "hill");
        assert_eq!(s.ignored.len(), 1);
        assert!(s.ignored[0].contains("colour"), "{:?}", s.ignored);
        let bad: Vec<String> = "--ros-args -p colour:=red -p record:=maybe"
            .split_whitespace()
            .map(String::from)
            .collect();
        assert!(setup(&bad).unwrap_err().to_string().contains("record"));
        // use_sim_time: a bool, the last value wins; with clock wall it follows /clock.
        let args = |s: &str| -> Vec<String> { s.split_whitespace().map(String::from).collect() };
        let s = setup(&args(
            "--ros-args -p use_sim_time:=false -p use_sim_time:=true",
        ))
        .unwrap()
        .unwrap();
        assert!(s.use_sim_time);
        assert_eq!(
            s.params.clock.with_sim_time(s.use_sim_time),
            super::super::clock::ClockMode::Follow
        );
        let s = setup(&args("--ros-args -p use_sim_time:=true -p clock:=sim"))
            .unwrap()
            .unwrap();
        assert_eq!(
            s.params.clock.with_sim_time(s.use_sim_time),
            super::super::clock::ClockMode::Sim
        );
        assert!(!setup(&args("--ros-args")).unwrap().unwrap().use_sim_time);
        assert!(setup(&args("--ros-args -p use_sim_time:=1"))
            .unwrap_err()
            .to_string()
            .contains("use_sim_time must be a bool"));
    }
}
