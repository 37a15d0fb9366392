//! LinuxCNC polar coordinates `@` (distance) and `^` (angle in degrees)
//! (`src/nc/polar.rs`). Expected points are written out here from
//! `(r cos θ, r sin θ)` about the program origin: G90 absolute, G91 adding
//! to the point's own polar distance and angle, a word left out keeping
//! it, inch scaling, the G92 origin, the corpus's bolt circle (G91 G81 with
//! L6) and spiral (800 o-word repeats), both writers' round trips, and the
//! refused cases with their line and column.

use mtmotion::nc::patch::write_source;
use mtmotion::nc::program::{parse, Program};

#[path = "support/corpus.rs"]
mod corpus;

const TOL: f64 = 1e-9;

fn prog(src: &str) -> Program {
    parse(src).unwrap_or_else(|e| panic!("{src}\n{e}"))
}

fn xy(r: f64, deg: f64) -> [f64; 2] {
    let (s, c) = deg.to_radians().sin_cos();
    [r * c, r * s]
}

fn close_xy(got: [f64; 3], want: [f64; 2], what: &str) {
    assert!(
        (got[0] - want[0]).abs() < TOL && (got[1] - want[1]).abs() < TOL,
        "{what}: got {got:?}, want {want:?}"
    );
}

#[test]
fn absolute_and_incremental_polar_points() {
    let p = prog(
        "G21 G90 G17\nG0 @10 ^30\nG1 ^90 F600\nG1 @5\nG91 G1 ^-90\nG1 @-2 ^45\nG1 @1\nG90 G1 @7 ^200 Z-1",
    );
    let e: Vec<[f64; 3]> = p.segments.iter().map(|s| s.end.p()).collect();
    close_xy(e[0], xy(10.0, 30.0), "G90 @10 ^30");
    close_xy(e[1], xy(10.0, 90.0), "^90 keeps the distance 10");
    close_xy(e[2], xy(5.0, 90.0), "@5 keeps the angle 90°");
    close_xy(e[3], xy(5.0, 0.0), "G91 ^-90 turns about the origin");
    close_xy(e[4], xy(3.0, 45.0), "G91 @-2 ^45 adds to both");
    close_xy(e[5], xy(4.0, 45.0), "G91 @1 keeps the angle");
    close_xy(e[6], xy(7.0, 200.0), "G90 again");
    assert!(
        (e[6][2] + 1.0).abs() < TOL,
        "Z with polar words: {:?}",
        e[6]
    );
    assert!(
        p.segments.iter().all(|s| s.fixed),
        "polar end points are not literal words"
    );
}

#[test]
fn polar_distance_is_scaled_in_inch_and_the_pole_follows_g92() {
    let p = prog("G20 G90\nG1 @1 ^90 F10");
    close_xy(p.segments[0].end.p(), [0.0, 25.4], "@1 inch");
    // G92 X0 Y0 at (10, 10) moves the program origin there.
    let p = prog("G21 G90\nG0 X10 Y10\nG92 X0 Y0\nG1 @5 ^0 F600\nG1 ^90");
    close_xy(
        p.segments[1].end.p(),
        [15.0, 10.0],
        "@5 ^0 about the G92 origin",
    );
    close_xy(
        p.segments[2].end.p(),
        [10.0, 15.0],
        "^90 about the G92 origin",
    );
}

/// LinuxCNC's bolt-circle example: from (1.5 in, 0), `G91 G81 … ^60 L6`
/// drills six holes 60° apart on the 1.5 in radius.
#[test]
fn corpus_bolt_circle_drills_six_holes_round_the_circle() {
    let Some(text) = corpus::text("linuxcnc_hole-circle.ngc") else {
        return;
    };
    let p = prog(&text);
    let r = 1.5 * 25.4;
    // Each hole: rapid to it, rapid to R, feed to the bottom, rapid out.
    let bottoms: Vec<[f64; 3]> = p
        .segments
        .iter()
        .filter(|s| s.feed > 0.0)
        .map(|s| s.end.p())
        .collect();
    assert_eq!(bottoms.len(), 6, "{:?}", bottoms);
    for (k, b) in bottoms.iter().enumerate() {
        close_xy(*b, xy(r, 60.0 * (k + 1) as f64), &format!("hole {k}"));
        // G91: R 0.1 in above the initial level Z0, bottom 0.5 in below R.
        assert!((b[2] - (-0.4 * 25.4)).abs() < TOL, "hole {k} depth {b:?}");
    }
}

/// LinuxCNC's spiral: from (2 in, 0), 800 repeats of `G91 G1 @-.0025 ^4.5`
/// step the distance down by 0.0025 in and the angle up by 4.5°.
#[test]
fn corpus_spiral_steps_in_by_distance_and_angle() {
    let Some(text) = corpus::text("linuxcnc_spiral.ngc") else {
        return;
    };
    let p = prog(&text);
    let cuts: Vec<[f64; 3]> = p
        .segments
        .iter()
        .filter(|s| s.feed > 0.0 && (s.end.x - s.start.x).hypot(s.end.y - s.start.y) > 0.0)
        .map(|s| s.end.p())
        .collect();
    assert_eq!(cuts.len(), 800);
    for (k, c) in cuts.iter().enumerate() {
        let r = (2.0 - 0.0025 * (k + 1) as f64) * 25.4;
        let want = xy(r, 4.5 * (k + 1) as f64);
        assert!(
            (c[0] - want[0]).abs() < 1e-6 && (c[1] - want[1]).abs() < 1e-6,
            "step {k}: {c:?} vs {want:?}"
        );
    }
}

#[test]
fn both_writers_round_trip_polar_programs() {
    let src = "G21 G90 G17\nG0 @10 ^30\nG1 ^90 F600\nG91 G1 @-2 ^45\nG90 G0 Z5\nM30\n";
    let p = prog(src);
    let flat = mtmotion::nc::writer::write(&p, &p.segments);
    assert!(!flat.contains('@') && !flat.contains('^'), "{flat}");
    let q = prog(&flat);
    for (a, b) in p.segments.iter().zip(&q.segments) {
        assert!(
            mtmotion::nc::program::dist(a.end.p(), b.end.p()) < 1e-4,
            "{flat}"
        );
    }
    assert_eq!(write_source(src, &p, &p.segments), src);
}

#[test]
fn polar_words_are_refused_where_linuxcnc_refuses_them() {
    for (src, line, col, phrase) in [
        ("G1 X1 @2 ^3 F100", 1, 4, "X1 with the polar word @2"),
        ("G18\nG1 @2 ^3 F100", 2, 4, "outside the G17 plane"),
        ("G28 @2", 1, 5, "polar word @2 on a G28 block"),
    ] {
        let first = parse(src).unwrap_err();
        assert_eq!((first.line, first.column), (line, col), "{src}: {first}");
        assert!(first.message.contains(phrase), "{src}: {first}");
    }
}
