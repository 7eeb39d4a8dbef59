//! Driven joints (docs/model.md §8c): the joint's angle and velocity are inputs, extrapolated
//! linearly over each tick, and the muscles are stepped for that motion. Each test checks against
//! something computed another way: a clamped muscle, a free run's own motion, the energy the
//! motion puts in, a limb without the driven joint.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::{
    default_stepping, Actuator, Scenario, Schedule, ScheduledInput, SetupKind, Signal,
};

#[path = "common/cli.rs"]
mod cli;
use cli::{bin, read_csv, run_ok, temp_dir};

const MODELS: [ModelKind; 2] = [ModelKind::HILL, ModelKind::HUXLEY];

fn config(text: &str) -> ActuatorConfig {
    ActuatorConfig::from_toml_str(text).unwrap()
}

/// The elbow with its two muscles, the joint driven or free.
fn elbow(driven: bool) -> ActuatorConfig {
    let mut c = ActuatorConfig::default();
    c.joints[0].driven = driven;
    c
}

fn input(signal: Signal, muscle: Option<&str>, joint: Option<&str>, s: Schedule) -> ScheduledInput {
    ScheduledInput {
        signal,
        muscle: muscle.map(Into::into),
        joint: joint.map(Into::into),
        schedule: s,
    }
}

fn scenario(attachment: SetupKind, length: Option<f64>, inputs: Vec<ScheduledInput>) -> Scenario {
    Scenario {
        name: "driven-test".into(),
        duration: 0.4,
        attachment,
        length,
        initial_force: 0.0,
        inputs,
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-300)
}

/// A driven joint held still is a clamp: its one muscle behaves as the `clamped` attachment at
/// the MTU length of that angle. The joint's entries stay exactly still (zero velocity, zero
/// error, zero Newton increments), so the sub-steps and the muscle's iterates are the clamped
/// run's: the forces agree to rounding.
#[test]
fn held_driven_joint_is_a_clamped_muscle() {
    let cfg = config(
        "[[joint]]\nname = \"elbow\"\ndriven = true\n\
         [[muscle]]\nname = \"flexor\"\nspan = [{ joint = \"elbow\", moment_arm = 0.03 }]\n",
    );
    let theta = -0.05; // rad: the path 1.5 mm longer than at 0, the tendon taut
    let length = cfg.muscles[0].path_length() - 0.03 * theta;
    let excitation = || {
        input(
            Signal::Excitation,
            Some("flexor"),
            None,
            Schedule::Pulse {
                start: 0.05,
                end: 0.25,
                value: 1.0,
                base: 0.0,
            },
        )
    };
    let driven = scenario(
        SetupKind::Driven,
        None,
        vec![
            excitation(),
            input(
                Signal::JointAngle,
                None,
                Some("elbow"),
                Schedule::Constant { value: theta },
            ),
        ],
    );
    let clamped = scenario(SetupKind::Clamped, Some(length), vec![excitation()]);
    for model in MODELS {
        let run = |s: &Scenario| s.run(&cfg, model, 1000.0, default_stepping(model)).unwrap();
        let (d, c) = (run(&driven), run(&clamped));
        let mut worst = 0.0f64;
        for (rd, rc) in d.records().zip(c.records()) {
            let (md, mc) = (rd.muscles[0], rc.muscles[0]);
            worst = worst.max(rel(md.force, mc.force));
            worst = worst.max(rel(md.fiber_length, mc.fiber_length));
            assert_eq!(rd.joints[0].position, theta);
            assert_eq!(rd.joints[0].velocity, 0.0);
            // The net torque on the joint is the moment arm times the clamped tendon force.
            assert!(rel(rd.joints[0].torque, 0.03 * mc.force) <= 1e-12);
        }
        let peak = c.records().map(|r| r.muscles[0].force).fold(0.0, f64::max);
        println!(
            "{model}: driven vs clamped worst relative difference {worst:.2e} (peak {peak:.1} N)"
        );
        assert!(peak > 1000.0, "{model}: the pulse should load the muscle");
        assert!(worst <= 1e-9, "{model}: worst relative difference {worst}");
    }
}

