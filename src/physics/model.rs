//! Which contractile-element model drives the muscles: the one place where models are named.
//! Each model is one file in `physics/models/` implementing
//! [`ContractileModel`](crate::physics::muscle_model::ContractileModel); adding one is that file
//! plus its line in [`MODELS`].

use crate::physics::models::{distribution_moment, hill, huxley_pde};
pub use crate::physics::muscle_model::ModelKind;
use crate::physics::muscle_model::ModelSpec;
use std::str::FromStr;

/// Every model, in the order of their names.
pub static MODELS: [&ModelSpec; 3] = [&hill::SPEC, &distribution_moment::SPEC, &huxley_pde::SPEC];

impl ModelKind {
    /// Hill-type: force–length × force–velocity × activation (docs/model.md §3).
    pub const HILL: ModelKind = ModelKind(&hill::SPEC);
    /// Huxley-type cross-bridges reduced by the Distribution-Moment approximation (§6).
    pub const HUXLEY: ModelKind = ModelKind(&distribution_moment::SPEC);
    /// The full Huxley model solved by the method of characteristics (§7).
    pub const HUXLEY_PDE: ModelKind = ModelKind(&huxley_pde::SPEC);

    /// All models, in the order of [`MODELS`].
    pub fn all() -> impl Iterator<Item = ModelKind> {
        MODELS.iter().map(|s| ModelKind(s))
    }

    /// The names, comma-separated (for messages).
    pub fn names() -> String {
        MODELS.iter().map(|s| s.name).collect::<Vec<_>>().join(", ")
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
