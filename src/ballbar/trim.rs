//! Trimming of ball-bar and contour traces to the constant-feed part (the
//! speed plateau): lead-in, lead-out, standstill, transients and overshoot
//! arcs are left out, and the feed is the plateau's median speed.
//!
//! Source: ball-bar practice (Renishaw QC10/QC20 test set-up; ISO 230-4
//! §5.2 "the data shall be taken at constant feed"): the machine runs an
//! overshoot arc to reach the feed, the analysis covers the data arc only
//! (360° per direction), and the feed is the programmed constant one.
//!
//! Rule (readings chosen; no standard states one for a raw capture):
//! - time: the trace's time column; without one, the sample index (uniform
//!   sampling assumed, and the trace says so: the plateau still trims, the
//!   feed stays unknown);
//! - speed of sample i of a direction segment (the runs split by the
//!   direction column or the turning points): the windowed angle
//!   difference s·(θ[i+h] − θ[i−h]) / (t[i+h] − t[i−h]), s = +1 CCW, −1 CW,
//!   the window clamped to the segment (so a reversal does not slow its
//!   neighbours), h = n/1000 samples, at least 2 and at most 50 (n: samples
//!   of the trace; 20 ms at 1 kHz for a 20 s capture): noise of the angle
//!   enters divided by 2h samples' travel;
//! - moving: speed above [`MOVING`] (20 %) of the reference speed, the
//!   99th percentile of the speeds (robust to a few wild samples); a
//!   trimmed sample below [`STANDSTILL`] (1 %) of it is listed as
//!   standstill (an acceleration from rest is lead-in from its start);
//! - plateau: speed within ±[`BAND`] (5 %) of the median speed of the
//!   moving samples of its direction; a gap off the plateau no longer than
//!   the window (2h samples) inside a run is noise and kept;
//! - a run keeps its plateau samples from the first to the last; what lies
//!   before is lead-in, after it lead-out, a longer gap inside is a
//!   transient (standstill where not moving); a standstill therefore
//!   neither splits a run nor survives as one;
//! - overshoot: a run whose kept arc exceeds whole revolutions by more than
//!   1° keeps the central whole revolutions (the data arc; one at least)
//!   and the excess, half at each end, is trimmed as overshoot;
//! - a segment with fewer than [`super::trace_import::MIN_RUN`] plateau
//!   samples is trimmed whole (short);
//! - feed: the median plateau speed × the nominal radius (time column only).
//!
//! Units: angle rad, time s (or samples: [`TimeBase::SampleIndex`]),
//! plateau speed rad/s (or rad per sample).

use serde::{Deserialize, Serialize};

use super::trace_import::{Direction, MIN_RUN};

/// Plateau band: a sample's speed within ±5 % of the median moving speed.
pub const BAND: f64 = 0.05;
/// Moving threshold, a fraction of the reference (99th percentile) speed.
pub const MOVING: f64 = 0.2;
/// Standstill threshold, a fraction of the reference speed (noise at rest
/// stays far below it; an acceleration passes it within 1 % of its time).
pub const STANDSTILL: f64 = 0.01;
/// Overshoot tolerance: an arc longer than whole revolutions by at most
/// this (1°, rad) is kept whole.
const OVERSHOOT_TOL: f64 = 1.0 * (std::f64::consts::PI / 180.0);

/// What the trace's time is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum TimeBase {
    /// The trace's time column, s.
    Column,
    /// No time column: the sample index (uniform sampling assumed).
    SampleIndex,
}

/// Why a stretch of samples was left out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum TrimReason {
    /// Before the plateau of a run, moving (acceleration, lead-in arc).
    LeadIn,
    /// After the plateau of a run, moving (deceleration, lead-out arc).
    LeadOut,
    /// Not moving (below the moving threshold).
    Standstill,
    /// Off the plateau inside a run, moving.
    Transient,
    /// Beyond the whole revolutions of a run (the data arc).
    Overshoot,
    /// A segment with too few plateau samples to be a run.
    Short,
}

/// A stretch of samples left out.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Trimmed {
    /// Why.
    pub reason: TrimReason,
    /// Source line of the first sample.
    pub first_line: usize,
    /// Source line of the last sample.
    pub last_line: usize,
    /// Samples in the stretch.
    pub samples: usize,
    /// Time of the first sample, s (sample index with [`TimeBase::SampleIndex`]).
    pub start_time: f64,
    /// Time of the last sample, as `start_time`.
    pub end_time: f64,
    /// Angle of the first sample, rad (unwrapped).
    pub start_angle: f64,
    /// Angle of the last sample, rad (unwrapped).
    pub end_angle: f64,
}

