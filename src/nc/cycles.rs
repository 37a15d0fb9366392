//! Canned drilling cycles G73, G74, G76, G81–G89 and G84.2/G84.3 expanded into the
//! moves the machine really makes, in the G17, G18 or G19 plane (drilling
//! along Z, Y or X). Fanuc rules (Fanuc Series 0i-MF/30i-B operator's
//! manuals, "canned cycles for drilling"); where LinuxCNC differs (its G98
//! returns to the *higher* of the initial level and R, it has no G74/G76),
//! Fanuc is followed:
//!
//! - A hole is drilled on the block that gives the cycle code and on every
//!   later block, until G80 or a G0–G3, that gives a plane-axis word, the
//!   drilling-axis word or R. Per hole: rapid to the hole position at the
//!   current level, rapid to the R level, the cycle's own moves, then the
//!   return: to the initial level under G98 (the drilling-axis position when
//!   the cycle mode began) and to R under G99.
//! - Under G90 the R and bottom words are absolute. Under G91, R is the
//!   distance from the initial level and the bottom the distance from R,
//!   and the hole position is incremental, so `K`/`L` repeats (K0: store
//!   the data, drill nothing) step from hole to hole. The G91 bottom is
//!   kept as its distance from R: a later block that gives a new R but no
//!   bottom word moves the bottom with R (`G91 G81 Z-0.6 R-0.5` then
//!   `X1 R-0.3` drills the second hole to R − 0.6, not to the first
//!   hole's bottom), also when that bottom word was written under G90
//!   (the sticky number is read as a G91 distance from R then: the NIST
//!   test program's `g81 x3 y4 r0.2 z-1.1`, `g91 … r0`, `y-2 r0.1` drills
//!   its last hole to R − 1.1). This is the reading of the LinuxCNC G-code manual
//!   (canned cycles: in incremental distance mode R is an increment from
//!   the initial level and Z an increment from R; the interpreter keeps
//!   the last R and Z numbers as sticky words and recomputes both levels
//!   from them on every block, checked with its `rs274`) and of Fanuc
//!   (the G91 Z is "the distance from point R to point Z").
//! - G81: feed to the bottom, rapid out. G82: the same with a dwell P at the
//!   bottom. G83 (peck): feed by Q, rapid back to R, rapid down to
//!   [`PECK_CLEARANCE`] above the last depth, feed on. G73 (high-speed
//!   peck): feed by Q, rapid back by [`PECK_CLEARANCE`], feed on. G84/G74
//!   (tapping, right-/left-hand): feed to the bottom, dwell P, feed back to
//!   R. G84.2/G84.3, Fanuc's rigid tapping (right-/left-hand; Fanuc Series
//!   15i-MA operator's manual, §13.2 "Rigid tapping": the spindle is
//!   position-controlled so that the feed F along the drilling axis and
//!   the spindle speed S keep the pitch P = F/S), move the axes as G84/G74
//!   do (and as G84 after M29 already does): in at F, dwell, out to R at
//!   F, F being pitch × S in mm/min (under G95 F is the pitch and the feed
//!   F × S). The spindle's own motion is not simulated. G85: feed in, feed out to R. G89: as G85 with a dwell. G86: feed
//!   in, rapid out. G76 (fine boring): feed in, dwell, rapid out; the tool
//!   shift Q at the bottom (a machine parameter gives its direction) is not
//!   modelled and is warned about. G88 (boring, manual retract): feed in,
//!   dwell P, then the spindle and the program stop and the operator jogs
//!   the tool out; simulated as a rapid out to the return level, warned
//!   (LinuxCNC's rs274 leaves the retract out and goes on from the
//!   bottom; a Fanuc control returns to the level at rapid after the
//!   manual retract).
//! - G87 back boring in the RS274/NGC form `G87 X Y Z R I J K` (NIST
//!   RS274/NGC Interpreter v3, NISTIR 6556, canned cycle G87, as
//!   LinuxCNC's `rs274` runs it, `convert_cycle_g87`; the LinuxCNC manual
//!   calls G87 unimplemented): the tool, oriented, is shifted by I/J/K in
//!   the plane (the offsets along X/Y/Z of the two plane axes), lowered at
//!   rapid through the hole to the bottom level (the drilling-axis word),
//!   moved back onto the hole's axis, fed to the top of the back bore (the
//!   drilling-axis letter of I/J/K: absolute under G90, from the bottom
//!   under G91) and fed back to the bottom, shifted again, raised at rapid
//!   to the return level and moved back onto the hole's axis. The three
//!   words are required on the cycle's first G87 block and kept after it
//!   (as LinuxCNC keeps them); its repeat count is L only (K is a level or
//!   an offset). The Fanuc form (a shift Q whose direction is a machine
//!   parameter, no I/J/K) is refused with a located error.
//! - P is read like a G4 P ([`super::program::DwellP`]); Q and the
//!   clearance are in the program's length unit (converted to mm).
//!
//! Every expanded segment is `fixed`: its end points are not words of one
//! block execution. Units: mm, s.

