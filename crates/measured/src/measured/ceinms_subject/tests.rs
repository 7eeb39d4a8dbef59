use super::*;

/// A small subject of the file's shape: two units, two degrees of freedom.
const GOOD: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<subject xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
  <mtuDefault>
    <emDelay>0.015</emDelay>
    <percentageChange>0.15</percentageChange>
    <damping>0.1</damping>
    <curve>
      <name>activeForceLength</name>
      <xPoints>0 1 2</xPoints>
      <yPoints>0 1 0</yPoints>
    </curve>
    <curve>
      <name>passiveForceLength</name>
      <xPoints>1 1.5</xPoints>
      <yPoints>0 1</yPoints>
    </curve>
    <curve>
      <name>forceVelocity</name>
      <xPoints>-1 0 1</xPoints>
      <yPoints>0 1 1.8</yPoints>
    </curve>
  </mtuDefault>
  <mtuSet>
    <mtu>
      <name>a_r</name>
      <c1>0.5</c1>
      <c2>-0.9</c2>
      <shapeFactor>-1.5</shapeFactor>
      <optimalFibreLength>0.1</optimalFibreLength>
      <pennationAngle>30</pennationAngle>
      <tendonSlackLength>0.2</tendonSlackLength>
      <maxIsometricForce>500</maxIsometricForce>
      <strengthCoefficient>1.2</strengthCoefficient>
    </mtu>
    <mtu>
      <name>b_r</name>
      <emDelay>0.02</emDelay>
      <c1>0.5</c1>
      <c2>-0.9</c2>
      <shapeFactor>0.1</shapeFactor>
      <optimalFibreLength>0.05</optimalFibreLength>
      <pennationAngle>0</pennationAngle>
      <tendonSlackLength>0.3</tendonSlackLength>
      <maxIsometricForce>800</maxIsometricForce>
      <strengthCoefficient>1</strengthCoefficient>
    </mtu>
  </mtuSet>
  <dofSet>
    <dof>
      <name>R_knee_fe</name>
      <mtuNameSet>a_r b_r</mtuNameSet>
    </dof>
    <dof>
      <name>R_ankle_fe</name>
      <mtuNameSet>b_r</mtuNameSet>
    </dof>
  </dofSet>
  <calibrationInfo>
    <uncalibrated>
      <subjectID>s0</subjectID>
      <additionalInfo></additionalInfo>
    </uncalibrated>
  </calibrationInfo>
</subject>
"#;

fn err(text: &str) -> SubjectError {
    Subject::parse(text).unwrap_err()
}

#[test]
fn a_subject_reads_with_its_units_in_si() {
    let s = Subject::parse(GOOD).unwrap();
    assert_eq!(s.defaults.em_delay_s, 0.015);
    assert_eq!(s.defaults.percentage_change, 0.15);
    assert_eq!(s.defaults.damping, 0.1);
    let c = &s.defaults.curves;
    assert_eq!(c.active_force_length.x(), [0.0, 1.0, 2.0]);
    assert_eq!(c.passive_force_length.y(), [0.0, 1.0]);
    assert_eq!(c.force_velocity.len(), 3);
    assert_eq!(c.tendon_force_strain, None);
    assert_eq!(s.units.len(), 2);
    let a = s.unit("a_r").unwrap();
    assert_eq!(
        *a,
        Unit {
            name: "a_r".into(),
            em_delay_s: None,
            c1: 0.5,
            c2: -0.9,
            shape_factor: -1.5,
            optimal_fibre_length_m: 0.1,
            pennation_angle_rad: 30f64.to_radians(),
            tendon_slack_length_m: 0.2,
            max_isometric_force_n: 500.0,
            strength_coefficient: 1.2,
        }
    );
    assert!((a.pennation_angle_rad - std::f64::consts::PI / 6.0).abs() < 1e-15);
    assert_eq!(s.em_delay_s(a), 0.015);
    assert_eq!(s.em_delay_s(s.unit("b_r").unwrap()), 0.02);
    assert_eq!(s.dof("R_knee_fe").unwrap().units, ["a_r", "b_r"]);
    assert_eq!(s.dofs.len(), 2);
    assert!(s.unit("c_r").is_none() && s.dof("R_hip_fe").is_none());
    assert_eq!(
        s.calibration,
        Calibration::Uncalibrated {
            subject_id: "s0".into(),
            additional_info: String::new()
        }
    );
}

#[test]
fn a_calibrated_subject_gives_its_sequence() {
    let text = GOOD.replace(
        "<uncalibrated>\n      <subjectID>s0</subjectID>\n      <additionalInfo></additionalInfo>\n    </uncalibrated>",
        "<calibrated><startSubjectFile>u.xml</startSubjectFile>\
         <calibrationSequence>first second</calibrationSequence></calibrated>",
    );
    assert_eq!(
        Subject::parse(&text).unwrap().calibration,
        Calibration::Calibrated {
            start_subject_file: "u.xml".into(),
            calibration_sequence: vec!["first".into(), "second".into()]
        }
    );
    let neither = GOOD
        .replace("<uncalibrated>", "<!--")
        .replace("</uncalibrated>", "-->");
    assert!(matches!(err(&neither), SubjectError::Calibration { .. }));
}

