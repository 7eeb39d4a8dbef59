//! ROS 2 type hashes (REP-2016, "RIHS01"), computed from the `.msg` definitions of
//! `super::DEFINITIONS`: the SHA-256 of the type description as JSON, the way
//! `rosidl_generator_type_description` writes it (`json.dumps` with `", "` and `": "`, no
//! default values, the referenced types sorted by name).

use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Why a type description could not be built from the `.msg` definitions.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub(crate) enum TypeHashError {
    /// The definitions do not know a type the description needs.
    #[error("no definition of {name}")]
    NoDefinition {
        /// The type, `pkg/msg/Type`.
        name: String,
    },
    /// A field's array type (`T[...`) lacks its closing bracket.
    #[error("no closing ] in the .msg type {ty:?}")]
    NoClosingBracket {
        /// The field's type as written.
        ty: String,
    },
    /// A bounded sequence's bound (`T[<=n]`) is not a number.
    #[error("a bound in the .msg type {ty:?}")]
    BadBound {
        /// The field's type as written.
        ty: String,
    },
    /// A fixed array's size (`T[n]`) is not a number.
    #[error("a size in the .msg type {ty:?}")]
    BadSize {
        /// The field's type as written.
        ty: String,
    },
    /// A bounded string's bound (`string<=n`) is not a number.
    #[error("a string bound in the .msg type {ty:?}")]
    BadStringBound {
        /// The field's type as written.
        ty: String,
    },
}

/// `FieldType` ids (`type_description_interfaces/msg/FieldType.msg`) of the primitive `.msg`
/// types, as `rosidl_adapter` maps them to IDL (`byte` is `octet`, `char` is `uint8`).
fn primitive_id(ty: &str) -> Option<u8> {
    Some(match ty {
        "int8" => 2,
        "uint8" | "char" => 3,
        "int16" => 4,
        "uint16" => 5,
        "int32" => 6,
        "uint32" => 7,
        "int64" => 8,
        "uint64" => 9,
        "float32" => 10,
        "float64" => 11,
        "bool" => 15,
        "byte" => 16,
        "string" => 17,
        "wstring" => 18,
        _ => return None,
    })
}
/// `FieldType.NESTED_TYPE`.
const NESTED: u8 = 1;
/// `FieldType.FIELD_TYPE_BOUNDED_STRING`, `..._BOUNDED_WSTRING`.
const BOUNDED_STRING: u8 = 21;
const BOUNDED_WSTRING: u8 = 22;
/// Added to the element's id for a fixed array, a bounded and an unbounded sequence.
const ARRAY: u8 = 48;
const BOUNDED_SEQUENCE: u8 = 96;
const UNBOUNDED_SEQUENCE: u8 = 144;

/// One field's type in the description.
struct FieldType {
    type_id: u8,
    capacity: u64,
    string_capacity: u64,
    nested_type_name: String,
}

/// The fields of the `.msg` text of `pkg/msg/Name`: (name, type), constants left out.
fn fields(pkg: &str, text: &str) -> Result<Vec<(String, FieldType)>, TypeHashError> {
    let mut out = Vec::new();
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or("").trim();
        let mut words = line.split_whitespace();
        let (Some(ty), Some(name)) = (words.next(), words.next()) else {
            continue;
        };
        if name.contains('=') || words.next().is_some_and(|w| w.starts_with('=')) {
            continue; // a constant: `TYPE NAME=VALUE`
        }
        out.push((name.to_string(), field_type(pkg, ty)?));
    }
    if out.is_empty() {
        // An empty structure carries one placeholder byte (rosidl_parser).
        out.push((
            "structure_needs_at_least_one_member".into(),
            field_type(pkg, "uint8")?,
        ));
    }
    Ok(out)
}

