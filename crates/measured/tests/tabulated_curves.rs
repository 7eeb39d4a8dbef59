//! `curves = "tabulated"` (docs/model.md §4b, docs/configuration.md "Curve sets"): a muscle whose
//! curves are its own points behaves as the curves it was sampled from (DeGroote 2016's, finely
//! sampled: the same isometric states and the same run on an equilibrium fibre), settles where
//! the CEINMS subject's own curves balance, and bad tables are refused on one line each.

// The engine's configuration fixtures, shared rather than copied.
#[path = "../../core/tests/common/fixtures.rs"]
mod fixtures;

use fixtures::{clamped, refusal};
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::curves::{Curve, CurveSet, TabulatedCurve};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{FibreKind, MuscleParams, Points, TabulatedCurves};
use muscle_actuator_core::sim::{default_stepping, Scenario, Schedule, ScheduledInput, Signal};
use muscle_actuator_measured::measured::Subject;
use std::path::PathBuf;

/// `f` at `n` points evenly over [a, b].
fn sampled(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> Points {
    (0..n)
        .map(|i| {
            let x = a + (b - a) * i as f64 / (n - 1) as f64;
            [x, f(x)]
        })
        .collect()
}

/// DeGroote 2016's default curves as points, 601 a curve.
fn degroote_points() -> TabulatedCurves {
    let dgf = |c: Curve, x: f64| CurveSet::DeGroote2016.evaluate(c, x).unwrap();
    TabulatedCurves {
        active_force_length: sampled(|x| dgf(Curve::ActiveForceLength, x), 0.2, 1.9, 601),
        passive_force_length: sampled(|x| dgf(Curve::PassiveForceLength, x), 0.2, 1.9, 601),
        force_velocity: sampled(|x| dgf(Curve::ForceVelocity, x), -1.5, 1.5, 601),
        tendon_force_strain: sampled(|e| dgf(Curve::TendonForceLength, 1.0 + e), -0.05, 0.1, 601),
    }
}

/// (force, fibre length) of the first muscle after a clamped run.
fn settle(cfg: &ActuatorConfig, model: ModelKind, u: f64, length: f64) -> (f64, f64) {
    let sc = clamped(u, length, 2.0);
    let mut runner = sc
        .runner(cfg, model, 1000.0, default_stepping(model))
        .unwrap();
    for _ in 0..2000 {
        runner.step().unwrap();
    }
    let m = runner.record().muscles[0];
    (m.force, m.fiber_length)
}

/// Sampled finely, DeGroote's curves give DeGroote's muscle: the clamped unit's steady force and
/// fibre length within 1e-6 (the spline's interpolation error), Hill and DM.
#[test]
fn degroote_sampled_is_degroote() {
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        for u in [0.3, 1.0] {
            let mut dgf = ActuatorConfig::default();
            dgf.muscles[0].params.curves = CurveSet::DeGroote2016;
            let mut tab = ActuatorConfig::default();
            tab.muscles[0].params.curves = CurveSet::Tabulated;
            tab.muscles[0].params.tabulated = Some(degroote_points());
            let p = &dgf.muscles[0].params;
            let length = p.l_opt + p.l_ts + 0.005;
            let (f_d, l_d) = settle(&dgf, model, u, length);
            let (f_t, l_t) = settle(&tab, model, u, length);
            let (ef, el) = ((f_t - f_d).abs() / f_d, (l_t - l_d).abs() / l_d);
            println!(
                "{model} u = {u}: force {f_t:.6} N against {f_d:.6} N ({ef:.1e}), l_m {el:.1e}"
            );
            assert!(ef < 1e-6 && el < 1e-6, "{model} u = {u}: {ef:e} {el:e}");
        }
    }
}

