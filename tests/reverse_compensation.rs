//! Proves the reverse compensation of qiu §4-3(2) on the built-in examples:
//! on the arc example the maximum error against the ORIGINAL path falls by
//! at least 60 % (paper: 63.1 → 18.2 µm, −71 %) while the motion time grows
//! by at most 5 % (paper: +3.9 %); the corrected program keeps the
//! original's N numbers and comments, parses, and its arcs keep their
//! centres; the line-only example improves by vertex shifting.

#[path = "support/corpus.rs"]
mod corpus;

use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
use mtmotion::nc::program::{parse, Motion};
use mtmotion::toolpath::example;

#[test]
fn arc_example_error_falls_by_60_percent_within_5_percent_time() {
    let src = example::arc_example();
    let c = reverse_compensate(&src, &ReverseConfig::default()).unwrap();
    println!(
        "arcs: {:?} -> {:?}, dwells {:?}, history {:?}",
        c.before, c.after, c.dwells, c.history_um
    );
    let cut = 1.0 - c.after.max_error_um / c.before.max_error_um;
    assert!(cut >= 0.60, "error cut {:.1} %", cut * 100.0);
    let grow = c.after.motion_time / c.before.motion_time - 1.0;
    assert!(grow <= 0.05, "time grows {:.1} %", grow * 100.0);
    assert!(c.nc != src && c.unchanged.is_none(), "{:?}", c.unchanged);
    // Line numbers and comments survive; centres are kept.
    for tag in ["N30 G1", "(B)", "(C)", "(D)", "(E)", "N470"] {
        assert!(c.nc.contains(tag), "{tag} missing");
    }
    let (p, q) = (parse(&src).unwrap(), parse(&c.nc).unwrap());
    let centres = |p: &mtmotion::nc::program::Program| -> Vec<[f64; 3]> {
        p.segments
            .iter()
            .filter_map(|s| {
                if let Motion::Arc(a) = s.motion {
                    Some(a.center)
                } else {
                    None
                }
            })
            .collect()
    };
    let (a, b) = (centres(&p), centres(&q));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x[0] - y[0]).abs() < 2e-4 && (x[1] - y[1]).abs() < 2e-4);
    }
    // Radii grew where the arcs lost radius, except next to a corner
    // spike (the short arcs of B and D), which pulls the path out itself.
    let near_spike = |l: usize| {
        c.spikes
            .iter()
            .any(|s| s.after_line + 1 >= l && s.after_line <= l + 1)
    };
    assert!(!c.spikes.is_empty());
    assert!(c
        .segments
        .iter()
        .filter(|s| s.kind == "arc" && !near_spike(s.line))
        .all(|s| s.radius_after > s.radius_before - 1e-3));
}

#[test]
fn line_example_improves_by_vertex_shifting() {
    let c = reverse_compensate(&example::line_example(), &ReverseConfig::default()).unwrap();
    println!(
        "lines: {:?} -> {:?}, dwells {:?}, history {:?}",
        c.before, c.after, c.dwells, c.history_um
    );
    assert!(c.after.max_error_um < 0.7 * c.before.max_error_um);
    assert!(c.segments.iter().any(|s| s.end_shift_um > 1.0));
}

// ---- Safety on real programs -------------------------------------------

use mtmotion::compensate::reverse::RegionNote;
use mtmotion::nc::patch::write_source;

/// The planar chord of an arc (start to end in its plane), mm.
fn chord(s: &mtmotion::nc::program::Segment) -> f64 {
    let Motion::Arc(a) = s.motion else {
        return f64::NAN;
    };
    let (u, v, _) = a.plane.axes();
    let (p, q) = (s.start.p(), s.end.p());
    (p[u] - q[u]).hypot(p[v] - q[v])
}

