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
//! Every chunk of a region (see [`super::region::chunks`]: a long region
//! is cut into parts of at least [`CHUNK_MEMORIES`] memories of motion)
//! keeps the edit of the round in which its own maximum error was lowest;
//! a chunk whose error stops falling for two rounds stops being corrected.
//! A round simulates only windows around the original segments whose
//! rebuilt command changed or moved in time since the previous round
//! ([`crate::toolpath::locality`]: the NC filter forgets a change after
//! `tA`, the servo lag after `12·T`), and the places whose nearest samples
//! come from there; the statistics elsewhere stand from earlier rounds
//! (the first round's are the original's simulation), and all of them
//! equal a whole-program simulation of the round's command. The written program is then checked against
//! the whole original path ([`super::reverse_compensate`]). Regions are
//! separated by rapids (which end in an exact stop) and by fixed segments,
//! chunks by at least several memories of motion, so the edit of one
//! barely changes another's error, and the best rounds of different
//! chunks combine (the check judges the combination).
//!
//! Units: mm, s.

use std::rc::Rc;

use super::geometry::{rebuild_indexed, Edit};
use super::region::{chunks, Regions};
use crate::budget::{
    MAX_REVERSE_CHECK_SAMPLES, MAX_REVERSE_SIMULATED_SAMPLES, MIN_REVERSE_SIMULATED_SAMPLES,
    REVERSE_PROGRAM_SIMULATIONS, REVERSE_SAMPLES_PER_SEGMENT,
};
use crate::nc::program::{Motion, Segment};
use crate::toolpath::contour::Path;
use crate::toolpath::locality::{memory, piece_starts, update, Windowed};
use crate::toolpath::{SimConfig, Simulation, ToolpathError, WindowStats};

/// A chunk spans at least this many [`memory`] spans of nominal motion
/// (8 × 0.22 s at tA 40 ms, T 15 ms): long against the reach of a change
/// across its border, short enough that a raster's parts keep their own
/// best rounds.
pub const CHUNK_MEMORIES: f64 = 8.0;

/// The outcome of the rounds: per region its best error and the edit that
/// gave it.
#[derive(Debug, Clone)]
pub struct Rounds {
    /// The combined edit (each chunk's best round).
    pub edit: Edit,
    /// Best maximum error per region (the largest of its chunks'), mm.
    pub error: Vec<f64>,
    /// Maximum error of the whole path per round, µm.
    pub history_um: Vec<f64>,
}

impl Rounds {
    /// The largest of the regions' best maximum errors, mm.
    pub fn worst(&self) -> f64 {
        self.error.iter().copied().fold(0.0, f64::max)
    }
}

/// The original program's simulation, from which every set of rounds
/// starts: its reference path and per-segment statistics.
#[derive(Debug)]
struct Base {
    path: Path,
    stats: Rc<Vec<Option<WindowStats>>>,
}

/// What one compensation may still simulate. The correction rounds
/// simulate windows around the places they change
/// ([`crate::toolpath::locality`]), up to [`window_budget`] samples in
/// all; the whole-program
/// simulations (the original, the checks of the written program) are
/// budgeted apart: each is at most one simulation's budget
/// ([`crate::budget::MAX_TOOLPATH_SAMPLES`]), and the checks may spend
/// [`MAX_REVERSE_CHECK_SAMPLES`], or two simulations of the program when
/// that is more.
#[derive(Debug, Clone)]
pub struct Work {
    /// The rounds' budget, window samples.
    limit: u64,
    left: u64,
    checks: u64,
    /// Samples of one simulation of the whole program.
    pub program: u64,
    /// A round or check was skipped for want of budget.
    pub stopped: bool,
    base: Option<Rc<Base>>,
}

