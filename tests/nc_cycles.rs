//! Canned cycles: each expansion compared with the cycle's written
//! definition (Fanuc 0i-MF/30i-B operator's manuals; the sequences below
//! are written out by hand from those definitions, with the peck clearance
//! `d` = `PECK_CLEARANCE` = 0.5 mm), and the reading of the levels: G90
//! levels scaled by the unit and shifted by G92, G91 levels from the
//! initial level and R (a new R moves a G91 bottom), Q in the program's
//! unit, and every boundary (a 1e-12 mm level change, P0, exactly
//! `MAX_PECKS` pecks, the repeat-count range, the segment budget) on both
//! sides. Positions to 1e-9 mm (sums of exact inputs).

use mtmotion::nc::cycles::{MAX_PECKS, PECK_CLEARANCE};
use mtmotion::nc::program::{parse, parse_with, Motion, ParseOptions};

/// A move as (kind, end): 'R' rapid, 'F' feed, 'D' dwell (end x = seconds).
type Move = (char, [f64; 3]);

fn moves(src: &str) -> Vec<Move> {
    let p = parse(src).unwrap_or_else(|e| panic!("{src}: {e}"));
    p.segments
        .iter()
        .map(|s| match s.motion {
            Motion::Rapid => ('R', s.end.p()),
            Motion::Linear => ('F', s.end.p()),
            Motion::Dwell { seconds } => ('D', [seconds, 0.0, 0.0]),
            Motion::Arc(_) => ('A', s.end.p()),
        })
        .collect()
}

fn check(src: &str, want: &[(char, [f64; 3])]) {
    let got = moves(src);
    assert_eq!(got.len(), want.len(), "{src}\n got {got:?}\nwant {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            g.0 == w.0 && (0..3).all(|k| (g.1[k] - w.1[k]).abs() < 1e-9),
            "{src}\n got {got:?}\nwant {want:?}"
        );
    }
}

const START: &str = "G0 X0 Y0 Z10\n";

#[test]
fn g81_drill_returns_to_the_initial_level_under_g98() {
    check(
        &format!("{START}G98 G81 X5 Y5 Z-3 R2 F100"),
        &[
            ('R', [0.0, 0.0, 10.0]),
            ('R', [5.0, 5.0, 10.0]),
            ('R', [5.0, 5.0, 2.0]),
            ('F', [5.0, 5.0, -3.0]),
            ('R', [5.0, 5.0, 10.0]),
        ],
    );
    let p = parse(&format!("{START}G81 X5 Y5 Z-3 R2 F100")).unwrap();
    assert!(p.segments[1..].iter().all(|s| s.fixed && s.line == 2));
}

#[test]
fn g82_dwells_and_g99_stays_at_r_for_the_next_hole() {
    check(
        &format!("{START}G99 G82 X5 Y5 Z-3 R2 P1500 F100\nX10"),
        &[
            ('R', [0.0, 0.0, 10.0]),
            ('R', [5.0, 5.0, 10.0]),
            ('R', [5.0, 5.0, 2.0]),
            ('F', [5.0, 5.0, -3.0]),
            ('D', [1.5, 0.0, 0.0]),
            ('R', [5.0, 5.0, 2.0]),
            // Modal: the next block with X drills again, from R.
            ('R', [10.0, 5.0, 2.0]),
            ('F', [10.0, 5.0, -3.0]),
            ('D', [1.5, 0.0, 0.0]),
            ('R', [10.0, 5.0, 2.0]),
        ],
    );
}

#[test]
fn g83_peck_retracts_to_r_and_returns_to_d_above_the_last_depth() {
    let d = PECK_CLEARANCE;
    check(
        &format!("{START}G83 X0 Y0 Z-10 R2 Q4 F100"),
        &[
            ('R', [0.0, 0.0, 10.0]),
            ('R', [0.0, 0.0, 2.0]),
            ('F', [0.0, 0.0, -2.0]),
            ('R', [0.0, 0.0, 2.0]),
            ('R', [0.0, 0.0, -2.0 + d]),
            ('F', [0.0, 0.0, -6.0]),
            ('R', [0.0, 0.0, 2.0]),
            ('R', [0.0, 0.0, -6.0 + d]),
            ('F', [0.0, 0.0, -10.0]),
            ('R', [0.0, 0.0, 10.0]),
        ],
    );
}

