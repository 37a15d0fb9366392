//! Fanuc coordinate system rotation G68/G69 (`src/nc/rotation.rs`): the
//! segments are in the un-rotated frame, each programmed point turned
//! about the G68 centre by R degrees, counter-clockwise seen from the
//! plane's positive normal. Expected end points are worked out by hand
//! (multiples of 90°) or from the closed form `c + (cos θ·du − sin θ·dv,
//! sin θ·du + cos θ·dv)` written out here, compared within 1e-9 mm. Also:
//! arcs by I/J/K and R, G91 moves and G91 R increments, G69, canned
//! cycles, the refused cases with their line and column, both writers'
//! round trips, and reverse compensation of a rotated program against the
//! same program written without G68.

use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
use mtmotion::nc::patch::write_source;
use mtmotion::nc::program::{parse, Motion, Plane, Program};

const TOL: f64 = 1e-9;

fn prog(src: &str) -> Program {
    parse(src).unwrap_or_else(|e| panic!("{src}\n{e}"))
}

/// The XYZ end points of the program's segments.
fn ends(src: &str) -> Vec<[f64; 3]> {
    prog(src).segments.iter().map(|s| s.end.p()).collect()
}

fn close(got: [f64; 3], want: [f64; 3], what: &str) {
    assert!(
        (0..3).all(|k| (got[k] - want[k]).abs() < TOL),
        "{what}: got {got:?}, want {want:?}"
    );
}

/// `(u, v)` turned by `deg` about `(cu, cv)`, written out.
fn turned(u: f64, v: f64, cu: f64, cv: f64, deg: f64) -> (f64, f64) {
    let (s, c) = deg.to_radians().sin_cos();
    let (du, dv) = (u - cu, v - cv);
    (cu + c * du - s * dv, cv + s * du + c * dv)
}

#[test]
fn g17_lines_turn_about_the_centre_and_g69_restores() {
    let e = ends("G0 X0 Y0 Z5\nG68 X10 Y5 R30\nG1 X20 Y5 F100\nY15 Z-1\nG69\nG1 X1 Y2");
    assert_eq!(e.len(), 4, "{e:?}");
    let (x, y) = turned(20.0, 5.0, 10.0, 5.0, 30.0);
    close(e[1], [x, y, 5.0], "X20 Y5 under R30");
    assert!((x - (10.0 + 10.0 * 0.75f64.sqrt())).abs() < TOL && (y - 10.0).abs() < TOL);
    let (x, y) = turned(20.0, 15.0, 10.0, 5.0, 30.0);
    close(
        e[2],
        [x, y, -1.0],
        "Y15 (X kept in the rotated frame), Z unchanged",
    );
    close(e[3], [1.0, 2.0, -1.0], "after G69");
}

#[test]
fn g18_and_g19_turn_their_own_planes() {
    // G18: Z → X is counter-clockwise seen from +Y; the centre words are Z, X.
    let e = ends("G18 G0 X0 Y7 Z0\nG68 Z2 X1 R90\nG1 Z3 X1 F100\nG1 Z2 X4");
    close(e[1], [2.0, 7.0, 2.0], "G18 R90 of Z3 X1 about Z2 X1");
    close(e[2], [1.0, 7.0, -1.0], "G18 R90 of Z2 X4");
    let e = ends("G18 G0 X0 Y0 Z0\nG68 Z0 X0 R-30\nG1 Z10 X0 Y3 F100");
    let (z, x) = turned(10.0, 0.0, 0.0, 0.0, -30.0);
    close(e[1], [x, 3.0, z], "G18 R-30");
    // G19: Y → Z; the centre words are Y, Z; X is the normal and stays.
    let e = ends("G19 G0 X5 Y0 Z0\nG68 Y1 Z1 R90\nG1 Y2 Z1 F100\nX6");
    close(e[1], [5.0, 1.0, 2.0], "G19 R90 of Y2 Z1 about Y1 Z1");
    close(e[2], [6.0, 1.0, 2.0], "G19: X alone moves X only");
}

