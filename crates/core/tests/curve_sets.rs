//! A muscle's curve set (docs/model.md §4b, docs/configuration.md `curves`): the OpenSim sets'
//! tendon, parallel element, overlap and Hill force–velocity inside a muscle–tendon unit, checked
//! against the normalised curves themselves: the isometric steady state of a clamped unit against
//! an independent bisection on the curves, stiffness and energy against differences of force, and
//! the configuration's refusals.

mod common;

use common::fixtures::{clamped, refusal};
use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::curves::{
    degroote2016 as dgf, thelen2003, Curve as Named, CurveSet,
};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{passive_strain, tendon_strain, Mtu, MuscleParams, TendonEnd};
use muscle_actuator_core::sim::{default_stepping, EnergeticsOutputs, Scenario, SetupKind};

const OPENSIM_SETS: [CurveSet; 3] = [
    CurveSet::DeGroote2016,
    CurveSet::Thelen2003,
    CurveSet::Millard2012,
];

fn params(curves: CurveSet) -> MuscleParams {
    let mut p = MuscleParams::default();
    p.curves = curves;
    p
}

/// One normalised curve.
type Curve = fn(f64) -> f64;

/// The set's normalised curves with its default constants: (f_T(l̃_T), f_L(l̃), f_PE(l̃)),
/// written from the curve functions, not from the unit.
fn curves(set: CurveSet) -> (Curve, Curve, Curve) {
    match set {
        CurveSet::DeGroote2016 => (
            |x| dgf::tendon_force_length(x, dgf::tendon_shape(0.049)),
            |x| dgf::active_force_length(x, 1.0),
            |x| dgf::passive_force_length(x, 0.6),
        ),
        CurveSet::Thelen2003 => (
            |x| thelen2003::tendon_force_length(x, 0.04),
            |x| thelen2003::active_force_length(x, 0.45),
            |x| thelen2003::passive_force_length(x, 0.6, 5.0),
        ),
        // Millard's curves are built per call from their corners (docs/model.md §4b).
        CurveSet::Millard2012 => (
            |x| millard(Named::TendonForceLength, x),
            |x| millard(Named::ActiveForceLength, x),
            |x| millard(Named::PassiveForceLength, x),
        ),
        CurveSet::Paper | CurveSet::Tabulated => {
            unreachable!("the paper's springs are not normalised; tabulated curves are a muscle's")
        }
    }
}

fn millard(curve: Named, x: f64) -> f64 {
    CurveSet::Millard2012.evaluate(curve, x).unwrap()
}

