//! Any limb (docs/model.md §8b): the built-in configurations, a biarticular muscle's coupling of
//! two joints, the joint stiffness matrix against finite differences of the joint torques, the
//! accuracy of multi-joint runs against the adaptive reference, energy balance of a passive
//! multi-joint limb, determinism, and one clear error per broken topology rule.

mod common;

use muscle_actuator_core::config::{ActuatorConfig, ConfigError};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::{
    default_stepping, Actuator, Scenario, Schedule, ScheduledInput, Signal,
};
use std::path::PathBuf;

const FORCE_TOL: f64 = 1e-3 * 3913.0;
const LENGTH_TOL: f64 = 1e-6;

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn settle(act: &mut Actuator, seconds: f64) {
    for _ in 0..(seconds * act.rate_hz()).round() as usize {
        act.step().unwrap();
    }
}

/// Two joints `a` and `b`, an antagonistic pair on each, and one biarticular muscle `bi` with
/// polynomial moment arms (+ at a, - at b) whose path is slack at rest (no passive stiffness
/// until it is activated).
const TWO_JOINTS: &str = r#"
[[joint]]
name = "a"
[[joint]]
name = "b"
inertia = 0.03

[[muscle]]
name = "a_flexor"
span = [{ joint = "a", moment_arm = 0.03 }]
[[muscle]]
name = "a_extensor"
span = [{ joint = "a", moment_arm = [-0.03, 0.004] }]
[[muscle]]
name = "b_flexor"
span = [{ joint = "b", moment_arm = 0.025 }]
[[muscle]]
name = "b_extensor"
span = [{ joint = "b", moment_arm = -0.025 }]
[[muscle]]
name = "bi"
f_max = 2500.0
path_length = 0.4104
span = [
    { joint = "a", moment_arm = [0.02, 0.003, -0.002] },
    { joint = "b", moment_arm = [-0.015, 0.002] },
]
"#;

fn two_joints() -> ActuatorConfig {
    ActuatorConfig::from_toml_str(TWO_JOINTS).unwrap()
}

#[test]
fn built_in_configurations_resolve_by_name() {
    assert_eq!(
        ActuatorConfig::resolve("elbow").unwrap(),
        ActuatorConfig::default()
    );
    let arm = ActuatorConfig::resolve("arm").unwrap();
    assert_eq!(arm.joint_names(), ["shoulder", "elbow"]);
    assert_eq!(
        arm.muscle_names(),
        ["TRIlong", "TRIlat", "TRImed", "BIClong", "BICshort", "BRA"]
    );
    let biarticular: Vec<&str> = arm
        .muscles
        .iter()
        .filter(|m| m.spans.len() == 2)
        .map(|m| m.name.as_str())
        .collect();
    assert_eq!(biarticular, ["TRIlong", "BIClong", "BICshort"]);
    // arm26's numbers (Holzbaur et al. 2005): Fmax, optimal fibre and tendon slack lengths.
    let bic = &arm.muscles[3].params;
    assert_eq!((bic.f_max, bic.l_opt, bic.l_ts), (624.3, 0.1157, 0.2723));
    let four =
        ActuatorConfig::resolve(root().join("configs/four_joints.toml").to_str().unwrap()).unwrap();
    assert_eq!(four.joints.len(), 4);
    assert_eq!(four.muscles.len(), 8);
    let e = ActuatorConfig::resolve("leg").unwrap_err().to_string();
    assert!(e.contains("elbow, arm"), "{e}");
}

/// Exciting only the biarticular muscle moves both joints, each the way of its moment arm.
#[test]
fn a_biarticular_muscle_moves_both_joints_its_ways() {
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        let cfg = two_joints();
        let mut act = Actuator::new(&cfg, model, 1000.0).unwrap();
        settle(&mut act, 0.1);
        let (a0, b0) = (act.joints()[0].position, act.joints()[1].position);
        act.set_excitation(4, 0.3);
        settle(&mut act, 0.2);
        let (a1, b1) = (act.joints()[0].position, act.joints()[1].position);
        println!("{model}: a {a0:.4} -> {a1:.4}, b {b0:.4} -> {b1:.4}");
        assert!(a1 - a0 > 0.02, "{model}: joint a should flex: {a0} -> {a1}");
        assert!(
            b1 - b0 < -0.02,
            "{model}: joint b should extend: {b0} -> {b1}"
        );
        // And the arm's long biceps: positive arms at shoulder and elbow.
        let arm = ActuatorConfig::resolve("arm").unwrap();
        let mut arm_act = Actuator::new(&arm, model, 1000.0).unwrap();
        settle(&mut arm_act, 0.05);
        let s0 = arm_act.joints()[0].position;
        let e0 = arm_act.joints()[1].position;
        arm_act.set_excitation(3, 0.5);
        settle(&mut arm_act, 0.15);
        let (s1, e1) = (arm_act.joints()[0].position, arm_act.joints()[1].position);
        assert!(
            s1 > s0 + 1e-3 && e1 > e0 + 1e-3,
            "{model} BIClong: shoulder {s0}->{s1}, elbow {e0}->{e1}"
        );
    }
}

