//! `~/external_load` (`muscle_actuator_msgs/ExternalLoad`): torques by joint name, applied at the
//! next tick boundary (or at the header's stamp, as `~/activation`).

use super::context::stamped;
use super::{Input, InputContext};
use crate::ros::tick::Command;
use muscle_actuator_core::sim::input;
use muscle_actuator_recording::msgs::muscle_actuator_msgs::ExternalLoad;

/// The topic's input.
pub(crate) const LOAD: Input<ExternalLoad> = Input {
    what: "external load",
    received: |s| Some(&s.load_received),
    handle,
};

fn handle(cx: &InputContext<'_>, _k: usize, msg: ExternalLoad) {
    match input::validate_load(&msg.joint, &msg.torque, &cx.shared.joints()) {
        Ok(acc) => cx.shared.send(stamped(
            Some(msg.header.stamp.to_nanos()),
            Command::Load(acc.values),
        )),
        Err(rej) => cx.rejected(
            &cx.stats.load_rejected,
            &rej,
            format!("external load rejected: {rej}"),
        ),
    }
}
