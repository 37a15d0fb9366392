//! The correction rounds of the reverse compensation (qiu §4-3(2)),
//! judged per region.
//!
//! One round: rebuild the edited path ([`super::geometry::rebuild`]),
//! simulate it against the ORIGINAL path, and correct the edit with the
//! remaining deviation:
//! - an arc's radius grows by the mean signed radius loss `R − ρ` of the
//!   samples nearest to it (any plane, helices included: the loss is
//!   measured in the arc's plane);
//! - a vertex between two lines moves by the mean contour-error vector
//!   `near − simulated`, per axis X, Y, Z, of the samples nearest to the
//!   half-segments on either side of it (the same model, in any plane and
//!   in 3D: where the tool cuts inside a corner the vector points out of
//!   it and the vertex moves out).
//!
//! Every region (see [`super::region`]) keeps the edit of the round in
//! which its own maximum error was lowest; a region whose error stops
//! falling for two rounds stops being corrected. A round simulates only
//! the windows (rapid to rapid) that hold a region still being corrected,
//! each alone — the cost of a round falls as regions settle; the written
//! program is then checked against the whole original path
//! ([`super::reverse_compensate`]). Regions are separated by
//! rapids (which end in an exact stop) and by fixed segments, so the edit
//! of one region barely changes another's error, and the best rounds of
//! different regions combine.
//!
//! Units: mm, s.

use super::geometry::{rebuild, Edit};
use super::region::{region_errors, Regions};
use crate::budget::{BudgetError, MAX_REVERSE_SIMULATED_SAMPLES};
use crate::nc::program::{Motion, Segment};
use crate::toolpath::{simulate_stats, SegmentStats, SimConfig, ToolpathError};

/// The outcome of the rounds: per region its best error and the edit that
/// gave it.
#[derive(Debug, Clone)]
pub struct Rounds {
    /// The combined edit (each region's best round).
    pub edit: Edit,
    /// Best maximum error per region, mm.
    pub error: Vec<f64>,
    /// Maximum error of the whole path per round, µm.
    pub history_um: Vec<f64>,
}

/// What one compensation may still simulate, in samples
/// ([`crate::budget::MAX_REVERSE_SIMULATED_SAMPLES`]). Correction rounds
/// spend only above a reserve kept for the checks of the written program;
/// the checks may spend the reserve too.
#[derive(Debug, Clone)]
pub struct Work {
    left: u64,
    reserve: u64,
    /// Samples of one simulation of the whole program.
    pub program: u64,
    /// A round or check was skipped for want of budget.
    pub stopped: bool,
}

impl Work {
    /// The budget of one compensation of a program of `program` samples
    /// ([`MAX_REVERSE_SIMULATED_SAMPLES`]).
    ///
    /// # Errors
    /// When the original, one round and two checks would not fit.
    pub fn for_program(program: u64) -> Result<Self, BudgetError> {
        crate::budget::check(
            "reverse compensation",
            program.saturating_mul(4),
            MAX_REVERSE_SIMULATED_SAMPLES,
            "simulated samples (the original, one round and two checks)",
            "raise dt, shorten the program, or compensate it in parts",
        )?;
        Ok(Self::new(MAX_REVERSE_SIMULATED_SAMPLES as u64, program))
    }

    /// What the result says when the budget cut the work short.
    pub fn note(&self) -> Option<String> {
        self.stopped.then(|| {
            format!(
                "the work budget ({MAX_REVERSE_SIMULATED_SAMPLES} simulated samples, {} per simulation of this program) stopped the correction early; the best rounds so far are kept and checked. Raise dt or compensate the program in parts for a full run",
                self.program
            )
        })
    }

    /// `limit` samples in all for a program of `program` samples, of
    /// which the original's simulation is spent at once; two more
    /// simulations of it are kept for the checks.
    pub fn new(limit: u64, program: u64) -> Self {
        Self {
            left: limit.saturating_sub(program),
            reserve: 2 * program,
            program,
            stopped: false,
        }
    }

    /// Samples still to spend (the checks' reserve included).
    pub fn left(&self) -> u64 {
        self.left
    }

    /// Spends `samples` on a correction round when the checks' reserve
    /// stays; otherwise marks the work as stopped and returns `false`.
    pub fn round(&mut self, samples: u64) -> bool {
        self.spend(samples, self.reserve)
    }

    /// Spends `samples` on a check (the reserve included); `false` when
    /// not even that is left.
    pub fn check(&mut self, samples: u64) -> bool {
        self.spend(samples, 0)
    }

    fn spend(&mut self, samples: u64, keep: u64) -> bool {
        if self.left >= samples.saturating_add(keep) {
            self.left -= samples;
            true
        } else {
            self.stopped = true;
            false
        }
    }
}

