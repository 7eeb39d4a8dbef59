//! Parameter values and parameter files as rcl reads them (`rcl_yaml_param_parser`, then
//! rclcpp's `parameter_map_from`): YAML values to ROS 2 parameter types, the node sections of a
//! file and which of them apply to a node, and the bounds checked before any YAML is parsed.

use super::error::{ArgsError, FlowTooDeep, ParamsFileError, ValueError};
use super::ParamAssignment;
use muscle_actuator_core::{files::read_regular_file, text::excerpt};
use ros2_client::ParameterValue;
use std::path::Path;

/// Largest parameters file, bytes.
pub const MAX_PARAMS_FILE_BYTES: u64 = 1 << 20;
/// Deepest nesting of YAML flow collections (`[`, `{`) in a parameters file or a `-p` value.
/// serde_norway refuses more than 128 levels, but only after libyaml has parsed the rest, which
/// takes minutes for 100,000 levels: the text is checked before it is parsed.
pub const MAX_FLOW_DEPTH: usize = 64;

/// One `-p NAME:=VALUE` rule: the value read as a YAML scalar or flow sequence, as rcl reads
/// it (a value that is not valid YAML is the string itself; an empty one is the empty string).
pub fn parse_param_rule(rule: &str) -> Result<ParamAssignment, ArgsError> {
    let quoted = || excerpt(rule);
    let (name, val) = rule
        .split_once(":=")
        .ok_or_else(|| ArgsError::ParamSyntax { rule: quoted() })?;
    if name.is_empty() {
        return Err(ArgsError::ParamEmptyName { rule: quoted() });
    }
    check_flow_depth(val).map_err(|source| ArgsError::ParamTooDeep {
        rule: quoted(),
        source,
    })?;
    let yaml: serde_norway::Value = if val.is_empty() {
        serde_norway::Value::String(String::new())
    } else {
        serde_norway::from_str(val).unwrap_or(serde_norway::Value::String(val.into()))
    };
    let value = yaml_to_param(&yaml).map_err(|source| ArgsError::ParamValue {
        rule: quoted(),
        source,
    })?;
    Ok(ParamAssignment {
        name: name.into(),
        value,
        source: format!("-p {}", excerpt(rule)),
    })
}

