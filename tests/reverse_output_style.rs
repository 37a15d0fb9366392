//! Proves that a compensated program is written like the program it came
//! from (issue 27, "written like the program"; `src/nc/num_style.rs`,
//! `src/nc/patch.rs`, `src/nc/dialect.rs`):
//! - every number that did not move stays byte for byte, also one whose
//!   move rounds away at the written resolution, and every line without a
//!   move is byte-identical, CRLF line ends included;
//! - a moved number takes the program's style: leading-dot inch Fanuc
//!   (`X-.75` → `X-.7512`, `X-3.`), one kept decimal (`Y-3.0` → `Y-4.0`),
//!   fixed 3 and 4 decimals padded (`25.250` → `25.252`, `0.2500`),
//!   LinuxCNC integers without a point, and a block's own fixed decimals;
//! - an inserted dwell takes the dialect's safe form, read back as the
//!   time meant under the control's own reading: `P<whole ms>` for Fanuc
//!   and Haas, `G4 P<seconds>` for LinuxCNC, the program's own `G04 X` or
//!   Haas `P1.5` form;
//! - on the shared corpus, every program the reverse compensation changes
//!   keeps every unmoved line and number (a line-by-line diff), and keeps
//!   its line ends.

#[path = "support/corpus.rs"]
mod corpus;

use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
use mtmotion::nc::patch::write_source;
use mtmotion::nc::program::{parse, parse_with, DwellP, Motion, ParseOptions, Segment};

/// `src` written with the end of the segment on `line` moved by `(dx, dy)`
/// (program units: inch under G20) and a 0.1 s dwell after each segment on
/// the lines `dwells`.
fn edited(src: &str, opts: &ParseOptions, moves: &[(usize, f64, f64)], dwells: &[usize]) -> String {
    let p = parse_with(src, opts).unwrap();
    let mut segs: Vec<Segment> = Vec::new();
    // A moved end carries over to the following blocks that do not move
    // that axis (they end where they start on it).
    let mut carry = [0.0f64; 2];
    for s in &p.segments {
        let mut s = s.clone();
        let u = if p.modal[s.block.unwrap()].inch {
            25.4
        } else {
            1.0
        };
        let own = moves
            .iter()
            .find(|m| m.0 == s.line)
            .map_or([0.0; 2], |m| [m.1 * u, m.2 * u]);
        let block = &p.blocks[s.block.unwrap()];
        for (k, c) in carry.iter_mut().enumerate() {
            let a = if k == 0 { &mut s.end.x } else { &mut s.end.y };
            if block.word(['X', 'Y'][k]).is_some() {
                *c = 0.0;
            }
            *c += own[k];
            *a += *c;
        }
        if let Some(prev) = segs.last() {
            s.start = prev.end;
        }
        let line = s.line;
        segs.push(s);
        if dwells.contains(&line) {
            let mut d = segs[segs.len() - 1].clone();
            d.block = None;
            d.start = d.end;
            d.motion = Motion::Dwell { seconds: 0.1 };
            segs.push(d);
        }
    }
    write_source(src, &p, &segs)
}

/// The lines of `out` that are not lines of `src` at the same place,
/// with the inserted lines (`inserted`, 1-based positions in `out`) left
/// out; every other line must be byte-identical, line end included.
fn changed_lines(src: &str, out: &str, inserted: &[usize]) -> Vec<(usize, String)> {
    let a: Vec<&str> = src.split_inclusive('\n').collect();
    let b: Vec<&str> = out
        .split_inclusive('\n')
        .enumerate()
        .filter(|(j, _)| !inserted.contains(&(j + 1)))
        .map(|(_, l)| l)
        .collect();
    assert_eq!(a.len(), b.len(), "{out}");
    a.iter()
        .zip(&b)
        .enumerate()
        .filter(|(_, (x, y))| x != y)
        .map(|(i, (_, y))| (i + 1, y.to_string()))
        .collect()
}