/// The identity edit of `orig` with `dwell_after`.
pub fn identity(orig: &[Segment], dwell_after: Vec<f64>) -> Edit {
    Edit {
        radius: orig
            .iter()
            .map(|s| match s.motion {
                Motion::Arc(a) => a.radius,
                _ => 0.0,
            })
            .collect(),
        vertex_shift: vec![[0.0; 3]; orig.len()],
        dwell_after,
        spike: vec![[0.0; 3]; orig.len()],
    }
}

/// Copies region `r`'s entries of `from` into `to`.
pub fn copy_region(regions: &Regions, r: usize, from: &Edit, to: &mut Edit) {
    for &i in &regions.members[r] {
        to.radius[i] = from.radius[i];
        to.vertex_shift[i] = from.vertex_shift[i];
        to.dwell_after[i] = from.dwell_after[i];
        to.spike[i] = from.spike[i];
    }
}

/// Runs up to `iterations + 1` rounds from `start` (see the module header),
/// as many as `work` allows: a round costs what the previous one
/// simulated (the whole program for the first); with none affordable the
/// errors stay infinite and `start` is returned.
///
/// # Errors
/// As [`simulate()`](crate::toolpath::simulate()).
pub fn run(
    orig: &[Segment],
    regions: &Regions,
    (cfg, step): (&SimConfig, f64),
    iterations: usize,
    start: Edit,
    work: &mut Work,
) -> Result<Rounds, ToolpathError> {
    let nr = regions.members.len();
    let mut edit = start;
    let mut best = edit.clone();
    let mut best_err = vec![f64::INFINITY; nr];
    let mut stall = vec![0usize; nr];
    let mut history = Vec::new();
    let mut errs = vec![0.0; nr];
    let mut live_window = vec![true; regions.windows.len()];
    let mut cost = work.program;
    for round in 0..=iterations {
        if !work.round(cost) {
            break;
        }
        let (stats, simulated) = simulate_windows(orig, regions, cfg, &edit, &live_window)?;
        cost = simulated;
        let fresh = region_errors(regions, &stats);
        for r in 0..nr {
            if live_window[regions.window[r]] {
                errs[r] = fresh[r];
            }
        }
        // No region, no round to report (the page would show "0 µm").
        if nr > 0 {
            history.push(errs.iter().copied().fold(0.0, f64::max) * 1e3);
        }
        let mut active = false;
        for r in 0..nr {
            if errs[r] < best_err[r] {
                best_err[r] = errs[r];
                copy_region(regions, r, &edit, &mut best);
                stall[r] = 0;
            } else {
                stall[r] += 1;
            }
            active |= stall[r] < 2 && regions.movable[r];
        }
        if round == iterations || !active {
            break;
        }
        live_window.iter_mut().for_each(|w| *w = false);
        for r in 0..nr {
            if stall[r] < 2 && regions.movable[r] {
                live_window[regions.window[r]] = true;
            }
        }
        let by_seg = super::corner::by_segment(&stats, orig.len());
        correct(orig, regions, &by_seg, (&stall, step), &mut edit);
    }
    Ok(Rounds {
        edit: best,
        error: best_err,
        history_um: history,
    })
}

/// Simulates the windows marked `live` of the edited program, each alone
/// against its own original segments (see [`Regions::windows`]); the
/// statistics carry whole-program segment indices, and the number of
/// samples simulated.
///
/// # Errors
/// As [`simulate()`](crate::toolpath::simulate()).
pub fn simulate_windows(
    orig: &[Segment],
    regions: &Regions,
    cfg: &SimConfig,
    edit: &Edit,
    live: &[bool],
) -> Result<(Vec<SegmentStats>, u64), ToolpathError> {
    let mut out = Vec::new();
    let mut samples = 0u64;
    for (w, range) in regions.windows.iter().enumerate() {
        if !live[w] {
            continue;
        }
        let part = Edit {
            radius: edit.radius[range.clone()].to_vec(),
            vertex_shift: edit.vertex_shift[range.clone()].to_vec(),
            dwell_after: edit.dwell_after[range.clone()].to_vec(),
            spike: edit.spike[range.clone()].to_vec(),
        };
        let reference = &orig[range.clone()];
        let segs = rebuild(reference, &part);
        let sim = match simulate_stats(&segs, reference, cfg) {
            Ok(s) => s,
            Err(ToolpathError::Empty) => continue,
            Err(e) => return Err(e),
        };
        samples += sim.samples as u64;
        out.extend(sim.segments.into_iter().map(|mut st| {
            st.segment += range.start;
            st
        }));
    }
    Ok((out, samples))
}

