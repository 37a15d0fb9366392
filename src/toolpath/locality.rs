//! Locality of the simulated response (qiu §4-2, Eqs. 1–2): where a change
//! of the command can change the contour error, and the windows that
//! re-simulate only there.
//!
//! Eq. 1's acc/dec is a moving average of length `tA`: the averaged
//! position at `t` depends on the command over `[t − tA, t]` only. Eq. 2's
//! servo is a first-order lag `T` per axis: a difference in its state
//! decays as `e^{−t/T}`, to e⁻¹² ≈ 6·10⁻⁶ of itself after `12·T`. So a
//! change of the command over `[a, b]` changes the response only over
//! `[a, b + tA + 12·max T]` ([`memory`]), and a run started from rest at
//! the command's position at `t₀` gives, from `t₀ + tA + 12·max T` on, the
//! samples of the run from the program start within e⁻¹² of the lag's
//! difference at `t₀` (a few nm for lags under a mm).
//!
//! Reading chosen: the statistics of a reference segment are over the
//! samples whose nearest point lies on it — from anywhere in time: where
//! the contour error exceeds the distance to another pass (a neighbouring
//! row, a return over the part), samples of that pass come nearest to it.
//! So a window is defined by its *sources*: reference segment `i`'s
//! *piece* of the command (its own segments, a dwell after it, a
//! connector before the next) owns the samples of the program's grid
//! (`k·dt` from the program start) from its start to the next piece's.
//! A window's *core* is a run of pieces; it is simulated from rest at the
//! command's position at least [`memory`] before the core (exact from
//! there, see above), on the program's grid
//! ([`Stepper::with_phase`](super::filter::Stepper::with_phase)), and
//! measures the samples its core owns against the whole reference path,
//! for whatever segment they come nearest to, each sample in one window
//! only; the trackers follow the commanded and the simulated point
//! through the pre-roll by their local search, as in a run from the
//! program start.
//!
//! [`update`] brings the statistics of one command to those of the next:
//! 1. A piece is *moved* when its command changed or its start time did
//!    (by more than [`SHIFT`]: a changed duration earlier moves every later
//!    sample on the grid, which changes its sampled maxima by up to their
//!    change within one `dt`, 11 µm on a CAM program's corners). The
//!    cores: the pieces within [`memory`] of a moved one, merged where
//!    their windows would overlap, cut at [`MAX_CORE`] pieces; they own
//!    every sample that can differ.
//! 2. A segment whose earlier samples all lie in the cores, or that had
//!    none, gets the cores' samples as its statistics; one that had
//!    earlier samples outside the cores (the hull of their pieces, from
//!    the first and last sample, [`WindowStats::sample_span`], and the
//!    earlier start times) keeps the cores' part open; those outside
//!    pieces are then simulated by windows of their own and counted for
//!    it alone (their samples are the earlier ones: nothing there moved).
//!    A segment that had samples in the cores and has none now is empty.
//!    One written from one core and then reached from another (a later
//!    pass) is simulated over all of its pieces again.
//! 3. Every other segment's statistics stand: none of its samples, earlier
//!    or now, lie in a core, so they are those of the earlier run.
//!
//! The statistics then equal a whole-program simulation of the command
//! within e⁻¹² of the lag (`tests/reverse_locality.rs`: 10⁻⁸ µm per
//! segment on a raster, a pocket and a CAM program whose error exceeds
//! its row spacing). Their cost is the windows around the moved pieces,
//! which reach to the program's end once a round changes a duration.
//!
//! Units: mm, s.

use std::collections::HashMap;
use std::ops::Range;

use super::contour::Path;
use super::simulate::{measure_window, part_stats, sample_count, timeline, Acc, Halves, Part};
use super::timeline::Timeline;
use super::{SimConfig, ToolpathError, WindowStats};
use crate::nc::program::Segment;

/// How long after a change of the command the response may still differ:
/// `tA + 12·max T`, s (see the module header).
pub fn memory(cfg: &SimConfig) -> f64 {
    cfg.t_a + 12.0 * cfg.t.per_axis().into_iter().fold(0.0, f64::max)
}