#[test]
fn omitted_words_are_the_current_position() {
    // Centre omitted: the position at G68 (Fanuc).
    let e = ends("G0 X3 Y4\nG68 R90\nG1 X4 Y4 F100");
    close(e[1], [3.0, 5.0, 0.0], "centre = current position");
    // One centre word omitted: that axis's current position.
    let e = ends("G0 X3 Y4\nG68 X0 R90\nG1 X1 Y4 F100");
    close(e[1], [0.0, 5.0, 0.0], "centre X0 Y4");
    // A lone X under G90 moves along the rotated X axis.
    let e = ends("G0 X0 Y0\nG68 X0 Y0 R90\nG1 X10 F100\nY5");
    close(e[1], [0.0, 10.0, 0.0], "lone X");
    close(e[2], [-5.0, 10.0, 0.0], "then Y5");
}

#[test]
fn incremental_moves_and_angles() {
    let e = ends("G0 X1 Y1\nG68 X0 Y0 R45\nG91 G1 X10 F100\nY-2");
    let h = 10.0 / 2f64.sqrt();
    close(e[1], [1.0 + h, 1.0 + h, 0.0], "G91 X10 at 45°");
    let d = 2.0 / 2f64.sqrt();
    close(e[2], [1.0 + h + d, 1.0 + h - d, 0.0], "G91 Y-2 at 45°");
    // G91 R adds to the rotation in force; G90 R replaces it.
    let e = ends("G0 X0 Y0\nG68 X0 Y0 R30\nG91 G68 X0 Y0 R15\nG90 G1 X10 Y0 F100");
    let (x, y) = turned(10.0, 0.0, 0.0, 0.0, 45.0);
    close(e[1], [x, y, 0.0], "R30 then G91 R15");
    let e = ends("G0 X0 Y0\nG68 X0 Y0 R30\nG68 X0 Y0 R15\nG1 X10 Y0 F100");
    let (x, y) = turned(10.0, 0.0, 0.0, 0.0, 15.0);
    close(e[1], [x, y, 0.0], "R30 then G90 R15");
    // G91 R without a rotation in force: from 0.
    let e = ends("G0 X0 Y0\nG91 G68 X0 Y0 R90\nG90 G1 X2 Y0 F100");
    close(e[1], [0.0, 2.0, 0.0], "G91 R90 from none");
    // The centre words stay absolute under G91; G92 shifts them.
    let e = ends("G0 X5 Y5\nG92 X0 Y0\nG91 G68 X1 Y0 R90\nG90 G1 X2 Y0 F100");
    close(e[1], [6.0, 6.0, 0.0], "centre X1 Y0 of the G92 frame");
}

#[test]
fn arcs_by_ijk_and_r_keep_radius_and_sweep() {
    let p = prog("G0 X10 Y0\nG68 X0 Y0 R90\nG0 X10 Y0\nG3 X-10 Y0 I-10 J0 F100\nG2 X10 Y0 R10");
    let s = &p.segments[2];
    close(s.start.p(), [0.0, 10.0, 0.0], "arc start");
    close(s.end.p(), [0.0, -10.0, 0.0], "arc end");
    let Motion::Arc(a) = s.motion else { panic!() };
    close(a.center, [0.0, 0.0, 0.0], "IJK centre (vector turned)");
    assert!((a.radius - 10.0).abs() < TOL && (a.sweep - std::f64::consts::PI).abs() < TOL);
    let Motion::Arc(a) = p.segments[3].motion else {
        panic!()
    };
    close(p.segments[3].end.p(), [0.0, 10.0, 0.0], "R arc end");
    close(a.center, [0.0, 0.0, 0.0], "R arc centre");
    assert!((a.radius - 10.0).abs() < TOL && (a.sweep + std::f64::consts::PI).abs() < TOL);
    // Off-centre rotation, 30°, a quarter arc by I/J: centre = turned(start + IJ).
    let p = prog("G0 X20 Y0\nG68 X5 Y5 R30\nG0 X20 Y0\nG3 X10 Y10 I-10 J0 F100");
    let Motion::Arc(a) = p.segments[2].motion else {
        panic!()
    };
    let (cx, cy) = turned(10.0, 0.0, 5.0, 5.0, 30.0);
    close(a.center, [cx, cy, 0.0], "30° IJK centre");
    let (ex, ey) = turned(10.0, 10.0, 5.0, 5.0, 30.0);
    close(p.segments[2].end.p(), [ex, ey, 0.0], "30° arc end");
    assert!((a.sweep - std::f64::consts::FRAC_PI_2).abs() < TOL);
    // G90.1 absolute centres are points of the rotated frame.
    let q = prog("G0 X20 Y0\nG68 X5 Y5 R30\nG0 X20 Y0\nG90.1 G3 X10 Y10 I10 J0 F100");
    assert_eq!(q.segments[2].motion, p.segments[2].motion);
    // A full circle stays closed exactly.
    let p = prog("G0 X0 Y0\nG68 X3 Y1 R17\nG0 X10 Y0\nG2 X10 Y0 I-5 J0 F100");
    let s = &p.segments[2];
    assert_eq!(s.start, s.end);
    let Motion::Arc(a) = s.motion else { panic!() };
    assert!((a.sweep + std::f64::consts::TAU).abs() < TOL && a.plane == Plane::XY);
}