/// The default share of the measured deviation one round corrects
/// ([`super::ReverseConfig::step`]). The full
/// deviation (qiu's reading) overshoots where neighbouring corrections add
/// up (CAM chains of short lines, small arcs between lines: ledfloor's
/// rounds went 120 → 142 → 219 µm). Measured over the corpus (`cargo run
/// --release --example reverse_corpus`, tA 40 ms, T 15 ms, dt 2 ms), the
/// median after/before fell from 0.82 at 1 to 0.68 at 0.5; 0.3, 0.7, and
/// a step halved each round a region's error rose (from 1 or from 0.5)
/// did no better.
pub const DEFAULT_STEP: f64 = 0.5;

/// One correction of `edit` from the per-segment statistics.
fn correct(
    orig: &[Segment],
    regions: &Regions,
    by_seg: &[Option<&SegmentStats>],
    (stall, step): (&[usize], f64),
    edit: &mut Edit,
) {
    let live = |i: usize| {
        regions.of[i].is_some_and(|r| stall[r] < 2) && regions.editable[i] && !orig[i].fixed
    };
    for (i, s) in orig.iter().enumerate() {
        if let (Motion::Arc(_), Some(st)) = (s.motion, by_seg[i]) {
            if live(i) && regions.arc_free[i] {
                edit.radius[i] += step * st.mean_deviation.unwrap_or(0.0);
            }
        }
    }
    for &(i, k) in &regions.line_joints {
        // A spiked corner's correction is its spike (super::corner).
        if !live(i) || !live(k) || super::corner::spiked(edit, i) {
            continue;
        }
        let v: Vec<[f64; 3]> = [
            by_seg[i].and_then(|s| s.half_vector[1]),
            by_seg[k].and_then(|s| s.half_vector[0]),
        ]
        .into_iter()
        .flatten()
        .collect();
        if v.is_empty() {
            continue;
        }
        // As for an offset polyline, a vertex moves 1/cos(φ/2) times the
        // offset of its lines (φ the turn between them).
        let turn_gain = 1.0 / half_turn_cos(&orig[i], &orig[k]).max(0.2);
        for ax in 0..3 {
            let mean = v.iter().map(|x| x[ax]).sum::<f64>() / v.len() as f64;
            edit.vertex_shift[i][ax] += step * turn_gain * mean;
        }
    }
}

/// cos(φ/2) of the turn φ from line `a` to line `b`.
fn half_turn_cos(a: &Segment, b: &Segment) -> f64 {
    let dir = |s: &Segment| {
        let (p, q) = (s.start.p(), s.end.p());
        let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if l > 0.0 {
            [d[0] / l, d[1] / l, d[2] / l]
        } else {
            [0.0; 3]
        }
    };
    let (u, w) = (dir(a), dir(b));
    let c = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
    (0.5 * (1.0 + c)).max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compensate::reverse::region::regions;
    use crate::nc::program::parse;
    use crate::toolpath::{example::arc_example, sample_estimate};

    #[test]
    fn work_keeps_the_checks_reserve_and_checks_may_spend_it() {
        let mut w = Work::new(10, 2); // 8 left after the original, 4 kept
        assert!(w.round(2) && w.round(2)); // 4 left
        assert!(!w.round(1) && w.stopped); // would eat into the reserve
        assert!(w.check(2) && w.check(2)); // the checks spend it
        assert!(!w.check(1));
    }

    #[test]
    fn rounds_stop_at_the_budget_and_keep_their_best() {
        let p = parse(&arc_example()).unwrap();
        let cfg = SimConfig::default();
        let n = sample_estimate(&p.segments, &cfg).unwrap() as u64;
        let rg = regions(&p);
        let start = || identity(&p.segments, vec![0.0; p.segments.len()]);
        // Room for the original, two rounds and the checks' reserve.
        let mut tight = Work::new(5 * n, n);
        let cut = run(&p.segments, &rg, (&cfg, 1.0), 6, start(), &mut tight).unwrap();
        assert!(tight.stopped);
        assert_eq!(cut.history_um.len(), 2, "{:?}", cut.history_um);
        // The same two rounds as an unbudgeted run's first two.
        let mut ample = Work::new(u64::MAX, n);
        let full = run(&p.segments, &rg, (&cfg, 1.0), 6, start(), &mut ample).unwrap();
        assert!(!ample.stopped && full.history_um.len() > 2);
        assert_eq!(cut.history_um[..], full.history_um[..2]);
        // No round affordable: the start edit, errors unknown.
        let mut none = Work::new(3 * n, n);
        let zero = run(&p.segments, &rg, (&cfg, 1.0), 6, start(), &mut none).unwrap();
        assert!(none.stopped && zero.history_um.is_empty());
        assert!(zero.error.iter().all(|e| e.is_infinite()));
    }
}