/// Most reference segments in one window's core: a longer stretch of
/// changes is cut into windows of this many, each with its own pre-roll
/// (an exact restart, see the module header), so that a window's
/// statistics, timed command and running sums stay small (a correction
/// round that changes the whole of a 1 M-segment program simulated it as
/// one window, 530 MB beside the statistics it updates).
pub const MAX_CORE: usize = 100_000;

/// A piece whose start moved by more than this, s, is re-simulated: its
/// samples fall elsewhere on the program's grid (the contour error moves
/// by at most its rate, a few hundred mm/s, times this: under 0.001 µm).
pub const SHIFT: f64 = 1e-9;

/// One window of a command (see the module header).
#[derive(Debug, Clone, PartialEq)]
pub struct Window {
    /// Command segments simulated.
    pub command: Range<usize>,
    /// Reference segments whose pieces' samples it measures (its sources).
    pub core: Range<usize>,
    /// Samples measured against the reference path: those whose time
    /// lies in the core's pieces (the others only run the filters).
    pub measured: Range<usize>,
    /// Time of the first sample after the window's start, s (`0 ≤ phase < dt`).
    pub phase: f64,
    /// Samples simulated (to the last measured one).
    pub samples: usize,
    /// Index on the whole program's grid of the window's first sample.
    pub first: usize,
}

/// The timing of a command and its pieces.
struct Timing {
    /// Start time of each command segment (a zero-length one: the next's)
    /// and the end time, s.
    start: Vec<f64>,
    /// Samples of a simulation of the whole command.
    total: usize,
    /// Start and end time of each reference segment's piece, s.
    ps: Vec<f64>,
    pe: Vec<f64>,
    dt: f64,
}

impl Timing {
    fn new(command: &[Segment], at: &[usize], cfg: &SimConfig) -> Result<Self, ToolpathError> {
        cfg.validate()?;
        let n = at.len();
        if at.windows(2).any(|w| w[0] >= w[1]) || at.last().is_some_and(|&l| l >= command.len()) {
            return Err(ToolpathError::Config {
                field: "at",
                message: "expected one rising command index per reference segment".into(),
            });
        }
        let tmax = cfg.t.per_axis().into_iter().fold(0.0, f64::max);
        let (mut start, end_time) = start_times(command, cfg, tmax, TIMED_AT_ONCE);
        let total = sample_count(
            &Timeline {
                items: Vec::new(),
                origin: [0.0; 3],
                end_time,
                max_speed: 0.0,
            },
            cfg,
            tmax,
            command,
        )
        // Too long: the whole timeline, for the error naming the slowest move.
        .or_else(|_| sample_count(&timeline(command, cfg, tmax), cfg, tmax, command))?;
        for j in (0..command.len()).rev() {
            if start[j].is_nan() {
                start[j] = start[j + 1];
            }
        }
        let piece = |i: usize| if i == 0 { 0 } else { at[i] };
        let ps = (0..n).map(|i| start[piece(i)]).collect();
        let pe = (0..n)
            .map(|i| start[if i + 1 == n { command.len() } else { at[i + 1] }])
            .collect();
        Ok(Self {
            start,
            total,
            ps,
            pe,
            dt: cfg.dt,
        })
    }

    /// The first sample of the program's grid in piece `i`'s time (the
    /// pieces' samples partition the run; the last piece's run to its end).
    fn bound(&self, i: usize) -> usize {
        if i >= self.ps.len() {
            self.total
        } else {
            bound(self.ps[i], self.dt).min(self.total)
        }
    }

    /// The window whose sources are the pieces `core`, with `m` of
    /// pre-roll (see the module header).
    fn window(&self, core: Range<usize>, m: f64) -> Window {
        let (ca, cb) = self.extent(&core, m);
        let t0 = self.start[ca];
        let j0 = (t0 / self.dt).ceil().max(0.0) as usize;
        let phase = (j0 as f64 * self.dt - t0).max(0.0);
        let (a, b) = (self.bound(core.start), self.bound(core.end));
        let j0 = j0.min(a);
        Window {
            command: ca..cb,
            measured: a - j0..b - j0,
            core,
            phase,
            samples: b - j0,
            first: j0,
        }
    }

