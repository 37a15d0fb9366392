//! Haas and Fanuc shop-floor constructs: Haas `M97 P… (L…)` local
//! subprogram calls to an N-numbered block of the same program (with
//! repeats, nested in and around M98 calls), Fanuc/Haas `M99 P…` returns
//! to a sequence number (from a subprogram and in the main program), and
//! the Haas machining settings G187 (P, E) and G103 (P), accepted with one
//! warning each. End points are checked exactly against positions worked
//! out by hand here (every coordinate is a whole or half millimetre, so
//! the interpreter's sums are exact in binary floating point: tolerance 0).
//! Both writers must round-trip these programs (`parse → write → parse`),
//! and reverse compensation must leave the M97 bodies' segments in place.

#[path = "support/fuzz_targets.rs"]
mod fuzz_targets;

use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
use mtmotion::nc::program::{
    parse, parse_all, parse_with, Motion, ParseOptions, Program, MAX_NESTING,
};

/// A Haas-style program as a Haas post writes it: `%`, an O number, N
/// numbers, G187/G103 settings, tool change, work offset, length
/// compensation, two local subprograms after M30 (a G91 square step
/// called three times with L3, a G91 full circle called once).
const HAAS: &str = "%
O01234 (HAAS M97 DEMO)
(T1 D10 FLAT ENDMILL)
N10 G00 G17 G40 G49 G80 G90 G21
N20 G187 P1 E0.01 (ROUGH)
N30 G103 P1
N40 T1 M06
N50 G00 G90 G54 X-5. Y-5. S3000 M03
N60 G43 H01 Z5.
N70 G01 Z-1. F300.
N80 M97 P1000 L3
N90 G90 G00 X50. Y0.
N100 M97 P2000
N110 G187 P3 E0.002 (FINISH)
N120 G00 Z50. M09
N130 M30
N1000 (SQUARE STEP)
G91 G01 X10. F600.
Y10.
X-10.
Y-10.
X5. (STEP OVER)
G90
M99
N2000 (CIRCLE)
G91 G02 X0. Y0. I5. J0. F500.
G90
M99
%
";

fn parsed(src: &str) -> Program {
    parse(src).unwrap_or_else(|e| panic!("{e}\n{src}"))
}

fn ends(p: &Program) -> Vec<[f64; 3]> {
    p.segments.iter().map(|s| s.end.p()).collect()
}

/// The line (1-based) of the first line of `src` that starts with `head`.
fn line_of(src: &str, head: &str) -> usize {
    1 + src
        .lines()
        .position(|l| l.starts_with(head))
        .unwrap_or_else(|| panic!("no line {head}"))
}

#[test]
fn haas_program_with_m97_bodies_runs_exactly() {
    let p = parsed(HAAS);
    // By hand: the approach, then three runs of the square step from
    // x0 = -5, 0, 5 (each ends 5 mm further in X), the rapid, the circle.
    let mut want = vec![[-5.0, -5.0, 0.0], [-5.0, -5.0, 5.0], [-5.0, -5.0, -1.0]];
    for k in 0..3 {
        let x0 = -5.0 + 5.0 * k as f64;
        for (x, y) in [
            (10.0, 0.0),
            (10.0, 10.0),
            (0.0, 10.0),
            (0.0, 0.0),
            (5.0, 0.0),
        ] {
            want.push([x0 + x, -5.0 + y, -1.0]);
        }
    }
    want.extend([[50.0, 0.0, -1.0], [50.0, 0.0, -1.0], [50.0, 0.0, 50.0]]);
    assert_eq!(ends(&p), want);
    let Motion::Arc(a) = p.segments[19].motion else {
        panic!("{:?}", p.segments[19])
    };
    assert_eq!(a.center, [55.0, 0.0, -1.0]);
    assert_eq!(a.sweep, -2.0 * std::f64::consts::PI);
    // The body's segments come from its lines, and are fixed (run 3 times).
    let body = line_of(HAAS, "G91 G01 X10.");
    let lines: Vec<usize> = p.segments[3..8].iter().map(|s| s.line).collect();
    assert_eq!(lines, (body..body + 5).collect::<Vec<_>>());
    assert!(p.segments[3..18].iter().all(|s| s.fixed) && p.segments[19].fixed);
    assert!(!p.segments[2].fixed && !p.segments[18].fixed && !p.segments[20].fixed);
    assert_eq!(p.segments[3].feed, 600.0);
    assert_eq!(p.segments[20].motion, Motion::Rapid);
}

