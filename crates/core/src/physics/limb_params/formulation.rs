//! How a muscle–tendon unit is formulated (docs/model.md §2b, §5b), three parameters of the
//! muscle: its fibre kind and its tendon kind, and how its excitation becomes activation. The
//! defaults are the paper's: a fibre with mass on an elastic tendon, first-order activation.

use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// How the fibre moves: with the muscle's mass, or massless in force balance with its tendon.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase", try_from = "String")]
pub enum FibreKind {
    /// The paper's eq. (8): the fibre carries the mass M, its velocity a state (docs/model.md §5).
    #[default]
    Massed,
    /// Massless (M → 0 in eq. 8): the contractile, parallel and damping forces equal the tendon's
    /// at every instant, and the fibre's velocity is the one that balances them (§5b); OpenSim's
    /// equilibrium muscles.
    Equilibrium,
}

/// How the tendon stretches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase", try_from = "String")]
pub enum TendonKind {
    /// The curve set's tendon (docs/model.md §4, §4b).
    #[default]
    Elastic,
    /// Inextensible, always at its slack length: the fibre follows the path (§5b); OpenSim's
    /// `ignore_tendon_compliance`. Needs an equilibrium fibre.
    Rigid,
}

/// How excitation becomes activation (docs/model.md §2, §2b).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", try_from = "String")]
pub enum ActivationKind {
    /// The paper's first-order dynamics, `da/dt = (u - a)/τ(u, a)`, exact over a tick (§2).
    #[default]
    FirstOrder,
    /// Lloyd & Besier's (2003) second-order recursion once per tick on the excitation (an EMG
    /// envelope), with its delay and its nonlinearity (§2b, `crate::emg`).
    LloydBesier,
}

/// The names of a kind's values, in configurations and messages.
trait Named: Sized + Copy + 'static {
    const ALL: &'static [Self];
    const WHAT: &'static str;
    fn name(self) -> &'static str;
}

impl Named for FibreKind {
    const ALL: &'static [Self] = &[FibreKind::Massed, FibreKind::Equilibrium];
    const WHAT: &'static str = "fibre kind";
    fn name(self) -> &'static str {
        match self {
            FibreKind::Massed => "massed",
            FibreKind::Equilibrium => "equilibrium",
        }
    }
}

impl Named for TendonKind {
    const ALL: &'static [Self] = &[TendonKind::Elastic, TendonKind::Rigid];
    const WHAT: &'static str = "tendon kind";
    fn name(self) -> &'static str {
        match self {
            TendonKind::Elastic => "elastic",
            TendonKind::Rigid => "rigid",
        }
    }
}

impl Named for ActivationKind {
    const ALL: &'static [Self] = &[ActivationKind::FirstOrder, ActivationKind::LloydBesier];
    const WHAT: &'static str = "activation kind";
    fn name(self) -> &'static str {
        match self {
            ActivationKind::FirstOrder => "first_order",
            ActivationKind::LloydBesier => "lloyd_besier",
        }
    }
}

impl ActivationKind {
    /// Its name in configurations.
    pub fn name(self) -> &'static str {
        Named::name(self)
    }
    /// Whether this is the default, the paper's first order (configurations omit it then).
    pub(crate) fn is_first_order(&self) -> bool {
        *self == ActivationKind::FirstOrder
    }
}

impl FromStr for ActivationKind {
    type Err = UnknownKind;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse(s)
    }
}

impl TryFrom<String> for ActivationKind {
    type Error = UnknownKind;
    fn try_from(s: String) -> Result<Self, Self::Error> {
        s.parse()
    }
}

impl std::fmt::Display for ActivationKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl FibreKind {
    /// Its name in configurations.
    pub fn name(self) -> &'static str {
        Named::name(self)
    }
    /// Whether this is the default, the paper's fibre with mass (configurations omit it then).
    pub(crate) fn is_massed(&self) -> bool {
        *self == FibreKind::Massed
    }
}

impl TendonKind {
    /// Its name in configurations.
    pub fn name(self) -> &'static str {
        Named::name(self)
    }
    /// Whether this is the default, the elastic tendon (configurations omit it then).
    pub(crate) fn is_elastic(&self) -> bool {
        *self == TendonKind::Elastic
    }
}

/// An unknown fibre, tendon or activation kind (quoted as a short excerpt), with the known
/// names.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown {what} {given:?}: expected one of {names}")]
pub struct UnknownKind {
    /// Which parameter: "fibre kind", "tendon kind" or "activation kind".
    pub what: &'static str,
    /// The name given, at most 64 characters of it.
    pub given: String,
    /// The known names, comma-separated.
    pub names: String,
}

fn parse<K: Named>(s: &str) -> Result<K, UnknownKind> {
    K::ALL
        .iter()
        .copied()
        .find(|k| k.name() == s)
        .ok_or_else(|| UnknownKind {
            what: K::WHAT,
            given: s.chars().take(64).collect(),
            names: K::ALL
                .iter()
                .map(|k| k.name())
                .collect::<Vec<_>>()
                .join(", "),
        })
}

impl FromStr for FibreKind {
    type Err = UnknownKind;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse(s)
    }
}

impl FromStr for TendonKind {
    type Err = UnknownKind;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse(s)
    }
}

impl TryFrom<String> for FibreKind {
    type Error = UnknownKind;
    fn try_from(s: String) -> Result<Self, Self::Error> {
        s.parse()
    }
}

impl TryFrom<String> for TendonKind {
    type Error = UnknownKind;
    fn try_from(s: String) -> Result<Self, Self::Error> {
        s.parse()
    }
}

impl std::fmt::Display for FibreKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::fmt::Display for TendonKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_names_are_refused_with_the_known_ones() {
        for k in FibreKind::ALL {
            assert_eq!(k.name().parse::<FibreKind>().unwrap(), *k);
        }
        for k in TendonKind::ALL {
            assert_eq!(k.name().parse::<TendonKind>().unwrap(), *k);
        }
        let e = "stiff".parse::<TendonKind>().unwrap_err().to_string();
        assert_eq!(
            e,
            "unknown tendon kind \"stiff\": expected one of elastic, rigid"
        );
        let e = "massles".parse::<FibreKind>().unwrap_err().to_string();
        assert!(e.contains("massed, equilibrium"), "{e}");
        for k in ActivationKind::ALL {
            assert_eq!(k.name().parse::<ActivationKind>().unwrap(), *k);
        }
        let e = "second_order"
            .parse::<ActivationKind>()
            .unwrap_err()
            .to_string();
        assert!(e.contains("first_order, lloyd_besier"), "{e}");
    }
}
