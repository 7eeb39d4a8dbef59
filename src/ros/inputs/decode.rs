//! A live-view client's message on an input topic, decoded from CDR (as DDS delivers it) or
//! JSON (the Foxglove app's other encoding) into the message type the DDS subscription gives.
//!
//! JSON may leave fields out (a hand-written `{"muscle": [...], "excitation": [...]}` without a
//! header): the missing ones take the message's default values, as an all-zero CDR header would.

use super::InputMessage;
use muscle_actuator_recording::recording::decode_cdr;
use serde_json::Value;

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

/// The message `payload` carries: CDR, or JSON when `json`.
pub(crate) fn decode<T: InputMessage>(json: bool, payload: &[u8]) -> Result<T, DecodeError> {
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
    use muscle_actuator_recording::msgs::muscle_actuator_msgs::ActivationCommand;
    use muscle_actuator_recording::recording::encode_cdr;

    #[test]
    fn cdr_and_json_give_the_same_message() {
        let msg = ActivationCommand {
            muscle: vec!["flexor".into()],
            excitation: vec![0.5],
            ..Default::default()
        };
        let cdr = encode_cdr(&msg).unwrap();
        let a: ActivationCommand = decode(false, &cdr).unwrap();
        assert_eq!(a, msg);
        let json = br#"{"muscle": ["flexor"], "excitation": [0.5]}"#;
        let b: ActivationCommand = decode(true, json).unwrap();
        assert_eq!(b, msg);
        let stamped =
            br#"{"header": {"stamp": {"sec": 2, "nanosec": 5}}, "muscle": [], "excitation": []}"#;
        let c: ActivationCommand = decode(true, stamped).unwrap();
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
            assert!(decode::<ActivationCommand>(json, bytes).is_err());
        }
    }
}