/// The rounds' window budget of a program of `segments` segments and
/// `program` samples (see [`Work`]): [`REVERSE_SAMPLES_PER_SEGMENT`] a
/// segment or [`REVERSE_PROGRAM_SIMULATIONS`] simulations of the program,
/// whichever is more, within [`MIN_REVERSE_SIMULATED_SAMPLES`] and
/// [`MAX_REVERSE_SIMULATED_SAMPLES`].
pub fn window_budget(segments: usize, program: u64) -> u64 {
    let places = segments.saturating_mul(REVERSE_SAMPLES_PER_SEGMENT) as u64;
    let runs = program.saturating_mul(REVERSE_PROGRAM_SIMULATIONS as u64);
    places.max(runs).clamp(
        MIN_REVERSE_SIMULATED_SAMPLES as u64,
        MAX_REVERSE_SIMULATED_SAMPLES as u64,
    )
}

impl Work {
    /// The budget of one compensation of a program of `segments`
    /// segments and `program` samples.
    pub fn for_program(segments: usize, program: u64) -> Self {
        Self::new(window_budget(segments, program), program)
    }

    /// What the result says when the budget cut the work short.
    pub fn note(&self) -> Option<String> {
        self.stopped.then(|| {
            format!(
                "the work budget ({} simulated samples of correction windows around the corrected places ({REVERSE_SAMPLES_PER_SEGMENT} per segment or {REVERSE_PROGRAM_SIMULATIONS} simulations of the program, within {MIN_REVERSE_SIMULATED_SAMPLES} and {MAX_REVERSE_SIMULATED_SAMPLES}), checks of the written program {} samples at most, {} per simulation of this program) stopped the correction early; the best rounds so far are kept and checked. Raise dt or compensate the program in parts for a full run",
                self.limit,
                MAX_REVERSE_CHECK_SAMPLES.max(2 * self.program as usize),
                self.program
            )
        })
    }

    /// `limit` window samples for the rounds of a program of `program`
    /// samples, and the checks' own budget (see [`Work`]).
    pub fn new(limit: u64, program: u64) -> Self {
        Self {
            limit,
            left: limit,
            checks: (MAX_REVERSE_CHECK_SAMPLES as u64).max(program.saturating_mul(2)),
            program,
            stopped: false,
            base: None,
        }
    }

    /// Samples the rounds may still spend.
    pub fn left(&self) -> u64 {
        self.left
    }

    /// Starts every set of rounds from `sim`, the simulation of `orig`
    /// against itself: a round then simulates only around what differs
    /// from it. Without it the first round simulates the whole program.
    pub fn set_original(&mut self, orig: &[Segment], sim: &Simulation) {
        let mut stats = vec![None; orig.len()];
        for st in &sim.segments {
            if let Some(slot) = stats.get_mut(st.segment) {
                *slot = Some(st.into());
            }
        }
        self.base = Some(Rc::new(Base {
            path: Path::new(orig),
            stats: Rc::new(stats),
        }));
    }

    /// The statistics of the original's simulation per original segment
    /// ([`Work::set_original`]; `None` without it): the caller may drop
    /// the simulation.
    pub fn original_stats(&self) -> Option<Rc<Vec<Option<WindowStats>>>> {
        self.base.as_ref().map(|b| b.stats.clone())
    }

    /// Drops the original's reference path and statistics
    /// ([`Work::set_original`]; 450 MB of a 1 M-segment program) once no
    /// more rounds run: the checks simulate the whole program.
    pub fn forget_original(&mut self) {
        self.base = None;
    }

    /// Sets aside `1/share` of the rounds' budget left (for a later stage:
    /// the dwells), to be given back with [`Work::release`].
    pub fn hold(&mut self, share: u64) -> u64 {
        let held = self.left / share.max(1);
        self.left -= held;
        held
    }

    /// Gives back what [`Work::hold`] set aside.
    pub fn release(&mut self, held: u64) {
        self.left += held;
    }

    /// Spends `samples` on a correction round when the rounds' budget
    /// holds them; otherwise marks the work as stopped and returns `false`.
    pub fn round(&mut self, samples: u64) -> bool {
        take(&mut self.left, samples, &mut self.stopped)
    }

    /// Spends `samples` on a check of the written program; `false` when
    /// the checks' budget is spent.
    pub fn check(&mut self, samples: u64) -> bool {
        take(&mut self.checks, samples, &mut self.stopped)
    }
}

fn take(left: &mut u64, samples: u64, stopped: &mut bool) -> bool {
    if *left >= samples {
        *left -= samples;
        true
    } else {
        *stopped = true;
        false
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
        tangent_lines: false,
    }
}

