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
//! Reading chosen: a window holds the *core* reference segments — every
//! one whose command time lies within [`memory`] of a changed segment —
//! with a pre-roll of at least [`memory`] of command before them and a
//! post-roll of at least [`memory`] after them (the tool lags the command,
//! so a core segment's samples fall inside); windows whose pre- and
//! post-rolls would overlap are merged, up to [`MAX_CORE`] core segments
//! (a longer stretch of changes is cut into windows that each restart
//! with their own pre-roll). A window is sampled on the whole
//! program's grid (`k·dt` from the program start,
//! [`Stepper::with_phase`](super::filter::Stepper::with_phase)), measured
//! against the whole
//! reference path from `tA + max T` before its core (the tool lags the
//! command, so no sample before comes nearest to a core segment) to
//! [`memory`] after it, and its statistics are taken for its core
//! segments only.
//! They equal the whole-program simulation's within e⁻¹² of the lag, except
//! where samples from far in time come nearest to a core segment (a later
//! pass within the contour error of it), which a window does not see.
//! Outside the cores the statistics of an earlier run stand; a changed
//! segment's duration shifts the later samples' phase on the grid, which
//! moves their sampled maxima by up to their change within one `dt`.
//!
//! Units: mm, s.

use std::ops::Range;

use super::contour::Path;
use super::simulate::{measure_window, sample_count, timeline};
use super::timeline::Timeline;
use super::{SegmentStats, SimConfig, ToolpathError};
use crate::nc::program::Segment;

/// How long after a change of the command the response may still differ:
/// `tA + 12·max T`, s (see the module header).
pub fn memory(cfg: &SimConfig) -> f64 {
    cfg.t_a + 12.0 * cfg.t.per_axis().into_iter().fold(0.0, f64::max)
}

/// Most reference segments in one window's core: a longer stretch of
/// changes is cut into windows of this many, each with its own pre- and
/// post-roll (an exact restart, see the module header), so that a window's
/// statistics, timed command and running sums stay small (a correction
/// round that changes the whole of a 1 M-segment program simulated it as
/// one window, 530 MB beside the statistics it updates).
pub const MAX_CORE: usize = 100_000;

/// One window of a command (see the module header).
#[derive(Debug, Clone, PartialEq)]
pub struct Window {
    /// Command segments simulated.
    pub command: Range<usize>,
    /// Reference segments whose statistics it gives.
    pub core: Range<usize>,
    /// Samples measured against the reference path (the others only
    /// run the filters): from `tA + max T` before the core, within the
    /// exact part, to [`memory`] after it (to the end at the program's).
    pub measured: Range<usize>,
    /// Time of the first sample after the window's start, s (`0 ≤ phase < dt`).
    pub phase: f64,
    /// Samples simulated (to the last measured one).
    pub samples: usize,
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
    cfg.validate()?;
    let max_core = max_core.max(1);
    let n = at.len();
    if changed.len() != n
        || at.windows(2).any(|w| w[0] >= w[1])
        || at.last().is_some_and(|&l| l >= command.len())
    {
        return Err(ToolpathError::Config {
            field: "at",
            message: "expected one rising command index per reference segment".into(),
        });
    }
    if !changed.contains(&true) {
        return Ok(Vec::new());
    }
    let tmax = cfg.t.per_axis().into_iter().fold(0.0, f64::max);
    let m = memory(cfg);
    // Start time of each command segment (a zero-length one: the next's).
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
    let ps: Vec<f64> = (0..n).map(|i| start[piece(i)]).collect();
    let pe: Vec<f64> = (0..n)
        .map(|i| start[if i + 1 == n { command.len() } else { at[i + 1] }])
        .collect();
    let dt = cfg.dt;
    // The command segments of a core's window: from the one in force `m`
    // before the core to the first starting `m` after it.
    let extent = |core: &Range<usize>| {
        let (lo, hi) = (ps[core.start] - m, pe[core.end - 1] + m);
        let ca = start.partition_point(|&s| s <= lo).saturating_sub(1);
        let cb = start.partition_point(|&s| s < hi).min(command.len());
        (ca, cb.max(ca + 1))
    };
    // Cores: the pieces within `m` of a changed one, merged where their
    // windows would overlap (one window costs less than both).
    // A core stops growing at `max_core` segments: the next one starts
    // where it ends, with its own pre-roll.
    let mut cores: Vec<(Range<usize>, usize)> = Vec::new();
    for i in (0..n).filter(|&i| changed[i]) {
        let (lo, hi) = (ps[i] - m, pe[i] + m);
        // Segment i itself is inside: pe[i] > lo and ps[i] < hi.
        let mut core = pe.partition_point(|&e| e < lo)..ps.partition_point(|&s| s <= hi);
        let (ca, cb) = extent(&core);
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
            let (_, cb) = extent(&core);
            cores.push((core, cb));
        }
    }
    Ok(cores
        .into_iter()
        .map(|(core, _)| {
            let (ca, cb) = extent(&core);
            let t0 = start[ca];
            let j0 = (t0 / dt).ceil();
            let phase = (j0 * dt - t0).max(0.0);
            // Sample index at global time t (the first at or after it).
            let k_at = |t: f64| ((t - t0 - phase) / dt).ceil().max(0.0) as usize;
            // Exact from the start at the program's start (it starts
            // from rest), else `m` after the window's start.
            let exact = if ca == 0 { t0 } else { t0 + m };
            let first = (ps[core.start] - cfg.t_a - tmax).max(exact);
            // To the end at the program's end (the tool settles after
            // the last command), else `m` after the core; nothing after
            // the last measured sample is needed.
            let last = if cb == command.len() {
                total.saturating_sub(j0 as usize)
            } else {
                k_at(pe[core.end - 1] + m)
            };
            let a = k_at(first.min(ps[core.start])).min(last);
            Window {
                command: ca..cb,
                core,
                phase,
                measured: a..last,
                samples: last,
            }
        })
        .collect())
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

/// The statistics of window `w`'s core segments (every one listed, as in
/// [`simulate()`](super::simulate())'s `segments`): `command` simulated
/// over the window alone and measured against the whole reference path
/// `path` of `reference`.
///
/// # Units
/// As [`SegmentStats`].
pub fn simulate_window(
    command: &[Segment],
    (path, reference): (&Path, &[Segment]),
    w: &Window,
    cfg: &SimConfig,
) -> Vec<SegmentStats> {
    let Some(part) = command.get(w.command.clone()) else {
        return Vec::new();
    };
    measure_window(
        part,
        (path, reference),
        cfg,
        (w.phase, w.samples),
        (w.measured.clone(), w.core.clone()),
    )
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
