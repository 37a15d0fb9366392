//! LinuxCNC's spline moves, read into the chords of their curve
//! ([`super::nurbs`]): G5, the cubic spline, G5.1, the quadratic
//! B-spline, and the G5.2 … G5.3 NURBS block.
//!
//! Source: the LinuxCNC G-code manual (2.9, §11.5.7–§11.5.9), and where
//! it is silent or differs, LinuxCNC's interpreter `rs274` (2.9.0~pre1,
//! `interp_convert.cc`: `convert_spline`, `convert_nurbs`), checked
//! against it by `tests/nc_linuxcnc_oracle.rs`.
//!
//! - `G5 X Y I J P Q`: the cubic Bézier from the current point P0 to
//!   X Y (P3) with control points P1 = P0 + (I, J) and P2 = P3 + (P, Q)
//!   (all four offsets always incremental, in the program's units; X Y
//!   read as any end point: G90/G91, G92, inch); a NURBS of order 4 on
//!   four points of weight 1 is exactly that curve. P and Q are required.
//!   I and J both or neither: without them the start direction continues
//!   the previous G5's end direction (P1 = P0 − its P Q), which the
//!   manual allows only inside a series of G5 blocks, so here only when no
//!   block with another motion, cycle or non-modal move code came in
//!   between (a dwell does not break the series). rs274 also accepts a G5
//!   without I J after other moves (it takes the stale P Q); that is
//!   refused here, as the manual says. As for G5.1, a block of axis words
//!   after a G5 (the manual: G5 modal; rs274: the mode before it, checked)
//!   is refused. Only X and Y, only in G17;
//! - `G5.1 X Y I J`: a quadratic B-spline from the current point to X Y
//!   whose middle control point is the start plus I J (always
//!   incremental, also under G90.1). The manual puts G5.1 in the motion
//!   group, but the interpreter leaves the motion mode as it was (a block
//!   of axis words after `G0 … G5.1 …` is a rapid), so such a block,
//!   whose reading the two disagree on, is refused: each curve names
//!   G5.1. Both I and J are required
//!   (the manual reads a missing one as 0, the interpreter refuses it; a
//!   program that runs on LinuxCNC has both), and not both 0 (the manual's
//!   error). Only X and Y may be given, only in G17.
//! - `G5.2` opens a NURBS block (motion group, modal): the current point is
//!   the first control point, of weight P when the G5.2 block gives P
//!   without X Y, else 1; every block with X Y up to `G5.3` adds a control
//!   point, each with its weight `P > 0` (the manual's default weight 1 is
//!   refused by the interpreter: it requires P on every point). `L` is the
//!   order (default 3; the interpreter reads an L below 3 as 3, so one is
//!   refused here). X Y are read as any end point (G90/G91, G92, inch):
//!   under G91 every point is an increment from the position before the
//!   block, since the tool does not move until G5.3. `G5.3` ends the block:
//!   the curve is cut there, from the first control point to the last,
//!   and the motion mode is left unset (the next move names its code).
//!   The order must not exceed the number of control points.
//! - Refused with a located error, as the interpreter refuses them or as
//!   ignoring them would move elsewhere: Z, A, B, C words (the curve is in
//!   XY), cutter compensation, a G68 rotation, polar words, corner words,
//!   a moving code inside an open NURBS block (it would lose its points),
//!   and a NURBS block the program never closes.
//!
//! Each curve becomes straight feed segments at the modal feed (under G93
//! the whole curve takes 1/F minutes), within
//! [`super::nurbs::CHORD_TOLERANCE`] of the curve, every one `fixed` (its
//! points are not words of the block). Units: mm, feed in mm/min.

use serde::{Deserialize, Serialize};

use super::block::axis_words;
use super::gcodes::{code10, GWords};
use super::moves::{move_feed, target};
use super::nurbs::{ControlPoint, Nurbs};
use super::program::{err, Ctx, Modal, MotionCode, Warning};
use super::segment::{Motion, Segment};
use super::{Block, NcError, Word};

/// Highest NURBS order L read (degree 9; CAM posts write 3 or 4).
pub const MAX_ORDER: usize = 10;

/// The spline motion mode in force (a G5.x code), with the motion code
/// [`MotionCode::Linear`]: its moves are feeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Spline {
    /// G5, the cubic Bézier.
    Cubic,
    /// G5.1, the quadratic B-spline.
    Quadratic,
    /// G5.2, the NURBS block (open until G5.3).
    Nurbs,
}

impl Spline {
    /// The spline mode of a G code (×10): G5.1, G5.2.
    pub(super) fn of(g: i64) -> Option<Self> {
        match g {
            50 => Some(Spline::Cubic),
            51 => Some(Spline::Quadratic),
            52 => Some(Spline::Nurbs),
            _ => None,
        }
    }
}

