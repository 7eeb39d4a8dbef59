//! The formulations of a muscle–tendon unit (docs/model.md §5b, docs/configuration.md `fibre`,
//! `tendon`): an equilibrium fibre is the massless limit of the paper's fibre with mass, a rigid
//! tendon is the limit of ever stiffer elastic ones, and each holds its defining balance at every
//! output; the combinations that cannot work are refused with a message that says why.
//!
//! Each limit is checked by convergence: the difference to the limit must fall in proportion as
//! the mass (or the tendon's compliance) falls tenfold, which a formulation that only looked
//! close could not do.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::Stepping;
use muscle_actuator_core::sim::{
    default_stepping, MuscleSnapshot, Scenario, Schedule, ScheduledInput, SetupKind, Signal,
};

const MODELS: [ModelKind; 2] = [ModelKind::HILL, ModelKind::HUXLEY];
const RATE: f64 = 1000.0;

/// One driven elbow (moment arm 3 cm) and one muscle with the given extra keys.
fn config(muscle_keys: &str) -> ActuatorConfig {
    ActuatorConfig::from_toml_str(&format!(
        "[[joint]]\nname = \"elbow\"\ndriven = true\n\
         [[muscle]]\nname = \"flexor\"\n{muscle_keys}\n\
         span = [{{ joint = \"elbow\", moment_arm = 0.03 }}]\n"
    ))
    .unwrap_or_else(|e| panic!("{muscle_keys}: {e}"))
}

fn input(signal: Signal, muscle: Option<&str>, joint: Option<&str>, s: Schedule) -> ScheduledInput {
    ScheduledInput {
        signal,
        muscle: muscle.map(Into::into),
        joint: joint.map(Into::into),
        schedule: s,
    }
}

/// An excitation pulse (0.05–0.35 s) while the elbow swings ±0.1 rad at 2 Hz, the path
/// lengthening and shortening by up to 3 mm: isometric onset, shortening and lengthening under
/// load, and relaxation.
fn swing() -> Scenario {
    Scenario {
        name: "fibre-kinds".into(),
        duration: 0.6,
        attachment: SetupKind::Driven,
        length: None,
        initial_force: 0.0,
        inputs: vec![
            input(
                Signal::Excitation,
                Some("flexor"),
                None,
                Schedule::Pulse {
                    start: 0.05,
                    end: 0.35,
                    value: 0.8,
                    base: 0.02,
                },
            ),
            input(
                Signal::JointAngle,
                None,
                Some("elbow"),
                Schedule::Sine {
                    offset: -0.05,
                    amplitude: 0.1,
                    frequency: 2.0,
                    phase: 0.0,
                },
            ),
        ],
    }
}

/// Sub-steps to a tolerance far below the differences the limits are judged by, so that the
/// stepper's own error does not hide their convergence.
const TIGHT: Stepping = Stepping::Adaptive {
    tolerance: 1e-10,
    max_substeps: 10_000,
};

fn run(cfg: &ActuatorConfig, model: ModelKind) -> Vec<MuscleSnapshot> {
    let sc = swing();
    let out = sc
        .run(cfg, model, RATE, TIGHT)
        .unwrap_or_else(|e| panic!("{model}: {e}"));
    out.records().map(|r| r.muscles[0]).collect()
}

/// The largest tendon-force difference between two runs, N.
fn worst_force_difference(a: &[MuscleSnapshot], b: &[MuscleSnapshot]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x.force - y.force).abs())
        .fold(0.0, f64::max)
}

/// As the fibre's mass falls tenfold twice, the run approaches the equilibrium fibre's, the
/// difference falling about tenfold each time (the singular perturbation's first order in M).
#[test]
fn an_equilibrium_fibre_is_the_massless_limit_of_the_fibre_with_mass() {
    for model in MODELS {
        let eq = run(&config("fibre = \"equilibrium\""), model);
        let peak = eq.iter().map(|m| m.force).fold(0.0, f64::max);
        assert!(peak > 500.0, "{model}: the pulse should load the muscle");
        let errs: Vec<f64> = [0.0095, 0.00095, 0.000095]
            .iter()
            .map(|mass| {
                worst_force_difference(&run(&config(&format!("mass = {mass}")), model), &eq)
            })
            .collect();
        println!(
            "{model}: worst |F_massed - F_equilibrium| for M = 9.5e-3, 9.5e-4, 9.5e-5 kg: \
             {:.3e}, {:.3e}, {:.3e} N (peak {peak:.0} N)",
            errs[0], errs[1], errs[2]
        );
        for w in errs.windows(2) {
            let ratio = w[0] / w[1];
            assert!(
                (5.0..20.0).contains(&ratio),
                "{model}: tenfold less mass should give about tenfold less difference: {errs:?}"
            );
        }
        assert!(errs[2] < 1e-3 * peak, "{model}: {errs:?}");
    }
}

