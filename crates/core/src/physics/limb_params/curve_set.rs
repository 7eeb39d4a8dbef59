//! The name of a muscle's curve set (docs/model.md §4b), a parameter of the muscle; the curves
//! themselves are [`crate::physics::curves`].

use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// Which curves a Hill-type muscle uses. Read from its name ([`CurveSet::from_str`]), so an
/// unknown name is refused with the names ([`UnknownCurveSet`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase", try_from = "String")]
pub enum CurveSet {
    /// The paper's curves (docs/model.md §3–§4).
    #[default]
    Paper,
    /// De Groote et al. (2016), Ann Biomed Eng 44(10), as OpenSim's DeGrooteFregly2016Muscle.
    DeGroote2016,
    /// Thelen (2003), J Biomech Eng 125(1), as OpenSim's Thelen2003Muscle.
    Thelen2003,
    /// Millard et al. (2013), J Biomech Eng 135(2), as OpenSim's Millard2012EquilibriumMuscle.
    Millard2012,
    /// Curves given as points in the muscle's `tabulated` table (a CEINMS subject's), each
    /// interpolated as CEINMS interpolates it (`crate::physics::curves::tabulated`).
    Tabulated,
}

impl CurveSet {
    /// Every curve set.
    pub(crate) const ALL: [CurveSet; 5] = [
        CurveSet::Paper,
        CurveSet::DeGroote2016,
        CurveSet::Thelen2003,
        CurveSet::Millard2012,
        CurveSet::Tabulated,
    ];

    /// Its name in configurations.
    pub fn name(self) -> &'static str {
        match self {
            CurveSet::Paper => "paper",
            CurveSet::DeGroote2016 => "degroote2016",
            CurveSet::Thelen2003 => "thelen2003",
            CurveSet::Millard2012 => "millard2012",
            CurveSet::Tabulated => "tabulated",
        }
    }

    /// Whether this is the paper's set, the default (configurations omit it then).
    pub(crate) fn is_paper(&self) -> bool {
        *self == CurveSet::Paper
    }

    /// The names, comma-separated (for messages and help).
    pub fn names() -> String {
        Self::ALL.map(|s| s.name()).join(", ")
    }
}

impl std::fmt::Display for CurveSet {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown curve set name (quoted as a short excerpt).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown curve set {0:?}: expected one of {names}", names = CurveSet::names())]
pub struct UnknownCurveSet(pub String);

impl FromStr for CurveSet {
    type Err = UnknownCurveSet;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| UnknownCurveSet(s.chars().take(64).collect()))
    }
}

impl TryFrom<String> for CurveSet {
    type Error = UnknownCurveSet;
    fn try_from(s: String) -> Result<Self, Self::Error> {
        s.parse()
    }
}