#[test]
fn helix_keeps_its_normal_axis() {
    let p = prog("G0 X10 Y0 Z0\nG68 X0 Y0 R90\nG0 X10 Y0\nG3 X-10 Y0 Z-4 I-10 J0 F100");
    close(p.segments[2].end.p(), [0.0, -10.0, -4.0], "helix end");
}

#[test]
fn canned_cycle_holes_turn_with_the_frame() {
    let p = prog("G0 X0 Y0 Z10\nG68 X0 Y0 R90\nG81 X10 Y0 Z-5 R2 F100\nX10 Y5\nG80");
    let holes: Vec<[f64; 3]> = p
        .segments
        .iter()
        .filter(|s| matches!(s.motion, Motion::Linear))
        .map(|s| s.end.p())
        .collect();
    assert_eq!(holes.len(), 2, "{holes:?}");
    close(holes[0], [0.0, 10.0, -5.0], "hole 1 bottom");
    close(holes[1], [-5.0, 10.0, -5.0], "hole 2 bottom");
    // G91 K repeats step along the rotated axis.
    let p = prog("G0 X0 Y0 Z10\nG68 X0 Y0 R30\nG91 G99 G81 X4 Y0 Z-3 R-8 K3 F100");
    let bottoms: Vec<[f64; 3]> = p
        .segments
        .iter()
        .filter(|s| matches!(s.motion, Motion::Linear))
        .map(|s| s.end.p())
        .collect();
    assert_eq!(bottoms.len(), 3);
    for (k, b) in bottoms.iter().enumerate() {
        let (x, y) = turned(4.0 * (k + 1) as f64, 0.0, 0.0, 0.0, 30.0);
        close(*b, [x, y, -1.0], "G91 hole");
    }
}

#[test]
fn g69_with_a_move_and_subprograms() {
    let e = ends("G0 X0 Y0\nG68 X0 Y0 R90\nG1 X1 Y0 F100\nG69 G90 X-5 Y-5\nM30");
    close(e[1], [0.0, 1.0, 0.0], "rotated");
    close(e[2], [-5.0, -5.0, 0.0], "G69 block's move is un-rotated");
    // A G91 subprogram body called under G68 walks in the rotated frame.
    let e = ends("O1\nG0 X0 Y0\nG68 X0 Y0 R90\nM98 P2 L2\nM30\nO2\nG91 G1 X1 F100\nG90\nM99");
    close(e[1], [0.0, 1.0, 0.0], "first call");
    close(e[2], [0.0, 2.0, 0.0], "second call");
}

/// The first error of `src`: (line, column, message).
fn error(src: &str) -> (usize, usize, String) {
    let e = parse(src).expect_err(src);
    (e.line, e.column, e.message)
}

