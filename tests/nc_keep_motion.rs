//! A program read for its motion only (`Keep::Motion`: what checkNc,
//! parseNc and simulateToolPath read, without a modal state per block,
//! 368 B each) gives the same segments, warnings, cutter stretches and
//! summary as the full read, the units included ("mm and inch" only where
//! it moves in both, the end state when it never moves), through
//! subprogram calls, canned cycles and macro loops; only its `modal` is
//! one state, the run's at its end.

use mtmotion::nc::files::{parse_files_keeping, NcFile};
use mtmotion::nc::program::{Keep, ParseOptions, Units};
use mtmotion::nc::summary::summarize;

fn both(text: &str, files: &[NcFile], opts: &ParseOptions) -> String {
    let all = parse_files_keeping(text, files, opts, Keep::All).unwrap();
    let motion = parse_files_keeping(text, files, opts, Keep::Motion).unwrap();
    assert_eq!(all.segments, motion.segments, "{text}");
    assert_eq!(all.warnings, motion.warnings, "{text}");
    assert_eq!(all.cutter, motion.cutter, "{text}");
    assert_eq!(all.modal.len(), all.blocks.len());
    assert_eq!(motion.modal.len(), 1);
    let (a, m) = (summarize(&all, 20_000.0), summarize(&motion, 20_000.0));
    assert_eq!(a, m, "{text}");
    a.units
}

#[test]
fn the_motion_only_read_gives_the_full_read_s_motion_and_summary() {
    let o = ParseOptions::default();
    let cases = [
        ("G21 G90\nG0 X1\nG20\nG1 X1.1 F10\nM30", "mm and inch"),
        ("G0 X1\nG20\nM30", "mm"),
        ("G20\nG0 X1\nG1 Y1 F10\nG21\nM30", "inch"),
        ("G20\nM30", "inch"),
        ("G21\nM30", "mm"),
        ("G90 G21 F100\nG0 Z5\nG83 X0 Y0 R1 Z-1 Q0.2 L10\nG80\nM98 P100 L3\nM30\nO100\nG91 G1 X1\nG90\nM99", "mm"),
        ("#1=0\nWHILE[#1LT5]DO1\nG1 X#1 F100\n#1=#1+1\nEND1\nM30", "mm"),
    ];
    for (text, units) in cases {
        assert_eq!(both(text, &[], &o), units, "{text}");
    }
    // A program that states no units, read in inch by the machine setting.
    let inch = ParseOptions {
        units: Units::Inch,
        ..ParseOptions::default()
    };
    assert_eq!(both("G0 X1\nG1 X2 F10\nM30", &[], &inch), "inch");
    // A subprogram in another file.
    let sub = NcFile {
        name: "O2000.nc".into(),
        text: "O2000\nG91 G1 X5 F100\nG90\nM99".into(),
    };
    assert_eq!(both("G0 X0\nM98 P2000\nG0 X100\nM30", &[sub], &o), "mm");
}
