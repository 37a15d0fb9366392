//! Reverse compensation of the NC program (qiu §4-3(2)), safe on real
//! programs.
//!
//! The paper's method, for arc programs: simulate the program (§4-2), take
//! each arc's mean radius loss `Δrᵢ` over the samples nearest to it, give
//! the arc the radius `Rᵢ + |Δrᵢ|` about the same centre, recompute the
//! joints between segments ([`geometry`]), and write the new program. Where
//! short segments cluster the servo's delay limits the effect, so the paper
//! adds 0.1 s dwells at B and D and compensates again: 63.1 µm → 18.2 µm,
//! motion time 11.018 s → 11.445 s.
//!
//! Readings and extensions:
//! - the loss is signed (`Rᵢ − ρ`, positive inside) rather than its
//!   absolute value, so an arc that overshoots is pulled in, not pushed out;
//!   arcs in G17, G18 and G19 and helices are treated alike (the loss is
//!   measured in the arc's plane, the centre and the helix rise are kept);
//! - *iteration* and *lines*: see [`rounds`] — the compensated program is
//!   simulated against the **original** path and corrected again; vertices
//!   between lines (CAM chains of short G01) move by the mean contour-error
//!   vector per axis;
//! - *regions* ([`region`]): runs of cutting moves between rapids and
//!   fixed segments. Each keeps the round in which its own maximum error
//!   was lowest, and keeps its change only when the *written* program,
//!   simulated against the original path, has a lower maximum error there
//!   than the original; otherwise it is left unchanged, with the reason in
//!   [`RegionNote`]. So the result is never worse than the original
//!   program: when in doubt it is the original text;
//! - *unsettled checks* (beyond that rule): when ten checks of reverting
//!   do not settle (passes closer than their error pass samples between
//!   regions), the checked program with the lowest maximum error is
//!   returned if it is below the original's (whole program, time budget,
//!   no fixed move raised), and each region whose own error rose says so;
//! - *tangent arc–line joints* (beyond the paper): when the written
//!   program's largest error sits where a line meets an arc tangentially,
//!   the compensation runs again with such lines keeping their ends
//!   ([`geometry::Edit::tangent_lines`]), and that result is kept when
//!   its maximum error is lower;
//! - fixed segments (subprogram bodies, canned-cycle expansions, Fanuc
//!   corners) never move, and arcs touching them keep their radius;
//! - *dwells*: candidates are the joints where a run of at least three short
//!   cutting segments (nominal duration `< max(2·tA, 4·T)`) meets a longer
//!   one — the paper's B and D — and, beyond the paper, the sharp corners
//!   of a region ([`sharp_corners`]: a turn over 10°, where the tool cuts
//!   the corner short; real programs' largest error sits there), the ones
//!   with the largest original error first, as many as the time budget
//!   allows. With `dwell` unset, 0.1 s dwells are tried
//!   at all candidates (for small programs, [`MAX_DWELL_TRIAL_SAMPLES`], each is
//!   then removed again if the error does not rise by more than 1 %
//!   without it); a region takes them only where they lower its error, and
//!   all are dropped when the motion time would exceed the time budget.
//!   `dwell: 0` disables them; a positive `dwell` sets their length;
//! - *time budget*: the compensated motion time may exceed the original's
//!   by at most `timeBudget` (default 5 %);
//! - the output is the original text with only the moved words changed
//!   ([`crate::nc::patch`]): units, number format, N numbers, comments,
//!   dwell form and line endings are the original's.
//! - *written flat* (beyond the paper): when the in-place result's largest
//!   error sits on a move the program computes (macro code, a canned
//!   cycle, a subprogram body), whose words cannot move, the program is
//!   written flat ([`crate::nc::writer::write_expanded`]) and that text is
//!   compensated; it is kept when, simulated against the original
//!   program's own path, its maximum error is below 0.99 × the
//!   in-place one within the time budget ([`Compensation::expanded`]).
//!
//! Units: mm, s; errors reported in µm where the field says so.

pub mod corner;
pub mod geometry;
pub mod lines;
pub mod region;
pub mod rounds;

use serde::{Deserialize, Serialize};

use crate::nc::patch::write_source_each;
use crate::nc::program::{dist, parse_with, DwellP, Keep, Motion, ParseOptions, Program, Segment};
use crate::toolpath::{sample_estimate, simulate, SimConfig, Simulation, ToolpathError};
use geometry::Edit;
use lines::{line_range, outside_notes, LineRange};
use region::{kinds, region_errors, regions_in, segment_errors, Regions};
use rounds::{copy_region, identity, Work};

/// Dwell candidates are removed one by one (each trial costs a full set
/// of rounds) only while candidates × samples stays below this; beyond it
/// they are tried all together only.
pub const MAX_DWELL_TRIAL_SAMPLES: usize = 2_000_000;
/// Default time budget: +5 % motion time (the paper's +3.9 % fits).
pub const DEFAULT_TIME_BUDGET: f64 = 0.05;
/// How much an unchanged region's error may rise through its neighbours'
/// changes (rounding of the written numbers), mm.
const NEIGHBOUR_SLACK: f64 = 1e-4;
/// Rounds of writing, checking and reverting regions at most.
const MAX_CHECKS: usize = 10;

/// Most segments for which the better single run of rounds is held for
/// the check beside their combination (64 B a segment: 6.4 MB here; the
/// 1 M-segment program's memory is budgeted without it).
const SINGLE_RUN_SEGMENTS: usize = 100_000;

/// Settings of the reverse compensation. Read through a flat mirror
/// (`ReverseConfigIn`): serde reads a flattened field as a map and drops
/// the keys no part names.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, from = "ReverseConfigIn")]
pub struct ReverseConfig {
    /// The model (tA, T, dt, …).
    #[serde(flatten)]
    pub sim: SimConfig,
    /// Dwell length at cluster joints, s: unset = automatic 0.1 s, 0 = none.
    pub dwell: Option<f64>,
    /// Most correction rounds after the first.
    pub iterations: usize,
    /// Largest allowed growth of the motion time, as a fraction (0.05 = +5 %).
    #[serde(rename = "timeBudget")]
    pub time_budget: f64,
    /// How G4 P is read, and so the form of an inserted dwell
    /// ([`crate::nc::dialect::dwell_form`]).
    #[serde(rename = "dwellP")]
    pub dwell_p: DwellP,
    /// First line to compensate (1-based; unset: the first), see [`lines`].
    #[serde(rename = "fromLine")]
    pub from_line: Option<usize>,
    /// Last line to compensate (inclusive; unset: the last).
    #[serde(rename = "toLine")]
    pub to_line: Option<usize>,
    /// Share of the measured deviation each correction round corrects
    /// (qiu's reading: 1; default [`rounds::DEFAULT_STEP`]).
    pub step: f64,
    /// Try corner spikes ([`corner`]) at sharp corners (default true;
    /// false gives qiu's method: radii, vertices and dwells only).
    #[serde(rename = "cornerSpikes")]
    pub corner_spikes: bool,
    /// Write the program flat and compensate that when its largest error
    /// sits on moves that cannot be rewritten in place (default true; see
    /// [`Compensation::expanded`]).
    pub expand: bool,
}

/// [`ReverseConfig`] as read: every key named, no other key accepted.
#[derive(Deserialize)]
#[serde(default, deny_unknown_fields)]
struct ReverseConfigIn {
    #[serde(rename = "tA")]
    t_a: f64,
    #[serde(rename = "T")]
    t: crate::toolpath::Lag,
    dt: f64,
    #[serde(rename = "rapidFeed")]
    rapid_feed: f64,
    #[serde(rename = "feedOverride")]
    feed_override: f64,
    #[serde(rename = "dwellExactStop")]
    dwell_exact_stop: bool,
    dwell: Option<f64>,
    iterations: usize,
    #[serde(rename = "timeBudget")]
    time_budget: f64,
    #[serde(rename = "dwellP")]
    dwell_p: DwellP,
    #[serde(rename = "fromLine")]
    from_line: Option<usize>,
    #[serde(rename = "toLine")]
    to_line: Option<usize>,
    step: f64,
    #[serde(rename = "cornerSpikes")]
    corner_spikes: bool,
    expand: bool,
}

impl Default for ReverseConfigIn {
    fn default() -> Self {
        let c = ReverseConfig::default();
        Self {
            t_a: c.sim.t_a,
            t: c.sim.t,
            dt: c.sim.dt,
            rapid_feed: c.sim.rapid_feed,
            feed_override: c.sim.feed_override,
            dwell_exact_stop: c.sim.dwell_exact_stop,
            dwell: c.dwell,
            iterations: c.iterations,
            time_budget: c.time_budget,
            dwell_p: c.dwell_p,
            from_line: c.from_line,
            to_line: c.to_line,
            step: c.step,
            corner_spikes: c.corner_spikes,
            expand: c.expand,
        }
    }
}

