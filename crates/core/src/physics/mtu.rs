//! One muscle–tendon unit (docs/model.md §5, paper eq. 8): the contractile element, parallel
//! spring and damper act between the origin and the fibre's end, the tendon between that end and
//! the load. Written once for every contractile model, in three formulations (§5b):
//!
//! | formulation                  | its state        | fibre velocity v                         | tendon force               |
//! |------------------------------|------------------|------------------------------------------|----------------------------|
//! | massed fibre, elastic tendon | `[l_m, v, x...]` | a state (eq. 8, mass M)                  | `F_T(L - l_m)`             |
//! | equilibrium, elastic tendon  | `[l_m, x...]`    | balances `(F_CE + F_P + B v) cos α = F_T` | `F_T(L - l_m cos α)`      |
//! | equilibrium, rigid tendon    | `[x...]`         | the path's, `cos α dL/dt`                | `(F_CE + F_P + B v) cos α` |
//!
//! (L: path length; x: the contractile model's own state; α: the pennation angle at constant
//! thickness, `physics::pennation`, 0 for a fibre with mass.)

use crate::physics::curves::overlap::ActiveForceLength;
use crate::physics::energetics::bridge_power::atp_mol_per_j;
use crate::physics::energetics::metabolic::{
    mechanism_rates, MetabolicRates, MetabolicSample, MuscleProbe,
};
use crate::physics::energetics::probe::{ExcitationTerms, ProbeInputs};
use crate::physics::limb_params::formulation::{FibreKind, TendonKind};
use crate::physics::limb_params::MuscleParams;
use crate::physics::models::{CeInputs, ContractileModel};
use crate::physics::models::{ModelBuildError, ModelKind};
use crate::physics::observables::{EnergeticsOutputs, MuscleSnapshot};
use crate::physics::parallel_element::{damper_force, ParallelElement};
use crate::physics::pennation::Pennation;
use crate::physics::stiffness::{fibre_stiffness, series_stiffness};
use crate::physics::tendon::Tendon;

/// The least activation an equilibrium fibre without a damper (`b_m = 0`) works with: OpenSim's
/// `minimum_activation` default (Thelen2003Muscle clamps its activation state to it). At zero
/// activation nothing would set such a fibre's velocity (docs/model.md §5b).
pub(crate) const UNDAMPED_MIN_ACTIVATION: f64 = 0.01;

/// An MTU's mechanical formulation (docs/model.md §5b), from its fibre and tendon kinds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mechanics {
    /// A fibre with mass on an elastic tendon (the paper's eq. 8): state `[l_m, v]`.
    Massed,
    /// A massless fibre on an elastic tendon: state `[l_m]`.
    Equilibrium,
    /// A massless fibre on a rigid tendon: no state of its own.
    Rigid,
}

impl Mechanics {
    /// The formulation of these parameters (a rigid tendon with a massed fibre is refused by the
    /// parameters' validation and taken as rigid here).
    pub(crate) fn of(p: &MuscleParams) -> Self {
        match (p.tendon, p.fibre) {
            (TendonKind::Rigid, _) => Mechanics::Rigid,
            (TendonKind::Elastic, FibreKind::Massed) => Mechanics::Massed,
            (TendonKind::Elastic, FibreKind::Equilibrium) => Mechanics::Equilibrium,
        }
    }

    /// Number of its state variables before the contractile model's.
    #[inline]
    pub(crate) fn dim(self) -> usize {
        match self {
            Mechanics::Massed => 2,
            Mechanics::Equilibrium => 1,
            Mechanics::Rigid => 0,
        }
    }
}

/// What holds the tendon's far end at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TendonEnd {
    /// A path over joints: its length L (m) and lengthening velocity dL/dt (m/s; read only by a
    /// rigid tendon, 0 otherwise).
    Path {
        /// L, m.
        length: f64,
        /// dL/dt, m/s.
        velocity: f64,
    },
    /// An external pull, N (docs/model.md §5: a force-driven tendon transmits no push).
    Force(f64),
}

/// The fibre and tendon at one instant, as every reader of an MTU's state sees them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FibreState {
    /// What the contractile element sees (activation, l_m, v, overlap).
    pub ce: CeInputs,
    /// Tendon length l_T, m.
    pub tendon_length: f64,
    /// Tendon force F_SE, N.
    pub tendon_force: f64,
}

