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

use super::contour::{Element, Nearest, Path, Tracker};
use super::filter::{filter_keeping, Filtered, Keep};
use super::timeline::Timeline;
use super::{SimConfig, ToolpathError, MAX_SAMPLES};
use crate::nc::program::{parse, Motion, Program, Segment};

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
    /// The same over the first and the second half of the segment's
    /// length (used to shift the vertices of line programs), mm.
    pub half_deviation: [Option<f64>; 2],
    /// The mean contour-error vector `near − simulated` per axis X, Y, Z
    /// over the first and the second half (any plane; used to shift the
    /// vertices of line chains per axis), mm.
    pub half_vector: [Option<[f64; 3]>; 2],
    /// Number of samples nearest to this segment.
    pub samples: usize,
}

/// Running statistics of one reference element.
#[derive(Debug, Clone, Copy, Default)]
struct Acc {
    samples: usize,
    max_error: f64,
    sum_dev: f64,
    n_dev: usize,
    /// Sum and count of the normal deviation over each half.
    half: [f64; 4],
    /// Sum of `near − simulated` per half and axis, and the count per half.
    vec: [[f64; 4]; 2],
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
    simulate_keeping(command, reference, cfg, Keep::All)
}

/// As [`simulate()`] without the per-sample series a caller of the
/// statistics alone never reads: `t`, `near`, `vel_cmd`, `vel_sim` and
/// `error` are empty, `cmd` and `sim` are kept; every statistic (maximum
/// error, its time and line, motion time, per-segment statistics,
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
    simulate_keeping(command, reference, cfg, Keep::Positions)
}

fn simulate_keeping(
    command: &[Segment],
    reference: &[Segment],
    cfg: &SimConfig,
    keep: Keep,
) -> Result<Simulation, ToolpathError> {
    cfg.validate()?;
    let tmax = cfg.t.per_axis().into_iter().fold(0.0, f64::max);
    let tl = timeline(command, cfg, tmax);
    let path = Path::new(reference);
    if path.elements.is_empty() || tl.items.is_empty() {
        return Err(ToolpathError::Empty);
    }
    let n = sample_count(&tl, cfg, tmax)?;
    let f = filter_keeping(&tl, cfg.t_a, cfg.t.per_axis(), cfg.dt, n, keep);
    let tr = track(&path, &f, n, keep == Keep::All);
    let end = reference.last().map_or(tl.origin, |s| s.end.p());
    let motion_time = settling_time(&f.sim, end, n, cfg.dt);
    let segments = path
        .elements
        .iter()
        .zip(&tr.acc)
        .map(|(el, a)| a.stats(el, &reference[el.segment]))
        .collect();
    Ok(Simulation {
        // The filter's sample times are k·dt.
        max_error_time: if tr.max_k < n {
            tr.max_k as f64 * cfg.dt
        } else {
            0.0
        },
        samples: n,
        max_error_line: reference[path.elements[tr.max_el].segment].line,
        t: f.t,
        cmd: f.cmd,
        sim: f.sim,
        near: tr.near,
        vel_cmd: f.vel_cmd,
        vel_sim: f.vel_sim,
        error: tr.error,
        max_error: tr.max_error,
        motion_time,
        nominal_time: tl.end_time,
        segments,
    })
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
    sample_count(&timeline(command, cfg, tmax), cfg, tmax)
}

