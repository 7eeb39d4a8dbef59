//! The standard ROS 2 command-line arguments, as `rcl` understands them:
//! `--ros-args -r __ns:=/ns -r __node:=name -r from:=to -p name:=value --params-file f.yaml
//! --log-level [logger:=]level [--]`, plus name expansion and remapping of topic and service
//! names.

use crate::{files::read_regular_file, text::excerpt};
use ros2_client::ParameterValue;
use std::path::Path;

/// Largest parameters file, bytes.
pub const MAX_PARAMS_FILE_BYTES: u64 = 1 << 20;
/// Deepest nesting of YAML flow collections (`[`, `{`) in a parameters file or a `-p` value.
/// serde_yaml refuses more than 128 levels, but only after libyaml has parsed the rest, which
/// takes minutes for 100,000 levels: the text is checked before it is parsed.
pub const MAX_FLOW_DEPTH: usize = 64;
/// Longest node name, characters (rmw's `RMW_NODE_NAME_MAX_NAME_LENGTH`).
pub const MAX_NODE_NAME_CHARS: usize = 255;
/// Longest namespace, characters (rmw's `RMW_NAMESPACE_MAX_LENGTH`: 247 - 2).
pub const MAX_NAMESPACE_CHARS: usize = 245;
/// Longest topic or service name, characters (rmw's `RMW_TOPIC_MAX_NAME_LENGTH`: 255 - 8).
pub const MAX_TOPIC_NAME_CHARS: usize = 247;

/// Log severities, ordered.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    Debug,
    Info,
    Warn,
    Error,
    Fatal,
}

impl Severity {
    /// Parses `debug`, `info`, `warn`/`warning`, `error`, `fatal` (any case).
    pub fn parse(s: &str) -> Option<Self> {
        match s.to_ascii_lowercase().as_str() {
            "debug" => Some(Self::Debug),
            "info" => Some(Self::Info),
            "warn" | "warning" => Some(Self::Warn),
            "error" => Some(Self::Error),
            "fatal" => Some(Self::Fatal),
            _ => None,
        }
    }
    /// Upper-case name as ROS prints it.
    pub fn label(self) -> &'static str {
        match self {
            Self::Debug => "DEBUG",
            Self::Info => "INFO",
            Self::Warn => "WARN",
            Self::Error => "ERROR",
            Self::Fatal => "FATAL",
        }
    }
}

/// One `-r [node:]from:=to` rule.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Remap {
    /// Applies only to the node of this (original) name, when given.
    pub node: Option<String>,
    pub from: String,
    pub to: String,
}

/// A parameter assignment from `-p` or a parameters file, in command-line order.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamAssignment {
    pub name: String,
    pub value: ParameterValue,
    /// Where it came from, for error messages (`-p` or the file name).
    pub source: String,
}

/// The parsed command line of `muscle_actuator node`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RosArgs {
    /// `-r __ns:=...`: the node's namespace (absolute, normalised).
    pub namespace: Option<String>,
    /// `-r __node:=...` (or `__name`): the node's name.
    pub node_name: Option<String>,
    /// Topic and service remaps, in order (the first match wins).
    pub remaps: Vec<Remap>,
    /// Parameter assignments in order (later ones win).
    pub params: Vec<ParamAssignment>,
    /// `--log-level`.
    pub log_level: Option<Severity>,
    /// `--disable-rosout-logs`.
    pub disable_rosout: bool,
    /// `--disable-stdout-logs`.
    pub disable_stdout: bool,
    /// `-h` / `--help` outside `--ros-args`.
    pub help: bool,
}

/// Usage text of `muscle_actuator node`.
pub const USAGE: &str = "\
usage: muscle_actuator node [--ros-args [-r __ns:=/NS] [-r __node:=NAME] [-r FROM:=TO]...
                             [-p NAME:=VALUE]... [--params-file FILE.yaml]...
                             [--log-level [LOGGER:=]LEVEL] [--]]