#[test]
fn g73_high_speed_peck_backs_off_by_d() {
    let d = PECK_CLEARANCE;
    check(
        &format!("{START}G73 X0 Y0 Z-10 R2 Q4 F100"),
        &[
            ('R', [0.0, 0.0, 10.0]),
            ('R', [0.0, 0.0, 2.0]),
            ('F', [0.0, 0.0, -2.0]),
            ('R', [0.0, 0.0, -2.0 + d]),
            ('F', [0.0, 0.0, -6.0]),
            ('R', [0.0, 0.0, -6.0 + d]),
            ('F', [0.0, 0.0, -10.0]),
            ('R', [0.0, 0.0, 10.0]),
        ],
    );
}

#[test]
fn tapping_g84_and_g74_feed_out_to_r() {
    // G84.2/G84.3, Fanuc's rigid tapping, move the axes as G84/G74
    for g in ["G84", "G74", "G84.2", "G84.3"] {
        check(
            &format!("{START}{g} X1 Y0 Z-5 R3 P200 F125"),
            &[
                ('R', [0.0, 0.0, 10.0]),
                ('R', [1.0, 0.0, 10.0]),
                ('R', [1.0, 0.0, 3.0]),
                ('F', [1.0, 0.0, -5.0]),
                ('D', [0.2, 0.0, 0.0]),
                ('F', [1.0, 0.0, 3.0]),
                ('R', [1.0, 0.0, 10.0]),
            ],
        );
    }
}

#[test]
fn boring_g85_g86_g89_g76() {
    let head = [
        ('R', [0.0, 0.0, 10.0]),
        ('R', [0.0, 0.0, 2.0]),
        ('F', [0.0, 0.0, -4.0]),
    ];
    let cases: [(&str, Vec<Move>); 4] = [
        ("G85", vec![('F', [0.0, 0.0, 2.0]), ('R', [0.0, 0.0, 10.0])]),
        ("G86", vec![('R', [0.0, 0.0, 10.0])]),
        (
            "G89",
            vec![
                ('D', [0.5, 0.0, 0.0]),
                ('F', [0.0, 0.0, 2.0]),
                ('R', [0.0, 0.0, 10.0]),
            ],
        ),
        ("G76", vec![('D', [0.5, 0.0, 0.0]), ('R', [0.0, 0.0, 10.0])]),
    ];
    for (g, tail) in cases {
        let mut want = head.to_vec();
        want.extend(tail);
        check(&format!("{START}{g} X0 Y0 Z-4 R2 P500 Q0.1 F80"), &want);
    }
    let p = parse(&format!("{START}G76 X0 Y0 Z-4 R2 P500 Q0.1 F80")).unwrap();
    assert!(p.warnings.iter().any(|w| w.message.contains("tool shift")));
}

#[test]
fn g91_repeats_step_from_hole_to_hole() {
    // Initial level 10; R = 10 − 8 = 2; bottom = R − 5 = −3; K3 and L3
    // drill at X10, X20, X30 and stay at R (G99).
    for k in ["K3", "L3"] {
        let src = format!("{START}G91 G99 G81 X10 Z-5 R-8 {k} F100");
        let mut want = vec![('R', [0.0, 0.0, 10.0])];
        for (i, x) in [10.0, 20.0, 30.0].into_iter().enumerate() {
            want.push(('R', [x, 0.0, if i == 0 { 10.0 } else { 2.0 }]));
            if i == 0 {
                want.push(('R', [x, 0.0, 2.0]));
            }
            want.push(('F', [x, 0.0, -3.0]));
            want.push(('R', [x, 0.0, 2.0]));
        }
        check(&src, &want);
    }
    // K0 stores the data and drills nothing.
    assert_eq!(moves(&format!("{START}G81 X5 Z-3 R2 K0 F100")).len(), 1);
}

