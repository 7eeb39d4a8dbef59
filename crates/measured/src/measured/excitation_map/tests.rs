use super::*;

const GOOD: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<emgGenerator>
<experimental>
	<emg id="gmax_r"/>
	<emg id="gmed_r"/>
	<emg id="sol_r"/>
</experimental>
<mapping>
	<emg id="gmax1_r" operation="assign">
		gmax_r
	</emg>
	<emg id="gmin1_r" operation="mean">
		gmed_r
		gmax_r
	</emg>
	<emg id="both_r" operation="sum"> gmed_r gmax_r </emg>
	<emg id="psoas_r" operation="nil"/>
</mapping>
<output>
	gmax1_r gmin1_r
	both_r psoas_r sol_r
</output>
</emgGenerator>
"#;

fn err(text: &str) -> ExcitationMapError {
    ExcitationMap::parse(text).unwrap_err()
}

#[test]
fn a_map_reads_each_unit_s_source_in_output_order() {
    let m = ExcitationMap::parse(GOOD).unwrap();
    assert_eq!(m.channels, ["gmax_r", "gmed_r", "sol_r"]);
    let units: Vec<_> = m.units.iter().map(|u| u.unit.as_str()).collect();
    assert_eq!(units, ["gmax1_r", "gmin1_r", "both_r", "psoas_r", "sol_r"]);
    assert_eq!(
        m.unit("gmax1_r"),
        Some(&Excitation::Channel("gmax_r".into()))
    );
    assert_eq!(
        m.unit("gmin1_r"),
        Some(&Excitation::Mean(vec!["gmed_r".into(), "gmax_r".into()]))
    );
    assert_eq!(
        m.unit("both_r"),
        Some(&Excitation::Sum(vec!["gmed_r".into(), "gmax_r".into()]))
    );
    assert_eq!(m.unit("psoas_r"), Some(&Excitation::Zero));
    assert_eq!(m.unit("sol_r"), Some(&Excitation::Channel("sol_r".into())));
    assert_eq!(m.unit("gmed_r"), None);
}

#[test]
fn excitations_are_the_channels_combined_per_row() {
    let m = ExcitationMap::parse(GOOD).unwrap();
    let emg = Table::parse(
        "datacolumns 4\ndatarows 2\ntime\tsol_r\tgmed_r\tgmax_r\n0\t0.5\t0.2\t0.4\n0.0005\t0.25\t0.1\t0.3\n",
    )
    .unwrap();
    let e = m.excitations(&emg).unwrap();
    assert_eq!(
        e.columns(),
        ["gmax1_r", "gmin1_r", "both_r", "psoas_r", "sol_r"]
    );
    assert_eq!(e.times(), emg.times());
    assert_eq!(e.column_named("gmax1_r"), Some(&[0.4, 0.3][..]));
    assert_eq!(
        e.column_named("gmin1_r"),
        Some(&[(0.2 + 0.4) / 2.0, (0.1 + 0.3) / 2.0][..])
    );
    assert_eq!(e.column_named("both_r"), Some(&[0.2 + 0.4, 0.1 + 0.3][..]));
    assert_eq!(e.column_named("psoas_r"), Some(&[0.0, 0.0][..]));
    assert_eq!(e.column_named("sol_r"), Some(&[0.5, 0.25][..]));
    let short = Table::parse("datacolumns 2\ndatarows 1\ntime\tsol_r\n0\t1\n").unwrap();
    assert_eq!(
        m.excitations(&short).unwrap_err().to_string(),
        "the channel table has no column \"gmax_r\""
    );
}

#[test]
fn an_unknown_channel_is_refused() {
    let e = err(&GOOD.replace("\t\tgmed_r\n\t\tgmax_r", "\t\tgmed_r\n\t\tgmin_r"));
    assert_eq!(
        e,
        ExcitationMapError::Entry {
            line: 12,
            unit: "gmin1_r".into(),
            kind: EntryError::UnknownChannel("gmin_r".into())
        }
    );
    assert_eq!(
        e.to_string(),
        "line 12: mapping of \"gmin1_r\": channel \"gmin_r\" is not one of <experimental>"
    );
}

