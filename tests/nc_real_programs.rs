//! Regressions of real shop-floor programs: every silent misread of real shop-floor programs
//! now has its fixed reading or a warning/error naming the line, and a
//! program reports all of its errors. Expected values come from the codes'
//! written definitions (Fanuc/LinuxCNC manuals) and plain geometry, not
//! from the parser's output.

#[path = "support/corpus.rs"]
mod corpus;

use std::f64::consts::PI;

use mtmotion::nc::program::{parse, parse_all, parse_with, DwellP, Motion, ParseOptions, Segment};

fn ends(segs: &[Segment]) -> Vec<[f64; 3]> {
    segs.iter().map(|s| s.end.p()).collect()
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9)
}

/// Reverse compensation of `src` with the default settings, which must
/// at least halve the largest contour error (a result it found worse would
/// be the source unchanged, and the checks on the written text void).
fn compensated(src: &str) -> mtmotion::compensate::reverse::Compensation {
    use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
    let c = reverse_compensate(src, &ReverseConfig::default()).unwrap();
    assert!(
        c.after.max_error_um < 0.5 * c.before.max_error_um,
        "{} -> {} µm",
        c.before.max_error_um,
        c.after.max_error_um
    );
    c
}

/// The moves of `p` (its dwells left out: a rewrite may add some).
fn moves(p: &mtmotion::nc::program::Program) -> Vec<Segment> {
    let dwell = |s: &&Segment| matches!(s.motion, Motion::Dwell { .. });
    p.segments.iter().filter(|s| !dwell(s)).cloned().collect()
}

/// The feeds of the moves of `p`, mm/min.
fn feeds(p: &mtmotion::nc::program::Program) -> Vec<f64> {
    moves(p).iter().map(|s| s.feed).collect()
}

/// `src` written by the patcher with one move added that has no source
/// block: a copy of segment `k` ending at Y = `y`, at `feed` (or the
/// copied segment's), before segment `k`. The text and the feeds it reads
/// back with.
fn with_added_move(src: &str, k: usize, y: f64, feed: Option<f64>) -> (String, Vec<f64>) {
    let p = parse(src).unwrap();
    let mut segs = p.segments.clone();
    let mut extra = segs[k].clone();
    extra.block = None;
    extra.end.y = y;
    extra.feed = feed.unwrap_or(extra.feed);
    segs[k].start = extra.end;
    segs.insert(k, extra);
    let text = mtmotion::nc::patch::write_source(src, &p, &segs);
    let read = feeds(&parse(&text).unwrap());
    (text, read)
}

#[test]
fn fanuc_chamfer_c_is_not_a_c_axis_move() {
    // 3-axis default: C on G01 is a chamfer of 2 mm from the virtual corner.
    let p = parse("G0 X0 Y0\nG1 X10 C2 F100\nG1 Y10").unwrap();
    let e = ends(&p.segments);
    assert_eq!(p.segments.len(), 4);
    assert!(close(e[1], [8.0, 0.0, 0.0]), "{e:?}");
    assert!(close(e[2], [10.0, 2.0, 0.0]), "{e:?}");
    assert!(close(e[3], [10.0, 10.0, 0.0]), "{e:?}");
    assert!(p.segments.iter().all(|s| s.end.c == 0.0));
    assert!((p.segments[2].length() - 2.0 * 2f64.sqrt()).abs() < 1e-12);
    assert!(p.segments[1].fixed && p.segments[2].fixed && !p.segments[3].fixed);
    // ,C is the same chamfer.
    let q = parse("G0 X0 Y0\nG1 X10 ,C2 F100\nG1 Y10").unwrap();
    assert_eq!(ends(&q.segments), e);
    // A declared C axis reads C15 as 15 degrees.
    let opt = ParseOptions {
        c_axis: true,
        ..Default::default()
    };
    let p = parse_with("G0 X0 C15", &opt).unwrap();
    assert_eq!(p.segments[0].end.c, 15.0);
    // A program with A or B words is multi-axis: C is its rotary axis.
    let p = parse("G0 X0 A10\nG1 X10 C30 F100").unwrap();
    assert_eq!(p.segments[1].end.c, 30.0);
    assert_eq!(p.segments.len(), 2);
    // So is C on a rapid (a 3-axis Fanuc program writes C only on G01).
    assert_eq!(parse("G0 X0 C15").unwrap().segments[0].end.c, 15.0);
    // A chamfer with no line after it is an error at the C word.
    let e = parse("G0 X5\nG1 X0 C15 F100").unwrap_err();
    assert_eq!((e.line, e.column), (2, 7));
    assert!(e.message.contains("next move to be a G01"), "{e}");
    // C alone (no move) on a 3-axis program is an error at the C word.
    let e = parse("G0 X5\nG1 X0 F100\nC2").unwrap_err();
    assert_eq!((e.line, e.column), (3, 1));
    assert!(e.message.contains("no C axis"), "{e}");
}

