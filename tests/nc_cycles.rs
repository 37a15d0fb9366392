//! Canned cycles: each expansion compared with the cycle's written
//! definition (Fanuc 0i-MF/30i-B operator's manuals; the sequences below
//! are written out by hand from those definitions, with the peck clearance
//! `d` = `PECK_CLEARANCE` = 0.5 mm).

use mtmotion::nc::cycles::PECK_CLEARANCE;
use mtmotion::nc::program::{parse, Motion};

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
    for g in ["G84", "G74"] {
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
        ("G88 X1 Z-1 R1 F100", 1, "manual retract"),
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