/// An open G5.2 NURBS block: where it opened, its order, its control
/// points so far (x, y in mm, weight).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct OpenNurbs {
    line: usize,
    column: usize,
    order: usize,
    points: Vec<ControlPoint>,
}

/// The error that a program ends with the NURBS block `open` not closed.
pub(super) fn unclosed(open: &OpenNurbs) -> NcError {
    NcError::new(
        open.line,
        open.column,
        "G5.2 opens a NURBS block that the program never closes; expected G5.3 after its control points",
    )
}

/// The error for a block that would interrupt an open NURBS block with a
/// move of another kind (a motion or cycle code other than G5.2, a dwell,
/// a non-modal move); the open block is dropped.
pub(super) fn interrupted(b: &Block, gw: &GWords, cx: &mut Ctx) -> Option<NcError> {
    let open = cx.nurbs.as_ref()?;
    let w = gw
        .motion
        .map(|(w, _)| w)
        .filter(|w| code10(w) != 52)
        .or(gw.cycle.map(|(w, _)| w))
        .or(gw.non_modal.map(|(w, _)| w))
        .or(gw.dwell)?;
    let e = err(
        b,
        w,
        format!(
            "G{} inside the G5.2 NURBS block of line {}; expected its control points (X Y P) and G5.3 to end it first",
            w.text, open.line
        ),
    );
    *cx.nurbs = None;
    Some(e)
}

/// A block in a spline mode: a G5.1 curve, or a control point (or the
/// opening) of a G5.2 block.
///
/// # Errors
/// See the module header.
pub(super) fn spline_block(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    spline: Spline,
    scale: f64,
) -> Result<(), NcError> {
    let axes = axis_words(b, cx);
    let g = b.words_of('G').find(|w| Spline::of(code10(w)).is_some());
    refuse_words(b, st, &axes, g, spline)?;
    match spline {
        Spline::Cubic => cubic(b, st, cx, &axes, g, scale),
        Spline::Quadratic => quadratic(b, st, cx, &axes, g, scale),
        Spline::Nurbs => nurbs_point(b, st, cx, &axes, g, scale),
    }
}

/// The words and states a spline block cannot take (see the module
/// header).
fn refuse_words(
    b: &Block,
    st: &Modal,
    axes: &[&Word],
    g: Option<&Word>,
    spline: Spline,
) -> Result<(), NcError> {
    let code = match spline {
        Spline::Cubic => "G5",
        Spline::Quadratic => "G5.1",
        Spline::Nurbs => "G5.2",
    };
    let at = g.or(b.words.first());
    let here = |msg: String| match at {
        Some(w) => err(b, w, msg),
        None => NcError::new(b.line, 1, msg),
    };
    if let Some(w) = axes.iter().find(|w| !matches!(w.letter, 'X' | 'Y')) {
        return Err(err(
            b,
            w,
            format!(
                "{}{} on a {code} spline block: a spline moves X and Y only (LinuxCNC refuses other axes); move {} in its own G1 block",
                w.letter, w.text, w.letter
            ),
        ));
    }
    if let Some(w) = b.comma_words.first() {
        return Err(err(
            b,
            w,
            format!("corner word ,{}{} on a {code} spline block; corner rounding and chamfer belong on G01", w.letter, w.text),
        ));
    }
    if let Some(c) = st.cutter {
        return Err(here(format!(
            "{code} spline with cutter compensation in force (stretch {}); LinuxCNC refuses it: cancel it with G40 first",
            c.stretch + 1
        )));
    }
    if st.rotation.is_some() {
        return Err(here(format!(
            "{code} spline under a G68 coordinate rotation is not simulated; cancel it with G69 or post the spline in the rotated frame's X/Y"
        )));
    }
    if spline != Spline::Nurbs && st.plane != super::segment::Plane::XY {
        return Err(here(format!(
            "{code} spline in the G{} plane; LinuxCNC's splines are in the XY plane: expected G17",
            st.plane.code()
        )));
    }
    Ok(())
}

