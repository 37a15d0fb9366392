//! Corner pre-distortion for reverse compensation — beyond qiu §4-3(2),
//! which corrects arc radii and adds dwells.
//!
//! At a sharp corner the NC's moving average (Eq. 1, length tA) and the
//! servo lag (Eq. 2, T) cut the corner short: at feed `v` through a turn of
//! 90° the moving average alone leaves `v·tA/8` (qiu's filter averages
//! half a window on each leg), the lag adds to it. A dwell removes the
//! error but costs a full stop (about 0.1 s + tA + 5·T per corner), which a
//! pocket's hundreds of corners cannot afford within a +5 % time budget;
//! moving the corner's vertex tilts both legs, which are long, and errs
//! along them by as much as it gains at the corner.
//!
//! What is done instead: a *spike*, two new `G1` lines after the corner's
//! block, out from the corner along the outward bisector of the turn
//! (`u_in − u_out`, normalised) by a depth `d` and straight back. Every
//! source block keeps its text; the filtered path is pulled outward at
//! the corner only. Its cost is its own length, `2·d / v`: about 0.02 s
//! per 90° corner at F1000, tA 40 ms, T 15 ms.
//!
//! The depth, measured by simulating one corner of two 50 mm legs (the
//! team's own search, the same for every case below): the best `d` is
//! linear in `v` (every error of the model is), and close to
//! `c(θ)·v·(tA + 2T)` with `c` = 0.09 at a 20° turn, 0.11 at 30°, 0.14 at
//! 60°, 0.155 at 90°, 0.167 at 120°, 0.173 at 150° (tA 40 ms, T 15 ms;
//! 0.12–0.2 at tA 20 ms, T 30 ms). [`model_depth`] takes
//! `c(θ) = 0.175·sin(θ/2)^0.4`, within 10 % of those, as the start; each
//! corner's depth is then searched per corner by simulation
//! ([`search`]). The maximum error at a lone corner falls to 0.17–0.27 of
//! the original (0.3–0.4 when T is larger than tA); a split of the legs
//! near the corner (a tent of vertex shifts) did no better than the spike
//! and changes source blocks.
//!
//! Reading: the model is the paper's (moving average + first-order lag)
//! and knows no jerk or acceleration limit; on a real control the spike's
//! reversal is itself filtered by the same acc/dec (that is the model), but
//! a control with a corner-rounding tolerance (G64 P, high-speed modes)
//! would round the spike away. The spike's length stays within 2·d of the
//! corner, below 0.2·v·(tA + 2T).
//!
//! Units: mm, s.

use super::geometry::Edit;
use super::region::Regions;
use super::rounds::{LocalStats, Work};
use crate::nc::program::{Motion, Segment};
use crate::toolpath::{SegmentStats, SimConfig, ToolpathError, WindowStats};

/// The smallest turn a spike is tried at, rad (as a dwell's corner,
/// [`super::CORNER_TURN`]).
pub const SPIKE_TURN: f64 = super::CORNER_TURN;

/// One sharp corner between two cutting moves of one region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corner {
    /// The segment that ends at the corner (the spike follows it).
    pub seg: usize,
    /// The segment that starts there.
    pub next: usize,
    /// Outward bisector of the turn (unit).
    pub out: [f64; 3],
    /// Turn angle, rad.
    pub turn: f64,
    /// Start depth ([`model_depth`]), mm.
    pub depth: f64,
}

/// Unit direction of `s` at its end (`at_end`) or start.
pub fn tangent(s: &Segment, at_end: bool) -> Option<[f64; 3]> {
    let (a, b) = if at_end {
        (1.0 - 1e-6, 1.0)
    } else {
        (0.0, 1e-6)
    };
    let (p, q) = (s.point_at(a), s.point_at(b));
    unit([q[0] - p[0], q[1] - p[1], q[2] - p[2]])
}

fn unit(d: [f64; 3]) -> Option<[f64; 3]> {
    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    (l > 0.0 && l.is_finite()).then(|| [d[0] / l, d[1] / l, d[2] / l])
}

/// The start depth of a spike at a turn of `turn` rad at `v` mm/s:
/// `0.175·sin(turn/2)^0.4·v·(tA + 2·T)` (see the module header), mm.
pub fn model_depth(turn: f64, v: f64, t_a: f64, t: f64) -> f64 {
    0.175 * (0.5 * turn).sin().max(0.0).powf(0.4) * v * (t_a + 2.0 * t)
}