#[test]
fn cycles_in_g18_and_g19_drill_along_y_and_x() {
    check(
        "G18 G0 X0 Y10 Z0\nG81 Z5 X5 Y-3 R2 F100",
        &[
            ('R', [0.0, 10.0, 0.0]),
            ('R', [5.0, 10.0, 5.0]),
            ('R', [5.0, 2.0, 5.0]),
            ('F', [5.0, -3.0, 5.0]),
            ('R', [5.0, 10.0, 5.0]),
        ],
    );
    check(
        "G19 G0 X10 Y0 Z0\nG81 Y5 Z5 X-3 R2 F100",
        &[
            ('R', [10.0, 0.0, 0.0]),
            ('R', [10.0, 5.0, 5.0]),
            ('R', [2.0, 5.0, 5.0]),
            ('F', [-3.0, 5.0, 5.0]),
            ('R', [10.0, 5.0, 5.0]),
        ],
    );
}

#[test]
fn g80_and_motion_codes_end_the_cycle() {
    check(
        &format!("{START}G81 X5 Z-3 R2 F100\nG80 X20\nG81 X6 Z-3 R2\nG1 X7"),
        &[
            ('R', [0.0, 0.0, 10.0]),
            ('R', [5.0, 0.0, 10.0]),
            ('R', [5.0, 0.0, 2.0]),
            ('F', [5.0, 0.0, -3.0]),
            ('R', [5.0, 0.0, 10.0]),
            // After G80 the modal G0 moves.
            ('R', [20.0, 0.0, 10.0]),
            ('R', [6.0, 0.0, 10.0]),
            ('R', [6.0, 0.0, 2.0]),
            ('F', [6.0, 0.0, -3.0]),
            ('R', [6.0, 0.0, 10.0]),
            // G1 cancels the cycle: a plain line.
            ('F', [7.0, 0.0, 10.0]),
        ],
    );
}

#[test]
fn refused_and_incomplete_cycles_are_located() {
    for (src, col, phrase) in [
        ("G87 X1 Z-1 R1 F100", 1, "back boring"),
        ("G81 X1 F100", 1, "needs the R level"),
        ("G83 X1 Z-5 R1 F100", 1, "peck depth Q"),
        ("G81 X1 Z-5 R1 K2.5 F100", 15, "whole number"),
    ] {
        let e = parse(src).unwrap_err();
        assert_eq!((e.line, e.column), (1, col), "{src}: {e}");
        assert!(e.message.contains(phrase), "{src}: {e}");
    }
}

#[test]
fn a_new_g91_r_without_a_bottom_moves_the_bottom_with_r() {
    // Issue 25: the second hole gives R−0.3 (from the initial level 1 in:
    // R = 0.7 in) and no Z, so its bottom is R − 0.6 = 0.1 in, as
    // LinuxCNC's rs274 prints it (STRAIGHT_FEED(2, 1, 0.1)); it was fed to
    // the first hole's −0.1 in, 5.08 mm deeper. G99 as LinuxCNC's default.
    let i = 25.4;
    check(
        "G20 G17 G90 G0 X0 Y0 Z1\nG91 G99 G81 X1 Y1 Z-0.6 R-0.5 F10\nX1 R-0.3\nG80\nM2",
        &[
            ('R', [0.0, 0.0, i]),
            ('R', [i, i, i]),
            ('R', [i, i, 0.5 * i]),
            ('F', [i, i, -0.1 * i]),
            ('R', [i, i, 0.5 * i]),
            // Fanuc: to the hole at the current level, then up to R
            // (LinuxCNC makes these one diagonal rapid).
            ('R', [2.0 * i, i, 0.5 * i]),
            ('R', [2.0 * i, i, 0.7 * i]),
            ('F', [2.0 * i, i, 0.1 * i]),
            ('R', [2.0 * i, i, 0.7 * i]),
        ],
    );
    // Under G90 the bottom is absolute: a new R leaves it where it is.
    check(
        &format!("{START}G99 G81 X1 Z-3 R2 F100\nX2 R4"),
        &[
            ('R', [0.0, 0.0, 10.0]),
            ('R', [1.0, 0.0, 10.0]),
            ('R', [1.0, 0.0, 2.0]),
            ('F', [1.0, 0.0, -3.0]),
            ('R', [1.0, 0.0, 2.0]),
            ('R', [2.0, 0.0, 2.0]),
            ('R', [2.0, 0.0, 4.0]),
            ('F', [2.0, 0.0, -3.0]),
            ('R', [2.0, 0.0, 4.0]),
        ],
    );
}