#[test]
fn leading_dot_inch_fanuc_crlf() {
    let src = "%\r\nO0001 (INCH PART)\r\nN10 G20 G90 G17\r\nN20 G0 X0. Y0.\r\nN30 G1 X-.75 Y.5 F20.\r\nN40 X-1.25 Y.5\r\nN50 X-3. Y-.967\r\nN60 G0 Z1.\r\nN70 M30\r\n%\r\n";
    // N40: X moved 0.5 thou; N50: Y moved 0.1 thou, X not; N30: a move
    // of 0.01 thou rounds away at 4 decimals and keeps its text.
    let out = edited(
        src,
        &ParseOptions::default(),
        &[(5, 0.00001, 0.0), (6, 0.0005, 0.0), (7, 0.0, -0.0001)],
        &[6],
    );
    assert_eq!(
        changed_lines(src, &out, &[7]),
        vec![
            (6, "N40 X-1.2495 Y.5\r\n".to_string()),
            (7, "N50 X-3. Y-.9671\r\n".to_string()),
        ]
    );
    // The dwell after N40: numbered N41, whole milliseconds, CRLF.
    assert_eq!(out.split_inclusive('\n').nth(6), Some("N41 G4 P100\r\n"));
    assert_eq!(out.matches('\n').count(), out.matches("\r\n").count());
    // A moved number at ±3 (an integer) keeps its trailing dot.
    let out = edited(src, &ParseOptions::default(), &[(7, 0.0, 0.967)], &[]);
    assert_eq!(
        changed_lines(src, &out, &[]),
        vec![(7, "N50 X-3. Y0.\r\n".to_string())]
    );
    let out = edited(src, &ParseOptions::default(), &[(6, -1.75, 0.0)], &[]);
    assert_eq!(
        changed_lines(src, &out, &[]),
        vec![(6, "N40 X-3. Y.5\r\n".to_string())]
    );
}

#[test]
fn fixed_three_decimals_inch_and_mm() {
    // Inch, 3 decimals padded, leading dot: padded to 3, up to 4.
    let src = "G20 G90\nG0 X0.000 Y0.000\nG1 X-.750 Y-.500 F20.\nX-1.250 Y-.500\nM30\n";
    let out = edited(
        src,
        &ParseOptions::default(),
        &[(3, -0.001, 0.0), (4, 0.00012, 0.5)],
        &[],
    );
    assert_eq!(
        changed_lines(src, &out, &[]),
        vec![
            (3, "G1 X-.751 Y-.500 F20.\n".to_string()),
            (4, "X-1.2499 Y0.000\n".to_string()),
        ]
    );
    // mm, 3 decimals padded with a leading zero; a move that rounds away
    // at 3 decimals (0.4 µm) keeps the number's text.
    let src = "G21 G90\nG0 X0.000 Y0.000\nG1 X10.000 Y-3.500 F600.\nX25.250 Y-3.500\nX25.250 Y0.750\nM30\n";
    let out = edited(
        src,
        &ParseOptions::default(),
        &[(4, 0.0004, -0.002), (5, 0.0, -1.0)],
        &[],
    );
    assert_eq!(
        changed_lines(src, &out, &[]),
        vec![
            (4, "X25.250 Y-3.502\n".to_string()),
            (5, "X25.250 Y-0.250\n".to_string()),
        ]
    );
}

#[test]
fn fixed_four_decimals_one_kept_decimal_and_a_block_of_its_own() {
    let src = "G21\nG0 X0.0000 Y0.0000\nG1 X12.5000 Y0.2500 F500.\nX20.0000 Y0.2500\nM30\n";
    let out = edited(
        src,
        &ParseOptions::default(),
        &[(3, 0.0123, 0.0), (4, 0.0, -0.25)],
        &[],
    );
    assert_eq!(
        changed_lines(src, &out, &[]),
        vec![
            (3, "G1 X12.5123 Y0.2500 F500.\n".to_string()),
            (4, "X20.0000 Y0.0000\n".to_string()),
        ]
    );
    // A post that keeps one decimal (Y-3.0) and trims the rest.
    let src = "G21\nG0 X0.0 Y0.0\nG1 X1.5 Y-3.0 F500.\nX2.25 Y-3.0\nM30\n";
    let out = edited(
        src,
        &ParseOptions::default(),
        &[(3, 0.25, -1.0), (4, 0.0012, 0.0)],
        &[],
    );
    assert_eq!(
        changed_lines(src, &out, &[]),
        vec![
            (3, "G1 X1.75 Y-4.0 F500.\n".to_string()),
            (4, "X2.251 Y-3.0\n".to_string()),
        ]
    );
    // A block with fixed decimals of its own in a program that trims.
    let src = "G21\nG0 X0 Y0\nG1 X1.5 Y2.125 F500\nX2.50 Y3.00\nX4.25 Y3.5\nM30\n";
    let out = edited(
        src,
        &ParseOptions::default(),
        &[(4, 0.5, 0.0), (5, -0.25, 0.0)],
        &[],
    );
    assert_eq!(
        changed_lines(src, &out, &[]),
        vec![
            (4, "X3.00 Y3.00\n".to_string()),
            (5, "X4 Y3.5\n".to_string())
        ]
    );
}

