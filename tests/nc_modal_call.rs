//! Fanuc modal macro call G66/G67 (`src/nc/modal_call.rs`): after each
//! move of the level that set it, the macro runs with the G66 block's
//! arguments; G67 cancels; moves inside the macro do not call it again;
//! blocks without motion do not call it. Expected end points are written
//! out by hand from the programs; also the refused cases with their line
//! and column, the flat writer's round trip and reverse compensation.

use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
use mtmotion::nc::program::{parse, Motion, Program};

fn prog(src: &str) -> Program {
    parse(src).unwrap_or_else(|e| panic!("{src}\n{e}"))
}

fn ends(p: &Program) -> Vec<[f64; 3]> {
    p.segments.iter().map(|s| s.end.p()).collect()
}

/// A drilling macro at two positions, then G67: the move, then the macro's
/// plunge at F#9 and its retract to R (#18), each position once.
const DRILL: &str = "G21 G90 G17
G0 X0 Y0 Z10
G66 P9110 R2 Z-5 F100
X10 Y10
M8
X20 Y10
G67
X30 Y0
M30
O9110
G1 Z#26 F#9
G0 Z#18
M99
";

#[test]
fn drilling_macro_runs_after_each_move_until_g67() {
    let p = prog(DRILL);
    assert_eq!(
        ends(&p),
        vec![
            [0.0, 0.0, 10.0],
            [10.0, 10.0, 10.0],
            [10.0, 10.0, -5.0],
            [10.0, 10.0, 2.0],
            [20.0, 10.0, 2.0],
            [20.0, 10.0, -5.0],
            [20.0, 10.0, 2.0],
            [30.0, 0.0, 2.0],
        ]
    );
    let plunges: Vec<f64> = p
        .segments
        .iter()
        .filter(|s| matches!(s.motion, Motion::Linear))
        .map(|s| s.feed)
        .collect();
    assert_eq!(plunges, vec![100.0, 100.0]);
    // The macro's moves are fixed (inside a call); the caller's are not.
    let fixed: Vec<bool> = p.segments.iter().map(|s| s.fixed).collect();
    assert_eq!(
        fixed,
        vec![false, false, true, true, false, true, true, false]
    );
}

/// L2 runs the macro twice per move; the macro's own moves (an X step)
/// do not call it again; a dwell, an F alone and an M code do not call it.
#[test]
fn repeats_and_what_does_not_call() {
    let p = prog(
        "G21 G90\nG0 X0 Y0 Z0\nG66 P100 L2 Z-1\nG1 X5 F300\nG4 P1\nF200\nM9\nG67\nM30\nO100\nG91 G1 Z#26 X1\nG90\nM99\n",
    );
    let e = ends(&p);
    // X5, then two calls each stepping X+1, Z−1; the dwell is a segment.
    assert_eq!(e[1], [5.0, 0.0, 0.0]);
    assert_eq!(e[2], [6.0, 0.0, -1.0]);
    assert_eq!(e[3], [7.0, 0.0, -2.0]);
    assert!(matches!(p.segments[4].motion, Motion::Dwell { .. }));
    assert_eq!(p.segments.len(), 5, "{e:?}");
}

#[test]
fn refused_cases_name_line_and_column() {
    for (src, line, col, phrase) in [
        (
            "G0 X0\nG66 P9999\nX1\nM30\n",
            3,
            1,
            "G66 P9999: macro program O9999 is not in this program",
        ),
        (
            "G0 X0\nG66 P1\nG66 P2\nM30\nO1\nM99\nO2\nM99\n",
            3,
            5,
            "G66 P2 while G66 P1 is in force",
        ),
        ("G66 P1\nG67 X1\nM30\nO1\nM99\n", 2, 5, "X1 on a G67 block"),
        (
            "G0 X0\nG66.1 P1\nM30\n",
            2,
            1,
            "G66.1: a macro call after every block is not supported",
        ),
        ("G66 L2\nM30\n", 1, 1, "G66 without P"),
        (
            "G66 P1 G1\nM30\nO1\nM99\n",
            1,
            8,
            "G1 on a G66 block: a macro-call block takes only P, L and arguments",
        ),
    ] {
        let e = parse(src).unwrap_err();
        assert!(e.message.contains(phrase), "{src}: {e}");
        assert_eq!((e.line, e.column), (line, col), "{src}: {e}");
    }
}

#[test]
fn flat_writer_round_trips_a_modal_call_program() {
    let p = prog(DRILL);
    let flat = mtmotion::nc::writer::write(&p, &p.segments);
    assert!(!flat.contains("G66"), "{flat}");
    let q = prog(&flat);
    assert_eq!(ends(&q), ends(&p), "{flat}");
}

#[test]
fn reverse_compensation_keeps_the_macro_and_is_never_worse() {
    let src = "G21 G90 G17\nG0 X0 Y0 Z5\nG66 P200 Z-1 F600\nG1 X20 F1200\nY20\nX0\nY0\nG67\nG0 Z10\nM30\nO200\nG1 Z#26 F#9\nG1 Z0\nM99\n";
    let p = prog(src);
    let c = reverse_compensate(src, &ReverseConfig::default()).unwrap();
    assert!(
        c.after.max_error_um <= c.before.max_error_um,
        "{} -> {}",
        c.before.max_error_um,
        c.after.max_error_um
    );
    let q = prog(&c.nc);
    // Every macro move keeps its end point.
    for (a, b) in p.segments.iter().zip(&q.segments).filter(|(a, _)| a.fixed) {
        assert!(
            mtmotion::nc::program::dist(a.end.p(), b.end.p()) < 1e-9,
            "{}",
            c.nc
        );
    }
    assert!(
        c.nc.contains("G66 P200 Z-1 F600") && c.nc.contains("O200"),
        "{}",
        c.nc
    );
}
