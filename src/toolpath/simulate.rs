//! The tool-path simulation of qiu §4-2 end to end: NC program → timeline
//! → Eq. 1 moving average → Eq. 2 first-order lag → contour error against a
//! reference path, with the maximum error, the motion time and statistics
//! per segment.
//!
//! Readings: a G0 ends in an exact stop — the NC's in-position check — so
//! the next block starts `tA + 10·max T` after the rapid's command ends (the
//! rapid's lag has then decayed to e⁻¹⁰ ≈ 5·10⁻⁵ of itself); the run lasts until `tA + 12·max T` after the last command
//! (the lag's residual is then e⁻¹² ≈ 6·10⁻⁶ of its steady lag); the
//! *motion time* is the time at which the simulated tool has settled within
//! 1 µm of the program's end point — the closest model counterpart of the
//! paper's "actual motion time". The reference path is normally the program
//! itself; reverse compensation simulates the corrected program against the
//! original path. A G4 dwell adds only its own time unless
//! `dwellExactStop` is set: then it first waits `tA + 5·max T`, the exact
//! stop and in-position check of a real NC (qiu's +0.427 s for two 0.1 s
//! dwells is more than the dwells alone).
//!
//! Units: mm, s; errors in mm (µm only in field names that say so).

use serde::Serialize;

use super::columns::{kind_radius, SegmentColumns};
use super::contour::{Element, Nearest, Path, Tracker};
use super::filter::{Filtered, Sample, Stepper};
use super::timeline::Timeline;
use super::{SimConfig, ToolpathError, MAX_SAMPLES, MAX_SERIES};
use crate::nc::program::{parse, Program, Segment};

/// Statistics of one reference segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SegmentStats {
    /// Index into the reference program's segments.
    pub segment: usize,
    /// Source line.
    pub line: usize,
    /// `"line"`, `"arc"` or `"rapid"`.
    pub kind: &'static str,
    /// Length, mm.
    pub length: f64,
    /// Arc radius, mm (0 for lines).
    pub radius: f64,
    /// Largest contour error of the samples nearest to this segment, µm.
    pub max_error_um: f64,
    /// Mean signed normal deviation of those samples (arcs: the mean radius
    /// loss, positive inside; lines in XY: positive to the left), mm.
    pub mean_deviation: Option<f64>,
    /// The mean contour-error vector `near − simulated` per axis X, Y, Z
    /// over the first and the second half of the segment's length (any
    /// plane; used to shift the vertices of line chains per axis), mm. Not
    /// serialised: reverse compensation's own input, and six JS numbers
    /// per segment that a 40,000-segment program's result would carry.
    #[serde(skip)]
    pub half_vector: [Option<[f64; 3]>; 2],
    /// Largest contour error of the samples nearest to the first and the
    /// second half of the segment's length, mm (0 with no sample): the
    /// error at each end's corner, used by reverse compensation's corner
    /// pre-distortion. Not serialised (as `half_vector`).
    #[serde(skip)]
    pub half_max: [f64; 2],
    /// Number of samples nearest to this segment.
    pub samples: usize,
    /// The first and the last of those samples, as indices `k` of the
    /// whole program's grid `k·dt` (`[0, 0]` with none): where in time a
    /// windowed re-simulation finds them ([`super::locality`]). Not
    /// serialised (as `half_vector`).
    #[serde(skip)]
    pub sample_span: [u32; 2],
}

/// What a windowed update ([`super::locality::Windowed`]) and reverse
/// compensation's rounds keep of a segment's [`SegmentStats`]: the same
/// values, bit for bit, without what the segment itself gives (index,
/// line, kind, length, radius), which they do not read, and with the
/// options as flags (96 B instead of 168: a 1 M-segment program's rounds
/// hold two such tables).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowStats {
    /// As [`SegmentStats::max_error_um`], µm.
    pub max_error_um: f64,
    mean_deviation: f64,
    half_vector: [[f64; 3]; 2],
    /// As [`SegmentStats::half_max`], mm.
    pub half_max: [f64; 2],
    /// As [`SegmentStats::sample_span`].
    pub sample_span: [u32; 2],
    /// As [`SegmentStats::samples`] (at most `u32::MAX`: the grid's
    /// indices are `u32`).
    pub samples: u32,
    /// `mean_deviation`, `half_vector[0]`, `half_vector[1]` are there.
    has: [bool; 3],
}

