//! Subprograms (Fanuc M98/M99): calls to an O-program in the same text,
//! repeats, nesting, the main program ending at M30, and a missing
//! subprogram refused with what to do.

use mtmotion::nc::program::{parse, MAX_NESTING};

fn xs(src: &str) -> Vec<f64> {
    parse(src)
        .unwrap_or_else(|e| panic!("{e}"))
        .segments
        .iter()
        .map(|s| s.end.x)
        .collect()
}

#[test]
fn m98_runs_the_body_after_m30_and_returns() {
    let src = "O1000\nG0 X0\nM98 P2000\nG0 X100\nM30\nO2000\nG91 G1 X5 F100\nG90\nM99\n%";
    let p = parse(src).unwrap();
    let x: Vec<f64> = p.segments.iter().map(|s| s.end.x).collect();
    // Main: X0, call (X5), X100; the body is not also run inline after M30.
    assert_eq!(x, vec![0.0, 5.0, 100.0]);
    assert!(!p.segments[0].fixed && p.segments[1].fixed && !p.segments[2].fixed);
    assert_eq!(p.segments[1].line, 7);
    assert!(p.warnings.iter().all(|w| !w.message.contains("not run")));
}

#[test]
fn repeats_by_l_and_by_the_fanuc_p_prefix() {
    let body = "M30\nO0010\nG91 G1 X1 F100\nG90\nM99";
    assert_eq!(
        xs(&format!("G0 X0\nM98 P10 L3\n{body}")),
        vec![0.0, 1.0, 2.0, 3.0]
    );
    assert_eq!(
        xs(&format!("G0 X0\nM98 P30010\n{body}")),
        vec![0.0, 1.0, 2.0, 3.0]
    );
    assert_eq!(xs(&format!("G0 X0\nM98 P10 L0\n{body}")), vec![0.0]);
}

#[test]
fn four_levels_of_nesting() {
    let src = "G0 X0\nM98 P1\nM30\nO1\nG91 G1 X1 F100\nM98 P2\nM99\nO2\nX10\nM98 P3\nM99\nO3\nX100\nM98 P4\nM99\nO4\nX1000\nM99";
    assert_eq!(xs(src), vec![0.0, 1.0, 11.0, 111.0, 1111.0]);
}

#[test]
fn missing_subprogram_says_what_to_do() {
    let e = parse("G0 X0\nM98 P2000\nM30").unwrap_err();
    assert_eq!((e.line, e.column), (2, 5));
    assert!(e.message.contains("O2000 is not in this program"), "{e}");
    assert!(e.message.contains("paste the subprogram"), "{e}");
}

#[test]
fn runaway_recursion_is_stopped_with_a_located_error() {
    let e = parse("M98 P1\nM30\nO1\nM98 P1\nM99").unwrap_err();
    assert_eq!(e.line, 4);
    assert!(
        e.message.contains(&format!("deeper than {MAX_NESTING}")),
        "{e}"
    );
    let e = parse("M98 P1\nM30\nO1\nG0 X1\nO2\nM99").unwrap_err();
    assert_eq!(e.line, 5);
    assert!(e.message.contains("without an M99"), "{e}");
}