/// Copies region `r`'s entries of `from` into `to`.
pub fn copy_region(regions: &Regions, r: usize, from: &Edit, to: &mut Edit) {
    copy(&regions.members[r], from, to);
}

fn copy(members: &[usize], from: &Edit, to: &mut Edit) {
    for &i in members {
        to.radius[i] = from.radius[i];
        to.vertex_shift[i] = from.vertex_shift[i];
        to.dwell_after[i] = from.dwell_after[i];
        to.spike[i] = from.spike[i];
    }
}

/// The command segments of original segment `i`'s piece (its own, a
/// dwell after it, a connector before the next; see
/// [`crate::toolpath::locality::plan`]).
fn piece<'a>(cmd: &'a [Segment], at: &[usize], i: usize) -> &'a [Segment] {
    let a = if i == 0 { 0 } else { at[i] };
    let b = at.get(i + 1).copied().unwrap_or(cmd.len());
    &cmd[a..b]
}

/// A 128-bit fingerprint of each piece of `cmd` ([`piece`]): what
/// [`LocalStats`] keeps of the last command to find the pieces that
/// changed, instead of the command itself (184 B a segment: 175 MB of a
/// 1 M-segment program). Two pieces that differ under `==` get different
/// fingerprints (always when they differ in one word, see `Fingerprint`;
/// otherwise but with a chance of about 2⁻¹²⁸); equal ones get equal
/// ones, except that ±0 are one value and a piece with a NaN gets
/// [`NEVER_EQUAL`] (a NaN is unequal to itself under `==`).
pub(super) fn fingerprints(cmd: &[Segment], at: &[usize]) -> Vec<u128> {
    (0..at.len())
        .map(|i| {
            let p = piece(cmd, at, i);
            let mut h = Fingerprint::new();
            for s in p {
                // Every field, named: a new one fails to compile here.
                let Segment {
                    block,
                    line,
                    motion,
                    start,
                    end,
                    feed,
                    fixed,
                } = s;
                let tag = match motion {
                    Motion::Rapid => 1,
                    Motion::Linear => 2,
                    Motion::Dwell { seconds } => {
                        h.f(*seconds);
                        3
                    }
                    Motion::Arc(a) => {
                        let crate::nc::program::Arc {
                            center,
                            radius,
                            plane,
                            sweep,
                            r_form,
                        } = a;
                        center.iter().for_each(|&c| h.f(c));
                        h.f(*radius);
                        h.f(*sweep);
                        4 + 8 * (*plane as u64) + 64 * u64::from(*r_form)
                    }
                };
                start.to_array().into_iter().for_each(|x| h.f(x));
                end.to_array().into_iter().for_each(|x| h.f(x));
                h.f(*feed);
                h.u(tag);
                h.u(block.map_or(u64::MAX, |b| b as u64));
                h.u(*line as u64);
                h.u(u64::from(*fixed));
            }
            h.u(p.len() as u64);
            if h.nan {
                return NEVER_EQUAL;
            }
            h.finish()
        })
        .collect()
}

/// The fingerprint of a piece that is changed whatever it was before.
pub(super) const NEVER_EQUAL: u128 = 0;

/// Two 64-bit lanes, each taking one word at a time through a bijective
/// mix (`h ← mix(h ^ word)`, the second lane's word first multiplied by
/// an odd constant and mixed by other constants): for a given prefix two
/// different words leave different states, and the same words after
/// them keep them different, so two pieces of the same length that
/// differ in one word never get the same fingerprint; other differences
/// collide by chance only. A third of the cost of two SipHash states
/// (the fingerprints were 3.8 % of Gates' compensation natively).
struct Fingerprint {
    h: [u64; 2],
    nan: bool,
}

/// A 64-bit finaliser of the form of MurmurHash3's `fmix64` (xor-shift,
/// odd multiplier, xor-shift, odd multiplier, xor-shift; here the shifts
/// 33, 29, 32, where `fmix64` shifts by 33 each time) with the
/// multipliers `(m1, m2)`: a bijection of u64 (each step is invertible)
/// that spreads every input bit.
#[inline]
fn fmix(mut x: u64, (m1, m2): (u64, u64)) -> u64 {
    x ^= x >> 33;
    x = x.wrapping_mul(m1);
    x ^= x >> 29;
    x = x.wrapping_mul(m2);
    x ^ (x >> 32)
}