impl From<ReverseConfigIn> for ReverseConfig {
    fn from(c: ReverseConfigIn) -> Self {
        Self {
            sim: SimConfig {
                t_a: c.t_a,
                t: c.t,
                dt: c.dt,
                rapid_feed: c.rapid_feed,
                feed_override: c.feed_override,
                dwell_exact_stop: c.dwell_exact_stop,
            },
            dwell: c.dwell,
            iterations: c.iterations,
            time_budget: c.time_budget,
            dwell_p: c.dwell_p,
            from_line: c.from_line,
            to_line: c.to_line,
            step: c.step,
            corner_spikes: c.corner_spikes,
            expand: c.expand,
        }
    }
}

impl Default for ReverseConfig {
    fn default() -> Self {
        Self {
            sim: SimConfig::default(),
            dwell: None,
            iterations: 6,
            time_budget: DEFAULT_TIME_BUDGET,
            dwell_p: DwellP::default(),
            from_line: None,
            to_line: None,
            step: rounds::DEFAULT_STEP,
            corner_spikes: true,
            expand: true,
        }
    }
}

impl ReverseConfig {
    /// qiu's method as the paper states it, with this crate's regions and
    /// checks: each round corrects the whole deviation (`step` 1), no
    /// corner spikes (radii, vertices and dwells only). The paper-table
    /// rows use it; the default's extensions go beyond the paper.
    pub fn paper() -> Self {
        Self {
            step: 1.0,
            corner_spikes: false,
            ..Self::default()
        }
    }
}

/// Maximum error and motion time of one program.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Summary {
    /// Maximum contour error against the original path, µm.
    pub max_error_um: f64,
    /// Motion time, s.
    pub motion_time: f64,
}

/// What happened to one original segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SegmentChange {
    /// Index into the original segments.
    pub segment: usize,
    /// Source line.
    pub line: usize,
    /// `"arc"`, `"line"`, `"rapid"` or `"dwell"`.
    pub kind: &'static str,
    /// Original radius (arcs), mm.
    pub radius_before: f64,
    /// New radius (arcs), mm.
    pub radius_after: f64,
    /// How far the segment's end point moved, µm.
    pub end_shift_um: f64,
}

/// A dwell the compensation inserted.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct DwellAt {
    /// After the block on this source line.
    pub after_line: usize,
    /// Length, s.
    pub seconds: f64,
}

/// A corner spike the compensation inserted ([`corner`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SpikeAt {
    /// After the block on this source line (two new lines before the next).
    pub after_line: usize,
    /// How far the spike reaches out from the corner, µm.
    pub depth_um: f64,
}

/// The verdict on one region.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct RegionNote {
    /// First and last source line of the region.
    pub first_line: usize,
    /// Last source line.
    pub last_line: usize,
    /// Arcs and lines in it.
    pub arcs: usize,
    /// Lines in it.
    pub lines: usize,
    /// Its maximum error in the original program, µm.
    pub before_um: f64,
    /// Its maximum error in the returned program, µm.
    pub after_um: f64,
    /// The returned program changes it.
    pub changed: bool,
    /// Why it was left unchanged (empty when changed).
    pub reason: String,
}

/// The result of [`reverse_compensate`].
#[derive(Debug, Clone)]
pub struct Compensation {
    /// The corrected program (the original text where nothing helped).
    pub nc: String,
    /// The original program against its own path.
    pub before: Summary,
    /// The corrected program against the original path.
    pub after: Summary,
    /// Per original segment.
    pub segments: Vec<SegmentChange>,
    /// Inserted dwells.
    pub dwells: Vec<DwellAt>,
    /// Inserted corner spikes.
    pub spikes: Vec<SpikeAt>,
    /// Per region: before, after, and why it was left unchanged.
    pub regions: Vec<RegionNote>,
    /// Maximum error of each correction round, µm.
    pub history_um: Vec<f64>,
    /// The simulation of the original program.
    pub sim_before: Simulation,
    /// The simulation of the corrected program against the original path.
    pub sim_after: Simulation,
    /// Set when the written program is the original text byte for byte:
    /// why, in words (the worst region's reason), so that nothing is
    /// offered as a compensated program that is not one.
    pub unchanged: Option<String>,
    /// Set when the work budget cut the rounds or checks short: what was
    /// kept and what to change for a full run.
    pub budget_note: Option<String>,
    /// Set when dwells were inserted in a form the program does not
    /// confirm (P in milliseconds, [`crate::nc::dialect::DwellForm::guessed`]):
    /// what was written and what to set if the control reads P as seconds.
    pub dwell_note: Option<String>,
    /// The written program is the original written flat
    /// ([`crate::nc::writer::write_expanded`]) and compensated, because the
    /// largest error sat on moves that cannot be rewritten in place.
    pub expanded: bool,
    /// Why it was written flat, or why it was not although its largest
    /// error sits on such moves.
    pub expand_note: Option<String>,
}

/// The joints after which a dwell may help: where a run of ≥ 3 short
/// cutting segments meets a longer one.
pub fn dwell_candidates(orig: &[Segment], sim: &SimConfig) -> Vec<usize> {
    let tmax = sim.t.per_axis().into_iter().fold(0.0, f64::max);
    let limit = (2.0 * sim.t_a).max(4.0 * tmax);
    let moves: Vec<usize> = (0..orig.len()).filter(|&i| orig[i].is_cutting()).collect();
    let short: Vec<bool> = moves
        .iter()
        .map(|&i| orig[i].length() / (orig[i].feed * sim.feed_override / 60.0) < limit)
        .collect();
    let mut out = Vec::new();
    let mut k = 0;
    while k < moves.len() {
        if !short[k] {
            k += 1;
            continue;
        }
        let a = k;
        while k < moves.len() && short[k] {
            k += 1;
        }
        if k - a >= 3 {
            if a > 0 {
                out.push(moves[a - 1]);
            }
            if k < moves.len() {
                out.push(moves[k - 1]);
            }
        }
    }
    out
}

/// Smallest turn between consecutive cutting moves that counts as a
/// corner for a dwell, rad (10°: CAM chains of short lines turn less).
pub const CORNER_TURN: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// The joints between two cutting moves of one region, and between a
/// region's last cutting move and the rapid after it, where the path
/// turns by more than [`CORNER_TURN`]: there the tool cuts the corner
/// short, and a dwell (the NC stops at the corner) removes that error.
pub fn sharp_corners(orig: &[Segment], rg: &Regions) -> Vec<usize> {
    let moves: Vec<usize> = (0..orig.len())
        .filter(|&i| !matches!(orig[i].motion, Motion::Dwell { .. }))
        .collect();
    moves
        .windows(2)
        .filter_map(|w| {
            let (i, k) = (w[0], w[1]);
            // A joint inside a region, or a region's exit into a rapid: the
            // rapid starts while the cut still settles and cuts that
            // corner too (a rapid ends in an exact stop, it does not start
            // with one).
            let exit = matches!(orig[k].motion, Motion::Rapid);
            if rg.of[i].is_none() || (rg.of[i] != rg.of[k] && !exit) {
                return None;
            }
            let (u, v) = (
                corner::tangent(&orig[i], true)?,
                corner::tangent(&orig[k], false)?,
            );
            let c = (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]).clamp(-1.0, 1.0);
            (c.acos() > CORNER_TURN).then_some(i)
        })
        .collect()
}

fn validate(cfg: &ReverseConfig) -> Result<(), ToolpathError> {
    cfg.sim.validate()?;
    let bad = |field, message: &str| {
        Err(ToolpathError::Config {
            field,
            message: message.into(),
        })
    };
    if let Some(d) = cfg.dwell {
        if !(d.is_finite() && (0.0..=10.0).contains(&d)) {
            return bad("dwell", "expected a dwell between 0 and 10 s");
        }
    }
    if !(cfg.step.is_finite() && cfg.step > 0.0 && cfg.step <= 1.0) {
        return bad(
            "step",
            "expected the share of the deviation a round corrects, above 0 and at most 1 (qiu: 1, default 0.5)",
        );
    }
    if cfg.iterations > 50 {
        return bad("iterations", "expected at most 50 iterations");
    }
    if !(cfg.time_budget.is_finite() && (0.0..=1.0).contains(&cfg.time_budget)) {
        return bad(
            "timeBudget",
            "expected a motion-time budget between 0 and 1 (0.05 = +5 %)",
        );
    }
    Ok(())
}

