//! Fanuc Custom Macro B: each construct's expansion compared with a path
//! computed by hand (bolt circle by WHILE with SIN/COS, G65 argument
//! mapping, vacant rules, IF GOTO / IF THEN, #3000 alarm at its line, the
//! loop budget), and segments from computed words, loops and macro calls
//! marked `fixed`.

use mtmotion::nc::program::{parse, parse_all, ParseOptions, Program};

/// Tolerance for positions computed through SIN/COS in degrees, mm.
const TOL: f64 = 1e-9;

fn ok(src: &str) -> Program {
    parse(src).unwrap_or_else(|e| panic!("{e}\n{src}"))
}

fn ends(p: &Program) -> Vec<(f64, f64)> {
    p.segments.iter().map(|s| (s.end.x, s.end.y)).collect()
}

#[test]
fn while_loop_drills_a_bolt_circle() {
    let src = "G21 G90 G17\n#1=0\n#2=6\n#3=50\nWHILE [#1 LT #2] DO1\n#4=#1*360/#2\nG0 X[#3*COS[#4]] Y[#3*SIN[#4]]\n#1=#1+1\nEND1\nM30";
    let p = ok(src);
    let got = ends(&p);
    assert_eq!(got.len(), 6);
    for (k, (x, y)) in got.iter().enumerate() {
        let a = (k as f64 * 60.0).to_radians();
        assert!(
            (x - 50.0 * a.cos()).abs() < TOL && (y - 50.0 * a.sin()).abs() < TOL,
            "hole {k}: {x} {y}"
        );
    }
    assert!(p.segments.iter().all(|s| s.fixed && s.line == 7));
}

#[test]
fn g65_arguments_map_to_locals() {
    // A→#1 B→#2 C→#3 I→#4 J→#5 K→#6 D→#7 X→#24 Y→#25 Z→#26; K is an
    // argument, not a repeat count.
    let src = "G90 G21 F100\nG65 P9010 A1 B2 C3 I4 J5 K6 D7 X24 Y25 Z26\nM30\nO9010\nG1 X[#1+#2+#3] Y[#4+#5+#6+#7] Z[#24+#25+#26]\nM99";
    let p = ok(src);
    let s = &p.segments[0];
    assert_eq!((s.end.x, s.end.y, s.end.z), (6.0, 22.0, 75.0));
    assert!(s.fixed);
    // L repeats the macro; locals are dropped at M99.
    let src = "G91 G21 F100\nG65 P9011 L3 A2\nG1 X#1\nM30\nO9011\nG1 X#1\nM99";
    let p = ok(src);
    let xs: Vec<f64> = p.segments.iter().map(|s| s.end.x).collect();
    assert_eq!(
        xs,
        vec![2.0, 4.0, 6.0],
        "X#1 after the call is vacant: no move"
    );
}

#[test]
fn vacant_rules_follow_fanuc() {
    // #10 vacant: [#10 EQ 0] is false, [#10 EQ #0] true, #10+5 is 5, and
    // X#10 drops the word.
    let src = "G90 G21 F100 G1\n#2=1\nIF [#10 EQ 0] THEN #2=2\nX#2\nIF [#10 EQ #0] THEN #2=3\nX#2\n#3=#10+5\nX#3\nX#10 Y7\n#4=#10\nIF [#4 EQ #0] THEN #5=9\nX#5";
    let p = ok(src);
    let got = ends(&p);
    assert_eq!(
        got,
        vec![(1.0, 0.0), (3.0, 0.0), (5.0, 0.0), (5.0, 7.0), (9.0, 7.0)]
    );
}

#[test]
fn if_goto_loop_and_computed_g_codes() {
    // A GOTO loop stepping X by 2 until X reaches 6; G#1 picks G1.
    let src = "G90 G21 F100\n#1=1\n#5=0\nN10 #5=#5+2\nG#1 X#5\nIF [#5 LT 6] GOTO 10\nGOTO 30\nG0 X99\nN30 M30";
    let p = ok(src);
    let xs: Vec<f64> = p.segments.iter().map(|s| s.end.x).collect();
    assert_eq!(xs, vec![2.0, 4.0, 6.0]);
    assert!(p
        .segments
        .iter()
        .all(|s| matches!(s.motion, mtmotion::nc::program::Motion::Linear)));
    assert!(p.segments.iter().all(|s| s.fixed));
}