/// The constants of one muscle–tendon unit, derived once from its parameters, and its
/// contractile element; its tendon, parallel element and overlap factor are those of its curve
/// set (docs/model.md §4b).
#[derive(Debug, Clone)]
pub struct Mtu {
    /// The parameters.
    pub params: MuscleParams,
    /// Series element.
    pub tendon: Tendon,
    /// Parallel element.
    pub parallel: ParallelElement,
    /// Active force–length relation, the overlap factor λ(l_m).
    pub(crate) active_force_length: ActiveForceLength,
    /// The contractile element.
    pub(crate) ce: Box<dyn ContractileModel>,
    /// Its phenomenological energy model (docs/model.md §11.4).
    pub probe: MuscleProbe,
    /// Its formulation.
    pub(crate) mechanics: Mechanics,
    /// Its pennation (none for a fibre with mass).
    pub(crate) pennation: Pennation,
    /// The scale its fibre length's error is judged on, m ([`Mtu::scales`]).
    length_scale: f64,
    /// The optimal length's lengthening at zero activation (`optimal_length_shift`; 0: none).
    length_shift: f64,
}

impl Mtu {
    /// Derives the constants and calibrates the contractile model.
    pub fn new(params: &MuscleParams, model: ModelKind) -> Result<Self, ModelBuildError> {
        let ce = model.build(params)?;
        let mechanics = Mechanics::of(params);
        if mechanics == Mechanics::Equilibrium
            && !ce.force_depends_on_velocity()
            && params.b_m <= 0.0
        {
            return Err(ModelBuildError::EquilibriumWithoutDamper {
                model: model.name(),
            });
        }
        let tendon = Tendon::new(params);
        let length_scale = match mechanics {
            Mechanics::Massed | Mechanics::Rigid => params.l_opt,
            // A massless fibre's length sets the tendon's force directly: its error is judged on
            // the tendon's stretch at Fmax (millimetres), not on l_opt, or a tolerance would let
            // through force errors l_opt / stretch times larger than the massed fibre's
            // (docs/benchmarks.md "Work and precision").
            Mechanics::Equilibrium => {
                (tendon.length_at_force(params.f_max) - params.l_ts).min(params.l_opt)
            }
        };
        Ok(Self {
            mechanics,
            length_scale,
            length_shift: params.optimal_length_shift.unwrap_or(0.0),
            pennation: Pennation::new(params),
            params: params.clone(),
            tendon,
            parallel: ParallelElement::new(params),
            active_force_length: ActiveForceLength::new(params),
            ce,
            probe: MuscleProbe {
                model: params.energetics.energy_model.phenomenological(),
                muscle: params
                    .energetics
                    .probe_muscle(params.f_max, params.l_opt, params.v_max),
                atp_mol_per_j: atp_mol_per_j(params.energetics.atp_free_energy),
            },
        })
    }

    /// Number of state variables: the formulation's (l_m, v; l_m; none), then the contractile
    /// model's.
    pub(crate) fn state_dim(&self) -> usize {
        self.mechanics.dim() + self.ce.state_dim()
    }

    /// Filament-overlap factor λ(l_m) = f(l_m).
    #[inline]
    pub fn overlap(&self, l_m: f64) -> f64 {
        self.active_force_length.at(l_m)
    }

    /// The overlap factor under activation `a`: λ at `l_m / (1 + s (1 − a))` for an optimal
    /// length that lengthens by s at zero activation (docs/model.md §3b), λ(l_m) for s = 0.
    #[inline]
    pub(crate) fn overlap_at(&self, l_m: f64, a: f64) -> f64 {
        if self.length_shift == 0.0 {
            self.overlap(l_m)
        } else {
            self.overlap(l_m / (1.0 + self.length_shift * (1.0 - a)))
        }
    }

    /// Slope of the overlap factor, 1/m.
    pub fn overlap_slope(&self, l_m: f64) -> f64 {
        self.active_force_length.slope(l_m)
    }

    /// What the contractile element sees.
    #[inline]
    pub(crate) fn ce_inputs(&self, activation: f64, l_m: f64, v: f64) -> CeInputs {
        CeInputs {
            activation,
            fibre_length: l_m,
            fibre_velocity: v,
            overlap: self.overlap_at(l_m, activation),
        }
    }

