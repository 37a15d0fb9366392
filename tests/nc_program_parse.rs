//! Proves the NC interpreter and writer: every error case names
//! its line and column and says what was expected; warnings are raised for
//! ignored words; and parse → write → parse gives the same segments back
//! (including G91, G20, R arcs over 180°, full circles, dwells, rotary words).

use mtmotion::nc::program::{parse, Motion, Program};

fn err_at(src: &str, line: usize, column: usize, needle: &str) {
    let e = parse(src).expect_err(src);
    assert_eq!((e.line, e.column), (line, column), "{src}: {e}");
    assert!(e.message.contains(needle), "{src}: {e}");
    assert!(e
        .to_string()
        .starts_with(&format!("line {line}, column {column}:")));
}

#[test]
fn every_error_case_names_line_column_and_expectation() {
    // An arc without a centre.
    err_at("G0 X0 Y0\nG2 X10 Y0 F100", 2, 4, "expected I/J or R");
    // An inconsistent radius: R too small, I/J off the circle.
    err_at("G0 X0 Y0\nG3 X10 Y0 R4 F100", 2, 11, "inconsistent radius");
    err_at(
        "G0 X0 Y0\nG3 X10 Y0 I5.2 J0 F100",
        2,
        11,
        "inconsistent radius",
    );
    // Full circle by R.
    err_at("G0 X0 Y0\nG2 X0 Y0 R5 F100", 2, 10, "full circle");
    // A missing feed and a zero feed on a cutting move.
    err_at("G0 X0\nG1 X5", 2, 4, "expected an F word");
    err_at("G1 X5 F0", 1, 7, "feed is zero");
    err_at("G3 X5 Y5 R5 F0", 1, 13, "feed is zero");
    // A bad number (from the lexer) and a letter without a number.
    err_at("G1 X1.2.3 F100", 1, 5, "not a valid number");
    err_at("G1 X F100", 1, 4, "expected a number");
    // Axis words with no motion mode; two motion codes; a cycle.
    err_at("X10 Y10", 1, 1, "no motion mode");
    err_at("G1 G2 X1 F1", 1, 4, "two motion codes");
    err_at("G87 X1 Y1 Z-1 R1 F100", 1, 1, "back boring");
    // Dwell without a time, negative feed.
    err_at("G4", 1, 1, "expected X (seconds) or P");
    err_at("G1 X1 F-5", 1, 7, "negative feed");
}

#[test]
fn ignored_words_are_warnings_with_columns() {
    let p = parse("T1 M6\nS10000 M3\nG41 D1 G1 X1 F100 Q5").unwrap();
    let w: Vec<(usize, usize)> = p.warnings.iter().map(|w| (w.line, w.column)).collect();
    assert_eq!(w, vec![(1, 1), (1, 4), (2, 1), (2, 8), (3, 1), (3, 19)]);
    assert!(p.warnings[5].message.contains("unknown word Q5"));
    // The D word belongs to the G41 (no warning of its own); without a
    // toolRadii entry for D1 the stretch is the programmed path, warned.
    assert!(p.warnings[4]
        .message
        .contains("cutter compensation G41 D1: no tool radius"));
}

const PROGRAM: &str = "%
O1000 (round-trip sample)
N10 G90 G17 G21 G40 G49 G80
N20 T1 M6
N30 S10000 M3 ; spindle
N40 G0 X-10. Y0 Z5. A0
N50 G1 Z-1. F500
N60 G1 X0 F2000
N70 G2 X10. Y0 R5.
N80 G3 X20. Y10. R-10. (over 180)
N90 G2 X20. Y10. I-5. J0 (full circle)
N100 G91 G1 X5. Y-2.5 A15.
N110 G3 X-5. Y-5. I0 J-5.
N120 G90 G4 P100
N130 G20 G1 X1. Y0.5 F40.
N140 G4 X0.25
N150 G21 G18 G2 X35.4 Z-1. I5. K0 F1000
N160 G19 G3 Y7.7 Z4. J0 K5.
N170 G0 Z50. M5
%";

