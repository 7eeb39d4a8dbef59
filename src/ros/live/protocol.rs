//! The Foxglove WebSocket protocol's frames (docs/live-view.md): the JSON operations a client
//! sends and the server's answers, and the binary frames both ways.
//!
//! Source: the protocol's specification (foxglove/ws-protocol, `docs/spec.md`, v1). Text frames
//! carry one JSON object with an `op`; binary frames start with an opcode byte, then
//! little-endian integers:
//! - server → client: `0x01` message data (`u32` subscription id, `u64` receive time ns,
//!   payload), `0x02` time (`u64` ns), `0x03` service call response (`u32` service id, `u32`
//!   call id, `u32` encoding length, encoding, payload);
//! - client → server: `0x01` message data (`u32` client channel id, payload), `0x02` service
//!   call request (as the response).

use serde::Deserialize;
use serde_json::{json, Value};

/// The WebSocket subprotocols served: the SDK's name and the specification's older one (which
/// older clients and forks still ask for). The handshake answers with the one the client
/// offered first.
pub(crate) const SUBPROTOCOLS: [&str; 2] = ["foxglove.sdk.v1", "foxglove.websocket.v1"];

/// The subprotocol to answer for a client's `Sec-WebSocket-Protocol` header values.
pub(crate) fn choose_subprotocol<'a>(
    offered: impl Iterator<Item = &'a str>,
) -> Option<&'static str> {
    offered
        .flat_map(|h| h.split(','))
        .map(str::trim)
        .find_map(|name| SUBPROTOCOLS.iter().copied().find(|s| *s == name))
}

