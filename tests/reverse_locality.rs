//! Reverse compensation simulates only around the places it corrects
//! (`toolpath::locality`, issue 27 item 1), and that is exact: on two
//! team-written programs with many corners — a raster without rapids
//! (one region, cut into chunks) and a pocket with rapids between its
//! contours, both asymmetric (pass lengths, step-overs, feeds and an arc
//! vary) — the windows' per-segment statistics of an edited program equal
//! a whole-program simulation of the same edited program within 0.1 µm
//! (maximum error and mean deviation per segment), a window's cost does
//! not grow with the program's length, and the compensated program's
//! reported after-error equals a whole-program re-simulation of the
//! written program against the original path within 0.1 µm.

use mtmotion::compensate::reverse::geometry::rebuild_indexed;
use mtmotion::compensate::reverse::rounds::identity;
use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
use mtmotion::nc::patch::write_source;
use mtmotion::nc::program::{parse, Motion, Segment};
use mtmotion::toolpath::contour::Path;
use mtmotion::toolpath::locality::{plan, plan_capped, simulate_window, MAX_CORE};
use mtmotion::toolpath::{simulate, simulate_stats, Lag, SimConfig};

/// A zigzag raster of `passes` passes in one cut (no rapid after the
/// plunge): pass lengths, step-overs and feeds vary, every fifth turn is
/// a diagonal step and one turn is an arc.
fn raster(passes: usize) -> String {
    let mut s = String::from("G21 G90 G17\nG0 X0 Y0 Z1\nG1 Z0 F400\n");
    let mut y = 0.0;
    for j in 0..passes {
        let x = if j % 2 == 0 {
            20.0 + 3.0 * (j % 5) as f64 + 0.7 * j as f64
        } else {
            1.5 * (j % 3) as f64
        };
        let f = 1200 + 300 * (j % 3);
        s += &format!("G1 X{x:.3} Y{y:.3} F{f}\n");
        let step = 0.8 + 0.15 * (j % 4) as f64;
        if j == 3 {
            // A half-circle turn to the next pass.
            s += &format!("G3 X{x:.3} Y{:.3} R{:.3}\n", y + step, 0.5 * step);
        } else if j % 5 == 4 {
            s += &format!("G1 X{:.3} Y{:.3}\n", x + 0.6, y + step);
        } else {
            s += &format!("G1 Y{:.3}\n", y + step);
        }
        y += step;
    }
    s + "G0 Z5\n"
}

/// Four closed contours (a rectangle, a pentagon, an L and a rectangle
/// with a rounded corner), each entered by a rapid and a plunge.
fn pocket() -> String {
    let mut s = String::from("G21 G90 G17\n");
    let shapes: [&[(f64, f64)]; 3] = [
        &[
            (0.0, 0.0),
            (30.0, 0.0),
            (30.0, 12.0),
            (0.0, 12.0),
            (0.0, 0.0),
        ],
        &[
            (40.0, 0.0),
            (52.0, 2.0),
            (55.0, 11.0),
            (46.0, 17.0),
            (38.0, 9.0),
            (40.0, 0.0),
        ],
        &[
            (0.0, 20.0),
            (25.0, 20.0),
            (25.0, 24.0),
            (6.0, 24.0),
            (6.0, 38.0),
            (0.0, 38.0),
            (0.0, 20.0),
        ],
    ];
    for (k, pts) in shapes.iter().enumerate() {
        let (x0, y0) = pts[0];
        s += &format!("G0 Z2\nG0 X{x0} Y{y0}\nG1 Z-1 F300\n");
        for &(x, y) in &pts[1..] {
            s += &format!("G1 X{x} Y{y} F{}\n", 1500 + 500 * k);
        }
    }
    s += "G0 Z2\nG0 X30 Y30\nG1 Z-1 F300\nG1 X50 F1800\nG1 Y40\nG3 X46 Y44 R4\nG1 X30\nG1 Y30\nG0 Z5\n";
    s
}

