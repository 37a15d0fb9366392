//! Cutter radius compensation G41/G42/G40 (`src/nc/cutter.rs`,
//! `src/nc/cutter_path.rs`) against oracles written here independently:
//! - a 40 mm square run counter-clockwise: with G41 (tool inside) the
//!   tool centre runs the square [r, 40 − r]² with sharp corners (the
//!   intersections); with G42 (outside) the lines of [−r, 40 + r]² joined
//!   by quarter arcs of radius r about the programmed corners; start-up
//!   and cancel run straight from and to the programmed points (type A);
//! - a full circle of radius R: R − r or R + r by side and direction, same
//!   centre, the helical Z passing through;
//! - the same square in G18 and G19 maps onto the G17 result;
//! - a property test: for random convex contours of lines and arcs (a
//!   polygon inscribed in a circle, some edges replaced by arcs of that
//!   circle), every sampled point of the offset path (elements and corner
//!   arcs, away from the start-up/cancel corner) is at distance r from the
//!   programmed contour (nearest point, computed here) within 1e-9 mm;
//! - random programs of lines, consistent arcs, plunges and G41/G42/G40
//!   (about 200 of 256 cases offset, the rest refused with a located
//!   error): the path is continuous (1e-9 mm) and each arc's centre,
//!   radius and sweep run from its start to its end (1e-6 mm);
//! - the corpus files linuxcnc_comp.ngc (G17 and G18: every offset point
//!   at r from the contour, 1e-9 mm) and cncjs_helical-thread-milling
//!   (arcs R + r, programmed Z);
//! - without a radius: the programmed path and one warning per stretch;
//! - the located refusals.
//!
//! Tolerances: 1e-9 mm on points (the geometry is closed-form in f64).
#![cfg(not(target_arch = "wasm32"))]

#[path = "support/corpus.rs"]
mod corpus;

use std::f64::consts::PI;

use mtmotion::nc::cutter::ToolRadii;
use mtmotion::nc::program::{parse_with, Motion, ParseOptions, Program};
use mtmotion::nc::summary::warning_kind;
use proptest::prelude::*;

const TOL: f64 = 1e-9;

fn opts(radii: &str) -> ParseOptions {
    ParseOptions {
        tool_radii: ToolRadii::parse(radii).unwrap(),
        ..Default::default()
    }
}

fn run(text: &str, radii: &str) -> Program {
    parse_with(text, &opts(radii)).unwrap_or_else(|e| panic!("{e}"))
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < TOL)
}

fn square(code: &str) -> String {
    format!("G0 X20 Y-10\n{code} D1 G1 X20 Y0 F500\nX40\nY40\nX0\nY0\nX20\nG40 X20 Y-10\nM30")
}

#[test]
fn g41_inside_square_is_the_inner_square_with_sharp_corners() {
    let r = 2.5;
    let p = run(&square("G41"), "D1=2.5");
    let ends: Vec<[f64; 3]> = p.segments.iter().map(|s| s.end.p()).collect();
    let want = [
        [20.0, -10.0, 0.0],
        [20.0, r, 0.0],
        [40.0 - r, r, 0.0],
        [40.0 - r, 40.0 - r, 0.0],
        [r, 40.0 - r, 0.0],
        [r, r, 0.0],
        [20.0, r, 0.0],
        [20.0, -10.0, 0.0],
    ];
    assert_eq!(ends.len(), want.len(), "{ends:?}");
    for (e, w) in ends.iter().zip(&want) {
        assert!(close(*e, *w), "{e:?} != {w:?}");
    }
    assert!(p.segments[1..].iter().all(|s| s.fixed));
    assert_eq!(p.cutter.len(), 1);
    assert_eq!(p.cutter[0].radius, Some(r));
    assert!(p
        .warnings
        .iter()
        .all(|w| warning_kind(&w.message) != "cutter compensation"));
}