/// A `.msg` type (`float64`, `string<=8`, `Header`, `pkg/Type`, `T[]`, `T[3]`, `T[<=3]`) as a
/// description field type; nested names are `pkg/msg/Type`, a bare `Header` is std_msgs'.
fn field_type(pkg: &str, ty: &str) -> Result<FieldType, TypeHashError> {
    let ty_owned = || ty.to_string();
    let (elem, offset, capacity) = match ty.split_once('[') {
        None => (ty, 0, 0),
        Some((elem, rest)) => {
            let inner = rest
                .strip_suffix(']')
                .ok_or_else(|| TypeHashError::NoClosingBracket { ty: ty_owned() })?;
            match inner.strip_prefix("<=") {
                _ if inner.is_empty() => (elem, UNBOUNDED_SEQUENCE, 0),
                Some(n) => (
                    elem,
                    BOUNDED_SEQUENCE,
                    n.parse()
                        .map_err(|_| TypeHashError::BadBound { ty: ty_owned() })?,
                ),
                None => (
                    elem,
                    ARRAY,
                    inner
                        .parse()
                        .map_err(|_| TypeHashError::BadSize { ty: ty_owned() })?,
                ),
            }
        }
    };
    let (base, string_capacity) = match elem.split_once("<=") {
        Some((b, n)) => (
            b,
            n.parse()
                .map_err(|_| TypeHashError::BadStringBound { ty: ty_owned() })?,
        ),
        None => (elem, 0),
    };
    let (id, nested_type_name) = match (primitive_id(base), string_capacity) {
        (Some(17), n) if n > 0 => (BOUNDED_STRING, String::new()),
        (Some(18), n) if n > 0 => (BOUNDED_WSTRING, String::new()),
        (Some(id), _) => (id, String::new()),
        (None, _) => (NESTED, nested_name(pkg, base)),
    };
    Ok(FieldType {
        type_id: id + offset,
        capacity,
        string_capacity,
        nested_type_name,
    })
}

/// The full name `pkg/msg/Type` of a nested type as written in a `.msg` of package `pkg`.
fn nested_name(pkg: &str, ty: &str) -> String {
    match ty.split_once('/') {
        Some((p, t)) => format!("{p}/msg/{t}"),
        None if ty == "Header" => "std_msgs/msg/Header".into(),
        None => format!("{pkg}/msg/{ty}"),
    }
}

/// `{"type_name": ..., "fields": [...]}` of one type.
fn individual_description(name: &str, fields: &[(String, FieldType)]) -> String {
    let mut s = format!("{{\"type_name\": {}, \"fields\": [", json_string(name));
    for (k, (field, t)) in fields.iter().enumerate() {
        let _ = write!(
            s,
            "{}{{\"name\": {}, \"type\": {{\"type_id\": {}, \"capacity\": {}, \
             \"string_capacity\": {}, \"nested_type_name\": {}}}}}",
            if k == 0 { "" } else { ", " },
            json_string(field),
            t.type_id,
            t.capacity,
            t.string_capacity,
            json_string(&t.nested_type_name)
        );
    }
    s.push_str("]}");
    s
}

/// A JSON string as Python's `json.dumps` writes it (ASCII, `\uXXXX` escapes).
fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(c),
            _ => {
                let mut buf = [0u16; 2];
                for u in c.encode_utf16(&mut buf) {
                    let _ = write!(out, "\\u{u:04x}");
                }
            }
        }
    }
    out.push('"');
    out
}

/// The type description of `type_name` (`pkg/msg/Type`) as hashed: the type and every type it
/// refers to, transitively, looked up with `definition`.
pub(crate) fn type_description_json(
    type_name: &str,
    definition: impl Fn(&str) -> Option<&'static str>,
) -> Result<String, TypeHashError> {
    let mut described: BTreeMap<String, String> = BTreeMap::new();
    let mut pending = vec![type_name.to_string()];
    while let Some(name) = pending.pop() {
        if described.contains_key(&name) {
            continue;
        }
        let text =
            definition(&name).ok_or_else(|| TypeHashError::NoDefinition { name: name.clone() })?;
        let pkg = name.split('/').next().unwrap_or_default();
        let fields = fields(pkg, text)?;
        pending.extend(
            fields
                .iter()
                .filter(|(_, t)| !t.nested_type_name.is_empty())
                .map(|(_, t)| t.nested_type_name.clone()),
        );
        described.insert(name.clone(), individual_description(&name, &fields));
    }
    let own = described.remove(type_name).unwrap_or_default();
    let referenced: Vec<String> = described.into_values().collect();
    Ok(format!(
        "{{\"type_description\": {own}, \"referenced_type_descriptions\": [{}]}}",
        referenced.join(", ")
    ))
}

/// `RIHS01_` and the hex SHA-256 of the type description of `type_name`.
pub(crate) fn rihs01(
    type_name: &str,
    definition: impl Fn(&str) -> Option<&'static str>,
) -> Result<String, TypeHashError> {
    let digest = Sha256::digest(type_description_json(type_name, definition)?.as_bytes());
    let mut out = String::from("RIHS01_");
    for b in digest {
        let _ = write!(out, "{b:02x}");
    }
    Ok(out)
}
