use super::*;

const GOOD: &str = "datacolumns 3\ndatarows 2\ntime\ta\tb\n2.32\t0.1\t0.2\n2.324\t0.3\t-4e-1\n";

fn err(text: &str) -> TableError {
    Table::parse(text).unwrap_err()
}

#[test]
fn a_table_reads_column_major_with_its_times() {
    let t = Table::parse(GOOD).unwrap();
    assert_eq!(t.columns(), ["a", "b"]);
    assert_eq!(t.times(), [2.32, 2.324]);
    assert_eq!(t.rows(), 2);
    assert_eq!((t.start(), t.end()), (2.32, 2.324));
    assert_eq!(t.column(0), Some(&[0.1, 0.3][..]));
    assert_eq!(t.column_named("b"), Some(&[0.2, -0.4][..]));
    assert_eq!(t.value(1, 1), Some(-0.4));
    assert_eq!(t.column(2), None);
    assert_eq!(t.value(2, 0), None);
    assert_eq!(t.column_named("time"), None);
    // CR LF line ends and blank lines after the last row read the same.
    let crlf = GOOD.replace('\n', "\r\n") + "\r\n  \n";
    assert_eq!(Table::parse(&crlf).unwrap(), t);
    // No final newline.
    assert_eq!(Table::parse(GOOD.trim_end()).unwrap(), t);
}

#[test]
fn declared_counts_are_checked_against_the_header_and_the_rows() {
    let e = err(&GOOD.replace("datacolumns 3", "datacolumns 4"));
    assert_eq!(
        e,
        TableError::HeaderCount {
            line: 3,
            found: 3,
            declared: 4
        }
    );
    assert_eq!(
        e.to_string(),
        "line 3: the header has 3 tab-separated names, datacolumns declares 4"
    );
    let e = err(&GOOD.replace("datarows 2", "datarows 3"));
    assert_eq!(
        e,
        TableError::MissingRows {
            found: 2,
            declared: 3
        }
    );
    let e = err(&GOOD.replace("datarows 2", "datarows 1"));
    assert_eq!(
        e,
        TableError::ExtraRow {
            line: 5,
            declared: 1
        }
    );
    assert_eq!(
        e.to_string(),
        "line 5: a row beyond the 1 that datarows declares"
    );
    assert!(matches!(
        err(&GOOD.replace("datarows 2", "datarows two")),
        TableError::CountLine {
            line: 2,
            key: "datarows",
            ..
        }
    ));
    assert!(matches!(
        err(&GOOD.replace("datacolumns 3", "columns 3")),
        TableError::CountLine { line: 1, .. }
    ));
    assert!(matches!(err(""), TableError::CountLine { line: 1, .. }));
    assert!(matches!(
        err("datacolumns 3\n"),
        TableError::CountLine { line: 2, .. }
    ));
    assert!(matches!(
        err("datacolumns 99999999999999999999999\ndatarows 1\n"),
        TableError::CountLine { line: 1, .. }
    ));
    assert_eq!(
        err("datacolumns 1\ndatarows 1\ntime\n0\n"),
        TableError::TooFewColumns { declared: 1 }
    );
    assert_eq!(err("datacolumns 2\ndatarows 0\n"), TableError::NoRows);
    assert_eq!(err("datacolumns 2\ndatarows 1\n"), TableError::NoHeader);
    assert_eq!(err("datacolumns 2\ndatarows 1"), TableError::NoHeader);
    assert_eq!(
        err("datacolumns 2\ndatarows 1\ntime\tx\n"),
        TableError::MissingRows {
            found: 0,
            declared: 1
        }
    );
}