fn cfg() -> SimConfig {
    SimConfig {
        t_a: 0.04,
        t: Lag::PerAxis([0.015, 0.012, 0.02]),
        dt: 1e-3,
        ..SimConfig::default()
    }
}

/// An edit of `orig`: vertex shifts at every `every`-th line–line joint
/// (varying), arcs grown by 5 µm, a dwell after segment 9.
fn edited(orig: &[Segment], every: usize) -> (Vec<Segment>, Vec<usize>, Vec<bool>) {
    let mut e = identity(orig, vec![0.0; orig.len()]);
    let lines = |i: usize| matches!(orig[i].motion, Motion::Linear);
    for i in 0..orig.len().saturating_sub(1) {
        if lines(i)
            && lines(i + 1)
            && orig[i].is_cutting()
            && orig[i + 1].is_cutting()
            && i % every == 1
        {
            let a = i as f64;
            e.vertex_shift[i] = [0.01 * (a * 0.7).sin(), 0.012 * (a * 1.3).cos(), 0.0];
        }
        if let Motion::Arc(a) = orig[i].motion {
            e.radius[i] = a.radius + 0.005;
        }
    }
    e.dwell_after[9] = 0.05;
    let (base, base_at) = rebuild_indexed(orig, &identity(orig, vec![0.0; orig.len()]));
    let (cmd, at) = rebuild_indexed(orig, &e);
    let piece = |c: &[Segment], at: &[usize], i: usize| {
        let a = if i == 0 { 0 } else { at[i] };
        c[a..at.get(i + 1).copied().unwrap_or(c.len())].to_vec()
    };
    let changed = (0..orig.len())
        .map(|i| piece(&cmd, &at, i) != piece(&base, &base_at, i))
        .collect();
    (cmd, at, changed)
}

/// Windows of the edited program against the whole-program simulation:
/// per core segment within 0.1 µm; returns (window samples, whole samples,
/// segments compared, largest difference µm).
fn compare(text: &str, every: usize) -> (usize, usize, usize, f64) {
    let ((samples, whole, compared, worst), windows) = compare_capped(text, every, MAX_CORE);
    assert!(windows > 1 && samples < whole, "{samples} of {whole}");
    (samples, whole, compared, worst)
}

/// As [`compare`] with at most `max_core` segments in a window's core;
/// also the number of windows.
fn compare_capped(
    text: &str,
    every: usize,
    max_core: usize,
) -> ((usize, usize, usize, f64), usize) {
    let p = parse(text).unwrap();
    let orig = &p.segments;
    let (cmd, at, changed) = edited(orig, every);
    let cfg = cfg();
    let whole = simulate_stats(&cmd, orig, &cfg).unwrap();
    let windows = plan_capped(&cmd, &at, &changed, &cfg, max_core).unwrap();
    assert!(!windows.is_empty());
    assert!(windows.iter().all(|w| w.core.len() <= max_core));
    // Cores in order, never overlapping.
    assert!(windows.windows(2).all(|p| p[0].core.end <= p[1].core.start));
    let path = Path::new(orig);
    let mut compared = 0;
    let mut worst: f64 = 0.0;
    let mut covered = vec![false; orig.len()];
    for w in &windows {
        for st in simulate_window(&cmd, (&path, orig), w, &cfg) {
            covered[st.segment] = true;
            // A rapid's statistics enter neither the maximum error nor a
            // correction; where a retract runs back along its plunge, the
            // samples of the two coincide and go to either.
            if !orig[st.segment].is_cutting() {
                continue;
            }
            let ws = whole
                .segments
                .iter()
                .find(|x| x.segment == st.segment)
                .unwrap();
            let d = (st.max_error_um - ws.max_error_um).abs();
            worst = worst.max(d);
            assert!(
                d < 0.1,
                "segment {} (line {}): window {} µm, whole {} µm",
                st.segment,
                st.line,
                st.max_error_um,
                ws.max_error_um
            );
            assert_eq!(st.samples, ws.samples, "segment {}", st.segment);
            if let (Some(a), Some(b)) = (st.mean_deviation, ws.mean_deviation) {
                assert!((a - b).abs() < 1e-4, "segment {}: {a} vs {b}", st.segment);
            }
            compared += 1;
        }
    }
    // Every changed segment with a length is in a window's core.
    for (i, s) in orig.iter().enumerate() {
        if changed[i] && s.length() > 0.0 {
            assert!(covered[i], "changed segment {i} not re-simulated");
        }
    }
    let samples = windows.iter().map(|w| w.samples).sum();
    ((samples, whole.samples, compared, worst), windows.len())
}