    /// Fibre acceleration from eq. (8): `(F_SE - F_CE - F_P - B_m v) / M`, m/s².
    pub(crate) fn fibre_acceleration(
        &self,
        tendon_force: f64,
        ce_force: f64,
        l_m: f64,
        v: f64,
    ) -> f64 {
        let p = &self.params;
        (tendon_force - ce_force - self.parallel.force(l_m) - damper_force(p.b_m, v)) / p.mass
    }

    /// The fibre length at muscle state `s` and tendon end `end`, m.
    #[inline]
    pub(crate) fn fibre_length(&self, s: &[f64], end: TendonEnd) -> f64 {
        match (self.mechanics, end) {
            (Mechanics::Rigid, TendonEnd::Path { length, .. }) => {
                self.pennation.fibre_length(length - self.params.l_ts)
            }
            // A rigid tendon on a force-driven anchor is refused by the plant.
            (Mechanics::Rigid, TendonEnd::Force(_)) => self.params.l_opt,
            _ => s[0],
        }
    }

    /// The tendon's length and force with the fibre at `l_m` (an elastic tendon): the path less
    /// the fibre's projection on it.
    #[inline]
    fn elastic_tendon(&self, l_m: f64, end: TendonEnd) -> (f64, f64) {
        match end {
            TendonEnd::Path { length, .. } => {
                let l_t = if self.pennation.is_none() {
                    length - l_m
                } else {
                    length - l_m * self.pennation.cos(l_m)
                };
                (l_t, self.tendon.force(l_t))
            }
            TendonEnd::Force(f) => (self.tendon.length_at_force(f), f.max(0.0)),
        }
    }

    /// The tendon force at muscle state `s`, N: [`Mtu::fibre_state`]'s, without the equilibrium
    /// fibre's velocity balance, which an elastic tendon's force does not need.
    pub(crate) fn tendon_force(&self, activation: f64, s: &[f64], end: TendonEnd) -> f64 {
        match self.mechanics {
            Mechanics::Massed | Mechanics::Equilibrium => self.elastic_tendon(s[0], end).1,
            Mechanics::Rigid => self.fibre_state(activation, s, end).tendon_force,
        }
    }

    /// The fibre and tendon at muscle state `s`, activation a and tendon end `end`
    /// (docs/model.md §5b).
    pub(crate) fn fibre_state(&self, activation: f64, s: &[f64], end: TendonEnd) -> FibreState {
        match self.mechanics {
            Mechanics::Massed => {
                let (tendon_length, tendon_force) = self.elastic_tendon(s[0], end);
                FibreState {
                    ce: self.ce_inputs(activation, s[0], s[1]),
                    tendon_length,
                    tendon_force,
                }
            }
            Mechanics::Equilibrium => {
                let l_m = s[0];
                let (tendon_length, tendon_force) = self.elastic_tendon(l_m, end);
                // Without a damper only the active force sets the velocity: it must not vanish.
                let activation = if self.params.b_m > 0.0 {
                    activation
                } else {
                    activation.max(UNDAMPED_MIN_ACTIVATION)
                };
                let mut ce = self.ce_inputs(activation, l_m, 0.0);
                let carried = tendon_force / self.pennation.cos(l_m) - self.parallel.force(l_m);
                ce.fibre_velocity =
                    self.ce
                        .balance_velocity(&ce, &s[1..], self.params.b_m, carried);
                FibreState {
                    ce,
                    tendon_length,
                    tendon_force,
                }
            }
            Mechanics::Rigid => {
                let velocity = match end {
                    TendonEnd::Path { velocity, .. } => velocity,
                    TendonEnd::Force(_) => 0.0,
                };
                let l_m = self.fibre_length(s, end);
                let cos = self.pennation.cos(l_m);
                let v = velocity * cos;
                let ce = self.ce_inputs(activation, l_m, v);
                let tendon_force = (self.ce.force(&ce, s)
                    + self.parallel.force(l_m)
                    + damper_force(self.params.b_m, v))
                    * cos;
                FibreState {
                    ce,
                    tendon_length: self.params.l_ts,
                    tendon_force,
                }
            }
        }
    }