    /// The command segments of a core's window: from the one in force `m`
    /// before the core to the first starting `m` after it.
    fn extent(&self, core: &Range<usize>, m: f64) -> (usize, usize) {
        let ncmd = self.start.len() - 1;
        let (lo, hi) = (self.ps[core.start] - m, self.pe[core.end - 1] + m);
        let ca = self.start[..ncmd]
            .partition_point(|&s| s <= lo)
            .saturating_sub(1);
        let cb = self.start[..ncmd].partition_point(|&s| s < hi).min(ncmd);
        (ca, cb.max(ca + 1))
    }
}

/// The first index `k` of the grid `k·dt` at or after `t`.
fn bound(t: f64, dt: f64) -> usize {
    (t / dt).ceil().max(0.0) as usize
}

/// The windows that re-simulate `command` where the reference segments
/// `changed` changed. Reference segment `i` owns the command segments
/// from `at[i]` up to `at[i + 1]` (the first from 0, the last to the end):
/// its own, a dwell after it, a connector before the next.
///
/// # Units
/// Times in s.
///
/// # Errors
/// As [`simulate()`](super::simulate()) (an invalid config, too many
/// samples); an `at` that does not rise, or not one per reference
/// segment, is [`ToolpathError::Config`].
pub fn plan(
    command: &[Segment],
    at: &[usize],
    changed: &[bool],
    cfg: &SimConfig,
) -> Result<Vec<Window>, ToolpathError> {
    plan_capped(command, at, changed, cfg, MAX_CORE)
}

/// As [`plan`] with at most `max_core` (at least 1) reference segments in
/// a window's core instead of [`MAX_CORE`].
///
/// # Errors
/// As [`plan`].
pub fn plan_capped(
    command: &[Segment],
    at: &[usize],
    changed: &[bool],
    cfg: &SimConfig,
    max_core: usize,
) -> Result<Vec<Window>, ToolpathError> {
    if changed.len() != at.len() {
        return Err(ToolpathError::Config {
            field: "at",
            message: "expected one rising command index per reference segment".into(),
        });
    }
    let tm = Timing::new(command, at, cfg)?;
    Ok(windows(&tm, changed, memory(cfg), max_core.max(1)))
}

/// The windows of `tm` around the pieces `changed`: cores of the pieces
/// within `m` of a changed one, merged where their windows would overlap,
/// up to `max_core` pieces.
fn windows(tm: &Timing, changed: &[bool], m: f64, max_core: usize) -> Vec<Window> {
    let (ps, pe) = (&tm.ps, &tm.pe);
    let mut cores: Vec<(Range<usize>, usize)> = Vec::new();
    for i in (0..ps.len()).filter(|&i| changed[i]) {
        let (lo, hi) = (ps[i] - m, pe[i] + m);
        // Segment i itself is inside: pe[i] > lo and ps[i] < hi.
        let mut core = pe.partition_point(|&e| e < lo)..ps.partition_point(|&s| s <= hi);
        let (ca, cb) = tm.extent(&core, m);
        match cores.last_mut() {
            Some((c, end)) if ca < *end && core.end <= c.start + max_core => {
                c.end = c.end.max(core.end);
                *end = (*end).max(cb);
                continue;
            }
            Some((c, _)) => core.start = core.start.max(c.end),
            None => {}
        }
        if core.start < core.end {
            let (_, cb) = tm.extent(&core, m);
            cores.push((core, cb));
        }
    }
    cores
        .into_iter()
        .map(|(core, _)| tm.window(core, m))
        .collect()
}

/// The windows whose cores are the runs of `pieces` (each cut at
/// `max_core`), each with its own pre-roll: no other piece is measured.
fn windows_over(tm: &Timing, pieces: &[bool], m: f64, max_core: usize) -> Vec<Window> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < pieces.len() {
        if !pieces[i] {
            i += 1;
            continue;
        }
        let a = i;
        while i < pieces.len() && pieces[i] && i - a < max_core {
            i += 1;
        }
        out.push(tm.window(a..i, m));
    }
    out
}