/// Reverse-compensates `text` (qiu §4-3(2)); see the module header.
///
/// # Units
/// Config in s and mm/min; summaries in µm and s.
///
/// # Errors
/// NC errors naming line and column, invalid settings, an empty program.
///
/// # Examples
/// ```
/// use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
/// let nc = mtmotion::toolpath::example::arc_example();
/// let c = reverse_compensate(&nc, &ReverseConfig::default()).unwrap();
/// assert!(c.after.max_error_um < 0.4 * c.before.max_error_um);
/// assert!(c.nc.contains("N40 G3") && c.nc.contains("(C)"));
/// ```
pub fn reverse_compensate(text: &str, cfg: &ReverseConfig) -> Result<Compensation, ToolpathError> {
    reverse_compensate_with(text, cfg, &mut |_, _| true)
}

/// As [`reverse_compensate`], reporting progress: `progress(fraction,
/// stage)` is called between simulations; returning `false` stops the run
/// with [`ToolpathError::Cancelled`].
///
/// # Errors
/// As [`reverse_compensate`], and the cancellation.
pub fn reverse_compensate_with(
    text: &str,
    cfg: &ReverseConfig,
    progress: &mut dyn FnMut(f64, &str) -> bool,
) -> Result<Compensation, ToolpathError> {
    validate(cfg)?;
    let opts = ParseOptions {
        dwell_p: cfg.dwell_p,
        ..ParseOptions::default()
    };
    let program = parse_with(text, &opts)?;
    let range = line_range(&program, cfg.from_line, cfg.to_line)?;
    // The cutting moves that cannot be rewritten in place.
    let pinned = if cfg.expand && range.whole {
        pinned_cuts(&program)
    } else {
        Vec::new()
    };
    let share = if pinned.contains(&true) { 0.5 } else { 1.0 };
    let mut src = Source::new(text, program);
    let (mut c, first) = ran(in_place(&mut src, &range, cfg, None, &mut |f, s| {
        progress(f * share, s)
    })?)?;
    if worst_at_tangent_line(src.segments(), &c.sim_after) {
        // Its largest error sits where a line meets an arc tangentially:
        // the variant that keeps such lines' ends (geometry::Edit::
        // tangent_lines), kept when its written program is better. It
        // starts from what the first run found that the variant does not
        // change (see `FirstRun`), and is checked only when its rounds
        // predict a lower largest error than the first run's.
        let t = in_place(
            &mut src,
            &range,
            cfg,
            Some((&c.sim_before, &first)),
            &mut |_, s| progress(share, &format!("tangent arc–line joints: {s}")),
        )?;
        if let Some((t, _)) = t {
            if t.unchanged.is_none() && t.after.max_error_um < c.after.max_error_um {
                c = t;
            }
        }
    }
    if !worst_is_pinned(src.segments(), &pinned, &c.sim_after) {
        return Ok(c);
    }
    let (flat, fp) = match crate::nc::writer::write_expanded(src.program(Keep::All)?) {
        Ok(flat) => flat,
        Err(why) => {
            c.expand_note = Some(format!("not written flat: {why}"));
            return Ok(c);
        }
    };
    src.slim();
    let whole = line_range(&fp, None, None)?;
    let (mut e, _) = ran(in_place(
        &mut Source::new(&flat, fp),
        &whole,
        cfg,
        None,
        &mut |f, s| progress(0.5 + 0.5 * f, &format!("written flat: {s}")),
    )?)?;
    if e.unchanged.is_some() {
        c.expand_note = Some("written flat, the program did not improve either".into());
        return Ok(c);
    }
    // The flat program's result, measured against the original's own path.
    let written = motion_of(&e.nc, &opts)?;
    let after = simulate(&written, src.segments(), &cfg.sim)?;
    let time_ok = after.motion_time <= c.before.motion_time * (1.0 + cfg.time_budget) + 1e-9;
    if !(time_ok && after.max_error < c.sim_after.max_error * EXPAND_GAIN) {
        c.expand_note = Some(format!(
            "written flat it would reach {} µm in {} s, against {} µm in {} s in place",
            crate::numeric::compact(after.max_error * 1e3),
            crate::numeric::compact(after.motion_time),
            crate::numeric::compact(c.after.max_error_um),
            crate::numeric::compact(c.after.motion_time)
        ));
        return Ok(c);
    }
    e.after = summary(&after);
    e.sim_after = after;
    e.before = c.before;
    e.sim_before = c.sim_before;
    e.expand_note = Some(EXPANDED.to_string());
    e.expanded = true;
    Ok(e)
}

/// The result of a run of [`in_place`] that is not the tangent variant
/// (which alone may stop before its check).
fn ran(r: Option<(Compensation, FirstRun)>) -> Result<(Compensation, FirstRun), ToolpathError> {
    r.ok_or_else(|| ToolpathError::Config {
        field: "text",
        message: "a compensation run stopped before its check; please report it".into(),
    })
}

/// The segments of a written program, read without the modal state per
/// block that only a writer needs (368 bytes a block: 368 MB of a 1 M-line
/// program, held beside the original's while the check simulates).
fn motion_of(text: &str, opts: &ParseOptions) -> Result<Vec<Segment>, crate::nc::NcError> {
    crate::nc::files::parse_files_keeping(text, &[], opts, crate::nc::program::Keep::Motion)
        .map(|p| p.segments)
        .map_err(|e| e.first())
}

/// A flat program is given out only when it lowers the in-place result's
/// maximum error below this share of it.
const EXPAND_GAIN: f64 = 0.99;

/// What an expanded result says.
const EXPANDED: &str = "the largest error sat on moves the program computes (macro code, canned \
     cycles, subprogram bodies, corner roundings), whose words cannot move in place; the \
     compensated program is written flat: one block per move in execution order, absolute \
     millimetres (G21 G90 G94 G17), with the work offsets, tool length offsets and M, S, T, D, \
     H words where they were; the lines named in this result are the written program's";

/// Per segment of `program`: a cutting move reverse compensation cannot
/// rewrite in place (fixed, or its block not editable; see [`regions_in`]).
fn pinned_cuts(program: &Program) -> Vec<bool> {
    let rg = regions_in(program, &|_| true);
    program
        .segments
        .iter()
        .zip(&rg.editable)
        .map(|(s, &e)| s.is_cutting() && (!e || s.fixed))
        .collect()
}

/// The segment of `segments` where the written program's largest error on
/// a cutting move sits (`after`'s statistics; `None` without one).
fn worst_cut(segments: &[Segment], after: &Simulation) -> Option<usize> {
    after
        .segments
        .iter()
        .filter(|st| segments.get(st.segment).is_some_and(Segment::is_cutting))
        .max_by(|a, b| a.max_error_um.total_cmp(&b.max_error_um))
        .map(|st| st.segment)
}

/// The written program's largest error on a cutting move sits on a
/// `pinned` one ([`pinned_cuts`]; none when it is empty).
fn worst_is_pinned(segments: &[Segment], pinned: &[bool], after: &Simulation) -> bool {
    worst_cut(segments, after).is_some_and(|w| pinned.get(w).copied().unwrap_or(false))
}

/// The written program's largest error on a cutting move sits on a line
/// that meets an arc tangentially, or on such an arc
/// ([`geometry::tangent_joint`]).
fn worst_at_tangent_line(segs: &[Segment], after: &Simulation) -> bool {
    let Some(w) = worst_cut(segs, after) else {
        return false;
    };
    let line_arc = |i: usize, k: usize| {
        let (a, b) = (&segs[i], &segs[k]);
        let kinds = matches!(
            (a.motion, b.motion),
            (Motion::Linear, Motion::Arc(_)) | (Motion::Arc(_), Motion::Linear)
        );
        kinds && geometry::tangent_joint(a, b)
    };
    (w > 0 && line_arc(w - 1, w)) || (w + 1 < segs.len() && line_arc(w, w + 1))
}

/// The program under compensation. Only the writers read its blocks
/// and per-block modal state (about 750 MB of a 1 M-line program, beside
/// 175 MB of segments; the patch writer ([`crate::nc::patch`]) only the
/// compact [`Program::modes`], [`Keep::Patch`]): they are dropped while
/// the rounds and checks simulate ([`Source::slim`]) and read again from
/// the text for a write ([`Source::program`]); everything else reads the
/// segments, which are kept.
struct Source<'t> {
    text: &'t str,
    program: Program,
    /// What of the blocks and modal states is there (`None`: dropped).
    kept: Option<Keep>,
    /// The segments' fingerprint ([`rounds::fingerprints`], taken when
    /// the blocks are first dropped), which a second reading must give.
    fingerprint: Option<u128>,
}

impl<'t> Source<'t> {
    /// `program`, parsed from `text` with its own options, whole.
    fn new(text: &'t str, program: Program) -> Self {
        Self {
            text,
            program,
            kept: Some(Keep::All),
            fingerprint: None,
        }
    }

