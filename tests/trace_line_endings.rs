//! Ball-bar and servo traces are read the same whatever the line endings
//! (LF, CRLF, CR alone), with a UTF-8 byte-order mark and with a trailing
//! Ctrl-Z; any other control character is refused with its line and
//! column (in characters), and a text over the budget is refused before it
//! is read.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::ballbar::{parse_ballbar_trace, ParseOptions};
use mtmotion::trace::Table;

fn ballbar_lf() -> String {
    let mut t = String::from("angle [deg],deviation [um]\n");
    for i in 0..=36 {
        t += &format!("{},{}\n", i * 10, 2.0 + (i as f64 * 0.3).sin());
    }
    for i in (0..36).rev() {
        t += &format!("{},{}\n", i * 10, -1.0 + (i as f64 * 0.2).cos());
    }
    t
}

fn variants(lf: &str) -> Vec<(&'static str, String)> {
    vec![
        ("CRLF", lf.replace('\n', "\r\n")),
        ("CR", lf.replace('\n', "\r")),
        ("BOM", format!("\u{feff}{lf}")),
        ("Ctrl-Z", format!("{lf}\u{1a}")),
        (
            "BOM+CR+Ctrl-Z",
            format!("\u{feff}{}\u{1a}\u{1a}", lf.replace('\n', "\r")),
        ),
    ]
}

#[test]
fn ballbar_trace_reads_the_same_with_every_line_ending() {
    let lf = ballbar_lf();
    let want = parse_ballbar_trace(&lf, ParseOptions::default()).unwrap();
    assert_eq!(want.runs.len(), 2);
    for (name, text) in variants(&lf) {
        let got = parse_ballbar_trace(&text, ParseOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(got, want, "{name}");
    }
}

#[test]
fn servo_trace_reads_the_same_with_every_line_ending() {
    let lf = "time [ms]\tX [mm]\tC [deg]\n0\t1.5\t0\n1\t1.6\t0.1\n2\t1.7\t0.2\n";
    let want = Table::parse(lf).unwrap();
    assert_eq!(want.lines, vec![2, 3, 4]);
    for (name, text) in variants(lf) {
        assert_eq!(Table::parse(&text).unwrap(), want, "{name}");
    }
}

#[test]
fn other_control_characters_name_their_line_and_column() {
    for (text, want) in [
        (
            "t,x\n0,1\n1,2\u{7}\n2,3\n",
            "line 3, column 4: control character U+0007 is not allowed in a trace; save it as plain text (CSV or TSV)",
        ),
        (
            "t,x\r0,1\r1\u{c},2\r2,3\r",
            "line 3, column 2: control character U+000C is not allowed in a trace; save it as plain text (CSV or TSV)",
        ),
        // Ctrl-Z is only an end-of-file mark at the very end.
        (
            "t,x\n0,1\u{1a}\n1,2\n",
            "line 2, column 4: control character U+001A is not allowed in a trace; save it as plain text (CSV or TSV)",
        ),
        (
            "\u{feff}t,x\n0,1\n\u{feff}\u{1b}1,2\n2,3\n",
            "line 3, column 2: control character U+001B is not allowed in a trace; save it as plain text (CSV or TSV)",
        ),
    ] {
        assert_eq!(Table::parse(text).unwrap_err().to_string(), want);
    }
    let e = parse_ballbar_trace(
        "angle,deviation\n0,1\n10,\u{8}2\n20,3\n",
        ParseOptions::default(),
    );
    assert!(e
        .unwrap_err()
        .to_string()
        .starts_with("line 3, column 4: control character U+0008"));
}

#[test]
fn a_trace_over_the_budget_is_refused_before_it_is_read() {
    let rows = "0,1\n".repeat(mtmotion::budget::MAX_LINES + 1);
    let text = format!("angle,deviation\n{rows}");
    let e = parse_ballbar_trace(&text, ParseOptions::default()).unwrap_err();
    assert_eq!(
        e.to_string(),
        "trace: 100002 lines, more than the limit of 100000; split the file into parts and run each"
    );
}
