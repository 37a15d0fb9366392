//! Fadal format-2 `L` subroutines (issue 25): team-written Fadal jobs
//! whose definitions (`L0100` … `M17`) and calls (`Lnnrr`, `rr` times) run
//! exactly the moves of the same job written out by hand without
//! subroutines (an independent second program, compared segment by
//! segment), in inch (G70, G20) and mm (G71); the called moves are
//! `fixed` like other subprogram bodies; each malformed definition or call
//! is refused at its line and column.

use mtmotion::nc::program::{parse, parse_all, ParseOptions, Program};
use mtmotion::nc::segment::{Motion, Segment};

/// Parses `src`, panicking with the program's errors.
fn run(src: &str) -> Program {
    parse(src).unwrap_or_else(|e| panic!("{e}\n{src}"))
}

/// The moves of `a` and `b` agree segment by segment: the same motion
/// (arc data included) and feed, start and end within 1e-12 mm.
fn assert_same_moves(a: &[Segment], b: &[Segment]) {
    assert_eq!(a.len(), b.len(), "segment counts");
    for (k, (s, t)) in a.iter().zip(b).enumerate() {
        let d = |p: &mtmotion::nc::segment::Pose, q: &mtmotion::nc::segment::Pose| {
            [
                p.x - q.x,
                p.y - q.y,
                p.z - q.z,
                p.a - q.a,
                p.b - q.b,
                p.c - q.c,
            ]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
        };
        assert!(
            d(&s.start, &t.start) < 1e-12 && d(&s.end, &t.end) < 1e-12,
            "segment {k}: {s:?} vs {t:?}"
        );
        assert_eq!(
            (s.motion, s.feed),
            (t.motion, t.feed),
            "segment {k} (lines {} and {})",
            s.line,
            t.line
        );
    }
}

/// An inch job (G70): subroutine 1 drills three holes in G91 increments
/// (called twice under a G81 with tool 1), subroutine 2 steps down 0.05 in
/// and cuts an arc and a line in G91 (called three times with tool 2);
/// the definitions end with the Fadal `M30` before the main program.
const INCH_JOB: &str = "%
N1 O1234 (FADAL FORMAT 2 JOB)
N2 L100 (SUB 1: THREE HOLES, INCREMENTAL)
N3 G91 X0.75 Y0.125
N4 X0.75 Y0.125
N5 X0.75 Y0.125
N6 G90 M17
N7 L0200 (SUB 2: ONE STEP OF A POCKET)
N8 G91 G17 G1 Z-0.05 F12. M8
N9 G3 X0.5 Y0.5 I0. J0.5
N10 G1 X-0.5 Y-0.5
N11 G90 M9 M17
(END OF THE SUBROUTINES)
N12 M30
N13 G70
N14 T1 M6
N15 G0 G90 G0 E1 X1.25 Y0.5 Z0.1 S2000 M3
N16 G81 X1.25 Y0.5 Z-0.3 R0.1 F8.
N17 L102
N18 G80
N19 T2 M6
N20 G0 X0.5 Y2.25 Z0.1
N21 G1 Z0. F20.
N22 L0203
N23 G0 Z1.
N24 M30
%";

/// [`INCH_JOB`] written out by hand: no subroutines, each call's blocks
/// repeated in place.
const INCH_BY_HAND: &str = "%
O1234
G70
T1 M6
G0 G90 X1.25 Y0.5 Z0.1 S2000 M3
G81 X1.25 Y0.5 Z-0.3 R0.1 F8.
G91 X0.75 Y0.125
X0.75 Y0.125
X0.75 Y0.125
G90
G91 X0.75 Y0.125
X0.75 Y0.125
X0.75 Y0.125
G90
G80
T2 M6
G0 X0.5 Y2.25 Z0.1
G1 Z0. F20.
G91 G17 G1 Z-0.05 F12. M8
G3 X0.5 Y0.5 I0. J0.5
G1 X-0.5 Y-0.5
G90 M9
G91 G17 G1 Z-0.05 F12. M8
G3 X0.5 Y0.5 I0. J0.5
G1 X-0.5 Y-0.5
G90 M9
G91 G17 G1 Z-0.05 F12. M8
G3 X0.5 Y0.5 I0. J0.5
G1 X-0.5 Y-0.5
G90 M9
G0 Z1.
M30
%";