/// G5: the cubic Bézier of the block, from the start P0 to the end P3,
/// with P1 = P0 + (I, J) and P2 = P3 + (P, Q), or without I J (a G5 right
/// after a G5) P1 = P0 − the previous G5's (P, Q).
fn cubic(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    axes: &[&Word],
    g: Option<&Word>,
    scale: f64,
) -> Result<(), NcError> {
    let (i, j) = (b.word('I'), b.word('J'));
    let (p, q) = (b.word('P'), b.word('Q'));
    let Some(first) = g.or(axes.first().copied()).or(i).or(j).or(p).or(q) else {
        return Ok(());
    };
    own_code(b, g, first, "G5")?;
    let (Some(p), Some(q)) = (p, q) else {
        return Err(err(
            b,
            first,
            "G5 needs both P and Q, the second control point's X and Y offsets from the end point (LinuxCNC refuses a G5 without them)",
        ));
    };
    let lead = match (i, j) {
        (Some(i), Some(j)) => [i.value * scale, j.value * scale],
        (None, None) => match st.cubic_end_offset {
            Some([pp, qq]) => [-pp, -qq],
            None => {
                return Err(err(
                    b,
                    first,
                    "G5 without I and J starts no series: only a G5 right after another G5 may leave them out (it then starts in that one's end direction); expected I and J, the first control point's offsets from the start",
                ))
            }
        },
        (Some(w), None) | (None, Some(w)) => {
            return Err(err(
                b,
                w,
                format!(
                    "G5 with {}{} alone: give both I and J (the first control point's offsets from the start) or neither (after a G5, to continue its end direction)",
                    w.letter, w.text
                ),
            ))
        }
    };
    warn_unused(b, cx, &['K', 'R', 'L'], "G5");
    let end = target(st, axes, scale);
    let (x0, y0) = (st.pos.x, st.pos.y);
    let trail = [p.value * scale, q.value * scale];
    let points = vec![
        [x0, y0, 1.0],
        [x0 + lead[0], y0 + lead[1], 1.0],
        [end.x + trail[0], end.y + trail[1], 1.0],
        [end.x, end.y, 1.0],
    ];
    cut(b, st, cx, points, 4, first)?;
    st.cubic_end_offset = Some(trail);
    Ok(())
}

/// The refusal of a spline block `b` without its own code `g` (`name`):
/// LinuxCNC's interpreter runs such a block in the mode before the spline.
fn own_code(b: &Block, g: Option<&Word>, first: &Word, name: &str) -> Result<(), NcError> {
    match g {
        Some(_) => Ok(()),
        None => Err(err(
            b,
            first,
            format!(
                "axis words after a {name} block without a motion code: the LinuxCNC manual makes {name} modal, its interpreter runs this block in the mode before the {name} (G0 or G1); write {name}, G1 or G0 on the block"
            ),
        )),
    }
}

/// G5.1: the quadratic B-spline of the block.
fn quadratic(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    axes: &[&Word],
    g: Option<&Word>,
    scale: f64,
) -> Result<(), NcError> {
    let (i, j) = (b.word('I'), b.word('J'));
    let Some(first) = g.or(axes.first().copied()).or(i).or(j) else {
        return Ok(());
    };
    own_code(b, g, first, "G5.1")?;
    let (Some(i), Some(j)) = (i, j) else {
        return Err(err(
            b,
            first,
            "G5.1 needs both I and J, the control point's X and Y offsets from the start (LinuxCNC's interpreter refuses one alone); write I0 or J0",
        ));
    };
    if i.value == 0.0 && j.value == 0.0 {
        return Err(err(
            b,
            i,
            "G5.1 with I0 J0: the control point is the start point, which the LinuxCNC manual refuses; expected a non-zero I or J (or a G1 line)",
        ));
    }
    warn_unused(b, cx, &['K', 'R', 'P', 'L'], "G5.1");
    let end = target(st, axes, scale);
    let (x0, y0) = (st.pos.x, st.pos.y);
    let points = vec![
        [x0, y0, 1.0],
        [x0 + i.value * scale, y0 + j.value * scale, 1.0],
        [end.x, end.y, 1.0],
    ];
    cut(b, st, cx, points, 3, first)
}