/// On an equilibrium fibre (its velocity from the force–velocity points' inverse) under a
/// swinging excitation, the tabulated muscle's tendon force follows DeGroote's within 1e-7 Fmax.
#[test]
fn an_equilibrium_fibre_on_sampled_curves_moves_as_on_the_curves() {
    let sc = Scenario {
        inputs: vec![ScheduledInput {
            signal: Signal::Excitation,
            muscle: None,
            joint: None,
            schedule: Schedule::Sine {
                offset: 0.5,
                amplitude: 0.4,
                frequency: 2.0,
                phase: 0.0,
            },
        }],
        ..clamped(0.0, 0.0959 + 0.3185 + 0.004, 1.0)
    };
    let run = |tabulated: bool| {
        let mut cfg = ActuatorConfig::default();
        let p = &mut cfg.muscles[0].params;
        p.fibre = FibreKind::Equilibrium;
        if tabulated {
            (p.curves, p.tabulated) = (CurveSet::Tabulated, Some(degroote_points()));
        } else {
            p.curves = CurveSet::DeGroote2016;
        }
        let model = ModelKind::HILL;
        let run = sc
            .run(&cfg, model, 1000.0, default_stepping(model))
            .unwrap();
        run.records()
            .map(|r| r.muscles[0].force)
            .collect::<Vec<_>>()
    };
    let (dgf, tab) = (run(false), run(true));
    let f_max = MuscleParams::default().f_max;
    let worst = dgf
        .iter()
        .zip(&tab)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let peak = dgf.iter().fold(0.0f64, |m, f| m.max(*f));
    println!("worst tendon-force difference {worst:.3e} N (peak {peak:.1} N)");
    assert!(peak > 0.3 * f_max, "the run must load the tendon: {peak}");
    assert!(worst < 1e-7 * f_max, "{worst}");
}