/// A driven joint fed each tick with a free run's own angle and velocity at the tick's start
/// reproduces the free run's muscles. Within a tick the driven angle is θ0 + ω0 t where the free
/// joint moved θ0 + ω0 t + α t²/2 + ..., so the difference is the tendon's stretch by
/// r α dt²/2 at most, restarted every tick: second order in dt. Checked: the worst force
/// difference is a small fraction of the peak, and falls about 4× when dt halves.
#[test]
fn driven_by_a_free_runs_motion_reproduces_it() {
    for model in MODELS {
        let mut worst = Vec::new();
        for rate in [1000.0, 2000.0] {
            let mut free = Actuator::new(&elbow(false), model, rate).unwrap();
            let mut driven = Actuator::new(&elbow(true), model, rate).unwrap();
            let (mut diff, mut peak) = (0.0f64, 0.0f64);
            for k in 0..(0.4 * rate) as usize {
                let t = k as f64 / rate;
                let (u_flexor, u_extensor) = if t < 0.2 { (0.3, 0.0) } else { (0.3, 0.4) };
                for a in [&mut free, &mut driven] {
                    a.set_excitation(0, u_flexor);
                    a.set_excitation(1, u_extensor);
                }
                let j = free.joints()[0];
                assert!(driven.set_joint_motion(0, j.position, j.velocity));
                free.step().unwrap();
                driven.step().unwrap();
                for (mf, md) in free.muscles().iter().zip(driven.muscles()) {
                    diff = diff.max((mf.force - md.force).abs());
                    peak = peak.max(mf.force.abs());
                }
            }
            let moved = free.joints()[0].position;
            println!("{model} at {rate} Hz: worst force difference {diff:.3e} N of peak {peak:.1} N; joint at {moved:.3} rad");
            assert!(moved.abs() > 0.05, "{model}: the free joint should move");
            assert!(
                diff <= 1e-2 * peak,
                "{model} at {rate} Hz: {diff} N of {peak} N"
            );
            worst.push(diff);
        }
        let ratio = worst[0] / worst[1];
        println!("{model}: halving dt divides the difference by {ratio:.2}");
        assert!(ratio > 3.0, "{model}: second order expected, ratio {ratio}");
    }
}

/// The work the driven motion does on the muscles, ∫ -τ ω dt with τ the muscles' net torque,
/// equals the change of their strain and kinetic energy plus what their dampers dissipate
/// (passive muscles: no contractile work). The motion is continuous: each tick starts where the
/// last one's extrapolation ended, with velocity A w cos(w t).
#[test]
fn driven_motion_work_balances_muscle_energy() {
    const RATE: f64 = 20_000.0;
    for model in MODELS {
        let cfg = elbow(true);
        let b_m = cfg.muscles[0].params.b_m;
        let mut act = Actuator::new(&cfg, model, RATE).unwrap();
        let energy = |a: &Actuator| -> f64 {
            a.muscles()
                .iter()
                .map(|m| m.tendon_energy + m.fiber_energy + m.crossbridge_energy)
                .sum::<f64>()
                + a.simulation().kinetic_energy()
        };
        let damper = |a: &Actuator| -> f64 {
            a.muscles()
                .iter()
                .map(|m| b_m * m.fiber_velocity.powi(2))
                .sum::<f64>()
        };
        let e0 = energy(&act);
        let (amplitude, w) = (0.4, 2.0 * std::f64::consts::PI * 3.0);
        let (mut work, mut dissipated) = (0.0, 0.0);
        let mut theta = act.joints()[0].position;
        let (mut tau_prev, mut p_prev) = (act.joints()[0].torque, damper(&act));
        for k in 0..(0.5 * RATE) as usize {
            let omega = amplitude * w * (w * k as f64 / RATE).cos();
            assert!(act.set_joint_motion(0, theta, omega));
            act.step().unwrap();
            let j = act.joints()[0];
            assert_eq!(j.position, theta + omega * (1.0 / RATE));
            theta = j.position;
            let tau = j.torque;
            work += -0.5 * (tau_prev + tau) * omega / RATE;
            let p = damper(&act);
            dissipated += 0.5 * (p_prev + p) / RATE;
            (tau_prev, p_prev) = (tau, p);
            assert_eq!(act.joint_efforts().collect::<Vec<_>>(), vec![tau]);
        }
        let stored = energy(&act) - e0;
        let residual = work - stored - dissipated;
        println!("{model}: work {work:.6e} J = stored {stored:.6e} + dissipated {dissipated:.6e} (residual {residual:.2e})");
        assert!(
            work.abs() > 1e-3,
            "{model}: the motion should do work ({work} J)"
        );
        assert!(
            residual.abs() <= 1e-3 * (work.abs() + stored.abs() + dissipated),
            "{model}: residual {residual} J"
        );
    }
}

