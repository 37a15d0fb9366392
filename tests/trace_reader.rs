//! The core's tolerant trace reader (issue 26): a simulated feed-vector
//! trace written as users' files are (`Time [ms]`, `;` with decimal
//! commas, tab, a preamble, quoted numbers, headerless with a sample
//! period, `POS X(um)`, torque in `%`) reads back to the same numbers
//! within 1e-9 relative, with the header's units applied by the core; every
//! refusal names its cause and the first offending line, never the last
//! line of the file when the fault is earlier; a trace whose C is constant
//! is refused naming C.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::feed_vector::trace_analysis::{analyze_trace, ColumnMap};
use mtmotion::feed_vector::FeedVectorResult;
use mtmotion::trace::{read_table, ColumnKind, ReadOptions, Table, TableRead};
use std::f64::consts::PI;

#[path = "support/feed_vector_trace.rs"]
mod feed_vector_trace;
use feed_vector_trace::{close, rows, sim};

#[test]
fn time_in_ms_is_read_as_ms_with_auto_detected_columns() {
    let (cond, r) = sim();
    let mut text = String::from("Time [ms],X [mm],Y [mm],C [deg]\n");
    for [t, x, y, c, _] in rows(&r) {
        text += &format!("{},{x},{y},{c}\n", t * 1e3);
    }
    let tr = analyze_trace(&text, &cond, &ColumnMap::default()).unwrap();
    let end = *tr.series.t.last().unwrap();
    assert!((end - 3.0).abs() < 1e-9, "{end} s");
    assert!(tr.summary.periods <= 2, "{} periods", tr.summary.periods);
    assert_eq!(tr.summary.periods, r.summary.periods);
    // on the simulation's own steady window, the same summary
    let same = ColumnMap {
        steady_from: Some(r.summary.steady_from),
        ..ColumnMap::default()
    };
    let tr = analyze_trace(&text, &cond, &same).unwrap();
    let d = (tr.summary.mean_angle_diff - r.summary.mean_angle_diff).abs();
    assert!(d < 1e-9, "{d} rad");
    // The same file with the header's units ignored (the old reading:
    // milliseconds taken for seconds) is refused, not summarised.
    let old = ColumnMap {
        header_units: false,
        ..ColumnMap::default()
    };
    let e = analyze_trace(&text, &cond, &old).unwrap_err().to_string();
    assert!(
        e.starts_with("C turns at 0.00313687 rad/s") && e.contains("the time unit"),
        "{e}"
    );
}

/// The trace written in one of the layouts users have.
fn written(r: &FeedVectorResult, layout: &str) -> String {
    let comma = |v: f64| v.to_string().replace('.', ",");
    let mut text = match layout {
        "semicolon" => "Zeit [s];X [mm];Y [mm];C [deg];Torque [Nm];Machining_Process\n".to_string(),
        "tab" => "time\tX_mm\tY_mm\tC_deg\tTCMD\n".to_string(),
        "preamble" => "SERVO GUIDE 2.0\nMachine: NMV5000\nSampling = 1 ms\nt(s),x(mm),y(mm),c(deg),torque(Nm)\n".to_string(),
        "quoted" => "\"time\",\"x\",\"y\",\"c\",\"tq\"\n".to_string(),
        _ => String::new(),
    };
    for [t, x, y, c, tq] in rows(r) {
        text += &match layout {
            "semicolon" => format!(
                "{};{};{};{};{};Finishing\n",
                comma(t),
                comma(x),
                comma(y),
                comma(c),
                comma(tq)
            ),
            "tab" => format!("{t}\t{x}\t{y}\t{c}\t{tq}\n"),
            "preamble" => format!("{t},{x},{y},{c},{tq}\n"),
            "quoted" => format!("\"{t}\",\"{x}\",\"{y}\",\"{c}\",\"{tq}\"\n"),
            _ => format!("{x} {y}  {c} {tq}\n"),
        };
    }
    text
}