#[test]
fn a_negative_length_names_the_element_and_the_unit() {
    let e = err(&GOOD.replace("<optimalFibreLength>0.05<", "<optimalFibreLength>-0.05<"));
    assert_eq!(
        e,
        SubjectError::OutOfRange {
            line: 41,
            within: "mtu \"b_r\"".into(),
            element: "optimalFibreLength",
            value: -0.05,
            rule: "above 0",
        }
    );
    assert_eq!(
        e.to_string(),
        "line 41: mtu \"b_r\": <optimalFibreLength> = -0.05, must be above 0"
    );
    let e = err(&GOOD.replace("<tendonSlackLength>0.2<", "<tendonSlackLength>0<"));
    assert!(matches!(
        e,
        SubjectError::OutOfRange {
            element: "tendonSlackLength",
            ..
        }
    ));
    let e = err(&GOOD.replace("<maxIsometricForce>500<", "<maxIsometricForce>-1<"));
    assert!(matches!(
        e,
        SubjectError::OutOfRange {
            element: "maxIsometricForce",
            ..
        }
    ));
}

#[test]
fn each_parameter_keeps_its_range() {
    let cases = [
        (
            "<c1>0.5</c1>\n      <c2>-0.9</c2>\n      <shapeFactor>-1.5",
            "<c1>1</c1>\n      <c2>-0.9</c2>\n      <shapeFactor>-1.5",
            "c1",
        ),
        (
            "<c2>-0.9</c2>\n      <shapeFactor>-1.5",
            "<c2>-1.2</c2>\n      <shapeFactor>-1.5",
            "c2",
        ),
        (
            "<pennationAngle>30<",
            "<pennationAngle>90<",
            "pennationAngle",
        ),
        (
            "<pennationAngle>30<",
            "<pennationAngle>-1<",
            "pennationAngle",
        ),
        (
            "<strengthCoefficient>1.2<",
            "<strengthCoefficient>0<",
            "strengthCoefficient",
        ),
        ("<emDelay>0.02<", "<emDelay>-0.001<", "emDelay"),
        ("<emDelay>0.015<", "<emDelay>-1<", "emDelay"),
        (
            "<percentageChange>0.15<",
            "<percentageChange>1<",
            "percentageChange",
        ),
        ("<damping>0.1<", "<damping>-0.1<", "damping"),
    ];
    for (from, to, element) in cases {
        let text = GOOD.replacen(from, to, 1);
        assert_ne!(text, GOOD, "{from}");
        match err(&text) {
            SubjectError::OutOfRange { element: e, .. } => assert_eq!(e, element),
            other => panic!("{element}: {other:?}"),
        }
    }
    let e = err(&GOOD.replace("<c1>0.5<", "<c1>NaN<"));
    assert!(
        matches!(e, SubjectError::Xml(XmlError::NotANumber { ref element, .. }) if element == "c1"),
        "{e:?}"
    );
    let e = err(&GOOD.replace("<shapeFactor>0.1<", "<shapeFactor>1e400<"));
    assert_eq!(
        e.to_string(),
        "line 40: mtu \"b_r\": <shapeFactor> \"1e400\" is not a finite number"
    );
}

#[test]
fn curves_need_increasing_x_and_equal_lengths() {
    let e = err(&GOOD.replace("<xPoints>0 1 2</xPoints>", "<xPoints>0 1 1</xPoints>"));
    assert_eq!(
        e,
        SubjectError::Curve {
            line: 7,
            name: "activeForceLength".into(),
            error: CurveError::NotIncreasing {
                index: 2,
                x: 1.0,
                previous: 1.0
            }
        }
    );
    assert_eq!(
        e.to_string(),
        "line 7: curve \"activeForceLength\": x[2] = 1 is not above x[1] = 1"
    );
    let e = err(&GOOD.replace("<yPoints>0 1 1.8</yPoints>", "<yPoints>0 1</yPoints>"));
    assert!(matches!(
        e,
        SubjectError::Curve {
            error: CurveError::Lengths { x: 3, y: 2 },
            ..
        }
    ));
    let e = err(&GOOD.replace("<xPoints>1 1.5</xPoints>", "<xPoints>1 x</xPoints>"));
    assert_eq!(
        e.to_string(),
        "line 14: curve \"passiveForceLength\": <xPoints> \"x\" is not a finite number"
    );
    let e = err(&GOOD.replace("<name>forceVelocity</name>", "<name>fv</name>"));
    assert!(
        matches!(e, SubjectError::UnknownCurve { line: 17, .. }),
        "{e:?}"
    );
    let e = err(&GOOD.replace(
        "<name>forceVelocity</name>",
        "<name>activeForceLength</name>",
    ));
    assert!(
        matches!(e, SubjectError::DuplicateCurve { line: 17, .. }),
        "{e:?}"
    );
    let no_velocity = GOOD.replace(
        "<name>forceVelocity</name>",
        "<name>tendonForceStrain</name>",
    );
    assert_eq!(
        err(&no_velocity),
        SubjectError::MissingCurve {
            line: 3,
            name: "forceVelocity"
        }
    );
    let s = Subject::parse(&no_velocity.replace(
        "<name>tendonForceStrain</name>",
        "<name>forceVelocity</name>",
    ))
    .unwrap();
    assert!(s.defaults.curves.tendon_force_strain.is_none());
}

