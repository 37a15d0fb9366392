//! Reverse compensation simulates only around the places it corrects
//! (`toolpath::locality`, issue 27 item 1), and that is exact: on two
//! team-written programs with many corners — a raster without rapids
//! (one region, cut into chunks) and a pocket with rapids between its
//! contours, both asymmetric (pass lengths, step-overs, feeds and an arc
//! vary) — the windowed per-segment statistics of an edited program,
//! brought from the unedited one's, equal a whole-program simulation of
//! the same edited program within 0.1 µm (maximum error, samples and mean
//! deviation of every cutting segment), as do the correction rounds'
//! statistics of their final command on a CAM-like program whose error
//! exceeds its row spacing; the windows around one changed place do not
//! grow with the program's length, and the compensated program's
//! reported after-error equals a whole-program re-simulation of the
//! written program against the original path within 0.1 µm.

use mtmotion::compensate::reverse::geometry::rebuild_indexed;
use mtmotion::compensate::reverse::rounds::identity;
use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
use mtmotion::nc::patch::write_source;
use mtmotion::nc::program::{parse, Motion, Segment};
use mtmotion::toolpath::contour::Path;
use mtmotion::toolpath::locality::{
    piece_starts, plan, plan_capped, update_capped, Windowed, MAX_CORE,
};
use mtmotion::toolpath::{simulate, simulate_stats, Lag, SimConfig, WindowStats};

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

/// The windowed statistics of `cmd` (pieces `at`, `changed`, at most
/// `max_core` segments a core) brought from those of the unedited
/// program, as a correction round has them; the window samples spent and
/// the unedited program's statistics.
fn windowed(
    orig: &[Segment],
    (cmd, at): (&[Segment], &[usize]),
    (changed, max_core): (&[bool], usize),
    cfg: &SimConfig,
) -> (Windowed, u64, Vec<Option<WindowStats>>) {
    let (base, base_at) = rebuild_indexed(orig, &identity(orig, vec![0.0; orig.len()]));
    let mut stats = vec![None; orig.len()];
    for st in simulate_stats(&base, orig, cfg).unwrap().segments {
        stats[st.segment] = Some((&st).into());
    }
    let mut w = Windowed {
        stats: stats.clone(),
        starts: Some(piece_starts(&base, &base_at, cfg).unwrap()),
    };
    let path = Path::new(orig);
    let mut samples = 0u64;
    let done = update_capped(
        cmd,
        at,
        (&path, orig),
        (changed, max_core),
        &mut w,
        cfg,
        &mut |s| {
            samples += s;
            true
        },
    )
    .unwrap();
    assert!(done);
    (w, samples, stats)
}

/// The windowed statistics of the edited program, brought from those of
/// the unedited one, against the whole-program simulation of the edited
/// program: every cutting segment within 0.1 µm (maximum error, samples,
/// mean deviation); returns (window samples, whole samples, segments
/// compared, largest difference µm).
fn compare(text: &str, every: usize) -> (usize, usize, usize, f64) {
    let ((samples, whole, compared, worst), windows) = compare_capped(text, every, MAX_CORE);
    assert!(windows > 1, "{windows}");
    (samples, whole, compared, worst)
}

/// As [`compare`] with at most `max_core` segments in a window's core;
/// also the number of windows of the changes alone.
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
    let (w, samples, _) = windowed(orig, (&cmd, &at), (&changed, max_core), &cfg);
    let mut compared = 0;
    let mut worst: f64 = 0.0;
    for ws in &whole.segments {
        // A rapid's statistics enter neither the maximum error nor a
        // correction; where a retract runs back along its plunge, the
        // samples of the two coincide and go to either.
        if !orig[ws.segment].is_cutting() {
            continue;
        }
        let st = w.stats[ws.segment].as_ref().unwrap();
        let d = (st.max_error_um - ws.max_error_um).abs();
        worst = worst.max(d);
        assert!(
            d < 0.1,
            "segment {} (line {}): window {} µm, whole {} µm",
            ws.segment,
            ws.line,
            st.max_error_um,
            ws.max_error_um
        );
        assert_eq!(st.samples as usize, ws.samples, "segment {}", ws.segment);
        if let (Some(a), Some(b)) = (st.mean_deviation(), ws.mean_deviation) {
            assert!((a - b).abs() < 1e-4, "segment {}: {a} vs {b}", ws.segment);
        }
        compared += 1;
    }
    (
        (samples as usize, whole.samples, compared, worst),
        windows.len(),
    )
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
/// in one of 60: the windows of the changes grow with the corrected
/// places, not the length. (A correction round also re-simulates the
/// pieces whose start time the change moved, to the program's end:
/// `locality::update`.)
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