parameters: model (hill|huxley|huxley-pde, default huxley), rate_hz (default 1000.0),
            publish_rate_hz (0 = every tick), config (TOML file, \"\" = embedded default),
            record (bool), record_dir (string)
environment: ROS_DOMAIN_ID (default 0); ROS_AUTOMATIC_DISCOVERY_RANGE=SUBNET to discover
             beyond this host (default: loopback only)";

impl RosArgs {
    /// Parses everything after `node` on the command line. Parameter files are read here.
    pub fn parse(args: &[String]) -> Result<Self, String> {
        let mut out = RosArgs::default();
        let mut i = 0;
        let mut in_ros = false;
        while i < args.len() {
            let a = args[i].as_str();
            if !in_ros {
                match a {
                    "--ros-args" => in_ros = true,
                    "-h" | "--help" => out.help = true,
                    other => {
                        return Err(format!(
                            "unexpected argument {:?}: ROS arguments go after --ros-args \
                             (try `muscle_actuator node --help`)",
                            excerpt(other)
                        ))
                    }
                }
                i += 1;
                continue;
            }
            let mut value = |flag: &str| -> Result<String, String> {
                i += 1;
                args.get(i)
                    .cloned()
                    .ok_or_else(|| format!("{flag} needs a value"))
            };
            match a {
                "--" => in_ros = false,
                "--ros-args" => {}
                "-r" | "--remap" => {
                    let rule = value(a)?;
                    out.add_remap(&rule)?;
                }
                "-p" | "--param" => {
                    let rule = value(a)?;
                    let (name, val) = rule.split_once(":=").ok_or_else(|| {
                        format!(
                            "-p {:?}: expected NAME:=VALUE (e.g. -p model:=hill)",
                            excerpt(&rule)
                        )
                    })?;
                    if name.is_empty() {
                        return Err(format!("-p {:?}: empty parameter name", excerpt(&rule)));
                    }
                    check_flow_depth(val).map_err(|e| format!("-p {:?}: {e}", excerpt(&rule)))?;
                    let yaml: serde_yaml::Value = if val.is_empty() {
                        serde_yaml::Value::String(String::new())
                    } else {
                        serde_yaml::from_str(val).unwrap_or(serde_yaml::Value::String(val.into()))
                    };
                    let value = yaml_to_param(&yaml)
                        .map_err(|e| format!("-p {:?}: {e}", excerpt(&rule)))?;
                    out.params.push(ParamAssignment {
                        name: name.into(),
                        value,
                        source: format!("-p {}", excerpt(&rule)),
                    });
                }
                "--params-file" => {
                    let file = value(a)?;
                    out.params.push(ParamAssignment {
                        name: String::new(),
                        value: ParameterValue::String(file),
                        source: PARAMS_FILE_MARK.into(),
                    });
                }
                "--log-level" => {
                    let spec = value(a)?;
                    // `--log-level level` or `--log-level logger:=level`; every logger of this
                    // process is the node's.
                    let level = spec.rsplit_once(":=").map(|(_, l)| l).unwrap_or(&spec);
                    out.log_level = Some(Severity::parse(level).ok_or_else(|| {
                        format!(
                            "--log-level {:?}: unknown level (debug, info, warn, error, fatal)",
                            excerpt(&spec)
                        )
                    })?);
                }
                "-e" | "--enclave" => {
                    value(a)?;
                }
                "--disable-rosout-logs" => out.disable_rosout = true,
                "--enable-rosout-logs" => out.disable_rosout = false,
                "--disable-stdout-logs" => out.disable_stdout = true,
                "--enable-stdout-logs" => out.disable_stdout = false,
                "--disable-external-lib-logs" | "--enable-external-lib-logs" => {}
                other => {
                    return Err(format!(
                        "unknown ROS argument {:?} (expected -r, -p, --params-file, \
                         --log-level, --)",
                        excerpt(other)
                    ))
                }
            }
            i += 1;
        }
        Ok(out)
    }

    fn add_remap(&mut self, rule: &str) -> Result<(), String> {
        let quoted = excerpt(rule);
        let (lhs, to) = rule
            .split_once(":=")
            .ok_or_else(|| format!("-r {quoted:?}: expected FROM:=TO"))?;
        // An optional `node:` prefix (a name has no ':' otherwise).
        let (node, from) = match lhs.split_once(':') {
            Some((n, f)) => (Some(n.to_string()), f),
            None => (None, lhs),
        };
        if from.is_empty() || to.is_empty() {
            return Err(format!("-r {quoted:?}: empty name"));
        }
        if node.is_some() && (from == "__ns" || from == "__node" || from == "__name") {
            // Node-specific namespace/name changes: apply only to our node; checked later.
        }
        match from {
            "__ns" => {
                let ns = normalise_namespace(to)
                    .map_err(|e| format!("-r {quoted:?}: bad namespace: {e}"))?;
                self.push_node_rule(node, |s| s.namespace = Some(ns));
            }
            "__node" | "__name" => {
                check_node_name(to).map_err(|e| format!("-r {quoted:?}: bad node name: {e}"))?;
                let name = to.to_string();
                self.push_node_rule(node, |s| s.node_name = Some(name));
            }
            _ => {
                check_name(from).map_err(|e| format!("-r {quoted:?}: bad name: {e}"))?;
                check_name(to).map_err(|e| format!("-r {quoted:?}: bad name: {e}"))?;
                self.remaps.push(Remap {
                    node,
                    from: from.into(),
                    to: to.into(),
                });
            }
        }
        Ok(())
    }

    fn push_node_rule(&mut self, node: Option<String>, apply: impl FnOnce(&mut Self)) {
        // A node-prefixed __ns/__node rule applies only to a node of that name; ours is the
        // default name unless renamed, so compare with the default.
        match node {
            Some(n) if n != super::DEFAULT_NODE_NAME => {}
            _ => apply(self),
        }
    }

    /// The parameter assignments with every `--params-file` expanded for the node `fqn`
    /// (its fully qualified name) in command-line order.
    pub fn resolved_params(&self, fqn: &str) -> Result<Vec<ParamAssignment>, String> {
        let mut out = Vec::new();
        for p in &self.params {
            if p.source == PARAMS_FILE_MARK {
                if let ParameterValue::String(file) = &p.value {
                    out.extend(read_params_file(Path::new(file), fqn)?);
                }
            } else {
                out.push(p.clone());
            }
        }
        Ok(out)
    }
}

const PARAMS_FILE_MARK: &str = "\u{0}params-file";

/// Converts a YAML scalar or sequence into a parameter value of the ROS 2 types.
pub fn yaml_to_param(v: &serde_yaml::Value) -> Result<ParameterValue, String> {
    use serde_yaml::Value as Y;
    Ok(match v {
        Y::Bool(b) => ParameterValue::Boolean(*b),
        Y::Number(n) => {
            if let Some(i) = n.as_i64() {
                ParameterValue::Integer(i)
            } else if let Some(f) = n.as_f64() {
                ParameterValue::Double(f)
            } else {
                return Err(format!("number {n} out of range"));
            }
        }
        Y::String(s) => ParameterValue::String(s.clone()),
        Y::Null => return Err("empty value".into()),
        Y::Sequence(items) => {
            if items.is_empty() {
                ParameterValue::StringArray(vec![])
            } else if items.iter().all(|x| x.is_bool()) {
                ParameterValue::BooleanArray(items.iter().filter_map(|x| x.as_bool()).collect())
            } else if items.iter().all(|x| x.is_i64()) {
                ParameterValue::IntegerArray(items.iter().filter_map(|x| x.as_i64()).collect())
            } else if items.iter().all(|x| x.is_number()) {
                ParameterValue::DoubleArray(items.iter().filter_map(|x| x.as_f64()).collect())
            } else if items.iter().all(|x| x.is_string()) {
                ParameterValue::StringArray(
                    items
                        .iter()
                        .filter_map(|x| x.as_str().map(String::from))
                        .collect(),
                )
            } else {
                return Err("an array must hold values of one type".into());
            }
        }
        Y::Mapping(_) => return Err("a mapping is not a parameter value".into()),
        Y::Tagged(t) => return yaml_to_param(&t.value),
    })
}

/// Reads the `ros__parameters` of every section of a parameters file that applies to the node
/// `fqn`, as rcl does (`rcl_yaml_param_parser` then rclcpp's `parameter_map_from`): the keys
/// above a `ros__parameters` join with `/` into the section's node name (`/arm:` then
/// `muscle_actuator:` is `/arm/muscle_actuator`); a name without a leading slash gets one, so
/// `muscle_actuator:` is the node in the root namespace only; `*` stands for one name segment
/// and `**` for any number (`/**` is every node). Nested keys become dotted parameter names.
/// Every matching section applies, in file order.
pub fn read_params_file(path: &Path, fqn: &str) -> Result<Vec<ParamAssignment>, String> {
    let shown = excerpt(&path.display().to_string());
    let bytes = read_regular_file(path, MAX_PARAMS_FILE_BYTES).map_err(|e| {
        format!("cannot read parameters file {shown} (a regular file of at most 1 MiB): {e}")
    })?;
    let text =
        String::from_utf8(bytes).map_err(|_| format!("parameters file {shown}: not UTF-8 text"))?;
    parse_params_yaml(&text, &shown, fqn)
}

/// The key that holds a node's parameters.
const PARAMS_KEY: &str = "ros__parameters";

/// See [`read_params_file`]; `source` names the file in errors.
pub fn parse_params_yaml(
    text: &str,
    source: &str,
    fqn: &str,
) -> Result<Vec<ParamAssignment>, String> {
    check_flow_depth(text).map_err(|e| format!("parameters file {source}: {e}"))?;
    let doc: serde_yaml::Value = serde_yaml::from_str(text)
        .map_err(|e| format!("parameters file {source}: not valid YAML: {e}"))?;
    let top = match &doc {
        serde_yaml::Value::Mapping(m) => m,
        serde_yaml::Value::Null => return Ok(vec![]),
        _ => {
            return Err(format!(
                "parameters file {source}: expected `node_name: {{ros__parameters: {{...}}}}`"
            ))
        }
    };
    let mut sections = Vec::new();
    node_sections(top, "", source, &mut sections)?;
    let mut out = Vec::new();
    for (node, params) in sections {
        if node_key_matches(&node, fqn) {
            flatten(params, "", source, &mut out)?;
        }
    }
    Ok(out)
}

/// Joins a node-name key to the names above it, as rcl's `add_name_to_ns` does: with a `/`
/// unless the names above already end with one.
fn join_node_key(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else if prefix.ends_with('/') {
        format!("{prefix}{key}")
    } else {
        format!("{prefix}/{key}")
    }
}

/// Collects `(node name, ros__parameters value)` for every section below `map`, whose keys
/// so far joined into `prefix`. As in rcl, the keys beside a `ros__parameters` are names in
/// the node's namespace (siblings of the node), and a plain value before any
/// `ros__parameters` is an error.
fn node_sections<'a>(
    map: &'a serde_yaml::Mapping,
    prefix: &str,
    source: &str,
    out: &mut Vec<(String, &'a serde_yaml::Value)>,
) -> Result<(), String> {
    let parent = match map.get(PARAMS_KEY) {
        Some(params) => {
            if prefix.is_empty() {
                return Err(format!(
                    "parameters file {source}: `{PARAMS_KEY}` needs a node name above it"
                ));
            }
            out.push((prefix.to_string(), params));
            // The node's own name dropped: its siblings live in its namespace.
            match prefix.rfind('/') {
                Some(0) => "/".to_string(),
                Some(i) => prefix[..i].to_string(),
                None => String::new(),
            }
        }
        None => prefix.to_string(),
    };
    for (key, value) in map {
        let key = key
            .as_str()
            .ok_or_else(|| format!("parameters file {source}: node keys must be strings"))?;
        if key == PARAMS_KEY {
            continue;
        }
        if key.is_empty() {
            return Err(format!("parameters file {source}: empty node key"));
        }
        let name = join_node_key(&parent, key);
        let Some(inner) = value.as_mapping() else {
            return Err(format!(
                "parameters file {source}: {:?} holds a value before any `{PARAMS_KEY}` \
                 (expected `node_name: {{{PARAMS_KEY}: {{...}}}}`)",
                excerpt(&name)
            ));
        };
        node_sections(inner, &name, source, out)?;
    }
    Ok(())
}

fn flatten(
    v: &serde_yaml::Value,
    prefix: &str,
    source: &str,
    out: &mut Vec<ParamAssignment>,
) -> Result<(), String> {
    let Some(map) = v.as_mapping() else {
        return Err(format!(
            "parameters file {source}: `ros__parameters` must be a mapping"
        ));
    };
    for (k, val) in map {
        let k = match k {
            serde_yaml::Value::String(s) => s.clone(),
            other => serde_yaml::to_string(other)
                .unwrap_or_default()
                .trim()
                .to_string(),
        };
        let name = if prefix.is_empty() {
            k
        } else {
            format!("{prefix}.{k}")
        };
        if val.is_mapping() {
            flatten(val, &name, source, out)?;
        } else {
            let value = yaml_to_param(val).map_err(|e| {
                format!(
                    "parameters file {source}: parameter {:?}: {e}",
                    excerpt(&name)
                )
            })?;
            out.push(ParamAssignment {
                name,
                value,
                source: source.into(),
            });
        }
    }
    Ok(())
}

/// Whether a parameters-file node name applies to the node `fqn`, as rclcpp's
/// `parameter_map_from` decides: a leading `/` is added when missing (so a bare name is a node
/// in the root namespace), then the whole name must match, `*` standing for one segment and
/// `**` for any number of segments (none included).
pub fn node_key_matches(key: &str, fqn: &str) -> bool {
    let key = key.strip_prefix('/').unwrap_or(key);
    let pat: Vec<&str> = key.split('/').collect();
    let name: Vec<&str> = fqn.split('/').skip(1).collect();
    glob(&pat, &name)
}

/// Whole-name match of segment patterns (`*` one segment, `**` any number), by dynamic
/// programming: a hostile key of thousands of `**` costs `pat × name` steps, not exponential.
fn glob(pat: &[&str], name: &[&str]) -> bool {
    // ok[j]: pat[..i] matches name[..j].
    let mut ok = vec![false; name.len() + 1];
    ok[0] = true;
    for p in pat {
        let mut next = vec![false; name.len() + 1];
        if *p == "**" {
            let mut any = false;
            for j in 0..=name.len() {
                any |= ok[j];
                next[j] = any;
            }
        } else {
            for j in 1..=name.len() {
                next[j] = ok[j - 1] && (*p == "*" || *p == name[j - 1]);
            }
        }
        ok = next;
    }
    ok[name.len()]
}

/// Checks the nesting of YAML flow collections before the text is parsed (see
/// [`MAX_FLOW_DEPTH`]). Brackets are counted wherever they stand, quoted or not: a text whose
/// strings open 64 brackets without closing them is refused too.
pub fn check_flow_depth(text: &str) -> Result<(), String> {
    let mut depth = 0usize;
    for b in text.bytes() {
        match b {
            b'[' | b'{' => {
                depth += 1;
                if depth > MAX_FLOW_DEPTH {
                    return Err(format!(
                        "nested deeper than {MAX_FLOW_DEPTH} levels of [ ] or {{ }}"
                    ));
                }
            }
            b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(())
}

/// Checks a node name: one token (see [`check_token`]) of at most 255 characters.
pub fn check_node_name(n: &str) -> Result<(), String> {
    if n.chars().count() > MAX_NODE_NAME_CHARS {
        return Err(format!(
            "{} characters: a node name has at most {MAX_NODE_NAME_CHARS}",
            n.chars().count()
        ));
    }
    check_token(n)
}

/// Checks one name token: starts with a letter or `_`, then letters, digits, `_`.
fn check_token(t: &str) -> Result<(), String> {
    let mut chars = t.chars();
    match chars.next() {
        None => return Err("empty".into()),
        Some(c) if c.is_ascii_alphabetic() || c == '_' => {}
        Some(c) => return Err(format!("must not start with {c:?}")),
    }
    if let Some(c) = t
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '_'))
    {
        return Err(format!("character {c:?} not allowed"));
    }
    if t.contains("__") {
        return Err("repeated underscores are not allowed".into());
    }
    Ok(())
}

/// Checks a topic or service name as written by a user: absolute, relative or private (`~`).
pub fn check_name(n: &str) -> Result<(), String> {
    if n.chars().count() > MAX_TOPIC_NAME_CHARS {
        return Err(format!(
            "{} characters: a topic or service name has at most {MAX_TOPIC_NAME_CHARS}",
            n.chars().count()
        ));
    }
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
        return Err("empty".into());
    }
    for tok in rest.split('/') {
        check_token(tok)?;
    }
    Ok(())
}