#[test]
fn every_field_is_a_finite_number_in_its_place() {
    let e = err(&GOOD.replace("0.3", "NaN"));
    assert_eq!(
        e,
        TableError::NotFinite {
            line: 5,
            column: 2,
            name: "a".into(),
            found: "NaN".into()
        }
    );
    assert_eq!(e.to_string(), "line 5, column 2 (a): \"NaN\" is not finite");
    assert!(matches!(
        err(&GOOD.replace("0.2", "inf")),
        TableError::NotFinite {
            line: 4,
            column: 3,
            ..
        }
    ));
    assert!(matches!(
        err(&GOOD.replace("0.2", "1e999")),
        TableError::NotFinite {
            line: 4,
            column: 3,
            ..
        }
    ));
    let e = err(&GOOD.replace("0.2", "0,2"));
    assert_eq!(
        e.to_string(),
        "line 4, column 3 (b): \"0,2\" is not a number"
    );
    assert!(matches!(
        err(&GOOD.replace("2.324\t", "x\t")),
        TableError::NotANumber { line: 5, column: 1, ref name, .. } if name == "time"
    ));
    assert!(matches!(
        err(&GOOD.replace("\t0.2", "\t\t0.2")),
        TableError::FieldCount {
            line: 4,
            found: 4,
            expected: 3
        }
    ));
    assert!(matches!(
        err(&GOOD.replace("\t0.2", " 0.2")),
        TableError::FieldCount {
            line: 4,
            found: 2,
            expected: 3
        }
    ));
    assert!(matches!(
        err(&GOOD.replace("\t0.2", "\t")),
        TableError::NotANumber {
            line: 4,
            column: 3,
            ..
        }
    ));
}

#[test]
fn times_increase_strictly() {
    let e = err(&GOOD.replace("2.324", "2.32"));
    assert_eq!(
        e,
        TableError::TimeNotIncreasing {
            line: 5,
            time: 2.32,
            previous: 2.32
        }
    );
    assert_eq!(
        e.to_string(),
        "line 5, column 1 (time): 2.32 s is not after the previous row's 2.32 s"
    );
    assert!(matches!(
        err(&GOOD.replace("2.324", "1")),
        TableError::TimeNotIncreasing { line: 5, .. }
    ));
}

#[test]
fn header_names_are_time_then_unique_and_non_empty() {
    assert!(matches!(
        err(&GOOD.replace("time\t", "Time\t")),
        TableError::HeaderNotTime { line: 3, .. }
    ));
    assert_eq!(
        err(&GOOD.replace("\tb\n", "\ta\n")),
        TableError::DuplicateName {
            line: 3,
            column: 3,
            name: "a".into(),
            first: 2
        }
    );
    assert_eq!(
        err(&GOOD.replace("\tb\n", "\t \n")),
        TableError::EmptyName { line: 3, column: 3 }
    );
    assert!(matches!(
        err(&GOOD.replace("\tb\n", "\ttime\n")),
        TableError::DuplicateName {
            column: 3,
            first: 1,
            ..
        }
    ));
}

#[test]
fn blank_lines_between_rows_are_refused() {
    let text = GOOD.replace("0.2\n", "0.2\n\n");
    assert_eq!(err(&text), TableError::BlankLine { line: 5 });
}

#[test]
fn long_user_text_is_quoted_as_an_excerpt_on_one_line() {
    let long = "x".repeat(500);
    let e = err(&GOOD.replace("0.2", &long));
    let message = e.to_string();
    assert!(message.len() < 150, "{message}");
    assert!(!message.contains('\n'));
}

#[test]
fn files_are_read_bounded_and_named_in_errors() {
    let dir = std::env::temp_dir().join(format!("measured_table_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("lmt.txt");
    std::fs::write(&path, GOOD).unwrap();
    assert_eq!(Table::read(&path).unwrap(), Table::parse(GOOD).unwrap());
    std::fs::write(&path, GOOD.replace("0.3", "nan")).unwrap();
    let e = Table::read(&path).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "{}: line 5, column 2 (a): \"nan\" is not finite",
            path.display()
        )
    );
    std::fs::write(&path, b"datacolumns 2\ndatarows 1\ntime\tx\n0\t\xff\n").unwrap();
    let e = Table::read(&path).unwrap_err();
    assert!(matches!(
        e,
        MeasuredError::Table {
            error: TableError::NotText { line: 4 },
            ..
        }
    ));
    let e = Table::read(&dir.join("missing.txt")).unwrap_err();
    assert!(e.is_not_found(), "{e}");
    let e = Table::read(&dir).unwrap_err();
    assert!(e.to_string().contains("not a regular file"), "{e}");
    let big = std::fs::File::create(&path).unwrap();
    big.set_len(MAX_TABLE_BYTES + 1).unwrap();
    let e = Table::read(&path).unwrap_err();
    assert!(e.to_string().contains("more than the"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}
