//! The limb as data (docs/model.md §8b): joints, and muscles that each span one or more of them
//! through a moment arm per spanned joint. Apart from the plant that steps it.

use crate::physics::limb_params::{JointParams, MuscleParams};
use crate::physics::moment_arm::MomentArm;

/// A joint a muscle spans, and its moment arm there.
#[derive(Debug, Clone, PartialEq)]
pub struct Span {
    /// Index of the joint in [`Topology::joints`].
    pub joint: usize,
    /// The moment arm r(θ), m; positive when the muscle's tension increases θ.
    pub moment_arm: MomentArm,
}

/// What the far end of a muscle's tendon is attached to (docs/model.md §5).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Anchor {
    /// A path over joints: `L(θ) = path_length - Σ_j ∫_0^{θ_j} r_j(s) ds`, `l_t = L - l_m`.
    Path {
        /// Path length with every spanned joint at 0 rad, m.
        path_length: f64,
        /// The joints spanned (none: the path is clamped at `path_length`).
        spans: Vec<Span>,
    },
    /// An external pull F(t) >= 0 on a massless tendon (a push is not transmitted).
    ForceDriven,
}

/// One muscle of a topology.
#[derive(Debug, Clone, PartialEq)]
pub struct MuscleSpec {
    /// Name used in commands and published states.
    pub name: String,
    /// Its parameters.
    pub params: MuscleParams,
    /// Its tendon's attachment.
    pub(crate) anchor: Anchor,
}

/// Joints and the muscles that drive them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Topology {
    /// The joints, in configuration order.
    pub joints: Vec<JointParams>,
    /// The muscles, in configuration order.
    pub muscles: Vec<MuscleSpec>,
}

impl Topology {
    /// One muscle clamped at total length `length` (no joints).
    pub fn clamped(name: &str, params: MuscleParams, length: f64) -> Self {
        Self {
            joints: vec![],
            muscles: vec![MuscleSpec {
                name: name.into(),
                params,
                anchor: Anchor::Path {
                    path_length: length,
                    spans: vec![],
                },
            }],
        }
    }

    /// One muscle whose tendon is pulled by an external force (no joints).
    pub fn force_driven(name: &str, params: MuscleParams) -> Self {
        Self {
            joints: vec![],
            muscles: vec![MuscleSpec {
                name: name.into(),
                params,
                anchor: Anchor::ForceDriven,
            }],
        }
    }

    /// Muscle names, in order.
    pub fn muscle_names(&self) -> Vec<String> {
        self.muscles.iter().map(|m| m.name.clone()).collect()
    }

    /// Joint names, in order.
    pub fn joint_names(&self) -> Vec<String> {
        self.joints.iter().map(|j| j.name.clone()).collect()
    }

    /// The spans of muscle i (empty unless it runs over joints).
    pub fn spans(&self, i: usize) -> &[Span] {
        match &self.muscles[i].anchor {
            Anchor::Path { spans, .. } => spans,
            Anchor::ForceDriven => &[],
        }
    }
}