#[test]
fn functions_round_fix_fup_atan_and_nested_loops() {
    let src = "G90 G21 F100 G1\nX[ROUND[1.5]] Y[FIX[2.7]]\nX[FUP[1.2]] Y[ATAN[1]/[1]]\nX[SQRT[16]+ABS[-1]] Y[7 MOD 4]\n#1=0\nWHILE [#1 LT 2] DO1\n#2=0\nWHILE [#2 LT 2] DO2\nG1 X[#1*10] Y[#2*10]\n#2=#2+1\nEND2\n#1=#1+1\nEND1";
    let p = ok(src);
    let got = ends(&p);
    assert_eq!(&got[..3], &[(2.0, 2.0), (2.0, 45.0), (5.0, 3.0)]);
    assert_eq!(
        &got[3..],
        &[(0.0, 0.0), (0.0, 10.0), (10.0, 0.0), (10.0, 10.0)]
    );
    // Literal blocks outside loops stay editable.
    let p = ok("G90 G21 F100\n#1=5\nG1 X1\nG1 X#1");
    assert!(!p.segments[0].fixed && p.segments[1].fixed);
}

#[test]
fn alarm_stops_with_its_message_at_its_line() {
    let src = "G90 G21 F100\nG1 X1\n#1=5\nIF [#1 GT 3] THEN #3000=1 (TOOL LIFE EXPIRED)\nG1 X2";
    let e = parse_all(src, &ParseOptions::default()).unwrap_err();
    assert_eq!(e.errors.len(), 1, "{e}");
    let e = &e.errors[0];
    assert_eq!(e.line, 4);
    assert!(
        e.message.contains("TOOL LIFE EXPIRED") && e.message.contains("#3000=1"),
        "{e}"
    );
    // #3006 is a warning; the program goes on.
    let p = ok("G90 G21 F100\n#3006=1 (TURN PART)\nG1 X2");
    assert!(p
        .warnings
        .iter()
        .any(|w| w.line == 2 && w.message.contains("TURN PART")));
    assert_eq!(p.segments.len(), 1);
}

#[test]
fn endless_loop_hits_the_budget_at_the_loop_line() {
    let src = "G90 G21\n#1=0\nN5 WHILE [#1 GE 0] DO1\n#1=#1+1\nEND1\nM30";
    let e = parse_all(src, &ParseOptions::default()).unwrap_err();
    assert_eq!(e.errors.len(), 1, "{e}");
    assert_eq!(e.errors[0].line, 3, "{e}");
    assert!(
        e.errors[0].message.contains(&format!(
            "more than {} iterations",
            mtmotion::budget::MAX_LOOP_ITERATIONS
        )),
        "{e}"
    );
}

#[test]
fn a_lower_block_budget_stops_loops_and_repeats_sooner_and_never_raises_the_budget() {
    let lower = |n: usize| ParseOptions {
        max_executed_blocks: n,
        ..Default::default()
    };
    // A loop of 300 iterations (3 blocks each) runs under a 2,000-block
    // budget (500 iterations) and stops at its line under a 1,000-block
    // one (250 iterations, 750 blocks).
    let src = "G90 G21 F100\n#1=0\nN5 WHILE [#1 LT 300] DO1\n#1=#1+1\nEND1\nG1 X#1\nM30";
    let p = parse_all(src, &lower(2_000)).unwrap();
    assert_eq!(p.segments.len(), 1);
    assert_eq!(p.segments[0].end.x, 300.0);
    let e = parse_all(src, &lower(1_000)).unwrap_err();
    assert_eq!(e.errors.len(), 1, "{e}");
    assert_eq!(e.errors[0].line, 3, "{e}");
    assert!(
        e.errors[0].message.contains("more than 250 iterations"),
        "{e}"
    );
    // A subprogram repeated 600 times (3 blocks a call) meets the block
    // budget of 1,000.
    let src = "O100\nG90 G21 G1 F100\nM98 P200 L600\nM30\nO200\nG91 X1\nM99\n";
    assert_eq!(parse_all(src, &lower(2_000)).unwrap().segments.len(), 600);
    let e = parse_all(src, &lower(1_000)).unwrap_err();
    assert!(
        e.errors[0]
            .message
            .contains("more than 1000 blocks executed"),
        "{e}"
    );
    // A budget above the product's is read as the product's.
    let o = lower(usize::MAX);
    assert_eq!(
        o.executed_block_budget(),
        mtmotion::budget::MAX_EXECUTED_BLOCKS
    );
    assert_eq!(
        o.loop_iteration_budget(),
        mtmotion::budget::MAX_LOOP_ITERATIONS
    );
    assert_eq!(
        ParseOptions::default().max_executed_blocks,
        mtmotion::budget::MAX_EXECUTED_BLOCKS
    );
}

