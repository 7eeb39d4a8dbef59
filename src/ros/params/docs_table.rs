//! docs/ros-interface.md's parameters table lists exactly [`PARAMETERS`] (and the standard
//! `use_sim_time`), each with the table's type and default, so the page cannot drift from the
//! node.

use super::given::Kind;
use super::table::{DefaultValue, USE_SIM_TIME};
use super::{NodeParams, PARAMETERS};
use crate::ros::markdown_table::rows_under;

const DOC: &str = include_str!("../../../docs/ros-interface.md");

/// The rows (name, type, default) of the table under `## Parameters`.
fn doc_rows() -> Vec<(String, String, String)> {
    rows_under(DOC, "Parameters")
        .into_iter()
        .map(|c| {
            (
                c[0].trim_matches('`').to_string(),
                c[1].clone(),
                c[2].clone(),
            )
        })
        .collect()
}

#[test]
fn the_docs_list_every_parameter_with_its_type_and_default() {
    let rows = doc_rows();
    let mut want: Vec<(String, String, String)> = PARAMETERS
        .iter()
        .map(|s| {
            (
                s.name.to_string(),
                s.kind.doc_name().to_string(),
                s.default.text(true),
            )
        })
        .collect();
    want.push((USE_SIM_TIME.into(), "bool".into(), "false".into()));
    assert_eq!(
        rows, want,
        "docs/ros-interface.md's parameters table must list, in order, every entry of \
         src/ros/params/table.rs as `| `name` | type | default | meaning |`"
    );
}

#[test]
fn defaults_pass_their_checks_and_read_back() {
    let p = NodeParams::default();
    for s in PARAMETERS {
        assert_eq!((s.get)(&p), s.default.value(), "{}", s.name);
    }
    assert_eq!(
        super::spec("model").unwrap().default,
        DefaultValue::Str(muscle_actuator_core::physics::models::ModelKind::DEFAULT.name())
    );
    // Names are unique.
    let mut names = super::table::names();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), PARAMETERS.len());
    assert!(PARAMETERS.iter().all(|s| s.kind != Kind::Name
        || matches!(s.default, DefaultValue::Str(d) if d.len() <= super::limits::MAX_NAME_CHARS)));
}