    fn segments(&self) -> &[Segment] {
        &self.program.segments
    }

    /// Drops the blocks and modal states.
    fn slim(&mut self) {
        if self.fingerprint.is_none() {
            self.fingerprint = Some(rounds::fingerprints(&self.program.segments, &[0])[0]);
        }
        self.program.blocks = Vec::new();
        self.program.modal = Vec::new();
        self.program.modes = Default::default();
        self.kept = None;
    }

    /// The program with what `keep` says (or more), read again if slimmed
    /// (the same segments, or an error: never a program whose blocks are
    /// not its segments'). The
    /// segments are dropped for the reading, which gives them again, and
    /// compared by their fingerprint: both copies at once were 175 MB of
    /// a 1 M-segment program at the reading's peak.
    fn program(&mut self, keep: Keep) -> Result<&Program, ToolpathError> {
        if self.kept.is_none_or(|k| k != Keep::All && k != keep) {
            let was = self.fingerprint;
            self.program.segments = Vec::new();
            let p =
                crate::nc::files::parse_files_keeping(self.text, &[], &self.program.options, keep)
                    .map_err(|e| e.first())?;
            let now = rounds::fingerprints(&p.segments, &[0])[0];
            if was.is_none_or(|f| f != now || f == rounds::NEVER_EQUAL) {
                return Err(ToolpathError::Config {
                    field: "text",
                    message: "the program read a second time gave other moves; please report it"
                        .into(),
                });
            }
            self.program = p;
            self.kept = Some(keep);
        }
        Ok(&self.program)
    }
}

/// What the compensation reads of the blocks, taken before they are
/// dropped ([`Source::slim`]).
struct Facts {
    blocks: usize,
    has_macros: bool,
    dwell_guessed: bool,
}

/// What the compensation keeps of the original program's simulation once
/// the rounds have their start ([`rounds::Work::set_original`]): its
/// summary and per-segment maxima, not its series and statistics (the
/// returned one is simulated again at the end, the same numbers).
struct Before {
    summary: Summary,
    max_error: f64,
    motion_time: f64,
    /// Samples kept in its series.
    kept: usize,
    /// Maximum error per original segment, mm (the check judges by it,
    /// [`try_dwells`] orders the joints by it).
    seg: Vec<f64>,
}

impl Before {
    fn of(sim: &Simulation, n: usize) -> Self {
        Self {
            summary: summary(sim),
            max_error: sim.max_error,
            motion_time: sim.motion_time,
            kept: sim.t.len(),
            seg: segment_errors(n, &sim.segments),
        }
    }
}

/// What the tangent arc–line variant takes over from the first run of
/// [`in_place`] on the same program instead of computing it again: the
/// original's simulation (the first run's [`Compensation::sim_before`],
/// passed beside this) and the corner spikes' search. The spikes sit at
/// turns over [`CORNER_TURN`], which the variant's rule (joints within 1°
/// of tangent) leaves as they are; the variant's rounds, dwells and
/// checks then run on its own geometry from those spikes, with the window
/// budget the search had spent taken off as in the first run.
struct FirstRun {
    /// The searched spikes (segment, vector), the nonzero ones only.
    spikes: Vec<(usize, [f64; 3])>,
    /// The search's maximum error per round, µm.
    history_um: Vec<f64>,
    /// Window samples the search spent, and whether the budget stopped it.
    spent: u64,
    stopped: bool,
    /// The largest of the regions' best predicted errors (the rounds'
    /// windowed statistics, before the check), mm.
    predicted: f64,
}

/// [`reverse_compensate_with`] on the program's own blocks: only literal
/// words move. With `variant` (the original's simulation and the first
/// run's [`FirstRun`]), the tangent arc–line variant: lines meeting arcs
/// tangentially keep their ends ([`geometry::Edit::tangent_lines`]);
/// `None` when its rounds do not predict a lower largest region error
/// than the first run's (`FirstRun::predicted`): then it is not checked.
fn in_place(
    src: &mut Source,
    range: &LineRange,
    cfg: &ReverseConfig,
    variant: Option<(&Simulation, &FirstRun)>,
    progress: &mut dyn FnMut(f64, &str) -> bool,
) -> Result<Option<(Compensation, FirstRun)>, ToolpathError> {
    let tangent = variant.is_some();
    let text = src.text;
    let (opts, facts, rg) = {
        let program = src.program(Keep::Patch)?;
        let facts = Facts {
            blocks: program.blocks.len(),
            has_macros: program.has_macros(),
            dwell_guessed: crate::nc::dialect::dwell_form(program).guessed,
        };
        let rg = regions_in(program, &|l| range.contains(l));
        (program.options.clone(), facts, rg)
    };
    src.slim();
    let orig = src.segments();
    let mut work = Work::for_program(orig.len(), sample_estimate(orig, &cfg.sim)? as u64);
    let mut tick = |f: f64, s: &str| {
        if progress(f, s) {
            Ok(())
        } else {
            Err(ToolpathError::Cancelled)
        }
    };
    tick(0.0, "simulating the original program")?;
    let (mut spikes_spent, mut spikes_stopped) = (0, false);
    let mut own = None;
    let sim_before = match variant {
        Some((sim, _)) => sim,
        None => own.insert(simulate(orig, orig, &cfg.sim)?),
    };
    work.set_original(orig, sim_before);
    let before_err = region_errors(&rg, &sim_before.segments);
    let before = Before::of(sim_before, orig.len());
    drop(own);
    tick(0.1, "corner spikes")?;
    let allowed = cfg.time_budget * before.motion_time;
    let spikes = match variant {
        Some((_, first)) => {
            let mut edit = identity(orig, vec![0.0; orig.len()]);
            edit.tangent_lines = true;
            for &(i, d) in &first.spikes {
                edit.spike[i] = d;
            }
            // The same budget as the first run's (the same program), so
            // what its search spent is there to take.
            work.round(first.spent);
            work.stopped |= first.stopped;
            corner::Spikes {
                edit,
                history_um: first.history_um.clone(),
            }
        }
        None => {
            let found = if cfg.corner_spikes {
                corner::corners(orig, &rg, &cfg.sim)
            } else {
                Vec::new()
            };
            let stats = work.original_stats().unwrap_or_default();
            let start = identity(orig, vec![0.0; orig.len()]);
            let left = work.left();
            let spikes =
                corner::search(orig, &cfg.sim, &found, &stats, &start, allowed, &mut work)?;
            spikes_spent = left - work.left();
            spikes_stopped = work.stopped;
            // `stats`, `start` and `found` are not held through the rounds
            // and checks (64 B a segment).
            spikes
        }
    };
    let mut first = FirstRun {
        spikes: (0..orig.len())
            .filter(|&i| spikes.edit.spike[i] != [0.0; 3])
            .map(|i| (i, spikes.edit.spike[i]))
            .collect(),
        history_um: spikes.history_um.clone(),
        spent: spikes_spent,
        stopped: spikes_stopped,
        predicted: 0.0,
    };
    tick(0.25, "correction rounds")?;
    // Half of what is left waits for the dwells, which rounds that reach
    // the budget would leave nothing: the CAMotics cameo raster (35k
    // lines, over the window budget) fell from 102.2 to 87.1 µm without
    // this and falls to 6.3 µm with it (dt 2 ms); no other corpus program
    // changed.
    let held = work.hold(2);
    let plain = rounds::run(
        orig,
        &rg,
        (&cfg.sim, cfg.step),
        cfg.iterations,
        spikes.edit.clone(),
        &mut work,
    )?;
    work.release(held);
    let mut history = spikes.history_um.clone();
    history.extend(&plain.history_um);
    let mut notes: Vec<Option<String>> = vec![None; rg.members.len()];
    tick(0.5, "dwells")?;
    let spent = corner::added_time(orig, &cfg.sim, &spikes.edit);
    let dwelt = try_dwells(
        orig,
        &rg,
        cfg,
        &before,
        (&spikes.edit, allowed - spent),
        &mut work,
    )?;
    drop(spikes);
    // Only the check's whole-program simulations run from here on.
    work.forget_original();
    tick(0.7, "checking the written program")?;
    // Without dwells: the plain rounds' regions that beat the original.
    let mut fallback = identity(orig, vec![0.0; orig.len()]);
    fallback.tangent_lines = tangent;
    for (r, &e) in plain.error.iter().enumerate() {
        if e < before_err[r] {
            copy_region(&rg, r, &plain.edit, &mut fallback);
        }
    }
    // The better of the two runs as it is, for when the check of their
    // combination does not settle (see `check`): a run's regions are
    // judged against its own command, and where passes lie closer than
    // their error (LinuxCNC threading) the combination of two runs'
    // regions is not their prediction. Held up to SINGLE_RUN_SEGMENTS
    // (64 B a segment).
    let single = (orig.len() <= SINGLE_RUN_SEGMENTS).then(|| match &dwelt {
        Dwelt::Ran(d) if d.worst() < plain.worst() => d.edit.clone(),
        _ => plain.edit.clone(),
    });
    let (mut edit, mut best) = (plain.edit, plain.error);
    match dwelt {
        Dwelt::None => {}
        Dwelt::Budget(why, rs) => {
            for r in rs {
                notes[r] = Some(why.clone());
            }
        }
        Dwelt::Ran(d) => {
            history.extend(&d.history_um);
            for (r, b) in best.iter_mut().enumerate() {
                if d.error[r] < *b {
                    *b = d.error[r];
                    copy_region(&rg, r, &d.edit, &mut edit);
                }
            }
        }
    }
    first.predicted = best.iter().copied().fold(0.0, f64::max);
    drop(best);
    // The variant's check (several whole-program simulations) only when
    // its rounds predict it better: the written program's error differs
    // from the prediction (regions are reverted), but on the corpus every
    // variant that won was predicted lower and the one that lost (Gates)
    // was predicted higher.
    if let Some((_, f)) = variant {
        if first.predicted >= f.predicted {
            return Ok(None);
        }
    }
    let checked = check(
        src,
        (&opts, range.whole),
        &rg,
        (&before_err, &before),
        cfg,
        (edit, &fallback, single),
        &mut tick,
        &mut work,
    )?;
    drop(fallback);
    let orig = src.segments();
    let sim_before = match variant {
        // The first run's, as the variant started from.
        Some((sim, _)) => sim.clone(),
        None => {
            // The original's simulation, again (deterministic: the same
            // numbers as the one the rounds started from, whose series
            // were not kept).
            let sim = simulate(orig, orig, &cfg.sim)?;
            if summary(&sim) != before.summary {
                return Err(ToolpathError::Config {
                    field: "text",
                    message:
                        "the original program simulated twice gave two results; please report it"
                            .into(),
                });
            }
            sim
        }
    };
    tick(1.0, "done")?;
    let mut c = finish(
        (orig, &facts),
        range,
        &rg,
        &before_err,
        sim_before,
        checked,
        notes,
        history,
    );
    c.budget_note = work.note();
    c.unchanged = (c.nc == text).then(|| unchanged_reason(&c.regions, range));
    if !c.dwells.is_empty() && c.unchanged.is_none() && facts.dwell_guessed {
        c.dwell_note = Some(format!(
            "{} dwell(s) written as G04 P<milliseconds> (Fanuc, Haas): nothing in the program says \
             how its control reads P; a LinuxCNC or Grbl control reads P in seconds, so each \
             dwell would last 1000 times longer: set dwellP to 'seconds' for such a control",
            c.dwells.len()
        ));
    }
    Ok(Some((c, first)))
}

