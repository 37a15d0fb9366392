//! LinuxCNC's splines (G5.1 quadratic B-spline, G5.2 … G5.3 NURBS block)
//! are simulated as the chords of their curve, within the chordal
//! tolerance, on programs written in LinuxCNC's form: analytic properties
//! of the curves (the manual's parabola through the origin, its end
//! points and tangents; a rational quadratic that is an exact quarter
//! circle), the feed (and G93's whole-curve time), G91/G92/inch, and a
//! located refusal for every form the manual or LinuxCNC's interpreter
//! refuses or reads differently. `tests/nc_linuxcnc_oracle.rs` compares
//! the same curves with LinuxCNC's own evaluation
//! (`tests/nc_programs/splines.ngc`, the corpus's `linuxcnc_systems`).

use mtmotion::nc::nurbs::{distance_to_chord, CHORD_TOLERANCE};
use mtmotion::nc::program::{parse, Motion, Program, Segment};

/// The XY polyline of the segments of `line`, from the start of its first.
fn polyline(p: &Program, line: usize) -> Vec<[f64; 2]> {
    let segs: Vec<&Segment> = p.segments.iter().filter(|s| s.line == line).collect();
    assert!(!segs.is_empty(), "no segments on line {line}");
    let mut v = vec![[segs[0].start.x, segs[0].start.y]];
    v.extend(segs.iter().map(|s| [s.end.x, s.end.y]));
    v
}