/// Start time of each segment of `command` (NaN for one the timeline
/// skips; one more entry, the end time) and the end time, s: the items'
/// start times of [`timeline`], bit for bit (their durations summed in
/// the same order), from timelines of `at_once` segments at a time
/// ([`TIMED_AT_ONCE`]), so that the whole program's timed command (230 B
/// a segment) is never held for the start times alone.
fn start_times(command: &[Segment], cfg: &SimConfig, tmax: f64, at_once: usize) -> (Vec<f64>, f64) {
    let mut start = vec![f64::NAN; command.len() + 1];
    let mut t = 0.0;
    for (k, part) in command.chunks(at_once).enumerate() {
        for it in &timeline(part, cfg, tmax).items {
            let s = &mut start[k * at_once + it.segment];
            if s.is_nan() {
                *s = t;
            }
            t += it.tau;
        }
    }
    start[command.len()] = t;
    (start, t)
}

/// Segments timed at once by [`start_times`].
const TIMED_AT_ONCE: usize = 1 << 16;

/// The parts of every element measured by window `w` of `command` against
/// `path`.
fn parts(command: &[Segment], path: &Path, at: &[usize], w: &Window, cfg: &SimConfig) -> Vec<Part> {
    let Some(part) = command.get(w.command.clone()) else {
        return Vec::new();
    };
    let piece = |j: usize| at.partition_point(|&a| a <= j).saturating_sub(1);
    let els = &path.elements;
    let (pa, pb) = (piece(w.command.start), piece(w.command.end - 1) + 1);
    let dense = els.partition_point(|e| e.segment < pa)..els.partition_point(|e| e.segment < pb);
    measure_window(
        part,
        path,
        cfg,
        (w.phase, w.first),
        w.measured.clone(),
        (dense.clone(), dense.start),
    )
}

/// Per reference segment, the statistics of a command against a reference
/// path, kept equal to a whole-program simulation of the command while the
/// command changes, by re-simulating windows ([`update`]).
#[derive(Debug, Clone, Default)]
pub struct Windowed {
    /// Statistics per reference segment (`None`: no length), as much of
    /// each as a windowed update and reverse compensation read.
    pub stats: Vec<Option<WindowStats>>,
    /// Start time of each reference segment's piece in the command the
    /// statistics are of, s (`None`: not known, every piece is
    /// re-simulated).
    pub starts: Option<Vec<f64>>,
}

/// Brings `w`, the statistics of an earlier command against `path` (of
/// `reference`), to those of `command`, whose pieces (reference segment
/// `i` owns the command segments from `at[i]`, see [`plan`]) are `changed`
/// where their command differs from the earlier one's, by re-simulating
/// windows (see the module header): the pieces within [`memory`] of a
/// changed or moved one, then the pieces whose samples came nearest to a
/// segment the first windows' samples came nearest to, or had come. Each
/// set of windows is offered to `afford` (its samples) first; `false`
/// when it refused one: `w` is then as before when it refused the first,
/// else its starts are cleared, so that the next update re-simulates
/// every piece.
///
/// # Errors
/// As [`plan`]; [`ToolpathError::Config`] when `w` does not hold one
/// entry per reference segment.
pub fn update(
    command: &[Segment],
    at: &[usize],
    (path, reference): (&Path, &[Segment]),
    changed: &[bool],
    w: &mut Windowed,
    cfg: &SimConfig,
    afford: &mut dyn FnMut(u64) -> bool,
) -> Result<bool, ToolpathError> {
    update_capped(
        command,
        at,
        (path, reference),
        (changed, MAX_CORE),
        w,
        cfg,
        afford,
    )
}