/// The CEINMS subject's own curves (data/ceinms): a clamped Hill unit settles where its tendon
/// carries `Fmax (a f_L + f_PE)` on those curves, found by bisection on the curves themselves.
#[test]
fn the_subjects_curves_balance_where_they_say() {
    let root = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let subject = Subject::read(&root.join("data/ceinms/uncalibratedSubject.xml")).unwrap();
    let c = &subject.defaults.curves;
    let table = TabulatedCurves {
        active_force_length: c.active_force_length.points(),
        passive_force_length: c.passive_force_length.points(),
        force_velocity: c.force_velocity.points(),
        tendon_force_strain: c.tendon_force_strain.as_ref().unwrap().points(),
    };
    let curve = |p: &Points| {
        let (x, y): (Vec<f64>, Vec<f64>) = p.iter().map(|&[x, y]| (x, y)).unzip();
        TabulatedCurve::new(&x, &y).unwrap()
    };
    let (f_t, f_l, f_pe) = (
        curve(&table.tendon_force_strain),
        curve(&table.active_force_length),
        curve(&table.passive_force_length),
    );
    let mut cfg = ActuatorConfig::default();
    let p = &mut cfg.muscles[0].params;
    (p.curves, p.tabulated) = (CurveSet::Tabulated, Some(table.clone()));
    let p = p.clone();
    // The subject's tendon is stiff (force 1 at a strain near 0.033): stretch it by 2 mm.
    let length = p.l_opt + p.l_ts + 0.002;
    for u in [0.2, 0.8] {
        let residual = |l_m: f64| {
            let x = l_m / p.l_opt;
            f_t.value((length - l_m) / p.l_ts - 1.0) - (u * f_l.value(x) + f_pe.value(x))
        };
        let (mut lo, mut hi) = (0.8 * p.l_opt, 1.2 * p.l_opt);
        assert!(residual(lo) > 0.0 && residual(hi) < 0.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if residual(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let want = 0.5 * (lo + hi);
        let want_force = p.f_max * f_t.value((length - want) / p.l_ts - 1.0);
        let (force, l_m) = settle(&cfg, ModelKind::HILL, u, length);
        println!(
            "u = {u}: l_m {l_m:.9} m (bisection {want:.9}), force {force:.4} N ({want_force:.4})"
        );
        assert!((l_m - want).abs() < 1e-6 * want, "{l_m} vs {want}");
        assert!((force - want_force).abs() < 1e-6 * want_force.abs().max(1.0));
    }
}

const GOOD: &str = "active_force_length = [[0.5, 0.0], [1.0, 1.0], [1.5, 0.0]]\n\
                    passive_force_length = [[1.0, 0.0], [1.6, 1.0]]\n\
                    force_velocity = [[-1.0, 0.0], [0.0, 1.0], [1.0, 1.5]]\n";

/// Each bad table is refused on one line naming the curve and the rule; a good one reads back
/// as written.
#[test]
fn bad_tables_are_refused_on_one_line() {
    let table = |tendon: &str| {
        format!(
            "curves = \"tabulated\"\n[muscle.tabulated]\n{GOOD}tendon_force_strain = {tendon}\n"
        )
    };
    let cases: Vec<(String, Vec<&str>)> = vec![
        (
            "curves = \"tabulated\"".into(),
            vec!["muscle.flexor.tabulated", "is needed"],
        ),
        (
            format!("[muscle.tabulated]\n{GOOD}tendon_force_strain = [[0.0, 0.0], [0.05, 1.0]]\n"),
            vec!["muscle.flexor.tabulated", "curves = \"tabulated\" only"],
        ),
        (
            table("[[0.0, 0.0], [0.0, 1.0]]"),
            vec![
                "muscle.flexor.tabulated.tendon_force_strain",
                "must rise from point to point",
            ],
        ),
        (
            table("[[0.0, 1.0], [0.05, 0.5]]"),
            vec![
                "muscle.flexor.tabulated.tendon_force_strain",
                "must rise somewhere",
            ],
        ),
        (
            table("[[0.0, 0.0]]"),
            vec![
                "muscle.flexor.tabulated.tendon_force_strain",
                "at least 2 points",
            ],
        ),
        (
            format!(
                "tendon_strain = 0.05\n{}",
                table("[[0.0, 0.0], [0.05, 1.0]]")
            ),
            vec!["muscle.flexor.tendon_strain", "tabulated"],
        ),
    ];
    for (keys, needles) in &cases {
        let message = refusal(keys);
        println!("{keys:?}: {message}");
        assert_eq!(message.lines().count(), 1, "{keys}: {message}");
        for n in needles {
            assert!(message.contains(n), "{keys}: {message:?} lacks {n:?}");
        }
    }
    let mut cfg = ActuatorConfig::default();
    let p = &mut cfg.muscles[0].params;
    (p.curves, p.tabulated) = (CurveSet::Tabulated, Some(degroote_points()));
    let back = ActuatorConfig::from_toml_str(&toml::to_string(&cfg).unwrap()).unwrap();
    assert_eq!(back, cfg);
    assert!(!toml::to_string(&ActuatorConfig::default())
        .unwrap()
        .contains("tabulated"));
}

/// CEINMS's two readings of a unit's curves (docs/model.md §4b): a tendon strain below 0 is read
/// as 0 (no push, no stiffness, whatever the spline does in the padding: −1.22 Fmax at strain
/// −5 on the subject's points), and the force–velocity curve at ṽ within [−1, 1] (flat beyond, so
/// the equilibrium balance never falls as v rises; the spline's bulge to 2.7 at ṽ = −7 unread).
#[test]
fn a_slack_tendon_pushes_nothing_and_the_force_velocity_curve_ends_at_vmax() {
    use muscle_actuator_core::physics::curves::HillForceVelocity;
    use muscle_actuator_core::physics::Tendon;
    let root = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let subject = Subject::read(&root.join("data/ceinms/uncalibratedSubject.xml")).unwrap();
    let model = muscle_actuator_measured::subject::SubjectModel::of_ceinms(&subject).unwrap();
    let p = &model.units[0].params;
    let tendon = Tendon::new(p);
    let points = &p.tabulated.as_ref().unwrap().tendon_force_strain;
    let (x, y): (Vec<f64>, Vec<f64>) = points.iter().map(|&[x, y]| (x, y)).unzip();
    let spline = TabulatedCurve::new(&x, &y).unwrap();
    assert!(
        spline.value(-5.0) < -1.0,
        "the padding's dip: {}",
        spline.value(-5.0)
    );
    for strain in [-5.0, -0.5, -0.01, -1e-9] {
        let l = p.l_ts * (1.0 + strain);
        assert_eq!(tendon.force(l), 0.0, "strain {strain}");
        assert_eq!(tendon.stiffness(l), 0.0);
        assert_eq!(tendon.energy(l), 0.0);
    }
    let l = p.l_ts * 1.01;
    let f = p.f_max * spline.value(l / p.l_ts - 1.0);
    assert!((tendon.force(l) - f).abs() <= 1e-12 * f);
    let fv = HillForceVelocity::new(p);
    let v_max = fv.v_max();
    for (beyond, end) in [(-7.084, -1.0), (-3.0, -1.0), (1.5, 1.0), (9.0, 1.0)] {
        assert_eq!(fv.at(beyond * v_max, 1.0), fv.at(end * v_max, 1.0));
        assert_eq!(fv.slope(beyond * v_max, 1.0), 0.0);
    }
    // The balance rises with v everywhere: a damper and a curve that never falls.
    let mut last = f64::NEG_INFINITY;
    for k in -400..=400 {
        let v = k as f64 * 0.01 * v_max;
        let f = 500.0 * fv.at(v, 1.0) + p.b_m * v;
        assert!(f > last, "falls at v = {v}");
        last = f;
    }
}