impl WindowStats {
    /// As [`SegmentStats::mean_deviation`], mm.
    pub fn mean_deviation(&self) -> Option<f64> {
        self.has[0].then_some(self.mean_deviation)
    }

    /// As [`SegmentStats::half_vector`]`[h]`, mm.
    pub fn half_vector(&self, h: usize) -> Option<[f64; 3]> {
        (h < 2 && self.has[1 + h]).then(|| self.half_vector[h])
    }
}

impl From<&SegmentStats> for WindowStats {
    fn from(s: &SegmentStats) -> Self {
        let [v0, v1] = s.half_vector;
        Self {
            max_error_um: s.max_error_um,
            mean_deviation: s.mean_deviation.unwrap_or(0.0),
            half_vector: [v0.unwrap_or_default(), v1.unwrap_or_default()],
            half_max: s.half_max,
            sample_span: s.sample_span,
            samples: u32::try_from(s.samples).unwrap_or(u32::MAX),
            has: [s.mean_deviation.is_some(), v0.is_some(), v1.is_some()],
        }
    }
}

/// Running statistics of one reference element.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Acc {
    samples: usize,
    max_error: f64,
    sum_dev: f64,
    n_dev: usize,
    /// The first and the last sample's index on the program's grid.
    span: [u32; 2],
}

/// Running statistics of one reference element over the first and the
/// second half of its length: reverse compensation's own input
/// ([`SegmentStats::half_vector`], `half_max`), not gathered for
/// [`simulate_columns`] (80 B per element).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Halves {
    /// Sum of `near − simulated` per half and axis, and the count per half.
    vec: [[f64; 4]; 2],
    /// Largest error per half.
    half_max: [f64; 2],
}

/// Result of a simulation.
#[derive(Debug, Clone, Default)]
pub struct Simulation {
    /// Sample times, s.
    pub t: Vec<f64>,
    /// Commanded position X/Y/Z, mm.
    pub cmd: [Vec<f64>; 3],
    /// Simulated position X/Y/Z, mm.
    pub sim: [Vec<f64>; 3],
    /// Nearest reference-path point X/Y/Z, mm.
    pub near: [Vec<f64>; 3],
    /// Commanded velocity `f_b` X/Y/Z, mm/s.
    pub vel_cmd: [Vec<f64>; 3],
    /// Simulated velocity X/Y/Z, mm/s.
    pub vel_sim: [Vec<f64>; 3],
    /// Contour error, mm.
    pub error: Vec<f64>,
    /// The reference segment each kept sample was measured against: the
    /// index into `reference` of the segment holding its nearest point
    /// (`near`), the same segment whose [`SegmentStats`] count the sample.
    /// One per kept sample, like every series (thinned with them).
    pub segment: Vec<u32>,
    /// Maximum contour error on cutting moves, mm.
    pub max_error: f64,
    /// When it occurs, s.
    pub max_error_time: f64,
    /// Source line of the reference segment where it occurs.
    pub max_error_line: usize,
    /// Settling time within 1 µm of the end point, s.
    pub motion_time: f64,
    /// Sum of the segments' nominal durations, s.
    pub nominal_time: f64,
    /// Per reference segment with a length.
    pub segments: Vec<SegmentStats>,
    /// Number of samples simulated.
    pub samples: usize,
    /// The series hold every sample when 1; for a run of more than
    /// [`MAX_SERIES`] samples, of each `series_stride` consecutive samples
    /// the one with the largest contour error (drawing and export only:
    /// every statistic uses every sample).
    pub series_stride: usize,
}