impl Fingerprint {
    fn new() -> Self {
        Self {
            h: [0x243f_6a88_85a3_08d3, 0x1319_8a2e_0370_7344],
            nan: false,
        }
    }

    #[inline]
    fn u(&mut self, x: u64) {
        self.h[0] = fmix(
            self.h[0] ^ x,
            (0xff51_afd7_ed55_8ccd, 0xc4ce_b9fe_1a85_ec53),
        );
        self.h[1] = fmix(
            self.h[1] ^ x.wrapping_mul(0x9e37_79b9_7f4a_7c15),
            (0xbf58_476d_1ce4_e5b9, 0x94d0_49bb_1331_11eb),
        );
    }

    /// `x`, with ±0 as one value; a NaN marks the piece.
    #[inline]
    fn f(&mut self, x: f64) {
        self.nan |= x.is_nan();
        self.u(if x == 0.0 { 0 } else { x.to_bits() });
    }

    fn finish(&self) -> u128 {
        (u128::from(self.h[0]) << 64) | u128::from(self.h[1])
    }
}

/// Runs up to `iterations + 1` rounds from `start` (see the module header),
/// as many as `work` allows. A round simulates the windows around the
/// original segments whose rebuilt command differs from the previous
/// round's (the first: from the original program's, when `work` holds it,
/// [`Work::set_original`]; else the whole program); the statistics of the
/// other segments stand. With no round affordable the errors stay
/// infinite and `start` is returned.
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
    let ch = chunks(
        regions,
        orig,
        CHUNK_MEMORIES * memory(cfg),
        cfg.feed_override,
    );
    let nc = ch.members.len();
    let mut movable = vec![false; nc];
    for (c, m) in ch.members.iter().enumerate() {
        movable[c] = m.iter().any(|&i| regions.arc_free[i]);
    }
    for &(i, _) in &regions.line_joints {
        if let Some(c) = ch.of[i] {
            movable[c] = true;
        }
    }
    let mut local = LocalStats::new(orig, work);
    let mut edit = start;
    let mut best = edit.clone();
    let mut best_err = vec![f64::INFINITY; nc];
    let mut stall = vec![0usize; nc];
    let mut history = Vec::new();
    for round in 0..=iterations {
        if !local.update(orig, cfg, &edit, work)? {
            break;
        }
        let seg_err = |i: usize| {
            local.by_seg[i]
                .as_ref()
                .map_or(0.0, |s| s.max_error_um * 1e-3)
        };
        let errs: Vec<f64> = ch
            .members
            .iter()
            .map(|m| m.iter().map(|&i| seg_err(i)).fold(0.0, f64::max))
            .collect();
        // No region, no round to report (the page would show "0 µm").
        if nc > 0 {
            history.push(errs.iter().copied().fold(0.0, f64::max) * 1e3);
        }
        let mut active = false;
        for c in 0..nc {
            if errs[c] < best_err[c] {
                best_err[c] = errs[c];
                copy(&ch.members[c], &edit, &mut best);
                stall[c] = 0;
            } else {
                stall[c] += 1;
            }
            active |= stall[c] < 2 && movable[c];
        }
        if round == iterations || !active {
            break;
        }
        let live = |i: usize| {
            ch.of[i].is_some_and(|c| stall[c] < 2) && regions.editable[i] && !orig[i].fixed
        };
        correct(orig, regions, &local.by_seg, (&live, step), &mut edit);
    }
    let mut error = vec![f64::NEG_INFINITY; regions.members.len()];
    for (c, &r) in ch.region.iter().enumerate() {
        error[r] = error[r].max(best_err[c]);
    }
    Ok(Rounds {
        edit: best,
        error,
        history_um: history,
    })
}