/// A stretch of changes longer than a window's core is cut into windows
/// of at most that many core segments, each restarted with its own
/// pre-roll: the statistics still equal the whole program's within
/// 0.1 µm (what keeps a correction round over the whole of a 1 M-segment
/// program from simulating it as one window).
#[test]
fn windows_cut_at_the_core_cap_equal_the_whole_program() {
    let text = raster(40);
    let ((_, _, n_all, _), w_all) = compare_capped(&text, 2, MAX_CORE);
    let ((_, _, n, worst), w) = compare_capped(&text, 2, 12);
    eprintln!(
        "cap 12: {w} windows (uncapped {w_all}), {n} segments compared, worst {worst:.2e} µm"
    );
    assert!(w > 3 * w_all, "{w} {w_all}");
    assert_eq!(n, n_all);
}

#[test]
fn windows_equal_the_whole_program_on_a_raster_without_rapids() {
    let (win, whole, n, worst) = compare(&raster(40), 17);
    eprintln!("raster: {n} segments compared, worst {worst:.2e} µm, {win} of {whole} samples");
    assert!(n > 15, "{n}");
}

#[test]
fn windows_equal_the_whole_program_on_a_pocket_with_rapids() {
    let (win, whole, n, worst) = compare(&pocket(), 7);
    eprintln!("pocket: {n} segments compared, worst {worst:.2e} µm, {win} of {whole} samples");
    assert!(n > 8, "{n}");
}

/// One changed vertex costs the same window in a raster of 10 passes as
/// in one of 60: the cost grows with the corrected places, not the length.
#[test]
fn a_windows_cost_does_not_grow_with_the_program() {
    let cost = |passes: usize| {
        let p = parse(&raster(passes)).unwrap();
        let orig = &p.segments;
        let mut e = identity(orig, vec![0.0; orig.len()]);
        e.vertex_shift[8] = [0.02, 0.0, 0.0];
        let (cmd, at) = rebuild_indexed(orig, &e);
        let mut changed = vec![false; orig.len()];
        changed[8] = true;
        changed[9] = true;
        let w = plan(&cmd, &at, &changed, &cfg()).unwrap();
        let whole = simulate_stats(&cmd, orig, &cfg()).unwrap().samples;
        (w.iter().map(|w| w.samples).sum::<usize>(), whole)
    };
    let (short, short_whole) = cost(10);
    let (long, long_whole) = cost(60);
    assert_eq!(short, long);
    assert!(
        long_whole > 5 * short_whole && long < short_whole,
        "{long} {short_whole}"
    );
    // Nothing changed: nothing to simulate.
    let p = parse(&raster(10)).unwrap();
    let (cmd, at) = rebuild_indexed(
        &p.segments,
        &identity(&p.segments, vec![0.0; p.segments.len()]),
    );
    let none = vec![false; p.segments.len()];
    assert!(plan(&cmd, &at, &none, &cfg()).unwrap().is_empty());
    // A mapping that does not fit the command is refused, not indexed.
    assert!(plan(&cmd, &at[..at.len() - 1], &none, &cfg()).is_err());
    let mut bad = at.clone();
    bad[1] = bad[0];
    assert!(plan(&cmd, &bad, &none, &cfg()).is_err());
}

