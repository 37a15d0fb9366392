//! Ball-bar traces are read from CSV/TSV with angle + deviation or X/Y
//! columns, split into CCW and CW runs, and malformed files are refused with
//! a message naming the line (and column) to fix.

use mtmotion::ballbar::{circular_test, parse_ballbar_trace, Direction, ParseOptions};

fn opts() -> ParseOptions {
    ParseOptions::default()
}

#[test]
fn renishaw_like_angle_deviation_file() {
    let mut s = String::from("Ballbar test 2024-01-01\nRadius 100 mm\nAngle(deg)\tDeviation(um)\n");
    for i in 0..=360 {
        s += &format!(
            "{}\t{:.3}\n",
            i,
            2.0 * (2.0 * (i as f64).to_radians()).sin()
        );
    }
    for i in (0..360).rev() {
        s += &format!(
            "{}\t{:.3}\n",
            i,
            2.0 * (2.0 * (i as f64).to_radians()).sin() + 1.0
        );
    }
    let t = parse_ballbar_trace(&s, opts()).unwrap();
    assert_eq!(t.runs.len(), 2);
    assert_eq!(
        (t.runs[0].direction, t.runs[1].direction),
        (Direction::Ccw, Direction::Cw)
    );
    assert_eq!(t.runs[0].lines[0], 4);
    assert_eq!(t.nominal_radius, 100.0);
    assert!(t.feed.is_none());
    let r = circular_test(&t).unwrap();
    assert!((r.runs[0].g_um - 4.0).abs() < 0.01, "{:?}", r.runs[0]);
    assert!((r.h_um.unwrap() - 1.0).abs() < 0.01, "{:?}", r.h_um);
}

#[test]
fn direction_column_and_units_in_mm() {
    let mut s = String::from("theta_rad;dev_mm;dir\n");
    for i in 0..20 {
        s += &format!("{};0.001;1\n", i as f64 * 0.1);
    }
    for i in 0..20 {
        s += &format!("{};0.002;-1\n", 1.9 - i as f64 * 0.1);
    }
    let t = parse_ballbar_trace(
        &s,
        ParseOptions {
            nominal_radius: Some(150.0),
            feed: Some(500.0),
        },
    )
    .unwrap();
    assert_eq!(t.runs.len(), 2);
    assert_eq!(t.runs[1].deviation[0], 0.002);
    assert!((t.runs[0].angle[19] - 1.9).abs() < 1e-12);
    assert_eq!((t.nominal_radius, t.feed), (150.0, Some(500.0)));
}

#[test]
fn malformed_traces_name_the_line() {
    let cases: [(&str, &str); 6] = [
        (
            "angle,deviation\n0,1\n1,2\n2,oops\n",
            "line 4, column 2 ('deviation'): 'oops' is not a number",
        ),
        (
            "angle,deviation\n0,1\n1,2,3\n",
            "line 3: 3 fields, expected 2 as in the header",
        ),
        (
            "angle,deviation\n",
            "line 1: header found, but no data rows follow",
        ),
        ("", "the trace is empty"),
        ("time,pos\n0,1\n", "no ball-bar columns found"),
        (
            "angle,deviation,direction\n0,1,1\n1,1,1\n2,1,2\n",
            "line 4: direction must be +1 (CCW) or -1 (CW), got 2",
        ),
    ];
    for (text, want) in cases {
        let e = parse_ballbar_trace(text, opts()).unwrap_err().to_string();
        assert!(e.starts_with(want), "{text:?}: {e}");
    }
    // Collinear X/Y data cannot define a nominal circle.
    let e = parse_ballbar_trace("x,y\n0,0\n1,1\n2,2\n3,3\n4,4\n5,5\n6,6\n7,7\n", opts())
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("line 2"), "{e}");
    // Too short to be a run.
    let e = parse_ballbar_trace("angle,dev\n0,1\n5,1\n10,1\n", opts())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("line 2: the trace has no run of at least 8 points"),
        "{e}"
    );
}

#[test]
fn noise_at_a_standstill_does_not_split_runs() {
    let mut s = String::from("angle,dev\n");
    for i in 0..100 {
        let jitter = if i % 2 == 0 { 0.3 } else { -0.3 };
        s += &format!("{},0\n", i as f64 * 3.6 + jitter);
    }
    let t = parse_ballbar_trace(&s, opts()).unwrap();
    assert_eq!(t.runs.len(), 1);
}