#[test]
fn every_layout_reads_back_to_the_same_numbers() {
    let (_, r) = sim();
    let want = rows(&r);
    for layout in ["semicolon", "tab", "preamble", "quoted", "headerless"] {
        let opts = ReadOptions {
            sample_period: (layout == "headerless").then_some(1e-3),
            ..ReadOptions::default()
        };
        let got =
            read_table(&written(&r, layout), &opts).unwrap_or_else(|e| panic!("{layout}: {e}"));
        let t = &got.table;
        assert_eq!(t.rows(), want.len(), "{layout}");
        // the generated time column comes last
        let order: [usize; 5] = if layout == "headerless" {
            [4, 0, 1, 2, 3]
        } else {
            [0, 1, 2, 3, 4]
        };
        for (j, &k) in order.iter().enumerate() {
            for (i, row) in want.iter().enumerate() {
                assert!(
                    close(t.columns[k][i], row[j]),
                    "{layout}: column {k} row {i}: {} vs {}",
                    t.columns[k][i],
                    row[j]
                );
            }
        }
        let notes = got.layout.notes.join(" | ");
        match layout {
            "semicolon" => {
                assert!(
                    got.layout.decimal_comma
                        && notes.contains("decimal commas with ';' found (line 2: "),
                    "{notes}"
                );
                assert!(notes.contains("column 'Machining_Process' (field 6) is text ('Finishing' on line 2): ignored"), "{notes}");
                assert_eq!(got.layout.columns[5].kind, ColumnKind::Text);
                assert_eq!(got.layout.columns[3].factor, Some(PI / 180.0));
            }
            "tab" => assert_eq!(
                (got.layout.delimiter, got.layout.columns[1].unit),
                ("tab", Some("mm"))
            ),
            "preamble" => {
                let m = metadata(&got);
                assert_eq!(
                    m,
                    [
                        ("SERVO GUIDE 2.0", ""),
                        ("Machine", "NMV5000"),
                        ("Sampling", "1 ms")
                    ]
                );
                assert_eq!(got.layout.header_line, Some(4));
            }
            "quoted" => assert!(notes.contains("quoted numbers (line 2: "), "{notes}"),
            _ => {
                assert_eq!(got.layout.header_line, None);
                assert_eq!(
                    t.names,
                    ["column 1", "column 2", "column 3", "column 4", "time"]
                );
                assert_eq!(got.layout.columns[4].kind, ColumnKind::Generated);
            }
        }
    }
}

#[test]
fn servo_guide_headers_in_um_and_torque_in_percent() {
    let (cond, r) = sim();
    let mut text = String::from("Time [ms],POS X(um),POS Y(um),POS C(deg),TCMD C(%)\n");
    for [t, x, y, c, tq] in rows(&r) {
        // 200 N·m rated: % = torque / 2
        text += &format!("{},{},{},{c},{}\n", t * 1e3, x * 1e3, y * 1e3, tq / 2.0);
    }
    let e = analyze_trace(&text, &cond, &ColumnMap::default())
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "line 1, column 5 ('TCMD C(%)'): the torque is in % of the rated torque; give mapping.ratedTorque (the motor's rated torque in N·m), or map a torque column in N·m"
    );
    let map = ColumnMap {
        rated_torque: Some(200.0),
        ..ColumnMap::default()
    };
    let tr = analyze_trace(&text, &cond, &map).unwrap();
    for i in (0..r.series.t.len()).step_by(97) {
        assert!(close(tr.series.x[i], r.series.x[i]), "x {i}");
        assert!(
            close(tr.series.torque_c[i], r.series.torque_c[i]),
            "torque {i}"
        );
    }
    assert!((tr.summary.peak_torque - r.summary.peak_torque).abs() < 1e-9 * r.summary.peak_torque);
    // a time unit on the X column is named, not used
    let swapped = text.replacen("POS X(um)", "POS X(ms)", 1);
    let e = analyze_trace(&swapped, &cond, &map)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("line 1, column 2 ('POS X(ms)'): the header states 'ms', a unit of s, but this column is read as the X or Y column"), "{e}");
}