/// The fibre length where `f_T((L - l_m)/l_ts) = a f_L(l_m/l_opt) + f_PE(l_m/l_opt)`, by
/// bisection between 0.3 l_opt and 1.7 l_opt.
fn isometric_fibre_length(set: CurveSet, p: &MuscleParams, length: f64, a: f64) -> f64 {
    let (f_t, f_l, f_pe) = curves(set);
    let residual = |l_m: f64| {
        let x = l_m / p.l_opt;
        f_t((length - l_m) / p.l_ts) - (a * f_l(x) + f_pe(x))
    };
    let (mut lo, mut hi) = (0.3 * p.l_opt, 1.7 * p.l_opt);
    assert!(residual(lo) > 0.0 && residual(hi) < 0.0);
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

/// Relative error allowed on the steady fibre length and tendon force.
const STEADY_REL_TOL: f64 = 1e-6;

/// A unit clamped at `l_opt + l_ts + 5 mm` under constant excitation settles, after 3 s, at the
/// fibre length where the set's tendon carries the active and passive force: Hill with its
/// `Fmax a f_L f_V`, the DM model with its calibrated `Fmax Q1/Q1_iso = Fmax a λ`.
#[test]
fn a_clamped_unit_settles_where_the_sets_curves_balance() {
    for set in OPENSIM_SETS {
        for model in [ModelKind::HILL, ModelKind::HUXLEY] {
            for u in [0.3, 1.0] {
                let mut cfg = ActuatorConfig::default();
                cfg.muscles[0].params.curves = set;
                let p = cfg.muscles[0].params.clone();
                let length = p.l_opt + p.l_ts + 0.005;
                let sc = clamped(u, length, 3.0);
                let rate = 1000.0;
                let mut runner = sc
                    .runner(&cfg, model, rate, default_stepping(model))
                    .unwrap();
                for _ in 0..(sc.duration * rate) as usize {
                    runner.step().unwrap();
                }
                let m = runner.record().muscles[0];
                let want = isometric_fibre_length(set, &p, length, u);
                let (f_t, _, _) = curves(set);
                let want_force = p.f_max * f_t((length - want) / p.l_ts);
                let err_l = (m.fiber_length - want).abs() / want;
                let err_f = (m.force - want_force).abs() / want_force;
                println!(
                    "{set} {model} u = {u}: l_m {:.9} m (bisection {want:.9}, rel. error {err_l:.1e}), \
                     force {:.6} N ({want_force:.6}, rel. error {err_f:.1e})",
                    m.fiber_length, m.force
                );
                assert!(
                    err_l < STEADY_REL_TOL && err_f < STEADY_REL_TOL,
                    "{set} {model} u = {u}: l_m {} vs {want}, F {} vs {want_force}",
                    m.fiber_length,
                    m.force
                );
                assert!(m.fiber_velocity.abs() < 1e-9, "{set} {model}: still moving");
            }
        }
    }
}

fn central_difference(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    (f(x + h) - f(x - h)) / (2.0 * h)
}

/// Within `rel` of `want` relative to `max(|want|, scale)`.
fn close(got: f64, want: f64, scale: f64, rel: f64) -> bool {
    (got - want).abs() <= rel * want.abs().max(scale)
}

/// The sets with their default strains and with configured ones.
fn element_cases() -> Vec<MuscleParams> {
    let mut cases = Vec::new();
    for set in OPENSIM_SETS {
        cases.push(params(set));
        let mut p = params(set);
        (p.tendon_strain, p.passive_strain) = (Some(0.07), Some(0.45));
        cases.push(p);
    }
    cases
}

/// Tendon and parallel element: stiffness is the central difference of force, the energy's
/// central difference is the force, the force at `length_at_force` is the force asked for; the
/// overlap's slope is its difference; the strains do what they say.
#[test]
fn elements_stiffness_and_energy_are_consistent_with_force() {
    for p in element_cases() {
        let mtu = Mtu::new(&p, ModelKind::HILL).unwrap();
        let (t, pe) = (&mtu.tendon, &mtu.parallel);
        let set = p.curves;
        let f = p.f_max;
        for i in 0..=60 {
            // Off the kinks of Thelen's curves at slack and optimal length.
            let x = (i as f64 + 0.37) / 60.0;
            let l_t = p.l_ts * (0.97 + 0.12 * x);
            let h = 1e-7 * p.l_ts;
            let k = t.stiffness(l_t);
            assert!(
                close(
                    k,
                    central_difference(|x| t.force(x), l_t, h),
                    f / p.l_ts,
                    1e-6
                ),
                "{set} tendon stiffness at {l_t}"
            );
            let force = t.force(l_t);
            assert!(
                close(central_difference(|x| t.energy(x), l_t, h), force, f, 1e-7),
                "{set} tendon energy' at {l_t}: {} vs {force}",
                central_difference(|x| t.energy(x), l_t, h)
            );
            assert!(t.energy(l_t) >= 0.0, "{set} tendon energy at {l_t}");
            if force > 0.0 {
                assert!(close(t.length_at_force(force), l_t, p.l_ts, 1e-12), "{set}");
            }
            let l_m = p.l_opt * (0.25 + 1.5 * x);
            let h = 1e-7 * p.l_opt;
            let k = pe.stiffness(l_m);
            assert!(
                close(
                    k,
                    central_difference(|x| pe.force(x), l_m, h),
                    f / p.l_opt,
                    1e-6
                ),
                "{set} parallel stiffness at {l_m}"
            );
            let force = pe.force(l_m);
            assert!(
                close(central_difference(|x| pe.energy(x), l_m, h), force, f, 1e-7),
                "{set} parallel energy' at {l_m}"
            );
            assert!(pe.energy(l_m) >= 0.0, "{set} parallel energy at {l_m}");
            if force > 0.0 {
                assert!(
                    close(pe.length_at_force(force), l_m, p.l_opt, 1e-12),
                    "{set}"
                );
            }
            let slope = central_difference(|x| mtu.overlap(x), l_m, h);
            assert!(
                close(mtu.overlap_slope(l_m), slope, 1.0 / p.l_opt, 1e-6),
                "{set} overlap slope at {l_m}"
            );
        }
        // The strains are those at Fmax: tendon and parallel force Fmax there.
        let (e_t, e_p) = (tendon_strain(&p), passive_strain(&p));
        assert!(close(t.force(p.l_ts * (1.0 + e_t)), f, f, 1e-12), "{set}");
        assert!(close(pe.force(p.l_opt * (1.0 + e_p)), f, f, 1e-12), "{set}");
        // A slack force-driven tendon rests at its slack length.
        assert_eq!(t.length_at_force(-1.0), p.l_ts);
    }
}

/// The overlap is the set's active force–length curve, and the Hill element's force is
/// `Fmax a f_L f_V(v/vmax)` with the set's force–velocity curve (Thelen's at the activation).
#[test]
fn the_hill_element_uses_the_sets_force_length_and_force_velocity() {
    for set in OPENSIM_SETS {
        let p = params(set);
        let mtu = Mtu::new(&p, ModelKind::HILL).unwrap();
        let (_, f_l, _) = curves(set);
        for (l, v, a) in [(0.9, -0.2, 1.0), (1.1, 0.1, 0.4), (1.0, -0.05, 0.7)] {
            let (l_m, v) = (l * p.l_opt, v * p.v_max);
            let f_v = match set {
                CurveSet::DeGroote2016 => dgf::force_velocity(v / p.v_max),
                CurveSet::Millard2012 => millard(Named::ForceVelocity, v / p.v_max),
                _ => thelen2003::force_velocity(v / p.v_max, a, &Default::default()),
            };
            assert_eq!(mtu.overlap(l_m), f_l(l));
            let end = TendonEnd::Path {
                length: l_m + p.l_ts,
                velocity: 0.0,
            };
            let out = mtu.outputs(a, a, &[l_m, v], end, &EnergeticsOutputs::default());
            let want = p.f_max * a * f_l(l) * f_v;
            assert!(
                close(out.ce_force, want, p.f_max, 1e-14),
                "{set} at {l}, {v}, {a}: {} vs {want}",
                out.ce_force
            );
        }
    }
}

/// The resting state balances the set's tendon and parallel element (DeGroote's parallel
/// element carries 1.8 % of Fmax at optimal length, so its tendon is stretched at rest).
#[test]
fn the_resting_fibre_balances_tendon_and_parallel_element() {
    for set in OPENSIM_SETS {
        let mut cfg = ActuatorConfig::default();
        cfg.muscles[0].params.curves = set;
        let p = cfg.muscles[0].params.clone();
        let length = p.l_opt + p.l_ts;
        let sc = Scenario {
            name: "rest".into(),
            duration: 0.1,
            attachment: SetupKind::Clamped,
            length: Some(length),
            initial_force: 0.0,
            inputs: vec![],
        };
        let mut runner = sc
            .runner(
                &cfg,
                ModelKind::HILL,
                1000.0,
                default_stepping(ModelKind::HILL),
            )
            .unwrap();
        let m = runner.record().muscles[0];
        assert!(
            close(m.force, m.pe_force, p.f_max, 1e-12),
            "{set}: tendon {} N, parallel {} N",
            m.force,
            m.pe_force
        );
        assert_eq!(
            m.force > 1.0,
            set == CurveSet::DeGroote2016,
            "{set}: {}",
            m.force
        );
    }
}

/// Bad values are refused, each on one line naming the parameter and the rule.
#[test]
fn bad_curve_settings_are_refused_on_one_line() {
    let cases: &[(&str, &[&str])] = &[
        (
            "curves = \"opensim\"",
            &["\"opensim\"", "paper, degroote2016, thelen2003"],
        ),
        (
            "tendon_strain = 0.05",
            &["muscle.flexor.tendon_strain", "OpenSim curve set", "k_te"],
        ),
        (
            "curves = \"paper\"\npassive_strain = 0.5",
            &["muscle.flexor.passive_strain", "OpenSim curve set", "k_me"],
        ),
        (
            "curves = \"degroote2016\"\ntendon_strain = 0.0",
            &["muscle.flexor.tendon_strain", "must be > 0"],
        ),
        (
            "curves = \"thelen2003\"\npassive_strain = -0.6",
            &["muscle.flexor.passive_strain", "must be > 0"],
        ),
        (
            "curves = \"millard2012\"\npassive_strain = 5.0",
            &["muscle.flexor.passive_strain", "< 5", "millard2012"],
        ),
        (
            "curves = \"thelen2003\"\ntendon_strain = nan",
            &["muscle.flexor.tendon_strain", "finite"],
        ),
        // Each set's shape constants: only with that set, within OpenSim's ranges.
        (
            "curves = \"thelen2003\"\nactive_force_width_scale = 1.5",
            &[
                "muscle.flexor.active_force_width_scale",
                "degroote2016\" only",
            ],
        ),
        (
            "curves = \"degroote2016\"\nactive_force_width_scale = 0.5",
            &["muscle.flexor.active_force_width_scale", "must be >= 1"],
        ),
        (
            "curves = \"degroote2016\"\nkshape_active = 0.5",
            &["muscle.flexor.kshape_active", "thelen2003\" only"],
        ),
        (
            "kshape_passive = 4.0",
            &["muscle.flexor.kshape_passive", "thelen2003\" only"],
        ),
        (
            "curves = \"thelen2003\"\naf = 0.0",
            &["muscle.flexor.af", "must be > 0"],
        ),
        (
            "curves = \"thelen2003\"\nflen = 1.0",
            &["muscle.flexor.flen", "must be > 1"],
        ),
    ];
    for (keys, needles) in cases {
        let message = refusal(keys);
        println!("{keys:?}: {message}");
        assert_eq!(message.lines().count(), 1, "{keys}: {message}");
        for n in *needles {
            assert!(message.contains(n), "{keys}: {message:?} lacks {n:?}");
        }
    }
}

/// The keys read back as written; at their defaults they are not written at all, so the
/// configurations that recordings and saved states carry are unchanged.
#[test]
fn curve_settings_round_trip_and_defaults_are_not_written() {
    let default = toml::to_string(&ActuatorConfig::default()).unwrap();
    for key in ["curves", "tendon_strain", "passive_strain"] {
        assert!(!default.contains(key), "{key} in\n{default}");
    }
    let text = "[[muscle]]\nname = \"flexor\"\ncurves = \"thelen2003\"\ntendon_strain = 0.05\n\
                [[muscle]]\nname = \"extensor\"\ncurves = \"degroote2016\"\n";
    let cfg = ActuatorConfig::from_toml_str(text).unwrap();
    let [flexor, extensor] = [&cfg.muscles[0].params, &cfg.muscles[1].params];
    assert_eq!(flexor.curves, CurveSet::Thelen2003);
    assert_eq!((tendon_strain(flexor), passive_strain(flexor)), (0.05, 0.6));
    assert_eq!(extensor.curves, CurveSet::DeGroote2016);
    assert_eq!(tendon_strain(extensor), 0.049);
    let written = toml::to_string(&cfg).unwrap();
    assert!(written.contains("curves = \"thelen2003\""), "{written}");
    assert!(!written.contains("passive_strain"), "{written}");
    let back = ActuatorConfig::from_toml_str(&written).unwrap();
    assert_eq!(back, cfg);
}