/// As [`update`] with at most `max_core` (at least 1) reference segments
/// in a window's core instead of [`MAX_CORE`].
///
/// # Errors
/// As [`update`].
pub fn update_capped(
    command: &[Segment],
    at: &[usize],
    (path, reference): (&Path, &[Segment]),
    (changed, max_core): (&[bool], usize),
    w: &mut Windowed,
    cfg: &SimConfig,
    afford: &mut dyn FnMut(u64) -> bool,
) -> Result<bool, ToolpathError> {
    let max_core = max_core.max(1);
    let n = at.len();
    if changed.len() != n || w.stats.len() != n || reference.len() != n {
        return Err(ToolpathError::Config {
            field: "at",
            message: "expected one rising command index per reference segment".into(),
        });
    }
    let tm = Timing::new(command, at, cfg)?;
    let m = memory(cfg);
    let dt = cfg.dt;
    // A piece re-simulates when its command changed or its start moved.
    let old = w.starts.as_deref().filter(|s| s.len() == n);
    let moved: Vec<bool> = (0..n)
        .map(|i| {
            changed[i]
                || old.is_none_or(|o| {
                    (o[i] - tm.ps[i]).abs() > SHIFT || bound(o[i], dt) != bound(tm.ps[i], dt)
                })
        })
        .collect();
    let first = windows(&tm, &moved, m, max_core);
    if first.is_empty() {
        w.starts = Some(tm.ps);
        return Ok(true);
    }
    if !afford(first.iter().map(|x| x.samples as u64).sum()) {
        return Ok(false);
    }
    // M: the pieces the first windows measure.
    let mut in_m = vec![false; n];
    for x in &first {
        in_m[x.core.clone()].fill(true);
    }
    let mut cnt = vec![0u32; n + 1];
    for i in 0..n {
        cnt[i + 1] = cnt[i] + u32::from(in_m[i]);
    }
    // The pieces of the earlier command whose time holds a segment's
    // earlier samples (all of M when the earlier command is not known).
    let old_pieces = |st: &WindowStats| -> Option<Range<usize>> {
        if st.samples == 0 {
            return None;
        }
        let o = old?;
        let piece = |g: u32| {
            o.partition_point(|&s| bound(s, dt) <= g as usize)
                .saturating_sub(1)
        };
        Some(piece(st.sample_span[0])..piece(st.sample_span[1]) + 1)
    };
    let all_in_m = |r: &Range<usize>| (cnt[r.end] - cnt[r.start]) as usize == r.len();
    let els = &path.elements;
    // Earlier spans of the elements, before the first windows overwrite
    // them (8 B an element: `[u32::MAX, 0]` for none).
    let spans: Vec<[u32; 2]> = els
        .iter()
        .map(|e| {
            w.stats[e.segment]
                .as_ref()
                .and_then(old_pieces)
                .map_or([u32::MAX, 0], |r| [r.start as u32, r.end as u32])
        })
        .collect();
    let span = |e: usize| {
        let [a, b] = spans[e];
        (a != u32::MAX).then_some(a as usize..b as usize)
    };
    // Pass 1. An element's parts are written at once unless it has
    // earlier samples outside M (`open`: completed by pass 2); a second
    // part for an element written this round sends it to pass 2 whole
    // (`redo`, with the pieces of its new samples).
    let mut written = vec![false; els.len()];
    let mut open: HashMap<usize, (Acc, Halves)> = HashMap::new();
    let mut redo: HashMap<usize, Range<usize>> = HashMap::new();
    for x in &first {
        for (e, a, h) in parts(command, path, at, x, cfg) {
            if let Some(r) = redo.get_mut(&e) {
                *r = r.start.min(x.core.start)..r.end.max(x.core.end);
            } else if written[e] {
                let prev = w.stats[els[e].segment]
                    .as_ref()
                    .map(|st| new_pieces(&tm, st));
                let r = prev.map_or(x.core.clone(), |p| {
                    p.start.min(x.core.start)..p.end.max(x.core.end)
                });
                redo.insert(e, r);
            } else if let Some((oa, oh)) = open.get_mut(&e) {
                oa.merge(&a);
                oh.merge(&h);
            } else if span(e).is_some_and(|r| !all_in_m(&r)) {
                open.insert(e, (a, h));
            } else {
                w.stats[els[e].segment] = Some((&part_stats(path, reference, &(e, a, h))).into());
                written[e] = true;
            }
        }
    }
    // Elements that had samples in M and got none now: empty, or open;
    // elements without statistics (none earlier): empty, as a whole run
    // lists them.
    let empty = |e: usize| part_stats(path, reference, &(e, Acc::default(), Halves::default()));
    for e in 0..els.len() {
        if written[e] || open.contains_key(&e) || redo.contains_key(&e) {
            continue;
        }
        let Some(r) = span(e) else {
            if w.stats[els[e].segment].is_none() {
                w.stats[els[e].segment] = Some((&empty(e)).into());
            }
            continue;
        };
        if cnt[r.end] == cnt[r.start] {
            continue; // untouched
        }
        if all_in_m(&r) {
            w.stats[els[e].segment] = Some((&empty(e)).into());
        } else {
            open.insert(e, (Acc::default(), Halves::default()));
        }
    }
    // Pass 2: the open elements' earlier pieces outside M, and the redone
    // elements' earlier and new pieces, each set counted for its own.
    let mut outside = vec![false; n];
    for e in open.keys() {
        if let Some(r) = span(*e) {
            for i in r {
                outside[i] |= !in_m[i];
            }
        }
    }
    let mut whole = vec![false; n];
    for (e, r) in &redo {
        whole[r.clone()].fill(true);
        if let Some(s) = span(*e) {
            whole[s].fill(true);
        }
    }
    let second = windows_over(&tm, &outside, m, max_core);
    let third = windows_over(&tm, &whole, m, max_core);
    let cost = second.iter().chain(&third).map(|x| x.samples as u64).sum();
    if cost > 0 && !afford(cost) {
        // Part of the first windows' statistics is written: the next
        // update re-simulates every piece.
        w.starts = None;
        return Ok(false);
    }
    for x in &second {
        for (e, a, h) in parts(command, path, at, x, cfg) {
            if let Some((oa, oh)) = open.get_mut(&e) {
                oa.merge(&a);
                oh.merge(&h);
            }
        }
    }
    let mut again: HashMap<usize, (Acc, Halves)> = redo
        .keys()
        .map(|&e| (e, (Acc::default(), Halves::default())))
        .collect();
    for x in &third {
        for (e, a, h) in parts(command, path, at, x, cfg) {
            if let Some((oa, oh)) = again.get_mut(&e) {
                oa.merge(&a);
                oh.merge(&h);
            }
        }
    }
    for (e, (a, h)) in open.into_iter().chain(again) {
        w.stats[els[e].segment] = Some((&part_stats(path, reference, &(e, a, h))).into());
    }
    w.starts = Some(tm.ps);
    Ok(true)
}