#[test]
fn g187_and_g103_give_one_warning_each_and_no_error() {
    let p = parsed(HAAS);
    let at = |line: usize| -> Vec<String> {
        p.warnings
            .iter()
            .filter(|w| w.line == line)
            .map(|w| format!("{}:{}", w.column, w.message))
            .collect()
    };
    for (head, code, words) in [
        ("N20", "G187", "P1 E0.01"),
        ("N30", "G103", "P1"),
        ("N110", "G187", "P3 E0.002"),
    ] {
        let w = at(line_of(HAAS, head));
        assert_eq!(w.len(), 1, "{head}: {w:?}");
        let want = format!("{code} {words} (Haas ");
        let col = format!("{}:", head.len() + 2);
        assert!(w[0].starts_with(&col) && w[0].contains(&want), "{w:?}");
        assert!(w[0].contains("not modelled"), "{w:?}");
        assert!(w[0].contains("acc/dec"), "{w:?}");
    }
    // No "blocks after the program end" warning for the bodies M97 ran.
    assert!(p.warnings.iter().all(|w| !w.message.contains("not run")));
    // G187 alone, and G103 P0 (look-ahead unlimited), are accepted too.
    let q = parsed("G187\nG103 P0\nG0 X1");
    assert_eq!(q.warnings.len(), 2, "{:?}", q.warnings);
    // An E word elsewhere still refuses the program as a 3D-printer one,
    // and a P/E word on a block with an unknown G code is still warned.
    let e = parse("G187 P2\nG1 X1 E0.5 F100").unwrap_err();
    assert_eq!((e.line, e.column), (2, 7), "{e}");
    assert!(e.message.contains("3D-printer"), "{e}");
    let q = parsed("G123 P1\nG0 X1");
    assert_eq!(q.warnings.len(), 2, "{:?}", q.warnings);
    assert!(q.warnings[1].message.contains("unknown word P1"));
}

/// M97 inside an M98 body (to an N block of that O-program) and M98
/// inside an M97 body, repeated.
#[test]
fn m97_and_m98_nest_in_each_other() {
    let src = "G0 X0 Y0\nM98 P2000\nM97 P500 L2\nM30\nN500 G91 G1 X1 F100\nM98 P2000\nG90\nM99\nO2000\nG91 G1 Y1 F100\nM97 P10\nG90\nM99\nN10 G91 G1 Z-1\nG90\nM99\n";
    // By hand: Y1, Z-1 (the O2000 call); then twice: X1, Y1, Z-1.
    let want = vec![
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 1.0, -1.0],
        [1.0, 1.0, -1.0],
        [1.0, 2.0, -1.0],
        [1.0, 2.0, -2.0],
        [2.0, 2.0, -2.0],
        [2.0, 3.0, -2.0],
        [2.0, 3.0, -3.0],
    ];
    assert_eq!(ends(&parsed(src)), want);
    // The N number is searched in the calling O-program only: N10 belongs
    // to O2000, so the main program's M97 P10 does not find it.
    let e = parse("G0 X0\nM97 P10\nM30\nO2000\nN10 G1 X1 F100\nM99").unwrap_err();
    assert_eq!((e.line, e.column), (2, 5), "{e}");
    assert!(
        e.message
            .starts_with("M97 P10: no block N10 in this program"),
        "{e}"
    );
}