#[test]
fn refused_cases_name_line_and_column() {
    let cases: [(&str, usize, usize, &str); 12] = [
        ("G17 G68 X0 Y0 R10\nG18", 2, 1, "plane change to G18"),
        ("G68 X0 Y0 R10\nG1 X1 F1\nG0 G19 X2", 3, 4, "plane change"),
        (
            "G41 D1 G1 X1 Y1 F100\nG68 X0 Y0 R10",
            2,
            1,
            "cutter compensation G41",
        ),
        (
            "G68 X0 Y0 R10\nG42 G1 X1 F100\nX2\nG69",
            4,
            1,
            "cutter compensation G42",
        ),
        (
            "G68 X0 Y0 R10\nG28 X0",
            2,
            1,
            "G28 while the coordinate rotation",
        ),
        ("G68 X0 Y0 R10\nG0 X1\nG92 X0", 3, 1, "G92 while"),
        ("G68 X0 Y0 R10\nG54 G0 X1", 2, 1, "G54 while"),
        ("G68 X0 Y0 Z1 R10", 1, 11, "Z1 on a G68 block"),
        ("G68 X0 Y0 I0 J0 K1 R10", 1, 11, "3D coordinate conversion"),
        ("G0 X1\nG68 X0 Y0", 2, 1, "G68 without R"),
        ("G68.2 X0 Y0 Z0 I0 J45 K0", 1, 1, "tilted working plane"),
        (
            "G0 Z5\nG81 X0 Y0 Z-1 R1 F10\nG68 X0 Y0 R5",
            3,
            1,
            "canned-cycle mode",
        ),
    ];
    for (src, line, column, text) in cases {
        let (l, c, m) = error(src);
        assert!(
            (l, c) == (line, column) && m.contains(text),
            "{src}\n got line {l} column {c}: {m}\nwant line {line} column {column}: …{text}…"
        );
    }
    // Beside another action, and G68 with G69.
    assert!(error("G68 G4 P1 X0 Y0 R1")
        .2
        .contains("in a block of its own"));
    assert!(error("G68 G69 X0 Y0 R1")
        .2
        .contains("two coordinate-rotation codes"));
}

#[test]
fn same_plane_and_refused_codes_after_g69_are_fine() {
    let p = prog("G17 G68 X0 Y0 R10\nG17 G0 X1\nG69\nG18\nG28 X0\nG92 X0");
    assert!(p.segments.len() >= 2);
    // A G69 with no rotation in force does nothing, also under G41.
    let p = prog("G0 X0 Y0\nG41 G1 X1 F100\nG69\nG1 X2\nG40 G1 X3");
    assert_eq!(p.segments.len(), 4);
}

#[test]
fn cutter_compensation_started_under_g68_is_the_turned_offset_path() {
    use mtmotion::nc::program::{parse_with, ParseOptions, ToolRadii};
    let opt = ParseOptions {
        tool_radii: ToolRadii::parse("D1=2").unwrap(),
        ..Default::default()
    };
    let run = |src: &str| parse_with(src, &opt).unwrap_or_else(|e| panic!("{src}\n{e}"));
    let p = run(
        "G0 X0 Y0\nG68 X0 Y0 R90\nG41 D1 G1 X10 Y0 F100\nY10\nG3 X0 Y10 R10\nG40 G1 X0 Y0\nG69",
    );
    // The same contour turned by hand: (x, y) → (−y, x).
    let q = run("G0 X0 Y0\nG41 D1 G1 X0 Y10 F100\nX-10\nG3 X-10 Y0 R10\nG40 G1 X0 Y0");
    assert_eq!(p.segments.len(), q.segments.len());
    for (a, b) in p.segments.iter().zip(&q.segments) {
        close(a.end.p(), b.end.p(), "offset end");
        if let (Motion::Arc(x), Motion::Arc(y)) = (a.motion, b.motion) {
            close(x.center, y.center, "offset arc centre");
            assert!((x.radius - y.radius).abs() < TOL);
        }
    }
}

