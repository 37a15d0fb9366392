//! Ball-bar traces are read from CSV/TSV with angle + deviation or X/Y
//! columns, split into CCW and CW runs, and malformed files are refused with
//! a message naming the line (and column) to fix.

use mtmotion::ballbar::{circular_test, parse_ballbar_trace, Direction, ParseOptions, PlanePoint};

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
            centre: None,
            ..ParseOptions::default()
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

/// An X/Y trace of a circle of R 121.5 mm about (250.010, −79.996) in
/// machine coordinates, 300° from 17°, with a 2 µm order-3 error.
fn xy_arc() -> String {
    let mut s = String::from("X [mm],Y [mm]\n");
    for i in 0..=300 {
        let a = (17.0 + i as f64).to_radians();
        let r = 121.5 + 0.002 * (3.0 * a).sin();
        s += &format!(
            "{:.6},{:.6}\n",
            250.010 + r * a.cos(),
            -79.996 + r * a.sin()
        );
    }
    s
}

#[test]
fn xy_trace_keeps_the_offset_from_a_given_centre() {
    // About the programmed centre (250, −80): the 10/4 µm offset stays in
    // the deviations, and the trace says the centre was given.
    let o = ParseOptions {
        centre: Some(PlanePoint { x: 250.0, y: -80.0 }),
        nominal_radius: Some(121.5),
        ..opts()
    };
    let t = parse_ballbar_trace(&xy_arc(), o).unwrap();
    let c = t.centre.unwrap();
    assert!(c.given && c.point == PlanePoint { x: 250.0, y: -80.0 });
    let r = &t.runs[0];
    // Δ(θ) ≈ e_x cos θ + e_y sin θ + 2 µm sin 3θ about the given centre.
    for (a, d) in r.angle.iter().zip(&r.deviation) {
        let want = 0.010 * a.cos() + 0.004 * a.sin() + 0.002 * (3.0 * a).sin();
        assert!((d - want).abs() < 2e-6, "{a}: {d} vs {want}");
    }
    // Without a centre: the trace's own LSC, which removes the offset and
    // says so.
    let t = parse_ballbar_trace(&xy_arc(), opts()).unwrap();
    let c = t.centre.unwrap();
    assert!(!c.given);
    assert!((c.point.x - 250.010).abs() < 2e-3 && (c.point.y + 79.996).abs() < 2e-3);
    // Angle/deviation traces have no X/Y centre.
    let t = parse_ballbar_trace(
        "angle,dev\n0,1\n10,1\n20,1\n30,1\n40,1\n50,1\n60,1\n70,1\n",
        opts(),
    )
    .unwrap();
    assert!(t.centre.is_none());
    let bad = ParseOptions {
        centre: Some(PlanePoint {
            x: f64::NAN,
            y: 0.0,
        }),
        ..opts()
    };
    let e = parse_ballbar_trace(&xy_arc(), bad).unwrap_err().to_string();
    assert!(e.starts_with("centre: expected finite x and y"), "{e}");
}
