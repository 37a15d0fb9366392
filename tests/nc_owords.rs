//! LinuxCNC o-word programs: sub/endsub/call with #1…#30 arguments,
//! if/elseif/else/endif, while/endwhile, do/while, repeat/endrepeat,
//! break, continue, return with a value, named parameters local and
//! global, and LinuxCNC's operators — each expansion compared with the
//! path computed by hand.

use mtmotion::nc::program::{parse, Program};

fn ok(src: &str) -> Program {
    parse(src).unwrap_or_else(|e| panic!("{e}\n{src}"))
}

fn xs(p: &Program) -> Vec<f64> {
    p.segments.iter().map(|s| s.end.x).collect()
}

#[test]
fn sub_call_with_arguments_and_locals() {
    // The sub is skipped where it is defined and runs at each call with
    // #1, #2 as its arguments; the caller's #1 is untouched.
    let src = "G21 G90 F100\n#1=7\no100 sub\nG1 X[#1+#2] Y#1\no100 endsub\no100 call [1] [2]\no100 call [10] [-4]\nG1 X#1 Y0";
    let p = ok(src);
    let got: Vec<(f64, f64)> = p.segments.iter().map(|s| (s.end.x, s.end.y)).collect();
    assert_eq!(got, vec![(3.0, 1.0), (6.0, 10.0), (7.0, 0.0)]);
    assert!(p.segments[0].fixed && p.segments[1].fixed);
    // A named sub, a return value in #<_value>.
    let src = "G21 G90 F100\no<half> sub\no<half> return [#1/2]\no<half> endsub\no<half> call [9]\nG1 X#<_value>";
    assert_eq!(xs(&ok(src)), vec![4.5]);
}

#[test]
fn if_elseif_else_picks_one_branch() {
    let prog = |v: f64| {
        format!("G21 G90 F100\n#1={v}\no1 if [#1 LT 0]\nG1 X-1\no1 elseif [#1 EQ 0]\nG1 X0.5\no1 elseif [#1 LT 10]\nG1 X5\no1 else\nG1 X99\no1 endif\nG1 Y1")
    };
    let first = |v: f64| ok(&prog(v)).segments[0].end.x;
    assert_eq!(first(-3.0), -1.0);
    assert_eq!(first(0.0), 0.5);
    assert_eq!(first(4.0), 5.0);
    assert_eq!(first(40.0), 99.0);
    assert_eq!(ok(&prog(4.0)).segments.len(), 2);
}

#[test]
fn loops_while_do_repeat_break_continue() {
    // while: X 1..3.
    let p = ok("G21 G91 F100\n#1=0\no2 while [#1 LT 3]\nG1 X1\n#1=[#1+1]\no2 endwhile");
    assert_eq!(xs(&p), vec![1.0, 2.0, 3.0]);
    // do … while runs the body once even when the condition is false.
    let p = ok("G21 G91 F100\no3 do\nG1 X2\no3 while [0]");
    assert_eq!(xs(&p), vec![2.0]);
    // repeat [4] with a continue skipping the third pass and a break at
    // the fourth.
    let src = "G21 G91 F100\n#1=0\no4 repeat [10]\n#1=[#1+1]\no5 if [#1 EQ 3]\no4 continue\no5 endif\no6 if [#1 EQ 5]\no4 break\no6 endif\nG1 X#1\no4 endrepeat\nG1 Y1";
    let p = ok(src);
    // Passes 1, 2, 4 move (by 1, 2, 4); pass 5 breaks.
    assert_eq!(xs(&p), vec![1.0, 3.0, 7.0, 7.0]);
    assert_eq!(p.segments[3].end.y, 1.0);
}

#[test]
fn named_parameters_operators_and_functions() {
    let src = "G21 G90 F100\n#<r> = 10\n#<_g> = 2\no7 sub\nG1 X[#<_g>**3] Y[EXISTS[#<r>]]\no7 endsub\no7 call\nG1 X[#<r> MOD 4] Y[EXISTS[#<r>]] Z[FIX[-1.5]]\nG1 X[ATAN[-1]/[-1]] Y[ACOS[0]] Z[LN[EXP[2]]]";
    let p = ok(src);
    let e: Vec<[f64; 3]> = p
        .segments
        .iter()
        .map(|s| [s.end.x, s.end.y, s.end.z])
        .collect();
    // Inside the sub #<r> (a local of the main level) does not exist,
    // #<_g> (global) does.
    assert_eq!(e[0], [8.0, 0.0, 0.0]);
    assert_eq!(e[1], [2.0, 1.0, -2.0]);
    assert!(
        (e[2][0] + 135.0).abs() < 1e-12
            && (e[2][1] - 90.0).abs() < 1e-12
            && (e[2][2] - 2.0).abs() < 1e-12
    );
}

#[test]
fn errors_are_located() {
    let e = parse("G21 G90 F100\nG1 X#<undefined>").unwrap_err();
    assert_eq!((e.line, e.column), (2, 4));
    assert!(e.message.contains("read before it is set"), "{e}");
    let e = parse("o200 call [1]").unwrap_err();
    assert!(e.message.contains("o200 is not in this program"), "{e}");
    assert_eq!((e.line, e.column), (1, 6));
    let e = parse("o1 if [1]\nG0 X1\no2 endif").unwrap_err();
    assert_eq!(e.line, 1, "{e}");
    let e = parse("o1 sub\no1 call\no1 endsub\no1 call").unwrap_err();
    assert!(e.message.contains("deeper than"), "{e}");
}
