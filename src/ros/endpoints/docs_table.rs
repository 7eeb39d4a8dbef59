//! docs/ros-interface.md's table of topics and services lists exactly the endpoints of
//! [`ENDPOINTS`] on DDS (kind, name, type), and docs/recordings.md names the recording's own,
//! so the pages cannot drift from the node.

use super::table::{Direction, ENDPOINTS};
use crate::ros::markdown_table::rows_under;

const INTERFACE: &str = include_str!("../../../docs/ros-interface.md");
const RECORDINGS: &str = include_str!("../../../docs/recordings.md");

/// The rows (kind, name, type) of the table under `## Topics and services`.
fn doc_rows() -> Vec<(String, String, String)> {
    let cell = |c: &String| c.trim_matches('`').to_string();
    rows_under(INTERFACE, "Topics and services")
        .iter()
        .map(|c| (cell(&c[0]), cell(&c[1]), cell(&c[2])))
        .collect()
}

/// The rows (kind, name, type) the table of docs/ros-interface.md must have: one per endpoint on
/// DDS.
pub(crate) fn expected_rows() -> Vec<(String, String, String)> {
    ENDPOINTS
        .iter()
        .filter(|s| s.direction != Direction::Recorded)
        .map(|s| {
            (
                s.direction.doc_name().to_string(),
                s.name.to_string(),
                s.type_name.to_string(),
            )
        })
        .collect()
}

#[test]
fn the_docs_list_every_endpoint() {
    let mut rows = doc_rows();
    let mut want = expected_rows();
    rows.sort();
    want.sort();
    assert_eq!(
        rows, want,
        "docs/ros-interface.md's topics and services table must list every entry of \
         src/ros/endpoints/table.rs on DDS as `| kind | `name` | `type` | notes |`"
    );
    for s in ENDPOINTS
        .iter()
        .filter(|s| s.direction == Direction::Recorded)
    {
        assert!(
            RECORDINGS.contains(&format!("`{}`", s.name)),
            "docs/recordings.md does not name {}",
            s.name
        );
    }
}

#[test]
fn every_endpoint_has_one_entry() {
    use super::table::{spec_of, Endpoint as E};
    assert_eq!(E::ALL.len(), ENDPOINTS.len());
    for &e in E::ALL {
        assert_eq!(ENDPOINTS.iter().filter(|s| s.endpoint == e).count(), 1);
        assert_eq!(spec_of(e).endpoint, e);
    }
}