/// The rounds of a CAM-like program of `lines` lines (20,000: issue 27's
/// program at 1/50 of its size; tA 40 ms, T 15 ms, dt 2 ms, one region
/// without rapids), and the windowed statistics of their final edit
/// brought from the original's (what a round computes).
fn cam_rounds(
    lines: usize,
) -> (
    String,
    mtmotion::nc::program::Program,
    SimConfig,
    mtmotion::toolpath::Simulation,
    mtmotion::compensate::reverse::geometry::Edit,
    (
        mtmotion::compensate::reverse::rounds::LocalStats,
        mtmotion::compensate::reverse::rounds::Work,
    ),
) {
    use mtmotion::compensate::reverse::region::regions;
    use mtmotion::compensate::reverse::rounds::{run, LocalStats, Work};
    let text = cam_program(lines);
    let p = parse(&text).unwrap();
    let orig = &p.segments;
    assert!(orig.len() > lines * 19 / 20, "{}", orig.len());
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
    let mut local = LocalStats::new(orig, &work);
    assert!(local.update(orig, &cfg, &r.edit, &mut work).unwrap());
    (text, p, cfg, sim, r.edit, (local, work))
}

/// Asserts that `windowed` equals `whole` (of `what`) per cutting
/// segment and over the program within 0.1 µm; `sim` is the original's,
/// whose maximum `whole`'s must be below `gain` times (the rounds did
/// lower it).
fn assert_within(
    orig: &[Segment],
    windowed: &[Option<WindowStats>],
    (whole, what): (&mtmotion::toolpath::Simulation, &str),
    (sim, gain): (&mtmotion::toolpath::Simulation, f64),
) {
    let (mut worst, mut at): (f64, usize) = (0.0, 0);
    let mut windowed_max: f64 = 0.0;
    let mut n = 0;
    for st in &whole.segments {
        if !orig[st.segment].is_cutting() {
            continue;
        }
        let w = windowed[st.segment].as_ref().unwrap();
        let d = (w.max_error_um - st.max_error_um).abs();
        if d > worst {
            worst = d;
            at = st.line;
        }
        windowed_max = windowed_max.max(w.max_error_um);
        n += 1;
    }
    eprintln!(
        "{n} segments: windowed {windowed_max:.4} µm, {what} {:.4} µm (original {:.4} µm), worst segment difference {worst:.2e} µm (line {at})",
        whole.max_error * 1e3,
        sim.max_error * 1e3
    );
    assert!(n > 19_000 && whole.max_error < gain * sim.max_error);
    assert!((windowed_max - whole.max_error * 1e3).abs() <= 0.1);
    assert!(worst <= 0.1, "{worst} µm at line {at}");
}

/// The correction rounds' windowed statistics of their final edit equal
/// a whole-program simulation of the same command (the edit rebuilt)
/// against the original path: per cutting segment and over the program
/// within 0.1 µm, on the 20,000-line CAM-like program, where the contour
/// error (up to 0.7 mm) exceeds the row spacing (0.4 mm), so samples of a
/// neighbouring row or of an end arc come nearest to a segment, and where
/// the rounds change segment durations (every later sample moves on the
/// program's grid). Before the windows measured by source and the moved
/// pieces were re-simulated (`toolpath::locality`), 11.1 µm apart on one
/// segment (line 12535).
#[test]
fn windowed_rounds_equal_a_whole_simulation_of_their_command() {
    use mtmotion::compensate::reverse::geometry::rebuild;
    let (_, p, cfg, sim, edit, (local, _)) = cam_rounds(20_000);
    let orig = &p.segments;
    let whole = simulate(&rebuild(orig, &edit), orig, &cfg).unwrap();
    assert_within(
        orig,
        &local.by_seg,
        (&whole, "whole simulation"),
        (&sim, 0.6),
    );
}

/// The correction rounds' windowed prediction of their final program as
/// written equals a whole-program re-simulation of the written program
/// against the original path: per cutting segment and over the program
/// within 0.1 µm, on the 20,000-line CAM-like program ([`cam_rounds`]).
/// The program is rebuilt, written into the text with its four decimals
/// and read back; the windows then bring the rounds' statistics to that
/// command (`LocalStats::update_command` with the rebuilt command's
/// pieces), re-simulating where the writer's rounding changed a piece.
/// Without that last update (the rounds' statistics of their unrounded
/// command against the written program): 281.59 against 281.86 µm, up to
/// 0.27 µm apart on one segment (line 19995), 7 segments over 0.1 µm: the
/// four decimals move end points by up to 0.05 µm, which changes the
/// segments' durations, so the written program ends 3.8 µs earlier and
/// its later samples fall elsewhere on the grid, where the error at the
/// program's sharpest Z reversal changes by about 0.1 µm per µs.
#[test]
fn windowed_rounds_predict_the_written_program_within_a_tenth_of_a_micron() {
    windowed_rounds_predict_the_written_program(20_000, 0.6);
}