/// Per-segment statistics of an edited program against the original
/// path, kept up to date by simulating only windows around what each new
/// edit changed ([`crate::toolpath::locality`]); they start from the
/// original's simulation when `work` holds it ([`Work::set_original`]),
/// else the first update simulates the whole program.
pub struct LocalStats {
    base: Option<Rc<Base>>,
    own: Option<Path>,
    /// Statistics per original segment (`None`: no sample nearest to it).
    pub by_seg: Vec<Option<WindowStats>>,
    /// The last command's [`fingerprints`].
    prev: Option<Vec<u128>>,
    /// The start time of each original segment's piece in the last
    /// command (`None` before the first update).
    starts: Option<Vec<f64>>,
}

impl LocalStats {
    /// The statistics of `orig` as `work` holds them.
    pub fn new(orig: &[Segment], work: &Work) -> Self {
        let n = orig.len();
        match &work.base {
            Some(b) => Self {
                base: Some(b.clone()),
                own: None,
                by_seg: b.stats.to_vec(),
                prev: Some({
                    let (cmd, at) = rebuild_indexed(orig, &identity(orig, vec![0.0; n]));
                    fingerprints(&cmd, &at)
                }),
                starts: None,
            },
            None => Self {
                base: None,
                own: Some(Path::new(orig)),
                by_seg: vec![None; n],
                prev: None,
                starts: None,
            },
        }
    }

    /// Times the original program's pieces, once: the original's
    /// statistics are of the original program, whose pieces are those of
    /// the identity edit (timed before an edit's command is built: one
    /// command at a time).
    fn time_original(&mut self, orig: &[Segment], cfg: &SimConfig) -> Result<(), ToolpathError> {
        if self.starts.is_none() && self.base.is_some() {
            let n = orig.len();
            let (id, id_at) = rebuild_indexed(orig, &identity(orig, vec![0.0; n]));
            self.starts = Some(piece_starts(&id, &id_at, cfg)?);
        }
        Ok(())
    }

    /// Simulates the windows around the original segments whose rebuilt
    /// command under `edit` differs from the last update's, when `work`
    /// affords them (`false`, nothing done, when not).
    ///
    /// # Errors
    /// As [`simulate()`](crate::toolpath::simulate()).
    pub fn update(
        &mut self,
        orig: &[Segment],
        cfg: &SimConfig,
        edit: &Edit,
        work: &mut Work,
    ) -> Result<bool, ToolpathError> {
        self.time_original(orig, cfg)?;
        let (cmd, at) = rebuild_indexed(orig, edit);
        self.update_command(orig, cfg, (&cmd, &at), work)
    }

    /// As [`LocalStats::update`] for a command given as it is: `cmd`,
    /// where original segment `i` owns `cmd[at[i]..at[i + 1]]` (the
    /// pieces of [`rebuild_indexed`]). The written program read back
    /// with its rebuilt command's `at` gives the windowed prediction of
    /// the program as written, its numbers rounded as the writer rounds
    /// them.
    ///
    /// # Errors
    /// As [`simulate()`](crate::toolpath::simulate()).
    pub fn update_command(
        &mut self,
        orig: &[Segment],
        cfg: &SimConfig,
        (cmd, at): (&[Segment], &[usize]),
        work: &mut Work,
    ) -> Result<bool, ToolpathError> {
        self.time_original(orig, cfg)?;
        let n = orig.len();
        let now = fingerprints(cmd, at);
        let changed: Vec<bool> = match &self.prev {
            Some(prev) => (0..n)
                .map(|i| now[i] != prev[i] || now[i] == NEVER_EQUAL)
                .collect(),
            None => vec![true; n],
        };
        let path = match (&self.base, &self.own) {
            (Some(b), _) => &b.path,
            (None, Some(p)) => p,
            (None, None) => return Ok(false),
        };
        let mut w = Windowed {
            stats: std::mem::take(&mut self.by_seg),
            starts: self.starts.take(),
        };
        let done = update(cmd, at, (path, orig), &changed, &mut w, cfg, &mut |s| {
            work.round(s)
        });
        self.by_seg = w.stats;
        self.starts = w.starts;
        if !done? {
            return Ok(false);
        }
        self.prev = Some(now);
        Ok(true)
    }
}