#[test]
fn fanuc_corner_rounding_inserts_a_tangent_arc() {
    for src in [
        "G0 X0 Y0\nG1 X20 ,R5 F100\nG1 Y20",
        "G0 X0 Y0\nG1 X20 R5 F100\nG1 Y20",
    ] {
        let p = parse(src).unwrap();
        assert_eq!(p.segments.len(), 4, "{src}");
        // 90° turn: the tangent points lie R·tan(45°) = 5 mm from the corner.
        let e = ends(&p.segments);
        assert!(close(e[1], [15.0, 0.0, 0.0]), "{e:?}");
        assert!(close(e[2], [20.0, 5.0, 0.0]), "{e:?}");
        let Motion::Arc(a) = p.segments[2].motion else {
            panic!("not an arc")
        };
        assert!(close(a.center, [15.0, 5.0, 0.0]), "{:?}", a.center);
        assert!((a.sweep - PI / 2.0).abs() < 1e-12);
        assert!((p.segments[2].length() - 2.5 * PI).abs() < 1e-12);
        assert!(close(p.segments[3].start.p(), [20.0, 5.0, 0.0]));
    }
    // A corner larger than the line is a located error.
    let e = parse("G0 X0 Y0\nG1 X2 ,R5 F100\nG1 Y20").unwrap_err();
    assert_eq!((e.line, e.column), (2, 7));
    assert!(e.message.contains("does not fit"), "{e}");
}

#[test]
fn g10_sets_data_and_does_not_move() {
    let p = parse("G0 X1 Y1\nG10 L2 P1 X-315. Y-315. Z-689.88\nG1 X2 F100").unwrap();
    assert_eq!(p.segments.len(), 2);
    assert!(close(p.segments[1].start.p(), [1.0, 1.0, 0.0]));
    assert!(p
        .warnings
        .iter()
        .any(|w| w.line == 2 && w.message.contains("does not move")));
}

#[test]
fn g90_1_absolute_arc_centres() {
    // Quarter circle about the origin: 90°, not the 270° an incremental
    // reading of I/J would need.
    let p = parse("G0 X10 Y0\nG90.1 G3 X0 Y10 I0 J0 F100").unwrap();
    let Motion::Arc(a) = p.segments[1].motion else {
        panic!()
    };
    assert!(close(a.center, [0.0, 0.0, 0.0]), "{:?}", a.center);
    assert!((a.sweep - PI / 2.0).abs() < 1e-12, "{}", a.sweep);
    let q = parse("G0 X10 Y0\nG91.1 G3 X0 Y10 I-10 J0 F100").unwrap();
    assert_eq!(q.segments[1].motion, p.segments[1].motion);
}

#[test]
fn threading_and_tapping_are_refused_at_their_word() {
    // G33 and G33.1 are simulated (tests/nc_field_programs.rs), and
    // Fanuc's rigid tapping G84.2/G84.3 (tests/nc_cycles.rs); G33.2 is
    // no code of LinuxCNC or Fanuc, and G84.1 no cycle known here.
    for (src, col, phrase) in [
        ("G0 X1\nS500 G33.2 Z-5 K1", 6, "neither LinuxCNC"),
        (
            "G0 X1\nG98 G84.1 Z-5 R1 F100",
            5,
            "this canned cycle is not simulated",
        ),
    ] {
        let e = parse(src).unwrap_err();
        assert_eq!((e.line, e.column), (2, col), "{e}");
        assert!(e.message.contains(phrase), "{e}");
    }
}

#[test]
fn dwell_in_every_common_form() {
    let secs = |src: &str, d: DwellP| -> (f64, usize) {
        let p = parse_with(
            src,
            &ParseOptions {
                dwell_p: d,
                ..Default::default()
            },
        )
        .unwrap();
        match p.segments[0].motion {
            Motion::Dwell { seconds } => (seconds, p.warnings.len()),
            m => panic!("{m:?}"),
        }
    };
    // LinuxCNC / Grbl: P in seconds.
    assert_eq!(secs("G4 P3", DwellP::Seconds), (3.0, 0));
    // Fanuc: P without a decimal point in ms, X and U in seconds.
    assert_eq!(secs("G04 P3", DwellP::Milliseconds), (0.003, 0));
    assert_eq!(secs("G04 X1.5", DwellP::Auto), (1.5, 0));
    assert_eq!(secs("G04 U2.", DwellP::Auto), (2.0, 0));
    assert_eq!(secs("G4 P0.5", DwellP::Auto), (0.5, 0));
    // Auto reads P3 as 3 ms but says that LinuxCNC/Grbl would mean 3 s.
    assert_eq!(secs("G4 P3", DwellP::Auto), (0.003, 1));
    let p = parse("G4 P3").unwrap();
    assert!(p.warnings[0].message.contains("3 s"), "{}", p.warnings[0]);
}

#[test]
fn implausible_feed_is_warned() {
    let p = parse("G20\nG1 X1 F100100").unwrap();
    let w = &p.warnings[0];
    assert_eq!((w.line, w.column), (2, 7));
    assert!(w.message.contains("implausible"), "{w}");
    let p = parse("G20\nG1 X1 F100").unwrap();
    assert!(p.warnings.is_empty());
}