/// What trimming did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Trimming {
    /// The time base used.
    pub time_base: TimeBase,
    /// Whether the stretches were left out (false: found and listed only).
    pub applied: bool,
    /// Plateau band, relative (0.05 = ±5 %).
    pub band: f64,
    /// Median plateau speed, rad/s (rad per sample with
    /// [`TimeBase::SampleIndex`]); 0 when nothing moves.
    pub plateau_speed: f64,
    /// Half-width of the speed window, samples.
    pub half_window: usize,
    /// The stretches left out, in file order within each segment.
    pub trimmed: Vec<Trimmed>,
}

/// A direction segment: first sample, end (exclusive), direction.
pub type Segment = (usize, usize, Direction);

/// The kept sample indices of each run, with its direction.
pub type KeptRun = (Direction, Vec<usize>);

/// The half-width of the speed window for a trace of `n` samples.
pub fn half_window(n: usize) -> usize {
    (n / 1000).clamp(2, 50)
}

/// Trims each direction segment to its speed plateau (module header).
/// `angle` unwrapped (rad), `time` increasing (s or samples), `lines` the
/// source line of each sample; with `apply` false the stretches are found
/// and listed but every segment is kept whole (segments shorter than
/// [`MIN_RUN`] are dropped either way).
///
/// # Units
/// Angle rad, time s (or samples).
///
/// # Examples
/// ```
/// use mtmotion::ballbar::trim::{trim, TimeBase, TrimReason};
/// use mtmotion::ballbar::Direction;
/// // 100 samples at rest, then 400 at 0.01 rad per sample.
/// let angle: Vec<f64> = (0..500).map(|i| if i < 100 { 0.0 } else { (i - 100) as f64 * 0.01 }).collect();
/// let time: Vec<f64> = (0..500).map(|i| i as f64).collect();
/// let lines: Vec<usize> = (2..502).collect();
/// let (runs, t) = trim(&angle, &time, &lines, &[(0, 500, Direction::Ccw)], TimeBase::SampleIndex, true);
/// assert_eq!(runs.len(), 1);
/// assert!((t.plateau_speed - 0.01).abs() < 1e-12);
/// assert_eq!(t.trimmed[0].reason, TrimReason::Standstill);
/// assert!(runs[0].1[0] >= 100 && runs[0].1[0] <= 103);
/// ```
pub fn trim(
    angle: &[f64],
    time: &[f64],
    lines: &[usize],
    segments: &[Segment],
    time_base: TimeBase,
    apply: bool,
) -> (Vec<KeptRun>, Trimming) {
    let h = half_window(angle.len());
    let speeds: Vec<Vec<f64>> = segments
        .iter()
        .map(|&(a, b, d)| {
            (a..b)
                .map(|i| {
                    let (lo, hi) = (i.saturating_sub(h).max(a), (i + h).min(b - 1));
                    let dt = time[hi] - time[lo];
                    if dt > 0.0 {
                        d.sign() * (angle[hi] - angle[lo]) / dt
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect();
    let mut all: Vec<f64> = speeds
        .iter()
        .flatten()
        .copied()
        .filter(|v| *v > 0.0)
        .collect();
    all.sort_by(f64::total_cmp);
    let reference = quantile(&all, 0.99);
    let moving = MOVING * reference;
    let median_of = |d: Direction| {
        let mut v: Vec<f64> = segments
            .iter()
            .zip(&speeds)
            .filter(|((_, _, e), _)| *e == d)
            .flat_map(|(_, s)| s.iter().copied().filter(|v| *v > moving && moving > 0.0))
            .collect();
        v.sort_by(f64::total_cmp);
        quantile(&v, 0.5)
    };
    let medians = [median_of(Direction::Ccw), median_of(Direction::Cw)];
    let mut ctx = Ctx {
        angle,
        time,
        lines,
        still: STANDSTILL * reference,
        out: Vec::new(),
    };
    let mut runs = Vec::new();
    let mut plateau = Vec::new();
    for (&(a, b, d), v) in segments.iter().zip(&speeds) {
        let med = medians[usize::from(d == Direction::Cw)];
        let on = |j: usize| med > 0.0 && (v[j] - med).abs() <= BAND * med;
        let kept = segment_plateau(a, b, h, &on);
        if kept.len() < MIN_RUN {
            if b > a {
                ctx.label(a, b - 1, TrimReason::Short, v, a);
            }
            continue;
        }
        let (first, last) = (kept[0], kept[kept.len() - 1]);
        if first > a {
            ctx.label(a, first - 1, TrimReason::LeadIn, v, a);
        }
        // Interior gaps longer than the window.
        for w in kept.windows(2) {
            if w[1] > w[0] + 1 {
                ctx.label(w[0] + 1, w[1] - 1, TrimReason::Transient, v, a);
            }
        }
        let kept = ctx.overshoot(kept);
        plateau.extend(kept.iter().map(|&i| v[i - a]));
        if last + 1 < b {
            ctx.label(last + 1, b - 1, TrimReason::LeadOut, v, a);
        }
        runs.push((d, if apply { kept } else { (a..b).collect() }));
    }
    plateau.sort_by(f64::total_cmp);
    let trimming = Trimming {
        time_base,
        applied: apply,
        band: BAND,
        plateau_speed: quantile(&plateau, 0.5),
        half_window: h,
        trimmed: ctx.out,
    };
    (runs, trimming)
}

/// The `q` quantile (0 … 1) of sorted values by the nearest rank below; 0
/// when empty.
fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

/// The plateau samples of segment a..b (`on(j)` for j = i − a), with the
/// gaps of at most 2h samples between them filled (noise, not a pause).
fn segment_plateau(a: usize, b: usize, h: usize, on: &dyn Fn(usize) -> bool) -> Vec<usize> {
    let mut kept: Vec<usize> = Vec::new();
    for i in a..b {
        if !on(i - a) {
            continue;
        }
        if let Some(&prev) = kept.last() {
            if i > prev + 1 && i - prev - 1 <= 2 * h {
                kept.extend(prev + 1..i);
            }
        }
        kept.push(i);
    }
    kept
}

/// The trace and the stretches found so far.
struct Ctx<'a> {
    angle: &'a [f64],
    time: &'a [f64],
    lines: &'a [usize],
    still: f64,
    out: Vec<Trimmed>,
}

impl Ctx<'_> {
    fn push(&mut self, i0: usize, i1: usize, reason: TrimReason) {
        self.out.push(Trimmed {
            reason,
            first_line: self.lines[i0],
            last_line: self.lines[i1],
            samples: i1 + 1 - i0,
            start_time: self.time[i0],
            end_time: self.time[i1],
            start_angle: self.angle[i0],
            end_angle: self.angle[i1],
        });
    }

    /// Records samples i0..=i1 of a segment starting at `a` (speeds `v`),
    /// split into standstill and moving stretches; the moving ones get
    /// `reason` (a short segment stays short throughout).
    fn label(&mut self, i0: usize, i1: usize, reason: TrimReason, v: &[f64], a: usize) {
        let limit = self.still;
        let still = |i: usize| reason != TrimReason::Short && v[i - a] <= limit;
        let mut start = i0;
        for i in i0..=i1 {
            if i == i1 || still(i + 1) != still(i) {
                let r = if still(i) {
                    TrimReason::Standstill
                } else {
                    reason
                };
                self.push(start, i, r);
                start = i + 1;
            }
        }
    }

    /// The central whole revolutions of a run's kept samples, the excess
    /// recorded as overshoot (module header).
    fn overshoot(&mut self, kept: Vec<usize>) -> Vec<usize> {
        let tau = std::f64::consts::TAU;
        let (t0, t1) = (self.angle[kept[0]], self.angle[kept[kept.len() - 1]]);
        let span = (t1 - t0).abs();
        let revs = (span / tau).floor().max(1.0);
        let excess = span - revs * tau;
        if excess <= OVERSHOOT_TOL {
            return kept;
        }
        let (lo, hi) = (t0.min(t1) + excess / 2.0, t0.max(t1) - excess / 2.0);
        let inside = |i: &usize| (lo..=hi).contains(&self.angle[*i]);
        let first = kept.iter().position(inside).unwrap_or(0);
        let last = kept.iter().rposition(inside).unwrap_or(kept.len() - 1);
        if first > 0 {
            self.push(kept[0], kept[first - 1], TrimReason::Overshoot);
        }
        if last + 1 < kept.len() {
            self.push(kept[last + 1], kept[kept.len() - 1], TrimReason::Overshoot);
        }
        kept[first..=last].to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(n: usize) -> Vec<usize> {
        (2..n + 2).collect()
    }

    #[test]
    fn a_standstill_between_directions_is_trimmed_not_a_run() {
        // CCW 0 → 2π in 600 samples, 300 at rest, CW back in 600.
        let step = std::f64::consts::TAU / 600.0;
        let mut angle: Vec<f64> = (0..=600).map(|i| i as f64 * step).collect();
        angle.extend(std::iter::repeat_n(std::f64::consts::TAU, 300));
        angle.extend((1..=600).map(|i| std::f64::consts::TAU - i as f64 * step));
        let n = angle.len();
        let time: Vec<f64> = (0..n).map(|i| i as f64 * 1e-3).collect();
        let segs = [(0, 901, Direction::Ccw), (900, n, Direction::Cw)];
        let (runs, t) = trim(&angle, &time, &lines(n), &segs, TimeBase::Column, true);
        assert_eq!(runs.len(), 2);
        // The standstill is the lead-out of the CCW segment.
        let still: Vec<_> = t
            .trimmed
            .iter()
            .filter(|s| s.reason == TrimReason::Standstill)
            .collect();
        assert_eq!(still.len(), 1, "{:?}", t.trimmed);
        assert!(
            still[0].samples >= 298 && still[0].samples <= 302,
            "{still:?}"
        );
        assert!((t.plateau_speed - step / 1e-3).abs() < 1e-9 * step / 1e-3);
        // The CCW run keeps the whole revolution but the last window.
        assert!(
            runs[0].1.len() > 590 && runs[0].1[0] == 0,
            "{}",
            runs[0].1.len()
        );
        // Not applied: found, listed, nothing dropped.
        let (whole, u) = trim(&angle, &time, &lines(n), &segs, TimeBase::Column, false);
        assert_eq!(whole[0].1.len(), 901);
        assert!(!u.applied && u.trimmed == t.trimmed);
    }

    #[test]
    fn an_arc_past_a_revolution_keeps_its_central_revolution() {
        // 450° at constant speed from 30°: 45° overshoot at each end.
        let n = 451;
        let angle: Vec<f64> = (0..n).map(|i| (30.0 + i as f64).to_radians()).collect();
        let time: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let (runs, t) = trim(
            &angle,
            &time,
            &lines(n),
            &[(0, n, Direction::Ccw)],
            TimeBase::SampleIndex,
            true,
        );
        let k = &runs[0].1;
        assert_eq!((k[0], k[k.len() - 1]), (45, 405));
        assert_eq!(t.trimmed.len(), 2);
        assert!(t.trimmed.iter().all(|s| s.reason == TrimReason::Overshoot));
        assert_eq!((t.trimmed[0].first_line, t.trimmed[0].samples), (2, 45));
        assert_eq!((t.trimmed[1].first_line, t.trimmed[1].samples), (408, 45));
        // 360.5° is within the tolerance: kept whole.
        let angle: Vec<f64> = (0..=721).map(|i| (i as f64 * 0.5).to_radians()).collect();
        let time: Vec<f64> = (0..=721).map(|i| i as f64).collect();
        let (runs, t) = trim(
            &angle,
            &time,
            &lines(722),
            &[(0, 722, Direction::Ccw)],
            TimeBase::SampleIndex,
            true,
        );
        assert_eq!(runs[0].1.len(), 722);
        assert!(t.trimmed.is_empty());
    }

    #[test]
    fn a_short_wiggle_is_trimmed_whole_and_nothing_moving_keeps_nothing() {
        let angle = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5];
        let time = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let (runs, t) = trim(
            &angle,
            &time,
            &lines(6),
            &[(0, 6, Direction::Ccw)],
            TimeBase::Column,
            true,
        );
        assert!(runs.is_empty());
        assert_eq!(t.trimmed[0].reason, TrimReason::Short);
        assert_eq!(t.trimmed[0].samples, 6);
        let still = [0.0; 20];
        let time: Vec<f64> = (0..20).map(f64::from).collect();
        let (runs, t) = trim(
            &still,
            &time,
            &lines(20),
            &[(0, 20, Direction::Ccw)],
            TimeBase::Column,
            true,
        );
        assert!(runs.is_empty() && t.plateau_speed == 0.0);
    }

    #[test]
    fn quantiles_and_windows() {
        assert_eq!(quantile(&[], 0.5), 0.0);
        assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0, 5.0], 0.5), 3.0);
        assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0, 5.0], 1.0), 5.0);
        assert_eq!(
            (
                half_window(10),
                half_window(7000),
                half_window(1e6 as usize)
            ),
            (2, 7, 50)
        );
    }
}
