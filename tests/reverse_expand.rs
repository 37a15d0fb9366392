//! Proves that reverse compensation writes a program flat when its
//! largest error sits on moves the program computes
//! (`src/compensate/reverse/mod.rs`, `crate::nc::writer::write_expanded`):
//! a Macro B program the team wrote (an ellipse of chords from a WHILE
//! loop, in G55 with a G43 tool length offset) is compensated written
//! flat, its result measured against the original program's own path;
//! every M, S, T, H and frame word is kept in order; an inch canned cycle
//! is written in millimetres after a `G21 G90 G94 G17` block; and a
//! program that a flat text would lose something of (G41, a computed S
//! word, an M8 in a subprogram body, G10) is not written flat, saying
//! where and why, as is every program with `expand: false`.

use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
use mtmotion::nc::program::parse;
use mtmotion::nc::writer::{write_expanded, FLAT_MODES};
use mtmotion::toolpath::simulate;

/// An ellipse pocket wall, 25 × 14 mm about (12.5, 12.25), in 7.5° chords
/// computed by a WHILE loop, at F2400, then a feed retract; work offset
/// G55, tool length G43.
const MACRO: &str = "%
O2001 (TEAM: ELLIPSE WALL BY MACRO)
G21 G17 G90 G55
T3 M6
S8000 M3
G0 G43 H3 X37.5 Y12.25 Z5.
M8
G1 Z-1.2 F400.
#1=7.5
WHILE [#1 LE 367.5] DO1
G1 X[12.5+25.*COS[#1]] Y[12.25+14.*SIN[#1]] F2400.
#1=#1+7.5
END1
G1 Z1. F400.
G0 Z5.
M9
M5
M30
%
";

fn cfg() -> ReverseConfig {
    let mut c = ReverseConfig::default();
    c.sim.t_a = 0.04;
    c.sim.t = mtmotion::toolpath::Lag::All(0.015);
    c.sim.dt = 1e-3;
    c
}

#[test]
fn a_macro_program_is_compensated_written_flat() {
    let c = reverse_compensate(MACRO, &cfg()).unwrap();
    assert!(c.expanded, "{:?} {:?}", c.expand_note, c.unchanged);
    assert!(c.unchanged.is_none());
    // In place no chord can move (every one is macro-computed): at most a
    // dwell after the plunge, and the wall's error stays.
    let mut off = cfg();
    off.expand = false;
    let inplace = reverse_compensate(MACRO, &off).unwrap();
    assert!(!inplace.expanded && inplace.expand_note.is_none());
    assert!(inplace.nc.contains("WHILE [#1 LE 367.5] DO1"));
    assert!(inplace.after.max_error_um > 0.9 * inplace.before.max_error_um);
    // Before: the original against its own path, the same either way.
    assert_eq!(c.before, inplace.before);
    assert!(c.before.max_error_um > 20.0, "{}", c.before.max_error_um);
    assert!(
        c.after.max_error_um < 0.5 * c.before.max_error_um,
        "{} -> {}",
        c.before.max_error_um,
        c.after.max_error_um
    );
    assert!(c.after.motion_time <= c.before.motion_time * 1.05 + 1e-9);
    // After: the written text against the ORIGINAL program's path.
    let orig = parse(MACRO).unwrap();
    let written = parse(&c.nc).unwrap();
    let again = simulate(&written.segments, &orig.segments, &cfg().sim).unwrap();
    assert!((again.max_error * 1e3 - c.after.max_error_um).abs() < 1e-9);
    assert!((again.motion_time - c.after.motion_time).abs() < 1e-12);
    // The flat text has no macro code and keeps every passive word, in order.
    assert!(!c.nc.contains('#') && !c.nc.contains("WHILE"), "{}", c.nc);
    let lines: Vec<&str> = c.nc.lines().collect();
    assert_eq!(lines[0], "%");
    assert_eq!(lines[1], FLAT_MODES);
    let find = |w: &str| {
        let hits: Vec<usize> = (0..lines.len())
            .filter(|&i| lines[i].split(' ').any(|x| x == w))
            .collect();
        assert_eq!(hits.len(), 1, "{w} in {}", c.nc);
        hits[0]
    };
    let order: Vec<usize> = [
        "G55", "T3", "M6", "S8000", "M3", "G43", "H3", "M8", "M9", "M5", "M30",
    ]
    .iter()
    .map(|w| find(w))
    .collect();
    assert!(
        order.windows(2).all(|w| w[0] <= w[1]),
        "{order:?}\n{}",
        c.nc
    );
    assert_eq!(find("G43"), find("H3"), "G43 and its H stay in one block");
}

#[test]
fn an_inch_canned_cycle_is_written_in_millimetres_after_the_modes() {
    // Two G81 holes and a G1 slot between them, in inch, absolute.
    let src = "G20 G17 G90 G54\nG0 X0.25 Y0.4 Z0.5\nG81 X0.25 Y0.4 Z-0.3 R0.1 F8.\nX1.35 Y0.55\nG80\nG1 Z-0.05 F12.\nX0.25 Y0.45\nG0 Z0.5\nM30\n";
    let p = parse(src).unwrap();
    let (flat, _) = write_expanded(&p).unwrap();
    let lines: Vec<&str> = flat.lines().collect();
    assert_eq!(lines[0], FLAT_MODES);
    assert_eq!(lines[1], "G54");
    assert!(!flat.contains("G81") && !flat.contains("G20"), "{flat}");
    let back = parse(&flat).unwrap();
    assert_eq!(back.segments.len(), p.segments.len());
    for (a, b) in p.segments.iter().zip(&back.segments) {
        assert!(
            (a.end.x - b.end.x).abs() < 1e-4 && (a.end.z - b.end.z).abs() < 1e-4,
            "{a:?} {b:?}"
        );
    }
    // The hole bottom in mm: -0.3 in.
    assert!(back.segments.iter().any(|s| (s.end.z + 7.62).abs() < 1e-9));
}

/// `src` is not written flat, and the reason names `what`.
fn refused(src: &str, what: &str) {
    let p = parse(src).unwrap();
    let why = write_expanded(&p).unwrap_err();
    assert!(why.contains(what), "{why}");
}

#[test]
fn what_a_flat_program_would_lose_is_refused_by_line() {
    // Cutter compensation with an unknown radius: the moves are the contour.
    refused(
        "G21 G90 G0 X0 Y0 Z1\n#1=10\nG41 D1 G1 X#1 Y0 F500\nY10\nG40 X0 Y0\nM30\n",
        "line 3: cutter compensation (G41)",
    );
    // A spindle speed computed by macro code.
    refused(
        "G21 G90\n#1=6000\nS#1 M3\nG0 X0 Y0\n#2=5\nG1 X#2 F300\nM30\n",
        "line 3, column 1: its S word is computed",
    );
    // Coolant switched in a subprogram body: the flat text would lose it.
    refused(
        "G21 G90 G0 X0 Y0 Z1\nM98 P100\nM30\nO100\nM8\nG1 X5 F300\nM99\n",
        "line 5: its M8",
    );
    // G10 sets a work offset in the source's units.
    refused(
        "G20 G90\nG10 L2 P1 X1. Y2.\n#1=1\nG0 X#1 Y0\nM30\n",
        "line 2: G10",
    );
}

#[test]
fn subprogram_calls_and_numbered_bodies_are_written_flat() {
    // The body's N numbers and the M98/M99 calls go (the flat text runs
    // the body's moves in place); nothing that matters is lost.
    // The call is a macro line (its P computed): its literal M98 is no
    // word a flat program must keep either.
    let src = "N10 G21 G90 G0 X0 Y0 Z1\n#1=100\nN20 M98 P#1 L2\nN30 M30\nO100\nN100 G91 G1 X5. Y1. F300\nN110 G90\nN120 M99\n";
    let p = parse(src).unwrap();
    let (flat, _) = write_expanded(&p).unwrap();
    assert!(!flat.contains("M98") && !flat.contains("N100"), "{flat}");
    let back = parse(&flat).unwrap();
    let ends: Vec<f64> = back.segments.iter().map(|s| s.end.x).collect();
    assert_eq!(ends, vec![0.0, 5.0, 10.0], "{flat}");
}

#[test]
fn a_program_that_cannot_be_written_flat_says_why_in_the_result() {
    // The error sits on the macro-computed chords, but S is computed too.
    let src = MACRO.replace("S8000 M3", "#9=8000\nS#9 M3");
    let c = reverse_compensate(&src, &cfg()).unwrap();
    assert!(!c.expanded);
    assert!(c.nc.contains("S#9 M3") && !c.nc.contains(FLAT_MODES));
    let note = c.expand_note.as_deref().unwrap();
    assert!(
        note.starts_with("not written flat: line 6, column 1: its S word"),
        "{note}"
    );
}

/// The progress of a compensation written flat: the run in place reports
/// the first half (its fractions times 0.5, as a share of the whole), the
/// flat run the second (0.5 + 0.5 × its fraction, its messages prefixed
/// "written flat: "); every fraction within [0, 1] and never going back.
#[test]
fn progress_of_a_flat_compensation_runs_through_both_halves_in_order() {
    let mut seen: Vec<(f64, String)> = Vec::new();
    let c = mtmotion::compensate::reverse::reverse_compensate_with(MACRO, &cfg(), &mut |f, s| {
        seen.push((f, s.to_string()));
        true
    })
    .unwrap();
    assert!(c.expanded);
    // Measured: in place 0, 0.05, 0.125, 0.25, 0.35, 0.35, 0.5 ("done"),
    // then flat 0.5, 0.55, 0.625, 0.75, 0.85, 0.85, 1.
    let flat = seen
        .iter()
        .position(|(_, s)| s.starts_with("written flat: "))
        .expect("the flat run reports");
    assert!(flat >= 5, "{seen:?}");
    assert!(seen[..flat]
        .iter()
        .all(|(f, s)| *f <= 0.5 && !s.contains("flat")));
    assert!(seen[flat..]
        .iter()
        .all(|(f, s)| *f >= 0.5 && s.starts_with("written flat: ")));
    assert!(seen.windows(2).all(|w| w[0].0 <= w[1].0), "{seen:?}");
    assert_eq!((seen[0].0, seen[flat - 1].0), (0.0, 0.5), "{seen:?}");
    assert_eq!(seen[flat].0, 0.5);
    assert_eq!(seen.last().unwrap().0, 1.0, "{seen:?}");
    // A stage in between: the in-place run's correction rounds at
    // 0.25 × 0.5, the flat run's at 0.5 + 0.25 × 0.5.
    let at = |name: &str| seen.iter().find(|(_, s)| s == name).map(|x| x.0);
    assert_eq!(at("correction rounds"), Some(0.125));
    assert_eq!(at("written flat: correction rounds"), Some(0.625));
}
