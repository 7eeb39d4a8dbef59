//! The parameter callbacks (run on the node's executor): a change is validated against the
//! current set, building the actuator it would give, before it is accepted; once accepted it
//! is applied by sending the tick loop the rebuilt actuator.

use super::node_state::{Names, NodeState};
use super::params::{self, BuildError, NodeParams, OnChange, ParameterError};
use super::tick::Command;
use muscle_actuator_core::sim::Actuator;
use ros2_client::NodeOptions;
use std::sync::atomic::Ordering;
use std::sync::mpsc;
use std::sync::Arc;
use std::time::Duration;

/// The declared parameters with their start-up values, the validator and the action, on
/// `options`.
pub(crate) fn attach(
    state: &Arc<NodeState>,
    mut options: NodeOptions,
    initial: &NodeParams,
) -> NodeOptions {
    for (n, v) in initial.values() {
        options = options.declare_parameter(n, v);
    }
    let sv = state.clone();
    let sa = state.clone();
    options
        .parameter_validator(Box::new(move |n, v| validate_param(&sv, n, v)))
        .parameter_set_action(Box::new(move |n, v| apply_param(&sa, n, v)))
}

/// Why a parameter change is refused; the parameter services send its text as the reason.
#[derive(Debug, thiserror::Error)]
enum ChangeError {
    /// The parameters in force cannot be read (a thread panicked holding them).
    #[error("internal error: parameter lock poisoned")]
    LockPoisoned,
    /// The value breaks its parameter's rules.
    #[error(transparent)]
    Parameter(#[from] ParameterError),
    /// `foxglove_port` changed: fixed at start-up.
    #[error(
        "foxglove_port is chosen at start-up (this node serves port {serving}); restart the \
         node with -p foxglove_port:={asked}"
    )]
    PortFixed {
        /// The port served.
        serving: u16,
        /// The port asked for.
        asked: u16,
    },
    /// `clock` changed: fixed at start-up.
    #[error(
        "clock is chosen at start-up (this node runs clock:={running}); restart the node with \
         -p clock:={asked}"
    )]
    ClockFixed {
        /// The clock mode in force.
        running: &'static str,
        /// The clock mode asked for.
        asked: &'static str,
    },
    /// The actuator the change gives cannot be built.
    #[error(transparent)]
    Build(#[from] RebuildError),
}

/// Why the actuator of a parameter change cannot be built off the executor.
#[derive(Debug, thiserror::Error)]
enum RebuildError {
    /// The thread that builds it cannot start.
    #[error("cannot start a thread to build the actuator: {0}")]
    Thread(#[source] std::io::Error),
    /// It took longer than [`BUILD_TIMEOUT`].
    #[error(
        "building the actuator took longer than {secs} s (is the configuration file on a \
         stalled file system?)"
    )]
    Timeout {
        /// The time allowed, s.
        secs: u64,
    },
    /// The parameters give no actuator.
    #[error(transparent)]
    Build(#[from] BuildError),
}

/// Longest a parameter change may take to build its actuator (configuration file read and
/// calibration) before it is refused.
const BUILD_TIMEOUT: Duration = Duration::from_secs(5);

/// Builds the actuator `params` describe on a thread of its own: the parameter callbacks run on
/// the node's executor, which must not wait on a slow file system for longer than
/// [`BUILD_TIMEOUT`] (a configuration is read only from a regular file of at most 1 MiB, but that
/// file may sit on a stalled network mount).
fn build_off_executor(params: &NodeParams) -> Result<Actuator, RebuildError> {
    let (tx, rx) = mpsc::sync_channel(1);
    let p = params.clone();
    std::thread::Builder::new()
        .name("build".into())
        .spawn(move || {
            let _ = tx.send(p.build());
        })
        .map_err(RebuildError::Thread)?;
    let built = rx
        .recv_timeout(BUILD_TIMEOUT)
        .map_err(|_| RebuildError::Timeout {
            secs: BUILD_TIMEOUT.as_secs(),
        })?;
    Ok(built?)
}

/// The validator ros2-client calls: its signature takes the refusal as the reason text the
/// parameter services send.
fn validate_param(
    shared: &NodeState,
    name: &str,
    value: &ros2_client::ParameterValue,
) -> Result<(), String> {
    check_change(shared, name, value).map_err(|e| e.to_string())
}

/// Checks one parameter change against the current set (and builds the actuator it would give
/// when it affects the simulation), without applying it.
fn check_change(
    shared: &NodeState,
    name: &str,
    value: &ros2_client::ParameterValue,
) -> Result<(), ChangeError> {
    let mut candidate = shared
        .params
        .lock()
        .map_err(|_| ChangeError::LockPoisoned)?
        .clone();
    let before = candidate.clock;
    let port_before = candidate.foxglove_port;
    candidate.set(name, value, false)?;
    if candidate.foxglove_port != port_before {
        return Err(ChangeError::PortFixed {
            serving: port_before,
            asked: candidate.foxglove_port,
        });
    }
    if candidate.clock != before {
        return Err(ChangeError::ClockFixed {
            running: before.name(),
            asked: candidate.clock.name(),
        });
    }
    if on_change(name) == Some(OnChange::Rebuild) {
        build_off_executor(&candidate)?;
    }
    Ok(())
}

/// What a change of parameter `name` does (its [`params::ParameterSpec::on_change`]).
fn on_change(name: &str) -> Option<OnChange> {
    params::spec(name).map(|s| s.on_change)
}

/// The set action ros2-client calls: its signature takes a failure as the reason text the
/// parameter services send.
fn apply_param(
    shared: &NodeState,
    name: &str,
    value: &ros2_client::ParameterValue,
) -> Result<(), String> {
    apply_change(shared, name, value).map_err(|e| e.to_string())
}

/// Applies an accepted parameter change.
fn apply_change(
    shared: &NodeState,
    name: &str,
    value: &ros2_client::ParameterValue,
) -> Result<(), ChangeError> {
    if !shared.armed.load(Ordering::SeqCst) {
        return Ok(());
    }
    let mut p = shared
        .params
        .lock()
        .map_err(|_| ChangeError::LockPoisoned)?;
    let mut candidate = p.clone();
    candidate.set(name, value, false)?;
    match on_change(name) {
        Some(OnChange::Rebuild) => {
            let act = build_off_executor(&candidate)?;
            if let Ok(mut n) = shared.names.write() {
                *n = Names::of(&act);
            }
            shared.send(Command::Replace(Box::new(act)));
            shared.send(Command::PublishEvery(candidate.publish_every()));
            shared.send(Command::ClockEvery(candidate.clock_every()));
        }
        Some(OnChange::PublishEvery) => {
            shared.send(Command::PublishEvery(candidate.publish_every()))
        }
        Some(OnChange::RealTimeFactor) => {
            shared.send(Command::RealTimeFactor(candidate.real_time_factor))
        }
        Some(OnChange::ClockEvery) => shared.send(Command::ClockEvery(candidate.clock_every())),
        // Refused ones never pass `validate_param`.
        Some(OnChange::NextStart | OnChange::Refused) | None => {}
    }
    *p = candidate;
    drop(p);
    if let Some(l) = shared.log() {
        let shown = match value {
            ros2_client::ParameterValue::String(s) => {
                format!("{:?}", muscle_actuator_core::text::excerpt(s))
            }
            other => muscle_actuator_core::text::excerpt(&format!("{other:?}")),
        };
        l.info(&format!("parameter {name} set to {shown}"));
    }
    Ok(())
}
