//! What live-view clients ask of the node, answered on the executor with the DDS side's own
//! code: inputs through the input tasks' handlers (validated, recorded, applied alike),
//! parameters through the node's parameter store (the validator and action of `ros2 param
//! set`), and `~/reset` / `~/step` with their services' answers.

use super::endpoints::Service;
use super::inputs::InputContext;
use super::live::protocol::{self, Level, ParameterIn};
use super::live::{Answer, Request};
use super::roles;
use super::sample_messages::sample_to_msgs;
use super::services;
use super::severity::Severity;
use super::tick::Command;
use futures::future::LocalBoxFuture;
use futures::stream::FuturesUnordered;
use futures::{FutureExt, StreamExt};
use muscle_actuator_recording::msgs::{StepRequest, StepResponse};
use muscle_actuator_recording::recording::{decode_cdr, encode_cdr};
use ros2_client::{Node, ParameterValue};
use serde_json::{json, Value};
use std::cell::Cell;

/// What the requests are answered with: the inputs' context (the node's state, log and
/// recording) and the node's parameter store.
pub(crate) struct Context<'a> {
    pub(crate) inputs: &'a InputContext<'a>,
    pub(crate) node: &'a Node,
}

/// Answers requests until the live view's queue closes (never, while the node runs). A
/// service call that waits for the tick loop is answered when it is done, the others go on.
pub(crate) async fn serve(rx: &smol::channel::Receiver<Request>, cx: &Context<'_>) {
    let step_running = Cell::new(false);
    let mut waiting: FuturesUnordered<LocalBoxFuture<'_, ()>> = FuturesUnordered::new();
    loop {
        futures::select! {
            r = rx.recv().fuse() => match r {
                Ok(req) => {
                    if let Some(f) = handle(req, cx, &step_running) {
                        waiting.push(f);
                    }
                }
                Err(_) => futures::future::pending::<()>().await,
            },
            _ = waiting.select_next_some() => {},
        }
    }
}

fn handle<'a>(
    req: Request,
    cx: &'a Context<'a>,
    step_running: &'a Cell<bool>,
) -> Option<LocalBoxFuture<'a, ()>> {
    let ic = cx.inputs;
    match req {
        Request::Input {
            endpoint,
            k,
            json,
            payload,
        } => roles::on_payload(ic, endpoint, k, json, &payload),
        Request::Log { key, warn, line } => {
            let sev = if warn { Severity::Warn } else { Severity::Info };
            ic.log.report(key, sev, line)
        }
        Request::GetParameters { names, id, answer } => {
            answer.text(parameter_values(cx.node, &names, id.as_deref()))
        }
        Request::SetParameters {
            parameters,
            id,
            answer,
        } => set_parameters(cx.node, &parameters, id.as_deref(), &answer),
        Request::Call {
            service: Service::Reset,
            call_id,
            answer,
            ..
        } => {
            return Some(
                async move {
                    let resp = services::reset_answer(ic.shared).await;
                    reply(&answer, Service::Reset, call_id, &resp);
                }
                .boxed_local(),
            )
        }
        Request::Call {
            service: Service::Step,
            call_id,
            payload,
            answer,
        } => return step(cx, step_running, call_id, &payload, answer),
    }
    None
}

fn reply<T: serde::Serialize>(answer: &Answer, service: Service, call_id: u32, resp: &T) {
    match encode_cdr(resp) {
        Ok(bytes) => answer.binary(protocol::service_response(
            service as u32,
            call_id,
            "cdr",
            &bytes,
        )),
        Err(e) => answer.text(protocol::service_failure(
            service as u32,
            call_id,
            &e.to_string(),
        )),
    }
}

/// `~/step` for a client: refused as the DDS service refuses (not lockstep, bad ticks, one
/// already running), else answered with the state after its last tick.
fn step<'a>(
    cx: &'a Context<'a>,
    running: &'a Cell<bool>,
    call_id: u32,
    payload: &[u8],
    answer: Answer,
) -> Option<LocalBoxFuture<'a, ()>> {
    let req: StepRequest = match decode_cdr(payload) {
        Ok(r) => r,
        Err(e) => {
            answer.text(protocol::service_failure(
                Service::Step as u32,
                call_id,
                &format!("unreadable request: {e}"),
            ));
            return None;
        }
    };
    let refusal = if running.get() {
        Some("a step is running; ask again once it has answered".to_string())
    } else {
        services::step_refusal(cx.inputs.mode, req.ticks)
    };
    if let Some(why) = refusal {
        reply(&answer, Service::Step, call_id, &services::step_failed(why));
        return None;
    }
    let (tx, rx) = futures::channel::oneshot::channel();
    cx.inputs.shared.send(Command::Step {
        ticks: req.ticks as u64,
        reply: Some(tx),
    });
    running.set(true);
    Some(
        async move {
            let resp = match rx.await {
                Ok(s) => StepResponse {
                    success: true,
                    message: String::new(),
                    tick: s.tick,
                    state: sample_to_msgs(&s).0,
                },
                Err(_) => {
                    services::step_failed("the tick loop stopped before the step was done".into())
                }
            };
            running.set(false);
            reply(&answer, Service::Step, call_id, &resp);
        }
        .boxed_local(),
    )
}