    /// `d/dt` of this muscle's state `s` (its formulation's, then the contractile model's) with
    /// its tendon's far end at `end`, written to `ds`; `t` is the time within the tick. Returns
    /// the tendon force, N.
    pub(crate) fn derivatives(
        &self,
        t: f64,
        activation: f64,
        s: &[f64],
        end: TendonEnd,
        ds: &mut [f64],
    ) -> f64 {
        if self.mechanics == Mechanics::Massed {
            // The paper's eq. (8): the tendon's force alone (a force-driven tendon's length is
            // not needed here), no balance to solve.
            let (l_m, v) = (s[0], s[1]);
            let f_se = match end {
                TendonEnd::Path { length, .. } => self.tendon.force(length - l_m),
                TendonEnd::Force(f) => f.max(0.0),
            };
            let ce = self.ce_inputs(activation, l_m, v);
            let f_ce = self.ce.force(&ce, &s[2..]);
            ds[0] = v;
            ds[1] = self.fibre_acceleration(f_se, f_ce, l_m, v);
            self.ce.rates(t, &ce, &s[2..], &mut ds[2..]);
            return f_se;
        }
        let f = self.fibre_state(activation, s, end);
        let m = self.mechanics.dim();
        if self.mechanics == Mechanics::Equilibrium {
            ds[0] = f.ce.fibre_velocity;
        }
        self.ce.rates(t, &f.ce, &s[m..], &mut ds[m..]);
        f.tendon_force
    }

    /// Typical magnitudes of this muscle's state variables.
    pub(crate) fn scales(&self, out: &mut [f64]) {
        let m = self.mechanics.dim();
        out[..m].copy_from_slice(&[self.length_scale, self.params.v_max][..m]);
        self.ce.state_scales(&mut out[m..]);
    }

    /// Everything observable about this MTU at muscle state `s` with its tendon's far end at
    /// `end`, excitation u and activation a, with the energetics `e` the stepping computed; the
    /// force is the tendon's.
    pub fn outputs(
        &self,
        excitation: f64,
        activation: f64,
        s: &[f64],
        end: TendonEnd,
        e: &EnergeticsOutputs,
    ) -> MuscleSnapshot {
        let f = self.fibre_state(activation, s, end);
        let (ce, l_t) = (f.ce, f.tendon_length);
        let (l_m, v, x) = (
            ce.fibre_length,
            ce.fibre_velocity,
            &s[self.mechanics.dim()..],
        );
        let ce_stiffness = self.ce.stiffness(&ce, x);
        let mut k_m = fibre_stiffness(ce_stiffness, self.parallel.stiffness(l_m));
        if !self.pennation.is_none() {
            let fibre_force =
                self.ce.force(&ce, x) + self.parallel.force(l_m) + damper_force(self.params.b_m, v);
            k_m = self.pennation.stiffness_along_tendon(k_m, fibre_force, l_m);
        }
        let [q0, q1, q2] = self.ce.moments(x);
        MuscleSnapshot {
            excitation,
            activation,
            force: f.tendon_force,
            ce_force: self.ce.force(&ce, x),
            pe_force: self.parallel.force(l_m),
            fiber_length: l_m,
            fiber_velocity: v,
            tendon_length: l_t,
            stiffness: ce_stiffness,
            mtu_stiffness: match self.mechanics {
                Mechanics::Rigid => k_m,
                Mechanics::Massed | Mechanics::Equilibrium => {
                    series_stiffness(k_m, self.tendon.stiffness(l_t))
                }
            },
            q0,
            q1,
            q2,
            tendon_energy: match self.mechanics {
                Mechanics::Rigid => 0.0,
                Mechanics::Massed | Mechanics::Equilibrium => self.tendon.energy(l_t),
            },
            fiber_energy: self.parallel.energy(l_m),
            crossbridge_energy: self.ce.energy(x),
            metabolic_power: e.metabolic_power,
            activation_heat_rate: e.activation_heat_rate,
            shortening_heat_rate: e.shortening_heat_rate,
            work_rate: e.work_rate,
            bridge_storage_rate: e.bridge_storage_rate,
            atp_rate: e.atp_rate,
            metabolic_energy: e.metabolic_energy,
            phenomenological_power: e.phenomenological_power,
            phenomenological_energy: e.phenomenological_energy,
        }
    }

    /// What the phenomenological energy model reads under excitation u, with the contractile
    /// element's inputs `ce` and its own state `x` (the passive force only if it reads it, else
    /// 0).
    fn probe_inputs(&self, excitation: f64, ce: &CeInputs, x: &[f64]) -> ProbeInputs {
        ProbeInputs {
            excitation,
            activation: ce.activation,
            fibre_length_norm: ce.fibre_length / self.params.l_opt,
            force_length: ce.overlap,
            fibre_velocity_m_s: ce.fibre_velocity,
            active_force_n: self.ce.force(ce, x),
            passive_force_n: if self.probe.model.reads_passive_force() {
                self.parallel.force(ce.fibre_length)
            } else {
                0.0
            },
        }
    }