/// Why a client's frame is outside the protocol (the client is disconnected with it).
#[derive(Debug, thiserror::Error)]
pub(crate) enum FrameError {
    /// A text frame that is not JSON.
    #[error("a text frame that is not JSON ({0})")]
    NotJson(#[source] serde_json::Error),
    /// A JSON text frame without an `op`.
    #[error("a text frame without an \"op\"")]
    NoOp,
    /// An operation that is unknown or malformed.
    #[error("op {op:?}: {reason}")]
    BadOp {
        /// The `op`, as an excerpt.
        op: String,
        /// The parser's reason, as an excerpt.
        reason: String,
    },
    /// A binary frame shorter than its opcode's fields.
    #[error("a binary frame of {0} bytes, too short for its opcode")]
    Short(usize),
    /// A service call whose encoding name is not UTF-8.
    #[error("a service call whose encoding is not UTF-8")]
    EncodingNotUtf8,
    /// A binary frame with an opcode the protocol does not define.
    #[error("a binary frame with the unknown opcode 0x{0:02x}")]
    UnknownOpcode(u8),
    /// A binary frame of no bytes.
    #[error("an empty binary frame")]
    Empty,
}

/// One operation a client sends in a text frame.
#[derive(Debug, Deserialize)]
#[serde(tag = "op", rename_all = "camelCase")]
pub(crate) enum ClientOp {
    Subscribe {
        subscriptions: Vec<Subscription>,
    },
    Unsubscribe {
        #[serde(rename = "subscriptionIds")]
        subscription_ids: Vec<u32>,
    },
    Advertise {
        channels: Vec<ClientChannel>,
    },
    Unadvertise {
        #[serde(rename = "channelIds")]
        channel_ids: Vec<u32>,
    },
    GetParameters {
        #[serde(rename = "parameterNames", default)]
        parameter_names: Vec<String>,
        #[serde(default)]
        id: Option<String>,
    },
    SetParameters {
        parameters: Vec<ParameterIn>,
        #[serde(default)]
        id: Option<String>,
    },
    /// Operations of capabilities this server does not announce: answered with an error
    /// status, the connection kept.
    SubscribeParameterUpdates {},
    UnsubscribeParameterUpdates {},
    SubscribeConnectionGraph {},
    UnsubscribeConnectionGraph {},
    FetchAsset {},
}

impl ClientOp {
    /// Parses a text frame. The client's `advertise` is named `advertise` in the specification
    /// and `clientAdvertise` in some clients: both are taken.
    pub(crate) fn parse(text: &str) -> Result<Self, FrameError> {
        let mut v: Value = serde_json::from_str(text).map_err(FrameError::NotJson)?;
        let op = v.get("op").and_then(Value::as_str).map(str::to_owned);
        let Some(op) = op else {
            return Err(FrameError::NoOp);
        };
        let renamed = match op.as_str() {
            "clientAdvertise" => Some("advertise"),
            "clientUnadvertise" => Some("unadvertise"),
            _ => None,
        };
        if let (Some(r), Some(obj)) = (renamed, v.as_object_mut()) {
            obj.insert("op".into(), Value::String(r.into()));
        }
        serde_json::from_value(v).map_err(|e| FrameError::BadOp {
            op: muscle_actuator_core::text::excerpt(&op),
            reason: muscle_actuator_core::text::excerpt(&e.to_string()),
        })
    }
}

/// A subscription a client asks for: its own id for the channel's messages.
#[derive(Debug, Deserialize)]
pub(crate) struct Subscription {
    pub(crate) id: u32,
    #[serde(rename = "channelId")]
    pub(crate) channel_id: u32,
}

/// A channel a client will publish on.
#[derive(Debug, Deserialize)]
pub(crate) struct ClientChannel {
    pub(crate) id: u32,
    pub(crate) topic: String,
    pub(crate) encoding: String,
    #[serde(rename = "schemaName")]
    pub(crate) schema_name: String,
}

/// A parameter as a client sets it: `type` is `float64` (or `float64_array`) for a number meant
/// as a double, `byte_array` for base64 bytes.
#[derive(Debug, Deserialize)]
pub(crate) struct ParameterIn {
    pub(crate) name: String,
    pub(crate) value: Value,
    #[serde(default, rename = "type")]
    pub(crate) ty: Option<String>,
}

/// A binary frame from a client.
#[derive(Debug, PartialEq)]
pub(crate) enum ClientBinary<'a> {
    MessageData {
        channel_id: u32,
        payload: &'a [u8],
    },
    ServiceCall {
        service_id: u32,
        call_id: u32,
        encoding: &'a str,
        payload: &'a [u8],
    },
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

impl<'a> ClientBinary<'a> {
    /// Parses a binary frame; an unknown opcode or a short frame is an error.
    pub(crate) fn parse(b: &'a [u8]) -> Result<Self, FrameError> {
        let short = || FrameError::Short(b.len());
        match b.first() {
            Some(0x01) => Ok(Self::MessageData {
                channel_id: u32_at(b, 1).ok_or_else(short)?,
                payload: &b[5..],
            }),
            Some(0x02) => {
                let service_id = u32_at(b, 1).ok_or_else(short)?;
                let call_id = u32_at(b, 5).ok_or_else(short)?;
                let len = u32_at(b, 9).ok_or_else(short)? as usize;
                let enc = b.get(13..13usize.saturating_add(len)).ok_or_else(short)?;
                let encoding = std::str::from_utf8(enc).map_err(|_| FrameError::EncodingNotUtf8)?;
                Ok(Self::ServiceCall {
                    service_id,
                    call_id,
                    encoding,
                    payload: &b[13 + len..],
                })
            }
            Some(op) => Err(FrameError::UnknownOpcode(*op)),
            None => Err(FrameError::Empty),
        }
    }
}

/// Server → client `0x01`: a channel's message for one subscription.
pub(crate) fn message_data(subscription: u32, receive_ns: u64, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(13 + payload.len());
    out.push(0x01);
    out.extend_from_slice(&subscription.to_le_bytes());
    out.extend_from_slice(&receive_ns.to_le_bytes());
    out.extend_from_slice(payload);
    out
}

/// Server → client `0x02`: the server's time, ns.
pub(crate) fn time(ns: u64) -> Vec<u8> {
    let mut out = Vec::with_capacity(9);
    out.push(0x02);
    out.extend_from_slice(&ns.to_le_bytes());
    out
}

/// Server → client `0x03`: a service's answer.
pub(crate) fn service_response(service: u32, call: u32, encoding: &str, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(13 + encoding.len() + payload.len());
    out.push(0x03);
    out.extend_from_slice(&service.to_le_bytes());
    out.extend_from_slice(&call.to_le_bytes());
    out.extend_from_slice(&(encoding.len() as u32).to_le_bytes());
    out.extend_from_slice(encoding.as_bytes());
    out.extend_from_slice(payload);
    out
}

/// Severity of a `status` message.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Level {
    Warning = 1,
    Error = 2,
}