/// Simulates `command` and measures it against `reference`.
///
/// # Units
/// Config in s and mm/min; results in mm and s.
///
/// # Errors
/// An invalid config field, an empty program, or too many samples.
///
/// # Examples
/// ```
/// use mtmotion::{nc::program::parse, toolpath::{simulate, SimConfig, Lag}};
/// let p = parse("G0 X10 Y0\nG3 X10 Y0 I-10 J0 F2000\nG3 X10 Y0 I-10 J0").unwrap();
/// let cfg = SimConfig { t_a: 0.0, t: Lag::All(0.03), dt: 1e-3, ..Default::default() };
/// let s = simulate(&p.segments, &p.segments, &cfg).unwrap();
/// // Steady state on R10 at F2000: Δr = R(1 − 1/√(1 + T²ω²)) = 0.049628 mm
/// // (the circle starts from rest after the rapid's exact stop).
/// assert!((s.max_error - 0.049628).abs() < 0.0005, "{}", s.max_error);
/// ```
pub fn simulate(
    command: &[Segment],
    reference: &[Segment],
    cfg: &SimConfig,
) -> Result<Simulation, ToolpathError> {
    simulate_thinned(command, reference, cfg, MAX_SERIES)
}

/// As [`simulate()`] with at most `max_series` samples in the series
/// (at least 1): a run of `n` samples keeps every sample when
/// `n ≤ max_series`, else, of each group of `⌈n / max_series⌉`
/// consecutive samples, the one with the largest contour error (the first
/// of equals; every series at that sample, `t` included). The statistics
/// are the same numbers either way. [`simulate()`] keeps
/// [`MAX_SERIES`].
///
/// # Errors
/// As [`simulate()`].
pub fn simulate_thinned(
    command: &[Segment],
    reference: &[Segment],
    cfg: &SimConfig,
    max_series: usize,
) -> Result<Simulation, ToolpathError> {
    simulate_keeping(
        command,
        reference,
        cfg,
        Some(max_series.max(1)),
        &mut |_| true,
    )
}