#[test]
fn m97_repeats_follow_the_m98_rules() {
    let body = "M30\nN7 G91 G1 X1 F100\nG90\nM99";
    let xs = |call: &str| -> Vec<f64> {
        parsed(&format!("G0 X0\n{call}\n{body}"))
            .segments
            .iter()
            .map(|s| s.end.x)
            .collect()
    };
    assert_eq!(xs("M97 P7"), vec![0.0, 1.0]);
    assert_eq!(xs("M97 P7 L4"), vec![0.0, 1.0, 2.0, 3.0, 4.0]);
    assert_eq!(xs("M97 P7 L0"), vec![0.0], "L0: not run");
    let e = parse(&format!("G0 X0\nM97 P7 L2.5\n{body}")).unwrap_err();
    assert_eq!((e.line, e.column), (2, 8), "{e}");
    assert!(
        e.message.contains("expected a whole number from 0 to 9999"),
        "{e}"
    );
    let e = parse(&format!("G0 X0\nM97\n{body}")).unwrap_err();
    assert!(e.message.contains("M97 without P"), "{e}");
    let e = parse(&format!("G0 X0\nM97 P-7\n{body}")).unwrap_err();
    assert!(
        e.message.contains("expected a whole sequence number"),
        "{e}"
    );
    // Runaway recursion meets the nesting limit, located at the M97.
    let e = parse("M97 P1\nM30\nN1 M97 P1\nM99").unwrap_err();
    assert_eq!((e.line, e.column), (3, 4), "{e}");
    assert!(
        e.message.contains(&format!("deeper than {MAX_NESTING}")),
        "{e}"
    );
    // A body without M99 that runs into the next O-program is named.
    let e = parse("M97 P1\nM30\nN1 G0 X1\nO2\nM99").unwrap_err();
    assert_eq!(e.line, 4);
    assert!(
        e.message
            .contains("local subprogram N1 (M97) reaches the next program O2"),
        "{e}"
    );
    // Repeats count against the executed-block budget.
    let small = ParseOptions {
        max_executed_blocks: 100,
        ..ParseOptions::default()
    };
    let e = parse_with(&format!("G0 X0\nM97 P7 L200\n{body}"), &small).unwrap_err();
    assert!(e.message.contains("blocks executed"), "{e}");
}

#[test]
fn missing_m97_target_is_a_located_error_saying_what_to_do() {
    let src = "O1000\nG0 X0\nN80 M97 P1000 L2\nM30\nN100 G1 X1 F100\nM99\n%";
    let e = parse(src).unwrap_err();
    assert_eq!((e.line, e.column), (3, 9), "{e}");
    assert_eq!(
        e.message,
        "M97 P1000: no block N1000 in this program; a local subprogram starts at a block numbered N1000 in the same O-program as the M97 (usually after M30) and ends with M99; add that block or correct the P number"
    );
}

