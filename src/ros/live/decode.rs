//! A client's message on an input topic, decoded from CDR (as DDS delivers it) or JSON (the
//! Foxglove app's other encoding) into the same message types the DDS inputs give.
//!
//! JSON may leave fields out (a hand-written `{"muscle": [...], "excitation": [...]}` without a
//! header): the missing ones take the message's default values, as an all-zero CDR header would.

use super::channels::InputTopic;
use super::request::Input;
use muscle_actuator_recording::msgs::muscle_actuator_msgs::{ActivationCommand, ExternalLoad};
use muscle_actuator_recording::msgs::{Float64, Float64MultiArray};
use muscle_actuator_recording::recording::decode_cdr;
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::Value;

/// Why a message could not be read: the input's name (as the DDS tasks name it) and the error.
#[derive(Debug)]
pub(crate) struct Unreadable {
    pub(crate) what: &'static str,
    pub(crate) error: DecodeError,
}

/// Why a payload is not the input topic's message.
#[derive(Debug, thiserror::Error)]
pub(crate) enum DecodeError {
    /// Not the type's CDR.
    #[error(transparent)]
    Cdr(#[from] muscle_actuator_recording::recording::CdrError),
    /// Not JSON; the parser's message as an excerpt.
    #[error("not JSON: {0}")]
    NotJson(String),
    /// The type's defaults cannot be written as JSON.
    #[error(transparent)]
    Defaults(serde_json::Error),
    /// JSON, but not the type's fields; the parser's message as an excerpt.
    #[error("{0}")]
    Fields(String),
}

/// The message `payload` carries for an input topic.
pub(crate) fn decode_input(
    kind: InputTopic,
    json: bool,
    payload: &[u8],
) -> Result<Input, Unreadable> {
    let what = match kind {
        InputTopic::Activation => "activation",
        InputTopic::ActivationArray => "activation_array",
        InputTopic::MuscleCommand(_) => "cmd_activation",
        InputTopic::Load => "external load",
    };
    let err = |error: DecodeError| Unreadable { what, error };
    Ok(match kind {
        InputTopic::Activation => Input::Activation(decode(json, payload).map_err(err)?),
        InputTopic::ActivationArray => Input::ActivationArray(decode(json, payload).map_err(err)?),
        InputTopic::MuscleCommand(k) => {
            Input::MuscleCommand(k, decode(json, payload).map_err(err)?)
        }
        InputTopic::Load => Input::Load(decode(json, payload).map_err(err)?),
    })
}

/// Types a client may send, with the defaults that fill a JSON message's missing fields.
trait InputMessage: DeserializeOwned + Serialize + Default {}
impl InputMessage for ActivationCommand {}
impl InputMessage for ExternalLoad {}
impl InputMessage for Float64 {}
impl InputMessage for Float64MultiArray {}

fn decode<T: InputMessage>(json: bool, payload: &[u8]) -> Result<T, DecodeError> {
    let excerpt = |e: serde_json::Error| muscle_actuator_core::text::excerpt(&e.to_string());
    if !json {
        return decode_cdr(payload).map_err(DecodeError::Cdr);
    }
    let given: Value =
        serde_json::from_slice(payload).map_err(|e| DecodeError::NotJson(excerpt(e)))?;
    let mut full = serde_json::to_value(T::default()).map_err(DecodeError::Defaults)?;
    merge(&mut full, given);
    serde_json::from_value(full).map_err(|e| DecodeError::Fields(excerpt(e)))
}

/// `given` over `base`, object by object (a given non-object replaces the base's value).
fn merge(base: &mut Value, given: Value) {
    match (base, given) {
        (Value::Object(b), Value::Object(g)) => {
            for (k, v) in g {
                match b.get_mut(&k) {
                    Some(slot) => merge(slot, v),
                    None => {
                        b.insert(k, v);
                    }
                }
            }
        }
        (slot, g) => *slot = g,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use muscle_actuator_recording::recording::encode_cdr;

    #[test]
    fn cdr_and_json_give_the_same_message() {
        let msg = ActivationCommand {
            muscle: vec!["flexor".into()],
            excitation: vec![0.5],
            ..Default::default()
        };
        let cdr = encode_cdr(&msg).unwrap();
        let Input::Activation(a) = decode_input(InputTopic::Activation, false, &cdr).unwrap()
        else {
            panic!()
        };
        assert_eq!(a, msg);
        let json = br#"{"muscle": ["flexor"], "excitation": [0.5]}"#;
        let Input::Activation(b) = decode_input(InputTopic::Activation, true, json).unwrap() else {
            panic!()
        };
        assert_eq!(b, msg);
        let stamped =
            br#"{"header": {"stamp": {"sec": 2, "nanosec": 5}}, "muscle": [], "excitation": []}"#;
        let Input::Activation(c) = decode_input(InputTopic::Activation, true, stamped).unwrap()
        else {
            panic!()
        };
        assert_eq!(c.header.stamp.to_nanos(), 2_000_000_005);
    }

    #[test]
    fn unreadable_messages_are_errors() {
        for (json, bytes) in [
            (true, &b"not json"[..]),
            (true, br#"{"excitation": "high"}"#),
            (true, br#"[1, 2]"#),
            (false, &[0, 1, 0, 0, 0xff, 0xff, 0xff, 0x7f][..]),
            (false, &[1, 2][..]),
        ] {
            let e = decode_input(InputTopic::Activation, json, bytes).unwrap_err();
            assert_eq!(e.what, "activation");
        }
    }
}