/// The default share of the measured deviation one round corrects
/// ([`super::ReverseConfig::step`]). The full deviation (qiu's reading)
/// overshoots where neighbouring corrections add up (CAM chains of short
/// lines, small arcs between lines: ledfloor's rounds went 120 → 142 →
/// 219 µm). Measured over the corpus (`cargo run --release --example
/// reverse_corpus`, tA 40 ms, T 15 ms, dt 2 ms), the median after/before
/// fell from 0.82 at 1 to 0.68 at 0.5; 0.3, 0.7, and a step halved each
/// round a region's error rose (from 1 or from 0.5) did no better.
pub const DEFAULT_STEP: f64 = 0.5;

/// One correction of `edit` from the per-segment statistics.
fn correct(
    orig: &[Segment],
    regions: &Regions,
    by_seg: &[Option<WindowStats>],
    (live, step): (&dyn Fn(usize) -> bool, f64),
    edit: &mut Edit,
) {
    for (i, s) in orig.iter().enumerate() {
        if let (Motion::Arc(_), Some(st)) = (s.motion, &by_seg[i]) {
            if live(i) && regions.arc_free[i] {
                edit.radius[i] += step * st.mean_deviation().unwrap_or(0.0);
            }
        }
    }
    for &(i, k) in &regions.line_joints {
        // A spiked corner's correction is its spike (super::corner).
        if !live(i) || !live(k) || super::corner::spiked(edit, i) {
            continue;
        }
        let v: Vec<[f64; 3]> = [
            by_seg[i].as_ref().and_then(|s| s.half_vector(1)),
            by_seg[k].as_ref().and_then(|s| s.half_vector(0)),
        ]
        .into_iter()
        .flatten()
        .collect();
        if v.is_empty() {
            continue;
        }
        // As for an offset polyline, a vertex moves 1/cos(φ/2) times the
        // offset of its lines (φ the turn between them).
        let gain = 1.0 / half_turn_cos(&orig[i], &orig[k]).max(0.2);
        for ax in 0..3 {
            let mean = v.iter().map(|x| x[ax]).sum::<f64>() / v.len() as f64;
            edit.vertex_shift[i][ax] += step * gain * mean;
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
    use crate::toolpath::{example::arc_example, simulate};

    /// `fmix` is a bijection of u64 (what makes a one-word difference
    /// never collide): undoing its steps in reverse order (a right
    /// xor-shift by s undone by xoring in the shifts by s, 2s, …; an odd
    /// multiplier by its inverse mod 2⁶⁴, from Newton's iteration) gives
    /// the input back, for both lanes' constants.
    #[test]
    fn fmix_is_undone_by_its_inverse() {
        let unshift = |y: u64, s: u32| {
            let mut x = y;
            for _ in 0..64 / s {
                x = y ^ (x >> s);
            }
            x
        };
        let inv = |m: u64| {
            let mut i = m;
            for _ in 0..6 {
                i = i.wrapping_mul(2u64.wrapping_sub(m.wrapping_mul(i)));
            }
            assert_eq!(m.wrapping_mul(i), 1);
            i
        };
        let unfmix = |y: u64, (m1, m2): (u64, u64)| {
            let x = unshift(y, 32).wrapping_mul(inv(m2));
            unshift(unshift(x, 29).wrapping_mul(inv(m1)), 33)
        };
        let lanes = [
            (0xff51_afd7_ed55_8ccd, 0xc4ce_b9fe_1a85_ec53),
            (0xbf58_476d_1ce4_e5b9, 0x94d0_49bb_1331_11eb),
        ];
        let mut x = 0x9e37_79b9_7f4a_7c15_u64;
        for k in 0..2_000u64 {
            x = x.rotate_left(17) ^ k.wrapping_mul(0x2545_f491_4f6c_dd1d);
            for m in lanes {
                assert_eq!(unfmix(fmix(x, m), m), x, "{x:#x}");
            }
        }
        assert_eq!(fmix(0, lanes[0]), 0);
    }

    /// Each lane of the fingerprint spreads every bit of every word:
    /// flipping one input bit (any of 64, in the first, middle or last of
    /// three words) changes both lanes, and about half of each lane's 64
    /// bits (fmix64's avalanche: 192 flips × 32 bits = 6,144 expected per
    /// lane, measured 6,152 and 6,071); the lanes differ from each other.
    #[test]
    fn the_fingerprint_mix_spreads_every_bit() {
        let fp = |words: &[u64; 3]| {
            let mut f = Fingerprint::new();
            words.iter().for_each(|&w| f.u(w));
            f.finish()
        };
        let words = [0x0123_4567_89ab_cdef_u64, 42, 7];
        let base = fp(&words);
        let lanes = |d: u128| [(d >> 64) as u64, d as u64];
        let [hi, lo] = lanes(base);
        assert_ne!(hi, lo);
        let mut flipped = [0u32; 2];
        for w in 0..3 {
            for bit in 0..64 {
                let mut ws = words;
                ws[w] ^= 1 << bit;
                for (k, d) in lanes(fp(&ws) ^ base).into_iter().enumerate() {
                    assert_ne!(d, 0, "lane {k}, word {w}, bit {bit}");
                    flipped[k] += d.count_ones();
                }
            }
        }
        // Within ±5 % of half the bits.
        for (k, n) in flipped.into_iter().enumerate() {
            assert!((5_837..=6_451).contains(&n), "lane {k}: {n} bits flipped");
        }
    }

    /// A piece's fingerprint changes with any word of its segments, and
    /// only then (±0 alike); a NaN piece is never unchanged.
    #[test]
    fn fingerprints_follow_the_pieces() {
        let p = parse(&arc_example()).unwrap();
        let o = &p.segments;
        let (cmd, at) = rebuild_indexed(o, &identity(o, vec![0.0; o.len()]));
        let base = fingerprints(&cmd, &at);
        assert_eq!(base, fingerprints(&cmd.clone(), &at));
        let distinct: std::collections::HashSet<_> = base.iter().collect();
        assert!(
            distinct.len() > o.len() / 2,
            "{} of {}",
            distinct.len(),
            o.len()
        );
        let k = at[5];
        let changed = |f: &dyn Fn(&mut Segment)| {
            let mut c = cmd.clone();
            f(&mut c[k]);
            let now = fingerprints(&c, &at);
            (0..at.len())
                .filter(|&i| now[i] != base[i])
                .collect::<Vec<_>>()
        };
        assert_eq!(changed(&|s| s.end.x += 1e-12), vec![5]);
        assert_eq!(changed(&|s| s.feed *= 1.0 + 1e-15), vec![5]);
        assert_eq!(changed(&|s| s.line += 1), vec![5]);
        assert_eq!(changed(&|s| s.fixed = !s.fixed), vec![5]);
        assert_eq!(changed(&|s| s.start.c = 1.0), vec![5]);
        assert_eq!(changed(&|s| s.block = None), vec![5]);
        let arc = cmd[k..]
            .iter()
            .position(|s| matches!(s.motion, Motion::Arc(_)))
            .map(|j| k + j)
            .unwrap();
        let piece = at.iter().rposition(|&a| a <= arc).unwrap();
        let mut c = cmd.clone();
        if let Motion::Arc(a) = &mut c[arc].motion {
            a.radius += 1e-9;
        }
        let now = fingerprints(&c, &at);
        assert_eq!(
            (0..at.len())
                .filter(|&i| now[i] != base[i])
                .collect::<Vec<_>>(),
            vec![piece]
        );
        // A zero changes sign (as under ==): unchanged.
        let mut c = cmd.clone();
        c[k].start.c = -0.0;
        assert_eq!(fingerprints(&c, &at), base);
        // A NaN: changed, and again the next time.
        c[k].start.c = f64::NAN;
        let nan = fingerprints(&c, &at);
        assert_eq!(nan[5], NEVER_EQUAL);
        assert_eq!(nan[..5], base[..5]);
    }

    #[test]
    fn work_budgets_rounds_and_checks_apart() {
        let mut w = Work::new(10, 2);
        assert!(w.round(6) && w.round(4)); // the rounds' 10, to the sample
        assert!(!w.round(1) && w.stopped);
        // The checks keep their own budget.
        let big = MAX_REVERSE_CHECK_SAMPLES as u64;
        let mut w = Work::new(0, 3);
        assert!(w.check(big) && !w.stopped);
        assert!(!w.check(1) && w.stopped);
        // A program larger than half of it is still checked twice.
        let mut w = Work::new(0, big);
        assert!(w.check(big) && w.check(big) && !w.check(1));
        assert!(Work::for_program(1, 1).note().is_none());
        assert!(w.note().unwrap().contains(&format!("{big} per simulation")));
    }

    /// The rounds' budget grows with the program: 400 window samples a
    /// segment or three simulations of it, whichever is more, from 8 M to
    /// 16 M.
    #[test]
    fn the_window_budget_grows_with_the_program() {
        assert_eq!(window_budget(0, 0), 8_000_000);
        assert_eq!(window_budget(20_000, 2_666_666), 8_000_000);
        assert_eq!(window_budget(20_001, 0), 8_000_400);
        assert_eq!(window_budget(35_288, 2_000_000), 14_115_200);
        assert_eq!(window_budget(6_216, 2_836_088), 8_508_264);
        assert_eq!(window_budget(10, 2_666_667), 8_000_001);
        assert_eq!(window_budget(40_000, 0), 16_000_000);
        assert_eq!(window_budget(0, 5_333_334), 16_000_000);
        assert_eq!(window_budget(usize::MAX, u64::MAX), 16_000_000);
        let mut w = Work::for_program(30_000, 5);
        assert_eq!(w.left(), 12_000_000);
        assert!(!w.round(12_000_001) && w.stopped);
        assert!(w
            .note()
            .unwrap()
            .starts_with("the work budget (12000000 simulated samples"));
    }

    #[test]
    fn rounds_stop_at_the_budget_and_keep_their_best() {
        let p = parse(&arc_example()).unwrap();
        let cfg = SimConfig::default();
        let rg = regions(&p);
        let start = || identity(&p.segments, vec![0.0; p.segments.len()]);
        let sim = simulate(&p.segments, &p.segments, &cfg).unwrap();
        let mut ample = Work::new(u64::MAX, sim.samples as u64);
        ample.set_original(&p.segments, &sim);
        let full = run(&p.segments, &rg, (&cfg, 1.0), 6, start(), &mut ample).unwrap();
        assert!(!ample.stopped && full.history_um.len() > 3);
        // Round 0 is the original's simulation, at no cost.
        assert_eq!(full.history_um[0], sim.max_error * 1e3);
        let spent = u64::MAX - ample.left;
        assert!(spent > 0);
        // The same first rounds with a budget that stops after the second.
        let mut probe = Work::new(u64::MAX, sim.samples as u64);
        probe.set_original(&p.segments, &sim);
        let one = run(&p.segments, &rg, (&cfg, 1.0), 1, start(), &mut probe).unwrap();
        let first = u64::MAX - probe.left;
        let mut tight = Work::new(first, sim.samples as u64);
        tight.set_original(&p.segments, &sim);
        let cut = run(&p.segments, &rg, (&cfg, 1.0), 6, start(), &mut tight).unwrap();
        assert!(tight.stopped);
        assert_eq!(cut.history_um[..], full.history_um[..2]);
        assert_eq!(one.history_um[..], full.history_um[..2]);
        // Without the original, round 0 simulates the whole program.
        let mut none = Work::new(sim.samples as u64 - 1, sim.samples as u64);
        let zero = run(&p.segments, &rg, (&cfg, 1.0), 6, start(), &mut none).unwrap();
        assert!(none.stopped && zero.history_um.is_empty());
        assert!(zero.error.iter().all(|e| e.is_infinite()));
        let mut whole = Work::new(sim.samples as u64, sim.samples as u64);
        let w = run(&p.segments, &rg, (&cfg, 1.0), 0, start(), &mut whole).unwrap();
        assert!(!whole.stopped && whole.left == 0);
        // The same error within 0.01 µm: the rebuilt unchanged program
        // puts arc end points exactly on their radius (2.3 nm here).
        let d = (w.history_um[0] - full.history_um[0]).abs();
        assert!(d < 1e-2, "{:?} {:?}", w.history_um, full.history_um);
    }
}