#[test]
fn g42_outside_square_has_quarter_arcs_about_the_corners() {
    let r = 2.5;
    let p = run(&square("G42"), "D1=2.5");
    // start-up, bottom to the corner, then per corner an arc and a side.
    let corners = [[40.0, 0.0], [40.0, 40.0], [0.0, 40.0], [0.0, 0.0]];
    let s = &p.segments;
    assert!(close(s[1].end.p(), [20.0, -r, 0.0]));
    assert!(close(s[2].end.p(), [40.0, -r, 0.0]));
    for (k, c) in corners.iter().enumerate() {
        let arc = &s[3 + 2 * k];
        let Motion::Arc(a) = arc.motion else {
            panic!("segment {} is not an arc: {arc:?}", 3 + 2 * k)
        };
        assert!((a.center[0] - c[0]).abs() < TOL && (a.center[1] - c[1]).abs() < TOL);
        assert!((a.radius - r).abs() < TOL && (a.sweep - PI / 2.0).abs() < TOL);
        let (q0, q1) = (arc.point_at(0.0), arc.point_at(1.0));
        assert!(
            close(q0, arc.start.p()) && close(q1, arc.end.p()),
            "{arc:?}"
        );
    }
    assert!(close(s[4].end.p(), [40.0 + r, 40.0, 0.0]));
    assert!(close(s[6].end.p(), [0.0, 40.0 + r, 0.0]));
    assert!(close(s[8].end.p(), [-r, 0.0, 0.0]));
    assert!(close(s[10].end.p(), [20.0, -r, 0.0]));
    assert!(close(s[11].end.p(), [20.0, -10.0, 0.0]));
    assert_eq!(s.len(), 12);
    let t = mtmotion::nc::summary::summarize(&p, 6000.0);
    let perimeter = 4.0 * 40.0 + 2.0 * PI * r;
    let expected = 500f64.sqrt() + (10.0 - r) + perimeter + (10.0 - r);
    assert!(
        (t.total_length - expected).abs() < 1e-9,
        "{} vs {expected}",
        t.total_length
    );
}

fn circle(code: &str, g: u32) -> String {
    format!("G0 X0 Y0 Z0\n{code} D3 G1 X20 F400\nG{g} X20 Y0 Z-2 I-20 J0\nG40 G1 X0 Y0\nM30")
}

#[test]
fn full_circle_offsets_to_r_minus_or_plus_and_keeps_z() {
    let (rr, r) = (20.0, 1.5);
    for (code, g, want) in [
        ("G41", 3, rr - r),
        ("G42", 3, rr + r),
        ("G41", 2, rr + r),
        ("G42", 2, rr - r),
    ] {
        let p = run(&circle(code, g), "D3=1.5");
        assert_eq!(p.segments.len(), 4, "{code} G{g}");
        let s = &p.segments[2];
        let Motion::Arc(a) = s.motion else { panic!() };
        assert!((a.radius - want).abs() < TOL, "{code} G{g}: {}", a.radius);
        assert!(a.center[0].abs() < TOL && a.center[1].abs() < TOL);
        assert!((a.sweep.abs() - 2.0 * PI).abs() < TOL);
        assert!(close(s.start.p(), [want, 0.0, 0.0]), "{:?}", s.start);
        assert!(close(s.end.p(), [want, 0.0, -2.0]), "{:?}", s.end);
        assert!(close(p.segments[1].end.p(), [want, 0.0, 0.0]));
        assert!(close(p.segments[3].end.p(), [0.0, 0.0, -2.0]));
    }
}

#[test]
fn inch_program_radius_is_in_inch() {
    let p = run(
        "G20 G0 X0 Y0\nG41 D1 G1 X1 F10\nG3 X1 Y0 I-1 J0\nG40 G1 X0",
        "D1=0.25",
    );
    let Motion::Arc(a) = p.segments[2].motion else {
        panic!()
    };
    assert!((a.radius - 0.75 * 25.4).abs() < TOL);
    let p = run(
        "G20 G0 X0 Y0\nG41.1 D0.5 G1 X1 F10\nG3 X1 Y0 I-1 J0\nG40 G1 X0",
        "",
    );
    let Motion::Arc(a) = p.segments[2].motion else {
        panic!()
    };
    assert!(
        (a.radius - 0.75 * 25.4).abs() < TOL,
        "G41.1 D is the diameter"
    );
    assert_eq!(p.cutter[0].code, "G41.1");
}

