//! Energetics on runs (docs/model.md §11.6): the Huxley models' energy balance with every term
//! from its own source, the parts of each power against its total, the energies against the
//! integrals of the powers, and the physiological sense of the numbers (isometric cost between
//! the phenomenological models', the cost of stiffness rising with co-contraction).

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::contractile::{calibrate_distribution_moment, calibrate_exact};
use muscle_actuator_core::physics::energetics::BridgeEnergyScale;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{EnergyModel, MuscleParams};
use muscle_actuator_core::sim::{default_stepping, Actuator, MuscleSnapshot, Run, Scenario};
use std::path::Path;

fn scenario(name: &str) -> Scenario {
    match name.strip_suffix(".toml") {
        Some(_) => Scenario::from_file(
            &Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join(name),
        )
        .unwrap(),
        None => Scenario::built_in(name, &MuscleParams::default()).unwrap(),
    }
}

fn run(name: &str, cfg: &ActuatorConfig, model: ModelKind, rate_hz: f64) -> Run {
    scenario(name)
        .run(cfg, model, rate_hz, default_stepping(model))
        .unwrap()
}

/// The trapezoidal integral of `f` over muscle i's records, J for a power in W.
fn integral(run: &Run, i: usize, f: impl Fn(&MuscleSnapshot) -> f64) -> f64 {
    run.records()
        .zip(run.records().skip(1))
        .map(|(a, b)| 0.5 * (b.time - a.time) * (f(&a.muscles[i]) + f(&b.muscles[i])))
        .sum()
}

/// Energy per unit Q0 of the bridges yet to split their ATP, `e N_hs B`, J (§11.2).
fn atp_energy_per_q0(model: ModelKind, p: &MuscleParams) -> f64 {
    let scale = if model == ModelKind::HUXLEY {
        calibrate_distribution_moment(p).unwrap()
    } else {
        calibrate_exact(p)
    };
    BridgeEnergyScale::new(&scale, p, &p.energetics.bridge()).chemical_power_w(1.0)
}

const BALANCE_RUNS: [&str; 3] = [
    "pulse",
    "scenarios/elbow_cocontraction_ramp.toml",
    "scenarios/elbow_cocontraction_10hz.toml",
];

/// The bridges' chemical energy, counted at attachment, equals the contractile element's work
/// plus the bridges' heat plus the change of their strain energy. The run publishes ATP as it
/// is split, at detachment; counted at attachment it is more by e times the change in the
/// number of attached bridges, `e N_hs B ΔQ0`, which the test adds from the states. Every term
/// has its own source: the chemical power from the detachment flux D_0, the heat from A_0, A_2
/// and D_2, the work from F_CE v, the strain energy from Q2 and the bridge count from Q0.
#[test]
fn bridges_balance_chemical_energy_with_work_heat_and_strain() {
    let cfg = ActuatorConfig::default();
    let p = &cfg.muscles[0].params;
    for model in [ModelKind::HUXLEY, ModelKind::HUXLEY_PDE] {
        let per_q0 = atp_energy_per_q0(model, p);
        for name in BALANCE_RUNS {
            let r = run(name, &cfg, model, 1000.0);
            for i in 0..r.muscle_names.len() {
                let chem_detach = integral(&r, i, |m| m.metabolic_power - m.activation_heat_rate);
                let work = integral(&r, i, |m| m.work_rate);
                let heat = integral(&r, i, |m| m.shortening_heat_rate);
                let (first, last) = (&r.record(0).muscles[i], &r.last().unwrap().muscles[i]);
                let strain = last.crossbridge_energy - first.crossbridge_energy;
                let bound = per_q0 * (last.q0 - first.q0);
                let chem_attach = chem_detach + bound;
                let residual = chem_attach - (work + heat + strain);
                let rel = residual / chem_attach;
                println!(
                    "{model} {name} {}: chemical {chem_detach:.6} J (+ bound {bound:.3e} J) = \
                     work {work:.5} + heat {heat:.5} + strain {strain:.3e}; residual {residual:.2e} J \
                     ({rel:.2e})",
                    r.muscle_names[i]
                );
                assert!(chem_detach > 1.0, "{model} {name}: {chem_detach} J");
                assert!(
                    rel.abs() < 2e-3,
                    "{model} {name}: residual {rel:.3e} of the chemical energy"
                );
            }
        }
    }
}