/// The corners of `orig` a spike may follow: a joint between two
/// consecutive cutting moves of one region that turns by more than
/// [`SPIKE_TURN`], whose next segment's block can be rewritten (so a line
/// may be written before it) and is not the one ending at the corner, with
/// no dwell between them.
pub fn corners(orig: &[Segment], rg: &Regions, cfg: &SimConfig) -> Vec<Corner> {
    let tmax = cfg.t.per_axis().into_iter().fold(0.0, f64::max);
    (1..orig.len())
        .filter_map(|k| {
            let i = k - 1;
            let (a, b) = (&orig[i], &orig[k]);
            if !(a.is_cutting() && b.is_cutting())
                || rg.of[i].is_none()
                || rg.of[i] != rg.of[k]
                || !rg.editable[i]
                || !rg.editable[k]
                || a.block == b.block
            {
                return None;
            }
            // A short arc (shorter than the filter's reach) turns like a
            // corner: its turn is counted from its far end.
            let v = a.feed * cfg.feed_override / 60.0;
            let short = |s: &Segment| {
                matches!(s.motion, Motion::Arc(_))
                    && s.length() < s.feed * cfg.feed_override / 60.0 * cfg.t_a
            };
            let (u, w) = (tangent(a, !short(a))?, tangent(b, short(b))?);
            let c = (u[0] * w[0] + u[1] * w[1] + u[2] * w[2]).clamp(-1.0, 1.0);
            let turn = c.acos();
            if turn <= SPIKE_TURN {
                return None;
            }
            let out = unit([u[0] - w[0], u[1] - w[1], u[2] - w[2]])?;
            let depth = model_depth(turn, v, cfg.t_a, tmax);
            (depth.is_finite() && depth > 0.0).then_some(Corner {
                seg: i,
                next: k,
                out,
                turn,
                depth,
            })
        })
        .collect()
}

/// The error at corner `c` in statistics indexed by segment: the larger
/// of the last half of the segment before it and the first half of the
/// one after, mm.
pub fn corner_error(c: &Corner, by_seg: &[Option<&WindowStats>]) -> f64 {
    let half = |i: usize, h: usize| {
        by_seg
            .get(i)
            .copied()
            .flatten()
            .map_or(0.0, |s| s.half_max[h])
    };
    half(c.seg, 1).max(half(c.next, 0))
}

/// The statistics of `stats` by segment index, over `n` segments.
pub fn by_segment(stats: &[SegmentStats], n: usize) -> Vec<Option<&SegmentStats>> {
    let mut by = vec![None; n];
    for st in stats {
        if let Some(slot) = by.get_mut(st.segment) {
            *slot = Some(st);
        }
    }
    by
}

/// The scales of the start depth tried, round by round: three first, then
/// around each corner's best so far, by ±0.15 and ±0.075.
const FIRST: [f64; 3] = [1.0, 0.7, 1.3];
const STEPS: [f64; 2] = [0.15, 0.075];

/// The outcome of [`search`].
#[derive(Debug, Clone)]
pub struct Spikes {
    /// `start` with each corner's best spike (none where none helped).
    pub edit: Edit,
    /// Maximum error of the whole path per round, µm.
    pub history_um: Vec<f64>,
}