/// A 360° helix in G19 (and G17, G18) written with a radius that does not
/// round evenly stays a full circle: chord < 1e-9 mm, sweep ±2π.
#[test]
fn full_circle_helices_stay_full_in_every_plane() {
    for (plane, start, lead, helix) in [
        (
            "G17",
            "X10 Y0 Z0",
            "G1 X10.5 F500",
            "G2 X10.5 Z-2. I-10.5 J0 F1500",
        ),
        (
            "G18",
            "X10 Y0 Z0",
            "G1 X10.5 F500",
            "G2 X10.5 Y-2. I-10.5 K0 F1500",
        ),
        (
            "G19",
            "X0 Y10 Z0",
            "G1 Y10.5 F500",
            "G2 Y10.5 X-2. J-10.5 K0 F1500",
        ),
    ] {
        let src = format!("G21 G90 {plane}\nG0 {start}\n{lead}\n{helix}\n");
        let p = parse(&src).unwrap();
        let mut segs = p.segments.clone();
        let Motion::Arc(mut a) = segs[2].motion else {
            panic!("{plane}: no arc")
        };
        let r = 10.500_37;
        let (u, v, n) = a.plane.axes();
        let mut st = segs[2].start.to_array();
        st[u] = a.center[u] + (st[u] - a.center[u]) * r / a.radius;
        st[v] = a.center[v] + (st[v] - a.center[v]) * r / a.radius;
        let mut en = st;
        en[n] = segs[2].end.get(n);
        a.radius = r;
        segs[2].motion = Motion::Arc(a);
        segs[2].start = mtmotion::nc::program::Pose::from_array(st);
        segs[2].end = mtmotion::nc::program::Pose::from_array(en);
        segs[1].end = segs[2].start;
        let text = write_source(&src, &p, &segs);
        let q = parse(&text).unwrap_or_else(|e| panic!("{plane}: {e}\n{text}"));
        let arc = q
            .segments
            .iter()
            .find(|s| matches!(s.motion, Motion::Arc(_)))
            .unwrap();
        let Motion::Arc(b) = arc.motion else {
            unreachable!()
        };
        assert!(
            chord(arc) < 1e-9,
            "{plane}: chord {} in\n{text}",
            chord(arc)
        );
        assert!(
            (b.sweep.abs() - std::f64::consts::TAU).abs() < 1e-9,
            "{plane}: sweep {}",
            b.sweep
        );
        assert!((b.radius - r).abs() < 1e-3, "{plane}: radius {}", b.radius);
        assert!(
            (arc.end.get(n) - (-2.0)).abs() < 1e-12,
            "{plane}: helix rise lost"
        );
    }
}

/// The compensation of a G19 helix program: every full circle of the
/// original is a full circle in the result (chord < 1e-9 mm).
#[test]
fn compensated_g19_helix_keeps_its_full_turns() {
    let src = "G21 G90 G19\nG0 X0 Y10 Z0\nG1 X-0.5 F600\nG3 X-2.5 J-10. K0 F3000\nG3 X-4.5 J-10. K0\nG3 X-6.5 J-10. K0\nG0 X10\n";
    let c = reverse_compensate(src, &ReverseConfig::default()).unwrap();
    let q = parse(&c.nc).unwrap();
    let arcs: Vec<_> = q
        .segments
        .iter()
        .filter(|s| matches!(s.motion, Motion::Arc(_)))
        .collect();
    assert_eq!(arcs.len(), 3, "{}", c.nc);
    for s in arcs {
        assert!(chord(s) < 1e-9, "chord {} in\n{}", chord(s), c.nc);
    }
    assert!(c.after.max_error_um <= c.before.max_error_um);
}

/// A `;` comment with parentheses in it survives byte for byte and the
/// result reads back.
#[test]
fn semicolon_comments_with_parentheses_survive() {
    let src = "G21 G90 G17 ; setup (metric)\nG0 X0 Y0\nG1 X10 F2000 ; in (fast)\nG3 X10 Y10 I0 J5 ; arc (top) ((x))\nG1 X0 ; out\n";
    let c = reverse_compensate(src, &ReverseConfig::default()).unwrap();
    parse(&c.nc).unwrap();
    for tag in [
        "; setup (metric)",
        "; in (fast)",
        "; arc (top) ((x))",
        "; out",
    ] {
        assert!(c.nc.contains(tag), "{tag} lost in\n{}", c.nc);
    }
}