/// As Thelen's tendon strain at Fmax falls tenfold twice, the elastic tendon's run
/// approaches the rigid tendon's, the difference falling about tenfold each time.
#[test]
fn a_rigid_tendon_is_the_limit_of_ever_stiffer_elastic_ones() {
    // Thelen's tendon is slack below its slack length whatever its strain (DeGroote's curve is
    // offset: with a strain below 0.005 it carries force at slack length, so it has no rigid
    // limit).
    let base = "curves = \"thelen2003\"\nfibre = \"equilibrium\"\nl_ts = 0.2\nl_opt = 0.1\n\
                path_length = 0.3";
    for model in MODELS {
        let rigid = run(&config(&format!("{base}\ntendon = \"rigid\"")), model);
        let peak = rigid.iter().map(|m| m.force).fold(0.0, f64::max);
        assert!(peak > 500.0, "{model}: the pulse should load the muscle");
        let errs: Vec<f64> = [1e-3, 1e-4]
            .iter()
            .map(|strain| {
                let elastic = run(&config(&format!("{base}\ntendon_strain = {strain}")), model);
                // Only while the tendon is loaded: a slack elastic tendon carries nothing, where
                // a rigid one still carries the fibre's passive and damping forces.
                let loaded = |m: &&MuscleSnapshot| m.force > 0.05 * peak;
                let (e, r): (Vec<_>, Vec<_>) = elastic
                    .iter()
                    .zip(&rigid)
                    .filter(|(_, r)| loaded(r))
                    .map(|(e, r)| (*e, *r))
                    .unzip();
                worst_force_difference(&e, &r)
            })
            .collect();
        println!(
            "{model}: worst |F_elastic - F_rigid| while loaded for tendon strain 1e-3, 1e-4: \
             {:.3e}, {:.3e} N (peak {peak:.0} N)",
            errs[0], errs[1]
        );
        assert!(
            errs[0] > 5.0 * errs[1],
            "{model}: a tenfold stiffer tendon should give at least fivefold less difference: \
             {errs:?}"
        );
        assert!(errs[1] < 0.02 * peak, "{model}: {errs:?}");
    }
}

/// At every output, an equilibrium fibre's tendon carries exactly its contractile, parallel and
/// damping forces along it, `F_T = (F_CE + F_P + B_m v) cos α`; a rigid tendon's fibre spans the
/// path less the slack length (its projection, with pennation), and the force is the same sum.
#[test]
fn the_balance_holds_at_every_output() {
    for model in MODELS {
        for keys in [
            "fibre = \"equilibrium\"",
            "fibre = \"equilibrium\"\ncurves = \"thelen2003\"",
            "fibre = \"equilibrium\"\ntendon = \"rigid\"\ncurves = \"degroote2016\"",
            "fibre = \"equilibrium\"\npennation = 0.35",
            "fibre = \"equilibrium\"\ntendon = \"rigid\"\npennation = 0.35",
        ] {
            let cfg = config(keys);
            let p = cfg.muscles[0].params.clone();
            let rigid = keys.contains("rigid");
            let sc = swing();
            let out = sc.run(&cfg, model, RATE, default_stepping(model)).unwrap();
            let mut worst = 0.0f64;
            // Constant thickness: sin α = l_opt sin α_opt / l_m.
            let height = p.l_opt * p.pennation.sin();
            for r in out.records() {
                let m = r.muscles[0];
                let cos = (1.0 - (height / m.fiber_length).powi(2)).sqrt();
                let sum = (m.ce_force + m.pe_force + p.b_m * m.fiber_velocity) * cos;
                worst = worst.max((m.force - sum).abs() / p.f_max);
                if rigid {
                    let path = cfg.muscles[0].path_length() - 0.03 * r.joints[0].position;
                    let along = path - p.l_ts;
                    assert!((m.fiber_length - along.hypot(height)).abs() < 1e-12);
                    assert_eq!(m.tendon_length, p.l_ts);
                    assert_eq!(m.tendon_energy, 0.0);
                }
            }
            println!(
                "{model} [{}]: worst |F_T - (F_CE + F_P + B v)| / Fmax = {worst:.1e}",
                keys.replace('\n', ", ")
            );
            assert!(worst < 1e-9, "{model} [{keys}]: {worst}");
        }
    }
}