#[test]
fn unknown_system_variables_read_vacant_with_a_warning() {
    // Haas-style tool-life check: #5401 (tool life) is unknown, so vacant.
    let src = "G90 G21 F100\nIF [#5401 GT 100] THEN #3000=1 (WORN)\n#1=#5001\nG1 X[#1+1]";
    let p = ok(src);
    let w: Vec<_> = p
        .warnings
        .iter()
        .filter(|w| w.message.contains("#5401"))
        .collect();
    assert_eq!(w.len(), 1);
    assert_eq!(w[0].line, 2);
    assert_eq!(p.segments[0].end.x, 1.0);
    // Position and modal system variables are known.
    let p = ok("G20 G91 G0 X1\n#1=#5001\n#2=#4003\n#3=#4006\nG90 G21 G1 X[#1] Y[#2] Z[#3] F10");
    let s = &p.segments[1];
    assert_eq!((s.end.x, s.end.y, s.end.z), (1.0, 91.0, 20.0));
}

#[test]
fn structure_and_expression_errors_are_located() {
    let e = parse_all("WHILE [1 EQ 1] DO1\nG0 X1\nEND2", &ParseOptions::default()).unwrap_err();
    let at: Vec<(usize, usize)> = e.errors.iter().map(|e| (e.line, e.column)).collect();
    assert_eq!(at, vec![(1, 1), (3, 1)], "{e}");
    let e = parse("G0 X[1/#1]").unwrap_err();
    assert_eq!((e.line, e.column), (1, 4));
    assert!(e.message.contains("division by zero"), "{e}");
    let e = parse("GOTO 40\nN30 G0 X1").unwrap_err();
    assert!(e.message.contains("no block N40"), "{e}");
    let e = parse("G65 P1234 A1").unwrap_err();
    assert!(e.message.contains("O1234 is not in this program"), "{e}");
    let e = parse("#50=1").unwrap_err();
    assert!(e.message.contains("does not exist"), "{e}");
}

#[test]
fn okuma_programs_are_recognised_at_their_first_mark() {
    let cases = [
        ("O1000\nG90 G0 X0\nVC1=10\nG1 X1", (3, 1)),
        ("G90\nIF [#1 EQ 0] N100\nG0 X1", (2, 14)),
        ("G90\nGOTO N100", (2, 1)),
        ("G90\nCALL O2000 PX=1", (2, 1)),
        ("G0 X0\nG15 H1\nG0 X1", (2, 1)),
        // The OSP file header comes before any other mark (the line-4
        // `CALL` of GCodeWorkShop's OSP5020M example was the first one
        // seen before the header was recognised).
        (
            "$BRACKET.SSB%\r\n(HAND-WRITTEN)\r\nOMAIN\r\nCALL OSUB1",
            (1, 1),
        ),
    ];
    for (src, at) in cases {
        let e = parse_all(src, &ParseOptions::default()).unwrap_err();
        assert_eq!(e.errors.len(), 1, "{src}: {e}");
        let e = &e.errors[0];
        assert_eq!((e.line, e.column), at, "{src}: {e}");
        assert!(
            e.message.contains("this looks like an Okuma OSP program"),
            "{e}"
        );
    }
}

// proptest is a native-only dev-dependency.
#[cfg(not(target_arch = "wasm32"))]
mod never_panics {
    use mtmotion::nc::program::{parse_all, ParseOptions};
    use proptest::prelude::*;

    /// Pieces of macro code, shuffled into random lines: whatever comes
    /// out, parsing returns a program or located errors, never a panic
    /// or a non-finite coordinate.
    const PIECES: [&str; 32] = [
        "#1",
        "#2",
        "#[#1]",
        "#0",
        "#3000",
        "#<a>",
        "=",
        "[",
        "]",
        "+",
        "-",
        "*",
        "/",
        "**",
        " EQ ",
        " LT ",
        " AND ",
        "SIN",
        "ATAN",
        "SQRT",
        "IF",
        "GOTO",
        "WHILE",
        "DO1",
        "END1",
        "G1",
        "X",
        "N10",
        "o1",
        " while ",
        " endwhile",
        "1.5",
    ];

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]
        #[test]
        fn random_macro_text(lines in prop::collection::vec(prop::collection::vec(0..PIECES.len(), 0..8), 1..8)) {
            let text: String = lines
                .iter()
                .map(|l| l.iter().map(|&i| PIECES[i]).collect::<String>())
                .collect::<Vec<_>>()
                .join("\n");
            if let Ok(p) = parse_all(&format!("G21 F100\n{text}"), &ParseOptions::default()) {
                for s in &p.segments {
                    prop_assert!(s.end.to_array().iter().all(|v| v.is_finite()), "{text}");
                }
            }
        }
    }
}