fn same_segments(a: &Program, b: &Program) {
    assert_eq!(a.segments.len(), b.segments.len());
    for (s, t) in a.segments.iter().zip(&b.segments) {
        let ds: f64 = (0..6)
            .map(|i| (s.start.get(i) - t.start.get(i)).abs())
            .fold(0.0, f64::max);
        let de: f64 = (0..6)
            .map(|i| (s.end.get(i) - t.end.get(i)).abs())
            .fold(0.0, f64::max);
        assert!(ds < 1e-4 && de < 1e-4, "line {}: {s:?} vs {t:?}", s.line);
        assert!((s.feed - t.feed).abs() < 1e-3, "line {}", s.line);
        assert_eq!(s.line, t.line);
        match (s.motion, t.motion) {
            (Motion::Arc(x), Motion::Arc(y)) => {
                assert!(
                    (x.radius - y.radius).abs() < 1e-4 && (x.sweep - y.sweep).abs() < 1e-6,
                    "line {}",
                    s.line
                );
                assert_eq!(x.plane, y.plane);
            }
            (Motion::Dwell { seconds: x }, Motion::Dwell { seconds: y }) => {
                assert!((x - y).abs() < 1e-12)
            }
            (x, y) => assert_eq!(x, y, "line {}", s.line),
        }
    }
}

#[test]
fn parse_write_parse_round_trip() {
    let p = parse(PROGRAM).unwrap();
    assert_eq!(p.segments.len(), 14);
    let text = p.write();
    let q = parse(&text).unwrap();
    same_segments(&p, &q);
    // Writing is idempotent once the program is absolute millimetres.
    assert_eq!(q.write(), text);
    // Lines, N numbers and comments survive.
    assert_eq!(text.lines().count(), PROGRAM.lines().count());
    assert!(text.contains("N80 G3 X20. Y10. R-10. (over 180)"));
    assert!(text.contains("N30 S10000 M3 (spindle)"));
    assert!(text.contains("N100 G90 G1 X25. Y7.5 A15."), "{text}");
    assert!(text.contains("N130 G21 G1 X25.4 Y12.7 F1016."), "{text}");
}

#[test]
fn canonical_absolute_program_is_written_back_verbatim() {
    let src = "N10 G90 G17 G21\nN20 G0 X0 Y0\nN30 G1 X10. Y0 F2000 (cut)\nN40 G2 X20. Y0 R5.\nN50 G4 P100";
    assert_eq!(parse(src).unwrap().write(), src);
}

/// A binary file (here a PNG as a browser decodes it: its bytes ≥ 0x80 as
/// U+FFFD) gets one error at line 1 that names what it is, not one error
/// per line of its bytes; a program that mentions PNG in a comment is read.
#[test]
fn a_binary_file_is_one_named_error() {
    use mtmotion::nc::program::{parse_all, ParseOptions};
    let mut png = String::from("\u{fffd}PNG\r\n\u{1a}\n\0\0\0\rIHDR\0\0\u{1}\0");
    for i in 0..400 {
        png.push_str(&format!("\u{fffd}x{i}\u{fffd}\u{3}\n"));
    }
    let e = parse_all(&png, &ParseOptions::default()).unwrap_err();
    assert_eq!(
        e.errors.len(),
        1,
        "{:?}",
        &e.errors[..2.min(e.errors.len())]
    );
    assert_eq!((e.errors[0].line, e.errors[0].column), (1, 1));
    assert!(
        e.errors[0].message.contains("a PNG image")
            && e.errors[0].message.contains("not an NC program"),
        "{}",
        e.errors[0].message
    );
    let pdf = "%PDF-1.7\n%\u{fffd}\u{fffd}\n1 0 obj\n";
    let e = parse_all(pdf, &ParseOptions::default()).unwrap_err();
    assert!(
        e.errors[0].message.contains("a PDF document"),
        "{}",
        e.errors[0].message
    );
    let p = parse_all(
        "(PNG drawing, 12/2026)\nG21 G90 G1 X1 Y2 F100\nM30\n",
        &ParseOptions::default(),
    )
    .unwrap();
    assert_eq!(p.segments.len(), 1);
}
