//! The first Markdown table under a `## Heading` of a docs page, as rows of trimmed cells (the
//! header and its rule left out): what the tests that keep docs/ros-interface.md in step with
//! the node's tables read.

/// The rows of the first table after the line `## {heading}` of `page`, each cell trimmed.
pub(crate) fn rows_under(page: &str, heading: &str) -> Vec<Vec<String>> {
    let section = page
        .split(&format!("\n## {heading}\n"))
        .nth(1)
        .unwrap_or_else(|| panic!("the page has a `## {heading}` section"));
    section
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .skip(2) // the header and its rule
        .map(|l| {
            let cells: Vec<&str> = l.split('|').collect();
            // The outer pipes leave an empty first and last cell.
            cells[1..cells.len().saturating_sub(1)]
                .iter()
                .map(|c| c.trim().to_string())
                .collect()
        })
        .collect()
}