/// Largest distance of `curve(t)`, t ∈ [0, 1], from the polyline.
fn deviation(poly: &[[f64; 2]], curve: impl Fn(f64) -> [f64; 2]) -> f64 {
    (0..=5000)
        .map(|i| {
            let q = curve(i as f64 / 5000.0);
            poly.windows(2)
                .map(|w| distance_to_chord(q, w[0], w[1]))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

fn bezier(p0: [f64; 2], p1: [f64; 2], p2: [f64; 2]) -> impl Fn(f64) -> [f64; 2] {
    move |t| {
        let (a, b, c) = ((1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t);
        [
            a * p0[0] + b * p1[0] + c * p2[0],
            a * p0[1] + b * p1[1] + c * p2[1],
        ]
    }
}

#[test]
fn the_manuals_parabola_runs_through_the_origin_with_its_end_tangents() {
    let p = parse("G21 G17 G90\nG0 X-2 Y4 Z1\nG1 Z0 F300\nG5.1 X2 I2 J-8\nM2").unwrap();
    let poly = polyline(&p, 4);
    assert_eq!(poly[0], [-2.0, 4.0]);
    assert_eq!(*poly.last().unwrap(), [2.0, 4.0]);
    // the vertex (t = 1/2) is a chord end, exactly at the origin
    assert!(poly
        .iter()
        .any(|q| q[0].abs() < 1e-12 && q[1].abs() < 1e-12));
    let d = deviation(&poly, bezier([-2.0, 4.0], [0.0, -4.0], [2.0, 4.0]));
    assert!(d <= CHORD_TOLERANCE, "{d}");
    // first and last chords along the control polygon's legs
    let dir = |a: [f64; 2], b: [f64; 2]| (b[1] - a[1]).atan2(b[0] - a[0]);
    let n = poly.len();
    assert!((dir(poly[0], poly[1]) - dir([-2.0, 4.0], [0.0, -4.0])).abs() < 0.02);
    assert!((dir(poly[n - 2], poly[n - 1]) - dir([0.0, -4.0], [2.0, 4.0])).abs() < 0.02);
    for s in p.segments.iter().filter(|s| s.line == 4) {
        assert_eq!(s.motion, Motion::Linear);
        assert_eq!(
            (s.feed, s.start.z, s.end.z, s.fixed),
            (300.0, 0.0, 0.0, true)
        );
    }
    // and not needlessly fine: the parabola's second difference |P0 − 2P1 + P2|
    // = 16 needs 32 equal chords at 1 µm; bisection gives at most twice that
    assert!(n - 1 <= 128, "{}", n - 1);
}

#[test]
fn g91_g92_and_inch_place_the_curve_as_any_end_point() {
    // G91: X Y from the start; I J always from the start
    let p = parse("G0 X10 Y10\nG91 G5.1 X10 Y0 I5 J5 F100").unwrap();
    let poly = polyline(&p, 2);
    assert_eq!(*poly.last().unwrap(), [20.0, 10.0]);
    let d = deviation(&poly, bezier([10.0, 10.0], [15.0, 15.0], [20.0, 10.0]));
    assert!(d <= CHORD_TOLERANCE, "{d}");
    // G92 shifts the end, not I J; G20 scales all
    let p = parse("G0 X1 Y1\nG92 X0 Y0\nG5.1 X4 Y0 I2 J2 F100").unwrap();
    assert_eq!(*polyline(&p, 3).last().unwrap(), [5.0, 1.0]);
    let p = parse("G20 G0 X0 Y0\nG5.1 X1 Y0 I0.5 J0.5 F10").unwrap();
    let poly = polyline(&p, 2);
    assert_eq!(*poly.last().unwrap(), [25.4, 0.0]);
    let d = deviation(&poly, bezier([0.0, 0.0], [12.7, 12.7], [25.4, 0.0]));
    assert!(d <= CHORD_TOLERANCE, "{d}");
    assert!(p
        .segments
        .iter()
        .skip(1)
        .all(|s| (s.feed - 254.0).abs() < 1e-9));
}

#[test]
fn a_nurbs_block_of_weight_half_root_two_is_an_exact_quarter_circle() {
    let text =
        "G21 G17 G90\nG0 X25 Y0\nF600\nG5.2 X25 Y25 P0.7071067811865476\nX0 Y25 P1\nG5.3\nG1 X0 Y0";
    let p = parse(text).unwrap();
    let poly = polyline(&p, 6);
    assert_eq!(poly[0], [25.0, 0.0]);
    assert_eq!(*poly.last().unwrap(), [0.0, 25.0]);
    for q in &poly {
        assert!((q[0].hypot(q[1]) - 25.0).abs() < 1e-9, "{q:?}");
    }
    // every chord's sagitta within the tolerance
    for w in poly.windows(2) {
        let c = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
        let sagitta = 25.0 - (625.0 - c * c / 4.0).sqrt();
        assert!(sagitta <= CHORD_TOLERANCE * (1.0 + 1e-9), "{sagitta}");
    }
    // the control-point blocks do not move; the curve is the G5.3 line's
    assert!(p.segments.iter().all(|s| s.line != 4 && s.line != 5));
    assert!(p
        .segments
        .iter()
        .filter(|s| s.line == 6)
        .all(|s| s.feed == 600.0));
    // after G5.3 the next block names its motion
    assert!(parse(&text.replace("G1 X0 Y0", "X0 Y0"))
        .unwrap_err()
        .message
        .contains("no motion mode"));
}

#[test]
fn the_manuals_nurbs_example_ends_where_it_started() {
    let p = parse("G0 X0 Y0\nF10\nG5.2 P1 L3\nX0 Y1 P1\nX2 Y2 P1\nX2 Y0 P1\nX0 Y0 P2\nG5.3\nM2")
        .unwrap();
    let poly = polyline(&p, 8);
    assert_eq!((poly[0], *poly.last().unwrap()), ([0.0, 0.0], [0.0, 0.0]));
    // inside the control polygon's hull (0..2 × 0..2), touching X2 at the
    // knot between the middle spans: the midpoint of (2,2)–(2,0)
    let xmax = poly.iter().map(|q| q[0]).fold(0.0, f64::max);
    assert!((xmax - 2.0).abs() < 1e-12, "{xmax}");
    assert!(poly.contains(&[2.0, 1.0]));
    assert!(poly.iter().all(|q| q[1] >= -1e-12 && q[1] <= 2.0));
}

#[test]
fn under_g93_the_whole_curve_takes_one_over_f_minutes() {
    let p = parse("G0 X0 Y0\nG93 G5.1 X10 Y0 I5 J5 F2").unwrap();
    let minutes: f64 = p
        .segments
        .iter()
        .filter(|s| s.line == 2)
        .map(|s| s.length() / s.feed)
        .sum();
    assert!((minutes - 0.5).abs() < 1e-12, "{minutes}");
}

/// The cubic Bézier of `c`: P0 start, P1 P2 control points, P3 end.
fn bezier3(c: [[f64; 2]; 4]) -> impl Fn(f64) -> [f64; 2] {
    move |t| {
        let u = 1.0 - t;
        let w = [u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t];
        let mut q = [0.0; 2];
        for (k, p) in c.iter().enumerate() {
            q[0] += w[k] * p[0];
            q[1] += w[k] * p[1];
        }
        q
    }
}

/// Distance of `v` from `curve(t)`, t ∈ [0, 1]: the nearest of 4001
/// samples, refined by a ternary search in the samples around it.
fn distance_to_curve(v: [f64; 2], curve: &impl Fn(f64) -> [f64; 2]) -> f64 {
    let d = |t: f64| {
        let q = curve(t.clamp(0.0, 1.0));
        (q[0] - v[0]).hypot(q[1] - v[1])
    };
    let n = 4000.0;
    let k = (0..=4000).min_by(|&a, &b| d(a as f64 / n).total_cmp(&d(b as f64 / n)));
    let t = k.unwrap_or(0) as f64 / n;
    let (mut lo, mut hi) = (t - 1.0 / n, t + 1.0 / n);
    for _ in 0..200 {
        let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if d(m1) < d(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    d((lo + hi) / 2.0)
}

/// The chords of `line` stand for the cubic Bézier `c`: they start at P0
/// and end at P3, every vertex lies on the curve (within 1e-9 mm), and
/// the curve stays within the chordal tolerance of them.
fn assert_cubic(p: &Program, line: usize, c: [[f64; 2]; 4]) {
    let poly = polyline(p, line);
    let curve = bezier3(c);
    let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9;
    assert!(close(poly[0], c[0]), "line {line}: {:?}", poly[0]);
    assert!(close(*poly.last().unwrap(), c[3]), "line {line}");
    for v in &poly {
        let e = distance_to_curve(*v, &curve);
        assert!(
            e < 1e-9,
            "line {line}: vertex {v:?} is {e} mm off the curve"
        );
    }
    let d = deviation(&poly, curve);
    assert!(d <= CHORD_TOLERANCE && d > 0.0, "line {line}: {d}");
    for s in p.segments.iter().filter(|s| s.line == line) {
        assert_eq!((s.motion, s.fixed), (Motion::Linear, true));
    }
}

#[test]
fn g5_is_the_cubic_bezier_of_its_control_points() {
    // The manual's curvy N moved to X3 Y2, then its continuation without
    // I J (P1 = start − the previous P Q), then a series in G91 (I J P Q
    // are offsets either way), with a dwell inside the series.
    let p = parse(
        "G21 G17 G90\nG0 X3 Y2\nG5 I0 J3 P0 Q-3 X4 Y3 F120\nG5 P0.5 Q-3 X5 Y4.5\nG4 P0.2\nG5 P1 Q-2 X7.25 Y3.5\nG91 G5 I2 J-1 P-1.5 Q2 X10 Y-2\nG5 P2 Q2 X-6 Y-7\nM2",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_cubic(&p, 3, [[3.0, 2.0], [3.0, 5.0], [4.0, 0.0], [4.0, 3.0]]);
    assert_cubic(&p, 4, [[4.0, 3.0], [4.0, 6.0], [5.5, 1.5], [5.0, 4.5]]);
    assert_cubic(&p, 6, [[5.0, 4.5], [4.5, 7.5], [8.25, 1.5], [7.25, 3.5]]);
    assert_cubic(
        &p,
        7,
        [[7.25, 3.5], [9.25, 2.5], [15.75, 3.5], [17.25, 1.5]],
    );
    assert_cubic(
        &p,
        8,
        [[17.25, 1.5], [18.75, -0.5], [13.25, -3.5], [11.25, -5.5]],
    );
    // the continued curve starts in the end direction of the one before
    let dir = |a: [f64; 2], b: [f64; 2]| (b[1] - a[1]).atan2(b[0] - a[0]);
    let (l3, l4) = (polyline(&p, 3), polyline(&p, 4));
    let n = l3.len();
    assert!((dir(l3[n - 2], l3[n - 1]) - dir(l4[0], l4[1])).abs() < 0.02);
    assert!(p
        .segments
        .iter()
        .filter(|s| s.line != 2 && s.line != 5)
        .all(|s| s.feed == 120.0));
    // inch: every number × 25.4
    let q = parse("G20 G17 G90\nG0 X0.5 Y0.25\nG5 I0.4 J0.6 P-0.3 Q0.5 X1.75 Y0.5 F20\nG5 P0.2 Q-0.4 X2.5 Y1.25\nM2").unwrap();
    let m = |x: f64, y: f64| [x * 25.4, y * 25.4];
    assert_cubic(
        &q,
        3,
        [m(0.5, 0.25), m(0.9, 0.85), m(1.45, 1.0), m(1.75, 0.5)],
    );
    assert_cubic(
        &q,
        4,
        [m(1.75, 0.5), m(2.05, 0.0), m(2.7, 0.85), m(2.5, 1.25)],
    );
    assert!(q
        .segments
        .iter()
        .filter(|s| s.line == 3)
        .all(|s| (s.feed - 508.0).abs() < 1e-9));
}

/// The first error of `text`: (line, column, message).
fn refused(text: &str) -> (usize, usize, String) {
    let e = parse(text).unwrap_err();
    (e.line, e.column, e.message)
}

#[test]
fn every_form_linuxcnc_refuses_or_reads_otherwise_is_a_located_error() {
    let cases: &[(&str, (usize, usize), &str)] = &[
        (
            "G0 X0 Y0\nG5.1 X1 Y1 Z1 I1 J0 F9",
            (2, 12),
            "Z1 on a G5.1 spline block: a spline moves X and Y only",
        ),
        ("G0 X0 Y0\nG5.1 X1 Y1 I1 F9", (2, 1), "both I and J"),
        ("G0 X0 Y0\nG5.1 X1 Y1 I0 J0 F9", (2, 12), "I0 J0"),
        ("G18 G0 X0 Y0\nG5.1 X1 Y1 I1 J0 F9", (2, 1), "expected G17"),
        (
            "G0 X0 Y0\nG41 D1 G1 X1 F9\nG5.1 X2 Y1 I1 J0",
            (3, 1),
            "cutter compensation",
        ),
        (
            "G0 X0 Y0\nG68 X0 Y0 R30\nG5.1 X2 Y1 I1 J0 F9",
            (3, 1),
            "G68",
        ),
        (
            "G0 X0 Y0\nG5.1 X2 Y1 I1 J0 F9\nX3 Y2 I1 J0",
            (3, 1),
            "write G5.1, G1 or G0",
        ),
        ("G0 X0 Y0\nG5.1 X2 Y1 I1 J0 F9,R1", (2, 20), "corner word"),
        ("G0 X0 Y0\nG5.3", (2, 1), "without a NURBS block"),
        (
            "G0 X0 Y0 F9\nG5.2 X1 Y1 P1\nX2 Y0 P1\nM2",
            (2, 1),
            "never closes",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 X1 Y1 P1\nG1 X2 Y0\nG5.3",
            (3, 1),
            "inside the G5.2 NURBS block of line 2",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 X1 Y1 P1\nG4 P1\nG5.3",
            (3, 1),
            "inside the G5.2",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 X1 Y1 P1\nX2 Y0\nG5.3",
            (3, 1),
            "without a weight",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 X1 Y1 P0\nX2 Y0 P1\nG5.3",
            (2, 12),
            "above 0",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 X1 Y1 P1\nX2 P1\nG5.3",
            (3, 1),
            "both X and Y",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 X1 Y1 P1\nP2\nG5.3",
            (3, 1),
            "only the G5.2 block",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 L2 X1 Y1 P1\nX2 Y0 P1\nG5.3",
            (2, 6),
            "from 3 to 10",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 L4.5 X1 Y1 P1\nX2 Y0 P1\nG5.3",
            (2, 6),
            "whole number",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 L4 X1 Y1 P1\nX2 Y0 P1\nG5.3",
            (4, 1),
            "3 control points (its start point included) for order L4",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 X1 Y1 P1\nX2 Y0 P1\nG5.3 X3 Y3",
            (4, 6),
            "only ends the NURBS block",
        ),
        (
            "G0 X0 Y0 F9\nG5.2 X1 Y1 Z2 P1\nX2 Y0 P1\nG5.3",
            (2, 12),
            "Z2 on a G5.2 spline block: a spline moves X and Y only",
        ),
        (
            "G0 X0 Y0\nG5 X1 Y1 P1 Q0 F9",
            (2, 1),
            "G5 without I and J starts no series",
        ),
        (
            "G0 X0 Y0\nG5 X1 Y1 I1 J0 P1 Q0 F9\nG1 X2\nG5 X3 Y1 P1 Q0",
            (4, 1),
            "G5 without I and J starts no series",
        ),
        (
            "G0 X0 Y0\nG5 X1 Y1 I1 J0 P1 Q0 F9\nG5 X3 Y1 J2 P1 Q0",
            (3, 10),
            "G5 with J2 alone",
        ),
        ("G0 X0 Y0\nG5 X1 Y1 I1 J0 P1 F9", (2, 1), "both P and Q"),
        (
            "G0 X0 Y0\nG5 X1 Y1 I1 J0 P1 Q0 F9\nX3 Y2 P1 Q0",
            (3, 1),
            "write G5, G1 or G0",
        ),
        (
            "G18 G0 X0 Y0\nG5 X1 Y1 I1 J0 P1 Q0 F9",
            (2, 1),
            "G5 spline in the G18 plane",
        ),
        (
            "G0 X0 Y0\nG5 X1 Y1 Z3 I1 J0 P1 Q0 F9",
            (2, 10),
            "Z3 on a G5 spline block",
        ),
        (
            "G0 X0 Y0\nG1 G5.1 X1 Y1 I1 J0 F9",
            (2, 4),
            "two motion codes",
        ),
        ("G0 X0 Y0\nG5.1 X1 Y1 I1 J0", (2, 1), "without a feed"),
        (
            "G0 X0 Y0 F9\nG5.1 X100000000 Y0 I50000000 J50000000",
            (2, 1),
            "more than 100000 chords",
        ),
    ];
    for (text, at, phrase) in cases {
        let (line, column, msg) = refused(text);
        assert_eq!((line, column), *at, "{text}: {msg}");
        assert!(msg.contains(phrase), "{text}: {msg}");
    }
}

#[test]
fn unused_words_on_a_spline_block_are_warned_about() {
    let p = parse("G0 X0 Y0\nG5.1 X1 Y1 I1 J0 K3 F9\nG5.2 X2 Y2 P1 I4\nX3 Y1 P1\nG5.3").unwrap();
    let w: Vec<&str> = p.warnings.iter().map(|w| w.message.as_str()).collect();
    assert!(
        w.iter()
            .any(|m| m.starts_with("K3 has no meaning on a G5.1")),
        "{w:?}"
    );
    assert!(
        w.iter()
            .any(|m| m.starts_with("I4 has no meaning on a G5.2")),
        "{w:?}"
    );
    assert!(!w.iter().any(|m| m.contains("P1")), "{w:?}");
}