#[test]
fn other_planes_map_onto_g17() {
    let g17 = run(&square("G42"), "D1=2");
    for (plane, map) in [("G18", [2usize, 0, 1]), ("G19", [1usize, 2, 0])] {
        // The square in (u, v) of the plane: u = Z, v = X in G18; u = Y, v = Z in G19.
        let letters = |k: usize| ['X', 'Y', 'Z'][map[k]];
        let text = square("G42")
            .replace('X', "u")
            .replace('Y', "v")
            .replace('u', &letters(0).to_string())
            .replace('v', &letters(1).to_string());
        let p = run(&format!("{plane}\n{text}"), "D1=2");
        assert_eq!(p.segments.len(), g17.segments.len(), "{plane}");
        for (a, b) in p.segments.iter().zip(&g17.segments) {
            let (pa, pb) = (a.end.p(), b.end.p());
            assert!(
                (pa[map[0]] - pb[0]).abs() < TOL && (pa[map[1]] - pb[1]).abs() < TOL,
                "{plane}: {pa:?} vs {pb:?}"
            );
            assert!(pa[map[2]].abs() < TOL);
        }
    }
}

#[test]
fn without_a_radius_the_path_is_the_programmed_one_with_one_warning() {
    let text = square("G41");
    let plain = run(&text.replace("G41 D1 ", "").replace("G40 ", ""), "");
    let p = run(&text, "");
    assert_eq!(p.segments, plain.segments);
    let w: Vec<_> = p
        .warnings
        .iter()
        .filter(|w| warning_kind(&w.message) == "cutter compensation")
        .collect();
    assert_eq!(w.len(), 1, "{:?}", p.warnings);
    assert_eq!((w[0].line, w[0].column), (2, 1));
    for phrase in ["G41 D1", "programmed (un-offset) path", "toolRadii"] {
        assert!(w[0].message.contains(phrase), "{}", w[0].message);
    }
    assert_eq!(p.cutter[0].radius, None);
    // A second stretch gets its own warning; D2 known, D1 not.
    let two = format!("{}\n{}", text.replace("M30", ""), text.replace("D1", "D2"));
    let p = run(&two, "D2=1");
    let n = p
        .warnings
        .iter()
        .filter(|w| warning_kind(&w.message) == "cutter compensation")
        .count();
    assert_eq!(n, 1);
    assert_eq!(p.cutter.len(), 2);
}

fn refused(text: &str, radii: &str) -> (usize, usize, String) {
    let e = parse_with(text, &opts(radii)).unwrap_err();
    (e.line, e.column, e.message)
}

#[test]
fn what_is_not_simulated_is_a_located_error() {
    let (l, c, m) = refused(&circle("G41", 3), "D3=25");
    assert_eq!((l, c), (3, 1));
    assert!(m.contains("≤ 0"), "{m}");
    let (l, _, m) = refused("G0 X0 Y0\nG41 D1\nG3 X10 Y10 R10 F100\nG1 X20", "D1=1");
    assert_eq!(l, 3);
    assert!(m.contains("start-up"), "{m}");
    let (l, _, m) = refused(
        "G0 X0 Y0\nG41 D1 G1 X10 F100\nG1 Z-1\nG1 Z-2\nG1 X20 Y5",
        "D1=1",
    );
    assert_eq!(l, 4);
    assert!(m.contains("two moves without motion"), "{m}");
    let (l, _, m) = refused("G0 X0 Y0\nG41 D1 G1 X10 F100\nY0.5\nX0\nG40 G1 X-5", "D1=1");
    assert!(m.contains("gouge"), "line {l}: {m}");
    let (l, c, m) = refused("G0 X0 Y0\nG41 D1 G1 X10 F100\nG18 G1 X20", "D1=1");
    assert_eq!((l, c), (3, 1));
    assert!(m.contains("plane change"), "{m}");
    let (l, _, m) = refused("G0 X0 Y0\nG41 D1 G1 X10 F100\nG81 X5 Z-1 R1", "D1=1");
    assert_eq!(l, 3);
    assert!(m.contains("G81 during cutter compensation"), "{m}");
    let (l, c, m) = refused("G0 X0 Y0\nG41 D1 G1 X10 F100\nG42 D1 X20", "");
    assert_eq!((l, c), (3, 1));
    assert!(m.contains("cancel with G40"), "{m}");
    let (l, _, m) = refused("G0 X0 Y0\nG41 D1 G1 X10 F100\nG40 G2 X20 R5", "D1=1");
    assert_eq!(l, 3);
    assert!(
        m.contains("cancels cutter compensation and is an arc"),
        "{m}"
    );
}