#[test]
fn an_inch_job_in_subroutines_moves_as_the_job_written_out() {
    let p = run(INCH_JOB);
    let q = run(INCH_BY_HAND);
    assert_same_moves(&p.segments, &q.segments);
    // Independently: the six holes the calls drill (after the first at
    // X1.25 Y0.5) step by 0.75, 0.125 in; the drill feeds to Z-0.3 in.
    let bottoms: Vec<(f64, f64)> = p
        .segments
        .iter()
        .filter(|s| (s.end.z + 0.3 * 25.4).abs() < 1e-9)
        .map(|s| (s.end.x, s.end.y))
        .collect();
    assert_eq!(bottoms.len(), 7, "{bottoms:?}");
    for (k, (x, y)) in bottoms.iter().enumerate() {
        let k = k as f64;
        assert!(
            (x - (1.25 + 0.75 * k) * 25.4).abs() < 1e-9
                && (y - (0.5 + 0.125 * k) * 25.4).abs() < 1e-9,
            "hole {k}: {x} {y}"
        );
    }
    // Three pocket steps: the last cut ends 0.15 in below Z0.
    let lowest = p.segments.iter().map(|s| s.end.z).fold(f64::MAX, f64::min);
    assert!((lowest + 0.3 * 25.4).abs() < 1e-9);
    let pocket_floor = p
        .segments
        .iter()
        .filter(|s| s.line == 11)
        .map(|s| s.end.z)
        .collect::<Vec<_>>();
    assert_eq!(pocket_floor.len(), 3);
    for (k, z) in pocket_floor.iter().enumerate() {
        assert!((z + 0.05 * (k + 1) as f64 * 25.4).abs() < 1e-9, "{z}");
    }
    // The called moves are fixed (their words run more than once), the
    // main program's are not.
    for s in &p.segments {
        // (line k + 1 holds N k up to N11, k + 2 after it; N16 is the
        // G81 block, a cycle's moves)
        let called = (4..=12).contains(&s.line);
        assert_eq!(s.fixed, called || s.line == 18, "line {} {s:?}", s.line);
    }
    let w: Vec<String> = p.warnings.iter().map(|w| w.to_string()).collect();
    let marker: Vec<&String> = w
        .iter()
        .filter(|m| m.contains("ends the definitions"))
        .collect();
    assert_eq!(marker.len(), 1, "{w:?}");
    assert!(marker[0].starts_with("line 14, column 5:"), "{marker:?}");
    assert!(
        w.iter().all(|m| !m.contains("M17") && !m.contains("L10")),
        "{w:?}"
    );
    // The M17 block's other words run before the return (M9 is warned
    // about, as any M word the motion model ignores, once per run).
    assert_eq!(
        w.iter()
            .filter(|m| m.starts_with("line 12") && m.contains("M9"))
            .count(),
        3,
        "{w:?}"
    );
}

/// A mm job (G71, then G21): subroutine 3 calls subroutine 1 (two levels),
/// subroutine 1 mills a G91 step; no `M30` between the definitions and the
/// main program; counts 4 and 2; an `M17` block with a move on it.
const MM_JOB: &str = "O0042
N10 L100
N11 G91 G1 X4.5 Y-1.25 F300.
N12 G90 Z-1. M17
N20 L300
N21 G91 G0 Z2.5
N22 L0104
N23 G90 M17
G71
G0 X12.5 Y7.25 Z5.
G1 Z-1. F150.
L302
G21 G0 X-3. Y40.
L101
M2";

const MM_BY_HAND: &str = "O0042
G71
G0 X12.5 Y7.25 Z5.
G1 Z-1. F150.
G91 G0 Z2.5
G91 G1 X4.5 Y-1.25 F300.
G90 Z-1.
G91 G1 X4.5 Y-1.25 F300.
G90 Z-1.
G91 G1 X4.5 Y-1.25 F300.
G90 Z-1.
G91 G1 X4.5 Y-1.25 F300.
G90 Z-1.
G90
G91 G0 Z2.5
G91 G1 X4.5 Y-1.25 F300.
G90 Z-1.
G91 G1 X4.5 Y-1.25 F300.
G90 Z-1.
G91 G1 X4.5 Y-1.25 F300.
G90 Z-1.
G91 G1 X4.5 Y-1.25 F300.
G90 Z-1.
G90
G21 G0 X-3. Y40.
G91 G1 X4.5 Y-1.25 F300.
G90 Z-1.
M2";

