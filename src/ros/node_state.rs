//! The node's shared state ([`NodeState`]): parameters in force, the names commands are
//! checked against, the tick loop's command queue; changed by the parameter callbacks
//! (`param_callbacks`), read by the executor's tasks.

use super::logging::Logger;
use super::params::NodeParams;
use super::tick::{self, Command};
use muscle_actuator_core::sim::Actuator;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, OnceLock, RwLock};

/// Names that commands are checked against (they change with the `config` parameter).
#[derive(Clone, Default)]
pub(super) struct Names {
    muscles: Vec<String>,
    joints: Vec<String>,
    /// (index, name) of the driven joints.
    driven: Vec<(usize, String)>,
}

impl Names {
    pub(super) fn of(a: &Actuator) -> Self {
        Self {
            muscles: a.muscle_names().to_vec(),
            joints: a.joint_names().to_vec(),
            driven: a
                .driven_joints()
                .iter()
                .map(|&j| (j, a.joint_names()[j].clone()))
                .collect(),
        }
    }
}

/// The node's state that its executor's tasks, the parameter callbacks, diagnostics and the live
/// view's requests share: the parameters in force, the names commands are checked against, the
/// tick loop's command queue.
pub(crate) struct NodeState {
    pub(super) params: Mutex<NodeParams>,
    pub(super) names: RwLock<Names>,
    commands: tick::CommandSender,
    /// Parameter changes act only once the node is up (the store also runs the action for the
    /// initial values).
    pub(super) armed: AtomicBool,
    logger: OnceLock<Logger>,
}

impl NodeState {
    pub(crate) fn new(
        params: &NodeParams,
        actuator: &Actuator,
        commands: tick::CommandSender,
    ) -> Self {
        Self {
            params: Mutex::new(params.clone()),
            names: RwLock::new(Names::of(actuator)),
            commands,
            armed: AtomicBool::new(false),
            logger: OnceLock::new(),
        }
    }
    /// From now on accepted changes act (and are logged to `logger`).
    pub(crate) fn arm(&self, logger: &Logger) {
        let _ = self.logger.set(logger.clone());
        self.armed.store(true, Ordering::SeqCst);
    }
    pub(super) fn log(&self) -> Option<&Logger> {
        self.logger.get()
    }
    pub(crate) fn send(&self, c: Command) {
        // Never waits for the tick loop; a full queue drops (and counts) the command.
        let _ = self.commands.send(c);
    }
    /// The parameters in force.
    pub(crate) fn params(&self) -> NodeParams {
        self.params.lock().map(|p| p.clone()).unwrap_or_default()
    }
    /// The muscles commands name now.
    pub(crate) fn muscles(&self) -> Vec<String> {
        self.names
            .read()
            .map(|n| n.muscles.clone())
            .unwrap_or_default()
    }
    /// The joints loads name now.
    pub(crate) fn joints(&self) -> Vec<String> {
        self.names
            .read()
            .map(|n| n.joints.clone())
            .unwrap_or_default()
    }
    /// The driven joints now: (index, name).
    pub(crate) fn driven(&self) -> Vec<(usize, String)> {
        self.names
            .read()
            .map(|n| n.driven.clone())
            .unwrap_or_default()
    }
}
