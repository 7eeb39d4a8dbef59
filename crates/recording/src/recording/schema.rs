//! ROS 2 message definitions as rosbag2 embeds them in MCAP (`ros2msg` schema encoding): the
//! type's own `.msg` text, then every dependency (depth first, each once) after a line of 80 `=`
//! and a `MSG: pkg/Type` header.

use std::collections::BTreeSet;

/// Why the `ros2msg` schema of a type could not be assembled.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SchemaError {
    /// The type asked for is not named `pkg/msg/Type` (or `pkg/Type`).
    #[error("{name:?} is not a pkg/msg/Type name")]
    NotATypeName {
        /// The name asked for.
        name: String,
    },
    /// The lookup knows no definition of the type asked for.
    #[error("no definition for {name}")]
    NoDefinition {
        /// The type asked for.
        name: String,
    },
    /// A definition names a field type that is not `pkg/Type`.
    #[error("bad type name {name:?}")]
    BadDependencyName {
        /// The dependency's name as derived from the field.
        name: String,
    },
    /// The lookup knows no definition of a type some definition depends on.
    #[error("no definition for {dependency} (needed by {name})")]
    NoDependencyDefinition {
        /// The missing type, `pkg/Type`.
        dependency: String,
        /// The type whose schema was asked for.
        name: String,
    },
    /// The channel's QoS profile could not be written as rosbag2's YAML.
    #[error("the QoS profile of {topic} as YAML: {reason}")]
    QosYaml {
        /// The channel's topic.
        topic: String,
        /// The YAML writer's reason.
        reason: String,
    },
}

/// The separator line rosbag2 puts between definitions.
pub const SEPARATOR: &str =
    "================================================================================";

const PRIMITIVES: [&str; 17] = [
    "bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32",
    "uint32", "int64", "uint64", "string", "wstring", "time", "duration",
];

/// `pkg/msg/Type` or `pkg/Type` → (`pkg`, `Type`).
fn split(name: &str) -> Option<(&str, &str)> {
    let mut parts = name.split('/');
    let pkg = parts.next()?;
    let a = parts.next()?;
    match parts.next() {
        None => Some((pkg, a)),
        Some(t) if a == "msg" && parts.next().is_none() => Some((pkg, t)),
        _ => None,
    }
}

/// The complex types a definition's fields name, as `pkg/Type` (in field order).
fn dependencies(pkg: &str, text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or("").trim();
        let Some(ty) = line.split_whitespace().next() else {
            continue;
        };
        // Constants (`TYPE NAME=value`) name only primitives.
        if line
            .split_whitespace()
            .nth(1)
            .is_some_and(|n| n.contains('='))
        {
            continue;
        }
        let base = ty.split('[').next().unwrap_or(ty);
        let base = base.split("<=").next().unwrap_or(base);
        if PRIMITIVES.contains(&base) {
            continue;
        }
        let full = if base == "Header" {
            "std_msgs/Header".to_string()
        } else if let Some((p, t)) = split(base) {
            format!("{p}/{t}")
        } else {
            format!("{pkg}/{base}")
        };
        out.push(full);
    }
    out
}

/// The `ros2msg` schema text of `type_name` (`pkg/msg/Type`), with `lookup` giving the `.msg`
/// text of any `pkg/msg/Type`. Fails on a type `lookup` does not know.
pub fn ros2msg_schema<'a>(
    type_name: &str,
    lookup: &dyn Fn(&str) -> Option<&'a str>,
) -> Result<String, SchemaError> {
    let (pkg, ty) = split(type_name).ok_or_else(|| SchemaError::NotATypeName {
        name: type_name.into(),
    })?;
    let root = lookup(&format!("{pkg}/msg/{ty}")).ok_or_else(|| SchemaError::NoDefinition {
        name: type_name.into(),
    })?;
    let mut out = root.trim_end().to_string();
    out.push('\n');
    let mut seen = BTreeSet::new();
    seen.insert(format!("{pkg}/{ty}"));
    let mut stack: Vec<String> = dependencies(pkg, root).into_iter().rev().collect();
    while let Some(dep) = stack.pop() {
        if !seen.insert(dep.clone()) {
            continue;
        }
        let (p, t) =
            split(&dep).ok_or_else(|| SchemaError::BadDependencyName { name: dep.clone() })?;
        let text =
            lookup(&format!("{p}/msg/{t}")).ok_or_else(|| SchemaError::NoDependencyDefinition {
                dependency: dep.clone(),
                name: type_name.into(),
            })?;
        out.push_str(SEPARATOR);
        out.push_str("\nMSG: ");
        out.push_str(&dep);
        out.push('\n');
        out.push_str(text.trim_end());
        out.push('\n');
        for d in dependencies(p, text).into_iter().rev() {
            stack.push(d);
        }
    }
    Ok(out)
}

/// The field names of `pkg/Type`'s definition within a `ros2msg` schema text (the root's
/// when `root` names it, else its `MSG: pkg/Type` section), constants left out; `None` when
/// the schema does not define it.
pub fn field_names(schema: &str, type_name: &str, root: bool) -> Option<Vec<String>> {
    let mut sections = schema.split(SEPARATOR);
    let body = if root {
        sections.next()?
    } else {
        let header = format!("MSG: {type_name}");
        sections.find_map(|s| {
            let s = s.trim_start_matches('\n');
            s.strip_prefix(header.as_str())
                .filter(|rest| rest.starts_with('\n'))
        })?
    };
    let fields = body
        .lines()
        .filter_map(|line| {
            let line = line.split('#').next().unwrap_or("").trim();
            let mut words = line.split_whitespace();
            let (_ty, name) = (words.next()?, words.next()?);
            (!name.contains('=')).then(|| name.to_string())
        })
        .collect();
    Some(fields)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn field_names_of_a_section() {
        let text = format!(
            "string A=\"a\"\nstd_msgs/Header header # c\nfloat64 x\n{SEPARATOR}\nMSG: std_msgs/Header\nint32 sec # s\nstring frame_id\n"
        );
        assert_eq!(field_names(&text, "root", true).unwrap(), ["header", "x"]);
        assert_eq!(
            field_names(&text, "std_msgs/Header", false).unwrap(),
            ["sec", "frame_id"]
        );
        assert_eq!(field_names(&text, "std_msgs/Head", false), None);
    }

    #[test]
    fn appends_dependencies_once() {
        let defs = |n: &str| -> Option<&'static str> {
            match n {
                "a/msg/Outer" => Some("std_msgs/Header header\nInner[] x  # inner\nInner y\n"),
                "a/msg/Inner" => Some("float64 v\nstd_msgs/Header h\n"),
                "std_msgs/msg/Header" => Some("builtin_interfaces/Time stamp\nstring frame_id\n"),
                "builtin_interfaces/msg/Time" => Some("int32 sec\nuint32 nanosec\n"),
                _ => None,
            }
        };
        let s = ros2msg_schema("a/msg/Outer", &defs).unwrap();
        let headers: Vec<&str> = s.lines().filter(|l| l.starts_with("MSG: ")).collect();
        assert_eq!(
            headers,
            [
                "MSG: std_msgs/Header",
                "MSG: builtin_interfaces/Time",
                "MSG: a/Inner"
            ]
        );
        assert_eq!(s.matches(SEPARATOR).count(), 3);
        assert!(ros2msg_schema("a/msg/Missing", &defs).is_err());
    }
}