use serde::{Deserialize, Serialize};

use super::moves::target;
use super::program::{err, Ctx, FeedMode, Modal, Warning};
use super::segment::{Motion, Plane, Pose, Segment, AXES};
use super::{Block, NcError, Word};

/// Retract/approach clearance of G73 and G83 pecks, mm (Fanuc parameters
/// 5114/5115; a common setting).
pub const PECK_CLEARANCE: f64 = 0.5;

/// Most pecks of one G73/G83 hole (a 1 m hole at 0.1 mm pecks): a larger
/// count is a typo in Q or the bottom level, and each peck is 2–3 segments.
pub const MAX_PECKS: usize = 10_000;

/// An active canned cycle (modal data).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Cycle {
    /// The G code ×10 (810 for G81).
    pub code: i64,
    /// Initial level: drilling-axis position when the cycle mode began, mm.
    pub initial: f64,
    /// R level, absolute, mm (`None` until given).
    pub r: Option<f64>,
    /// Bottom, absolute, mm (`None` until given).
    pub bottom: Option<f64>,
    /// The last bottom word's number, mm (under G91 the bottom's distance
    /// from R; under G90 the level before the G92 shift), `None` until
    /// given: a later block that gives a new R under G91 without a bottom
    /// word puts the bottom this far from R, as LinuxCNC re-reads its
    /// sticky Z number.
    pub depth: Option<f64>,
    /// Peck depth Q, mm.
    pub q: f64,
    /// Dwell at the bottom, s.
    pub dwell: f64,
    /// G87: the tool shift along X, Y, Z (I, J, K; the drilling axis's
    /// entry unused), mm.
    #[serde(default)]
    pub shift: [f64; 3],
    /// G87: the top of the back bore as written (the drilling axis's
    /// letter among I/J/K), mm: absolute before the G92 shift under G90,
    /// from the bottom under G91; `None` until given.
    #[serde(default)]
    pub back: Option<f64>,
}