/// The stiffness matrix: symmetric, positive semi-definite here, off-diagonal exactly when the
/// biarticular muscle is active, and equal to the finite-difference derivative of the joint
/// torques with respect to the angles, each fibre re-balancing quasi-statically (its
/// contractile element a spring of stiffness k_CE, bonds held).
#[test]
fn stiffness_matrix_is_the_derivative_of_the_joint_torques() {
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        let cfg = two_joints();
        let mut act = Actuator::new(&cfg, model, 1000.0).unwrap();
        act.set_excitation(0, 0.2);
        act.set_excitation(1, 0.2);
        act.set_excitation(2, 0.3);
        act.set_excitation(3, 0.3);
        settle(&mut act, 0.3);
        let k = act.state().stiffness_matrix.clone();
        assert_eq!(
            k[1], 0.0,
            "{model}: inactive, slack biarticular muscle: {k:?}"
        );
        assert_eq!(k[2], 0.0);
        act.set_excitation(4, 0.4);
        settle(&mut act, 0.3);
        let k = act.state().stiffness_matrix.clone();
        assert!(
            k[1] != 0.0 && k[1] == k[2],
            "{model}: symmetric coupling: {k:?}"
        );
        // Positive semi-definite (2 × 2: trace and determinant).
        assert!(
            k[0] + k[3] > 0.0 && k[0] * k[3] - k[1] * k[2] >= 0.0,
            "{k:?}"
        );
        for (j, joint) in act.joints().iter().enumerate() {
            assert_eq!(joint.stiffness, k[j * 2 + j]);
        }
        let fd = finite_difference_stiffness(&act);
        println!("{model}: K = {k:?}\n      FD = {fd:?}");
        let scale = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in k.iter().zip(&fd) {
            assert!((a - b).abs() <= 1e-4 * scale, "{model}: {k:?} vs {fd:?}");
        }
    }
}

/// `-∂τ_j/∂θ_k` by central differences: the angles moved by ±h, every fibre re-balanced so that
/// its tendon force change equals the fibre's (contractile element as a spring of stiffness
/// k_CE, the parallel element exact).
fn finite_difference_stiffness(act: &Actuator) -> Vec<f64> {
    let sim = act.simulation();
    let plant = sim.plant();
    let y0 = sim.state().to_vec();
    let n = plant.joint_count();
    let muscles = act.muscles().to_vec();
    let torques = |y: &[f64]| -> Vec<f64> {
        let forces: Vec<f64> = (0..plant.muscle_count())
            .map(|i| {
                let mtu = &plant.mtus[i];
                let m = &muscles[i];
                let path = plant.path_length(y, i).unwrap();
                let fibre = |l: f64| {
                    m.force + m.stiffness * (l - m.fiber_length) + mtu.parallel.force(l)
                        - mtu.parallel.force(m.fiber_length)
                };
                // Bisection on the balance F_SE(path - l) = fibre(l) (monotone in l).
                let (mut lo, mut hi) = (m.fiber_length - 0.01, m.fiber_length + 0.01);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if mtu.tendon.force(path - mid) > fibre(mid) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                mtu.tendon.force(path - 0.5 * (lo + hi))
            })
            .collect();
        let mut tau = vec![0.0; n];
        plant.add_muscle_torques(y, |i| forces[i], |j, t| tau[j] += t);
        tau
    };
    let h = 1e-6;
    let mut k = vec![0.0; n * n];
    for c in 0..n {
        let (mut yp, mut ym) = (y0.clone(), y0.clone());
        yp[2 * c] += h;
        ym[2 * c] -= h;
        let (tp, tm) = (torques(&yp), torques(&ym));
        for r in 0..n {
            k[r * n + c] = -(tp[r] - tm[r]) / (2.0 * h);
        }
    }
    k
}

fn scenario(name: &str) -> Scenario {
    Scenario::from_file(&root().join("scenarios").join(name)).unwrap()
}

fn accuracy(sc: &Scenario, cfg: &ActuatorConfig, model: ModelKind) {
    let (df, dl) =
        common::worst_deviation_from_reference(sc, cfg, model, 1000.0, default_stepping(model));
    println!(
        "{} {model}: worst |dF| = {df:.3e} N, worst |dl_m| = {dl:.3e} m",
        sc.name
    );
    assert!(df <= FORCE_TOL, "{} {model}: {df} N", sc.name);
    assert!(dl <= LENGTH_TOL, "{} {model}: {dl} m", sc.name);
}