#[test]
fn m99_p_returns_to_a_sequence_number_of_the_caller() {
    // The block after the call is skipped: the return goes to N50.
    let src = "G0 X0 Y0\nM98 P100\nG0 X1\nN50 G0 X2\nM30\nO100\nG91 G1 Y1 F100\nG90\nM99 P50";
    assert_eq!(
        ends(&parsed(src)),
        vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [2.0, 1.0, 0.0]]
    );
    // With L2 the body repeats first, then returns to N50.
    let src2 = src.replace("M98 P100", "M98 P100 L2");
    assert_eq!(
        ends(&parsed(&src2)),
        vec![
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 2.0, 0.0],
            [2.0, 2.0, 0.0]
        ]
    );
    // From an M97 body too.
    let src3 = "G0 X0 Y0\nM97 P100\nG0 X1\nN50 G0 X2\nM30\nN100 G91 G1 Y1 F100\nG90\nM99 P50";
    assert_eq!(
        ends(&parsed(src3)),
        vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [2.0, 1.0, 0.0]]
    );
    // Two N50 in the caller: the one after the call is taken first.
    let src4 = "N50 G0 X5\nM98 P100\nG0 X1\nN50 G0 X7\nM30\nO100\nM99 P50";
    let x: Vec<f64> = parsed(src4).segments.iter().map(|s| s.end.x).collect();
    assert_eq!(x, vec![5.0, 7.0]);
    // Only before the call: the search wraps to the start, so this program
    // calls O100 again and again; the executed-block budget stops it.
    let small = ParseOptions {
        max_executed_blocks: 200,
        ..ParseOptions::default()
    };
    let e = parse_with("N50 G0 X5\nM98 P100\nM30\nO100\nM99 P50", &small).unwrap_err();
    assert!(e.message.contains("more than 200 blocks executed"), "{e}");
    // A missing N in the caller: located at the P word.
    let e = parse("G0 X0\nM98 P100\nM30\nO100\nG1 X1 F100\nM99 P77").unwrap_err();
    assert_eq!((e.line, e.column), (6, 5), "{e}");
    assert!(
        e.message
            .starts_with("M99 P77: no block N77 in the calling program"),
        "{e}"
    );
    // A bad P is one error at it; the M99 still returns (no second error).
    let e = parse_all(
        "G0 X0\nM98 P100\nM30\nO100\nM99 P1.5",
        &ParseOptions::default(),
    )
    .unwrap_err();
    assert_eq!(e.errors.len(), 1, "{e:?}");
    assert_eq!((e.errors[0].line, e.errors[0].column), (5, 5));
    assert!(
        e.errors[0]
            .message
            .contains("expected a whole sequence number"),
        "{e:?}"
    );
}

#[test]
fn m99_p_in_the_main_program() {
    // Backwards: endless on the control; warned, simulated once.
    let p = parsed("N10 G0 X0\nG0 X1\nM99 P10\nG0 X9");
    let x: Vec<f64> = p.segments.iter().map(|s| s.end.x).collect();
    assert_eq!(x, vec![0.0, 1.0]);
    let w: Vec<_> = p
        .warnings
        .iter()
        .filter(|w| w.message.contains("M99 P10"))
        .collect();
    assert_eq!(w.len(), 1, "{:?}", p.warnings);
    assert_eq!((w[0].line, w[0].column), (3, 5));
    assert!(w[0].message.contains("endlessly") && w[0].message.contains("simulated once"));
    // Forwards: the blocks between are skipped and the run goes on.
    let p = parsed("G0 X0\nM99 P30\nG0 X1\nN30 G0 X2\nM30");
    let x: Vec<f64> = p.segments.iter().map(|s| s.end.x).collect();
    assert_eq!(x, vec![0.0, 2.0]);
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    let e = parse("G0 X0\nM99 P30\nM30").unwrap_err();
    assert_eq!((e.line, e.column), (2, 5), "{e}");
    assert!(
        e.message
            .starts_with("M99 P30: no block N30 in this program"),
        "{e}"
    );
}

/// Programs with M97 and M99 P through both writers' round trips (the
/// fuzz target's property), and the flat text they are written as.
#[test]
fn writers_round_trip_m97_and_m99_p() {
    let programs = [
        HAAS.to_string(),
        "G0 X0 Y0\nM98 P2000\nM97 P500 L2\nM30\nN500 G91 G1 X1 F100\nM98 P2000\nG90\nM99\nO2000\nG91 G1 Y1 F100\nM97 P10\nG90\nM99\nN10 G91 G1 Z-1\nG90\nM99\n".into(),
        "G0 X0 Y0\nM98 P100 L2\nG0 X1\nN50 G0 X2\nM30\nO100\nG91 G1 Y1 F100\nG90\nM99 P50".into(),
        "N10 G0 X0\nG91 G1 X1 F100\nM99 P10\nG0 X9".into(),
        "G0 X0\nM99 P30\nG91 G0 X1\nN30 G0 X2\nM30".into(),
        "G0 X0\nM97 P7 L0\nG1 X3 F100\nM30\nN7 G1 X1\nM99".into(),
    ];
    for src in &programs {
        fuzz_targets::nc_write_target(src).unwrap_or_else(|e| panic!("{e}\n{src}"));
    }
    // The flat form of the Haas program runs the same path without calls.
    let w = parsed(HAAS).write();
    let calls = mtmotion::nc::lex(&w)
        .unwrap()
        .iter()
        .flat_map(|b| b.words.clone())
        .filter(|x| x.letter == 'M' && matches!(x.text.as_str(), "97" | "99"))
        .count();
    assert_eq!(calls, 0, "{w}");
    assert!(w.contains("(HAAS M97 DEMO)"), "{w}");
    assert_eq!(ends(&parsed(&w)), ends(&parsed(HAAS)));
}