/// Absolute (G90) R and bottom levels are scaled by the unit and shifted by
/// the G92 offset; a modal block with a new R keeps the absolute bottom;
/// after G21 the same offset (mm) applies to metric words. Inch: 25.4 mm.
/// G92 X1 Z0.5 at X0 Z1 in: offsets X −25.4 mm, Z +12.7 mm.
#[test]
fn g90_levels_are_scaled_by_the_unit_and_shifted_by_g92() {
    let i = 25.4;
    check(
        "G20 G17 G90 G0 X0 Y0 Z1\nG92 X1 Z0.5\nG99 G81 X0.2 Y0.3 Z-0.25 R0.1 F10\nX0.4 R0.2\nG21 X10 Z-5 R3",
        &[
            ('R', [0.0, 0.0, i]),
            // R 0.1 in + 12.7 = 15.24; bottom −0.25 in + 12.7 = 6.35.
            ('R', [0.2 * i - i, 0.3 * i, i]),
            ('R', [0.2 * i - i, 0.3 * i, 15.24]),
            ('F', [0.2 * i - i, 0.3 * i, 6.35]),
            ('R', [0.2 * i - i, 0.3 * i, 15.24]),
            // R 0.2 in + 12.7 = 17.78; the bottom stays 6.35.
            ('R', [0.4 * i - i, 0.3 * i, 15.24]),
            ('R', [0.4 * i - i, 0.3 * i, 17.78]),
            ('F', [0.4 * i - i, 0.3 * i, 6.35]),
            ('R', [0.4 * i - i, 0.3 * i, 17.78]),
            // G21: X10 − 25.4, R 3 + 12.7, bottom −5 + 12.7.
            ('R', [10.0 - i, 0.3 * i, 17.78]),
            ('R', [10.0 - i, 0.3 * i, 15.7]),
            ('F', [10.0 - i, 0.3 * i, 7.7]),
            ('R', [10.0 - i, 0.3 * i, 15.7]),
        ],
    );
}

/// G91 levels in inch from a non-zero initial level: R from the initial
/// level, the bottom from R, both × 25.4, and Q in inch.
#[test]
fn g91_levels_and_the_peck_depth_are_read_in_inch() {
    let d = PECK_CLEARANCE;
    // Initial 1 in = 25.4; R = 25.4 − 0.9 × 25.4 = 2.54; bottom = R − 15.24
    // = −12.7; Q 0.25 in = 6.35: pecks to −3.81, −10.16, −12.7.
    check(
        "G20 G0 X0 Y0 Z1\nG91 G98 G83 X0.5 Z-0.6 R-0.9 Q0.25 F10",
        &[
            ('R', [0.0, 0.0, 25.4]),
            ('R', [12.7, 0.0, 25.4]),
            ('R', [12.7, 0.0, 2.54]),
            ('F', [12.7, 0.0, -3.81]),
            ('R', [12.7, 0.0, 2.54]),
            ('R', [12.7, 0.0, 2.54 - (6.35 - d)]),
            ('F', [12.7, 0.0, -10.16]),
            ('R', [12.7, 0.0, 2.54]),
            ('R', [12.7, 0.0, 2.54 - (12.7 - d)]),
            ('F', [12.7, 0.0, -12.7]),
            ('R', [12.7, 0.0, 25.4]),
        ],
    );
}