/// A parameter as the protocol gives it: doubles with `type: "float64"`.
fn to_json(name: &str, v: &ParameterValue) -> Value {
    let (value, ty) = match v {
        ParameterValue::NotSet => (Value::Null, None),
        ParameterValue::Boolean(b) => (json!(b), None),
        ParameterValue::Integer(i) => (json!(i), None),
        ParameterValue::Double(d) => (json!(d), Some("float64")),
        ParameterValue::String(s) => (json!(s), None),
        ParameterValue::ByteArray(b) => (json!(b), None),
        ParameterValue::BooleanArray(b) => (json!(b), None),
        ParameterValue::IntegerArray(i) => (json!(i), None),
        ParameterValue::DoubleArray(d) => (json!(d), Some("float64_array")),
        ParameterValue::StringArray(s) => (json!(s), None),
    };
    let mut p = json!({"name": name, "value": value});
    if let Some(t) = ty {
        p["type"] = json!(t);
    }
    p
}

/// A client's JSON value that is no value of this node's parameters.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
enum UnsupportedValue {
    /// `null`.
    #[error("a parameter cannot be unset")]
    Null,
    /// An array or an object.
    #[error("this node has no array or object parameters")]
    Compound,
}

/// A client's value as a ROS parameter: a number is a double when it says `float64` or the
/// parameter is one (Foxglove's parameter panel sends `500` for a double of 500.0), else an
/// integer when it is whole.
fn from_json(
    p: &ParameterIn,
    current: Option<&ParameterValue>,
) -> Result<ParameterValue, UnsupportedValue> {
    let double =
        p.ty.as_deref() == Some("float64") || matches!(current, Some(ParameterValue::Double(_)));
    Ok(match &p.value {
        Value::Bool(b) => ParameterValue::Boolean(*b),
        Value::String(s) => ParameterValue::String(s.clone()),
        Value::Number(n) => match (double, n.as_i64()) {
            (false, Some(i)) => ParameterValue::Integer(i),
            _ => ParameterValue::Double(n.as_f64().unwrap_or(f64::NAN)),
        },
        Value::Null => return Err(UnsupportedValue::Null),
        Value::Array(_) | Value::Object(_) => return Err(UnsupportedValue::Compound),
    })
}

/// `parameterValues` for `names` (all when empty); unknown names are left out.
fn parameter_values(node: &Node, names: &[String], id: Option<&str>) -> String {
    let names: Vec<String> = if names.is_empty() {
        node.list_parameters()
    } else {
        names.to_vec()
    };
    let params: Vec<Value> = names
        .iter()
        .filter_map(|n| node.get_parameter(n).map(|v| to_json(n, &v)))
        .collect();
    let mut msg = json!({"op": "parameterValues", "parameters": params});
    if let Some(id) = id {
        msg["id"] = json!(id);
    }
    msg.to_string()
}

/// Longest refusal reason passed on, characters: the store's reasons are whole sentences of
/// at most a few hundred (user strings in them are excerpts already); this is the last guard.
const MAX_REASON_CHARS: usize = 1000;

fn bounded(why: &str) -> String {
    why.chars().take(MAX_REASON_CHARS).collect()
}

/// Sets each parameter through the node's store, as `ros2 param set` does; a refusal is an
/// error status with the store's reason. With an `id`, the values after are the answer.
fn set_parameters(node: &Node, params: &[ParameterIn], id: Option<&str>, answer: &Answer) {
    for p in params {
        // The store's refusal is ros2-client's reason text.
        let result = from_json(p, node.get_parameter(&p.name).as_ref())
            .map_err(|e| e.to_string())
            .and_then(|v| node.set_parameter(&p.name, v));
        if let Err(why) = result {
            answer.text(protocol::status(
                Level::Error,
                &format!(
                    "parameter {} not set: {}",
                    muscle_actuator_core::text::excerpt(&p.name),
                    bounded(&why)
                ),
                id,
            ));
        }
    }
    if let Some(id) = id {
        let names: Vec<String> = params.iter().map(|p| p.name.clone()).collect();
        answer.text(parameter_values(node, &names, Some(id)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(value: Value, ty: Option<&str>) -> ParameterIn {
        ParameterIn {
            name: "x".into(),
            value,
            ty: ty.map(String::from),
        }
    }

    #[test]
    fn numbers_take_the_parameters_type() {
        let d = ParameterValue::Double(1.0);
        let i = ParameterValue::Integer(1);
        assert_eq!(
            from_json(&p(json!(500), None), Some(&d)),
            Ok(ParameterValue::Double(500.0))
        );
        assert_eq!(
            from_json(&p(json!(500), None), Some(&i)),
            Ok(ParameterValue::Integer(500))
        );
        assert_eq!(
            from_json(&p(json!(5), Some("float64")), None),
            Ok(ParameterValue::Double(5.0))
        );
        // A fraction for an integer stays a double: the store refuses it with its own reason.
        assert_eq!(
            from_json(&p(json!(0.5), None), Some(&i)),
            Ok(ParameterValue::Double(0.5))
        );
        assert!(from_json(&p(Value::Null, None), Some(&i)).is_err());
        assert_eq!(to_json("r", &d)["type"], "float64");
        assert!(to_json("r", &i).get("type").is_none());
    }
}