/// A `status` message (shown to the user by the client).
pub(crate) fn status(level: Level, message: &str, id: Option<&str>) -> String {
    let mut v = json!({"op": "status", "level": level as u8, "message": message});
    if let Some(id) = id {
        v["id"] = json!(id);
    }
    v.to_string()
}

/// A `serviceCallFailure` message.
pub(crate) fn service_failure(service: u32, call: u32, message: &str) -> String {
    json!({"op": "serviceCallFailure", "serviceId": service, "callId": call, "message": message})
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_subprotocol_names_are_served_and_others_refused() {
        let pick = |h: &[&str]| choose_subprotocol(h.iter().copied());
        assert_eq!(pick(&["foxglove.sdk.v1"]), Some("foxglove.sdk.v1"));
        assert_eq!(
            pick(&["foxglove.websocket.v1"]),
            Some("foxglove.websocket.v1")
        );
        assert_eq!(
            pick(&["x, foxglove.websocket.v1"]),
            Some("foxglove.websocket.v1")
        );
        assert_eq!(pick(&["foxglove.sdk.v1.1"]), None);
        assert_eq!(pick(&[]), None);
    }

    #[test]
    fn client_ops_parse_and_unknown_ones_are_errors() {
        let op = ClientOp::parse(r#"{"op":"subscribe","subscriptions":[{"id":3,"channelId":1}]}"#)
            .unwrap();
        assert!(matches!(op, ClientOp::Subscribe { subscriptions } if subscriptions[0].id == 3));
        let op = ClientOp::parse(
            r#"{"op":"clientAdvertise","channels":[{"id":1,"topic":"/a","encoding":"json","schemaName":"std_msgs/msg/Float64"}]}"#,
        )
        .unwrap();
        assert!(matches!(op, ClientOp::Advertise { channels } if channels[0].topic == "/a"));
        for bad in [
            "",
            "[1]",
            r#"{"op":"explode"}"#,
            r#"{"op":"subscribe"}"#,
            "{}",
        ] {
            assert!(ClientOp::parse(bad).is_err(), "{bad}");
        }
        // A very long op name is quoted as an excerpt.
        let e = ClientOp::parse(&format!(r#"{{"op":"{}"}}"#, "x".repeat(10_000)))
            .unwrap_err()
            .to_string();
        assert!(e.len() < 300, "{e}");
    }

    #[test]
    fn binary_frames_round_trip() {
        let mut call = vec![0x02];
        for v in [7u32, 9, 3] {
            call.extend_from_slice(&v.to_le_bytes());
        }
        call.extend_from_slice(b"cdr\x00\x01\x00\x00");
        assert_eq!(
            ClientBinary::parse(&call).unwrap(),
            ClientBinary::ServiceCall {
                service_id: 7,
                call_id: 9,
                encoding: "cdr",
                payload: &[0, 1, 0, 0]
            }
        );
        let mut data = vec![0x01];
        data.extend_from_slice(&5u32.to_le_bytes());
        data.push(42);
        assert_eq!(
            ClientBinary::parse(&data).unwrap(),
            ClientBinary::MessageData {
                channel_id: 5,
                payload: &[42]
            }
        );
        // The encoding's length beyond the frame, short frames, unknown opcodes.
        let mut lying = call.clone();
        lying[9..13].copy_from_slice(&u32::MAX.to_le_bytes());
        for bad in [&lying[..], &[0x01, 0, 0], &[0x09, 0, 0, 0, 0], &[]] {
            assert!(ClientBinary::parse(bad).is_err(), "{bad:?}");
        }
        let m = message_data(4, 1_000, &[1, 2]);
        assert_eq!(m.len(), 15);
        assert_eq!(&m[..5], &[1, 4, 0, 0, 0]);
        let r = service_response(1, 2, "cdr", &[9]);
        assert_eq!(r.len(), 1 + 12 + 3 + 1);
    }
}