#[test]
fn operations_take_their_count_of_channels() {
    let e = err(&GOOD.replace(
        "\t\tgmax_r\n\t</emg>\n\t<emg id=\"gmin1_r\"",
        "\t\tgmax_r gmed_r\n\t</emg>\n\t<emg id=\"gmin1_r\"",
    ));
    assert_eq!(
        e.to_string(),
        "line 9: mapping of \"gmax1_r\": operation assign takes one channel(s), found 2"
    );
    let e = err(&GOOD.replace("operation=\"nil\"/>", "operation=\"nil\">sol_r</emg>"));
    assert!(matches!(
        e,
        ExcitationMapError::Entry {
            kind: EntryError::Arity { found: 1, .. },
            ..
        }
    ));
    let e = err(&GOOD.replace("> gmed_r gmax_r <", "> <"));
    assert!(matches!(
        e,
        ExcitationMapError::Entry {
            kind: EntryError::Arity { found: 0, .. },
            ..
        }
    ));
    let e = err(&GOOD.replace("operation=\"sum\"", "operation=\"max\""));
    assert_eq!(
        e.to_string(),
        "line 16: mapping of \"both_r\": unknown operation \"max\" (expected assign, mean, sum or nil)"
    );
    let e = err(&GOOD.replace("> gmed_r gmax_r <", "> gmed_r gmed_r <"));
    assert!(matches!(
        e,
        ExcitationMapError::Entry {
            kind: EntryError::RepeatedChannel(_),
            ..
        }
    ));
    let e = err(&GOOD.replace(" operation=\"sum\"", ""));
    assert!(matches!(
        e,
        ExcitationMapError::Xml(XmlError::MissingAttribute {
            attribute: "operation",
            ..
        })
    ));
}

#[test]
fn names_are_declared_once_and_every_unit_has_a_source() {
    let e = err(&GOOD.replace("psoas_r sol_r", "psoas_r sol_r gmed1_r"));
    assert_eq!(
        e.to_string(),
        "line 19: output: unit \"gmed1_r\" has no mapping entry and no channel of its name \
         (give it one; operation=\"nil\" for none)"
    );
    let e = err(&GOOD.replace("<emg id=\"sol_r\"/>", "<emg id=\"gmed_r\"/>"));
    assert_eq!(
        e,
        ExcitationMapError::Repeated {
            line: 6,
            list: "experimental",
            name: "gmed_r".into()
        }
    );
    assert!(matches!(
        err(&GOOD.replace("psoas_r sol_r", "psoas_r psoas_r")),
        ExcitationMapError::Repeated { list: "output", .. }
    ));
    assert!(matches!(
        err(&GOOD.replace("id=\"both_r\"", "id=\"gmin1_r\"")),
        ExcitationMapError::Repeated {
            list: "mapping",
            ..
        }
    ));
    assert!(matches!(
        err(&GOOD.replace("id=\"both_r\"", "id=\"other_r\"")),
        ExcitationMapError::NotAnOutput { line: 16, .. }
    ));
    assert!(matches!(
        err(&GOOD.replace("id=\"sol_r\"", "id=\" \"")),
        ExcitationMapError::EmptyId { line: 6, .. }
    ));
    let no_output = GOOD.replace("gmax1_r gmin1_r\n\tboth_r psoas_r sol_r", "");
    assert!(matches!(
        err(&no_output),
        ExcitationMapError::UnitCount { found: 0, .. }
    ));
    let many = (0..=MAX_UNITS)
        .map(|i| format!("u{i} "))
        .collect::<String>();
    let text = GOOD.replace("gmax1_r gmin1_r\n\tboth_r psoas_r sol_r", &many);
    assert!(matches!(err(&text), ExcitationMapError::UnitCount { .. }));
    let e = err(&GOOD
        .replace("<output>", "<outputs>")
        .replace("</output>", "</outputs>"));
    assert!(
        matches!(e, ExcitationMapError::Xml(XmlError::Unknown { .. })),
        "{e:?}"
    );
}

#[test]
fn files_are_read_and_named_in_errors() {
    let dir = std::env::temp_dir().join(format!("measured_map_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("emgGenerator.xml");
    std::fs::write(&path, GOOD).unwrap();
    assert_eq!(
        ExcitationMap::read(&path).unwrap(),
        ExcitationMap::parse(GOOD).unwrap()
    );
    std::fs::write(
        &path,
        GOOD.replace("operation=\"sum\"", "operation=\"max\""),
    )
    .unwrap();
    let e = ExcitationMap::read(&path).unwrap_err();
    assert!(
        e.to_string().starts_with(&format!(
            "{}: line 16: mapping of \"both_r\"",
            path.display()
        )),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