/// Normalises a namespace: absolute, no trailing slash (except the root `/`).
pub fn normalise_namespace(ns: &str) -> Result<String, String> {
    if ns.chars().count() > MAX_NAMESPACE_CHARS {
        return Err(format!(
            "{} characters: a namespace has at most {MAX_NAMESPACE_CHARS}",
            ns.chars().count()
        ));
    }
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

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn parses_the_standard_arguments() {
        let a = RosArgs::parse(&args(
            "--ros-args -r __ns:=/lab/arm -r __node:=elbow_sim -r ~/state:=/st \
             -p model:=hill -p rate_hz:=500 -p publish_rate_hz:=100.0 -p record:=false \
             --log-level WARN --",
        ))
        .unwrap();
        assert_eq!(a.namespace.as_deref(), Some("/lab/arm"));
        assert_eq!(a.node_name.as_deref(), Some("elbow_sim"));
        assert_eq!(a.remaps.len(), 1);
        assert_eq!(a.params.len(), 4);
        assert_eq!(a.params[0].value, ParameterValue::String("hill".into()));
        assert_eq!(a.params[1].value, ParameterValue::Integer(500));
        assert_eq!(a.params[2].value, ParameterValue::Double(100.0));
        assert_eq!(a.params[3].value, ParameterValue::Boolean(false));
        assert_eq!(a.log_level, Some(Severity::Warn));
    }

    #[test]
    fn rejects_bad_arguments_with_a_reason() {
        for bad in [
            "--bogus",
            "--ros-args -r nothing",
            "--ros-args -p novalue",
            "--ros-args -p",
            "--ros-args --log-level loud",
            "--ros-args -r __ns:=/bad-name",
            "--ros-args -r __node:=9x",
            "--ros-args --frobnicate",
        ] {
            let e = RosArgs::parse(&args(bad)).unwrap_err();
            assert!(!e.is_empty(), "{bad}");
        }
    }

    /// Oversized arguments are refused with the rule they break, quoted as short excerpts.
    #[test]
    fn oversized_arguments_are_refused_briefly() {
        let long = |prefix: &str, n: usize| {
            vec![
                "--ros-args".to_string(),
                "-r".into(),
                format!("{prefix}{}", "n".repeat(n)),
            ]
        };
        let e = RosArgs::parse(&long("__node:=", 10_000)).unwrap_err();
        assert!(e.contains("at most 255") && e.len() < 300, "{e}");
        assert!(RosArgs::parse(&long("__node:=", 255)).is_ok());
        let e = RosArgs::parse(&long("__ns:=/", 300)).unwrap_err();
        assert!(e.contains("at most 245") && e.len() < 300, "{e}");
        let e = RosArgs::parse(&long("state:=", 300)).unwrap_err();
        assert!(e.contains("at most 247") && e.len() < 300, "{e}");
        let deep = format!("x:={}{}", "[".repeat(100_000), "]".repeat(100_000));
        let e = RosArgs::parse(&["--ros-args".into(), "-p".into(), deep]).unwrap_err();
        assert!(e.contains("nested deeper than 64") && e.len() < 300, "{e}");
        let e = RosArgs::parse(&["--ros-args".into(), "--bogus".into(), "b".repeat(1 << 20)])
            .unwrap_err();
        assert!(e.len() < 300, "{e}");
    }

    /// A parameters file nested 100,000 levels deep is refused at once (libyaml alone took
    /// minutes); `/dev/zero` and a FIFO are refused without reading them.
    #[test]
    fn hostile_parameters_files_are_refused() {
        let deep = format!(
            "/**:\n  ros__parameters:\n    x: {}1{}\n",
            "{a: ".repeat(100_000),
            "}".repeat(100_000)
        );
        let e = parse_params_yaml(&deep, "deep.yaml", "/muscle_actuator").unwrap_err();
        assert!(e.contains("nested deeper than 64"), "{e}");
        let e = read_params_file(Path::new("/dev/zero"), "/muscle_actuator").unwrap_err();
        assert!(e.contains("regular file"), "{e}");
        let dir = std::env::temp_dir().join(format!("params-fifo-{}", std::process::id()));
        let _ = std::fs::remove_file(&dir);
        let c = std::ffi::CString::new(dir.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let e = read_params_file(&dir, "/muscle_actuator").unwrap_err();
        let _ = std::fs::remove_file(&dir);
        assert!(e.contains("regular file"), "{e}");
        // Ordinary nesting still reads.
        let ok = "/**:\n  ros__parameters:\n    rate_hz: 500.0\n    nested: {list: [1, 2, 3]}\n";
        assert!(parse_params_yaml(ok, "ok.yaml", "/muscle_actuator").is_ok());
    }

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

    /// The names of the parameters a file gives the node `fqn`.
    fn names_for(yaml: &str, fqn: &str) -> Vec<String> {
        parse_params_yaml(yaml, "f.yaml", fqn)
            .unwrap()
            .into_iter()
            .map(|a| a.name)
            .collect()
    }

    #[test]
    fn params_file_sections_apply_by_node_name() {
        let yaml = "
/**:
  ros__parameters:
    record: false
    robot_name: r2
muscle_actuator:
  ros__parameters:
    model: hill
    nested:
      value: 3
/other/node:
  ros__parameters:
    model: huxley
/lab/*:
  ros__parameters:
    rate_hz: 250.0
";
        // `muscle_actuator:` is the root namespace's node only.
        assert_eq!(
            names_for(yaml, "/lab/muscle_actuator"),
            ["record", "robot_name", "rate_hz"]
        );
        assert_eq!(
            names_for(yaml, "/muscle_actuator"),
            ["record", "robot_name", "model", "nested.value"]
        );
        assert_eq!(
            names_for(yaml, "/other/node"),
            ["record", "robot_name", "model"]
        );
        assert!(parse_params_yaml("a: [", "f", "/x").is_err());
        assert!(parse_params_yaml("x:\n  nope: 1\n", "f", "/x").is_err());
        assert!(parse_params_yaml("ros__parameters:\n  a: 1\n", "f", "/x").is_err());
    }

    /// Each layout of the rcl documentation, for the node `/arm/muscle_actuator`.
    #[test]
    fn params_file_layouts() {
        let fqn = "/arm/muscle_actuator";
        let one = |key: &str| format!("{key}:\n  ros__parameters:\n    rate_hz: 250.0\n");
        // Flat `/**`, `/**/name`, the exact name, `/arm/*`.
        for key in [
            "/**",
            "\"**\"",
            "/**/muscle_actuator",
            "/arm/muscle_actuator",
            "/arm/*",
        ] {
            assert_eq!(names_for(&one(key), fqn), ["rate_hz"], "{key}");
        }
        // A key without a leading slash is the root namespace's node; others do not apply.
        for key in [
            "muscle_actuator",
            "/muscle_actuator",
            "/other/muscle_actuator",
            "/*",
        ] {
            assert!(names_for(&one(key), fqn).is_empty(), "{key}");
        }
        assert_eq!(
            names_for(&one("muscle_actuator"), "/muscle_actuator"),
            ["rate_hz"]
        );
        assert_eq!(names_for(&one("/*"), "/muscle_actuator"), ["rate_hz"]);
        // Nested namespace keys: `/arm:` then `muscle_actuator:`.
        let nested = "
/arm:
  muscle_actuator:
    ros__parameters:
      rate_hz: 250.0
      model: hill
  other_node:
    ros__parameters:
      robot_name: r2
";
        assert_eq!(names_for(nested, fqn), ["rate_hz", "model"]);
        assert!(names_for(nested, "/muscle_actuator").is_empty());
        assert_eq!(names_for(nested, "/arm/other_node"), ["robot_name"]);
        // Deeper: `/lab:` then `arm:` then the node; `arm/` ending in a slash; `/**:` then the node.
        let deeper =
            "/lab:\n  arm:\n    muscle_actuator:\n      ros__parameters:\n        record: true\n";
        assert_eq!(names_for(deeper, "/lab/arm/muscle_actuator"), ["record"]);
        assert!(names_for(deeper, fqn).is_empty());
        let slash = "/lab/:\n  muscle_actuator:\n    ros__parameters:\n      record: true\n";
        assert_eq!(names_for(slash, "/lab/muscle_actuator"), ["record"]);
        let wild = "/**:\n  muscle_actuator:\n    ros__parameters:\n      record: true\n";
        assert_eq!(names_for(wild, fqn), ["record"]);
        assert_eq!(names_for(wild, "/muscle_actuator"), ["record"]);
        assert!(names_for(wild, "/arm/other").is_empty());
        // A bare top key nests the same way: `arm:` then the node is `/arm/muscle_actuator`.
        let bare = "arm:\n  muscle_actuator:\n    ros__parameters:\n      record: true\n";
        assert_eq!(names_for(bare, fqn), ["record"]);
        // Keys beside `ros__parameters` are the node's siblings, as rcl reads them.
        let sib = "/arm:\n  a:\n    ros__parameters:\n      x: 1\n    b:\n      ros__parameters:\n        y: 2\n";
        assert_eq!(names_for(sib, "/arm/a"), ["x"]);
        assert_eq!(names_for(sib, "/arm/b"), ["y"]);
        // A section for another node with values this node would refuse is not read.
        let other =
            "/other:\n  ros__parameters:\n    x: ~\n/**:\n  ros__parameters:\n    record: true\n";
        assert_eq!(names_for(other, fqn), ["record"]);
    }

    #[test]
    fn node_keys_glob() {
        assert!(node_key_matches("/**", "/a/b"));
        assert!(node_key_matches("/**/b", "/a/b"));
        assert!(node_key_matches("/**/b", "/b"));
        assert!(node_key_matches("/a/**/b", "/a/b"));
        assert!(node_key_matches("/a/**/b", "/a/x/y/b"));
        assert!(node_key_matches("/a/*", "/a/b"));
        assert!(!node_key_matches("/a/*", "/a/c/b"));
        assert!(!node_key_matches("b", "/a/b"));
        assert!(node_key_matches("b", "/b"));
        assert!(!node_key_matches("/c/b", "/a/b"));
        // Thousands of `**` cost little.
        let hostile = format!("/{}x", "**/".repeat(100_000));
        assert!(!node_key_matches(&hostile, &"/a".repeat(100)));
    }
}
