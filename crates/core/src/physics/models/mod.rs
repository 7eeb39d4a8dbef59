//! The contractile-element models: the interface each implements (`contractile_model`:
//! `ContractileModel`, its `ModelSpec` and the [`ModelKind`] that names it), one file per
//! model, named by the model's name (`hill`, `huxley`, `huxley_pde`), and [`MODELS`], the one
//! place where they are named. Adding a model is its file plus its line in [`MODELS`].
//! Everything that names models (the command line's help and default, the node's `model`
//! parameter and its usage text, figures, the `MODEL_*` constants of `ActuatorState.msg`,
//! checked by `crates/recording/tests/msg_definitions.rs`) reads this list.

pub(crate) mod contractile_model;
pub(crate) mod hill;
pub(crate) mod huxley;
pub(crate) mod huxley_pde;

pub(crate) use contractile_model::{CeInputs, ContractileModel, ModelSpec, SubstepMotion};
pub use contractile_model::{ModelBuildError, ModelKind};
use std::str::FromStr;

/// Every model, from the simplest to the reference (the full Huxley model, docs/model.md §7).
#[cfg(not(any(test, feature = "test-model")))]
pub static MODELS: [&ModelSpec; 3] = [&hill::SPEC, &huxley::SPEC, &huxley_pde::SPEC];

/// Every model, and a fourth that only the tests know ([`test_model`]): whatever reads the list
/// must reach it by its name.
#[cfg(any(test, feature = "test-model"))]
pub static MODELS: [&ModelSpec; 4] = [
    &hill::SPEC,
    &huxley::SPEC,
    &huxley_pde::SPEC,
    &test_model::SPEC,
];

impl ModelKind {
    /// Hill-type: force–length × force–velocity × activation (docs/model.md §3).
    pub const HILL: ModelKind = ModelKind(&hill::SPEC);
    /// Huxley-type cross-bridges reduced by the Distribution-Moment approximation (§6).
    pub const HUXLEY: ModelKind = ModelKind(&huxley::SPEC);
    /// The full Huxley model solved by the method of characteristics (§7).
    pub const HUXLEY_PDE: ModelKind = ModelKind(&huxley_pde::SPEC);
    /// The model used when none is named: on the command line and as the node's `model`
    /// parameter.
    pub const DEFAULT: ModelKind = ModelKind::HUXLEY;

    /// All models, in the order of [`MODELS`].
    pub fn all() -> impl Iterator<Item = ModelKind> {
        MODELS.iter().map(|s| ModelKind(s))
    }

    /// The names, comma-separated (for messages).
    pub fn names() -> String {
        Self::names_joined(", ", ", ")
    }

    /// The names joined by `sep`, the last two by `last` (`hill, huxley or huxley-pde`).
    pub fn names_joined(sep: &str, last: &str) -> String {
        join(MODELS.iter().map(|s| s.name), sep, last)
    }
}

/// `items` joined by `sep`, the last two by `last`.
pub fn join<'a>(items: impl IntoIterator<Item = &'a str>, sep: &str, last: &str) -> String {
    let items: Vec<&str> = items.into_iter().collect();
    match items.split_last() {
        None => String::new(),
        Some((tail, [])) => tail.to_string(),
        Some((tail, init)) => format!("{}{last}{tail}", init.join(sep)),
    }
}

/// An unknown model name (quoted as a short excerpt).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown model {0:?}: expected one of {names}", names = ModelKind::names())]
pub struct UnknownModel(pub String);

impl FromStr for ModelKind {
    type Err = UnknownModel;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ModelKind::all()
            .find(|m| m.name() == s)
            .ok_or_else(|| UnknownModel(s.chars().take(64).collect()))
    }
}

/// A fourth model for the tests: the Hill element under another name, with a stepping of its
/// own (the `test-model` feature). The `muscle_actuator` crate's `src/tests_fourth_model.rs`
/// checks that every reader of [`MODELS`] reaches it.
#[cfg(any(test, feature = "test-model"))]
pub mod test_model {
    use crate::physics::limb_params::MuscleParams;
    use crate::physics::models::hill;
    use crate::physics::models::{CeInputs, ContractileModel, ModelBuildError, ModelSpec};
    use crate::physics::stepping::Stepping;

    /// Its entry in [`super::MODELS`].
    pub static SPEC: ModelSpec = ModelSpec {
        name: "hill-copy",
        label: "Hill (copy)",
        short_label: "Hill copy",
        summary: "the Hill element under another name (tests only)",
        stepping: Stepping::Adaptive {
            tolerance: 5e-5,
            max_substeps: 48,
        },
        fourth_order_transients: false,
        build,
    };

    /// The Hill element, answering to this model's spec.
    #[derive(Debug, Clone)]
    struct HillCopy(Box<dyn ContractileModel>);

    fn build(p: &MuscleParams) -> Result<Box<dyn ContractileModel>, ModelBuildError> {
        Ok(Box::new(HillCopy((hill::SPEC.build)(p)?)))
    }

    impl ContractileModel for HillCopy {
        fn state_dim(&self) -> usize {
            self.0.state_dim()
        }
        fn state_scales(&self, out: &mut [f64]) {
            self.0.state_scales(out)
        }
        fn force(&self, ce: &CeInputs, x: &[f64]) -> f64 {
            self.0.force(ce, x)
        }
        fn rates(&self, t: f64, ce: &CeInputs, x: &[f64], dx: &mut [f64]) {
            self.0.rates(t, ce, x, dx)
        }
        fn stiffness(&self, ce: &CeInputs, x: &[f64]) -> f64 {
            self.0.stiffness(ce, x)
        }
        fn energy(&self, x: &[f64]) -> f64 {
            self.0.energy(x)
        }
        fn moments(&self, x: &[f64]) -> [f64; 3] {
            self.0.moments(x)
        }
        fn clone_box(&self) -> Box<dyn ContractileModel> {
            Box::new(self.clone())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_join_as_prose() {
        assert_eq!(join(["a"], ", ", " or "), "a");
        assert_eq!(join(["a", "b"], ", ", " or "), "a or b");
        assert_eq!(join(["a", "b", "c"], ", ", " or "), "a, b or c");
        assert_eq!(join([], ", ", " or "), "");
    }

    /// The three models of the paper are the first three entries, in this order.
    #[test]
    fn the_paper_models_lead_the_list() {
        let names: Vec<&str> = ModelKind::all().map(|m| m.name()).take(3).collect();
        assert_eq!(names, ["hill", "huxley", "huxley-pde"]);
        assert_eq!(ModelKind::DEFAULT.name(), "huxley");
        for m in ModelKind::all() {
            assert_eq!(m.name().parse::<ModelKind>(), Ok(m));
        }
    }
}