#[test]
fn unknown_option_keys_are_rejected_by_name() {
    let e = serde_json::from_str::<ParseOptions>(r#"{"dwelP": "seconds"}"#).unwrap_err();
    assert!(e.to_string().contains("dwelP"), "{e}");
    let o: ParseOptions = serde_json::from_str(r#"{"dwellP": "seconds", "cAxis": true}"#).unwrap();
    // KEYS lists exactly the serialised keys.
    let v = serde_json::to_value(ParseOptions::default()).unwrap();
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    keys.sort_unstable();
    let mut want = ParseOptions::KEYS.to_vec();
    want.sort_unstable();
    assert_eq!(keys, want);
    assert_eq!(o.dwell_p, DwellP::Seconds);
    assert!(o.c_axis && o.skip_block_delete);
}

#[test]
fn machine_coordinate_moves_and_offsets() {
    // G53: not simulated, warned; the tool stays where it was.
    let p = parse("G0 X5 Y5 Z5\nG53 G0 Z0\nG1 X6 F100").unwrap();
    assert_eq!(p.segments.len(), 2);
    assert!(close(p.segments[1].start.p(), [5.0, 5.0, 5.0]));
    assert!(p
        .warnings
        .iter()
        .any(|w| w.line == 2 && w.message.contains("machine coordinates")));
    // G28: the rapid to the intermediate point is simulated and fixed.
    let p = parse("G0 X1 Y1\nG28 X10 Y10\nG1 X11 F100").unwrap();
    assert_eq!(p.segments.len(), 3);
    assert!(p.segments[1].fixed);
    assert!(close(p.segments[1].end.p(), [10.0, 10.0, 0.0]));
    assert!(p
        .warnings
        .iter()
        .any(|w| w.line == 2 && w.message.contains("reference point")));
    // G92 X0 Y0 at (10, 10): X5 is 5 mm further, the path stays continuous.
    let p = parse("G0 X10 Y10\nG92 X0 Y0\nG1 X5 F100\nG92.1\nG1 X0").unwrap();
    assert!(close(p.segments[1].end.p(), [15.0, 10.0, 0.0]));
    assert!(close(p.segments[2].end.p(), [0.0, 10.0, 0.0]));
    // Work offsets: warned, program frame kept.
    let p = parse("G55 G0 X1\nG54.1 P3 G0 X2").unwrap();
    assert_eq!(
        p.warnings
            .iter()
            .filter(|w| w.message.starts_with("work offset"))
            .count(),
        2
    );
    assert_eq!(p.segments[1].end.x, 2.0);
}

#[test]
fn program_end_and_subprogram_calls() {
    // M30 ends the main program: the O2000 body after it is not run inline
    // (it is a subprogram, so no warning), but other text after M30 is
    // warned about.
    let p = parse("G0 X1\nM30\nO2000\nG1 X50 F100\nM99").unwrap();
    assert_eq!(p.segments.len(), 1);
    assert!(p.warnings.iter().all(|w| !w.message.contains("not run")));
    let p = parse("G0 X1\nM30\nG1 X50 F100").unwrap();
    assert_eq!(p.segments.len(), 1);
    assert!(p
        .warnings
        .iter()
        .any(|w| w.line == 3 && w.message.contains("not run")));
    // M98 to a subprogram that is not in the text: refused at its P word.
    let e = parse("G0 X1\nM98 P2000\nM30").unwrap_err();
    assert_eq!((e.line, e.column), (2, 5));
    assert!(e.message.contains("O2000 is not in this program"), "{e}");
}

#[test]
fn block_delete_is_an_option() {
    let src = "G0 X0\n/G1 X5 F100\nG1 X1 F100";
    let p = parse(src).unwrap();
    assert_eq!(p.segments.len(), 2);
    assert!(p
        .warnings
        .iter()
        .any(|w| w.line == 2 && w.message.contains("block delete")));
    let opt = ParseOptions {
        skip_block_delete: false,
        ..Default::default()
    };
    assert_eq!(parse_with(src, &opt).unwrap().segments.len(), 3);
}

#[test]
fn three_d_printer_program_is_recognised() {
    let e = parse("G21\nG92 E0\nG1 X10 Y10 E1.2 F1800").unwrap_err();
    assert_eq!((e.line, e.column), (2, 5));
    assert!(
        e.message.contains("this looks like a 3D-printer program"),
        "{e}"
    );
}

#[test]
fn every_error_is_reported_in_order() {
    let src = "G21\nG1 X1\nG0 X1 (DRILL 5 HOLES\nIF [#1 GT] GOTO 5\nG1 X2 F100\nG2 X3\nG0 X\u{1a}2";
    let e = parse_all(src, &ParseOptions::default()).unwrap_err();
    let at: Vec<(usize, usize)> = e.errors.iter().map(|e| (e.line, e.column)).collect();
    assert_eq!(at, vec![(2, 4), (3, 7), (4, 10), (6, 4), (7, 5)]);
    let text = e.to_string();
    assert!(text.starts_with("5 errors in the program:"), "{text}");
    assert!(
        text.contains("line 7, column 5: control character U+001A"),
        "{text}"
    );
}

#[test]
fn summary_groups_warnings_by_kind_with_their_lines() {
    use mtmotion::nc::summary::summarize;
    let p = parse("G55 G0 X1\nM8\nG56 G0 X2\nM8 S100").unwrap();
    let s = summarize(&p, 10_000.0);
    let g: Vec<(&str, usize, Vec<usize>)> = s
        .warnings
        .iter()
        .map(|g| (g.kind.as_str(), g.count, g.lines.clone()))
        .collect();
    assert_eq!(
        g,
        vec![
            ("work offset", 2, vec![1, 3]),
            ("M8", 2, vec![2, 4]),
            ("S", 1, vec![4])
        ]
    );
    // Every warning is in exactly one group.
    let mut idx: Vec<usize> = s.warnings.iter().flat_map(|g| g.indices.clone()).collect();
    idx.sort_unstable();
    assert_eq!(idx, (0..p.warnings.len()).collect::<Vec<_>>());
    // 2 mm of rapids at 10 m/min.
    assert!((s.motion_time - 2.0 / 10_000.0 * 60.0).abs() < 1e-15);
    assert_eq!(s.units, "mm");
}

#[test]
fn a_bare_program_name_is_a_header_not_an_address_error() {
    // Laser Macro B programs (the shared corpus's cncsprayer_*.NC) open with
    // `OCIRCLE(Circle)` and `O7997A(NestedShtCutoff)`: a program name, as
    // Mitsubishi and Fanuc 30i-series controls allow.
    for (head, name) in [
        ("OCIRCLE(Circle)", "CIRCLE"),
        ("O7997A(NestedShtCutoff)", "7997A"),
        ("Oface_mill", "face_mill"),
    ] {
        let src = format!("%\n{head}\nG0 X1 Y2\nG1 X3 F100\nM30\n%\n");
        let p = parse(&src).unwrap_or_else(|e| panic!("{head}: {e}"));
        assert_eq!(p.blocks[1].program_name.as_deref(), Some(name), "{head}");
        assert!(p.blocks[1].program_name_bare, "{head}");
        assert_eq!(p.blocks[1].write(), head.replacen('(', " (", 1), "{head}");
        assert_eq!(ends(&p.segments), vec![[1.0, 2.0, 0.0], [3.0, 2.0, 0.0]]);
    }
    // Not a name: a LinuxCNC o-word keyword, or words after the O number.
    let e = parse("o100sub\nG0 X1").unwrap_err();
    assert!(e.message.contains("o100 sub is never closed"), "{e}");
    let p = parse("O1000 M30").unwrap();
    assert!(p.blocks[0].program_name.is_none());
    assert_eq!(p.blocks[0].word('O').unwrap().value, 1000.0);
}

#[test]
fn a_stray_paren_inside_a_comment_ends_at_the_first_close_paren() {
    // cncsprayer_CIRCLE.NC line 28 comments out a block with its own
    // comment: `(G0G40X0Y#140+.25(move up)`. Fanuc comments do not nest,
    // so the comment ends at the `)`.
    let p = parse("G0 X1 (G0G40X0Y5+.25(move up)\nG1 X2 F100").unwrap();
    assert_eq!(p.blocks[0].comments, vec!["G0G40X0Y5+.25(move up"]);
    assert_eq!(ends(&p.segments), vec![[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
    // The same in a macro line.
    let p = parse_all("#1=2 (G0X#1+.25(up)\nG0 X#1", &ParseOptions::default()).unwrap();
    assert_eq!(ends(&p.segments), vec![[2.0, 0.0, 0.0]]);
    // Balanced nesting stays one comment; no `)` at all is still an error.
    let p = parse("G0 X1 (DRILL (5 HOLES)) Y2").unwrap();
    assert_eq!(p.blocks[0].comments, vec!["DRILL (5 HOLES)"]);
    assert_eq!(ends(&p.segments), vec![[1.0, 2.0, 0.0]]);
    let e = parse("G0 X1 (open").unwrap_err();
    assert_eq!((e.line, e.column), (1, 7));
}

#[test]
fn unbracketed_macro_arithmetic_and_macro_corner_words_are_named() {
    // `X#140/2` (Mitsubishi-style) and `X0,R#144` in the laser programs.
    let e = parse_all("#1=4\nG0 X#1/2 Y0", &ParseOptions::default()).unwrap_err();
    let first = &e.errors[0];
    assert_eq!((first.line, first.column), (2, 7));
    assert!(
        first
            .message
            .contains("put the arithmetic in brackets (X[#1/2])"),
        "{first}"
    );
    let e = parse_all("#1=4\nG1 X0,R#1 F100\nY5", &ParseOptions::default()).unwrap_err();
    let first = &e.errors[0];
    assert_eq!((first.line, first.column), (2, 6));
    assert!(
        first.message.contains("corner word ',R' in a macro line"),
        "{first}"
    );
    // `IF[#1EQ#2]AND[#3EQ#4]GOTO10` (cncsprayer_7997A.NC line 25).
    let src = "#1=1\n#2=1\nIF[#1EQ#2]AND[#2EQ1]GOTO10\nG0 X1\nN10 G0 X2";
    let e = parse_all(src, &ParseOptions::default()).unwrap_err();
    let first = &e.errors[0];
    assert_eq!((first.line, first.column), (3, 11));
    assert!(
        first.message.contains("write IF[[…] AND […]] GOTO n"),
        "{first}"
    );
}

/// LinuxCNC's `G64 P.1` (and `G64 P0.02 Q0.01`): P and Q are the
/// path-blending tolerances of G64, one warning naming them (not
/// "unknown word"), and the path is the programmed one; a plain G64 or
/// G61 is silent, and a P on a block without G64 is still unknown.
#[test]
fn g64_blending_tolerance_is_named_not_unknown() {
    let p = parse("G21 G90\nG64 P.1\nG64 P0.02 Q0.01\nG64\nG61\nG1 X10 F600\nG0 X0 P3").unwrap();
    let msgs: Vec<(usize, String)> = p
        .warnings
        .iter()
        .map(|w| (w.line, w.message.clone()))
        .collect();
    assert_eq!(msgs.len(), 3, "{msgs:?}");
    assert_eq!(msgs[0].0, 2);
    assert!(
        msgs[0]
            .1
            .starts_with("G64 P.1 (path-blending tolerance) is not modelled"),
        "{msgs:?}"
    );
    assert_eq!(msgs[1].0, 3);
    assert!(
        msgs[1]
            .1
            .starts_with("G64 P0.02 Q0.01 (path-blending tolerance)"),
        "{msgs:?}"
    );
    assert_eq!(msgs[2], (7, "unknown word P3 was ignored".to_string()));
    assert_eq!(ends(&p.segments), vec![[10.0, 0.0, 0.0], [0.0, 0.0, 0.0]]);
}

/// An axis or polar word twice on one block is a located error at the
/// second, naming the first (it had been read silently: the last X, but
/// the first `@`).
#[test]
fn a_repeated_axis_word_is_refused() {
    for (src, col, phrase) in [
        ("G1 X1 X2 F100", 7, "X2 repeats X1 on one block"),
        ("G1 @1 ^30 @2 F100", 11, "@2 repeats @1 on one block"),
        (
            "G0 X0\nG1 Z-1 Y2 Z-2 F100",
            11,
            "Z-2 repeats Z-1 on one block",
        ),
    ] {
        let e = parse(src).unwrap_err();
        assert_eq!(e.column, col, "{src}: {e}");
        assert!(e.message.contains(phrase), "{src}: {e}");
    }
    assert!(parse("G1 X1 Y2 Z3 A4 B5 F100").is_ok());
}

#[test]
fn codes_that_move_or_transform_the_path_are_refused_at_their_word() {
    // Ignoring these (as an unknown code is, with a warning) would simulate
    // another path: a Haas pocket or engraving cut nowhere, a mirrored or
    // scaled part at its programmed size, a probe move run to its end.
    for (code, what) in [
        ("G12 I5 D1 K2 Q1 Z-1 F100", "circular pocket"),
        ("G13 I5 D1 K2 Q1 Z-1 F100", "circular pocket"),
        ("G47 P0 E20. I0 J4 R1. Z-0.3 F40 (ABC)", "text engraving"),
        ("G70 I1 J0 L6 F100", "bolt-hole"),
        ("G71 I1 J0 K30 L3 F100", "bolt-hole"),
        ("G72 I1 J45 L4 F100", "bolt-hole"),
        (
            "G150 P1000 D0.25 K0.01 G41 J0.3 R0.1 Q0.2 Z-1 F10",
            "pocket milling",
        ),
        ("G51 X0 Y0 P2", "scaling"),
        ("G51.1 X0", "mirror"),
        ("G101 X0", "mirror"),
        ("G31 X20 F50", "probing"),
        ("G38.2 Z-10 F50", "probing"),
        ("G37 H1 Z0", "tool measurement"),
        ("G141 D1 G1 X10 F100", "3D cutter"),
        ("G107 A0 Y0 R2", "cylindrical"),
        ("G7.1 C57", "cylindrical"),
        ("G12.1", "polar coordinate interpolation"),
        ("G16", "FANUC G16"),
        ("G6.2 P3 K0 X0 Y0 R1 F100", "NURBS"),
    ] {
        let src = format!("G0 X0 Y0\nT1 {code}");
        let e = parse(&src).unwrap_err();
        assert_eq!((e.line, e.column), (2, 4), "{code}: {e}");
        assert!(
            e.message.contains(what) && e.message.contains("is not simulated"),
            "{code}: {e}"
        );
    }
    // G47's E is its plunge feed: the program is not taken for a 3D printer's.
    let e = parse("G0 X0\nG47 P0 E20. I0 J4 R1. Z-0.3 F40 (ABC)").unwrap_err();
    assert!(!e.message.contains("3D-printer"), "{e}");
    // Their cancels pass in silence: the modes they cancel are refused.
    let p = parse("G50 G50.1 G100 G13.1 G15\nG0 X1").unwrap();
    assert!(p.warnings.iter().all(|w| w.line != 1), "{:?}", p.warnings);
    assert_eq!(p.segments[0].end.x, 1.0);
    // Haas G110–G129 and G154 P1–P99 are work offsets, warned as such.
    let p = parse("G110 G0 X1\nG154 P5 G0 X2").unwrap();
    let offsets = p
        .warnings
        .iter()
        .filter(|w| w.message.starts_with("work offset"));
    assert_eq!(offsets.count(), 2, "{:?}", p.warnings);
}

#[test]
fn g52_local_coordinate_system_shifts_later_absolute_words() {
    // FANUC/Haas G52: a program point X is the work point X + the G52 value;
    // values are absolute (not incremental) and in the program's units, axes
    // it does not name keep their shift, G52 X0 Y0 cancels.
    let p = parse(
        "G90 G0 X0 Y0 Z5\nG52 X100 Y50\nG1 X10 Y0 F1000\nG52 Z-24\nG1 Z1\nG91 G1 X1\nG90 G52 X0 Y0 Z0\nG1 X10 Y0 Z0",
    )
    .unwrap();
    let e = ends(&p.segments);
    assert!(close(e[1], [110.0, 50.0, 5.0]), "{e:?}");
    assert!(close(e[2], [110.0, 50.0, -23.0]), "{e:?}");
    assert!(
        close(e[3], [111.0, 50.0, -23.0]),
        "G91 increments are not shifted: {e:?}"
    );
    assert!(close(e[4], [10.0, 0.0, 0.0]), "{e:?}");
    assert!(p
        .warnings
        .iter()
        .any(|w| w.line == 2 && w.message.contains("(100.0000, 50.0000, 0.0000)")));
    assert!(p
        .warnings
        .iter()
        .any(|w| w.line == 7 && w.message.contains("cancelled")));
    // Inch: G52 X1 is 25.4 mm.
    let p = parse("G20 G0 X0 Y0\nG52 X1\nG1 X1 F10").unwrap();
    assert!(
        close(p.segments[1].end.p(), [50.8, 0.0, 0.0]),
        "{:?}",
        p.segments[1].end.p()
    );
    // G92.1 cancels the G92 shift and keeps the G52 one.
    let p = parse("G0 X10 Y0\nG52 X100\nG92 X0\nG1 X5 F100\nG92.1\nG1 X5").unwrap();
    let e = ends(&p.segments);
    assert!(
        close(e[1], [15.0, 0.0, 0.0]),
        "G92 at X10 (program X−90): {e:?}"
    );
    assert!(
        close(e[2], [105.0, 0.0, 0.0]),
        "G52 kept after G92.1: {e:?}"
    );
}

#[test]
fn reverse_compensation_writes_g52_programs_in_their_local_frame() {
    // Two parts through one contour at two G52 origins: the compensated
    // words must be written in the local frame (a point written in the work
    // frame would land 100 mm away when the control adds the shift again).
    let part = "G0 X0 Y0\nG1 X20 F3000\nY20\nG2 X0 Y0 I-10 J-10\nG0 Z5\n";
    let src = format!("G21 G90 G17\nG52 X100 Y50\n{part}G52 X200 Y50\n{part}G52 X0 Y0\nM30\n");
    let p = parse(&src).unwrap();
    // It did compensate (a result it found worse would be the source unchanged).
    let c = compensated(&src);
    let q = parse(&c.nc).unwrap();
    // The compensation may add dwells (G4) and corner spikes (two G1
    // lines out and back) at corners: compare the moves, spikes left out.
    let (pm, qm) = (moves(&p), moves(&q));
    assert_eq!(qm.len(), pm.len() + 2 * c.spikes.len(), "{}", c.nc);
    let mut k = 0;
    for a in &pm {
        let skipped = k;
        while k < qm.len() && mtmotion::nc::program::dist(a.end.p(), qm[k].end.p()) >= 0.05 {
            k += 1;
        }
        assert!(
            k < qm.len() && k - skipped <= 2,
            "{:?} not reached after at most one spike\n{}",
            a.end.p(),
            c.nc
        );
        k += 1;
    }
    assert!(
        c.nc.contains("G52 X100 Y50") && c.nc.contains("G52 X200 Y50"),
        "{}",
        c.nc
    );
}

#[test]
fn other_controls_languages_are_refused_by_name() {
    // Siemens Sinumerik: ISO-looking blocks, then a cycle call.
    let e = parse("N10 G17 G54 G90\nN20 G0 X0 Y0 Z5\nN80 CYCLE81(5,0,1,-10)\nM30").unwrap_err();
    assert_eq!((e.line, e.column), (3, 5), "{e}");
    assert!(e.message.contains("Siemens Sinumerik"), "{e}");
    // Heidenhain conversational: refused at its first line.
    let e = parse_all(
        "0 BEGIN PGM TEST MM\n1 BLK FORM 0.1 Z X+0 Y+0 Z-20\n2 L X+10 R0 FMAX",
        &ParseOptions::default(),
    )
    .unwrap_err();
    assert_eq!((e.errors[0].line, e.errors[0].column), (1, 1));
    assert!(
        e.errors[0].message.contains("Heidenhain conversational"),
        "{:?}",
        e.errors
    );
    assert_eq!(
        e.errors.len(),
        1,
        "one refusal for the program: {:?}",
        e.errors
    );
    // A decimal comma is named with the word as it should be.
    let e = parse("G21 G90\nG1 X1,5 Y2 F100").unwrap_err();
    assert_eq!((e.line, e.column), (2, 6), "{e}");
    assert!(
        e.message.contains("'X1,5': a decimal comma") && e.message.contains("'X1.5'"),
        "{e}"
    );
}

#[test]
fn g95_feed_per_revolution_is_f_times_s() {
    // FANUC/Haas G95: F is mm (G20: inch) per spindle revolution, so the
    // feed is F × S mm/min; G94 returns to F in mm/min.
    let p = parse("G21 G90 G0 X0 Y0\nS1000 M3\nG95 G1 X10 F0.1\nG94 G1 X20 F300").unwrap();
    assert_eq!(p.segments[1].feed, 0.1 * 1000.0);
    assert_eq!(p.segments[2].feed, 300.0);
    // The S word under G94 is warned about; under G95 it is the feed's.
    assert!(p
        .warnings
        .iter()
        .any(|w| w.line == 2 && w.message.starts_with("S1000: ")));
    let p = parse("G20 G90 G0 X0\nG95 S500 G1 X1 F0.004").unwrap();
    assert!((p.segments[1].feed - 0.004 * 25.4 * 500.0).abs() < 1e-9);
    assert!(p.warnings.iter().all(|w| w.line != 2), "{:?}", p.warnings);
    // A G84 rigid tap as FreeCAD's Fanuc post writes it: F is the pitch.
    let p =
        parse("G21 G90 G0 X10 Y10 Z25\nG95\nM29 S1000\nG84 Z-10 R20 F1 P1 Q1\nG80\nG94").unwrap();
    let cutting: Vec<f64> = p
        .segments
        .iter()
        .filter(|s| s.feed > 0.0)
        .map(|s| s.feed)
        .collect();
    assert!(
        !cutting.is_empty() && cutting.iter().all(|&f| f == 1000.0),
        "{cutting:?}"
    );
    // A negative S is refused at the S.
    let e = parse("G0 X0\nG95 S-1000 G1 X1 F1").unwrap_err();
    assert_eq!((e.line, e.column), (2, 5), "{e}");
    assert!(e.message.contains("negative spindle speed"), "{e}");
    // Without S the move says what is missing, at the move.
    let e = parse("G0 X0\nG95 G1 X10 F0.1").unwrap_err();
    assert_eq!(e.line, 2, "{e}");
    assert!(e.message.contains("needs the spindle speed"), "{e}");
    // Reverse compensation keeps G95 and writes any feed it adds per
    // revolution: every move of the written program (its connectors at
    // tangent arc-line joints included) reads back at 0.5 mm × 4000/min.
    let src = "G21 G90 G0 X0 Y0\nS4000 M3\nG95 G1 X20 F0.5\nG3 X30 Y10 R10\nG1 Y30\nG2 X40 Y40 I10 J0\nG1 X60\nG0 Z5\nG94 M30";
    let p = parse(src).unwrap();
    let c = compensated(src);
    let q = parse(&c.nc).unwrap();
    assert!(feeds(&p).iter().all(|&f| f == 0.0 || f == 2000.0));
    let (fp, fq) = (feeds(&p), feeds(&q));
    assert!(fq.len() >= fp.len(), "{}", c.nc);
    assert!(
        fq.iter().all(|&f| f == 0.0 || f == 2000.0),
        "{fq:?}\n{}",
        c.nc
    );
    assert_eq!(
        fq.iter().filter(|&&f| f > 0.0).count(),
        fq.len() - 2,
        "only the first and last moves are rapids: {fq:?}"
    );
    assert!(c.nc.contains("G95"), "{}", c.nc);
}

#[test]
fn the_flat_writer_writes_a_g95_program_in_mm_per_minute() {
    // writer::write writes each move's feed in mm/min: the G95 of the
    // source must not be written with it (F0.1 × S1000 → F100, under G94).
    let p = parse("G21 G90 G0 X0 Y0\nS1000 M3\nG95 G1 X10 F0.1\nY10\nG94 G1 X0 F300").unwrap();
    let flat = mtmotion::nc::writer::write(&p, &p.segments);
    let q = parse(&flat).unwrap();
    assert_eq!(feeds(&q), feeds(&p), "{flat}");
}

#[test]
fn the_patcher_writes_a_new_move_under_g95_per_revolution() {
    // A move the rewrite adds (no source block) before a block that sets a
    // new feed takes that feed: under G95 S4000 its 1000 mm/min is written
    // F0.25 (per revolution), not F1000 (which would read as 4 m/min × 1000).
    let src = "G21 G90 G0 X0 Y0\nS4000 M3\nG95 G1 X20 F0.5\nG1 Y20 F0.25\nM30";
    let (text, read) = with_added_move(src, 2, 5.0, None);
    assert_eq!(read, [0.0, 2000.0, 1000.0, 1000.0], "{text}");
    assert!(text.contains("Y5 F0.25"), "{text}");
}

#[test]
fn an_absurdly_low_feed_is_named_with_its_true_sample_count() {
    // G95 with S1e-21 rpm: 1e-21 mm/min. The count of samples it would need
    // (6e25) was cast to an integer and reported as 4294967295 in wasm.
    use mtmotion::toolpath::{simulate::simulate, SimConfig};
    let p = parse("G0 X0\nG95 S0.000000000000000000001 G1 X1 F1").unwrap();
    let e = simulate(&p.segments, &p.segments, &SimConfig::default()).unwrap_err();
    let m = e.to_string();
    assert!(
        m.contains("would need 6.000e25 samples") && m.contains("very low feed"),
        "{m}"
    );
}

#[test]
fn g93_inverse_time_moves_take_one_over_f_minutes() {
    // RS274/NGC and FANUC G93: each cutting move takes 1/F minutes and
    // needs its own F; the feed is then its length × F (mm/min), or for a
    // rotary-only move its largest rotary move × F (deg/min). F is 1/min
    // under G20 as under G21.
    let p = parse("G21 G90 G0 X0 Y0\nG93 G1 X10 F2\nG1 X10 Y10 F0.5\nG1 A90 F4").unwrap();
    assert_eq!(feeds(&p), [0.0, 20.0, 5.0, 360.0]);
    let p = parse("G20 G90 G0 X0\nG93 G1 X1 F2").unwrap();
    assert!((p.segments[1].feed - 50.8).abs() < 1e-12);
    // Every G93 move needs its own F; a change of mode clears F (FANUC):
    // F2 under G93 is no feed per minute after G94.
    for (src, line) in [
        ("G0 X0\nG93 G1 X10 F2\nX20", 3),
        ("G0 X0\nG93 G1 X10 F2\nG94 G1 X20", 3),
        ("G0 X0\nG94 G1 X10 F300\nG95 S1000 G1 X20", 3),
    ] {
        let e = parse(src).unwrap_err();
        assert_eq!(e.line, line, "{src}: {e}");
        assert!(e.message.contains("without a feed"), "{src}: {e}");
    }
    // A canned cycle needs a feed per minute.
    let e = parse("G0 X0 Z5\nG93 G81 X1 Y1 Z-1 R1 F2").unwrap_err();
    assert!(e.message.contains("under G93"), "{e}");
    // LinuxCNC's daisy.ngc plays a song: each note is one G93 move of
    // F[60/t] (t seconds). The cutting moves' time is the sum of the note
    // lengths written in its O200 calls, 31.993 s.
    let Some(text) = corpus::text("linuxcnc_daisy.ngc") else {
        return;
    };
    let notes: f64 = text
        .lines()
        .filter_map(|l| l.strip_prefix("O200 call ["))
        .map(|l| l.split(']').next().unwrap().parse::<f64>().unwrap())
        .sum();
    let p = parse(&text).unwrap();
    let cutting: f64 = p
        .segments
        .iter()
        .filter(|s| s.is_cutting())
        .map(|s| s.timed_length() / s.feed * 60.0)
        .sum();
    assert!(
        (notes - 31.993).abs() < 1e-9 && (cutting - notes).abs() < 1e-9,
        "{cutting} vs {notes}"
    );
}

#[test]
fn the_writers_keep_g93_timing() {
    // The flat writer writes G94 and each move's feed in mm/min (deg/min
    // for a rotary-only move); reverse compensation keeps the G93 words.
    let src = "G21 G90 G0 X0 Y0\nG93 G1 X20 F40\nG3 X30 Y10 R10 F60\nG1 Y30 F30\nG1 A90 F8\nG1 X60 F20\nG94 M30";
    let p = parse(src).unwrap();
    let flat = mtmotion::nc::writer::write(&p, &p.segments);
    let q = parse(&flat).unwrap();
    let (a, b) = (feeds(&p), feeds(&q));
    assert!(
        a.iter()
            .zip(&b)
            .all(|(x, y)| (x - y).abs() < 1e-6 * x.max(1.0)),
        "{a:?} {b:?}\n{flat}"
    );
    assert!(!flat.contains("G93"), "{flat}");
    use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
    let c = reverse_compensate(src, &ReverseConfig::default()).unwrap();
    assert!(c.after.max_error_um <= c.before.max_error_um);
    let q = parse(&c.nc).unwrap();
    // Moved end points change a G93 move's length by microns: its feed by as little.
    let b = feeds(&q);
    assert!(
        a.iter()
            .zip(&b)
            .all(|(x, y)| (x - y).abs() < 1e-3 * x.max(1.0)),
        "{a:?} {b:?}\n{}",
        c.nc
    );
}

#[test]
fn the_patcher_writes_a_new_move_under_g93_with_its_own_inverse_time() {
    // A move the rewrite adds under G93 needs its own F: its feed over its
    // length (here 1000 mm/min over 5 mm: F200, 0.3 s).
    let src = "G21 G90 G0 X0 Y0\nG93 G1 X20 F100\nG1 Y20 F50\nG94 M30";
    let (text, read) = with_added_move(src, 2, 5.0, Some(1000.0));
    assert!(text.contains("Y5 F200"), "{text}");
    assert_eq!(read[2], 1000.0, "{text}");
}