/// Segments of one hole at plane position (`pu`, `pv`) from `pos`.
///
/// `r`, `bottom`: levels (mm); `back`: G87's top of the back bore (mm,
/// absolute); `g99`: return to R; `feed`: mm/min.
#[allow(clippy::too_many_arguments)]
pub fn hole(
    c: &Cycle,
    plane: Plane,
    pos: Pose,
    pu: f64,
    pv: f64,
    r: f64,
    bottom: f64,
    back: f64,
    g99: bool,
    feed: f64,
    block: usize,
    line: usize,
) -> Vec<Segment> {
    let (u, v, n) = plane.axes();
    let mut path = HolePath {
        out: Vec::new(),
        cur: pos,
        n,
        block,
        line,
    };
    let mut over = pos;
    over.set(u, pu);
    over.set(v, pv);
    path.go(Motion::Rapid, over, 0.0);
    path.level(Motion::Rapid, r, 0.0);
    let level = if g99 { r } else { c.initial };
    match c.code {
        730 | 830 => path.peck(c, r, bottom, feed),
        870 => {
            // G87: shifted down through the hole, back bore upwards, shifted out
            let mut shifted = over;
            shifted.set(u, pu + c.shift[u]);
            shifted.set(v, pv + c.shift[v]);
            path.go(Motion::Rapid, shifted.with(n, r), 0.0);
            path.level(Motion::Rapid, bottom, 0.0);
            path.go(Motion::Rapid, over.with(n, bottom), 0.0);
            path.level(Motion::Linear, back, feed);
            path.level(Motion::Linear, bottom, feed);
            path.go(Motion::Rapid, shifted.with(n, bottom), 0.0);
            path.level(Motion::Rapid, level, 0.0);
            path.go(Motion::Rapid, over.with(n, level), 0.0);
        }
        _ => path.level(Motion::Linear, bottom, feed),
    }
    if matches!(c.code, 820 | 760 | 880 | 890 | 840 | 740 | 842 | 843) {
        path.dwell(c.dwell);
    }
    if matches!(c.code, 840 | 740 | 842 | 843 | 850 | 890) {
        path.level(Motion::Linear, r, feed);
    }
    path.level(Motion::Rapid, level, 0.0);
    path.out
}

/// `pose` with axis `i` set to `v`.
trait With {
    fn with(self, i: usize, v: f64) -> Self;
}

impl With for Pose {
    fn with(mut self, i: usize, v: f64) -> Self {
        self.set(i, v);
        self
    }
}

/// The segments of one hole as they are built, and the tool pose after
/// them.
struct HolePath {
    out: Vec<Segment>,
    cur: Pose,
    /// Index of the drilling axis.
    n: usize,
    block: usize,
    line: usize,
}

impl HolePath {
    /// A `fixed` segment of this hole's block.
    fn segment(&self, motion: Motion, start: Pose, end: Pose, feed: f64) -> Segment {
        Segment {
            block: Some(self.block),
            line: self.line,
            motion,
            start,
            end,
            feed,
            fixed: true,
        }
    }

    /// A move to `target` (none when it is already there within 1e-12 mm).
    fn go(&mut self, motion: Motion, target: Pose, feed: f64) {
        if (0..3).all(|k| (target.get(k) - self.cur.get(k)).abs() < 1e-12) {
            return;
        }
        self.out.push(self.segment(motion, self.cur, target, feed));
        self.cur = target;
    }

    /// A move along the drilling axis to `level`.
    fn level(&mut self, motion: Motion, level: f64, feed: f64) {
        let mut t = self.cur;
        t.set(self.n, level);
        self.go(motion, t, feed);
    }

    /// A dwell of `seconds` (none when zero).
    fn dwell(&mut self, seconds: f64) {
        if seconds > 0.0 {
            let s = self.segment(Motion::Dwell { seconds }, self.cur, self.cur, 0.0);
            self.out.push(s);
        }
    }

    /// G73/G83 pecks from R to the bottom by Q: between pecks G83 rapids
    /// out to R, both rapid back to [`PECK_CLEARANCE`] above the last depth.
    fn peck(&mut self, c: &Cycle, r: f64, bottom: f64, feed: f64) {
        let dir = if bottom < r { -1.0 } else { 1.0 };
        let depth_total = (bottom - r).abs();
        let mut done = 0.0;
        // `hole_data` allows at most MAX_PECKS (⌈depth/Q⌉); one more for a
        // sum of Q's that rounds short of the bottom. The bound keeps the
        // loop finite whatever the arithmetic.
        for _ in 0..=MAX_PECKS {
            if done >= depth_total - 1e-12 {
                break;
            }
            let next = (done + c.q).min(depth_total);
            if done > 0.0 {
                if c.code == 830 {
                    self.level(Motion::Rapid, r, 0.0);
                }
                let back = (done - PECK_CLEARANCE).max(0.0);
                self.level(Motion::Rapid, r + dir * back, 0.0);
            }
            self.level(Motion::Linear, r + dir * next, feed);
            done = next;
        }
    }
}