/// Shoulder driven and held, elbow free, a biarticular muscle over both: the elbow moves as in
/// a limb without the shoulder where the biarticular path is shortened by r_shoulder θ_shoulder
/// (and the shoulder's own muscle is a clamped muscle apart). The shoulder starts there too
/// (`initial_angle`), so both limbs start from the same rest.
#[test]
fn biarticular_muscle_over_a_driven_and_a_free_joint() {
    let theta_s = 0.3;
    let with = config(
        "[[joint]]\nname = \"shoulder\"\ndriven = true\ninitial_angle = 0.3\n[[joint]]\nname = \"elbow\"\n\
         [[muscle]]\nname = \"deltoid\"\nspan = [{ joint = \"shoulder\", moment_arm = 0.02 }]\n\
         [[muscle]]\nname = \"biceps\"\npath_length = 0.42\nspan = [{ joint = \"shoulder\", moment_arm = 0.02 }, { joint = \"elbow\", moment_arm = 0.03 }]\n\
         [[muscle]]\nname = \"triceps\"\nspan = [{ joint = \"elbow\", moment_arm = -0.03 }]\n",
    );
    let without = config(&format!(
        "[[joint]]\nname = \"elbow\"\n\
         [[muscle]]\nname = \"biceps\"\npath_length = {}\nspan = [{{ joint = \"elbow\", moment_arm = 0.03 }}]\n\
         [[muscle]]\nname = \"triceps\"\nspan = [{{ joint = \"elbow\", moment_arm = -0.03 }}]\n",
        0.42 - 0.02 * theta_s
    ));
    for model in MODELS {
        let mut a = Actuator::new(&with, model, 1000.0).unwrap();
        let mut b = Actuator::new(&without, model, 1000.0).unwrap();
        assert_eq!(a.driven_joints(), &[0]);
        assert_eq!(
            a.simulation().part_count(),
            2,
            "the deltoid alone is a part"
        );
        assert!(!a.set_joint_motion(1, 0.0, 0.0), "the elbow is not driven");
        assert!(!a.set_joint_motion(0, f64::NAN, 0.0));
        let mut worst = 0.0f64;
        for k in 0..300 {
            assert!(a.set_joint_motion(0, theta_s, 0.0));
            let u = if k < 150 { 0.15 } else { 0.05 };
            a.set_excitation(1, u);
            b.set_excitation(0, u);
            a.step().unwrap();
            b.step().unwrap();
            worst = worst.max(rel(a.joints()[1].position, b.joints()[0].position));
            worst = worst.max(rel(a.muscles()[1].force, b.muscles()[0].force));
            assert_eq!(a.joints()[0].position, theta_s);
        }
        let elbow = a.joints()[1].position;
        println!("{model}: elbow at {elbow:.4} rad, worst relative difference {worst:.2e}");
        assert!(elbow > 0.05, "{model}: the biceps should flex the elbow");
        assert!(worst <= 1e-9, "{model}: {worst}");
        // What the simulator applies to the shoulder: the deltoid and the biceps' moments.
        let m = a.muscles();
        let effort: Vec<f64> = a.joint_efforts().collect();
        assert!(rel(effort[0], 0.02 * m[0].force + 0.02 * m[1].force) <= 1e-12);
    }
}