/// Fixed segments (a subprogram body called twice) never move in place,
/// and the result is never worse than the original (`expand: false`; the
/// flat form is tests/reverse_expand.rs's).
#[test]
fn fixed_segments_never_move() {
    let src = "G21 G90 G17\nG0 X0 Y0\nG1 X20 F3000\nG3 X20 Y20 I0 J10\nM98 P100 L2\nG1 X0 Y20\nM30\nO100\nG91 G1 X-2 Y1\nG1 X-2 Y-1\nG90\nM99\n";
    let p = parse(src).unwrap();
    let in_place = ReverseConfig {
        expand: false,
        ..ReverseConfig::default()
    };
    let c = reverse_compensate(src, &in_place).unwrap();
    let q = parse(&c.nc).unwrap();
    let fixed = |p: &mtmotion::nc::program::Program| -> Vec<[f64; 3]> {
        p.segments
            .iter()
            .filter(|s| s.fixed)
            .map(|s| s.end.p())
            .collect()
    };
    let (a, b) = (fixed(&p), fixed(&q));
    assert!(!a.is_empty());
    assert_eq!(a, b, "fixed end points moved:\n{}", c.nc);
    assert!(c.after.max_error_um <= c.before.max_error_um);
}

/// The time budget holds: with a zero budget no dwell may be added, and
/// the motion time does not grow beyond one sample.
#[test]
fn time_budget_is_kept() {
    let src = example::arc_example();
    let cfg = ReverseConfig {
        time_budget: 0.0,
        ..ReverseConfig::default()
    };
    let c = reverse_compensate(&src, &cfg).unwrap();
    assert!(c.dwells.is_empty(), "{:?}", c.dwells);
    assert!(c.after.motion_time <= c.before.motion_time + cfg.sim.dt);
    let d = reverse_compensate(&src, &ReverseConfig::default()).unwrap();
    assert!(d.after.motion_time <= 1.05 * d.before.motion_time + d.after.motion_time * 0.0);
    let bad = ReverseConfig {
        time_budget: -0.1,
        ..ReverseConfig::default()
    };
    let e = reverse_compensate(&src, &bad).unwrap_err().to_string();
    assert!(e.contains("timeBudget"), "{e}");
}

/// A region whose error cannot fall is left unchanged, with its reason.
#[test]
fn unchanged_regions_say_why() {
    // One line between two rapids: nothing to move.
    let src =
        "G21 G90\nG0 X0 Y0\nG1 X10 F3000\nG0 Z5\nG0 X20\nG1 X30 Y5 F3000\nG1 X40 Y0\nG0 Z10\n";
    let c = reverse_compensate(src, &ReverseConfig::default()).unwrap();
    assert!(c.after.max_error_um <= c.before.max_error_um);
    // Nothing changed: the text is returned byte for byte and the result
    // says so, naming the worst region's lines and reason.
    if c.nc == src {
        let why = c.unchanged.as_deref().unwrap();
        assert!(why.starts_with("nothing in the program changed"), "{why}");
        assert!(why.contains("lines "), "{why}");
    } else {
        assert!(c.unchanged.is_none());
    }
    let notes: &[RegionNote] = &c.regions;
    assert_eq!(notes.len(), 2, "{notes:?}");
    assert!(notes[0].reason.contains("no corner"), "{notes:?}");
    for n in notes {
        assert!(n.changed || !n.reason.is_empty(), "{n:?}");
        assert!(n.after_um <= n.before_um + 1e-9 || !n.changed, "{n:?}");
    }
}