/// The levels, feed and repeat count of a cycle block's holes.
struct Holes {
    /// R level, mm.
    r: f64,
    /// Bottom, mm.
    bottom: f64,
    /// G87's top of the back bore, mm (the bottom for other cycles).
    back: f64,
    /// Feed, mm/min.
    feed: f64,
    /// K/L repeat count.
    repeats: usize,
}

/// One block in canned-cycle mode: update the cycle data, drill the holes
/// (a block without a plane-axis, drilling-axis, R or cycle word drills
/// none).
///
/// # Errors
/// An axis outside the cycle's plane, a bottom before any R level, a
/// negative dwell, missing levels, peck depth or feed, a bad repeat count,
/// too many pecks.
pub(super) fn canned_cycle(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    cycle_word: Option<&Word>,
    scale: f64,
) -> Result<(), NcError> {
    let Some(mut c) = st.cycle else {
        return Ok(());
    };
    let (u, v, n) = st.plane.axes();
    let (wu, wv) = (b.word(AXES[u]), b.word(AXES[v]));
    let (wn, wr) = (b.word(AXES[n]), b.word('R'));
    let Some(anchor) = cycle_word
        .or(wu)
        .or(wv)
        .or(super::polar::polar_word(b))
        .or(wn)
        .or(wr)
    else {
        return Ok(());
    };
    check_cycle_axes(b, st, cx)?;
    read_levels(b, st, &mut c, wr, wn, scale, cx.warnings)?;
    read_q_and_p(b, &mut c, cx, scale)?;
    if c.code == 870 {
        read_back_bore(b, st, &mut c, anchor, scale)?;
    }
    st.cycle = Some(c);
    let holes = hole_data(b, st, &c, anchor)?;
    if c.code == 880 {
        cx.warnings.push(Warning::at(
            b.line,
            anchor.column,
            "G88 boring: after the dwell the spindle stops and the program stops for a manual retract; the retract is simulated as a rapid to the return level (LinuxCNC's rs274 leaves it out and goes on from the bottom), and the time of the stop is not counted",
        ));
    }
    if c.code == 760 {
        cx.warnings.push(Warning::at(
            b.line,
            anchor.column,
            "G76 fine boring: the tool shift at the bottom (direction set by a machine parameter) is not simulated",
        ));
    }
    // The hole position: the plane's words, or LinuxCNC polar words
    // (G17 only, checked by `polar::check`).
    let plane_words: Vec<&Word> = [wu, wv]
        .into_iter()
        .flatten()
        .chain(b.words.iter().filter(|w| super::polar::is_polar(w.letter)))
        .collect();
    for _ in 0..holes.repeats {
        let at = target(st, &plane_words, scale);
        let (pu, pv) = (at.get(u), at.get(v));
        let segs = hole(
            &c,
            st.plane,
            st.pos,
            pu,
            pv,
            holes.r,
            holes.bottom,
            holes.back,
            st.cycle_return_r,
            holes.feed,
            cx.bi,
            b.line,
        );
        if let Some(last) = segs.last() {
            st.pos = last.end;
        }
        cx.segments.extend(segs);
        if cx.segments.len() > cx.opt.segment_budget() {
            // The run stops here with the segment-budget error
            // (`run::Run::run_block`).
            break;
        }
    }
    Ok(())
}