#[test]
fn arm_co_contraction_matches_the_reference_solver() {
    let arm = ActuatorConfig::resolve("arm").unwrap();
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        accuracy(&scenario("arm_cocontraction.toml"), &arm, model);
    }
}

#[test]
fn arm_single_biarticular_muscle_matches_the_reference_solver() {
    let arm = ActuatorConfig::resolve("arm").unwrap();
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        accuracy(&scenario("arm_biceps.toml"), &arm, model);
    }
}

#[test]
fn four_joints_match_the_reference_solver() {
    let cfg = ActuatorConfig::from_file(&root().join("configs/four_joints.toml")).unwrap();
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        accuracy(&scenario("four_joints.toml"), &cfg, model);
    }
}

#[test]
fn limb_runs_are_bit_identical() {
    let arm = ActuatorConfig::resolve("arm").unwrap();
    let sc = scenario("arm_cocontraction.toml");
    for model in ModelKind::all() {
        let a = sc
            .run(&arm, model, 1000.0, default_stepping(model))
            .unwrap();
        let b = sc
            .run(&arm, model, 1000.0, default_stepping(model))
            .unwrap();
        for (ra, rb) in a.records().zip(b.records()) {
            let bits = |r: &muscle_actuator_core::sim::Record| -> Vec<u64> {
                r.muscles
                    .iter()
                    .flat_map(|m| m.values())
                    .chain(r.joints.iter().flat_map(|j| j.values()))
                    .chain(r.stiffness_matrix.iter().copied())
                    .map(f64::to_bits)
                    .collect()
            };
            assert_eq!(bits(&ra), bits(&rb), "{model} t = {}", ra.time);
        }
    }
}

/// A passive limb of two joints and six muscles under external torques: their work equals the
/// change of strain (tendons, parallel elements) and kinetic energy (joints, fibres) plus what
/// the joint and fibre dampers dissipate.
#[test]
fn passive_limb_balances_energy() {
    const RATE: f64 = 20_000.0;
    let mut arm = ActuatorConfig::resolve("arm").unwrap();
    arm.joints[0].initial_angle = 0.3;
    arm.joints[1].initial_angle = 1.0;
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        let mut act = Actuator::new(&arm, model, RATE).unwrap();
        let energy = |a: &Actuator| -> f64 {
            a.muscles()
                .iter()
                .map(|m| m.tendon_energy + m.fiber_energy)
                .sum::<f64>()
                + a.simulation().kinetic_energy()
        };
        let power = |a: &Actuator| -> f64 {
            let joints: f64 = a
                .joints()
                .iter()
                .zip(&arm.joints)
                .map(|(j, p)| p.damping * j.velocity.powi(2))
                .sum();
            joints
                + a.muscles()
                    .iter()
                    .zip(&arm.muscles)
                    .map(|(m, c)| c.params.b_m * m.fiber_velocity.powi(2))
                    .sum::<f64>()
        };
        let e0 = energy(&act);
        let (mut work, mut dissipated) = (0.0, 0.0);
        let mut theta: Vec<f64> = act.joints().iter().map(|j| j.position).collect();
        let mut p_prev = power(&act);
        for k in 0..(0.5 * RATE) as usize {
            let t = k as f64 / RATE;
            let tau = [
                2.0 * (2.0 * std::f64::consts::PI * 3.0 * t).sin(),
                -(2.0 * std::f64::consts::PI * 5.0 * t).sin(),
            ];
            act.set_external_torque(0, tau[0]);
            act.set_external_torque(1, tau[1]);
            act.step().unwrap();
            for (j, joint) in act.joints().iter().enumerate() {
                work += tau[j] * (joint.position - theta[j]);
                theta[j] = joint.position;
                let p = &arm.joints[j];
                assert!(
                    joint.position > p.min_angle && joint.position < p.max_angle,
                    "the end stops must stay out of this balance"
                );
            }
            let p_now = power(&act);
            dissipated += 0.5 * (p_prev + p_now) / RATE;
            p_prev = p_now;
        }
        let stored = energy(&act) - e0;
        let residual = work - stored - dissipated;
        println!("arm {model}: work {work:.6e} J = stored {stored:.6e} + dissipated {dissipated:.6e} (residual {residual:.2e})");
        assert!(
            theta.iter().all(|t| t.abs() > 0.01),
            "the loads should move the joints"
        );
        assert!(
            residual.abs() <= 1e-3 * (work.abs() + dissipated),
            "{model}: residual {residual} J"
        );
    }
}

fn errors_of(text: &str) -> String {
    match ActuatorConfig::from_toml_str(text) {
        Err(e @ ConfigError::Invalid(_)) => e.to_string(),
        Err(other) => panic!("expected rule violations, got {other}"),
        Ok(_) => panic!("accepted:\n{text}"),
    }
}

