//! The accuracy setting (docs/configuration.md, `[stepper]`): a tighter tolerance is closer to
//! the reference solver; absent, each model keeps its own stepping; the tolerance survives a
//! saved state. Its way through files, recordings and the command line: the node package's
//! tests/accuracy_setting.rs.

mod common;

use muscle_actuator_core::config::{with_overrides, ActuatorConfig};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{MuscleParams, Stepping, DEFAULT_MAX_SUBSTEPS};
use muscle_actuator_core::sim::{default_stepping, Actuator, Scenario};

/// The default elbow with `[stepper] tolerance = t` (None: no `[stepper]` table), set as the
/// override `stepper.tolerance`.
fn elbow_with(tolerance: Option<f64>) -> ActuatorConfig {
    let over: Vec<(String, toml::Value)> = tolerance
        .map(|t| ("stepper.tolerance".to_string(), toml::Value::Float(t)))
        .into_iter()
        .collect();
    with_overrides(&ActuatorConfig::default(), &over).unwrap()
}

/// Force within 1e-5 Fmax and fibre length within 1e-8 m of the reference: what 1e-7 meets on
/// the pulse and the default tolerances do not (their bounds are 1e-3 Fmax and 1e-6 m, model.md
/// §10).
const TIGHT_FORCE: f64 = 1e-5 * 3913.0;
const TIGHT_LENGTH: f64 = 1e-8;

/// On the pulse (activation's rise and fall: the transients), each model's worst deviations
/// from the Dop853 reference shrink as the tolerance tightens: 1e-3, the model's own, 1e-7;
/// and 1e-7 meets the tight bounds above, which the default does not.
#[test]
fn a_tighter_tolerance_is_closer_to_the_reference() {
    let sc = Scenario::built_in("pulse", &MuscleParams::default()).unwrap();
    for model in [ModelKind::HILL, ModelKind::HUXLEY] {
        let deviation = |tolerance: Option<f64>| {
            let cfg = elbow_with(tolerance);
            let stepping = cfg.stepping(model, None).unwrap();
            let (df, dl) =
                common::worst_deviation_from_reference(&sc, &cfg, model, 1000.0, stepping);
            let shown = tolerance.map_or("default".to_string(), |t| format!("{t:e}"));
            println!(
                "pulse {model}, tolerance {shown}: worst |dF| = {df:.3e} N, worst |dl_m| = \
                 {dl:.3e} m"
            );
            (df, dl)
        };
        let (loose, default, tight) = (
            deviation(Some(1e-3)),
            deviation(None),
            deviation(Some(1e-7)),
        );
        assert!(
            tight.0 < default.0 && default.0 < loose.0,
            "{model}: force deviations {loose:?} (1e-3), {default:?} (default), {tight:?} (1e-7)"
        );
        assert!(
            tight.1 < default.1 && default.1 < loose.1,
            "{model}: length deviations {loose:?} (1e-3), {default:?} (default), {tight:?} (1e-7)"
        );
        assert!(
            tight.0 <= TIGHT_FORCE && tight.1 <= TIGHT_LENGTH,
            "{model}: 1e-7 gives {tight:?}, not within {TIGHT_FORCE} N and {TIGHT_LENGTH} m"
        );
        assert!(
            default.0 > TIGHT_FORCE && default.1 > TIGHT_LENGTH,
            "{model}: the default gives {default:?}, already within {TIGHT_FORCE} N and \
             {TIGHT_LENGTH} m: the bound shows nothing"
        );
    }
}

/// Absent, every model steps as it always has; the table is not written into the TOML that
/// recordings and saved states carry.
#[test]
fn absent_is_each_models_own_stepping() {
    for name in ["elbow", "arm"] {
        let cfg = ActuatorConfig::resolve(name).unwrap();
        assert!(cfg.stepper.is_empty());
        assert!(!toml::to_string(&cfg).unwrap().contains("stepper"));
        for model in ModelKind::all() {
            let a = Actuator::new(&cfg, model, 1000.0).unwrap();
            assert_eq!(a.simulation().stepping(), default_stepping(model));
        }
    }
}

/// A saved state carries the tolerance (in its configuration and its stepping) and continues
/// bit for bit.
#[test]
fn the_tolerance_survives_a_saved_states_round_trip() {
    let cfg = elbow_with(Some(1e-7));
    let mut a = Actuator::new(&cfg, ModelKind::HUXLEY, 1000.0).unwrap();
    a.set_excitation(0, 1.0);
    for _ in 0..30 {
        a.step().unwrap();
    }
    let mut b = Actuator::from_bytes(&a.to_bytes()).unwrap();
    assert_eq!(b.config().stepper.tolerance, Some(1e-7));
    assert_eq!(
        b.simulation().stepping(),
        Stepping::Adaptive {
            tolerance: 1e-7,
            max_substeps: DEFAULT_MAX_SUBSTEPS
        }
    );
    for _ in 0..50 {
        a.step().unwrap();
        b.step().unwrap();
        assert_eq!(
            format!("{:?}", a.state()),
            format!("{:?}", b.state()),
            "tick {}",
            a.tick()
        );
    }
}
