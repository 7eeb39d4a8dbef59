//! One muscle–tendon unit (docs/model.md §5, paper eq. 8): the fibre carries the muscle mass; the
//! contractile element, parallel spring and damper act between the origin and the mass, the
//! tendon between the mass and the load. Written once for every contractile model.

use crate::physics::curves::overlap::ActiveForceLength;
use crate::physics::energetics::bridge_power::atp_mol_per_j;
use crate::physics::energetics::metabolic::{
    mechanism_rates, MetabolicRates, MetabolicSample, MuscleProbe,
};
use crate::physics::energetics::probe::{ExcitationTerms, ProbeInputs};
use crate::physics::models::{CeInputs, ContractileModel};
use crate::physics::models::{ModelBuildError, ModelKind};
use crate::physics::observables::{EnergeticsOutputs, MuscleSnapshot};
use crate::physics::parallel_element::{damper_force, ParallelElement};
use crate::physics::params::MuscleParams;
use crate::physics::stiffness::{fibre_stiffness, series_stiffness};
use crate::physics::tendon::Tendon;

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
    pub active_force_length: ActiveForceLength,
    /// The contractile element.
    pub(crate) ce: Box<dyn ContractileModel>,
    /// Its phenomenological energy model (docs/model.md §11.4).
    pub probe: MuscleProbe,
}

impl Mtu {
    /// Derives the constants and calibrates the contractile model.
    pub fn new(params: &MuscleParams, model: ModelKind) -> Result<Self, ModelBuildError> {
        Ok(Self {
            params: params.clone(),
            tendon: Tendon::new(params),
            parallel: ParallelElement::new(params),
            active_force_length: ActiveForceLength::new(params),
            ce: model.build(params)?,
            probe: MuscleProbe {
                model: params.energetics.energy_model.phenomenological(),
                muscle: params
                    .energetics
                    .probe_muscle(params.f_max, params.l_opt, params.v_max),
                atp_mol_per_j: atp_mol_per_j(params.energetics.atp_free_energy),
            },
        })
    }

    /// Number of state variables: l_m, v, then the contractile model's.
    pub(crate) fn state_dim(&self) -> usize {
        2 + self.ce.state_dim()
    }

    /// Filament-overlap factor λ(l_m) = f(l_m).
    #[inline]
    pub fn overlap(&self, l_m: f64) -> f64 {
        self.active_force_length.at(l_m)
    }

    /// Slope of the overlap factor, 1/m.
    pub fn overlap_slope(&self, l_m: f64) -> f64 {
        self.active_force_length.slope(l_m)
    }

    /// What the contractile element sees.
    pub(crate) fn ce_inputs(&self, activation: f64, l_m: f64, v: f64) -> CeInputs {
        CeInputs {
            activation,
            fibre_length: l_m,
            fibre_velocity: v,
            overlap: self.overlap(l_m),
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

    /// `d/dt` of this muscle's state `s = [l_m, v, x...]` under tendon force `f_se`, written to
    /// `ds`; `t` is the time within the tick.
    pub fn derivatives(&self, t: f64, activation: f64, s: &[f64], f_se: f64, ds: &mut [f64]) {
        let (l_m, v) = (s[0], s[1]);
        let ce = self.ce_inputs(activation, l_m, v);
        let f_ce = self.ce.force(&ce, &s[2..]);
        ds[0] = v;
        ds[1] = self.fibre_acceleration(f_se, f_ce, l_m, v);
        self.ce.rates(t, &ce, &s[2..], &mut ds[2..]);
    }

    /// Typical magnitudes of this muscle's state variables.
    pub fn scales(&self, out: &mut [f64]) {
        out[0] = self.params.l_opt;
        out[1] = self.params.v_max;
        self.ce.state_scales(&mut out[2..]);
    }

    /// Everything observable about this MTU at muscle state `s = [l_m, v, x...]`, tendon length
    /// l_t, excitation u and activation a, with the energetics `e` the stepping computed; the
    /// force is the tendon's, F_SE(l_t).
    pub fn outputs(
        &self,
        excitation: f64,
        activation: f64,
        s: &[f64],
        l_t: f64,
        e: &EnergeticsOutputs,
    ) -> MuscleSnapshot {
        let (l_m, v, x) = (s[0], s[1], &s[2..]);
        let ce = self.ce_inputs(activation, l_m, v);
        let ce_stiffness = self.ce.stiffness(&ce, x);
        let k_m = fibre_stiffness(ce_stiffness, self.parallel.stiffness(l_m));
        let [q0, q1, q2] = self.ce.moments(x);
        MuscleSnapshot {
            excitation,
            activation,
            force: self.tendon.force(l_t),
            ce_force: self.ce.force(&ce, x),
            pe_force: self.parallel.force(l_m),
            fiber_length: l_m,
            fiber_velocity: v,
            tendon_length: l_t,
            stiffness: ce_stiffness,
            mtu_stiffness: series_stiffness(k_m, self.tendon.stiffness(l_t)),
            q0,
            q1,
            q2,
            tendon_energy: self.tendon.energy(l_t),
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
    /// element's inputs `ce` at muscle state `s = [l_m, v, x...]` (the passive force only if it
    /// reads it, else 0).
    fn probe_inputs(&self, excitation: f64, ce: &CeInputs, s: &[f64]) -> ProbeInputs {
        ProbeInputs {
            excitation,
            activation: ce.activation,
            fibre_length_norm: ce.fibre_length / self.params.l_opt,
            force_length: ce.overlap,
            fibre_velocity_m_s: ce.fibre_velocity,
            active_force_n: self.ce.force(ce, &s[2..]),
            passive_force_n: if self.probe.model.reads_passive_force() {
                self.parallel.force(ce.fibre_length)
            } else {
                0.0
            },
        }
    }

    /// The metabolic rates at muscle state `s`, the excitation of `terms` (the probe's
    /// [`MuscleProbe::excitation_terms`]) and activation a (docs/model.md §11.6), with the
    /// probe's inputs they came from. Models with state outside the ODE must be asked after the
    /// sub-step hooks have brought it in step with `s`.
    pub fn metabolic(
        &self,
        terms: &ExcitationTerms,
        activation: f64,
        s: &[f64],
    ) -> MetabolicSample {
        let ce = self.ce_inputs(activation, s[0], s[1]);
        let x = self.probe_inputs(terms.excitation, &ce, s);
        let mechanism = self.ce.bridge_energy(&ce, &s[2..]).map(|(fluxes, b)| {
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
    /// the tendon force equals the parallel force, by bisection. The residual
    /// `F_T(length - l_m) - F_PE(l_m)` never rises with l_m for every curve set: DeGroote's
    /// tendon, negative when slack, still rises with its length, and so does its passive curve
    /// below 0.2 l_opt; where both forces are flat at zero (a slack tendon and fibre, the
    /// paper's and Thelen's curves) the shortest such fibre is taken.
    pub(crate) fn resting_fibre_length(&self, length: f64) -> f64 {
        let residual = |l_m: f64| self.tendon.force(length - l_m) - self.parallel.force(l_m);
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
