//! Tests of the curve sets: their names and what every set shares, and (`opensim`) the three
//! OpenSim sets against OpenSim 4.6's own evaluation of them.

mod opensim;

use super::*;
use serde::{Deserialize, Serialize};

#[derive(Debug, Deserialize, Serialize, PartialEq)]
struct Muscle {
    curves: CurveSet,
}

#[test]
fn names_parse_display_and_serialise_alike() {
    for set in CurveSet::ALL {
        assert_eq!(set.name().parse::<CurveSet>(), Ok(set));
        assert_eq!(set.to_string(), set.name());
        let text = format!("curves = \"{}\"\n", set.name());
        assert_eq!(
            toml::from_str::<Muscle>(&text).unwrap(),
            Muscle { curves: set }
        );
        assert_eq!(toml::to_string(&Muscle { curves: set }).unwrap(), text);
    }
    assert_eq!(CurveSet::default(), CurveSet::Paper);
}

#[test]
fn an_unknown_name_lists_the_names() {
    let err = "DeGroote2016".parse::<CurveSet>().unwrap_err();
    assert_eq!(err, UnknownCurveSet("DeGroote2016".into()));
    let message = err.to_string();
    assert!(
        message.contains("paper, degroote2016, thelen2003"),
        "{message}"
    );
    assert!(toml::from_str::<Muscle>("curves = \"hill\"").is_err());
}

#[test]
fn every_set_is_one_at_optimal_length_and_isometric() {
    // (A tabulated muscle's curves are its own points.)
    for set in CurveSet::ALL
        .into_iter()
        .filter(|&s| s != CurveSet::Tabulated)
    {
        let fl = set.evaluate(Curve::ActiveForceLength, 1.0).unwrap();
        assert!((fl - 1.0).abs() < 1e-15, "{set}: {fl}");
        assert_eq!(
            set.evaluate(Curve::ForceVelocity, -1.0)
                .map(|f| f.abs() < 1e-15),
            Some(true)
        );
        let fv = set.evaluate(Curve::ForceVelocity, 0.0).unwrap();
        assert!((fv - 1.0).abs() < 1e-15, "{set}: {fv}");
    }
}

#[test]
fn the_opensim_sets_have_every_curve_and_the_paper_only_the_contractile_ones() {
    for curve in Curve::ALL {
        assert!(CurveSet::DeGroote2016.evaluate(curve, 1.02).is_some());
        assert!(CurveSet::Thelen2003.evaluate(curve, 1.02).is_some());
    }
    assert_eq!(
        CurveSet::Paper.evaluate(Curve::PassiveForceLength, 1.2),
        None
    );
    assert_eq!(
        CurveSet::Paper.evaluate(Curve::TendonForceLength, 1.02),
        None
    );
    // Tendon force 1 at each OpenSim set's strain at one normalised force.
    let dgf = CurveSet::DeGroote2016
        .evaluate(Curve::TendonForceLength, 1.049)
        .unwrap();
    let thelen = CurveSet::Thelen2003
        .evaluate(Curve::TendonForceLength, 1.04)
        .unwrap();
    assert!(
        (dgf - 1.0).abs() < 1e-14 && (thelen - 1.0).abs() < 1e-14,
        "{dgf} {thelen}"
    );
}