/// Why a program came back as it was: the worst region's reason, with its
/// lines and error (inside the line range, when one is given); or that it
/// has no cutting region at all.
fn unchanged_reason(regions: &[RegionNote], range: &LineRange) -> String {
    let inside =
        |r: &&RegionNote| range.whole || r.last_line >= range.first && r.first_line <= range.last;
    let worst = regions
        .iter()
        .filter(|r| !r.reason.is_empty())
        .filter(inside)
        .max_by(|a, b| a.before_um.total_cmp(&b.before_um));
    match worst {
        Some(r) => format!(
            "nothing in the program changed: the largest error ({:.1} µm, lines {}–{}) was left \
             as it was because {}",
            r.before_um, r.first_line, r.last_line, r.reason
        ),
        None if range.whole => {
            "nothing in the program changed: it has no cutting move to correct".to_string()
        }
        None => format!(
            "nothing in the program changed: lines {}–{} hold no cutting move to correct",
            range.first, range.last
        ),
    }
}

/// The motion time one inserted dwell adds, s: its length (`dwell`,
/// 0.1 s unset), and with `dwellExactStop` the NC's exact stop before it
/// (tA + 5·max T).
fn dwell_cost(cfg: &ReverseConfig) -> f64 {
    let tmax = cfg.sim.t.per_axis().into_iter().fold(0.0, f64::max);
    cfg.dwell.unwrap_or(0.1)
        + if cfg.sim.dwell_exact_stop {
            cfg.sim.t_a + 5.0 * tmax
        } else {
            0.0
        }
}

/// The dwell variant.
enum Dwelt {
    /// No dwell to try.
    None,
    /// The rounds with dwells.
    Ran(rounds::Rounds),
    /// Dwells would exceed the time budget: why, and the regions concerned.
    Budget(String, Vec<usize>),
}

/// Tries dwells on `base` (the spiked edit) within `allowed` s of added
/// motion time (a dwell replaces a spike at its joint): the regions'
/// exits into a rapid first (the rapid starts while the cut still
/// settles, which no spike reaches; putting every unspiked candidate
/// first did worse on the corpus, median after/before 0.76 against 0.61),
/// then the others, each group largest original error first.
fn try_dwells(
    orig: &[Segment],
    rg: &Regions,
    cfg: &ReverseConfig,
    before: &Before,
    (base, allowed): (&Edit, f64),
    work: &mut Work,
) -> Result<Dwelt, ToolpathError> {
    let dwell = cfg.dwell.unwrap_or(0.1);
    let mut cands: Vec<usize> = dwell_candidates(orig, &cfg.sim);
    cands.extend(sharp_corners(orig, rg));
    cands.retain(|&i| rg.of[i].is_some());
    cands.sort_unstable();
    cands.dedup();
    if dwell <= 0.0 || cands.is_empty() {
        return Ok(Dwelt::None);
    }
    let each = dwell_cost(cfg);
    let allowed = allowed.max(0.0);
    let with = |set: &[usize], work: &mut Work| {
        let mut start = base.clone();
        for &i in set {
            start.dwell_after[i] = dwell;
            start.spike[i] = [0.0; 3];
        }
        rounds::run(orig, rg, (&cfg.sim, cfg.step), cfg.iterations, start, work)
    };
    if each > allowed {
        let note = format!(
            "corner dwells ({} s each) would exceed the time budget (+{} s)",
            crate::numeric::compact(each),
            crate::numeric::compact(allowed)
        );
        return Ok(Dwelt::Budget(
            note,
            cands.iter().filter_map(|&i| rg.of[i]).collect(),
        ));
    }
    // The joints with the largest original error first, as many as the
    // budget allows.
    let seg_err = &before.seg;
    let next_err = |i: usize| seg_err.get(i + 1).copied().unwrap_or(0.0);
    let exit = |i: usize| {
        orig.get(i + 1)
            .is_some_and(|s| matches!(s.motion, Motion::Rapid))
    };
    cands.sort_by(|&a, &b| {
        exit(b).cmp(&exit(a)).then(
            seg_err[b]
                .max(next_err(b))
                .total_cmp(&seg_err[a].max(next_err(a))),
        )
    });
    cands.truncate((allowed / each) as usize);
    cands.sort_unstable();
    let mut set = cands.clone();
    let mut cur = with(&set, work)?;
    if set.len() * before.kept <= MAX_DWELL_TRIAL_SAMPLES {
        for c in set.clone() {
            let trial_set: Vec<usize> = set.iter().copied().filter(|&x| x != c).collect();
            if trial_set.is_empty() || work.stopped {
                break;
            }
            let trial = with(&trial_set, work)?;
            if trial.worst() <= cur.worst() * 1.01 {
                set = trial_set;
                cur = trial;
            }
        }
    }
    Ok(Dwelt::Ran(cur))
}

/// The written program and its check.
struct Checked {
    nc: String,
    edit: Edit,
    /// The simulation of the written program against the original path
    /// (`None`: the original program is given back).
    sim: Option<Simulation>,
    after: Vec<f64>,
    reverted: Vec<Option<String>>,
}

/// Region `r` of `edit` differs from the unchanged program's edit
/// ([`identity`] with no dwell), whose radii are `radius0`.
fn changed(rg: &Regions, r: usize, edit: &Edit, radius0: &[f64]) -> bool {
    rg.members[r].iter().any(|&i| {
        edit.radius[i] != radius0[i]
            || edit.vertex_shift[i] != [0.0; 3]
            || edit.dwell_after[i] != 0.0
            || edit.spike[i] != [0.0; 3]
    })
}

/// The radii of the unchanged program's edit (as [`identity`]'s; the
/// rest of it is zeros), without the 64 B a segment of a whole edit.
fn radii(orig: &[Segment]) -> Vec<f64> {
    orig.iter()
        .map(|s| match s.motion {
            Motion::Arc(a) => a.radius,
            _ => 0.0,
        })
        .collect()
}