/// Searches each corner's spike depth by simulation (see the module
/// header). All corners are tried at once, each with its own scale of its
/// [`model_depth`]: 1, 0.7 and 1.3, then its best ± 0.15 and ± 0.075. A
/// corner keeps the scale with the lowest [`corner_error`], and no spike
/// when none was below its error without one (`before`, the original
/// simulation's statistics). Neighbouring corners filter into each
/// other's error, so a corner's best is judged with its neighbours at
/// their trial depths of the same round; searching a cluster of close
/// corners with one common scale did worse on the corpus (median
/// after/before 0.82 against 0.68), and the written program is checked
/// as a whole afterwards ([`super::reverse_compensate`]). Corners are
/// taken largest error first while their spikes' added length, at most
/// `2·1.45·d/v` each, fits `time_left` s; corners with a dwell in `start`
/// are left out. Rounds stop when they would spend more than a third of
/// the `work` left at the start.
///
/// # Errors
/// As [`crate::toolpath::simulate()`].
#[allow(clippy::too_many_arguments)]
pub fn search(
    orig: &[Segment],
    cfg: &SimConfig,
    found: &[Corner],
    before: &[Option<WindowStats>],
    start: &Edit,
    time_left: f64,
    work: &mut Work,
) -> Result<Spikes, ToolpathError> {
    let by0: Vec<Option<&WindowStats>> = before.iter().map(Option::as_ref).collect();
    let found: Vec<Corner> = found
        .iter()
        .copied()
        .filter(|c| start.dwell_after[c.seg] == 0.0)
        .collect();
    let mut order: Vec<(f64, usize)> = (0..found.len())
        .map(|n| (corner_error(&found[n], &by0), n))
        .filter(|(e, _)| *e > 0.0)
        .collect();
    order.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut budget = time_left;
    let mut chosen: Vec<(&Corner, f64)> = Vec::new();
    for (e, n) in order {
        let c = &found[n];
        let cost = 1.45 * spike_time(&orig[c.seg], cfg, c.out.map(|x| x * c.depth));
        if cost <= budget {
            budget -= cost;
            chosen.push((c, e));
        }
    }
    // Per corner: the best scale so far (0: none) and its error.
    let mut best: Vec<(f64, f64)> = chosen.iter().map(|(_, e)| (0.0, *e)).collect();
    let mut edit = start.clone();
    let set = |edit: &mut Edit, c: &Corner, s: f64| {
        edit.spike[c.seg] = c.out.map(|x| x * s * c.depth);
    };
    let mut local = LocalStats::new(orig, work);
    let mut history = Vec::new();
    // The search spends at most a third of the work left, so that the
    // correction rounds, dwells and checks after it still run.
    let floor = work.left() - work.left() / 3;
    for round in 0..FIRST.len() + 2 * STEPS.len() {
        if chosen.is_empty() || work.left() < floor {
            break;
        }
        let scales: Vec<f64> = best.iter().map(|&(b, _)| trial_scale(round, b)).collect();
        for (&(c, _), &s) in chosen.iter().zip(&scales) {
            set(&mut edit, c, s);
        }
        if !local.update(orig, cfg, &edit, work)? {
            break;
        }
        let by: Vec<Option<&WindowStats>> = local.by_seg.iter().map(Option::as_ref).collect();
        history.push(
            by.iter()
                .flatten()
                .map(|s| s.max_error_um)
                .fold(0.0, f64::max),
        );
        for ((&(c, _), &s), b) in chosen.iter().zip(&scales).zip(best.iter_mut()) {
            let e = corner_error(c, &by);
            if e < b.1 {
                *b = (s, e);
            }
        }
    }
    for (&(c, _), &(s, _)) in chosen.iter().zip(&best) {
        set(&mut edit, c, s);
    }
    Ok(Spikes {
        edit,
        history_um: history,
    })
}

/// True when segment `i` of `orig` is a line whose end is a spiked corner
/// in `edit` (its vertex is then not shifted by the rounds).
pub fn spiked(edit: &Edit, i: usize) -> bool {
    edit.spike.get(i).is_some_and(|s| *s != [0.0; 3])
}

/// The scale of the start depth that round `round` tries at a corner
/// whose best scale so far is `best` (0: no spike yet did better than
/// none, then the search goes on around 0.4).
fn trial_scale(round: usize, best: f64) -> f64 {
    if let Some(&s) = FIRST.get(round) {
        return s;
    }
    let k = round - FIRST.len();
    let step = STEPS[(k / 2).min(STEPS.len() - 1)];
    let base = if best > 0.0 { best } else { 0.4 };
    (base + if k % 2 == 0 { -step } else { step }).max(0.05)
}

/// The motion time a spike reaching `d` (mm) out from the end of `s` adds
/// by its length, `2·|d|/v` at `s`'s feed, s (0 for no spike).
pub fn spike_time(s: &Segment, cfg: &SimConfig, d: [f64; 3]) -> f64 {
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if len == 0.0 {
        return 0.0;
    }
    2.0 * len / (s.feed * cfg.feed_override / 60.0)
}