/// The same on the 1,000,000-line program (the program of
/// `bench/node/large-program.bench.mjs` and `reverse-large`): minutes and
/// about 3 GB in a release build, so run with `cargo test --release --test
/// reverse_locality -- --ignored`.
#[test]
#[ignore = "a 1 M-line program: run with --release -- --ignored"]
fn windowed_rounds_predict_the_written_million_line_program_within_a_tenth_of_a_micron() {
    // Six unbudgeted rounds lower it less than on 20,000 lines (measured
    // 590.6 → 418.0 µm; compensateNc's 203.0 adds dwells and the check).
    windowed_rounds_predict_the_written_program(1_000_000, 0.75);
}

fn windowed_rounds_predict_the_written_program(lines: usize, gain: f64) {
    let (text, p, cfg, sim, edit, (mut local, mut work)) = cam_rounds(lines);
    let orig = &p.segments;
    let (cmd, at) = rebuild_indexed(orig, &edit);
    let written = write_source(&text, &p, &cmd);
    let back = parse(&written).unwrap().segments;
    assert_eq!(
        back.len(),
        cmd.len(),
        "the written program reads back move for move"
    );
    // The writer rounded: some pieces differ from the rounds' command.
    let moved = back
        .iter()
        .zip(&cmd)
        .filter(|(a, b)| a.end != b.end)
        .count();
    assert!(moved > lines / 20, "{moved} moves rounded");
    assert!(local
        .update_command(orig, &cfg, (&back, &at), &mut work)
        .unwrap());
    let whole = simulate(&back, orig, &cfg).unwrap();
    assert_within(
        orig,
        &local.by_seg,
        (&whole, "whole re-simulation"),
        (&sim, gain),
    );
}

/// A sample from far in time comes nearest to a segment that no window
/// around the change holds: a short diagonal cut first, inside the corner
/// that a later pass turns 2 s afterwards, whose rounding at F3000 passes
/// nearer to the diagonal than to its own path (measured: the diagonal's
/// samples span 0.397–2.377 s, its maximum 184.9 µm before the edit,
/// 197.4 µm after). Moving that corner's vertex re-simulates the corner's
/// pieces only, yet changes the diagonal's statistics: they still equal
/// the whole program's (2·10⁻¹¹ µm), which keeping the diagonal's earlier
/// statistics would miss by 12.6 µm.
#[test]
fn a_later_pass_nearest_to_an_earlier_segment_is_counted_for_it() {
    let text = "G21 G90 G17\nG0 X10.2 Y0.5 Z1\nG1 Z0 F600\nG1 X11.2 Y1.5 F3000\n\
                G1 X40 Y1.5\nG1 X40 Y20\nG1 X10 Y20\nG1 X10 Y0.3\nG1 X30 Y0.3\nG0 Z5\n";
    let p = parse(text).unwrap();
    let orig = &p.segments;
    let cfg = cfg();
    let diagonal = orig.iter().position(|s| s.line == 4).expect("the diagonal");
    let corner = orig.iter().position(|s| s.line == 8).expect("the corner");
    let mut e = identity(orig, vec![0.0; orig.len()]);
    e.vertex_shift[corner] = [0.05, -0.03, 0.0];
    let (cmd, at) = rebuild_indexed(orig, &e);
    let changed: Vec<bool> = (0..orig.len())
        .map(|i| i == corner || i == corner + 1)
        .collect();
    let windows = plan(&cmd, &at, &changed, &cfg).unwrap();
    assert!(
        windows.iter().all(|w| !w.core.contains(&diagonal)),
        "{windows:?}"
    );
    let (w, _, before) = windowed(orig, (&cmd, &at), (&changed, MAX_CORE), &cfg);
    let diag_before = before[diagonal].unwrap();
    let whole = simulate_stats(&cmd, orig, &cfg).unwrap();
    let got = w.stats[diagonal].as_ref().unwrap();
    let want = whole
        .segments
        .iter()
        .find(|s| s.segment == diagonal)
        .unwrap();
    eprintln!(
        "diagonal: before {} µm ({} samples), windowed {} µm ({}), whole {} µm ({})",
        diag_before.max_error_um,
        diag_before.samples,
        got.max_error_um,
        got.samples,
        want.max_error_um,
        want.samples
    );
    eprintln!(
        "spans {:?} -> {:?}, mean {:?} -> {:?}, halves {:?} -> {:?}",
        diag_before.sample_span,
        want.sample_span,
        diag_before.mean_deviation(),
        want.mean_deviation,
        diag_before.half_max,
        want.half_max
    );
    // The corner's samples reach the diagonal, and the change shows there.
    assert!((diag_before.max_error_um - want.max_error_um).abs() > 1.0);
    assert!((got.max_error_um - want.max_error_um).abs() < 0.1);
    assert_eq!(got.samples as usize, want.samples);
    for ws in &whole.segments {
        let st = w.stats[ws.segment].as_ref().unwrap();
        assert!(
            (st.max_error_um - ws.max_error_um).abs() < 0.1 && st.samples as usize == ws.samples,
            "segment {}: {st:?} vs {ws:?}",
            ws.segment
        );
    }
}