/// The boundaries: an R level 1e-12 mm from the current level is a move
/// (only closer is none); P0 dwells not at all and is allowed, a negative
/// P is refused; a 20 m deep hole (where bottom − 1e-12 rounds to the
/// bottom) ends at its bottom after exactly four pecks.
#[test]
fn level_dwell_and_peck_boundaries() {
    check(
        "G0 X0 Y0 Z0\nG81 X0 Y0 Z-1 R0.000000000001 F100",
        &[
            ('R', [0.0, 0.0, 0.0]),
            ('R', [0.0, 0.0, 1e-12]),
            ('F', [0.0, 0.0, -1.0]),
            ('R', [0.0, 0.0, 0.0]),
        ],
    );
    let p = parse("G0 X0 Y0 Z0\nG81 X0 Y0 Z-1 R0.000000000001 F100").unwrap();
    assert_eq!(p.segments.len(), 4);
    assert_eq!(p.segments[1].end.z, 1e-12);
    check(
        &format!("{START}G82 X0 Y0 Z-1 R1 P0 F100"),
        &[
            ('R', [0.0, 0.0, 10.0]),
            ('R', [0.0, 0.0, 1.0]),
            ('F', [0.0, 0.0, -1.0]),
            ('R', [0.0, 0.0, 10.0]),
        ],
    );
    let e = parse(&format!("{START}G82 X0 Y0 Z-1 R1 P-1 F100")).unwrap_err();
    assert_eq!((e.line, e.column), (2, 18), "{e}");
    assert!(e.message.contains("zero or positive"), "{e}");
    let d = PECK_CLEARANCE;
    let mut want = vec![('R', [0.0, 0.0, 10.0]), ('R', [0.0, 0.0, 0.0])];
    for k in 1..=4 {
        let depth = -5000.0 * k as f64;
        if k > 1 {
            want.push(('R', [0.0, 0.0, depth + 5000.0 + d]));
        }
        want.push(('F', [0.0, 0.0, depth]));
    }
    want.push(('R', [0.0, 0.0, 10.0]));
    check(&format!("{START}G73 X0 Y0 Z-20000 R0 Q5000 F100"), &want);
}

/// A feed of zero is refused; a block with only A beside the cycle's
/// axes, or C on a machine with a C axis, is refused naming the word.
#[test]
fn a_zero_feed_and_axes_outside_the_plane_are_refused() {
    let e = parse(&format!("{START}G81 X1 Z-1 R1 F0")).unwrap_err();
    assert!(e.message.contains("without a feed"), "{e}");
    let e = parse(&format!("{START}G81 X1 Z-1 R1 A5 F100")).unwrap_err();
    assert_eq!((e.line, e.column), (2, 15), "{e}");
    assert!(e.message.starts_with("A5 in a canned-cycle block"), "{e}");
    let opt = ParseOptions {
        c_axis: true,
        ..ParseOptions::default()
    };
    let e = parse_with(&format!("{START}G81 X1 Z-1 R1 C5 F100"), &opt).unwrap_err();
    assert!(e.message.starts_with("C5 in a canned-cycle block"), "{e}");
}

/// The peck count is ⌈|bottom − R| / Q⌉ and at most `MAX_PECKS`: R 1,
/// bottom −1249, Q 0.125 gives exactly 10,000 pecks (accepted: 1 feed,
/// then 3 moves per later peck but for the 4 that return to R itself,
/// within the 0.5 mm clearance of it), 0.125 mm deeper gives 10,001
/// (refused, at Q, with the count).
#[test]
fn exactly_max_pecks_are_drilled_and_one_more_is_refused() {
    assert_eq!(MAX_PECKS, 10_000);
    let p = parse(&format!("{START}G83 X0 Y0 Z-1249 R1 Q0.125 F100")).unwrap();
    // Start, rapid to R, 1 + 3 × 9999 − 4 peck moves, the return.
    assert_eq!(p.segments.len(), 1 + 1 + 1 + 3 * 9_999 - 4 + 1);
    let last_feed = p
        .segments
        .iter()
        .rev()
        .find(|s| s.motion == Motion::Linear)
        .unwrap();
    assert_eq!(last_feed.end.z, -1249.0);
    // Q of a cycle that does not peck (G76's shift) counts no pecks.
    let p = parse(&format!("{START}G76 X0 Y0 Z-4 R2 P500 Q0.0001 F80")).unwrap();
    assert_eq!(p.segments.len(), 5);
    let e = parse(&format!("{START}G83 X0 Y0 Z-1249.125 R1 Q0.125 F100")).unwrap_err();
    assert_eq!((e.line, e.column), (2, 25), "{e}");
    assert!(
        e.message
            .starts_with("10001 pecks of Q0.125 mm for a 1250.12"),
        "{e}"
    );
}

/// K/L: a negative count and one over 9999 are refused.
#[test]
fn repeat_counts_outside_0_to_9999_are_refused() {
    for (k, col) in [("K-1", 20), ("L10000", 20)] {
        let e = parse(&format!("{START}G81 X1 Z-5 R1 F100 {k}")).unwrap_err();
        assert_eq!((e.line, e.column), (2, col), "{k}: {e}");
        assert!(
            e.message.contains("whole number from 0 to 9999"),
            "{k}: {e}"
        );
    }
}