/// Only the plane axes and the drilling axis may be on a cycle block.
fn check_cycle_axes(b: &Block, st: &Modal, cx: &Ctx) -> Result<(), NcError> {
    let (u, v, n) = st.plane.axes();
    let (lu, lv, ln) = (AXES[u], AXES[v], AXES[n]);
    match b.words.iter().find(|w| {
        AXES.contains(&w.letter)
            && ![lu, lv, ln].contains(&w.letter)
            && (w.letter != 'C' || cx.opt.c_axis)
    }) {
        Some(w) => Err(err(
            b,
            w,
            format!("{}{} in a canned-cycle block: only the plane axes {lu}/{lv} and the drilling axis {ln} are allowed", w.letter, w.text),
        )),
        // In a 3-axis program C is no axis, and a cycle has no chamfer:
        // ignoring it would pass a typo (or a rotary move) in silence.
        None => match b.word('C').filter(|_| !cx.opt.c_axis) {
            Some(w) => Err(err(
                b,
                w,
                format!("C{} in a canned-cycle block: C is no axis of this program (no A, B or C move elsewhere; set the option cAxis if the machine has a C axis) and a cycle takes no chamfer", w.text),
            )),
            None => Ok(()),
        },
    }
}

/// The R level (`wr`) and the bottom (`wn`, the drilling-axis word) as
/// absolute levels: under G91 R is from the initial level and the bottom
/// from R; under G90 both are shifted by the G92 offset. A new R under G91
/// without a bottom word keeps the bottom's G91 distance from R (the
/// bottom moves with R), as LinuxCNC and Fanuc do. A bottom with no R
/// level given yet takes the initial level as R, warned: Fanuc and Haas
/// controls run a cycle without R from the initial level (LinuxCNC
/// refuses it).
fn read_levels(
    b: &Block,
    st: &Modal,
    c: &mut Cycle,
    wr: Option<&Word>,
    wn: Option<&Word>,
    scale: f64,
    warnings: &mut Vec<Warning>,
) -> Result<(), NcError> {
    let (_, _, n) = st.plane.axes();
    if let Some(r) = wr {
        let r = if st.incremental {
            c.initial + r.value * scale
        } else {
            r.value * scale + st.offset[n]
        };
        c.r = Some(r);
        if let (None, true, Some(depth)) = (wn, st.incremental, c.depth) {
            c.bottom = Some(r + depth);
        }
    }
    if let Some(z) = wn {
        let r = match c.r {
            Some(r) => r,
            None => {
                warnings.push(Warning::at(
                    b.line,
                    z.column,
                    format!(
                        "canned cycle without R: the R level is taken as the initial level {:.4} mm, as Fanuc and Haas controls do (the tool feeds from there; LinuxCNC refuses it); write R for a rapid approach",
                        c.initial
                    ),
                ));
                c.r = Some(c.initial);
                c.initial
            }
        };
        c.depth = Some(z.value * scale);
        c.bottom = Some(if st.incremental {
            r + z.value * scale
        } else {
            z.value * scale + st.offset[n]
        });
    }
    Ok(())
}

/// G87's words (see the module header): the shift along the plane axes
/// and the top of the back bore, the letters I/J/K of X/Y/Z; all three
/// are required until the cycle has them.
///
/// # Errors
/// A G87 without them: the Fanuc form, whose shift direction is a
/// machine parameter.
fn read_back_bore(
    b: &Block,
    st: &Modal,
    c: &mut Cycle,
    anchor: &Word,
    scale: f64,
) -> Result<(), NcError> {
    const LETTERS: [char; 3] = ['I', 'J', 'K'];
    let (u, v, n) = st.plane.axes();
    if c.back.is_none() && [u, v, n].iter().any(|&a| b.word(LETTERS[a]).is_none()) {
        return Err(err(
            b,
            anchor,
            format!(
                "G87 back boring without {}, {} and {}: the Fanuc form (a shift Q whose direction is a machine parameter) is not simulated; the RS274/NGC form G87 {}{}{} R {}(shift) {}(shift) {}(top of the back bore) is",
                LETTERS[u], LETTERS[v], LETTERS[n], AXES[u], AXES[v], AXES[n], LETTERS[u], LETTERS[v], LETTERS[n]
            ),
        ));
    }
    for a in [u, v] {
        if let Some(w) = b.word(LETTERS[a]) {
            c.shift[a] = w.value * scale;
        }
    }
    if let Some(w) = b.word(LETTERS[n]) {
        c.back = Some(w.value * scale);
    }
    Ok(())
}