/// Each broken topology rule gets its own line naming the joint or muscle.
#[test]
fn each_invalid_topology_gets_its_own_error() {
    let joint = "[[joint]]\nname = \"a\"\n";
    let pair = "[[muscle]]\nname = \"f\"\nspan = [{ joint = \"a\", moment_arm = 0.03 }]\n\
                [[muscle]]\nname = \"e\"\nspan = [{ joint = \"a\", moment_arm = -0.03 }]\n";
    let cases: &[(String, &[&str])] = &[
        (
            format!("{joint}{pair}[[muscle]]\nname = \"x\"\n"),
            &["muscle.x.span", "at least one joint"],
        ),
        (
            format!("{joint}{pair}[[muscle]]\nname = \"x\"\nspan = [{{ joint = \"knee\", moment_arm = 0.03 }}]\n"),
            &["muscle.x.span[0].joint", "\"knee\"", "names no joint", "joints: a"],
        ),
        (
            format!("{joint}[[joint]]\nname = \"lonely\"\n{pair}"),
            &["joint.lonely", "spanned by at least one muscle"],
        ),
        (
            format!("{joint}{joint}{pair}"),
            &["joint[1].name", "must be unique"],
        ),
        (
            format!("{joint}{pair}[[muscle]]\nname = \"f\"\nspan = [{{ joint = \"a\", moment_arm = 0.01 }}]\n"),
            &["muscle[2].name", "must be unique"],
        ),
        (
            format!("{joint}{pair}[[muscle]]\nname = \"x\"\nspan = [{{ joint = \"a\", moment_arm = nan }}]\n"),
            &["muscle.x.span[0].moment_arm", "finite"],
        ),
        (
            format!("{joint}{pair}[[muscle]]\nname = \"x\"\nspan = [{{ joint = \"a\", moment_arm = 0.0 }}]\n"),
            &["muscle.x.span[0].moment_arm", "must not be zero"],
        ),
        (
            format!("{joint}{pair}[[muscle]]\nname = \"x\"\nspan = [{{ joint = \"a\", moment_arm = [0.01, 0.02] }}]\n"),
            &["muscle.x.span[0].moment_arm", "changes sign"],
        ),
        (
            format!("{joint}{pair}[[muscle]]\nname = \"x\"\nspan = [{{ joint = \"a\", moment_arm = 0.01 }}, {{ joint = \"a\", moment_arm = 0.02 }}]\n"),
            &["muscle.x.span[1].joint", "at most once"],
        ),
        (
            format!("{joint}inertia = -1.0\n{pair}"),
            &["joint.a.inertia", "must be > 0"],
        ),
        (
            format!("{joint}{pair}[[muscle]]\nname = \"x\"\npath_length = -0.4\nspan = [{{ joint = \"a\", moment_arm = 0.01 }}]\n"),
            &["muscle.x.path_length", "> 0"],
        ),
    ];
    for (text, needles) in cases {
        let e = errors_of(text);
        for n in *needles {
            assert!(e.contains(n), "expected {n:?} in: {e}\nfor:\n{text}");
        }
        assert_eq!(e.lines().count(), 1, "one rule broken, one line: {e}");
    }
    // A real sign change is accepted when the configuration says so.
    let ok = format!("{joint}{pair}[[muscle]]\nname = \"x\"\nspan = [{{ joint = \"a\", moment_arm = [0.01, 0.02], changes_sign = true }}]\n");
    ActuatorConfig::from_toml_str(&ok).unwrap();
}

#[test]
fn a_scenario_naming_an_unknown_muscle_or_joint_lists_the_valid_ones() {
    let arm = ActuatorConfig::resolve("arm").unwrap();
    let run = |signal: Signal, muscle: Option<&str>, joint: Option<&str>| {
        let sc = Scenario {
            inputs: vec![ScheduledInput {
                signal,
                muscle: muscle.map(String::from),
                joint: joint.map(String::from),
                schedule: Schedule::Constant { value: 0.5 },
            }],
            duration: 0.02,
            ..scenario("arm_biceps.toml")
        };
        let hill = ModelKind::HILL;
        sc.run(&arm, hill, 1000.0, default_stepping(hill))
    };
    let e = run(Signal::Excitation, Some("biceps"), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("unknown muscle \"biceps\""), "{e}");
    assert!(
        e.contains("TRIlong, TRIlat, TRImed, BIClong, BICshort, BRA"),
        "{e}"
    );
    let e = run(Signal::ExternalTorque, None, Some("wrist"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unknown joint \"wrist\"") && e.contains("shoulder, elbow"),
        "{e}"
    );
    // The same inputs with names the arm has run.
    run(Signal::Excitation, Some("BRA"), None).unwrap();
    run(Signal::ExternalTorque, None, Some("elbow")).unwrap();
}