/// The compensated program's reported after-error is that of the written
/// program simulated whole against the original path.
#[test]
fn compensated_after_error_equals_a_whole_resimulation() {
    for text in [raster(30), pocket()] {
        let rc = ReverseConfig {
            sim: cfg(),
            ..ReverseConfig::default()
        };
        let c = reverse_compensate(&text, &rc).unwrap();
        assert!(c.unchanged.is_none(), "{:?}", c.unchanged);
        assert!(c.after.max_error_um < c.before.max_error_um);
        let orig = parse(&text).unwrap().segments;
        let written = parse(&c.nc).unwrap().segments;
        let again = simulate(&written, &orig, &rc.sim).unwrap();
        let d = (again.max_error * 1e3 - c.after.max_error_um).abs();
        eprintln!(
            "{} -> {} µm, re-simulated {} µm",
            c.before.max_error_um,
            c.after.max_error_um,
            again.max_error * 1e3
        );
        assert!(d < 0.1, "{d} µm");
    }
}

/// A zero-length move takes no time: its piece starts and ends where the
/// next move starts, so a change next to it reaches past it (the core
/// holds every segment within the memory, 0.22 s, of the change).
#[test]
fn a_zero_length_move_is_timed_as_the_next_one() {
    let p = parse("G1 X10 F600\nG1 X10\nG1 X20\nG1 Y10").unwrap();
    let orig = &p.segments;
    assert_eq!(orig.len(), 4);
    let (cmd, at) = rebuild_indexed(orig, &identity(orig, vec![0.0; 4]));
    let changed = [false, false, true, false];
    let w = plan(&cmd, &at, &changed, &cfg()).unwrap();
    assert_eq!(w.len(), 1, "{w:?}");
    // Each move lasts 1 s: the changed one (1–2 s) reaches 0.78–2.22 s,
    // the first and the last move; the window runs from the start.
    assert_eq!(w[0].core, 0..4, "{w:?}");
    assert_eq!(w[0].command.start, 0, "{w:?}");
    assert!(w[0].phase.is_finite() && w[0].samples > 2000, "{w:?}");
    // A change of the first move (0–1 s) reaches to 1.28 s: through the
    // zero-length move (at 1 s) into the third, not the fourth (2–3 s).
    let w = plan(&cmd, &at, &[true, false, false, false], &cfg()).unwrap();
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].core, 0..3, "{w:?}");
}

/// The CAM-like program of `bench/node/large-program.bench.mjs`
/// (`camProgram`) at `lines` lines: rows of 0.2 mm chords at F3000 along a
/// slightly slanted X with a 1 mm Z wave, four decimals, 0.2 mm-radius
/// half circles between rows, a comment every 500 lines and a feed change
/// every 250.
fn cam_program(lines: usize) -> String {
    let f = |v: f64| {
        let s = format!("{v:.4}");
        s.replacen(
            "0.",
            ".",
            usize::from(s.starts_with("0.") || s.starts_with("-0.")),
        )
    };
    let mut out: Vec<String> = [
        "%",
        "O1000 (GENERATED FINISHING PASS)",
        "N10 G21 G90 G17 G94",
        "N20 T1 M6",
        "N30 S12000 M3",
        "N40 G0 X10. Y10. Z5.",
        "N50 G1 Z0. F600.",
    ]
    .map(String::from)
    .to_vec();
    let (mut x, mut y, mut dir) = (10.0f64, 10.0f64, 1.0f64);
    let mut n = out.len();
    'rows: loop {
        for _ in 0..500 {
            if n >= lines - 3 {
                break 'rows;
            }
            if n % 500 == 0 {
                out.push(format!("(PASS {} ROW Y{})", n / 500, f(y)));
                n += 1;
                continue;
            }
            x += 0.2 * dir;
            y += 0.001;
            let z = -0.5 + 0.5 * (x * 0.3 + y * 0.2).sin();
            out.push(if n % 250 == 0 {
                let feed = if n % 1000 == 0 { 2800 } else { 3000 };
                format!("G1 X{} Y{} Z{} F{feed}.", f(x), f(y), f(z))
            } else {
                format!("G1 X{} Y{} Z{}", f(x), f(y), f(z))
            });
            n += 1;
        }
        y += 0.4;
        out.push(format!(
            "{} X{} Y{} I0. J.2",
            if dir > 0.0 { "G3" } else { "G2" },
            f(x),
            f(y)
        ));
        n += 1;
        dir = -dir;
    }
    out.extend(["G0 Z5.", "M30", "%"].map(String::from));
    out.join("\n") + "\n"
}