/// Writes, parses and simulates the edit against the original path, and
/// reverts every region whose error did not fall, until none is left.
#[allow(clippy::too_many_arguments)]
fn check(
    src: &mut Source,
    (opts, whole): (&ParseOptions, bool),
    rg: &Regions,
    (before_err, before): (&[f64], &Before),
    cfg: &ReverseConfig,
    (edit, fallback, single): (Edit, &Edit, Option<Edit>),
    tick: &mut dyn FnMut(f64, &str) -> Result<(), ToolpathError>,
    work: &mut Work,
) -> Result<Checked, ToolpathError> {
    let text = src.text;
    let mut rv = Review {
        rg,
        before_err,
        before_seg: &before.seg,
        radius0: radii(src.segments()),
        edit,
        fallback,
        reverted: vec![None; rg.members.len()],
        undo: Vec::new(),
    };
    let limit = before.motion_time * (1.0 + cfg.time_budget) + cfg.sim.dt;
    // The NC filter forgets a change after tA, the servo lag after a few
    // T: a corner spike's transient (up to 0.2 mm) is below 1 nm after
    // 12·T (e⁻¹² ≈ 6·10⁻⁶).
    let memory = crate::toolpath::locality::memory(&cfg.sim);
    // The checked edit with the lowest maximum error below the original's
    // (whole program, within the time budget, no fixed move raised), for
    // when reverting does not settle.
    let mut best: Option<(f64, Edit)> = None;
    for round in 0..MAX_CHECKS {
        tick(0.7 + 0.07 * round as f64, "checking the written program")?;
        if (0..rg.members.len()).all(|r| !rv.changed(r)) {
            break;
        }
        let nc = write_edit(src, &rv.edit)?;
        let Ok(written) = motion_of(&nc, opts) else {
            // A writer limit: never hand out a program that does not read back.
            break;
        };
        if !work.check(work.program) {
            // Out of budget: the original program, unchecked edits never.
            break;
        }
        let orig = src.segments();
        let sim = simulate(&written, orig, &cfg.sim)?;
        drop(written);
        let after = region_errors(rg, &sim.segments);
        let over_time = sim.motion_time > limit;
        rv.undo.clear();
        let unimproved = rv.revert_unimproved(orig, &after, sim.motion_time - limit, &cfg.sim);
        let raised = rv.revert_neighbours(orig, &after);
        let strays = rv.revert_near_strays(
            orig,
            &segment_errors(orig.len(), &sim.segments),
            memory,
            &cfg.sim,
        );
        let bad = unimproved || raised || strays;
        // With a line range the largest error may lie outside, past the
        // changes' reach, where only the sampling phase differs (nm).
        let worse = sim.max_error > before.max_error + if whole { 0.0 } else { NEIGHBOUR_SLACK };
        // The edit this round checked, when the next round goes on from
        // less of it (without reverts it is returned or given up below).
        if bad
            && whole
            && !over_time
            && !strays
            && sim.max_error < before.max_error
            && best.as_ref().is_none_or(|b| sim.max_error < b.0)
        {
            best = Some((sim.max_error, rv.tried()));
        }
        if !bad && !worse && !over_time {
            return Ok(Checked {
                nc,
                edit: rv.edit,
                sim: Some(sim),
                after,
                reverted: rv.reverted,
            });
        }
        if !bad {
            break;
        }
    }
    // Reverting did not settle: each round raised other regions (passes
    // closer than their error, as LinuxCNC threading's 12.7 µm infeed,
    // move samples between them). The best checked program, checked once
    // more, or the better single run of rounds as it is (`single`), when
    // it is lower still: whichever lowers the program's maximum most; the
    // regions whose own error rose say so.
    let mut unsettled: Option<(Checked, f64)> = None;
    let from_best = best.is_some();
    let candidates = [best.map(|b| b.1), single.filter(|_| whole)];
    for (k, edit) in candidates.into_iter().flatten().enumerate() {
        let nc = write_edit(src, &edit)?;
        let Ok(written) = motion_of(&nc, opts) else {
            continue;
        };
        if !work.check(work.program) {
            break;
        }
        let sim = simulate(&written, src.segments(), &cfg.sim)?;
        drop(written);
        let lowest = unsettled.as_ref().map_or(before.max_error, |u| u.1);
        // The single run was not reviewed: no cutting move outside every
        // region may rise (stricter than `revert_near_strays`).
        let single_run = k == usize::from(from_best);
        let orig = src.segments();
        let fixed_rose = single_run
            && segment_errors(orig.len(), &sim.segments)
                .iter()
                .zip(rv.before_seg)
                .enumerate()
                .any(|(i, (a, b))| {
                    rg.of[i].is_none() && orig[i].is_cutting() && *a > b + NEIGHBOUR_SLACK
                });
        if sim.max_error < lowest && sim.motion_time <= limit && !fixed_rose {
            let after = region_errors(rg, &sim.segments);
            let reverted = rv.unsettled(&edit, &after, (before.max_error, sim.max_error));
            let max_error = sim.max_error;
            let c = Checked {
                nc,
                edit,
                sim: Some(sim),
                after,
                reverted,
            };
            unsettled = Some((c, max_error));
        }
    }
    if let Some((c, _)) = unsettled {
        return Ok(c);
    }
    // Nothing left to change, or still not better everywhere.
    Ok(rv.give_back(text))
}

/// The program `edit` makes of `src`, written. The blocks are read again
/// for the patch writer, which takes the rebuilt segments one at a time
/// as they are made ([`geometry::rebuild_each`]): the rebuilt command is
/// never held beside the blocks (176 MB of a 1 M-segment program). The
/// blocks go before the caller simulates the text.
fn write_edit(src: &mut Source, edit: &Edit) -> Result<String, ToolpathError> {
    src.program(Keep::Patch)?;
    let program = &src.program;
    let nc = write_source_each(src.text, program, |put| {
        geometry::rebuild_each(&program.segments, edit, &mut |s, _| put(&s));
    });
    src.slim();
    Ok(nc)
}

/// The edit under [`check`], against the original program's regions and
/// their errors, with the reason each reverted region went back.
struct Review<'a> {
    rg: &'a Regions,
    /// Maximum error per region of the original program, mm.
    before_err: &'a [f64],
    /// Maximum error per segment of the original program, mm.
    before_seg: &'a [f64],
    /// The unchanged program's radii ([`radii`]).
    radius0: Vec<f64>,
    edit: Edit,
    reverted: Vec<Option<String>>,
    /// The edit without dwells (spikes and rounds), which a region over
    /// the time budget with dwells falls back to before the original.
    fallback: &'a Edit,
    /// The entries of the segments this round's reverts changed, as they
    /// were before each change (segment, radius, vertex shift, dwell,
    /// spike): the checked edit is had back from them ([`Review::tried`])
    /// without a copy of the whole edit each round (64 MB for 1 M
    /// segments).
    undo: Vec<(usize, Entry)>,
}

/// One segment's entries of an [`Edit`]: radius, vertex shift, dwell, spike.
type Entry = (f64, [f64; 3], f64, [f64; 3]);