/// The peck depth Q (mm, sign ignored) and the dwell P (read as a G4 P).
fn read_q_and_p(b: &Block, c: &mut Cycle, cx: &Ctx, scale: f64) -> Result<(), NcError> {
    if let Some(q) = b.word('Q') {
        c.q = q.value.abs() * scale;
    }
    if let Some(p) = b.word('P') {
        c.dwell = cx.opt.dwell_p.seconds(p).0;
        if c.dwell.is_nan() || c.dwell < 0.0 {
            return Err(err(b, p, "canned-cycle dwell P must be zero or positive"));
        }
    }
    Ok(())
}

/// The levels, feed and repeat count of the block's holes, once the cycle
/// data is complete.
///
/// # Errors
/// No R level or bottom, a peck cycle without Q, no feed, a repeat count
/// that is not a whole number from 0 to 9999, more than [`MAX_PECKS`]
/// pecks.
fn hole_data(b: &Block, st: &Modal, c: &Cycle, anchor: &Word) -> Result<Holes, NcError> {
    let code = format!("G{}", c.code as f64 / 10.0);
    let (_, _, n) = st.plane.axes();
    let ln = AXES[n];
    let (Some(r), Some(bottom)) = (c.r, c.bottom) else {
        return Err(err(
            b,
            anchor,
            format!("{code} needs the R level (R) and the bottom ({ln}) before its first hole"),
        ));
    };
    let peck = matches!(c.code, 730 | 830);
    if peck && c.q <= 0.0 {
        return Err(err(
            b,
            anchor,
            format!("{code} (peck drilling) needs a peck depth Q greater than 0"),
        ));
    }
    if st.feed_mode == FeedMode::InverseTime {
        return Err(err(
            b,
            anchor,
            format!("{code} under G93 (inverse time): a canned cycle needs a feed per minute; program G94 and an F in mm/min before it"),
        ));
    }
    let feed = match st.feed_mm_min(0.0) {
        Some(f) if f > 0.0 => f,
        _ => {
            return Err(err(
                b,
                anchor,
                format!("{code} without a feed; {}", st.no_feed_reason()),
            ))
        }
    };
    // G87: K is a level or a shift, the repeat count L only
    let repeats = repeat_count(b, c.code != 870)?;
    // A peck cycle has Q > 0 (checked above).
    let pecks = if peck {
        ((bottom - r).abs() / c.q).ceil()
    } else {
        1.0
    };
    if pecks.is_nan() || pecks > MAX_PECKS as f64 {
        let w = b.word('Q').unwrap_or(anchor);
        return Err(err(
            b,
            w,
            format!(
                "{} pecks of Q{} mm for a {} mm deep hole; at most {} per hole: check Q, R and the bottom level",
                crate::numeric::compact(pecks),
                crate::numeric::compact(c.q),
                crate::numeric::compact((bottom - r).abs()),
                MAX_PECKS
            ),
        ));
    }
    let (_, _, n) = st.plane.axes();
    let back = match (c.code, c.back) {
        (870, Some(k)) if st.incremental => bottom + k,
        (870, Some(k)) => k + st.offset[n],
        _ => bottom,
    };
    Ok(Holes {
        r,
        bottom,
        back,
        feed,
        repeats,
    })
}

/// The K (when `k`) or L repeat count of a cycle block, 1 without one.
fn repeat_count(b: &Block, k: bool) -> Result<usize, NcError> {
    match b.word('K').filter(|_| k).or(b.word('L')) {
        Some(k) if k.value >= 0.0 && k.value.fract() == 0.0 && k.value <= 9999.0 => {
            Ok(k.value as usize)
        }
        Some(k) => Err(err(
            b,
            k,
            format!(
                "repeat count {}{} must be a whole number from 0 to 9999",
                k.letter, k.text
            ),
        )),
        None => Ok(1),
    }
}