#[test]
fn tool_radii_are_validated_naming_the_entry() {
    for (text, phrase) in [
        ("D1=-1", "D1"),
        ("D1=inf", "D1"),
        ("D1=NaN", "D1"),
        ("X1=3", "'X1'"),
        ("D1 3", "no '='"),
        ("D2=abc", "D2"),
    ] {
        let e = ToolRadii::parse(text).unwrap_err();
        assert!(e.contains(phrase) && e.contains("toolRadii"), "{text}: {e}");
    }
    let o: ParseOptions = serde_json::from_str(r#"{"toolRadii": {"1": 3, "D08": 0.25}}"#).unwrap();
    assert_eq!(
        (o.tool_radii.get(1), o.tool_radii.get(8)),
        (Some(3.0), Some(0.25))
    );
    let o: ParseOptions = serde_json::from_str(r#"{"toolRadii": "D1=3, D8=0.25"}"#).unwrap();
    assert_eq!(o.tool_radii.get(8), Some(0.25));
    let e = serde_json::from_str::<ParseOptions>(r#"{"toolRadii": {"D1": -2}}"#).unwrap_err();
    assert!(e.to_string().contains("toolRadii D1"), "{e}");
}

/// Nearest distance from `q` (in the XY plane) to the segment a–b.
fn dist_line(q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    let t = (((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0);
    (q[0] - a[0] - t * d[0]).hypot(q[1] - a[1] - t * d[1])
}

/// Nearest distance from `q` to the CCW arc about the origin of radius
/// `rc` from angle `t0` to `t1` (t0 < t1 < t0 + 2π).
fn dist_arc(q: [f64; 2], rc: f64, t0: f64, t1: f64) -> f64 {
    let th = q[1].atan2(q[0]);
    let rel = (th - t0).rem_euclid(2.0 * PI);
    if rel <= t1 - t0 {
        return (q[0].hypot(q[1]) - rc).abs();
    }
    let end = |t: f64| (q[0] - rc * t.cos()).hypot(q[1] - rc * t.sin());
    end(t0).min(end(t1))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn offset_points_are_at_r_from_a_convex_contour(
        gaps in prop::collection::vec(0.3f64..2.0, 4..9),
        arcs in prop::collection::vec(any::<bool>(), 9),
        rc in 20.0f64..60.0,
        r in 0.2f64..3.0,
        left_side in any::<bool>(),
    ) {
        // Vertex angles: the gaps scaled to one turn, none over 150°.
        let sum: f64 = gaps.iter().sum();
        let steps: Vec<f64> = gaps.iter().map(|g| g / sum * 2.0 * PI).collect();
        prop_assume!(steps.iter().all(|s| *s < 150f64.to_radians()));
        let mut angles = vec![0.0];
        for s in &steps[..steps.len() - 1] {
            angles.push(angles.last().unwrap() + s);
        }
        let n = angles.len();
        let pt = |t: f64| [rc * t.cos(), rc * t.sin()];
        let mut text = format!(
            "G0 X0 Y0\n{} D1 G1 X{:.17} Y{:.17} F600\n",
            if left_side { "G41" } else { "G42" },
            pt(0.0)[0],
            pt(0.0)[1]
        );
        let mut edges = Vec::new();
        for k in 0..n {
            let (t0, t1) = (angles[k], if k + 1 < n { angles[k + 1] } else { 2.0 * PI });
            let e = pt(t1);
            if arcs[k] {
                text += &format!("G3 X{:.17} Y{:.17} I{:.17} J{:.17}\n", e[0], e[1], -pt(t0)[0], -pt(t0)[1]);
            } else {
                text += &format!("G1 X{:.17} Y{:.17}\n", e[0], e[1]);
            }
            edges.push((arcs[k], t0, t1));
        }
        text += "G40 G1 X0 Y0\nM30\n";
        let p = match parse_with(&text, &opts(&format!("D1={r}"))) {
            Ok(p) => p,
            Err(e) => {
                prop_assert!(e.message.contains("gouge"), "{}", e);
                return Ok(());
            }
        };
        let dist = |q: [f64; 2]| {
            edges.iter().map(|&(is_arc, t0, t1)| if is_arc {
                dist_arc(q, rc, t0, t1)
            } else {
                dist_line(q, pt(t0), pt(t1))
            }).fold(f64::INFINITY, f64::min)
        };
        let v0 = pt(0.0);
        let segs = &p.segments;
        // Skip the rapid, the start-up and the cancel move.
        for s in &segs[2..segs.len() - 1] {
            for i in 0..=20 {
                let q = s.point_at(i as f64 / 20.0);
                if (q[0] - v0[0]).hypot(q[1] - v0[1]) < 3.0 * r {
                    continue;
                }
                let d = dist([q[0], q[1]]);
                prop_assert!((d - r).abs() < TOL, "line {}: {q:?} at {d}, r = {r}\n{text}", s.line);
            }
        }
    }
}

/// Nearest in-plane distance from `q` to programmed segment `s` (a line,
/// or an arc of either direction), in plane axes `(u, v)`.
fn dist_seg(q: [f64; 2], s: &mtmotion::nc::program::Segment, (u, v): (usize, usize)) -> f64 {
    let (a, b) = (s.start.p(), s.end.p());
    let (a, b) = ([a[u], a[v]], [b[u], b[v]]);
    match s.motion {
        Motion::Arc(arc) => {
            let c = [arc.center[u], arc.center[v]];
            let t0 = (a[1] - c[1]).atan2(a[0] - c[0]);
            // The same arc run counter-clockwise.
            let (lo, sweep) = if arc.sweep >= 0.0 {
                (t0, arc.sweep)
            } else {
                (t0 + arc.sweep, -arc.sweep)
            };
            let shifted = [q[0] - c[0], q[1] - c[1]];
            dist_arc(shifted, arc.radius, lo, lo + sweep)
        }
        _ => dist_line(q, a, b),
    }
}

#[test]
fn linuxcnc_comp_offsets_at_r_in_g17_and_g18_and_simulates() {
    use mtmotion::toolpath::{simulate, SimConfig};
    let Some(text) = corpus::text("linuxcnc_comp.ngc") else {
        return;
    };
    let r = 0.0625 * 25.4;
    let programmed = run(&text, "");
    let p = run(&text, "D1=0.0625");
    assert_eq!(p.cutter.len(), 4);
    for w in p.segments.windows(2) {
        assert!(
            close(w[0].end.p(), w[1].start.p()),
            "gap at line {}",
            w[1].line
        );
    }
    let mut checked = 0;
    for st in &p.cutter {
        let (u, v, _) = st.plane.axes();
        let g40 = p
            .blocks
            .iter()
            .find(|b| {
                b.line > st.line && b.words.iter().any(|w| w.letter == 'G' && w.value == 40.0)
            })
            .map_or(usize::MAX, |b| b.line);
        let in_stretch = |line: usize| line > st.line + 1 && line < g40;
        let contour: Vec<_> = programmed
            .segments
            .iter()
            .filter(|s| in_stretch(s.line) && s.is_cutting())
            .collect();
        let (first, last) = (contour[0].start.p(), contour.last().unwrap().end.p());
        for s in p
            .segments
            .iter()
            .filter(|s| in_stretch(s.line) && s.is_cutting())
        {
            for i in 0..=20 {
                let q = s.point_at(i as f64 / 20.0);
                let near = |c: [f64; 3]| (q[u] - c[u]).hypot(q[v] - c[v]) < 3.0 * r;
                if near(first) || near(last) {
                    continue;
                }
                let d = contour
                    .iter()
                    .map(|c| dist_seg([q[u], q[v]], c, (u, v)))
                    .fold(f64::INFINITY, f64::min);
                assert!((d - r).abs() < TOL, "line {}: {q:?} at {d}", s.line);
                checked += 1;
            }
        }
    }
    assert!(checked > 100, "{checked}");
    let sim = simulate(&p.segments, &p.segments, &SimConfig::default()).unwrap();
    assert!(sim.max_error.is_finite());
}

#[test]
fn cncjs_helical_thread_milling_keeps_z_and_grows_each_arc_by_r() {
    let Some(text) = corpus::text("cncjs_helical-thread-milling.gcode") else {
        return;
    };
    let programmed = run(&text, "");
    let p = run(&text, "D08=0.05");
    let r = 0.05 * 25.4;
    assert_eq!(p.cutter[0].radius, Some(r));
    for w in p.segments.windows(2) {
        assert!(
            close(w[0].end.p(), w[1].start.p()),
            "gap at line {}",
            w[1].line
        );
    }
    // G42 with G3 arcs: the tool runs outside, R + r about the same centre;
    // every block's Z end is the programmed one (helical Z passes through).
    let mut arcs = 0;
    for s in &p.segments {
        let q = programmed
            .segments
            .iter()
            .find(|q| q.line == s.line)
            .unwrap();
        assert!((s.end.z - q.end.z).abs() < TOL, "line {}", s.line);
        if let (Motion::Arc(a), Motion::Arc(b)) = (s.motion, q.motion) {
            assert!((a.radius - (b.radius + r)).abs() < TOL, "line {}", s.line);
            assert!(
                (a.center[0] - b.center[0]).abs() < TOL && (a.center[1] - b.center[1]).abs() < TOL
            );
            arcs += 1;
        }
    }
    assert_eq!(arcs, 10);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    /// Any program of lines, arcs (I/J, the end on the circle), plunges and
    /// G41/G42 … G40 stretches with a tool radius is either refused with a
    /// located error or gives a continuous path whose arcs are consistent.
    #[test]
    fn random_programs_are_refused_or_continuous(
        blocks in prop::collection::vec((0u8..7, -30i32..30, -30i32..30, 1i32..40), 1..25),
        r in 0.0f64..4.0,
    ) {
        let mut text = String::from("G0 X0 Y0 Z0\nF500\n");
        let (mut cur, mut active) = ([0.0f64, 0.0], false);
        for (kind, x, y, rad) in &blocks {
            let (x, y) = (f64::from(*x), f64::from(*y));
            text += &match kind {
                0 => {
                    cur = [x, y];
                    format!("G1 X{x} Y{y}\n")
                }
                1 | 2 => {
                    // A consistent arc: centre at cur + (I, J), end on its circle.
                    let (i, j) = (x / 3.0 + 0.5, y / 3.0);
                    let c = [cur[0] + i, cur[1] + j];
                    let th = f64::from(*rad) * 0.157;
                    let rr = i.hypot(j);
                    cur = [c[0] + rr * th.cos(), c[1] + rr * th.sin()];
                    format!("G{} X{:.12} Y{:.12} I{i} J{j}\n", kind + 1, cur[0], cur[1])
                }
                3 => format!("G1 Z{}\n", rad % 5),
                4 | 5 if !active => {
                    active = true;
                    cur = [x, y];
                    format!("G4{} D1 G1 X{x} Y{y}\n", kind - 3)
                }
                _ => {
                    active = false;
                    cur = [x, y];
                    format!("G40 G1 X{x} Y{y}\n")
                }
            };
        }
        match parse_with(&text, &opts(&format!("D1={r}"))) {
            Ok(p) => {
                for w in p.segments.windows(2) {
                    let (a, b) = (w[0].end.p(), w[1].start.p());
                    prop_assert!(close(a, b), "gap before line {}\n{text}", w[1].line);
                }
                for s in &p.segments {
                    prop_assert!(s.start.p().iter().chain(s.end.p().iter()).all(|v| v.is_finite()));
                    // An arc's own geometry (centre, radius, sweep) runs
                    // from its start to its end.
                    if let Motion::Arc(a) = s.motion {
                        let (q0, q1) = (s.point_at(0.0), s.point_at(1.0));
                        let r0 = (s.start.x - a.center[0]).hypot(s.start.y - a.center[1]);
                        prop_assert!((r0 - a.radius).abs() < 1e-6, "line {}: radius {} vs {r0}", s.line, a.radius);
                        prop_assert!(close(q0, s.start.p()), "line {}", s.line);
                        prop_assert!((q1[0] - s.end.x).hypot(q1[1] - s.end.y) < 1e-6, "line {}: {q1:?} vs {:?}\n{text}", s.line, s.end);
                    }
                }
            }
            Err(e) => prop_assert!(e.line >= 1 && e.column >= 1, "{e}"),
        }
    }
}