/// Converts a YAML scalar or sequence into a parameter value of the ROS 2 types.
pub fn yaml_to_param(v: &serde_norway::Value) -> Result<ParameterValue, ValueError> {
    use serde_norway::Value as Y;
    Ok(match v {
        Y::Bool(b) => ParameterValue::Boolean(*b),
        Y::Number(n) => {
            if let Some(i) = n.as_i64() {
                ParameterValue::Integer(i)
            } else if let Some(f) = n.as_f64() {
                ParameterValue::Double(f)
            } else {
                return Err(ValueError::OutOfRange(n.to_string()));
            }
        }
        Y::String(s) => ParameterValue::String(s.clone()),
        Y::Null => return Err(ValueError::Empty),
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
                return Err(ValueError::MixedArray);
            }
        }
        Y::Mapping(_) => return Err(ValueError::Mapping),
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
pub fn read_params_file(path: &Path, fqn: &str) -> Result<Vec<ParamAssignment>, ParamsFileError> {
    let shown = excerpt(&path.display().to_string());
    let bytes =
        read_regular_file(path, MAX_PARAMS_FILE_BYTES).map_err(|source| ParamsFileError::Read {
            file: shown.clone(),
            source,
        })?;
    let text = String::from_utf8(bytes).map_err(|_| ParamsFileError::NotUtf8 {
        file: shown.clone(),
    })?;
    parse_params_yaml(&text, &shown, fqn)
}

/// The key that holds a node's parameters.
const PARAMS_KEY: &str = "ros__parameters";

/// See [`read_params_file`]; `source` names the file in errors.
pub fn parse_params_yaml(
    text: &str,
    source: &str,
    fqn: &str,
) -> Result<Vec<ParamAssignment>, ParamsFileError> {
    let file = || source.to_string();
    check_flow_depth(text).map_err(|e| ParamsFileError::TooDeep {
        file: file(),
        source: e,
    })?;
    let doc: serde_norway::Value =
        serde_norway::from_str(text).map_err(|e| ParamsFileError::Yaml {
            file: file(),
            source: e,
        })?;
    let top = match &doc {
        serde_norway::Value::Mapping(m) => m,
        serde_norway::Value::Null => return Ok(vec![]),
        _ => return Err(ParamsFileError::NotNodeSections { file: file() }),
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
    map: &'a serde_norway::Mapping,
    prefix: &str,
    source: &str,
    out: &mut Vec<(String, &'a serde_norway::Value)>,
) -> Result<(), ParamsFileError> {
    let file = || source.to_string();
    let parent = match map.get(PARAMS_KEY) {
        Some(params) => {
            if prefix.is_empty() {
                return Err(ParamsFileError::NoNodeName { file: file() });
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
            .ok_or_else(|| ParamsFileError::NodeKeyNotString { file: file() })?;
        if key == PARAMS_KEY {
            continue;
        }
        if key.is_empty() {
            return Err(ParamsFileError::EmptyNodeKey { file: file() });
        }
        let name = join_node_key(&parent, key);
        let Some(inner) = value.as_mapping() else {
            return Err(ParamsFileError::ValueBeforeParameters {
                file: file(),
                name: excerpt(&name),
            });
        };
        node_sections(inner, &name, source, out)?;
    }
    Ok(())
}

fn flatten(
    v: &serde_norway::Value,
    prefix: &str,
    source: &str,
    out: &mut Vec<ParamAssignment>,
) -> Result<(), ParamsFileError> {
    let Some(map) = v.as_mapping() else {
        return Err(ParamsFileError::ParametersNotMapping {
            file: source.to_string(),
        });
    };
    for (k, val) in map {
        let k = match k {
            serde_norway::Value::String(s) => s.clone(),
            other => serde_norway::to_string(other)
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
            let value = yaml_to_param(val).map_err(|e| ParamsFileError::Value {
                file: source.to_string(),
                name: excerpt(&name),
                source: e,
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
pub fn check_flow_depth(text: &str) -> Result<(), FlowTooDeep> {
    let mut depth = 0usize;
    for b in text.bytes() {
        match b {
            b'[' | b'{' => {
                depth += 1;
                if depth > MAX_FLOW_DEPTH {
                    return Err(FlowTooDeep {
                        max: MAX_FLOW_DEPTH,
                    });
                }
            }
            b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A parameters file nested 100,000 levels deep is refused before libyaml parses it (which
    /// takes minutes); `/dev/zero` and a FIFO are refused without reading them.
    #[test]
    fn hostile_parameters_files_are_refused() {
        let deep = format!(
            "/**:\n  ros__parameters:\n    x: {}1{}\n",
            "{a: ".repeat(100_000),
            "}".repeat(100_000)
        );
        let e = parse_params_yaml(&deep, "deep.yaml", "/muscle_actuator")
            .unwrap_err()
            .to_string();
        assert!(e.contains("nested deeper than 64"), "{e}");
        let e = read_params_file(Path::new("/dev/zero"), "/muscle_actuator")
            .unwrap_err()
            .to_string();
        assert!(e.contains("regular file"), "{e}");
        let dir = std::env::temp_dir().join(format!("params-fifo-{}", std::process::id()));
        let _ = std::fs::remove_file(&dir);
        let c = std::ffi::CString::new(dir.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let e = read_params_file(&dir, "/muscle_actuator")
            .unwrap_err()
            .to_string();
        let _ = std::fs::remove_file(&dir);
        assert!(e.contains("regular file"), "{e}");
        // Ordinary nesting still reads.
        let ok = "/**:\n  ros__parameters:\n    rate_hz: 500.0\n    nested: {list: [1, 2, 3]}\n";
        assert!(parse_params_yaml(ok, "ok.yaml", "/muscle_actuator").is_ok());
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