#[test]
fn dwells_take_the_dialects_safe_form() {
    // (program, dwell line expected, the reading of the control it is for)
    let cases: [(&str, &str, DwellP); 6] = [
        // Fanuc/Haas, no G4 of its own: whole milliseconds.
        (
            "G0 X0 Y0\nG1 X10. F600.\nG1 Y10.\n",
            "G4 P100",
            DwellP::Milliseconds,
        ),
        (
            "G00 X0 Y0\nG01 X10. F600.\nG01 Y10.\n",
            "G04 P100",
            DwellP::Milliseconds,
        ),
        // Its own G04 X form: seconds with a point.
        (
            "G0 X0 Y0\nG04 X0.5\nG1 X10. F600.\nG1 Y10.\n",
            "G04 X0.1",
            DwellP::Milliseconds,
        ),
        // Haas P with a point: seconds, as the program writes them.
        (
            "G0 X0 Y0\nG4 P1.5\nG1 X10. F600.\nG1 Y10.\n",
            "G4 P0.1",
            DwellP::Auto,
        ),
        // LinuxCNC (G64 P): seconds with a point, even beside its own
        // `G4 P2` (read as 2 s by LinuxCNC, which a copy `P100` would
        // turn into 100 s).
        (
            "G21 G64 P0.01\nG0 X0 Y0\nG4 P2\nG1 X10 F600\nG1 Y10\n",
            "G4 P0.1",
            DwellP::Seconds,
        ),
        (
            "g0 x0 y0\ng1 x10 f600 (msg, cutting)\ng1 y10\n",
            "g4 p0.1",
            DwellP::Seconds,
        ),
    ];
    for (src, want, reading) in cases {
        let n = src
            .lines()
            .position(|l| l.to_ascii_uppercase().contains("X10"))
            .unwrap()
            + 1;
        let out = edited(src, &ParseOptions::default(), &[], &[n]);
        let new: Vec<&str> = out
            .lines()
            .filter(|l| !src.lines().any(|s| s == *l))
            .collect();
        assert_eq!(new, vec![want], "{src}");
        // Read back as 0.1 s by the control's own reading and by auto.
        for d in [reading, DwellP::Auto] {
            let opts = ParseOptions {
                dwell_p: d,
                ..ParseOptions::default()
            };
            let q = parse_with(&out, &opts).unwrap();
            let s = q.segments.iter().find(|s| s.line == n + 1).unwrap();
            assert_eq!(
                s.motion,
                Motion::Dwell { seconds: 0.1 },
                "{src} under {d:?}"
            );
        }
    }
    // dwellP 'seconds' (a LinuxCNC or Grbl machine) without another sign.
    let src = "G0 X0 Y0\nG1 X10 F600\nG1 Y10\n";
    let opts = ParseOptions {
        dwell_p: DwellP::Seconds,
        ..ParseOptions::default()
    };
    let out = edited(src, &opts, &[], &[2]);
    assert!(out.contains("\nG4 P0.1\n"), "{out}");
}

/// The compensation of a generated inch program in the Fanuc style keeps
/// it: its moved numbers have no leading zero and at most 4 decimals, its
/// zeros stay `0.`, and every line it did not move is byte-identical.
#[test]
fn a_compensated_fanuc_inch_program_keeps_its_style() {
    // A rounded rectangle, 2 x 1 in, corner radius .25 in, at 60 in/min.
    let src =
        "%\r\nO0002 (POCKET)\r\nN10 G20 G90 G17\r\nN20 G0 X.25 Y0. Z.1\r\nN30 G1 Z-.05 F20.\r\n\
N40 X1.75 F60.\r\nN50 G3 X2. Y.25 R.25\r\nN60 G1 Y.75\r\nN70 G3 X1.75 Y1. R.25\r\n\
N80 G1 X.25\r\nN90 G3 X0. Y.75 R.25\r\nN100 G1 Y.25\r\nN110 G3 X.25 Y0. R.25\r\n\
N120 G0 Z1.\r\nN130 M30\r\n%\r\n";
    let c = reverse_compensate(src, &ReverseConfig::default()).unwrap();
    assert!(c.unchanged.is_none(), "{:?}", c.regions);
    assert!(c.after.max_error_um < c.before.max_error_um);
    assert!(
        check_unmoved_bytes("generated Fanuc inch", src, &c.nc).0 >= 4,
        "{}",
        c.nc
    );
    let new: Vec<&str> =
        c.nc.lines()
            .filter(|l| !src.lines().any(|s| s == *l))
            .collect();
    for l in &new {
        for w in numbers(l) {
            let digits = w.trim_start_matches('-');
            assert!(!digits.starts_with("0.") || digits == "0.", "{l}");
            assert!(digits.split('.').nth(1).is_none_or(|d| d.len() <= 4), "{l}");
            assert!(digits.contains('.'), "{l}");
        }
    }
}

