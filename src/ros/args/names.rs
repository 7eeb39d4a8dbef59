//! ROS 2 names (design article "Topic and Service name mapping to DDS", rcl's
//! `rcl_validate_*` and `rcl_remap_*`): the rules of node names, namespaces, topic and service
//! names, their expansion to absolute names, and remapping.

/// The node's name unless remapped with `-r __node:=...`.
pub const DEFAULT_NODE_NAME: &str = "muscle_actuator";

/// Longest node name, characters (rmw's `RMW_NODE_NAME_MAX_NAME_LENGTH`).
pub const MAX_NODE_NAME_CHARS: usize = 255;
/// Longest namespace, characters (rmw's `RMW_NAMESPACE_MAX_LENGTH`: 247 - 2).
pub const MAX_NAMESPACE_CHARS: usize = 245;
/// Longest topic or service name, characters (rmw's `RMW_TOPIC_MAX_NAME_LENGTH`: 255 - 8).
pub const MAX_TOPIC_NAME_CHARS: usize = 247;

/// One `-r [node:]from:=to` rule.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Remap {
    /// Applies only to the node of this (original) name, when given.
    pub node: Option<String>,
    pub from: String,
    pub to: String,
}

/// Why a name, node name or namespace breaks the rules of ROS 2 names.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum NameError {
    /// Longer than its kind allows.
    #[error("{chars} characters: a {kind} has at most {max}")]
    TooLong {
        /// Its length, characters.
        chars: usize,
        /// What it names: "node name", "topic or service name", "namespace".
        kind: &'static str,
        /// The most its kind allows, characters.
        max: usize,
    },
    /// A token (or the whole name) is empty.
    #[error("empty")]
    Empty,
    /// A token starts with a character other than a letter or `_`.
    #[error("must not start with {0:?}")]
    BadStart(char),
    /// A token holds a character other than a letter, a digit or `_`.
    #[error("character {0:?} not allowed")]
    BadCharacter(char),
    /// A token holds `__`.
    #[error("repeated underscores are not allowed")]
    RepeatedUnderscores,
}

/// `s` if it has at most `max` characters, else the error naming `kind`.
fn check_length(s: &str, kind: &'static str, max: usize) -> Result<(), NameError> {
    let chars = s.chars().count();
    if chars > max {
        return Err(NameError::TooLong { chars, kind, max });
    }
    Ok(())
}

/// Checks a node name: one token (see `check_token`) of at most 255 characters.
pub fn check_node_name(n: &str) -> Result<(), NameError> {
    check_length(n, "node name", MAX_NODE_NAME_CHARS)?;
    check_token(n)
}

/// Checks one name token: starts with a letter or `_`, then letters, digits, `_`.
fn check_token(t: &str) -> Result<(), NameError> {
    let mut chars = t.chars();
    match chars.next() {
        None => return Err(NameError::Empty),
        Some(c) if c.is_ascii_alphabetic() || c == '_' => {}
        Some(c) => return Err(NameError::BadStart(c)),
    }
    if let Some(c) = t
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '_'))
    {
        return Err(NameError::BadCharacter(c));
    }
    if t.contains("__") {
        return Err(NameError::RepeatedUnderscores);
    }
    Ok(())
}

/// Checks a topic or service name as written by a user: absolute, relative or private (`~`).
pub fn check_name(n: &str) -> Result<(), NameError> {
    check_length(n, "topic or service name", MAX_TOPIC_NAME_CHARS)?;
    let rest = if n == "~" {
        return Ok(());
    } else if let Some(r) = n.strip_prefix("~/") {
        r
    } else if let Some(r) = n.strip_prefix('/') {
        r
    } else {
        n
    };
    if rest.is_empty() {
        return Err(NameError::Empty);
    }
    for tok in rest.split('/') {
        check_token(tok)?;
    }
    Ok(())
}

/// Normalises a namespace: absolute, no trailing slash (except the root `/`).
pub fn normalise_namespace(ns: &str) -> Result<String, NameError> {
    check_length(ns, "namespace", MAX_NAMESPACE_CHARS)?;
    let trimmed = ns.trim_matches('/');
    if trimmed.is_empty() {
        return Ok("/".into());
    }
    for tok in trimmed.split('/') {
        check_token(tok)?;
    }
    Ok(format!("/{trimmed}"))
}

/// Expands a name to its absolute form for a node in namespace `ns` named `node`.
pub fn expand(name: &str, ns: &str, node: &str) -> String {
    let fqn = if ns == "/" {
        format!("/{node}")
    } else {
        format!("{ns}/{node}")
    };
    if name == "~" {
        fqn
    } else if let Some(r) = name.strip_prefix("~/") {
        format!("{fqn}/{r}")
    } else if name.starts_with('/') {
        name.to_string()
    } else if ns == "/" {
        format!("/{name}")
    } else {
        format!("{ns}/{name}")
    }
}

/// The absolute name of `name` (as the node declares it, e.g. `~/state`) after the remap rules.
/// `original_node` is the node's name before `__node` (node-prefixed rules match it or the
/// new name).
pub fn resolve(name: &str, ns: &str, node: &str, original_node: &str, remaps: &[Remap]) -> String {
    let expanded = expand(name, ns, node);
    for r in remaps {
        if let Some(n) = &r.node {
            if n != node && n != original_node {
                continue;
            }
        }
        if expand(&r.from, ns, node) == expanded {
            return expand(&r.to, ns, node);
        }
    }
    expanded
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_expand_and_remap() {
        assert_eq!(expand("~/state", "/", "m"), "/m/state");
        assert_eq!(expand("~/state", "/a/b", "m"), "/a/b/m/state");
        assert_eq!(expand("joint_states", "/a", "m"), "/a/joint_states");
        assert_eq!(expand("/diagnostics", "/a", "m"), "/diagnostics");
        let r = vec![
            Remap {
                node: None,
                from: "joint_states".into(),
                to: "/robot/joint_states".into(),
            },
            Remap {
                node: Some("other".into()),
                from: "~/state".into(),
                to: "x".into(),
            },
            Remap {
                node: Some("m".into()),
                from: "/a/m/activation".into(),
                to: "cmd".into(),
            },
        ];
        assert_eq!(
            resolve("joint_states", "/a", "m", "m", &r),
            "/robot/joint_states"
        );
        assert_eq!(resolve("~/state", "/a", "m", "m", &r), "/a/m/state");
        assert_eq!(resolve("~/activation", "/a", "m", "m", &r), "/a/cmd");
    }
}
