//! Deeply nested and very long macro expressions are refused or read
//! without a stack overflow: every nesting form 2,000 levels deep (`[…]`,
//! `IF[[…]]`, an o-word `[…]`, `SIN[SIN[…]]`, `#[#[…]]`, `##…#1`, a `**`
//! tower, an address word `X[[…]]`) is an error at the line and column of
//! the level one past [`MAX_EXPR_DEPTH`], naming the limit, through every
//! entry point that reads a program (parse, the collecting parse, the
//! tool-path simulation, reverse and 5-axis compensation); exactly
//! [`MAX_EXPR_DEPTH`] levels still read and evaluate, also in the shape
//! that builds the deepest tree; and a 500,000-term `1+1+…` and a
//! 100,000-sign `--…-1` are read as flat lists, with the right value, well
//! within a second in a release build.

use std::time::Instant;

use mtmotion::compensate::nc5::{compensate_nc5, Nc5Config};
use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
use mtmotion::machine::MachineRef;
use mtmotion::nc::macro_expr::MAX_EXPR_DEPTH;
use mtmotion::nc::program::{parse, parse_all, ParseOptions, Program};
use mtmotion::nc::NcError;
use mtmotion::toolpath::{simulate_text, SimConfig};

/// Levels of the hostile inputs: far past the limit, and as deep as the
/// inputs that killed the wasm instance.
const DEEP: usize = 2_000;

/// A form of nesting: the program at `depth` levels, and the line and
/// column where level `MAX_EXPR_DEPTH + 1` opens.
struct Form {
    name: &'static str,
    program: fn(usize) -> String,
    at: (usize, usize),
}

fn open_close(open: &str, depth: usize, close: &str) -> String {
    format!("{}1{}", open.repeat(depth), close.repeat(depth))
}

const M: usize = MAX_EXPR_DEPTH;

fn forms() -> Vec<Form> {
    vec![
        Form {
            name: "#1=[[…]]",
            program: |d| format!("#1={}\nG1 X#1 F100\nM30", open_close("[", d, "]")),
            // "#1=" then one '[' per level
            at: (1, 4 + M),
        },
        Form {
            name: "IF[[…]]",
            program: |d| format!("IF{}GOTO5\nN5 G1 X1 F100\nM30", open_close("[", d, "]")),
            at: (1, 3 + M),
        },
        Form {
            name: "o-word [[…]]",
            program: |d| {
                format!(
                    "G1 F100\no100 if {}\nG1 X1\no100 endif\nM30",
                    open_close("[", d, "]")
                )
            },
            at: (2, 9 + M),
        },
        Form {
            name: "SIN[SIN[…]]",
            program: |d| format!("#1={}\nG1 X#1 F100\nM30", open_close("SIN[", d, "]")),
            // the k-th '[' is at column 3 + 4k
            at: (1, 3 + 4 * (M + 1)),
        },
        Form {
            name: "#[#[…]]",
            program: |d| format!("#1=1\n#2={}\nG1 X#2 F100\nM30", open_close("#[", d, "]")),
            at: (2, 3 + 2 * (M + 1)),
        },
        Form {
            name: "##…#1",
            program: |d| format!("#1=1\n#2={}1\nG1 X#2 F100\nM30", "#".repeat(d + 1)),
            // the first '#' of the value is at column 4; each further one
            // opens a level
            at: (2, 4 + M + 1),
        },
        Form {
            name: "1**1**…",
            program: |d| format!("#1=1{}\nG1 X#1 F100\nM30", "**1".repeat(d)),
            // the k-th right operand is at column 4 + 3k
            at: (1, 4 + 3 * (M + 1)),
        },
        Form {
            name: "X[[…]]",
            program: |d| format!("G1 X{} F100\nM30", open_close("[", d, "]")),
            at: (1, 5 + M),
        },
    ]
}

fn assert_depth_error(e: &NcError, form: &Form, via: &str) {
    assert_eq!(
        (e.line, e.column),
        form.at,
        "{} via {via}: wrong place: {e}",
        form.name
    );
    assert!(
        e.message
            .contains(&format!("nested deeper than {MAX_EXPR_DEPTH} levels")),
        "{} via {via}: {e}",
        form.name
    );
}

fn nc5_config() -> Nc5Config {
    Nc5Config::new(MachineRef::Name("pocketnc-v2-10".into()))
}