/// Reverse compensation of a program with an M97 body called twice (the
/// arc example, qiu Fig. 2-like, with a call before its M30): the body's
/// segments are fixed and stay where they were, the calls are kept, the
/// error falls, and the connecting lines it inserts are numbered without
/// taking the body's number N341 (the line after N340 would otherwise be
/// N341, and M97 P341 would run it instead of the body).
#[test]
fn reverse_compensation_keeps_m97_bodies_fixed() {
    let ex = mtmotion::toolpath::example::arc_example();
    assert!(
        ex.contains("\nN340 G2") && ex.contains("\nN480 M30"),
        "{ex}"
    );
    let src = ex.replace(
        "N480 M30",
        "N475 M97 P341 L2\nN480 M30\nN341 G91 G1 Y1.\nG1 Y-1.\nG90\nM99",
    );
    let p = parsed(&src);
    let c = reverse_compensate(&src, &ReverseConfig::default()).unwrap();
    let q = parsed(&c.nc);
    let fixed = |p: &Program| -> Vec<[f64; 3]> {
        p.segments
            .iter()
            .filter(|s| s.fixed)
            .map(|s| s.end.p())
            .collect()
    };
    assert_eq!(fixed(&p).len(), 4);
    assert_eq!(fixed(&p), fixed(&q), "fixed end points moved:\n{}", c.nc);
    for keep in ["N475 M97 P341 L2", "N341 G91 G1 Y1.", "M99"] {
        assert!(c.nc.contains(keep), "{keep} lost:\n{}", c.nc);
    }
    assert!(
        c.after.max_error_um < 0.5 * c.before.max_error_um,
        "{} -> {} um",
        c.before.max_error_um,
        c.after.max_error_um
    );
    assert!(
        c.nc.contains("\nN331 G1"),
        "no numbered inserted line:\n{}",
        c.nc
    );
    let ns: Vec<&str> =
        c.nc.lines()
            .filter_map(|l| l.split_whitespace().next().filter(|w| w.starts_with('N')))
            .collect();
    let mut sorted = ns.clone();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(sorted.len(), ns.len(), "{}", c.nc);
}

/// With the subprogram in its own file: its M97 finds N10 in that file,
/// and its M99 P50 returns to N50 of the main program's file.
#[test]
fn m97_and_m99_p_across_files() {
    use mtmotion::nc::files::{parse_files, NcFile};
    let sub = NcFile {
        name: "O2000.nc".into(),
        text: "O2000\nG91 G1 Y1 F100\nM97 P10\nG90\nM99 P50\nN10 G91 G1 Z-1\nG90\nM99".into(),
    };
    let main = "G0 X0 Y0\nM98 P2000\nG0 X1\nN50 G0 X2\nM30";
    let p = parse_files(main, &[sub], &ParseOptions::default()).unwrap();
    assert_eq!(
        ends(&p),
        vec![
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 1.0, -1.0],
            [2.0, 1.0, -1.0]
        ]
    );
    // The main program's M97 does not reach N10 of the other file.
    let sub = NcFile {
        name: "O2000.nc".into(),
        text: "O2000\nN10 G1 X1 F100\nM99".into(),
    };
    let e = parse_files("M97 P10\nM30", &[sub], &ParseOptions::default()).unwrap_err();
    assert_eq!((e.errors[0].line, e.errors[0].column), (1, 5));
    assert_eq!(e.errors[0].file, None);
}