/// The timed command: a G0 ends in an exact stop of `tA + 10·max T`, and
/// with `dwellExactStop` a G4 first waits `tA + 5·max T` (see the module
/// header). `tmax` is the largest axis lag, s.
fn timeline(command: &[Segment], cfg: &SimConfig, tmax: f64) -> Timeline {
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
/// ends, or [`ToolpathError::TooLong`] past [`MAX_SAMPLES`].
fn sample_count(tl: &Timeline, cfg: &SimConfig, tmax: f64) -> Result<usize, ToolpathError> {
    let t_end = tl.end_time + cfg.t_a + 12.0 * tmax + cfg.dt;
    let n_f = (t_end / cfg.dt).ceil() + 1.0;
    if n_f > MAX_SAMPLES as f64 {
        return Err(ToolpathError::TooLong {
            samples: n_f as usize,
            limit: MAX_SAMPLES,
        });
    }
    Ok(n_f as usize)
}

/// The contour error of every sample and its statistics per element.
struct Tracked {
    /// Contour error per sample, mm.
    error: Vec<f64>,
    /// Nearest reference-path point X/Y/Z per sample, mm.
    near: [Vec<f64>; 3],
    /// Running statistics per element of the reference path.
    acc: Vec<Acc>,
    /// Largest contour error on cutting moves, mm, its sample and element.
    max_error: f64,
    max_k: usize,
    max_el: usize,
}

/// Measures the first `n` simulated samples of `f` against `path`: the
/// nearest point of each, followed along the path by a [`Tracker`].
fn track(path: &Path, f: &Filtered, n: usize, series: bool) -> Tracked {
    let mut tracker = Tracker::default();
    let m = if series { n } else { 0 };
    let mut error = Vec::with_capacity(m);
    let mut near: [Vec<f64>; 3] = [
        Vec::with_capacity(m),
        Vec::with_capacity(m),
        Vec::with_capacity(m),
    ];
    let mut acc = vec![Acc::default(); path.elements.len()];
    let (mut max_error, mut max_k, mut max_el) = (0.0f64, 0usize, 0usize);
    let (sx, sy, sz) = (&f.sim[0][..n], &f.sim[1][..n], &f.sim[2][..n]);
    let (cx, cy, cz) = (&f.cmd[0][..n], &f.cmd[1][..n], &f.cmd[2][..n]);
    for k in 0..n {
        let q = [sx[k], sy[k], sz[k]];
        // The commanded point: on the reference path when the reference is
        // the command, close to it otherwise (reverse compensation).
        let lag = ((cx[k] - q[0]).powi(2) + (cy[k] - q[1]).powi(2) + (cz[k] - q[2]).powi(2)).sqrt();
        let Some(nr) = tracker.nearest_within(path, q, lag) else {
            break;
        };
        if series {
            error.push(nr.dist);
            for ax in 0..3 {
                near[ax].push(nr.point[ax]);
            }
        }
        let e = nr.element;
        let (Some(a), Some(el)) = (acc.get_mut(e), path.elements.get(e)) else {
            continue;
        };
        a.add(el, &nr, q);
        if !el.rapid && nr.dist > max_error {
            max_error = nr.dist;
            max_k = k;
            max_el = e;
        }
    }
    Tracked {
        error,
        near,
        acc,
        max_error,
        max_k,
        max_el,
    }
}

/// The motion time: the end of the last of the first `n` samples of `sim`
/// farther than 1 µm from `end`, s (0 when every sample is within it).
fn settling_time(sim: &[Vec<f64>; 3], end: [f64; 3], n: usize, dt: f64) -> f64 {
    for k in (0..n).rev() {
        let d = ((sim[0][k] - end[0]).powi(2)
            + (sim[1][k] - end[1]).powi(2)
            + (sim[2][k] - end[2]).powi(2))
        .sqrt();
        if d > 1e-3 {
            return (k + 1) as f64 * dt;
        }
    }
    0.0
}

impl Acc {
    /// Adds the sample `q` whose nearest point `nr` lies on element `el`.
    #[inline]
    fn add(&mut self, el: &Element, nr: &Nearest, q: [f64; 3]) {
        self.samples += 1;
        let h = usize::from(nr.s - el.s0 > 0.5 * el.len);
        for ax in 0..3 {
            self.vec[h][ax] += nr.point[ax] - q[ax];
        }
        self.vec[h][3] += 1.0;
        if nr.dist > self.max_error {
            self.max_error = nr.dist;
        }
        if nr.normal.is_finite() {
            self.sum_dev += nr.normal;
            self.n_dev += 1;
            self.half[2 * h] += nr.normal;
            self.half[2 * h + 1] += 1.0;
        }
    }

    /// The statistics of element `el`, whose reference segment is `seg`.
    fn stats(&self, el: &Element, seg: &Segment) -> SegmentStats {
        let (kind, radius) = match seg.motion {
            Motion::Arc(a) => ("arc", a.radius),
            Motion::Rapid => ("rapid", 0.0),
            _ => ("line", 0.0),
        };
        SegmentStats {
            segment: el.segment,
            line: seg.line,
            kind,
            length: el.len,
            radius,
            max_error_um: self.max_error * 1e3,
            mean_deviation: (self.n_dev > 0).then(|| self.sum_dev / self.n_dev as f64),
            half_deviation: [0, 1].map(|h| {
                let half = &self.half;
                (half[2 * h + 1] > 0.0).then(|| half[2 * h] / half[2 * h + 1])
            }),
            half_vector: [0, 1].map(|h| {
                let v = &self.vec[h];
                (v[3] > 0.0).then(|| [v[0] / v[3], v[1] / v[3], v[2] / v[3]])
            }),
            samples: self.samples,
        }
    }
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