/// A motion set once carries on linearly: the same run as setting, each tick, the angle where
/// the last tick ended, bit for bit; the angle after n ticks is θ0 + n ω0 Δt to rounding.
#[test]
fn motion_set_once_carries_on_linearly() {
    let (rate, theta0, omega0) = (1000.0, 0.1, -0.8);
    let mut once = Actuator::new(&elbow(true), ModelKind::HILL, rate).unwrap();
    let mut each = Actuator::new(&elbow(true), ModelKind::HILL, rate).unwrap();
    assert!(once.set_joint_motion(0, theta0, omega0));
    let mut theta = theta0;
    for _ in 0..200 {
        once.set_excitation(0, 0.3);
        each.set_excitation(0, 0.3);
        assert!(each.set_joint_motion(0, theta, omega0));
        once.step().unwrap();
        each.step().unwrap();
        theta = each.joints()[0].position;
        assert_eq!(once.state(), each.state());
    }
    let want = theta0 + 200.0 * omega0 / rate;
    assert!((theta - want).abs() < 1e-12, "{theta} vs {want}");
    assert_eq!(once.joints()[0].velocity, omega0);
}

/// A schedule's velocity is its derivative: against central differences.
#[test]
fn schedule_slopes_are_derivatives() {
    let kinds = [
        Schedule::Sine {
            offset: 0.1,
            amplitude: 0.5,
            frequency: 1.7,
            phase: 0.3,
        },
        Schedule::Ramp {
            start: 0.1,
            end: 0.6,
            from: -0.2,
            to: 0.4,
        },
        Schedule::Piecewise {
            points: vec![[0.0, 0.0], [0.3, 0.5], [0.7, -0.1]],
        },
        Schedule::Constant { value: 2.0 },
    ];
    for s in kinds {
        for t in [0.05, 0.2, 0.45, 0.65, 0.9] {
            let h = 1e-6;
            let numeric = (s.value(t + h) - s.value(t - h)) / (2.0 * h);
            assert!(
                (s.slope(t) - numeric).abs() <= 1e-6 * (1.0 + numeric.abs()),
                "{s:?} at {t}: {} vs {numeric}",
                s.slope(t)
            );
        }
    }
}

#[test]
fn driven_must_be_a_boolean() {
    let err = ActuatorConfig::from_toml_str(
        "[[joint]]\nname = \"elbow\"\ndriven = \"yes\"\n\
         [[muscle]]\nname = \"flexor\"\nspan = [{ joint = \"elbow\", moment_arm = 0.03 }]\n",
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("driven") || err.contains("boolean"), "{err}");
    assert!(err.contains("boolean"), "{err}");
}