/// The pieces of `tm` whose time holds the samples of `st`.
fn new_pieces(tm: &Timing, st: &WindowStats) -> Range<usize> {
    let piece = |g: u32| {
        tm.ps
            .partition_point(|&s| bound(s, tm.dt) <= g as usize)
            .saturating_sub(1)
    };
    piece(st.sample_span[0])..piece(st.sample_span[1]) + 1
}

/// The start time of each reference segment's piece of `command` (see
/// [`plan`]), s: what [`Windowed::starts`] holds.
///
/// # Errors
/// As [`plan`].
pub fn piece_starts(
    command: &[Segment],
    at: &[usize],
    cfg: &SimConfig,
) -> Result<Vec<f64>, ToolpathError> {
    Ok(Timing::new(command, at, cfg)?.ps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::program::parse;

    /// The start times timed a few segments at a time are the whole
    /// timeline's, bit for bit (rapids with their stop, a dwell, a
    /// zero-length move).
    #[test]
    fn start_times_by_parts_are_the_whole_timelines() {
        let text = "G0 X1 Y1\nG1 X10 F600\nG2 X20 Y1 I5 J0\nG4 P0.3\nG0 X5 Y5\nG1 X5 Y5\n\
                    G1 Y8\nG1 X12 Y9 Z1 F900\nG3 X14 Y11 R2\nG0 Z5\nG1 X3 F300";
        let p = parse(text).unwrap();
        let cfg = SimConfig::default();
        let tmax = cfg.t.per_axis().into_iter().fold(0.0, f64::max);
        let tl = timeline(&p.segments, &cfg, tmax);
        let mut want = vec![f64::NAN; p.segments.len() + 1];
        for it in tl.items.iter().rev() {
            want[it.segment] = it.t0;
        }
        want[p.segments.len()] = tl.end_time;
        for at_once in [1, 2, 3, 7, p.segments.len()] {
            let (got, end) = start_times(&p.segments, &cfg, tmax, at_once);
            assert_eq!(end.to_bits(), tl.end_time.to_bits(), "{at_once}");
            for (g, w) in got.iter().zip(&want) {
                assert!(g.to_bits() == w.to_bits(), "{at_once}: {got:?} {want:?}");
            }
        }
        assert!(got_nan(&start_times(&p.segments, &cfg, tmax, 2).0));
    }

    /// The zero-length move has no item: its start is NaN before `plan`
    /// fills it.
    fn got_nan(s: &[f64]) -> bool {
        s.iter().any(|x| x.is_nan())
    }
}