/// As [`simulate()`], calling `progress(fraction done)` every
/// [`PROGRESS_EVERY`] samples; a `false` from it stops the run with
/// [`ToolpathError::Cancelled`].
///
/// # Errors
/// As [`simulate()`], and [`ToolpathError::Cancelled`].
pub fn simulate_with_progress(
    command: &[Segment],
    reference: &[Segment],
    cfg: &SimConfig,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Simulation, ToolpathError> {
    simulate_keeping(command, reference, cfg, Some(MAX_SERIES), progress)
}

/// How often, in samples, [`simulate_with_progress`] reports.
pub const PROGRESS_EVERY: usize = 1 << 18;

/// As [`simulate()`] without the per-sample series a caller of the
/// statistics alone never reads: every series is empty; every statistic
/// (maximum error, its time and line, motion time, per-segment statistics,
/// `samples`) is the same number [`simulate()`] gives. Reverse
/// compensation's correction rounds use it.
///
/// # Errors
/// As [`simulate()`].
pub fn simulate_stats(
    command: &[Segment],
    reference: &[Segment],
    cfg: &SimConfig,
) -> Result<Simulation, ToolpathError> {
    simulate_keeping(command, reference, cfg, None, &mut |_| true)
}

fn simulate_keeping(
    command: &[Segment],
    reference: &[Segment],
    cfg: &SimConfig,
    max_series: Option<usize>,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Simulation, ToolpathError> {
    let done = prepare(command, reference, cfg, max_series)?.run(cfg, true, progress)?;
    let segments = done
        .path
        .elements
        .iter()
        .zip(&done.run.acc)
        .zip(&done.run.halves)
        .map(|((el, a), h)| a.stats(el, &reference[el.segment], h))
        .collect();
    let line = reference[done.path.elements[done.run.max_el].segment].line;
    Ok(done.finish(cfg, line, segments))
}

/// As [`simulate_with_progress`] with the per-segment statistics as
/// [`SegmentColumns`] (the returned [`Simulation::segments`] is empty):
/// the same numbers as the serialised fields of [`SegmentStats`], without
/// the halves only reverse compensation reads, in a quarter of the memory
/// (a program of millions of segments; see [`super::columns`]).
///
/// # Errors
/// As [`simulate_with_progress`].
pub fn simulate_columns(
    command: &[Segment],
    reference: &[Segment],
    cfg: &SimConfig,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(Simulation, SegmentColumns), ToolpathError> {
    let (prep, columns) = prepare_columns(command, reference, cfg)?;
    run_columns(prep, columns, cfg, progress)
}

/// As [`simulate_columns`] of a program against itself, taking its
/// segments and dropping them once the timed command and the reference
/// path are built: the run does not hold them (168 B a segment in wasm;
/// 336 MB of a 2 M-segment program).
///
/// # Errors
/// As [`simulate_columns`].
pub fn simulate_columns_owned(
    segments: Vec<Segment>,
    cfg: &SimConfig,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(Simulation, SegmentColumns), ToolpathError> {
    let (prep, columns) = prepare_columns(&segments, &segments, cfg)?;
    drop(segments);
    run_columns(prep, columns, cfg, progress)
}

/// [`prepare`] with series of at most [`MAX_SERIES`] samples, and the
/// columns of the reference path's elements with their segment, line,
/// kind, length and radius.
fn prepare_columns(
    command: &[Segment],
    reference: &[Segment],
    cfg: &SimConfig,
) -> Result<(Prepared, SegmentColumns), ToolpathError> {
    let prep = prepare(command, reference, cfg, Some(MAX_SERIES))?;
    let els = &prep.path.elements;
    let mut columns = SegmentColumns::for_segments(els.len());
    for el in els {
        columns.push_segment(el, &reference[el.segment]);
    }
    Ok((prep, columns))
}

/// Runs `prep` without the halves and completes `columns` with each
/// element's statistics.
fn run_columns(
    prep: Prepared,
    mut columns: SegmentColumns,
    cfg: &SimConfig,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(Simulation, SegmentColumns), ToolpathError> {
    let done = prep.run(cfg, false, progress)?;
    columns.reserve_stats();
    for a in &done.run.acc {
        columns.push_stats(a.max_error, a.mean(), a.samples);
    }
    let line = columns.line.get(done.run.max_el).map_or(0, |&l| l as usize);
    Ok((done.finish(cfg, line, Vec::new()), columns))
}

/// A finished run: its measurement, the reference path, the sample count,
/// the series stride and the nominal time (s).
struct Done {
    run: Run,
    path: Path,
    n: usize,
    stride: usize,
    nominal_time: f64,
}

/// A run ready to start: the timed command, the reference path, the
/// sample count, the end point of the reference (mm) and the series
/// stride (0: no series).
struct Prepared {
    tl: Timeline,
    path: Path,
    n: usize,
    end: [f64; 3],
    stride: usize,
}

/// Checks the config and the budgets and builds the timed `command` and
/// the `reference` path, for series of at most `max_series` samples (none
/// for `None`).
fn prepare(
    command: &[Segment],
    reference: &[Segment],
    cfg: &SimConfig,
    max_series: Option<usize>,
) -> Result<Prepared, ToolpathError> {
    cfg.validate()?;
    check_segments(command)?;
    check_segments(reference)?;
    let tmax = cfg.t.per_axis().into_iter().fold(0.0, f64::max);
    let tl = timeline(command, cfg, tmax);
    let path = Path::new(reference);
    if path.elements.is_empty() || tl.items.is_empty() {
        return Err(ToolpathError::Empty);
    }
    let n = sample_count(&tl, cfg, tmax, command)?;
    let end = reference.last().map_or(tl.origin, |s| s.end.p());
    let stride = max_series.map_or(0, |m| n.div_ceil(m));
    Ok(Prepared {
        tl,
        path,
        n,
        end,
        stride,
    })
}

impl Prepared {
    /// Simulates the command sample by sample and measures it against the
    /// reference, gathering the halves' statistics when `halves`.
    fn run(
        self,
        cfg: &SimConfig,
        halves: bool,
        progress: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Done, ToolpathError> {
        let Prepared {
            tl,
            path,
            n,
            end,
            stride,
        } = self;
        let mut run = Run::new(&path, 0..path.elements.len(), n, stride, halves);
        let mut stepper = Stepper::new(&tl, cfg.t_a, cfg.t.per_axis(), cfg.dt);
        for k in 0..n {
            if k % PROGRESS_EVERY == 0 && k > 0 && !progress(k as f64 / n as f64) {
                return Err(ToolpathError::Cancelled);
            }
            let s = stepper.next_sample();
            run.sample(&path, k, &s, end);
        }
        Ok(Done {
            run,
            path,
            n,
            stride,
            nominal_time: tl.end_time,
        })
    }
}

impl Done {
    /// The simulation of this run, whose largest error is on source line
    /// `max_error_line`, with `segments`.
    fn finish(
        self,
        cfg: &SimConfig,
        max_error_line: usize,
        segments: Vec<SegmentStats>,
    ) -> Simulation {
        let Done {
            run,
            n,
            stride,
            nominal_time,
            ..
        } = self;
        let rec = run
            .series
            .map(|mut r| {
                r.flush();
                r
            })
            .unwrap_or_default();
        Simulation {
            // The filter's sample times are k·dt.
            max_error_time: run.max_k as f64 * cfg.dt,
            samples: n,
            series_stride: stride.max(1),
            max_error_line,
            t: rec.f.t,
            cmd: rec.f.cmd,
            sim: rec.f.sim,
            near: rec.near,
            vel_cmd: rec.f.vel_cmd,
            vel_sim: rec.f.vel_sim,
            error: rec.error,
            segment: rec.segment,
            max_error: run.max_error,
            // The end of the last sample farther than 1 µm from the end point.
            motion_time: run.last_far as f64 * cfg.dt,
            nominal_time,
            segments,
        }
    }
}

/// How many samples [`simulate()`] takes for `command` under `cfg`: the
/// work estimate a caller checks before simulating (microseconds: the
/// timeline only).
///
/// # Errors
/// A bad `cfg`, or [`ToolpathError::TooLong`] past [`MAX_SAMPLES`].
pub fn sample_estimate(command: &[Segment], cfg: &SimConfig) -> Result<usize, ToolpathError> {
    cfg.validate()?;
    let tmax = cfg.t.per_axis().into_iter().fold(0.0, f64::max);
    sample_count(&timeline(command, cfg, tmax), cfg, tmax, command)
}

/// [`ToolpathError::TooManySegments`] when `segments` are more than the
/// simulation may hold, naming the line of the first one over the budget.
fn check_segments(segments: &[Segment]) -> Result<(), ToolpathError> {
    let limit = crate::budget::MAX_TOOLPATH_SEGMENTS;
    match segments.get(limit) {
        None => Ok(()),
        Some(s) => Err(ToolpathError::TooManySegments {
            segments: segments.len(),
            limit,
            next: limit + 1,
            line: s.line,
        }),
    }
}

/// The timed command: a G0 ends in an exact stop of `tA + 10·max T`, and
/// with `dwellExactStop` a G4 first waits `tA + 5·max T` (see the module
/// header). `tmax` is the largest axis lag, s.
pub(super) fn timeline(command: &[Segment], cfg: &SimConfig, tmax: f64) -> Timeline {
    let dwell_stop = if cfg.dwell_exact_stop {
        cfg.t_a + 5.0 * tmax
    } else {
        0.0
    };
    Timeline::with_stops(
        command,
        cfg.rapid_feed,
        cfg.feed_override,
        cfg.t_a + 10.0 * tmax,
        dwell_stop,
    )
}

/// Number of samples at `dt` until `tA + 12·max T` after the last command
/// ends, or [`ToolpathError::TooLong`] past [`MAX_SAMPLES`], naming the
/// source line of the longest move of `command` (usually a very low feed).
pub(super) fn sample_count(
    tl: &Timeline,
    cfg: &SimConfig,
    tmax: f64,
    command: &[Segment],
) -> Result<usize, ToolpathError> {
    let t_end = tl.end_time + cfg.t_a + 12.0 * tmax + cfg.dt;
    let n_f = (t_end / cfg.dt).ceil() + 1.0;
    if n_f > MAX_SAMPLES as f64 {
        let slowest = tl
            .items
            .iter()
            .max_by(|a, b| a.tau.total_cmp(&b.tau))
            .and_then(|it| command.get(it.segment).map(|s| (s, it.tau)))
            .map(|(s, tau)| {
                format!(
                    "; the longest move is line {} ({tau:.3e} s at {} mm/min)",
                    s.line, s.feed
                )
            })
            .unwrap_or_default();
        return Err(ToolpathError::TooLong {
            samples: n_f,
            limit: MAX_SAMPLES,
            slowest,
        });
    }
    Ok(n_f as usize)
}

/// The measurement of a run, sample by sample: the nearest reference point
/// of each simulated sample, followed along the path by a [`Tracker`], its
/// statistics per element, the motion time, and the series kept.
struct Run {
    tracker: Tracker,
    /// Follows the commanded point along the reference path; the
    /// tracker's ties go towards it ([`Tracker::tie_towards`]).
    command: Tracker,
    /// Running statistics per element of the reference path, from element
    /// `base` on (a window keeps only its own).
    acc: Vec<Acc>,
    /// The same over each half of the element, when gathered (else empty).
    halves: Vec<Halves>,
    base: usize,
    /// A window's statistics of the elements outside `base..base +
    /// acc.len()` that its samples come nearest to (with the halves), when
    /// gathered ([`measure_window`]); else such samples are not counted.
    far: Option<std::collections::HashMap<usize, (Acc, Halves)>>,
    /// Index on the program's grid of this run's sample 0.
    offset: usize,
    /// Largest contour error on cutting moves, mm, its sample and element.
    max_error: f64,
    max_k: usize,
    max_el: usize,
    /// One past the last sample farther than 1 µm from the end point.
    last_far: usize,
    series: Option<Series>,
}

/// The series a run returns: every sample, or for a run longer than
/// [`MAX_SERIES`] samples, of each `stride` consecutive samples the one
/// with the largest contour error (the first of equals), so a plot keeps
/// every peak; the statistics always use every sample.
#[derive(Default)]
struct Series {
    stride: usize,
    f: Filtered,
    /// Contour error per kept sample, mm.
    error: Vec<f64>,
    /// Nearest reference-path point X/Y/Z per kept sample, mm.
    near: [Vec<f64>; 3],
    /// Reference segment of the nearest point per kept sample.
    segment: Vec<u32>,
    /// The candidate of the current group of `stride` samples, with its
    /// reference segment.
    held: Option<(Sample, Nearest, u32)>,
}

impl Run {
    /// A run of `n` samples on `path` with statistics for the elements
    /// `elements` (over their halves too when `halves`), keeping series at
    /// `stride` (none when 0).
    fn new(
        path: &Path,
        elements: std::ops::Range<usize>,
        n: usize,
        stride: usize,
        halves: bool,
    ) -> Self {
        Self {
            tracker: Tracker::at(path, elements.start),
            command: Tracker::at(path, elements.start),
            acc: vec![Acc::default(); elements.len()],
            halves: vec![Halves::default(); if halves { elements.len() } else { 0 }],
            base: elements.start,
            far: None,
            offset: 0,
            max_error: 0.0,
            max_k: 0,
            max_el: 0,
            last_far: 0,
            series: (stride > 0).then(|| Series::with_capacity(n.div_ceil(stride), stride)),
        }
    }

    /// Measures sample `k`, `s`, against `path`, whose end point is `end`.
    #[inline]
    fn sample(&mut self, path: &Path, k: usize, s: &Sample, end: [f64; 3]) {
        let q = s.sim;
        if d3(q, end) > 1e-3 {
            self.last_far = k + 1;
        }
        // The commanded point: on the reference path when the reference is
        // the command, close to it otherwise (reverse compensation).
        let lag = d3(s.cmd, q);
        if let Some(sc) = self.command.follow(path, s.cmd) {
            self.tracker.tie_towards(sc);
        }
        // `None` only for an empty path, which the caller refuses.
        let Some(nr) = self.tracker.nearest_within(path, q, lag) else {
            return;
        };
        let e = nr.element;
        let Some(el) = path.elements.get(e) else {
            return;
        };
        // At most `MAX_SAMPLES` samples, below `u32::MAX`.
        let g = u32::try_from(self.offset + k).unwrap_or(u32::MAX);
        let i = e.checked_sub(self.base).filter(|&i| i < self.acc.len());
        if let Some(i) = i {
            if let Some(series) = &mut self.series {
                // At most `MAX_TOOLPATH_SEGMENTS` segments
                // (`check_segments`), far below `u32::MAX`.
                series.offer(k, s, &nr, u32::try_from(el.segment).unwrap_or(u32::MAX));
            }
            self.acc[i].add(&nr, g);
            if let Some(h) = self.halves.get_mut(i) {
                h.add(el, &nr, q);
            }
        } else if let Some(far) = &mut self.far {
            let (a, h) = far.entry(e).or_default();
            a.add(&nr, g);
            h.add(el, &nr, q);
        } else {
            return;
        }
        if !el.rapid && nr.dist > self.max_error {
            self.max_error = nr.dist;
            self.max_k = k;
            self.max_el = e;
        }
    }
}

impl Series {
    fn with_capacity(m: usize, stride: usize) -> Self {
        Self {
            stride,
            f: Filtered::with_capacity(m),
            error: Vec::with_capacity(m),
            near: [
                Vec::with_capacity(m),
                Vec::with_capacity(m),
                Vec::with_capacity(m),
            ],
            segment: Vec::with_capacity(m),
            held: None,
        }
    }

    /// Sample `k`, `s`, whose nearest reference point is `nr` on reference
    /// segment `seg`: kept at once when every sample is kept, else held
    /// while it is the largest error of its group and kept at the group's
    /// last sample.
    #[inline]
    fn offer(&mut self, k: usize, s: &Sample, nr: &Nearest, seg: u32) {
        if self.stride == 1 {
            self.keep(s, nr, seg);
            return;
        }
        if self.held.as_ref().is_none_or(|(_, h, _)| nr.dist > h.dist) {
            self.held = Some((*s, *nr, seg));
        }
        if (k + 1) % self.stride == 0 {
            self.flush();
        }
    }

    /// Keeps the held sample of an unfinished last group.
    fn flush(&mut self) {
        if let Some((s, nr, seg)) = self.held.take() {
            self.keep(&s, &nr, seg);
        }
    }

    fn keep(&mut self, s: &Sample, nr: &Nearest, seg: u32) {
        self.f.push(s);
        self.error.push(nr.dist);
        self.segment.push(seg);
        for ax in 0..3 {
            self.near[ax].push(nr.point[ax]);
        }
    }
}

/// Distance between two points, mm.
#[inline]
fn d3(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

impl Acc {
    /// Adds sample `g` (its index on the program's grid), whose nearest
    /// point is `nr`.
    #[inline]
    fn add(&mut self, nr: &Nearest, g: u32) {
        if self.samples == 0 {
            self.span[0] = g;
        }
        self.span[1] = g;
        self.samples += 1;
        if nr.dist > self.max_error {
            self.max_error = nr.dist;
        }
        if nr.normal.is_finite() {
            self.sum_dev += nr.normal;
            self.n_dev += 1;
        }
    }

    /// The statistics of `self`'s samples and `o`'s together (`o`'s come
    /// after `self`'s when both have some).
    pub(super) fn merge(&mut self, o: &Acc) {
        if o.samples == 0 {
            return;
        }
        if self.samples == 0 {
            *self = *o;
            return;
        }
        self.samples += o.samples;
        self.max_error = self.max_error.max(o.max_error);
        self.sum_dev += o.sum_dev;
        self.n_dev += o.n_dev;
        self.span = [self.span[0].min(o.span[0]), self.span[1].max(o.span[1])];
    }

    /// The mean normal deviation, mm (`None` with no sample that has one).
    fn mean(&self) -> Option<f64> {
        (self.n_dev > 0).then(|| self.sum_dev / self.n_dev as f64)
    }

    /// The statistics of element `el`, whose reference segment is `seg`,
    /// with its halves' `h`.
    fn stats(&self, el: &Element, seg: &Segment, h: &Halves) -> SegmentStats {
        let (kind, radius) = kind_radius(seg);
        SegmentStats {
            segment: el.segment,
            line: seg.line,
            kind,
            length: el.len,
            radius,
            max_error_um: self.max_error * 1e3,
            mean_deviation: self.mean(),
            half_vector: [0, 1].map(|k| {
                let v = &h.vec[k];
                (v[3] > 0.0).then(|| [v[0] / v[3], v[1] / v[3], v[2] / v[3]])
            }),
            half_max: h.half_max,
            samples: self.samples,
            sample_span: self.span,
        }
    }
}

impl Halves {
    /// The sums of `self`'s samples and `o`'s together.
    pub(super) fn merge(&mut self, o: &Halves) {
        for h in 0..2 {
            for k in 0..4 {
                self.vec[h][k] += o.vec[h][k];
            }
            self.half_max[h] = self.half_max[h].max(o.half_max[h]);
        }
    }

    /// Adds the sample `q` whose nearest point `nr` lies on element `el`.
    #[inline]
    fn add(&mut self, el: &Element, nr: &Nearest, q: [f64; 3]) {
        let h = usize::from(nr.s - el.s0 > 0.5 * el.len);
        for ax in 0..3 {
            self.vec[h][ax] += nr.point[ax] - q[ax];
        }
        self.vec[h][3] += 1.0;
        if nr.dist > self.half_max[h] {
            self.half_max[h] = nr.dist;
        }
    }
}

/// One element's statistics from part of a run: its index in
/// [`Path::elements`], the accumulated samples and their halves.
pub(super) type Part = (usize, Acc, Halves);

/// The statistics, per element of the reference `path` they come nearest
/// to, of the samples `measured` of a run of `command`, a window of a
/// longer command sampled at `k·dt + phase` whose sample 0 is sample
/// `offset` of the longer command's grid: the per-segment part of
/// [`simulate()`] for [`super::locality`], which merges the parts of
/// several windows. The samples before `measured` only run the filters,
/// and the trackers follow the commanded and the simulated point by their
/// local search from element `from` on, as they follow them in a run from
/// the program start. Elements `dense` are gathered in an array, any
/// other in a map; only elements with samples are listed.
pub(super) fn measure_window(
    command: &[Segment],
    path: &Path,
    cfg: &SimConfig,
    (phase, offset): (f64, usize),
    measured: std::ops::Range<usize>,
    (dense, from): (std::ops::Range<usize>, usize),
) -> Vec<Part> {
    let tmax = cfg.t.per_axis().into_iter().fold(0.0, f64::max);
    let tl = timeline(command, cfg, tmax);
    let mut run = Run::new(path, dense.clone(), 0, 0, true);
    run.far = Some(std::collections::HashMap::new());
    run.offset = offset;
    run.tracker = Tracker::at(path, from);
    run.command = Tracker::at(path, from);
    if !tl.items.is_empty() {
        let mut stepper = Stepper::with_phase(&tl, cfg.t_a, cfg.t.per_axis(), cfg.dt, phase);
        for k in 0..measured.end {
            let s = stepper.next_sample();
            if k >= measured.start {
                run.sample(path, k, &s, tl.origin);
            } else {
                run.command.follow(path, s.cmd);
                run.tracker.follow(path, s.sim);
            }
        }
    }
    let mut parts: Vec<Part> = dense
        .zip(run.acc.iter().zip(&run.halves))
        .filter(|(_, (a, _))| a.samples > 0)
        .map(|(e, (a, h))| (e, *a, *h))
        .collect();
    parts.extend(run.far.into_iter().flatten().map(|(e, (a, h))| (e, a, h)));
    parts
}

/// The statistics of element `el` of `path` (of `reference`) from the
/// merged parts `a`, `h` ([`measure_window`]).
pub(super) fn part_stats(path: &Path, reference: &[Segment], (el, a, h): &Part) -> SegmentStats {
    let e = &path.elements[*el];
    a.stats(e, &reference[e.segment], h)
}

/// Simulates a parsed program against itself.
///
/// # Errors
/// As [`simulate`].
pub fn simulate_program(p: &Program, cfg: &SimConfig) -> Result<Simulation, ToolpathError> {
    simulate(&p.segments, &p.segments, cfg)
}

/// Parses `text` and simulates it against itself.
///
/// # Errors
/// NC errors naming line and column, and those of [`simulate`].
///
/// # Examples
/// ```
/// use mtmotion::toolpath::{simulate_text, SimConfig};
/// let s = simulate_text("G1 X10 F600\nG1 Y10", &SimConfig::default()).unwrap();
/// assert!(s.max_error > 0.0 && s.max_error < 0.2);
/// assert!((s.nominal_time - 2.0).abs() < 1e-12);
/// ```
pub fn simulate_text(text: &str, cfg: &SimConfig) -> Result<Simulation, ToolpathError> {
    simulate_program(&parse(text)?, cfg)
}