#[test]
fn every_nesting_form_2000_deep_is_a_located_error_at_every_entry_point() {
    for form in forms() {
        let text = (form.program)(DEEP);
        let e = parse(&text).expect_err(form.name);
        assert_depth_error(&e, &form, "parse");
        let all = parse_all(&text, &ParseOptions::default()).expect_err(form.name);
        assert_depth_error(&all.errors[0], &form, "parse_all");
        let msg = simulate_text(&text, &SimConfig::default())
            .expect_err(form.name)
            .to_string();
        let located = format!("line {}, column {}", form.at.0, form.at.1);
        assert!(msg.contains(&located), "{} via simulate: {msg}", form.name);
        let msg = reverse_compensate(&text, &ReverseConfig::default())
            .expect_err(form.name)
            .to_string();
        assert!(msg.contains(&located), "{} via reverse: {msg}", form.name);
        let msg = compensate_nc5(&text, &nc5_config())
            .expect_err(form.name)
            .to_string();
        assert!(msg.contains(&located), "{} via nc5: {msg}", form.name);
    }
}

#[test]
fn one_level_past_the_limit_is_refused_and_the_limit_itself_runs() {
    for form in forms() {
        let e = parse(&(form.program)(M + 1)).expect_err(form.name);
        assert_depth_error(&e, &form, "parse at the limit + 1");
        let p =
            parse(&(form.program)(M)).unwrap_or_else(|e| panic!("{} at the limit: {e}", form.name));
        assert!(!p.segments.is_empty(), "{}: no move", form.name);
    }
    // the values at the limit: brackets and ## keep 1, SIN of SIN … of 1°
    // is the iterated sine
    let x = |p: Program| p.segments[0].end.x;
    assert_eq!(x(parse(&(forms()[0].program)(M)).unwrap()), 1.0);
    assert_eq!(x(parse(&(forms()[5].program)(M)).unwrap()), 1.0);
    let want = (0..M).fold(1.0_f64, |v, _| v.to_radians().sin());
    let got = x(parse(&(forms()[3].program)(M)).unwrap());
    assert!((got - want).abs() < 1e-12, "{got} vs {want}");
}

#[test]
fn the_deepest_tree_the_parser_allows_evaluates() {
    // every level adds four operator chains, a sign and a function: the
    // largest tree a level can give
    let level = "0 OR 0 EQ 0 + 0 * -ABS[";
    let at = |d: usize| {
        format!(
            "#1={}2{}\nG1 X[#1+1] F100\nM30",
            level.repeat(d),
            "]".repeat(d)
        )
    };
    // innermost: 0 + 0 * -ABS[2] = 0 → 0 EQ 0 = 1 → 0 OR 1 = 1; each
    // level out sees ABS[1] and gives 1 again
    let p = parse(&at(M)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.segments[0].end.x, 2.0);
    let e = parse(&at(M + 1)).unwrap_err();
    assert_eq!((e.line, e.column), (1, 3 + level.len() * (M + 1)), "{e}");
}

#[test]
fn a_500000_term_sum_is_one_flat_list() {
    let text = format!("#1={}1\nG1 X#1 F100\nM30", "1+".repeat(499_999));
    let t = Instant::now();
    let p = parse(&text).unwrap_or_else(|e| panic!("{e}"));
    let s = t.elapsed().as_secs_f64();
    assert_eq!(p.segments[0].end.x, 500_000.0);
    eprintln!("500,000-term sum: {s:.3} s");
    // about 0.2 s in a release build, 2 s in a debug build: linear, so far
    // from the minutes a quadratic reading would take
    assert!(s < 20.0, "{s} s");
    // left to right within a precedence, products first: 100 - 1 - … - 1
    // (99,998 of them) - 1*2 + 1
    let text = format!("#1=100{}*2+1\nG1 X#1 F100\nM30", "-1".repeat(99_999));
    assert_eq!(parse(&text).unwrap().segments[0].end.x, -99_899.0);
}

#[test]
fn a_100000_sign_run_is_read_in_a_loop() {
    for (signs, want) in [(100_000, 1.0), (99_999, -1.0)] {
        for text in [
            format!("#1={}1\nG1 X#1 F100\nM30", "-".repeat(signs)),
            format!("G1 X[{}1] F100\nM30", "-+".repeat(signs)),
        ] {
            let t = Instant::now();
            let p = parse(&text).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(p.segments[0].end.x, want, "{signs} signs");
            assert!(t.elapsed().as_secs_f64() < 20.0);
        }
    }
}