/// The numbers of the X Y Z I J K R words of `line`.
fn numbers(line: &str) -> Vec<String> {
    tokens(line)
        .into_iter()
        .filter(|t| is_coordinate(t))
        .map(|t| t[1..].to_string())
        .collect()
}

/// The tokens of `line`: each address word (letter and number), each
/// `( … )` comment, the `;` comment with the line end, and each other
/// character.
fn tokens(line: &str) -> Vec<String> {
    let c: Vec<char> = line.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let mut j = i + 1;
        if c[i].is_ascii_alphabetic() {
            while j < c.len() && (c[j].is_ascii_digit() || matches!(c[j], '.' | '-' | '+')) {
                j += 1;
            }
        } else if c[i] == '(' {
            while j < c.len() && c[j - 1] != ')' {
                j += 1;
            }
        } else if c[i] == ';' {
            j = c.len();
        }
        out.push(c[i..j].iter().collect());
        i = j;
    }
    out
}

fn is_coordinate(t: &str) -> bool {
    t.len() > 1 && t.starts_with(|c: char| "XYZIJKR".contains(c.to_ascii_uppercase()))
}

fn is_motion(t: &str) -> bool {
    let u = t.to_ascii_uppercase();
    ["G0", "G1", "G2", "G3", "G00", "G01", "G02", "G03"].contains(&u.as_str())
}

/// Whether `new` is `old` with some coordinate numbers replaced by other
/// values, and coordinate words or a motion code inserted (each with at
/// most one space), or an arc turned into a line (`G1`, centre words
/// dropped), and nothing else: every other word, comment and the line end
/// the same and in the same order.
fn same_but_numbers(old: &str, new: &str) -> bool {
    let (a, b) = (tokens(old), tokens(new));
    let skeleton = |t: &[String]| -> Vec<String> {
        t.iter()
            .filter(|x| !is_coordinate(x) && x.as_str() != " ")
            .cloned()
            .collect()
    };
    let (sa, mut sb) = (skeleton(&a), skeleton(&b));
    let mut inserted = 0;
    let mut became_line = false;
    if sa != sb {
        // A motion code written on a block that relied on a modal one, or
        // changed (an arc that became a line).
        let Some(k) = (0..sb.len()).find(|&k| is_motion(&sb[k]) && sa.get(k) != Some(&sb[k]))
        else {
            return false;
        };
        became_line = matches!(sb[k].to_ascii_uppercase().as_str(), "G1" | "G01");
        if sa.len() == sb.len() && is_motion(&sa[k]) {
            sb[k] = sa[k].clone();
        } else {
            sb.remove(k);
            inserted += 1;
        }
        if sa != sb {
            return false;
        }
    }
    let coords =
        |t: &[String]| -> Vec<String> { t.iter().filter(|x| is_coordinate(x)).cloned().collect() };
    let (ca, cb) = (coords(&a), coords(&b));
    let mut j = 0;
    for w in &ca {
        let centre = matches!(w[..1].to_ascii_uppercase().as_str(), "R" | "I" | "J" | "K");
        if became_line && centre {
            // an arc's centre word, dropped with its arc
            continue;
        }
        while j < cb.len() && cb[j][..1] != w[..1] {
            j += 1;
            inserted += 1;
        }
        let Some(v) = cb.get(j) else { return false };
        if v != w && v[1..].parse::<f64>().ok() == w[1..].parse::<f64>().ok() {
            return false; // rewritten with the same value
        }
        j += 1;
    }
    inserted += cb.len() - j;
    let spaces = |t: &[String]| t.iter().filter(|x| x.as_str() == " ").count();
    (spaces(&a)..=spaces(&a) + inserted).contains(&spaces(&b))
}