#[test]
fn source_writer_rewrites_incremental_blocks_and_centres_in_the_rotated_frame() {
    let src = "G0 X0 Y0\nG68 X3 Y-2 R40\nG0 X10 Y0\nG91 G1 X20 F500\nG3 X-10 Y10 I-10 J0\nG1 Y15\nG90 G69\nM30\n";
    let p = prog(src);
    let mut segs = p.segments.clone();
    // Grow the arc's radius by 0.1 mm about its centre (machine frame):
    // its start and end move radially, the G91 lines before and after
    // follow, the last line keeps its end.
    let Motion::Arc(a) = segs[3].motion else {
        panic!()
    };
    let grow = |p: [f64; 3]| {
        let k = (a.radius + 0.1) / a.radius;
        [0, 1, 2].map(|i| a.center[i] + (p[i] - a.center[i]) * k)
    };
    let (s1, e1) = (grow(segs[3].start.p()), grow(segs[3].end.p()));
    let set = |pose: &mut mtmotion::nc::program::Pose, p: [f64; 3]| {
        (pose.x, pose.y, pose.z) = (p[0], p[1], p[2]);
    };
    set(&mut segs[2].end, s1);
    set(&mut segs[3].start, s1);
    set(&mut segs[3].end, e1);
    set(&mut segs[4].start, e1);
    segs[3].motion = Motion::Arc(mtmotion::nc::program::Arc {
        radius: a.radius + 0.1,
        ..a
    });
    let out = write_source(src, &p, &segs);
    assert_ne!(out, src);
    let q = prog(&out);
    for (k, (a, b)) in segs.iter().zip(&q.segments).enumerate() {
        assert!(
            mtmotion::nc::program::dist(a.end.p(), b.end.p()) < 2e-3,
            "segment {k}: {:?} vs {:?}\n{out}",
            a.end.p(),
            b.end.p()
        );
    }
    let (Motion::Arc(a), Motion::Arc(b)) = (segs[3].motion, q.segments[3].motion) else {
        panic!("{out}")
    };
    assert!(
        mtmotion::nc::program::dist(a.center, b.center) < 2e-3,
        "centre {:?} vs {:?}\n{out}",
        a.center,
        b.center
    );
}

/// Largest distance between the end points of two programs' segments.
fn max_end_gap(p: &Program, q: &Program) -> f64 {
    assert_eq!(p.segments.len(), q.segments.len());
    p.segments
        .iter()
        .zip(&q.segments)
        .map(|(a, b)| mtmotion::nc::program::dist(a.end.p(), b.end.p()))
        .fold(0.0, f64::max)
}

const SQUARE: &str = "G0 X0 Y0\nG68 X20 Y10 R25\nG0 X10 Y0\nG1 X50 Y0 F3000\nG3 X60 Y10 R10\nG1 X60 Y40\nG3 X50 Y50 I-10 J0\nG1 X10 Y50\nG1 X10 Y0\nG69\nG0 X0 Y0\nM30\n";

#[test]
fn writers_round_trip_a_rotated_program() {
    let p = prog(SQUARE);
    // The flat writer writes the un-rotated path (no G68) to 4 decimals.
    let flat = mtmotion::nc::writer::write(&p, &p.segments);
    assert!(!flat.contains("G68"), "{flat}");
    let q = prog(&flat);
    assert!(max_end_gap(&p, &q) < 1e-4, "{flat}");
    // The source writer keeps the text when nothing changes…
    assert_eq!(write_source(SQUARE, &p, &p.segments), SQUARE);
    // …and writes a moved end point back in the rotated frame.
    let mut segs = p.segments.clone();
    segs[3].end.x += 0.1;
    segs[3].end.y -= 0.05;
    let out = write_source(SQUARE, &p, &segs);
    assert!(out.contains("G68 X20 Y10 R25"), "{out}");
    let q = prog(&out);
    let got = q.segments[3].end.p();
    let want = segs[3].end.p();
    assert!(
        mtmotion::nc::program::dist(got, want) < 1e-3,
        "{out}\n got {got:?} want {want:?}"
    );
}