#[test]
fn a_mm_job_with_nested_subroutines_moves_as_the_job_written_out() {
    let p = run(MM_JOB);
    let q = run(MM_BY_HAND);
    assert_same_moves(&p.segments, &q.segments);
    // 8 steps of 4.5 mm from X12.5 in the nested calls, then one from X-3.
    let ends: Vec<f64> = p
        .segments
        .iter()
        .filter(|s| s.line == 3)
        .map(|s| s.end.x)
        .collect();
    let expected: Vec<f64> = (1..=8)
        .map(|k| 12.5 + 4.5 * f64::from(k))
        .chain([1.5])
        .collect();
    assert_eq!(ends.len(), expected.len());
    for (e, x) in ends.iter().zip(&expected) {
        assert!((e - x).abs() < 1e-9, "{ends:?}");
    }
    assert!(p.segments.iter().filter(|s| s.fixed).all(|s| s.line <= 8));
    assert_eq!(p.segments.iter().filter(|s| s.fixed).count(), 2 + 8 * 2 + 2);
    // The same job in inch (G20) moves 25.4 times as far.
    let inch = run(&MM_JOB.replace("G71", "G20").replace("G21", "G20"));
    assert_eq!(inch.segments.len(), p.segments.len());
    for (s, t) in inch.segments.iter().zip(&p.segments) {
        assert!((s.end.x - 25.4 * t.end.x).abs() < 1e-9, "{s:?} {t:?}");
    }
    assert!(matches!(p.segments[1].motion, Motion::Linear));
}

/// The errors of `src`, as (line, column, message).
fn errors(src: &str) -> Vec<(usize, usize, String)> {
    parse_all(src, &ParseOptions::default())
        .unwrap_err()
        .errors
        .into_iter()
        .map(|e| (e.line, e.column, e.message))
        .collect()
}

/// The single error of `src`, at (line, column), containing `text`.
fn refused(src: &str, at: (usize, usize), text: &str) {
    let e = errors(src);
    assert_eq!(e.len(), 1, "{e:?}");
    assert_eq!((e[0].0, e[0].1), at, "{e:?}");
    assert!(e[0].2.contains(text), "{e:?}");
}

#[test]
fn each_malformed_subroutine_is_refused_at_its_line() {
    // A call of a subroutine that is not defined.
    refused(
        "L100\nG0 X1.\nM17\nG0 X2.\nN5 L0301\nM30",
        (5, 4),
        "calls Fadal subroutine 3, which this program does not define",
    );
    refused("G0 X2.\nL101\nM30", (2, 1), "does not define; define it");
    // A definition without M17: before M30, before the end of the text.
    refused(
        "N1 L100\nG0 X1.\nM30",
        (1, 4),
        "subroutine 1 reaches the program end on line 3 without M17",
    );
    refused(
        "G0 X1.\nL200\nG0 X1.",
        (2, 1),
        "reaches the end of its file without M17",
    );
    // A definition inside a definition.
    refused(
        "L100\nG0 X1.\nL200\nG0 X2.\nM17\nM17\nL101\nM30",
        (3, 1),
        "inside the definition of subroutine 1 (line 1)",
    );
    // Defined twice.
    refused(
        "L100\nG0 X1.\nM17\nL100\nG0 X2.\nM17\nL101\nM30",
        (4, 1),
        "defines Fadal subroutine 1 again (it is defined on line 1)",
    );
    // Recursion, directly and through another subroutine.
    refused(
        "L100\nG91 G0 X1.\nL101\nM17\nL101\nM30",
        (3, 1),
        "calls Fadal subroutine 1 from inside itself",
    );
    refused(
        "L100\nG91 G0 X1.\nL201\nM17\nL200\nY1.\nL101\nM17\nL101\nM30",
        (7, 1),
        "calls Fadal subroutine 1 from inside itself",
    );
    // An L word with other words on its block.
    refused("G0 X1. L101\nM30", (1, 8), "on a block with other words");
}