/// Aligns `src` and `out` line by line (line ends included): each source
/// line is in `out`, in order, byte for byte or changed in place with only
/// some of its coordinate numbers replaced ([`same_but_numbers`]), and
/// every other line of `out` is an inserted `G1`/`G4` line with the
/// program's line end. (The alignment is searched over all of them, so a
/// run of look-alike lines cannot mislead it.) Returns the lines changed
/// in place and the lines inserted.
fn check_unmoved_bytes(name: &str, src: &str, out: &str) -> (usize, usize) {
    let a: Vec<&str> = src.split_inclusive('\n').collect();
    let b: Vec<&str> = out.split_inclusive('\n').collect();
    let (n, m) = (a.len(), b.len());
    assert!(m >= n, "{name}: lines lost");
    let extra = m - n;
    let end = if src.contains("\r\n") { "\r\n" } else { "\n" };
    let insertable = |l: &str| {
        let t = l.trim_start().to_ascii_uppercase();
        let t = t
            .trim_start_matches(|c: char| c == 'N' || c.is_ascii_digit())
            .trim_start();
        ["G1", "G01", "G4", "G04"].iter().any(|g| t.starts_with(g)) && l.ends_with(end)
    };
    let fits = |i: usize, j: usize| a[i] == b[j] || same_but_numbers(a[i], b[j]);
    // can[i][d]: a[i..] aligns with b[i + d..].
    let mut can = vec![vec![false; extra + 1]; n + 1];
    can[n][extra] = true;
    for d in (0..extra).rev() {
        can[n][d] = can[n][d + 1] && insertable(b[n + d]);
    }
    for i in (0..n).rev() {
        for d in (0..=extra).rev() {
            can[i][d] = (fits(i, i + d) && can[i + 1][d])
                || (d < extra && insertable(b[i + d]) && can[i][d + 1]);
        }
    }
    if !can[0][0] {
        // The first source line that cannot be placed, for the message.
        let i = (0..n)
            .find(|&i| !(0..=extra).any(|d| can[i][d]))
            .unwrap_or(0);
        panic!(
            "{name}: line {} {:?} has no counterpart in the output",
            i + 1,
            a[i]
        );
    }
    let (mut i, mut d, mut changed) = (0, 0, 0);
    while i < n {
        if fits(i, i + d) && can[i + 1][d] {
            changed += usize::from(a[i] != b[i + d]);
            i += 1;
        } else {
            d += 1;
        }
    }
    (changed, extra)
}

/// Compensates each corpus program of `names`: one that changes keeps its
/// unmoved lines and numbers byte for byte and its line ends, and reads
/// back; one left unchanged comes back as the same bytes. Returns how many
/// changed.
fn keeps_unmoved_bytes(names: &[&str]) -> usize {
    let mut changed_programs = 0;
    for name in names {
        let src = corpus::read(name);
        let c = reverse_compensate(&src, &ReverseConfig::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        if c.unchanged.is_some() {
            assert_eq!(c.nc, src, "{name}");
            continue;
        }
        let (n, new) = check_unmoved_bytes(name, &src, &c.nc);
        assert!(n + new > 0, "{name}: changed but no line differs");
        changed_programs += 1;
        corpus::say(&format!(
            "{name}: {n} lines changed in place, {new} inserted, of {}",
            src.lines().count()
        ));
        if src.contains("\r\n") {
            assert_eq!(
                c.nc.matches('\n').count(),
                c.nc.matches("\r\n").count(),
                "{name}"
            );
        }
        assert!(parse(&c.nc).is_ok(), "{name}");
    }
    changed_programs
}

/// The small corpus programs that compensate (CRLF: gcws_HAAS).
#[test]
fn corpus_programs_keep_every_unmoved_byte() {
    if corpus::available("corpus_programs_keep_every_unmoved_byte").is_none() {
        return;
    }
    let n = keeps_unmoved_bytes(&[
        "cncjs_arc-xz-plane.gcode",
        "cncjs_arc-yz-plane.gcode",
        "cncjs_circle-inch.gcode",
        "cncjs_helical-thread-milling.gcode",
        "gcws_FANUC0M.nc",
        "gcws_HAAS.nc",
        "ugs_arc_rword_test.gcode",
        "ugs_no_spaces.gcode",
    ]);
    assert_eq!(n, 8);
}

/// The larger ones (`cargo test --release --test reverse_output_style --
/// --ignored`): LinuxCNC programs, CRLF files left unchanged (Pasta,
/// Gates), the Fusion 360 program.
#[test]
#[ignore = "larger programs: run with --release --ignored"]
fn larger_corpus_programs_keep_every_unmoved_byte() {
    if corpus::available("larger_corpus_programs_keep_every_unmoved_byte").is_none() {
        return;
    }
    let n = keeps_unmoved_bytes(&[
        "linuxcnc_comp.ngc",
        "linuxcnc_arcspiral.ngc",
        "linuxcnc_cds.ngc",
        "linuxcnc_tort.ngc",
        "linuxcnc_Pasta.ngc",
        "ugs_Gates_combined_R12.nc",
        "cncsprayer_fusion-output.nc",
        "ledfloor_1003.nc",
    ]);
    assert!(n >= 5, "{n}");
}
