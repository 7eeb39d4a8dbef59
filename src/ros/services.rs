//! The node's services, one function each: `~/reset` (`std_srvs/Trigger`) and `~/step`
//! (`muscle_actuator_msgs/Step`), served on the DDS executor; their answers are made here for
//! the live view's clients too (`live_requests.rs`).

use super::clock::ClockMode;
use super::logging::Reporter;
use super::node_state::NodeState;
use super::sample_messages::sample_to_msgs;
use super::tick::{Command, Sample};
use futures::{FutureExt, StreamExt};
use muscle_actuator_recording::msgs::muscle_actuator_msgs::ActuatorState;
use muscle_actuator_recording::msgs::{StepRequest, StepResponse, TriggerRequest, TriggerResponse};
use ros2_client::{RmwRequestId, Server};
use std::time::Duration;

/// Longest the reset service waits for the tick loop's answer.
const RESET_ANSWER_TIMEOUT: Duration = Duration::from_secs(2);

/// `~/reset` (`std_srvs/Trigger`): back to the initial state, answered with the ticks run.
pub(crate) async fn reset(
    server: &Server<TriggerRequest, TriggerResponse>,
    shared: &NodeState,
    log: &Reporter,
) {
    let mut stream = server.receive_request_stream();
    while let Some(r) = stream.next().await {
        let Ok((id, _req)) = r else {
            continue;
        };
        let resp = reset_answer(shared).await;
        if let Err(e) = server.async_send_response(id, resp).await {
            log.logger
                .warn(&format!("reset: cannot send the response: {e:?}"));
        }
    }
}

/// Resets the actuator and answers as `~/reset` does (from DDS or the live view).
pub(crate) async fn reset_answer(shared: &NodeState) -> TriggerResponse {
    let (tx, rx) = futures::channel::oneshot::channel();
    shared.send(Command::Reset(Some(tx)));
    let timeout = smol::Timer::after(RESET_ANSWER_TIMEOUT);
    futures::select! {
        r = rx.fuse() => match r {
            Ok(before) => TriggerResponse {
                success: true,
                message: format!("reset to the initial state after {before} ticks"),
            },
            Err(_) => TriggerResponse {
                success: false,
                message: "the tick loop is not running".into(),
            },
        },
        _ = FutureExt::fuse(timeout) => TriggerResponse {
            success: false,
            message: format!(
                "the tick loop did not answer within {} s",
                RESET_ANSWER_TIMEOUT.as_secs()
            ),
        },
    }
}

/// Most ticks one step may ask for (about 2.8 h of simulated time at 1 kHz); more is refused.
pub(crate) const MAX_STEP_TICKS: i64 = 10_000_000;

/// Why a step of `ticks` cannot be done in `mode`, if it cannot.
pub(crate) fn step_refusal(mode: ClockMode, ticks: i64) -> Option<String> {
    if mode != ClockMode::Lockstep {
        return Some(format!(
            "~/step needs clock:=lockstep; this node runs clock:={}",
            mode.name()
        ));
    }
    if !(1..=MAX_STEP_TICKS).contains(&ticks) {
        return Some(format!(
            "ticks = {ticks} is invalid: must be from 1 to {MAX_STEP_TICKS}"
        ));
    }
    None
}

pub(crate) fn step_failed(message: String) -> StepResponse {
    StepResponse {
        success: false,
        message,
        tick: 0,
        state: ActuatorState::default(),
    }
}

/// `~/step` (`muscle_actuator_msgs/Step`): advances a lockstep node and answers with the state
/// after the last tick. One step at a time: a request while one is running is refused at once.
pub(crate) async fn step(
    server: &Server<StepRequest, StepResponse>,
    shared: &NodeState,
    mode: ClockMode,
    log: &Reporter,
) {
    let mut requests = server.receive_request_stream().fuse();
    // The step running: its request id, its ticks, and the loop's answer to come.
    let mut running: Option<(
        RmwRequestId,
        i64,
        futures::channel::oneshot::Receiver<Sample>,
    )> = None;
    loop {
        let request = match running.take() {
            None => requests.next().await,
            Some((id, ticks, mut done)) => futures::select! {
                r = done => {
                    let resp = match r {
                        Ok(s) => StepResponse {
                            success: true,
                            message: String::new(),
                            tick: s.tick,
                            state: sample_to_msgs(&s).0,
                        },
                        Err(_) => step_failed(
                            "the tick loop stopped before the step was done".into(),
                        ),
                    };
                    if let Err(e) = server.async_send_response(id, resp).await {
                        log.logger.warn(&format!("step: cannot send the response: {e:?}"));
                    }
                    continue;
                },
                r = requests.next() => {
                    running = Some((id, ticks, done));
                    r
                },
            },
        };
        let Some(request) = request else {
            return;
        };
        let Ok((id, req)) = request else {
            continue;
        };
        let refusal = match &running {
            Some((_, ticks, _)) => Some(format!(
                "a step of {ticks} ticks is running; ask again once it has answered"
            )),
            None => step_refusal(mode, req.ticks),
        };
        if let Some(why) = refusal {
            if let Err(e) = server.async_send_response(id, step_failed(why)).await {
                log.logger
                    .warn(&format!("step: cannot send the response: {e:?}"));
            }
            continue;
        }
        let (tx, rx) = futures::channel::oneshot::channel();
        shared.send(Command::Step {
            ticks: req.ticks as u64,
            reply: Some(tx),
        });
        running = Some((id, req.ticks, rx));
    }
}