/// Only the lines whose words moved change: a line diff of a lowercase,
/// unspaced inch program and of a CRLF program shows nothing else, and
/// inch stays inch (feeds untouched).
#[test]
fn a_line_diff_shows_only_the_compensation() {
    let crlf = example::arc_example().replace('\n', "\r\n");
    let comp = corpus::text("linuxcnc_comp.ngc").map(|t| ("comp", t));
    for (name, src) in comp.into_iter().chain([("arcs CRLF", crlf)]) {
        let c = reverse_compensate(&src, &ReverseConfig::default()).unwrap();
        let p = parse(&src).unwrap();
        let moved: std::collections::BTreeSet<usize> = c
            .segments
            .iter()
            .filter(|s| s.end_shift_um > 0.0 || s.radius_after != s.radius_before)
            .flat_map(|s| [s.line, s.line + 1])
            .collect();
        let (a, b): (Vec<&str>, Vec<&str>) = (
            src.split_inclusive('\n').collect(),
            c.nc.split_inclusive('\n').collect(),
        );
        let mut j = 0;
        let mut changed = 0;
        for (i, line) in a.iter().enumerate() {
            // Inserted lines (connecting G1, dwells) are new lines.
            while j < b.len() && b[j] != *line && !moved.contains(&(i + 1)) {
                let t = b[j].trim_start().to_ascii_uppercase();
                assert!(
                    t.starts_with("G1")
                        || t.starts_with("G01")
                        || t.starts_with("G4")
                        || t.starts_with("G04"),
                    "{name}: unexpected new line {:?}",
                    b[j]
                );
                j += 1;
            }
            if j < b.len() && b[j] != *line {
                assert!(
                    moved.contains(&(i + 1)),
                    "{name}: line {} changed without a move: {:?} -> {:?}",
                    i + 1,
                    line,
                    b[j]
                );
                changed += 1;
            }
            j += 1;
            if j < b.len() && moved.contains(&(i + 1)) {
                while j < b.len()
                    && i + 1 < a.len()
                    && b[j] != a[i + 1]
                    && !moved.contains(&(i + 2))
                {
                    j += 1;
                }
            }
        }
        println!("{name}: {changed} changed lines of {}", a.len());
        if src.contains("\r\n") {
            assert_eq!(
                c.nc.matches('\n').count(),
                c.nc.matches("\r\n").count(),
                "{name}: line endings"
            );
        }
        assert_eq!(
            p.modal.iter().any(|m| m.inch),
            parse(&c.nc).unwrap().modal.iter().any(|m| m.inch)
        );
        let feeds = |t: &str| t.to_ascii_uppercase().matches('F').count();
        assert!(feeds(&c.nc) >= feeds(&src), "{name}: feeds lost");
    }
}