/// A block of an open (or opening) G5.2 NURBS block: its order L and its
/// control point.
fn nurbs_point(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    axes: &[&Word],
    g: Option<&Word>,
    scale: f64,
) -> Result<(), NcError> {
    let (x, y, p) = (b.word('X'), b.word('Y'), b.word('P'));
    if cx.nurbs.is_none() {
        let (line, column) = (b.line, g.or(b.words.first()).map_or(1, |w| w.column));
        let w0 = match (p, x.or(y)) {
            (Some(p), None) => weight(b, p)?,
            _ => 1.0,
        };
        *cx.nurbs = Some(OpenNurbs {
            line,
            column,
            order: 3,
            points: vec![[st.pos.x, st.pos.y, w0]],
        });
    } else if let (Some(p), None) = (p, x.or(y)) {
        return Err(err(
            b,
            p,
            format!(
                "P{} without X and Y inside a NURBS block: only the G5.2 block may give the first control point's weight alone; expected X Y P",
                p.text
            ),
        ));
    }
    warn_unused(b, cx, &['I', 'J', 'K', 'R'], "G5.2");
    if let Some(l) = b.word('L') {
        let order = l.value as usize;
        if l.value.fract() != 0.0 || !(3.0..=MAX_ORDER as f64).contains(&l.value) {
            return Err(err(
                b,
                l,
                format!(
                    "L{}: a NURBS order is a whole number from 3 to {MAX_ORDER} (LinuxCNC reads an L below 3 as 3)",
                    l.text
                ),
            ));
        }
        if let Some(open) = cx.nurbs.as_mut() {
            open.order = order;
        }
    }
    match (x, y) {
        (None, None) => Ok(()),
        (Some(w), None) | (None, Some(w)) => Err(err(
            b,
            w,
            format!(
                "{}{} alone: a NURBS control point needs both X and Y",
                w.letter, w.text
            ),
        )),
        (Some(xw), Some(_)) => {
            let Some(p) = p else {
                return Err(err(
                    b,
                    xw,
                    "NURBS control point without a weight: expected P (above 0) on every control point, as LinuxCNC's interpreter requires",
                ));
            };
            let w = weight(b, p)?;
            let end = target(st, axes, scale);
            if let Some(open) = cx.nurbs.as_mut() {
                open.points.push([end.x, end.y, w]);
            }
            Ok(())
        }
    }
}

/// A control point's weight P: a positive number.
fn weight(b: &Block, p: &Word) -> Result<f64, NcError> {
    if p.value > 0.0 && p.value.is_finite() {
        Ok(p.value)
    } else {
        Err(err(
            b,
            p,
            format!("P{}: a NURBS weight must be above 0", p.text),
        ))
    }
}

/// G5.3 (`w`): the curve of the open NURBS block is cut, and the motion
/// mode is left unset.
///
/// # Errors
/// No open block, axis words on the G5.3 block, fewer control points than
/// the order, a curve too long for its chords.
pub(super) fn nurbs_end(b: &Block, st: &mut Modal, cx: &mut Ctx, w: &Word) -> Result<(), NcError> {
    let Some(open) = cx.nurbs.take() else {
        return Err(err(
            b,
            w,
            "G5.3 without a NURBS block to end; expected G5.2 and its control points first",
        ));
    };
    st.motion = None;
    st.spline = None;
    if let Some(a) = axis_words(b, cx).first() {
        return Err(err(
            b,
            a,
            format!(
                "{}{} on the G5.3 block: G5.3 only ends the NURBS block; give the last control point on its own block before it",
                a.letter, a.text
            ),
        ));
    }
    if open.points.len() < open.order {
        return Err(err(
            b,
            w,
            format!(
                "the G5.2 NURBS block of line {} has {} control points (its start point included) for order L{}; expected at least {}",
                open.line,
                open.points.len(),
                open.order,
                open.order
            ),
        ));
    }
    cut(b, st, cx, open.points, open.order, w)
}

/// Warns about the words in `letters` that the spline block `code` does
/// not use.
fn warn_unused(b: &Block, cx: &mut Ctx, letters: &[char], code: &str) {
    for w in b.words.iter().filter(|w| letters.contains(&w.letter)) {
        cx.warnings.push(Warning::at(
            b.line,
            w.column,
            format!(
                "{}{} has no meaning on a {code} block and was ignored",
                w.letter, w.text
            ),
        ));
    }
}

/// Cuts the curve of `points` (`order`) from the current point: its chords
/// as feed segments, the tool left at the last control point.
fn cut(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    points: Vec<ControlPoint>,
    order: usize,
    first: &Word,
) -> Result<(), NcError> {
    let curve_err = |e: super::nurbs::NurbsError| err(b, first, format!("spline: {e}"));
    let chords = Nurbs::new(points, order)
        .and_then(|c| c.chords())
        .map_err(curve_err)?;
    let mut at = st.pos;
    let mut segments = Vec::with_capacity(chords.len());
    for [x, y] in chords {
        let mut end = at;
        end.x = x;
        end.y = y;
        if end != at {
            segments.push(Segment {
                block: Some(cx.bi),
                line: b.line,
                motion: Motion::Linear,
                start: at,
                end,
                feed: 0.0,
                fixed: true,
            });
        }
        at = end;
    }
    if !segments.is_empty() {
        let length: f64 = segments.iter().map(Segment::length).sum();
        let feed = move_feed(b, st, MotionCode::Linear, first, length)?;
        for s in &mut segments {
            s.feed = feed;
        }
    }
    cx.segments.extend(segments);
    st.pos = at;
    Ok(())
}
