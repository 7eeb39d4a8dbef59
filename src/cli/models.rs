//! `models`: the contractile models of the registry, one a line, the default marked.

use muscle_actuator_core::physics::models::ModelKind;

/// The `models` listing: each model's name and summary, the default marked.
pub fn models_listing() -> String {
    let width = ModelKind::all().map(|m| m.name().len()).max().unwrap_or(0);
    let mut out = String::new();
    for m in ModelKind::all() {
        let mark = if m == ModelKind::DEFAULT {
            " [default]"
        } else {
            ""
        };
        out.push_str(&format!(
            "{:width$}  {}{mark}\n",
            m.name(),
            m.spec().summary
        ));
    }
    out
}