impl Review<'_> {
    /// The notes of `edit` when it is returned without the checks having
    /// settled ([`check`]): a region whose own error rose (`after`, mm per
    /// region) says so, with the program's maximum `(before, now)`, mm;
    /// another region it leaves as it was keeps its reason.
    fn unsettled(&self, edit: &Edit, after: &[f64], (was, now): (f64, f64)) -> Vec<Option<String>> {
        let um = |x: f64| crate::numeric::compact(x * 1e3);
        (0..self.rg.members.len())
            .map(|r| {
                if after[r] > self.before_err[r] + NEIGHBOUR_SLACK {
                    Some(format!(
                        "its own error rose ({} → {} µm) while the program's maximum fell ({} → {} µm): reverting the regions whose error rose did not settle (passes closer than their error pass samples between them), so the checked program with the lowest maximum error is returned",
                        um(self.before_err[r]),
                        um(after[r]),
                        um(was),
                        um(now)
                    ))
                } else if changed(self.rg, r, edit, &self.radius0) {
                    None
                } else {
                    self.reverted[r].clone()
                }
            })
            .collect()
    }

    /// The original program as the result, with a note on every region
    /// still changed.
    fn give_back(mut self, text: &str) -> Checked {
        for r in 0..self.rg.members.len() {
            if self.changed(r) {
                self.reverted[r] = Some("the program as a whole would not improve (error or time budget); the original is returned".into());
            }
        }
        // The unchanged program's edit, in place of the edit.
        self.edit.radius.clone_from(&self.radius0);
        self.edit.vertex_shift.fill([0.0; 3]);
        self.edit.dwell_after.fill(0.0);
        self.edit.spike.fill([0.0; 3]);
        Checked {
            nc: text.to_string(),
            edit: self.edit,
            sim: None,
            after: self.before_err.to_vec(),
            reverted: self.reverted,
        }
    }

    /// Region `r` differs from the original.
    fn changed(&self, r: usize) -> bool {
        changed(self.rg, r, &self.edit, &self.radius0)
    }

    /// Gives region `r` of the edit its original entries.
    /// Saves region `r`'s entries before a revert changes them.
    fn save(&mut self, r: usize) {
        for &i in &self.rg.members[r] {
            let e = &self.edit;
            self.undo.push((
                i,
                (e.radius[i], e.vertex_shift[i], e.dwell_after[i], e.spike[i]),
            ));
        }
    }

    /// The edit as the round checked it: the edit with this round's
    /// reverts undone (latest first, so each entry gets its oldest value).
    fn tried(&self) -> Edit {
        let mut e = self.edit.clone();
        for &(i, (radius, shift, dwell, spike)) in self.undo.iter().rev() {
            e.radius[i] = radius;
            e.vertex_shift[i] = shift;
            e.dwell_after[i] = dwell;
            e.spike[i] = spike;
        }
        e
    }

    fn reset(&mut self, r: usize) {
        self.save(r);
        for &i in &self.rg.members[r] {
            self.edit.radius[i] = self.radius0[i];
            self.edit.vertex_shift[i] = [0.0; 3];
            self.edit.dwell_after[i] = 0.0;
            self.edit.spike[i] = [0.0; 3];
        }
    }

    /// Gives region `r` its original segments back, for reason `why`.
    fn revert(&mut self, r: usize, why: String) {
        self.reset(r);
        self.reverted[r] = Some(why);
    }

    /// Reverts every changed region whose written error (`after`, mm per
    /// region) did not fall, and, when the program runs `over` s past its
    /// time budget, the changed regions with dwells or corner spikes that
    /// gain the least error per second of the time they add, until the
    /// time they add covers `over` (regions whose best rounds came from
    /// different variants may each fit the budget alone and not together).
    /// Whether any was reverted.
    fn revert_unimproved(
        &mut self,
        orig: &[Segment],
        after: &[f64],
        over: f64,
        sim: &SimConfig,
    ) -> bool {
        let mut bad = false;
        // `after` has one error per region.
        for (r, &a) in after.iter().enumerate() {
            if self.changed(r) && a >= self.before_err[r] {
                self.revert(
                    r,
                    format!(
                        "the written program's error here did not fall ({} → {} µm)",
                        crate::numeric::compact(self.before_err[r] * 1e3),
                        crate::numeric::compact(a * 1e3)
                    ),
                );
                bad = true;
            }
        }
        if over <= 0.0 {
            return bad;
        }
        // (gain per second, added time, region)
        let mut timed: Vec<(f64, f64, usize)> = (0..after.len())
            .filter(|&r| self.changed(r))
            .filter_map(|r| {
                let t: f64 = self.rg.members[r]
                    .iter()
                    .map(|&i| {
                        self.edit.dwell_after[i]
                            + corner::spike_time(&orig[i], sim, self.edit.spike[i])
                    })
                    .sum();
                (t > 0.0).then(|| ((self.before_err[r] - after[r]) / t, t, r))
            })
            .collect();
        timed.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut freed = 0.0;
        for (_, t, r) in timed {
            if freed >= over {
                break;
            }
            let m = &self.rg.members[r];
            let dwells: f64 = m.iter().map(|&i| self.edit.dwell_after[i]).sum();
            if dwells > 0.0
                && changed(self.rg, r, self.fallback, &self.radius0)
                && m.iter().all(|&i| self.fallback.dwell_after[i] == 0.0)
            {
                // Its dwells go, its spikes and corrections stay.
                self.save(r);
                copy_region(self.rg, r, self.fallback, &mut self.edit);
                freed += dwells;
                bad = true;
                continue;
            }
            self.revert(
                r,
                "its dwells and corner spikes would exceed the time budget (it gained the least per second added)".to_string(),
            );
            freed += t;
            bad = true;
        }
        bad
    }

    /// An unchanged region that got worse (`after`, mm per region): its
    /// changed neighbours reached it (no exact stop between them); they go
    /// back. Whether any was reverted.
    fn revert_neighbours(&mut self, orig: &[Segment], after: &[f64]) -> bool {
        let (rg, before_err) = (self.rg, self.before_err);
        let mut bad = false;
        for r in 0..rg.members.len() {
            if self.changed(r) || after[r] <= before_err[r] + NEIGHBOUR_SLACK {
                continue;
            }
            for q in [r.wrapping_sub(1), r + 1] {
                if q < rg.members.len() && self.changed(q) && !self.stopped_between(orig, r, q) {
                    self.revert(
                        q,
                        format!(
                            "it raised the error of the neighbouring region (lines {}–{}) from {} to {} µm",
                            orig[rg.members[r][0]].line,
                            orig[rg.members[r][rg.members[r].len() - 1]].line,
                            crate::numeric::compact(before_err[r] * 1e3),
                            crate::numeric::compact(after[r] * 1e3)
                        ),
                    );
                    bad = true;
                }
            }
        }
        bad
    }
}

impl Review<'_> {
    /// Regions `r` and `q` are parted by a rapid, whose exact stop keeps
    /// one's changes from the other's motion: a rise of `r`'s sampled
    /// error is then the sampling phase only (a corner spike's length,
    /// unlike a 0.1 s dwell, is no whole number of samples; a V-carve's
    /// stroke of three 0.04 mm moves at 2 ms per sample rose from 1.7 to
    /// 8.3 µm), not `q`'s doing. The program's maximum error is checked
    /// as a whole all the same.
    fn stopped_between(&self, orig: &[Segment], r: usize, q: usize) -> bool {
        region::rapid_between(orig, self.rg, r, q)
    }

    /// A cutting move in no region (fixed, or outside the line range)
    /// whose error rose (`after`, mm per segment) while within `memory`
    /// seconds (nominal) after a changed region: that region reached it
    /// (no stop between them); it goes back, and so does the changed
    /// region after the move, if any. Whether any was reverted.
    ///
    /// Past that memory the command is the original's and only the
    /// sampling phase differs (the changed region's time shifts the grid),
    /// which moves a sampled maximum by up to its change in one step: no
    /// sign of the edit, so not judged.
    fn revert_near_strays(
        &mut self,
        orig: &[Segment],
        after: &[f64],
        memory: f64,
        sim: &SimConfig,
    ) -> bool {
        let rg = self.rg;
        let changed: Vec<usize> = (0..rg.members.len()).filter(|&r| self.changed(r)).collect();
        let mut reach = vec![None; orig.len()];
        for &r in &changed {
            let mut t = 0.0;
            for k in rg.members[r][rg.members[r].len() - 1] + 1..orig.len() {
                if t >= memory || rg.of[k].is_some_and(|q| q != r) {
                    break;
                }
                reach[k] = Some(r);
                t += match orig[k].motion {
                    Motion::Dwell { seconds } => seconds,
                    Motion::Rapid => break,
                    _ => orig[k].length() / (orig[k].feed * sim.feed_override / 60.0),
                };
            }
        }
        let mut bad = false;
        for i in 0..orig.len() {
            let (b, a) = (self.before_seg[i], after.get(i).copied().unwrap_or(0.0));
            let Some(r) = reach[i] else { continue };
            if rg.of[i].is_some() || !orig[i].is_cutting() || a <= b + NEIGHBOUR_SLACK {
                continue;
            }
            let next = changed.iter().copied().find(|&q| rg.members[q][0] > i);
            for q in std::iter::once(r).chain(next) {
                self.revert(
                    q,
                    format!(
                        "it raised the error of line {}, which may not change (a fixed move or outside the lines to compensate), from {} to {} µm",
                        orig[i].line,
                        crate::numeric::compact(b * 1e3),
                        crate::numeric::compact(a * 1e3)
                    ),
                );
                bad = true;
            }
        }
        bad
    }
}

/// Why region `r` is unchanged.
fn reason(
    rg: &Regions,
    r: usize,
    orig: &[Segment],
    err: f64,
    dwell_note: Option<&String>,
) -> String {
    let (arcs, lines) = kinds(rg, r, orig);
    if !rg.movable[r] {
        return if arcs > 0 {
            "its arcs touch fixed segments (subprogram, cycle or corner), so nothing may move"
                .into()
        } else {
            "a single line between rapids or fixed segments: no corner to move".into()
        };
    }
    let e = crate::numeric::compact(err * 1e3);
    let what = if arcs == 0 {
        format!("line-only region ({lines} lines): vertex shifts did not lower its error ({e} µm)")
    } else {
        format!("no correction round lowered its error ({e} µm)")
    };
    match dwell_note {
        Some(d) => format!("{what}, and {d}"),
        None => what,
    }
}