/// The parts of the metabolic power sum to it at every tick, for every model; the metabolic
/// energy of the Huxley models is the trapezoidal integral of their power; Hill's metabolic
/// power is its phenomenological model's.
#[test]
fn parts_sum_to_totals_and_energies_integrate_powers() {
    let cfg = ActuatorConfig::default();
    for model in ModelKind::all() {
        let r = run(
            "scenarios/elbow_cocontraction_10hz.toml",
            &cfg,
            model,
            1000.0,
        );
        for rec in r.records() {
            for m in rec.muscles {
                let parts = m.activation_heat_rate
                    + m.shortening_heat_rate
                    + m.work_rate
                    + m.bridge_storage_rate;
                let scale = m.activation_heat_rate.abs()
                    + m.shortening_heat_rate.abs()
                    + m.work_rate.abs()
                    + 1.0;
                assert!(
                    (parts - m.metabolic_power).abs() <= 1e-12 * scale,
                    "{model} at {} s: parts {parts} W, total {} W",
                    rec.time,
                    m.metabolic_power
                );
                if model == ModelKind::HILL {
                    assert_eq!(m.metabolic_power, m.phenomenological_power);
                    assert_eq!(m.bridge_storage_rate, 0.0);
                }
            }
        }
        let last = &r.last().unwrap().muscles;
        for (i, end) in last.iter().enumerate() {
            let integral = integral(&r, i, |m| m.metabolic_power);
            if model != ModelKind::HILL {
                // The bridges do not see the excitation: their power at a tick's start is the
                // previous tick's end, so the run's energy is exactly this integral.
                let d = (end.metabolic_energy - integral).abs();
                assert!(
                    d <= 1e-9 * integral,
                    "{model}: {} J against {integral} J",
                    end.metabolic_energy
                );
            }
            assert!(end.metabolic_energy > 0.0 && end.phenomenological_energy > 0.0);
        }
    }
}

/// a and b within `rel` of the larger in size.
fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

/// What a run publishes is what the muscle's end state gives when evaluated afresh: to the bit
/// for Hill (the phenomenological model's terms of the excitation, computed once per command,
/// change nothing), and to rounding (1e-14 of the largest power) for DM, whose bridges' fluxes take the error
/// function and exponential at the closure's limits from the stepper's last closure evaluation
/// by a Taylor series (docs/model.md §11.1, Cost). The command changes every tick, and the
/// activation crosses it both ways; each tick's energy is the trapezoid between the previous
/// end state under the new excitation and the new end state.
#[test]
fn published_rates_and_energies_are_those_of_a_fresh_evaluation() {
    for energy_model in EnergyModel::ALL {
        let cfg = ActuatorConfig::default().with_energy_model(energy_model);
        // The full model's grid is stepped in its part, not in the simulation's plant.
        for model in [ModelKind::HILL, ModelKind::HUXLEY] {
            let mut a = Actuator::new(&cfg, model, 1000.0).unwrap();
            let dt = 1.0 / a.rate_hz();
            let mut energy = [0.0; 2];
            for k in 0..300u32 {
                let sim = a.simulation();
                let (y0, a0) = (sim.state().to_vec(), sim.activations().to_vec());
                let u = [0.5 + 0.5 * (0.05 * k as f64).sin(), 0.3];
                a.set_excitation(0, u[0]);
                a.set_excitation(1, u[1]);
                a.step().unwrap();
                let sim = a.simulation();
                for (i, mtu) in sim.plant().mtus.iter().enumerate() {
                    let terms = mtu.probe.excitation_terms(u[i]);
                    let (plant, inputs) = (sim.plant(), sim.inputs());
                    let start = plant.metabolic(&y0, i, a0[i], inputs, &terms);
                    let end = plant.metabolic(sim.state(), i, sim.activations()[i], inputs, &terms);
                    let m = &a.muscles()[i];
                    let r = &end.rates;
                    let published = [
                        m.metabolic_power,
                        m.activation_heat_rate,
                        m.shortening_heat_rate,
                        m.work_rate,
                        m.bridge_storage_rate,
                        m.atp_rate,
                        m.phenomenological_power,
                    ];
                    let fresh = [
                        r.metabolic_w,
                        r.activation_heat_w,
                        r.shortening_heat_w,
                        r.work_w,
                        r.storage_w,
                        r.atp_rate_mol_s,
                        r.phenomenological_w,
                    ];
                    let what = format!("{model} {energy_model:?} tick {k} muscle {i}");
                    energy[i] += 0.5 * dt * (start.rates.metabolic_w + r.metabolic_w);
                    if model == ModelKind::HILL {
                        assert_eq!(published, fresh, "{what}");
                        assert_eq!(m.metabolic_energy, energy[i], "{what}");
                    } else {
                        // The powers to rounding of the largest (the storage rate is a
                        // difference of larger ones), the ATP rate of itself.
                        let watts = published.iter().fold(0.0f64, |m, p| m.max(p.abs()));
                        for (j, (p, f)) in published.iter().zip(fresh).enumerate() {
                            let ok = if j == 5 {
                                close(*p, f, 1e-14)
                            } else {
                                (p - f).abs() <= 1e-14 * watts
                            };
                            assert!(ok, "{what}: {published:?} vs {fresh:?}");
                        }
                        assert!(close(m.metabolic_energy, energy[i], 1e-13), "{what}");
                    }
                }
            }
        }
    }
}