/// Combinations that cannot work are refused, each with its reason.
#[test]
fn impossible_formulations_are_refused_with_the_reason() {
    let refused = |keys: &str, needle: &str| {
        let text = format!(
            "[[joint]]\nname = \"elbow\"\n[[muscle]]\nname = \"flexor\"\n{keys}\n\
             span = [{{ joint = \"elbow\", moment_arm = 0.03 }}]\n"
        );
        let e = ActuatorConfig::from_toml_str(&text)
            .unwrap_err()
            .to_string();
        assert!(e.contains(needle), "[{keys}]: {e}");
    };
    refused("tendon = \"rigid\"", "needs fibre = \"equilibrium\"");
    refused(
        "tendon = \"rigid\"\nfibre = \"equilibrium\"\ncurves = \"thelen2003\"\ntendon_strain = 0.05",
        "does not apply to a rigid tendon",
    );
    refused("fibre = \"massles\"", "expected one of massed, equilibrium");
    refused("pennation = 0.2", "needs fibre = \"equilibrium\"");
    refused(
        "fibre = \"equilibrium\"\npennation = 1.5",
        "must be >= 0 and < 1.4706 rad",
    );
    refused(
        "fibre = \"equilibrium\"\npennation = -0.1",
        "must be >= 0 and < 1.4706 rad",
    );
    refused("tendon = \"stiff\"", "expected one of elastic, rigid");
    // The bridge models' force does not depend on velocity: without a damper nothing sets an
    // equilibrium fibre's velocity on an elastic tendon.
    let cfg = config("fibre = \"equilibrium\"\nb_m = 0.0");
    let e = swing()
        .run(
            &cfg,
            ModelKind::HUXLEY,
            RATE,
            default_stepping(ModelKind::HUXLEY),
        )
        .unwrap_err()
        .to_string();
    assert!(e.contains("b_m must be > 0"), "{e}");
    // Hill's force-velocity relation sets it, with the activation held at 0.01 or more (at zero
    // activation nothing would): the balance still holds at every output.
    let out = swing()
        .run(
            &cfg,
            ModelKind::HILL,
            RATE,
            default_stepping(ModelKind::HILL),
        )
        .unwrap_or_else(|e| panic!("hill, b_m = 0: {e}"));
    for r in out.records() {
        let m = r.muscles[0];
        assert!(
            (m.force - (m.ce_force + m.pe_force)).abs() <= 1e-9 * 3913.0,
            "at {}: F {} CE {} PE {} v {} a {} l_m {}",
            r.time,
            m.force,
            m.ce_force,
            m.pe_force,
            m.fiber_velocity,
            m.activation,
            m.fiber_length
        );
    }
    // On a rigid tendon the path sets the velocity: no damper needed.
    let cfg = config("fibre = \"equilibrium\"\ntendon = \"rigid\"\nb_m = 0.0");
    assert!(swing()
        .run(
            &cfg,
            ModelKind::HUXLEY,
            RATE,
            default_stepping(ModelKind::HUXLEY)
        )
        .is_ok());
}

/// A rigid tendon pulled by an external force is refused: nothing would set its fibre's length.
#[test]
fn a_force_driven_rigid_tendon_is_refused() {
    let cfg = ActuatorConfig::from_toml_str(
        "[[muscle]]\nname = \"flexor\"\nfibre = \"equilibrium\"\ntendon = \"rigid\"\n",
    )
    .unwrap();
    let sc = Scenario {
        name: "pull".into(),
        duration: 0.1,
        attachment: SetupKind::Force,
        length: None,
        initial_force: 100.0,
        inputs: vec![],
    };
    let e = sc
        .run(
            &cfg,
            ModelKind::HILL,
            RATE,
            default_stepping(ModelKind::HILL),
        )
        .unwrap_err()
        .to_string();
    assert!(e.contains("a rigid tendon needs a path over joints"), "{e}");
}