#[allow(clippy::too_many_arguments)]
fn finish(
    (orig, facts): (&[Segment], &Facts),
    range: &LineRange,
    rg: &Regions,
    before_err: &[f64],
    sim_before: Simulation,
    c: Checked,
    notes: Vec<Option<String>>,
    history: Vec<f64>,
) -> Compensation {
    // The written program's segments are the check's rebuilt ones.
    let rebuilt = c.sim.is_some();
    let sim_after = c.sim.unwrap_or_else(|| sim_before.clone());
    let radius0 = radii(orig);
    let line = |i: usize| orig[i].line;
    let mut regions: Vec<RegionNote> = (0..rg.members.len())
        .map(|r| {
            let ch = changed(rg, r, &c.edit, &radius0);
            let m = &rg.members[r];
            let (arcs, lines) = kinds(rg, r, orig);
            RegionNote {
                first_line: m.first().map_or(0, |&i| line(i)),
                last_line: m.last().map_or(0, |&i| line(i)),
                arcs,
                lines,
                before_um: before_err[r] * 1e3,
                after_um: c.after[r] * 1e3,
                changed: ch,
                reason: if ch {
                    // Only a result taken before the checks settled
                    // notes a changed region (its error rose).
                    c.reverted[r].clone().unwrap_or_default()
                } else {
                    c.reverted[r]
                        .clone()
                        .unwrap_or_else(|| reason(rg, r, orig, before_err[r], notes[r].as_ref()))
                },
            }
        })
        .collect();
    regions.extend(fixed_moves_note(
        (orig, facts.has_macros),
        range,
        rg,
        &sim_before,
        &sim_after,
    ));
    regions.extend(outside_notes(orig, rg, range, &sim_before, &sim_after));
    let dwells = c
        .edit
        .dwell_after
        .iter()
        .enumerate()
        .filter(|(_, &d)| d > 0.0)
        .map(|(i, &d)| DwellAt {
            after_line: orig[i].line,
            seconds: d,
        })
        .collect();
    let spikes = c
        .edit
        .spike
        .iter()
        .enumerate()
        .filter(|(_, d)| **d != [0.0; 3])
        .map(|(i, d)| SpikeAt {
            after_line: orig[i].line,
            depth_um: (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() * 1e3,
        })
        .collect();
    Compensation {
        before: summary(&sim_before),
        after: summary(&sim_after),
        segments: changes((orig, facts.blocks), rebuilt, &c.edit),
        dwells,
        spikes,
        regions,
        history_um: history,
        nc: c.nc,
        sim_before,
        sim_after,
        unchanged: None,
        dwell_note: None,
        expanded: false,
        expand_note: None,
        budget_note: None,
    }
}

/// The note of the cutting moves that belong to no region because they
/// cannot be rewritten (macro-computed or polar end points, subprogram or
/// macro bodies, cycles, corner roundings, cutter-compensated stretches):
/// one entry over them, with their largest error before and after and why
/// they were left as they are, so an error peak there is never unexplained.
/// `None` when every cutting move belongs to a region.
fn fixed_moves_note(
    (segs, has_macros): (&[Segment], bool),
    range: &LineRange,
    rg: &Regions,
    sim_before: &Simulation,
    sim_after: &Simulation,
) -> Option<RegionNote> {
    let fixed: Vec<usize> = (0..segs.len())
        .filter(|&i| segs[i].is_cutting() && rg.of[i].is_none() && range.contains(segs[i].line))
        .collect();
    let (first, last) = (*fixed.first()?, *fixed.last()?);
    let arcs = fixed
        .iter()
        .filter(|&&i| matches!(segs[i].motion, Motion::Arc(_)))
        .count();
    let worst = |sim: &Simulation| {
        sim.segments
            .iter()
            .filter(|st| fixed.binary_search(&st.segment).is_ok())
            .map(|st| st.max_error_um)
            .fold(0.0, f64::max)
    };
    let macros = if has_macros {
        "the program computes words with macro variables or expressions (Macro B, o-words, \
         G65), and "
    } else {
        ""
    };
    let every = if rg.members.is_empty() {
        "no cutting move can be rewritten"
    } else {
        "these cutting moves cannot be rewritten"
    };
    Some(RegionNote {
        first_line: segs[first].line,
        last_line: segs[last].line,
        arcs,
        lines: fixed.len() - arcs,
        before_um: worst(sim_before),
        after_um: worst(sim_after),
        changed: false,
        reason: format!(
            "{every}: {macros}their end points are not literal words of their \
             own block (macro-computed or LinuxCNC polar words, subprogram or macro bodies, \
             canned cycles, corner roundings, cutter-compensated stretches); reverse \
             compensation moves only literal coordinate words. Post the path with literal \
             coordinates (a CAM post, or the control's expanded program) to compensate it"
        ),
    })
}

fn summary(s: &Simulation) -> Summary {
    Summary {
        max_error_um: s.max_error * 1e3,
        motion_time: s.motion_time,
    }
}

/// Per original segment of `orig` (of a program of `blocks` blocks), what
/// the written program made of it: `edit` rebuilt ([`geometry::rebuild_each`],
/// one segment at a time), or with `rebuilt` false the original itself.
fn changes((orig, blocks): (&[Segment], usize), rebuilt: bool, edit: &Edit) -> Vec<SegmentChange> {
    let mut end_of = vec![None; blocks];
    let mut note = |x: &Segment| {
        if let Some(b) = x.block.filter(|&b| b < end_of.len()) {
            end_of[b] = Some(x.end.p());
        }
    };
    if rebuilt {
        geometry::rebuild_each(orig, edit, &mut |x, _| note(&x));
    } else {
        orig.iter().for_each(note);
    }
    orig.iter()
        .enumerate()
        .map(|(i, s)| {
            let new_end = s.block.and_then(|b| end_of[b]).unwrap_or(s.end.p());
            let (kind, r) = match s.motion {
                Motion::Arc(a) => ("arc", a.radius),
                Motion::Linear => ("line", 0.0),
                Motion::Rapid => ("rapid", 0.0),
                Motion::Dwell { .. } => ("dwell", 0.0),
            };
            SegmentChange {
                segment: i,
                line: s.line,
                kind,
                radius_before: r,
                radius_after: if kind == "arc" { edit.radius[i] } else { 0.0 },
                end_shift_um: dist(s.end.p(), new_end) * 1e3,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "G21 G90 G17\nG0 X1.5 Y-2\nG1 X12.25 F900\nG2 X15.25 Y1 I0 J3\nG1 Z-1.75\n";

    fn source(text: &str) -> Source<'_> {
        Source::new(text, parse_with(text, &ParseOptions::default()).unwrap())
    }

    #[test]
    fn slim_drops_the_blocks_and_program_reads_them_again() {
        let whole = parse_with(TEXT, &ParseOptions::default()).unwrap();
        assert_eq!(whole.modal.len(), 5);
        let mut s = source(TEXT);
        s.slim();
        assert!(s.program.blocks.is_empty() && s.program.modal.is_empty());
        assert_eq!(s.program.modes.states(), 0);
        assert_eq!(s.segments(), &whole.segments[..]);
        assert_eq!(s.program(Keep::All).unwrap(), &whole);
        // Read whole, a Patch reading needs nothing more.
        let at = s.program(Keep::Patch).unwrap() as *const Program;
        assert_eq!(s.program(Keep::All).unwrap() as *const Program, at);
        assert_eq!(s.program.modal.len(), 5);
        // A second slim keeps the first fingerprint; the writer's reading
        // keeps the blocks and the writer's modes, one whole modal state.
        s.slim();
        assert!(s.program.blocks.is_empty());
        let patch = s.program(Keep::Patch).unwrap();
        assert_eq!(patch.blocks, whole.blocks);
        assert_eq!(patch.segments, whole.segments);
        assert_eq!(patch.modes, whole.modes);
        assert_eq!(patch.modal.len(), 1);
        // … and a whole reading after it reads again.
        assert_eq!(s.program(Keep::All).unwrap(), &whole);
    }

    #[test]
    fn a_second_reading_with_other_moves_is_an_error() {
        let mut s = source(TEXT);
        s.slim();
        let right = s.fingerprint.unwrap();
        assert_ne!(right, rounds::NEVER_EQUAL);
        for wrong in [right ^ 1, rounds::NEVER_EQUAL] {
            s.slim();
            s.fingerprint = Some(wrong);
            match s.program(Keep::All) {
                Err(ToolpathError::Config { field, message }) => {
                    assert_eq!(field, "text");
                    assert!(message.contains("other moves"), "{message}");
                }
                other => panic!("fingerprint {wrong:#x}: {other:?}"),
            }
        }
    }
}