/// The same contour without G68: every point of `SQUARE` turned by hand.
fn square_unrotated() -> String {
    let t = |x: f64, y: f64| turned(x, y, 20.0, 10.0, 25.0);
    let f = |(x, y): (f64, f64)| format!("X{x:.6} Y{y:.6}");
    let (ix, iy) = {
        let (s, c) = 25f64.to_radians().sin_cos();
        (-10.0 * c, -10.0 * s)
    };
    format!(
        "G0 X0 Y0\nG0 {}\nG1 {} F3000\nG3 {} R10\nG1 {}\nG3 {} I{ix:.6} J{iy:.6}\nG1 {}\nG1 {}\nG0 X0 Y0\nM30\n",
        f(t(10.0, 0.0)),
        f(t(50.0, 0.0)),
        f(t(60.0, 10.0)),
        f(t(60.0, 40.0)),
        f(t(50.0, 50.0)),
        f(t(10.0, 50.0)),
        f(t(10.0, 0.0)),
    )
}

#[test]
fn reverse_compensation_of_a_rotated_program_matches_the_unrotated_one() {
    let plain = square_unrotated();
    let (p, q) = (prog(SQUARE), prog(&plain));
    assert!(
        max_end_gap(&p, &q) < 1e-5,
        "the hand-turned program differs"
    );
    let cfg = ReverseConfig::default();
    let rot = reverse_compensate(SQUARE, &cfg).unwrap();
    let flat = reverse_compensate(&plain, &cfg).unwrap();
    println!(
        "rotated: {:.3} -> {:.3} µm; plain: {:.3} -> {:.3} µm",
        rot.before.max_error_um,
        rot.after.max_error_um,
        flat.before.max_error_um,
        flat.after.max_error_um
    );
    assert!(rot.after.max_error_um < 0.7 * rot.before.max_error_um);
    // Same model, same path up to the 1e-6 mm of the hand-turned words:
    // the errors agree within 0.05 µm before, and within 1 µm after (the
    // corrected words are rounded to 1 µm in different frames).
    assert!((rot.before.max_error_um - flat.before.max_error_um).abs() < 0.05);
    assert!((rot.after.max_error_um - flat.after.max_error_um).abs() < 1.0);
    assert!(rot.nc.contains("G68 X20 Y10 R25"), "{}", rot.nc);
}

#[test]
fn both_writers_round_trip_rotations_in_every_plane() {
    // (plane code, its two axis letters, the normal's letter, the centre
    // letters of its two axes)
    let planes = [
        (17, 'X', 'Y', 'Z', 'I', 'J'),
        (18, 'Z', 'X', 'Y', 'K', 'I'),
        (19, 'Y', 'Z', 'X', 'J', 'K'),
    ];
    for (g, u, v, n, cu, cv) in planes {
        for angle in [0.0, 17.3, 90.0, -135.0, 400.0] {
            let src = format!(
                "G{g} G0 {u}1 {v}2 {n}3\nG68 {u}4 {v}-1 R{angle}\nG1 {u}10 {v}0 F800\nG91 {v}5 {n}-1\nG90 G3 {u}0 {v}5 R5\nG2 {u}0 {v}5 {cu}3 {cv}0\nG91 G68 R-20\nG90 G1 {u}2\nG69 G0 {u}0 {v}0\nM30\n"
            );
            let p = prog(&src);
            assert_eq!(write_source(&src, &p, &p.segments), src);
            let flat = mtmotion::nc::writer::write(&p, &p.segments);
            let q = prog(&flat);
            assert!(max_end_gap(&p, &q) < 1e-4, "{src}\n{flat}");
            for (a, b) in p.segments.iter().zip(&q.segments) {
                if let (Motion::Arc(x), Motion::Arc(y)) = (a.motion, b.motion) {
                    let d = mtmotion::nc::program::dist(x.center, y.center);
                    assert!(
                        d < 1e-4 && (x.sweep - y.sweep).abs() < 1e-4,
                        "{src}\n{flat}"
                    );
                }
            }
        }
    }
}

#[test]
fn macro_position_variables_are_rotated_frame_positions() {
    // #5001/#5002 give the position in the rotated frame, so writing them
    // back is no move along that axis.
    let e = ends("G0 X0 Y0\nG68 X0 Y0 R90\nG1 X5 Y0 F100\n#1=#5001\n#2=#5002\nG1 X#1 Y[#2+3]");
    close(e[1], [0.0, 5.0, 0.0], "X5 Y0 turned");
    close(e[2], [-3.0, 5.0, 0.0], "X#5001 Y[#5002+3] turned");
}
