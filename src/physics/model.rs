//! Which contractile-element model drives the muscles.

use std::fmt;
use std::str::FromStr;

/// The contractile-element model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModelKind {
    /// Hill-type: force–length × force–velocity × activation (MODEL.md §3).
    Hill,
    /// Huxley-type cross-bridges reduced by the Distribution-Moment approximation (MODEL.md §6).
    Huxley,
    /// The full Huxley model solved by the method of characteristics (MODEL.md §7).
    HuxleyPde,
}

impl ModelKind {
    /// All models, in the order of their names.
    pub const ALL: [ModelKind; 3] = [ModelKind::Hill, ModelKind::Huxley, ModelKind::HuxleyPde];

    /// The name used on the command line, in parameters and in messages.
    pub fn name(self) -> &'static str {
        match self {
            ModelKind::Hill => "hill",
            ModelKind::Huxley => "huxley",
            ModelKind::HuxleyPde => "huxley-pde",
        }
    }
}

impl fmt::Display for ModelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown model name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown model {0:?}: expected one of hill, huxley, huxley-pde")]
pub struct UnknownModel(pub String);

impl FromStr for ModelKind {
    type Err = UnknownModel;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ModelKind::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| UnknownModel(s.into()))
    }
}