/// The segment budget stops a cycle's holes as soon as it is exceeded,
/// not when it is reached: with a budget of 7 segments, the start and two
/// holes (1 + 4 + 2) fit, the third (9) is refused.
#[test]
fn the_segment_budget_is_exceeded_by_the_third_hole_not_reached_by_the_second() {
    let src = format!("{START}G99 G81 X5 Z-3 R2 L3 F100");
    assert_eq!(parse(&src).unwrap().segments.len(), 9);
    let opt = |n| ParseOptions {
        max_executed_blocks: n,
        ..ParseOptions::default()
    };
    assert_eq!(parse_with(&src, &opt(9)).unwrap().segments.len(), 9);
    let e = parse_with(&src, &opt(7)).unwrap_err();
    assert!(e.message.starts_with("more than 7 segments"), "{e}");
    let two = format!("{START}G99 G81 X5 Z-3 R2 L2 F100");
    assert_eq!(parse_with(&two, &opt(7)).unwrap().segments.len(), 7);
}

/// A remnant of less than 1e-12 mm below the last peck is not drilled: a
/// G73 from R0 to −1.000000000001 by Q1 is one peck to −1 (one more peck
/// would back off and feed 1e-12 mm).
#[test]
fn a_remnant_under_1e_12_mm_is_not_pecked() {
    check(
        "G0 X0 Y0 Z5\nG73 X0 Y0 Z-1.000000000001 R0 Q1 F100",
        &[
            ('R', [0.0, 0.0, 5.0]),
            ('R', [0.0, 0.0, 0.0]),
            ('F', [0.0, 0.0, -1.0]),
            ('R', [0.0, 0.0, 5.0]),
        ],
    );
    let p = parse("G0 X0 Y0 Z5\nG73 X0 Y0 Z-1.000000000001 R0 Q1 F100").unwrap();
    assert_eq!(p.segments[2].end.z, -1.0);
}

#[test]
fn g87_back_bores_through_the_hole_in_the_rs274_ngc_form() {
    // From Z5: hole at X10 Y20, shift I2 J-1, R1, bottom Z-10, top of the
    // back bore K-6 (NISTIR 6556 G87; LinuxCNC's rs274): shifted down,
    // fed up to K and back, shifted out, up to the initial level.
    check(
        "G0 X0 Y0 Z5\nG98 G87 X10 Y20 Z-10 R1 I2 J-1 K-6 F100",
        &[
            ('R', [0.0, 0.0, 5.0]),
            ('R', [10.0, 20.0, 5.0]),
            ('R', [10.0, 20.0, 1.0]),
            ('R', [12.0, 19.0, 1.0]),
            ('R', [12.0, 19.0, -10.0]),
            ('R', [10.0, 20.0, -10.0]),
            ('F', [10.0, 20.0, -6.0]),
            ('F', [10.0, 20.0, -10.0]),
            ('R', [12.0, 19.0, -10.0]),
            ('R', [12.0, 19.0, 5.0]),
            ('R', [10.0, 20.0, 5.0]),
        ],
    );
    // G99 returns to R; I/J/K are kept for the next hole; K is no repeat
    // count (L is); under G91 K is from the bottom
    let got =
        moves("G0 X0 Y0 Z5\nG99 G87 X10 Y0 Z-10 R1 I2 J0 K-6 F100\nX20 L2\nG91 X5 Z-11 R-4 K4");
    let feeds: Vec<[f64; 3]> = got.iter().filter(|m| m.0 == 'F').map(|m| m.1).collect();
    assert_eq!(
        feeds,
        vec![
            [10.0, 0.0, -6.0],
            [10.0, 0.0, -10.0],
            [20.0, 0.0, -6.0],
            [20.0, 0.0, -10.0],
            [20.0, 0.0, -6.0],
            [20.0, 0.0, -10.0],
            // G91: R = 5 − 4 = 1, bottom R − 11 = −10, top −10 + 4 = −6
            [25.0, 0.0, -6.0],
            [25.0, 0.0, -10.0],
        ]
    );
    assert_eq!(got.last().unwrap(), &('R', [25.0, 0.0, 1.0]));
    // G18: the shift is K (Z) and I (X), the top of the bore J (along Y)
    let got = moves("G18 G0 X0 Y5 Z0\nG87 Z3 X4 Y-10 R1 K1 I-1 J-6 F100");
    assert!(got.contains(&('R', [3.0, 1.0, 4.0])), "{got:?}");
    assert!(got.contains(&('F', [4.0, -6.0, 3.0])), "{got:?}");
}