/// The motion time the spikes of `edit` add by their length
/// ([`spike_time`] summed), s.
pub fn added_time(orig: &[Segment], cfg: &SimConfig, edit: &Edit) -> f64 {
    orig.iter()
        .zip(&edit.spike)
        .map(|(s, &d)| spike_time(s, cfg, d))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compensate::reverse::geometry::rebuild;
    use crate::compensate::reverse::region::regions;
    use crate::compensate::reverse::rounds::identity;
    use crate::nc::program::parse;
    use crate::toolpath::Lag;

    fn cfg() -> SimConfig {
        SimConfig {
            t_a: 0.04,
            t: Lag::All(0.015),
            ..SimConfig::default()
        }
    }

    #[test]
    fn model_depth_follows_the_measured_table() {
        // c(θ)·v·(tA + 2T) at F1000 (16.67 mm/s), tA 40 ms, T 15 ms: the
        // module's searched best depths 0.108 (20°), 0.182 (90°), 0.201 mm
        // (150°) within 10 %.
        let v = 1000.0 / 60.0;
        for (deg, best) in [(20.0f64, 0.1078), (90.0, 0.1813), (150.0, 0.2014)] {
            let d = model_depth(deg.to_radians(), v, 0.04, 0.015);
            assert!((d / best - 1.0).abs() < 0.1, "{deg}: {d} vs {best}");
        }
        // exactly: 0.175·sin(45°)^0.4·v·0.07
        let d = model_depth(std::f64::consts::FRAC_PI_2, v, 0.04, 0.015);
        assert!((d - 0.175 * 0.5f64.sqrt().powf(0.4) * v * 0.07).abs() < 1e-12);
        assert_eq!(model_depth(0.0, v, 0.04, 0.015), 0.0);
    }

    #[test]
    fn corners_are_sharp_joints_of_one_region_with_the_outward_bisector() {
        // A 90° turn, a 5° turn (no corner), a 120° turn, then a rapid
        // (no corner across it), then a lone line.
        let p = parse(
            "G21 G90\nG0 X2 Y1\nG1 X12 Y1 F1200\nG1 X12 Y11\nG1 X12.8749 Y20.9617\nG1 X4.2146 Y15.9617\nG0 X30\nG1 X40 Y30\n",
        )
        .unwrap();
        let rg = regions(&p);
        let c = corners(&p.segments, &rg, &cfg());
        let at: Vec<usize> = c.iter().map(|c| p.segments[c.seg].line).collect();
        assert_eq!(at, vec![3, 5], "{c:?}");
        // 90°: out = (u_in − u_out)/|…| = (1, −1)/√2.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((c[0].out[0] - h).abs() < 1e-9 && (c[0].out[1] + h).abs() < 1e-9);
        assert!((c[0].turn.to_degrees() - 90.0).abs() < 1e-6);
        assert!(
            (c[1].turn.to_degrees() - 125.0).abs() < 0.1,
            "{}",
            c[1].turn.to_degrees()
        );
        assert!((c[0].depth - model_depth(c[0].turn, 20.0, 0.04, 0.015)).abs() < 1e-12);
    }

    #[test]
    fn corners_need_rewritable_blocks_on_both_sides_and_scale_with_the_override() {
        let src =
            "G21 G90\nG0 X2 Y1\nG1 X12 Y1 F1200\nG1 X12 Y11\nG1 X2 Y11\nG1 X2 Y21\nG1 X12 Y21\n";
        let p = parse(src).unwrap();
        let all = corners(&p.segments, &regions(&p), &cfg());
        let lines = |c: &[Corner]| c.iter().map(|c| p.segments[c.seg].line).collect::<Vec<_>>();
        assert_eq!(lines(&all), vec![3, 4, 5, 6]);
        // Line 5 outside the lines to compensate: no spike after line 4
        // (before it) nor after line 5 (its own end).
        let part = crate::compensate::reverse::region::regions_in(&p, &|l| l != 5);
        assert_eq!(lines(&corners(&p.segments, &part, &cfg())), vec![3, 6]);
        // At half the feed (override 0.5) half the depth.
        let slow = SimConfig {
            feed_override: 0.5,
            ..cfg()
        };
        let half = corners(&p.segments, &regions(&p), &slow);
        for (a, b) in all.iter().zip(&half) {
            assert!((b.depth - 0.5 * a.depth).abs() < 1e-12, "{a:?} {b:?}");
        }
    }

    #[test]
    fn a_corner_in_3d_turns_and_points_out_in_3d() {
        // From (1, 0, 1)/√2 to (0, 1, 1)/√2: a 60° turn, out along
        // (1, −1, 0)/√2; then straight down into Z: out has a Z part.
        let p = parse("G21 G90\nG0 X3 Y2 Z1\nG1 X13 Y2 Z11 F1200\nG1 X13 Y12 Z21\nG1 X13 Y12 Z1\n")
            .unwrap();
        let c = corners(&p.segments, &regions(&p), &cfg());
        assert_eq!(c.len(), 2, "{c:?}");
        assert!((c[0].turn.to_degrees() - 60.0).abs() < 1e-6, "{c:?}");
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!(
            (c[0].out[0] - h).abs() < 1e-9
                && (c[0].out[1] + h).abs() < 1e-9
                && c[0].out[2].abs() < 1e-9
        );
        // (0, 1, 1)/√2 to (0, 0, −1): 135°, out ∝ (0, 1/√2, 1/√2 + 1).
        assert!((c[1].turn.to_degrees() - 135.0).abs() < 1e-6, "{c:?}");
        let n = (0.5f64 + (h + 1.0) * (h + 1.0)).sqrt();
        assert!((c[1].out[1] - h / n).abs() < 1e-9 && (c[1].out[2] - (h + 1.0) / n).abs() < 1e-9);
    }

    #[test]
    fn a_short_arc_turns_like_a_corner_a_long_one_does_not() {
        // R0.2 quarter arc (0.31 mm, below v·tA = 0.67 mm at F1000): both
        // its joints are corners of 90°; an R20 quarter arc is not.
        // R0.5 (0.785 mm) is short only at override 2 (v·tA 1.33 mm).
        for (r, ov, n) in [(0.2, 1.0, 2), (20.0, 1.0, 0), (0.5, 1.0, 0), (0.5, 2.0, 2)] {
            let p = parse(&format!(
                "G21 G90\nG0 X0 Y0\nG1 X50 F1000\nG3 X{} Y{r} J{r}\nG1 Y50\n",
                50.0 + r
            ))
            .unwrap();
            let k = SimConfig {
                feed_override: ov,
                ..cfg()
            };
            let c = corners(&p.segments, &regions(&p), &k);
            assert_eq!(c.len(), n, "R{r}: {c:?}");
            for k in &c {
                assert!((k.turn.to_degrees() - 90.0).abs() < 1e-3, "{k:?}");
            }
        }
    }

    #[test]
    fn a_spike_is_two_lines_out_and_back_at_the_feed_before_it() {
        let p = parse("G21 G90\nG0 X2 Y1\nG1 X12 Y1 F1200\nG1 X12 Y11 F600\n").unwrap();
        let mut e = identity(&p.segments, vec![0.0; p.segments.len()]);
        e.spike[1] = [0.1, -0.2, 0.0];
        let out = rebuild(&p.segments, &e);
        assert_eq!(out.len(), p.segments.len() + 2);
        let (tip, back) = (&out[2], &out[3]);
        assert_eq!(tip.block, None);
        assert_eq!(tip.start.p(), [12.0, 1.0, 0.0]);
        assert!((tip.end.p()[0] - 12.1).abs() < 1e-12 && (tip.end.p()[1] - 0.8).abs() < 1e-12);
        assert_eq!(back.end.p(), [12.0, 1.0, 0.0]);
        assert_eq!((tip.feed, back.feed), (1200.0, 1200.0));
        assert_eq!(out[4].start.p(), [12.0, 1.0, 0.0]);
        // 2·|d|/v: 2 × 0.2236 mm at 20 mm/s.
        let t = added_time(&p.segments, &cfg(), &e);
        assert!((t - 2.0 * 0.05f64.sqrt() / 20.0).abs() < 1e-12, "{t}");
    }

    #[test]
    fn trial_scales_run_the_grid_then_about_the_best() {
        assert_eq!(
            (0..3).map(|r| trial_scale(r, 0.0)).collect::<Vec<_>>(),
            FIRST
        );
        assert_eq!(trial_scale(3, 1.3), 1.3 - 0.15);
        assert_eq!(trial_scale(4, 1.3), 1.3 + 0.15);
        assert_eq!(trial_scale(5, 0.7), 0.7 - 0.075);
        assert_eq!(trial_scale(6, 0.7), 0.7 + 0.075);
        // No spike better than none yet: the search goes on about 0.4.
        assert_eq!(trial_scale(3, 0.0), 0.4 - 0.15);
        assert_eq!(trial_scale(6, 0.0), 0.4 + 0.075);
        assert_eq!(trial_scale(5, 0.1), 0.05);
    }
}