    /// The metabolic rates at muscle state `s`, with what its contractile element sees there
    /// (`ce`: [`Mtu::fibre_state`]'s), the excitation of `terms` (the probe's
    /// [`MuscleProbe::excitation_terms`]) and activation a (docs/model.md §11.6), with the
    /// probe's inputs they came from. Models with state outside the ODE must be asked after the
    /// sub-step hooks have brought it in step with `s`.
    pub(crate) fn metabolic(
        &self,
        terms: &ExcitationTerms,
        activation: f64,
        ce: &CeInputs,
        s: &[f64],
    ) -> MetabolicSample {
        let ce = *ce;
        let own = &s[self.mechanics.dim()..];
        let x = self.probe_inputs(terms.excitation, &ce, own);
        let mechanism = self.ce.bridge_energy(&ce, own).map(|(fluxes, b)| {
            mechanism_rates(
                b,
                &fluxes,
                activation,
                x.active_force_n,
                x.fibre_velocity_m_s,
            )
        });
        let probe = self.probe.rates(&x, terms);
        MetabolicSample {
            bridges: mechanism.is_some(),
            probe_inputs: x,
            rates: MetabolicRates::of(mechanism.as_ref(), &probe, self.probe.atp_mol_per_j),
        }
    }

    /// Fibre length at rest with the MTU held at total length `length` (a = 0, no bonds): where
    /// the tendon force equals the parallel force along it, by bisection. The residual
    /// `F_T(length - l_m cos α) - F_PE(l_m) cos α` never rises with l_m for every curve set (α = 0
    /// shown; pennation only scales and shifts it): DeGroote's
    /// tendon, negative when slack, still rises with its length, and so does its passive curve
    /// below 0.2 l_opt; where both forces are flat at zero (a slack tendon and fibre, the
    /// paper's and Thelen's curves) the shortest such fibre is taken.
    pub(crate) fn resting_fibre_length(&self, length: f64) -> f64 {
        let residual = |l_m: f64| {
            let cos = self.pennation.cos(l_m);
            self.tendon.force(length - l_m * cos) - self.parallel.force(l_m) * cos
        };
        let (mut lo, mut hi) = (0.0, length);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if residual(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `optimal_length_shift` s reads the overlap at `l_m / (1 + s (1 − a))` (model.md eq. 3b):
    /// at full activation and at s = 0 it is the overlap at l_m bit for bit, at rest the curve
    /// stretched by 1 + s; the passive force does not depend on it.
    #[test]
    fn the_optimal_length_lengthens_at_low_activation() {
        let plain = MuscleParams::default();
        let shifted = MuscleParams {
            optimal_length_shift: Some(0.15),
            ..plain.clone()
        };
        let (m0, m1) = (
            Mtu::new(&plain, ModelKind::HILL).unwrap(),
            Mtu::new(&shifted, ModelKind::HILL).unwrap(),
        );
        for l in [0.06, 0.0959, 0.11, 0.13] {
            assert_eq!(m1.overlap_at(l, 1.0).to_bits(), m0.overlap(l).to_bits());
            for a in [0.0, 0.3, 0.7] {
                assert_eq!(m0.overlap_at(l, a).to_bits(), m0.overlap(l).to_bits());
                let want = m0.overlap(l / (1.0 + 0.15 * (1.0 - a)));
                assert_eq!(m1.overlap_at(l, a), want);
                assert_eq!(m1.ce_inputs(a, l, 0.0).overlap, want);
            }
            assert_eq!(m1.parallel.force(l), m0.parallel.force(l));
        }
        // At rest the peak sits at 1.15 l_opt.
        assert!((m1.overlap_at(1.15 * plain.l_opt, 0.0) - 1.0).abs() < 1e-12);
        let mut errors = Vec::new();
        for s in [-0.1, 1.0, f64::NAN] {
            MuscleParams {
                optimal_length_shift: Some(s),
                ..plain.clone()
            }
            .validate("m.", &mut errors);
        }
        assert_eq!(errors.len(), 3, "{errors:?}");
        assert!(errors
            .iter()
            .all(|e| e.parameter == "m.optimal_length_shift"));
    }
}