#[test]
fn driven_scenario_names_must_exist_and_fit() {
    let cfg = ActuatorConfig::default();
    let angle = |joint: &str| {
        input(
            Signal::JointAngle,
            None,
            Some(joint),
            Schedule::Constant { value: 0.1 },
        )
    };
    let err = scenario(SetupKind::Driven, None, vec![angle("knee")])
        .run(
            &cfg,
            ModelKind::HILL,
            1000.0,
            default_stepping(ModelKind::HILL),
        )
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("unknown joint \"knee\"") && err.contains("elbow"),
        "{err}"
    );
    // A configuration's driven joint under attachment "joint": it has no motion.
    let err = scenario(SetupKind::Joint, None, vec![])
        .run(
            &elbow(true),
            ModelKind::HILL,
            1000.0,
            default_stepping(ModelKind::HILL),
        )
        .unwrap_err()
        .to_string();
    assert!(err.contains("\"elbow\" is driven"), "{err}");
    // An external torque on a driven joint would do nothing.
    let torque = input(
        Signal::ExternalTorque,
        None,
        Some("elbow"),
        Schedule::Constant { value: 1.0 },
    );
    let err = scenario(SetupKind::Driven, None, vec![angle("elbow"), torque])
        .run(
            &cfg,
            ModelKind::HILL,
            1000.0,
            default_stepping(ModelKind::HILL),
        )
        .unwrap_err()
        .to_string();
    assert!(err.contains("no effect"), "{err}");
    // joint_angle belongs to attachment "driven" only (checked when the file is read).
    let dir = temp_dir("driven");
    let path = dir.join("joint_angle_on_joint.toml");
    std::fs::write(
        &path,
        "duration = 0.1\nattachment = \"joint\"\n[[input]]\nsignal = \"joint_angle\"\nkind = \"constant\"\nvalue = 0.1\n",
    )
    .unwrap();
    let err = Scenario::from_file(&path).unwrap_err().to_string();
    assert!(err.contains("JointAngle") && err.contains("Joint"), "{err}");
}

/// The example scenario runs from the command line (CSV); its recording says `driven`, holds
/// the motion as applied at every tick and the motion it started from, and `replay` reproduces
/// every state bit for bit, for either model.
#[test]
fn driven_example_simulates_and_replays_bit_for_bit() {
    let dir = temp_dir("driven_cli");
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/driven_elbow.toml");
    let csv = dir.join("driven.csv");
    run_ok(
        bin()
            .args(["simulate", example, "--model", "hill", "--csv"])
            .arg(&csv),
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let (header, rows) = read_csv(&text);
    let pos = header.iter().position(|h| h == "elbow.position").unwrap();
    // Row of tick 250 (two muscles per tick): θ = 0.1 + 0.5 sin(2π 0.249) plus one tick of the
    // schedule's slope there.
    let row = &rows[2 * 250];
    let w = 2.0 * std::f64::consts::PI;
    let want = 0.1 + 0.5 * (w * 0.249).sin() + 0.5 * w * (w * 0.249).cos() * 1e-3;
    let got: f64 = row[pos].parse().unwrap();
    assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    for model in ["hill", "huxley"] {
        let mcap = dir.join(format!("driven_{model}.mcap"));
        run_ok(
            bin()
                .args(["simulate", example, "--model", model, "--out"])
                .arg(&mcap),
        );
        let run = muscle_actuator_recording::runs::load_run(&mcap).unwrap();
        assert_eq!(
            run.meta.attachment,
            muscle_actuator_recording::runs::AttachmentMeta::Driven
        );
        assert!(run.meta.config.joints[0].driven);
        // The sine starts at 0.1 rad moving at 0.5 · 2π rad/s: not the configuration's initial
        // angle at rest, so a replay that ignored it would differ from tick 0.
        assert_eq!(run.meta.initial_joint_motion, vec![(0.1, 0.5 * w)]);
        // 1000 ticks, each with the motion it applied.
        assert_eq!(run.joint_motions.len(), 1000);
        let (t, names, angles, _) = &run.joint_motions[250];
        assert_eq!(
            (*t, names.as_slice()),
            (250, ["elbow".to_string()].as_slice())
        );
        assert!((angles[0] - (0.1 + 0.5 * (w * 0.25).sin())).abs() < 1e-12);
        let again = dir.join(format!("again_{model}.mcap"));
        let s = muscle_actuator_recording::runs::replay(&mcap, None, &again).unwrap();
        assert_eq!((s.ticks, s.compared), (1000, 1001), "{s:?}");
        assert_eq!(s.identical, s.compared, "{s:?}");
        // The replay's own recording replays bit for bit too.
        let s2 =
            muscle_actuator_recording::runs::replay(&again, None, &dir.join("third.mcap")).unwrap();
        assert_eq!(s2.identical, 1001, "{s2:?}");
    }
}