#[test]
fn a_trace_whose_c_is_constant_is_refused_naming_c() {
    let (cond, r) = sim();
    let mut text = String::from("Time [ms],X [mm],Y [mm],C [V]\n");
    for [t, x, y, _, _] in rows(&r) {
        text += &format!("{},{x},{y},0.0\n", t * 1e3);
    }
    let e = analyze_trace(
        &text,
        &cond,
        &ColumnMap {
            c: Some("C [V]".into()),
            ..ColumnMap::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("C is constant: 0 deg over 3 s (column 'C [V]', lines 2–3002); is this the C channel? The condition's ω = 3.14159 rad/s turns C by 456.48 deg"),
        "{e}"
    );
}

/// Each malformed file, the line its error must name, and a word of the cause.
const REFUSED: [(&str, usize, &str); 10] = [
    (
        "t;x;Machining_Process\n0;1,5;Rough\n0,001;x;Rough\n1;2;Rough\n2;3;Rough\n",
        3,
        "'x' is not a number",
    ),
    (
        "<?xml version=\"1.0\"?>\n<trace>\n<row t=\"0\"/>\n</trace>\n",
        2,
        "root is <trace> without traceData/dataFrame, so it is not a SINUMERIK trace",
    ),
    (
        "t;x\n0;1,5\n1;2.5\n2;3\n3;4\n",
        2,
        "decimal comma but line 3 has '2.5'",
    ),
    (
        "a;b\nc;d\ne;f\ng;h\n",
        2,
        "'c' (field 1), 'd' (field 2) are not numbers",
    ),
    (
        "a,b,c\nd,e\nf,g\nh,i\n",
        2,
        "'d' (field 1), 'e' (field 2) are not numbers",
    ),
    ("t,x\n0,1\n1\n2,3\n3,4\n", 3, "1 fields, expected 2"),
    ("time,x\n0,1\n1,2\n2,3\n", 1, "its own time column 'time'"),
    ("# export\n\n1,2\n3,4\n5,6\n", 3, "samplePeriod"),
    ("t,x\n0,1\n1,2\u{7}\n2,3\n", 3, "control character U+0007"),
    ("t,tq(%)\n0,1\n1,2\n2,3\n", 1, "ratedTorque"),
];

#[test]
fn every_refusal_names_its_cause_and_first_offending_line() {
    for (k, (text, line, cause)) in REFUSED.iter().enumerate() {
        let opts = ReadOptions {
            sample_period: [6, 7]
                .contains(&k)
                .then_some(if k == 7 { -1.0 } else { 1e-3 }),
            rated_torque: (k == 9).then_some(0.0),
        };
        let e = read_table(text, &opts).unwrap_err().to_string();
        let last = text.trim_end().lines().count();
        assert!(e.starts_with(&format!("line {line}")), "{text:?}: {e}");
        assert!(e.contains(cause), "{text:?}: {e}");
        assert!(
            *line < last && !e.starts_with(&format!("line {last}")),
            "{text:?}: {e}"
        );
    }
    // The strict import (ball-bar) says why no row is plain numbers, at the
    // first data line, instead of "header found" at the last line.
    let e = Table::parse("t;x\n0;1,5\n1;2,5\n2;3,5\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("line 2: no row of numbers found: the rows are not plain numbers (decimal commas with ';' found (line 2: '1,5'): read as such)"),
        "{e}"
    );
    let e = Table::parse("t;x\nab;1,5\nab;2,5\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("line 2: no row of numbers found: the rows are not plain numbers (column 't' (field 1) is text ('ab' on line 2): ignored;"),
        "{e}"
    );
    assert_eq!(
        Table::parse("a,b\n").unwrap_err().to_string(),
        "line 1: header found, but no data rows follow"
    );
    // no line to name: the cause alone
    assert_eq!(
        read_table("\n# x\n", &ReadOptions::default())
            .unwrap_err()
            .to_string(),
        "the trace is empty: expected a header line such as 'time,x,y,c'"
    );
}

/// The layout preview marks what the feed-vector import reads each column
/// as; a text column in between takes no role and shifts none.
#[test]
fn the_preview_marks_each_columns_role_past_text_columns() {
    let text =
        "Note;Zeit [ms];Status;POS X(um);Y;C [deg];TCMD C(Nm)\na;0;ok;1;2;3;4\nb;1;ok;2;3;4;5\n";
    let mut r = read_table(text, &ReadOptions::default()).unwrap();
    mtmotion::feed_vector::trace_analysis::roles(&mut r);
    let got: Vec<(&str, Option<&str>)> = r
        .layout
        .columns
        .iter()
        .map(|c| (c.name.as_str(), c.role))
        .collect();
    assert_eq!(
        got,
        [
            ("Note", None),
            ("Zeit [ms]", Some("time")),
            ("Status", None),
            ("POS X(um)", Some("x")),
            ("Y", Some("y")),
            ("C [deg]", Some("c")),
            ("TCMD C(Nm)", Some("torque"))
        ]
    );
}

/// The metadata lines above the header, as (key, value).
fn metadata(r: &TableRead) -> Vec<(&str, &str)> {
    r.layout
        .metadata
        .iter()
        .map(|m| (m.key.as_str(), m.value.as_str()))
        .collect()
}

/// The header's line and the first data line.
fn lines_of(r: &TableRead) -> (Option<usize>, usize) {
    (r.layout.header_line, r.layout.first_data_line)
}

/// A preamble line of numbers with fewer fields than the table is
/// metadata, not the first data row.
#[test]
fn a_short_preamble_line_of_numbers_is_metadata() {
    let text = "1;2\n3;4\nt;x;y\n0;1;2\n1;2;3\n";
    let r = read_table(text, &ReadOptions::default()).unwrap();
    assert_eq!(lines_of(&r), (Some(3), 4));
    assert_eq!(r.table.columns, [[0.0, 1.0], [1.0, 2.0], [2.0, 3.0]]);
    let m = metadata(&r);
    assert_eq!(m, [("1", "2"), ("3", "4")]);
}

/// A key/value preamble line of a number (`Rate;1000`) above the header is
/// metadata, not data: a row followed by a line of names and a row is not
/// where the data start.
#[test]
fn a_rate_line_above_the_header_is_metadata() {
    let text = "Machine: NMV5000\nRate;1000\nt;x\n0;1\n1;2\n2;3\n";
    let r = read_table(text, &ReadOptions::default()).unwrap();
    assert_eq!(lines_of(&r), (Some(3), 4));
    assert_eq!(r.table.names, ["t", "x"]);
    assert_eq!(r.table.columns, [[0.0, 1.0, 2.0], [1.0, 2.0, 3.0]]);
    let m = metadata(&r);
    assert_eq!(m, [("Machine", "NMV5000"), ("Rate", "1000")]);
    // the same above a header of three: a line of three numbers too
    let r = read_table("1;2;3\nt;x;y\n0;1;2\n1;2;3\n", &ReadOptions::default()).unwrap();
    assert_eq!(r.layout.header_line, Some(2));
    assert_eq!(r.layout.metadata[0].value, "2 3");
}

/// A data row has at least half its fields numbers: one number in three
/// fields is no row of numbers, and the refusal says so at line 2.
#[test]
fn a_row_needs_half_its_fields_numbers() {
    let e = read_table(
        "t;Status;Note\n0;ok;a\n1;ok;b\n2;ok;c\n",
        &ReadOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("line 2: no row of numbers found"), "{e}");
    // two in three is a row: the text column is ignored
    let r = read_table("t;x;Note\n0;1;a\n1;2;b\n", &ReadOptions::default()).unwrap();
    assert_eq!(r.table.names, ["t", "x"]);
}

/// A sample period must be above 0 s and at most 1e4 s; the refusal names
/// the option and the header's line.
#[test]
fn a_sample_period_of_zero_is_refused() {
    let text = "a,b\n1,2\n3,4\n";
    for (dt, ok) in [
        (0.0, false),
        (-0.0, false),
        (1e-9, true),
        (1e4, true),
        (1.0001e4, false),
    ] {
        let opts = ReadOptions {
            sample_period: Some(dt),
            ..ReadOptions::default()
        };
        match read_table(text, &opts) {
            Ok(r) => assert!(ok && r.table.columns[2] == [0.0, dt], "{dt}"),
            Err(e) => assert!(
                !ok && e.to_string().starts_with(&format!(
                    "line 1: option samplePeriod: {dt} s is not a sample period"
                )),
                "{dt}: {e}"
            ),
        }
    }
}
