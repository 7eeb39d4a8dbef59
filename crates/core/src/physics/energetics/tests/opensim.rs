//! The phenomenological models against OpenSim's probe test (`testMuscleMetabolicsProbes.cpp`:
//! Umberger et al. 2003's soleus and rectus femoris on a van Soest & Bobbert 1993 contractile
//! element), and OpenSim's muscle mass.

use super::assert_rel;
use crate::physics::energetics::probe::*;
use crate::physics::energetics::umberger::*;

/// A muscle of OpenSim's test: Fmax, lopt, A_rel, B_rel, slow-twitch ratio, mass, and the
/// polynomial fits to Umberger et al. (2003) Fig. 1 (W/kg against v̂ = v/V_max in [-1, 0]:
/// below -0.4, then above), coefficients highest power first.
struct TestMuscle {
    f_max: f64,
    l_opt: f64,
    a_rel: f64,
    b_rel: f64,
    ratio: f64,
    mass: f64,
    fast: &'static [f64],
    slow: &'static [f64],
}

const SOLEUS: TestMuscle = TestMuscle {
    f_max: 3127.0,
    l_opt: 0.055,
    a_rel: 0.18,
    b_rel: 2.16,
    ratio: 0.8,
    mass: 0.805,
    fast: &[-187.6077328, -553.9650747, -194.9721769, 332.9105995],
    slow: &[
        -54693.72433,
        -73876.93352,
        -41460.1508,
        -13203.6807,
        -2682.925993,
        51.39363659,
    ],
};

const RECTUS_FEMORIS: TestMuscle = TestMuscle {
    f_max: 1118.0,
    l_opt: 0.084,
    a_rel: 0.36,
    b_rel: 4.32,
    ratio: 0.35,
    mass: 0.4275,
    fast: &[-404.1161485, -1267.967225, -744.3435788, 362.7505521],
    slow: &[
        -10181.27442,
        -13652.40864,
        -8368.687834,
        -2747.369194,
        109.028979,
    ],
};

fn horner(c: &[f64], x: f64) -> f64 {
    c.iter().fold(0.0, |acc, k| acc * x + k)
}

impl TestMuscle {
    fn probe(&self) -> ProbeMuscle {
        ProbeMuscle {
            mass_kg: self.mass,
            f_max_n: self.f_max,
            l_opt_m: self.l_opt,
            v_max_lopt_s: self.b_rel / self.a_rel,
            slow_twitch_ratio: self.ratio,
        }
    }
    /// Van Soest & Bobbert's concentric force at a = 1, l = lopt: `(B lopt + A v)/(B lopt - v)`.
    fn force(&self, v: f64) -> f64 {
        let b = self.b_rel * self.l_opt;
        self.f_max * (b + self.a_rel * v) / (b - v)
    }
    fn inputs(&self, v_hat: f64) -> ProbeInputs {
        let v = v_hat * self.b_rel / self.a_rel * self.l_opt;
        ProbeInputs {
            excitation: 1.0,
            activation: 1.0,
            fibre_length_norm: 1.0,
            force_length: 1.0,
            fibre_velocity_m_s: v,
            active_force_n: self.force(v),
            passive_force_n: 0.0,
        }
    }
    fn published(&self, v_hat: f64) -> f64 {
        horner(if v_hat >= -0.4 { self.slow } else { self.fast }, v_hat)
    }
}

/// OpenSim's test configuration: anaerobic S = 1; at u = a = 1 while shortening the Umberger
/// 2010 and Uchida 2016 options give the same rates.
fn test_options() -> [UmbergerOptions; 2] {
    let s1 = |o: UmbergerOptions| UmbergerOptions {
        aerobic_factor: 1.0,
        ..o
    };
    [
        s1(UmbergerOptions::umberger_2010()),
        s1(UmbergerOptions::uchida_2016()),
    ]
}

/// The total rate within 1.0 W/kg of the fits to Umberger et al. (2003) at 21 velocities
/// from 0 to -V_max: the tolerance of OpenSim's test.
#[test]
fn umberger_matches_the_published_curves() {
    for m in [SOLEUS, RECTUS_FEMORIS] {
        for o in test_options() {
            for i in 0..21 {
                let v_hat = -(i as f64) / 20.0;
                let r = umberger_rates(&o, &m.probe(), &m.inputs(v_hat));
                let got = r.total_w() / m.mass;
                let want = m.published(v_hat);
                assert!(
                    (got - want).abs() < 1.0,
                    "v̂ = {v_hat}: {got} W/kg against {want}"
                );
            }
        }
    }
}

/// Totals from the formulas by hand, W/kg (V_max = 12 lopt/s, α_ST = 100/(12/2.5),
/// α_FT = 153/12): isometric `128 (1 - r) + 25`; at -0.2 V_max (|v̄| = 2.4 lopt/s) plus
/// `α_ST 2.4 r + α_FT 2.4 (1 - r)` plus the work `F̃ Fmax 2.4 lopt / m`; at -V_max the slow
/// fibres' term is capped at 100 and the force is zero. Rounded: soleus 50.6, 291.0, 161.2;
/// rectus femoris 108.2, 416.7, 242.7.
#[test]
fn umberger_totals_by_hand() {
    for (m, rounded) in [
        (SOLEUS, [50.6, 291.0, 161.2]),
        (RECTUS_FEMORIS, [108.2, 416.7, 242.7]),
    ] {
        let (a_st, a_ft, r) = (100.0 / (12.0 / 2.5), 153.0 / 12.0, m.ratio);
        let am = 128.0 * (1.0 - r) + 25.0;
        let f_hat = m.a_rel * 0.8 / (m.a_rel + 0.2);
        let w = f_hat * m.f_max * 2.4 * m.l_opt / m.mass;
        let by_hand = [
            am,
            am + a_st * 2.4 * r + a_ft * 2.4 * (1.0 - r) + w,
            am + 100.0 * r + a_ft * 12.0 * (1.0 - r),
        ];
        for ((v_hat, want), round) in [0.0, -0.2, -1.0].iter().zip(by_hand).zip(rounded) {
            let got = umberger_rates(&test_options()[1], &m.probe(), &m.inputs(*v_hat)).total_w();
            assert_rel(got / m.mass, want, 1e-12, 1.0, &format!("v̂ = {v_hat}"));
            assert!(
                (want - round).abs() <= 0.05 + 1e-9,
                "{want} rounds to {round}"
            );
        }
    }
}

/// OpenSim's mass `(Fmax/σ) ρ lopt`: 1.5906 kg for the paper's muscle, 0.7290 kg for the soleus
/// (whose test gives 0.805 kg explicitly).
#[test]
fn opensim_mass() {
    let m = muscle_mass_kg(3913.0, 0.0959, SPECIFIC_TENSION_PA, MUSCLE_DENSITY_KG_M3);
    assert_rel(m, 1.59063809996, 1e-10, 0.0, "paper's muscle");
    let m = muscle_mass_kg(3127.0, 0.055, SPECIFIC_TENSION_PA, MUSCLE_DENSITY_KG_M3);
    assert_rel(m, 0.729010018, 1e-9, 0.0, "soleus");
}