/// The correction rounds' windowed prediction of their final program
/// equals a whole-program re-simulation of that program as written
/// (rebuilt, written into the text with its four decimals, read back)
/// against the original path: per segment and over the program within
/// 0.1 µm, on a generated 20,000-line CAM-like program (issue 27's
/// program at 1/50 of its size, tA 40 ms, T 15 ms, dt 2 ms, one region
/// without rapids: every round's windows cover the whole program, cut at
/// the core cap).
///
/// NOT MET today, so ignored (run it with `--ignored`): 382.46 µm
/// windowed against 382.27 µm re-simulated over the program, up to
/// 12.6 µm apart on one segment (line 7518), 7.2 µm on the last chord
/// before an end arc (line 10024), 0.2–0.4 µm on many segments of 2
/// samples. Where the contour error (up to
/// 0.7 mm) exceeds the row spacing (0.4 mm), samples of a neighbouring
/// row or of the arc come nearest to a segment, which a window does not
/// see (`toolpath::locality`, module header), and segments of two
/// samples change their maximum with a sample's assignment. The same
/// numbers before this memory changes.
#[test]
#[ignore = "issue 27: the windowed prediction is not within 0.1 µm on this program (see the doc)"]
fn windowed_rounds_predict_the_written_program_within_a_tenth_of_a_micron() {
    use mtmotion::compensate::reverse::geometry::rebuild;
    use mtmotion::compensate::reverse::region::regions;
    use mtmotion::compensate::reverse::rounds::{run, LocalStats, Work};
    let text = cam_program(20_000);
    let p = parse(&text).unwrap();
    let orig = &p.segments;
    assert!(orig.len() > 19_000, "{}", orig.len());
    let cfg = SimConfig {
        t_a: 0.04,
        t: Lag::All(0.015),
        dt: 2e-3,
        ..SimConfig::default()
    };
    let sim = simulate(orig, orig, &cfg).unwrap();
    let mut work = Work::new(u64::MAX, sim.samples as u64);
    work.set_original(orig, &sim);
    let rg = regions(&p);
    let start = identity(orig, vec![0.0; orig.len()]);
    let r = run(orig, &rg, (&cfg, 0.5), 6, start, &mut work).unwrap();
    // The windowed statistics of the rounds' final edit, from the
    // original's (what a round computes).
    let mut local = LocalStats::new(orig, &work);
    assert!(local.update(orig, &cfg, &r.edit, &mut work).unwrap());
    let written = write_source(&text, &p, &rebuild(orig, &r.edit));
    let back = parse(&written).unwrap().segments;
    let whole = simulate(&back, orig, &cfg).unwrap();
    let (mut worst, mut at): (f64, usize) = (0.0, 0);
    let mut windowed_max: f64 = 0.0;
    let mut n = 0;
    for st in &whole.segments {
        if !orig[st.segment].is_cutting() {
            continue;
        }
        let w = local.by_seg[st.segment].as_ref().unwrap();
        let d = (w.max_error_um - st.max_error_um).abs();
        if d > worst {
            worst = d;
            at = st.line;
        }
        windowed_max = windowed_max.max(w.max_error_um);
        n += 1;
    }
    eprintln!(
        "{n} segments: windowed {windowed_max:.4} µm, whole re-simulation {:.4} µm (original {:.4} µm), worst segment difference {worst:.2e} µm (line {at})",
        whole.max_error * 1e3,
        sim.max_error * 1e3
    );
    assert!(n > 19_000 && whole.max_error < 0.6 * sim.max_error);
    assert!((windowed_max - whole.max_error * 1e3).abs() <= 0.1);
    assert!(worst <= 0.1, "{worst} µm at line {at}");
}