/// New lines of a program that numbers its blocks get N numbers of their
/// own between their neighbours' (zero-padded like them), so a diff shows
/// numbered lines as the original has; where the numbers leave no room
/// (N1 then N2), or the program does not number its blocks, new lines
/// have none.
#[test]
fn new_lines_are_numbered_like_the_program() {
    let with_dwells = |src: &str, after: &[usize]| {
        let p = parse(src).unwrap();
        let mut segs = Vec::new();
        for (k, s) in p.segments.iter().enumerate() {
            segs.push(s.clone());
            if after.contains(&k) {
                let mut d = s.clone();
                d.block = None;
                d.start = s.end;
                d.motion = Motion::Dwell { seconds: 0.1 };
                segs.push(d);
            }
        }
        write_source(src, &p, &segs)
    };
    assert_eq!(
        with_dwells("N10 G0 X0 Y0\nN20 G1 X10 F600\nN30 G1 Y10\n", &[1]),
        "N10 G0 X0 Y0\nN20 G1 X10 F600\nN21 G4 P100\nN30 G1 Y10\n"
    );
    assert_eq!(
        with_dwells("N0010 G0 X0 Y0\nN0020 G1 X10 F600\nN0030 G1 Y10\n", &[1, 2]),
        "N0010 G0 X0 Y0\nN0020 G1 X10 F600\nN0021 G4 P100\nN0030 G1 Y10\nN0031 G4 P100\n"
    );
    assert_eq!(
        with_dwells("N1 G0 X0 Y0\nN2 G1 X10 F600\nN3 G1 Y10\n", &[1]),
        "N1 G0 X0 Y0\nN2 G1 X10 F600\nG4 P100\nN3 G1 Y10\n"
    );
    assert_eq!(
        with_dwells("G0 X0 Y0\nG1 X10 F600\nN30 G1 Y10\n", &[1]),
        "G0 X0 Y0\nG1 X10 F600\nG4 P100\nN30 G1 Y10\n"
    );
    // A reverse compensation of a numbered program: every line it adds is
    // numbered and the numbers still rise.
    let src = "N10 G21 G90 G17\nN20 G0 X0 Y0 Z1\nN30 G1 Z0 F2000\nN40 G1 X40 F3000\nN50 G1 Y40\nN60 G2 X60 Y20 I0 J-20\nN70 G1 X0 Y0\nN80 G0 Z10\nN90 M30\n";
    let c = reverse_compensate(src, &ReverseConfig::default()).unwrap();
    let ns: Vec<u64> =
        c.nc.lines()
            .map(|l| {
                l.strip_prefix('N')
                    .and_then(|r| r.split(' ').next()?.parse().ok())
                    .unwrap_or_else(|| panic!("unnumbered line {l:?} in\n{}", c.nc))
            })
            .collect();
    assert!(
        ns.len() > 9 && ns.windows(2).all(|w| w[0] < w[1]),
        "{}",
        c.nc
    );
}

/// A program none of whose cutting moves can be rewritten is returned as
/// it is with one note saying why, and no correction round is reported:
/// with macro variables (every word computed), and with every cut in a
/// subprogram body (`expand: false`: in place).
#[test]
fn a_program_with_nothing_to_move_says_why_as_a_whole() {
    let in_place = ReverseConfig {
        expand: false,
        ..ReverseConfig::default()
    };
    let macro_prog =
        "#1=20\n#2=0\nG0 X0 Y0 Z1\nG1 Z#2 F600\nG1 X#1 F2000\nG1 Y#1\nG1 X#2\nG1 Y[#1-20]\nG0 Z5\nM30\n";
    let sub_prog = "G0 X0 Y0 Z1\nM98 P100\nG0 Z5\nM30\nO100\nG1 Z0 F600\nG1 X20 F2000\nG1 Y20\nG1 X0\nG1 Y0\nM99\n";
    for (text, phrase, lines) in [
        (macro_prog, "macro variables or expressions", (4, 8)),
        (sub_prog, "subprogram or macro bodies", (6, 10)),
    ] {
        let c = reverse_compensate(text, &in_place).unwrap();
        assert_eq!(c.nc, text);
        let why = c.unchanged.as_deref().unwrap();
        assert!(
            why.starts_with("nothing in the program changed") && why.contains(phrase),
            "{why}"
        );
        assert!(c.before.max_error_um > 1.0, "{}", c.before.max_error_um);
        assert_eq!(c.after.max_error_um, c.before.max_error_um);
        assert!(c.history_um.is_empty(), "{:?}", c.history_um);
        assert_eq!(c.regions.len(), 1, "{:?}", c.regions);
        let n = &c.regions[0];
        assert!(!n.changed);
        assert_eq!((n.first_line, n.last_line), lines);
        assert_eq!((n.arcs, n.lines), (0, 5));
        assert_eq!(n.before_um, c.before.max_error_um);
        assert!(
            n.reason.starts_with("no cutting move can be rewritten: "),
            "{}",
            n.reason
        );
        assert!(n.reason.contains(phrase), "{}", n.reason);
    }
}