/// Subroutines 1 to `depth`, each calling the next, the last moving.
fn chain(depth: u32) -> String {
    let mut s = String::new();
    for n in 1..depth {
        s += &format!("L{n}00\nG91 G0 X1.\nL{}01\nM17\n", n + 1);
    }
    s + &format!("L{depth}00\nG91 G0 Y1.\nM17\nG90 G0 X10. Y20.\nL101\nM30")
}

#[test]
fn an_m30_after_the_definitions_ends_a_program_with_nothing_after_it() {
    // Definitions only: the M30 is the program end, not the marker.
    let p = run("L100\nG0 X1.\nM17\n(NO MAIN PROGRAM)\nM30\n%");
    assert!(p.segments.is_empty());
    assert!(p
        .warnings
        .iter()
        .all(|w| !w.message.contains("ends the definitions")));
    // An M30 that is not right after the definitions ends the program.
    let p = run("L100\nG0 X1.\nM17\nG0 X2.\nM30\nG0 X3.");
    assert_eq!(p.segments.len(), 1);
    // Nor does one on a block that also moves.
    let p = run("L100\nG0 X1.\nM17\nG0 Z1. M30\nG0 X3.");
    assert_eq!(p.segments.len(), 1);
    assert_eq!(p.segments[0].end.z, 1.0);
    // Two L words on a block are no call.
    refused("L101 L201\nM30", (1, 1), "on a block with other words");
}

#[test]
fn calls_nest_four_levels_and_no_deeper() {
    let p = run(&chain(4));
    let last = p.segments.last().unwrap().end;
    assert_eq!((last.x, last.y), (13.0, 21.0));
    assert_eq!(p.segments.len(), 5);
    refused(&chain(5), (15, 1), "nested deeper than 4 levels");
}

#[test]
fn the_old_refusal_fixture_now_drills() {
    // The job: G81 five holes in subroutine 1, G83 in subroutine 2.
    let src = "%\nN1 L100\nN2 G81 X0 Y0 Z-5. R1. F200\nN3 X10.\nN4 M17\nN5 L200\nN6 G83 X0 Y0 Z-8. R1. Q2. F150\nN7 M17\nN9 G0 G90 G0 E1 X0 Y0 Z10.\nN10 L101\nN11 L201\nN12 M30\n%";
    let p = run(src);
    let bottoms: Vec<(usize, f64)> = p
        .segments
        .iter()
        .filter(|s| matches!(s.motion, Motion::Linear) && s.end.z < 0.0)
        .map(|s| (s.line, s.end.z))
        .collect();
    // (line k + 1 holds N k) G81: two holes to Z-5; G83: pecks of Q2
    // from R1 (-1, -3, -5, -7), then the bottom Z-8.
    assert_eq!(
        bottoms,
        vec![
            (3, -5.0),
            (4, -5.0),
            (7, -1.0),
            (7, -3.0),
            (7, -5.0),
            (7, -7.0),
            (7, -8.0)
        ]
    );
    assert!(p.segments.iter().skip(1).all(|s| s.fixed));
}

#[test]
fn a_fadal_job_is_written_flat_and_reads_back_to_its_moves() {
    // (the third: a call before any move of the main program; its body
    // is written as moves only, as an M98 body is, without its comment)
    let first_call = "L100\nG91 G1 X1. F100. (BODY)\nG90 M17\nL102\nG0 X0\nM30";
    for src in [INCH_JOB, MM_JOB, first_call] {
        let p = run(src);
        let text = mtmotion::nc::writer::write(&p, &p.segments);
        let q = run(&text);
        assert_eq!(q.segments.len(), p.segments.len(), "{text}");
        for (s, t) in p.segments.iter().zip(&q.segments) {
            assert!(
                (s.end.x - t.end.x).abs() < 1e-4 && (s.end.z - t.end.z).abs() < 1e-4,
                "{text}"
            );
        }
        // No subroutine end or definitions' end marker in the flat text,
        // and its only program end is its last block.
        assert!(!text.contains("M17") && !text.contains("BODY"), "{text}");
        let ends: Vec<usize> = text
            .lines()
            .enumerate()
            .filter(|(_, l)| l.contains("M30") || l.contains("M2"))
            .map(|(k, _)| k)
            .collect();
        assert_eq!(
            ends,
            vec![text.lines().count() - 1 - usize::from(text.ends_with("%"))],
            "{text}"
        );
    }
}