#[test]
fn structure_is_the_schema_s() {
    let e = err(&GOOD.replace("<c2>-0.9</c2>\n      <shapeFactor>0.1", "<shapeFactor>0.1"));
    assert_eq!(e.to_string(), "line 35: mtu \"b_r\": no <c2>");
    let e = err(&GOOD.replace("<c1>0.5</c1>", "<c1>0.5</c1><c1>0.5</c1>"));
    assert!(matches!(
        e,
        SubjectError::Xml(XmlError::Duplicate { element: "c1", .. })
    ));
    let e = err(&GOOD.replace("<damping>0.1</damping>", "<damping>0.1</damping><dampnig/>"));
    assert!(
        matches!(e, SubjectError::Xml(XmlError::Unknown { .. })),
        "{e:?}"
    );
    let e = err(&GOOD.replace("<name>a_r</name>", "<name> </name>"));
    assert!(
        matches!(e, SubjectError::Xml(XmlError::Empty { .. })),
        "{e:?}"
    );
    let e = err(&GOOD
        .replace("<subject ", "<subjects ")
        .replace("</subject>", "</subjects>"));
    assert!(matches!(e, SubjectError::Xml(XmlError::WrongRoot { .. })));
    let e = err(&GOOD[..GOOD.len() / 2]);
    assert!(matches!(e, SubjectError::Xml(XmlError::Parse { .. })));
    let no_units = GOOD.replace("<mtu>", "<!--").replace("</mtu>", "-->");
    assert!(matches!(
        err(&no_units),
        SubjectError::Xml(XmlError::Missing { element: "mtu", .. })
    ));
}

#[test]
fn degrees_of_freedom_name_known_units_once() {
    let e = err(&GOOD.replace("a_r b_r", "a_r c_r"));
    assert_eq!(
        e,
        SubjectError::UnknownUnit {
            line: 51,
            dof: "R_knee_fe".into(),
            unit: "c_r".into()
        }
    );
    assert_eq!(
        e.to_string(),
        "line 51: dof \"R_knee_fe\": unit \"c_r\" is not in <mtuSet>"
    );
    assert!(matches!(
        err(&GOOD.replace("a_r b_r", "a_r a_r")),
        SubjectError::RepeatedUnit { .. }
    ));
    assert!(matches!(
        err(&GOOD.replace("a_r b_r", " ")),
        SubjectError::EmptyDof { .. }
    ));
    assert!(matches!(
        err(&GOOD.replace("<name>R_ankle_fe</name>", "<name>R_knee_fe</name>")),
        SubjectError::DuplicateDof { .. }
    ));
    assert!(matches!(
        err(&GOOD.replace("<name>b_r</name>", "<name>a_r</name>")),
        SubjectError::DuplicateUnit { .. }
    ));
}

#[test]
fn files_are_read_bounded_and_named_in_errors() {
    let dir = std::env::temp_dir().join(format!("measured_subject_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("subject.xml");
    std::fs::write(&path, GOOD).unwrap();
    assert_eq!(Subject::read(&path).unwrap(), Subject::parse(GOOD).unwrap());
    std::fs::write(&path, GOOD.replace("<c1>0.5<", "<c1>-1<")).unwrap();
    let e = Subject::read(&path).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "{}: line 26: mtu \"a_r\": <c1> = -1, must be in (-1, 1)",
            path.display()
        )
    );
    std::fs::write(&path, b"<subject>\n\xfe</subject>").unwrap();
    assert!(matches!(
        Subject::read(&path).unwrap_err(),
        MeasuredError::Subject {
            error: SubjectError::Xml(XmlError::NotText { line: 2 }),
            ..
        }
    ));
    std::fs::File::create(&path)
        .unwrap()
        .set_len(xml::MAX_XML_BYTES + 1)
        .unwrap();
    assert!(matches!(
        Subject::read(&path),
        Err(MeasuredError::Io { .. })
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}