/// The energies converge with the tick: at 1 kHz within 1e-3 of those at 8 kHz, for a pulse
/// whose excitation steps (the phenomenological models see the step at the tick's start).
#[test]
fn energies_converge_with_the_tick() {
    let cfg = ActuatorConfig::default();
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        let coarse = run("pulse", &cfg, model, 1000.0);
        let fine = run("pulse", &cfg, model, 8000.0);
        let (a, b) = (
            &coarse.last().unwrap().muscles[0],
            &fine.last().unwrap().muscles[0],
        );
        for (what, x, y) in [
            ("metabolic", a.metabolic_energy, b.metabolic_energy),
            (
                "phenomenological",
                a.phenomenological_energy,
                b.phenomenological_energy,
            ),
        ] {
            let rel = (x - y) / y;
            println!("{model} pulse {what}: {x:.6} J at 1 kHz, {y:.6} J at 8 kHz ({rel:.2e})");
            assert!(rel.abs() < 1e-3, "{model} {what}: {x} J against {y} J");
        }
    }
}

/// Isometric at full activation (the pulse's plateau), the Huxley models' metabolic power per
/// kg lies between the phenomenological models' for the same muscle: Umberger's (Uchida's
/// options) and Bhargava's, computed on the same run.
#[test]
fn isometric_cost_lies_between_the_phenomenological_models() {
    let p = MuscleParams::default();
    let mass = p.energetics.mass_kg(p.f_max, p.l_opt);
    let at_plateau = |energy_model: EnergyModel, model: ModelKind| {
        let cfg = ActuatorConfig::default().with_energy_model(energy_model);
        let r = run("pulse", &cfg, model, 1000.0);
        let m = &r.record(1900).muscles[0];
        (m.metabolic_power / mass, m.phenomenological_power / mass)
    };
    for model in [ModelKind::HUXLEY, ModelKind::HUXLEY_PDE] {
        let (mech, umberger) = at_plateau(EnergyModel::Umberger, model);
        let (_, bhargava) = at_plateau(EnergyModel::Bhargava, model);
        println!("{model}: {mech:.1} W/kg; Umberger {umberger:.1}, Bhargava {bhargava:.1} W/kg");
        assert!(umberger < mech && mech < bhargava, "{model}: {mech} W/kg");
    }
}

/// The cost of stiffness: isometric co-contraction of the elbow at rising excitation stiffens
/// the joint and costs more, for every model and energy model (the paper's trade-off).
#[test]
fn stiffness_and_its_cost_rise_with_cocontraction() {
    for model in ModelKind::all() {
        let mut prev = (f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for level in [0.0, 0.1, 0.2, 0.4, 0.6, 0.8, 1.0] {
            let (k, power, phen) = cocontraction(model, level);
            println!("{model} at {level}: {k:.1} N m/rad for {power:.2} W ({phen:.2} W phenomenological)");
            assert!(
                k > prev.0 && power > prev.1 && phen > prev.2,
                "{model} at {level}"
            );
            prev = (k, power, phen);
        }
    }
}

/// The elbow held by both muscles at `level` for 0.3 s: joint stiffness, N m/rad, and the
/// total metabolic and phenomenological power, W.
fn cocontraction(model: ModelKind, level: f64) -> (f64, f64, f64) {
    let text = format!(
        "duration = 0.3\nattachment = \"joint\"\n\
         [[input]]\nsignal = \"excitation\"\nmuscle = \"flexor\"\nkind = \"constant\"\nvalue = {level}\n\
         [[input]]\nsignal = \"excitation\"\nmuscle = \"extensor\"\nkind = \"constant\"\nvalue = {level}\n"
    );
    let path = std::env::temp_dir().join(format!("cocontraction_{}_{level}.toml", model.name()));
    std::fs::write(&path, text).unwrap();
    let sc = Scenario::from_file(&path).unwrap();
    let r = sc
        .run(
            &ActuatorConfig::default(),
            model,
            1000.0,
            default_stepping(model),
        )
        .unwrap();
    let last = r.last().unwrap();
    let sum = |f: fn(&MuscleSnapshot) -> f64| last.muscles.iter().map(f).sum::<f64>();
    (
        last.joints[0].stiffness,
        sum(|m| m.metabolic_power),
        sum(|m| m.phenomenological_power),
    )
}