#[test]
fn a_fanuc_g87_without_i_j_k_stays_refused_by_name() {
    for (src, col, phrase) in [
        (
            "G87 X1 Z-1 R1 Q2 F100",
            1,
            "without I, J and K: the Fanuc form",
        ),
        (
            "G87 X1 Z-1 R1 I1 J0 F100",
            1,
            "the RS274/NGC form G87 XYZ R I(shift) J(shift) K(top",
        ),
        ("G18 G87 Z1 Y-1 R1 K1 I0 F100", 5, "without K, I and J"),
    ] {
        let e = parse(src).unwrap_err();
        assert_eq!((e.line, e.column), (1, col), "{src}: {e}");
        assert!(e.message.contains(phrase), "{src}: {e}");
    }
}

#[test]
fn a_g91_r_after_a_g90_bottom_reads_the_bottom_number_from_r() {
    // the NIST test program (printhor_example3, lines 3-5): Z-1.1 under
    // G90, then G91 blocks with R but no Z: LinuxCNC re-reads the sticky
    // Z number as the distance from R
    let got = moves("G20 G0 X0 Y0 Z0\nG81 X3 Y4 R0.2 Z-1.1 F10\nG91 X1 R0\nY-2 R0.1");
    let feeds: Vec<f64> = got
        .iter()
        .filter(|m| m.0 == 'F')
        .map(|m| m.1[2] / 25.4)
        .collect();
    assert_eq!(feeds.len(), 3);
    for (f, want) in feeds.iter().zip([-1.1, -1.1, -1.0]) {
        assert!((f - want).abs() < 1e-12, "{feeds:?}");
    }
}

#[test]
fn rigid_tapping_feeds_at_pitch_times_speed() {
    // G95: F is the pitch (1.25 mm), the feed F × S = 1.25 × 800 mm/min,
    // in and out (Fanuc 15i-MA §13.2: P = F/S)
    let p = parse("G0 X0 Y0 Z10\nG95 S800 G99 G84.2 X1 Z-5 R3 F1.25").unwrap();
    let feeds: Vec<f64> = p
        .segments
        .iter()
        .filter(|s| s.motion == Motion::Linear)
        .map(|s| s.feed)
        .collect();
    assert_eq!(feeds, vec![1000.0, 1000.0]);
    assert_eq!(p.segments.last().unwrap().end.z, 3.0);
    let e = parse("G0 X0 Y0 Z10\nG95 G84.3 X1 Z-5 R3 F1.25").unwrap_err();
    assert!(e.message.contains("G84.3 without a feed"), "{e}");
}

/// G87's K (the top of the back bore) and its I/J shift are read in the
/// program's unit and K is shifted by the work offset, like R and Z: an
/// inch G87 after a G92 that moves Z by 0.3 in (7.62 mm). By hand, in mm:
/// hole X25.4 Y50.8, shift I0.08 = 2.032, R 2.54 + 7.62 = 10.16, bottom
/// −10.16 + 7.62 = −2.54, top of the bore −6.096 + 7.62 = 1.524.
#[test]
fn g87_levels_and_shift_are_in_inch_and_shifted_by_g92() {
    check(
        "G20 G0 X0 Y0 Z0.5\nG92 Z0.2\nG98 G87 X1 Y2 Z-0.4 R0.1 I0.08 J0 K-0.24 F4",
        &[
            ('R', [0.0, 0.0, 12.7]),
            ('R', [25.4, 50.8, 12.7]),
            ('R', [25.4, 50.8, 10.16]),
            ('R', [27.432, 50.8, 10.16]),
            ('R', [27.432, 50.8, -2.54]),
            ('R', [25.4, 50.8, -2.54]),
            ('F', [25.4, 50.8, 1.524]),
            ('F', [25.4, 50.8, -2.54]),
            ('R', [27.432, 50.8, -2.54]),
            ('R', [27.432, 50.8, 12.7]),
            ('R', [25.4, 50.8, 12.7]),
        ],
    );
}
