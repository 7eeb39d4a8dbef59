//! `~/activation` (`muscle_actuator_msgs/ActivationCommand`): excitations by muscle name, applied
//! at the next tick boundary, or at the header's stamp when it is ahead of a simulated clock.

use super::{Input, InputContext};
use muscle_actuator_recording::msgs::muscle_actuator_msgs::ActivationCommand;

/// The topic's input.
pub(crate) const ACTIVATION: Input<ActivationCommand> = Input {
    what: "activation",
    received: |s| Some(&s.activation_received),
    handle,
};

fn handle(cx: &InputContext<'_>, _k: usize, msg: ActivationCommand) {
    let stamp = msg.header.stamp.to_nanos();
    cx.excite(
        &msg.muscle,
        &msg.excitation,
        &cx.shared.muscles(),
        Some(stamp),
    );
}
