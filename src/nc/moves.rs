//! The move of one block in the active motion mode (G0–G3): its end point
//! (G90/G91, the G92 shift, the inch scale, the G68 rotation), its feed, its motion (a line,
//! or an arc with I/J/K or R centres, G90.1 absolute centres converted),
//! and the Fanuc corner word it carries (`,R`/`,C`, or a plain `R`/`C` on
//! G01; applied later by [`super::corner`]). The readings are those of the
//! interpreter's header ([`super::program`]).
//!
//! Units: mm, degrees for A/B/C, feed in mm/min.

use super::arc::arc_warned;
use super::block::axis_words;
use super::program::{err, Corner, CornerKind, Ctx, FeedMode, Modal, Warning};
use super::rotation::end_to_machine;
use super::segment::{Motion, MotionCode, Pose, Segment, AXES};
use super::{Block, NcError, Word};

/// The move of block `b`: one segment from the current pose to the end of
/// its axis words, and its corner word if any. A block without axis or
/// centre words does nothing, and so does a G0/G1 block without axis
/// words (its I/J/K/R are warned about as meaningless).
///
/// # Errors
/// Axis words before any motion mode, a cutting move without a feed, an
/// arc error ([`arc`]), a chamfer `C` where it cannot be one, a misplaced
/// or doubled corner word.
pub(super) fn move_block(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    scale: f64,
) -> Result<(), NcError> {
    let axis_words = axis_words(b, cx);
    let chamfer_c = if cx.opt.c_axis { None } else { b.word('C') };
    let centre_words: Vec<&Word> = b
        .words
        .iter()
        .filter(|w| matches!(w.letter, 'I' | 'J' | 'K' | 'R'))
        .filter(|w| !(st.spindle_sync && w.letter == 'K'))
        .collect();
    if axis_words.is_empty() && centre_words.is_empty() {
        return match chamfer_c {
            Some(c) => Err(err(
                b,
                c,
                format!(
                    "C{} without a move: this machine has no C axis (set cAxis: true if it has one); a Fanuc chamfer C belongs on a G01 block with an end point",
                    c.text
                ),
            )),
            None => Ok(()),
        };
    }
    let first = axis_words
        .first()
        .or(centre_words.first())
        .copied()
        .ok_or_else(|| NcError::new(b.line, 1, "internal: empty move"))?;
    let Some(mode) = st.motion else {
        return Err(err(
            b,
            first,
            "axis words but no motion mode has been programmed; expected G0, G1, G2 or G3 first",
        ));
    };
    if axis_words.is_empty() && matches!(mode, MotionCode::Rapid | MotionCode::Linear) {
        return no_move(b, cx, mode, chamfer_c, scale, first);
    }
    let start = st.pos;
    let end = target(st, &axis_words, scale);
    let (motion, warning) = move_motion(b, st, mode, first, start, end, scale)?;
    if let Some(m) = warning {
        cx.warnings.push(Warning::at(b.line, first.column, m));
    }
    let mut seg = Segment {
        block: Some(cx.bi),
        line: b.line,
        motion,
        start,
        end,
        feed: 0.0,
        // A polar end point is not a literal X/Y word.
        fixed: super::polar::polar_word(b).is_some(),
    };
    if let Motion::Arc(a) = seg.motion {
        if let Some(sagitta) = flat_arc(&a, start, end, mode == MotionCode::Cw) {
            seg.motion = Motion::Linear;
            cx.warnings.push(Warning::at(
                b.line,
                first.column,
                format!(
                    "flat arc: G{} of radius {} mm bulges {} mm from its chord, below the numeric resolution of its centre; simulated as a straight move along the chord",
                    mode.code(),
                    crate::numeric::compact(a.radius),
                    crate::numeric::compact(sagitta)
                ),
            ));
        }
    }
    seg.feed = move_feed(b, st, mode, first, seg.timed_length())?;
    let corner = corner_word(b, mode, chamfer_c, scale)?;
    corner_or_centre_warning(b, cx, mode, corner, centre_words.first().copied());
    if st.rigid_tap && mode == MotionCode::Linear {
        return rigid_tap(b, st, cx, seg, first);
    }
    st.pos = end;
    cx.segments.push(seg);
    Ok(())
}

/// The sagitta (mm) of a minor arc so flat that its bulge is below the
/// numeric resolution of its centre, or `None`. A centre `R` away holds
/// its coordinates to about `R·ε`, so the arc's angles and sampled points
/// are only that good: `G2 X1 R999999999` (a 1 mm move, sagitta 1.25e-10
/// mm) swept almost a full circle of 1e9 mm and gave a contour error of
/// 1,095,477 µm. Such an arc is its chord: flat when the sagitta is at
/// most 1000·R·ε (R = 1e9 mm: 0.2 µm; R = 1000 mm: 2e-10 mm, so no real
/// arc is touched).
fn flat_arc(a: &super::segment::Arc, start: Pose, end: Pose, cw: bool) -> Option<f64> {
    let (u, v, _) = a.plane.axes();
    let (p0, p1) = (start.p(), end.p());
    let (du, dv) = (p1[u] - p0[u], p1[v] - p0[v]);
    let chord = du.hypot(dv);
    // a centre beyond the coordinate limit is refused as such ("check the
    // units"), not straightened
    if chord.is_nan()
        || chord <= 0.0
        || a.sweep.abs() >= std::f64::consts::TAU
        || a.center
            .iter()
            .any(|c| c.abs() > super::segment::MAX_COORDINATE)
    {
        return None;
    }
    // minor arc: the centre is left of the chord for G3, right for G2
    let (mu, mv) = ((p0[u] + p1[u]) / 2.0, (p0[v] + p1[v]) / 2.0);
    let side = (a.center[u] - mu) * -dv + (a.center[v] - mv) * du;
    if (cw && side > 0.0) || (!cw && side < 0.0) {
        return None;
    }
    let (r, half) = (a.radius, chord / 2.0);
    let sagitta = half * half / (r + (r * r - half * half).max(0.0).sqrt());
    (sagitta <= 1e3 * r * f64::EPSILON).then_some(sagitta)
}

/// A G33.1 rigid tap (LinuxCNC): the synchronised move `seg` to its end
/// point and the same move back to its start (the spindle reverses), both
/// at K × S; the tool ends where it started. Both segments are `fixed`
/// (the return has no word of its own). Under cutter compensation it is
/// refused (LinuxCNC refuses it too).
fn rigid_tap(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    seg: Segment,
    first: &Word,
) -> Result<(), NcError> {
    if st.cutter.is_some() {
        return Err(err(
            b,
            first,
            "G33.1 rigid tapping with cutter compensation in force; cancel it with G40 first",
        ));
    }
    let back = Segment {
        start: seg.end,
        end: seg.start,
        fixed: true,
        ..seg.clone()
    };
    cx.segments.push(Segment { fixed: true, ..seg });
    cx.segments.push(back);
    Ok(())
}

/// A G0/G1 block with centre words (`first`) but no axis words: no move
/// (a zero-length segment would not survive the writer, which writes the
/// block without the meaningless words); the centre words are warned
/// about.
///
/// # Errors
/// A corner word (`R` on G01, `,R`, `,C`, a chamfer `C`): it needs the
/// move it ends.
fn no_move(
    b: &Block,
    cx: &mut Ctx,
    mode: MotionCode,
    chamfer_c: Option<&Word>,
    scale: f64,
    first: &Word,
) -> Result<(), NcError> {
    if let Some((w, _)) = corner_word(b, mode, chamfer_c, scale)? {
        return Err(err(
            b,
            w,
            format!(
                "corner word {}{} on a G{} block without an end point; expected the X/Y/Z end of the move it rounds or chamfers",
                w.letter,
                w.text,
                mode.code()
            ),
        ));
    }
    corner_or_centre_warning(b, cx, mode, None, Some(first));
    Ok(())
}

/// Queues the block's corner word for [`super::corner`] (at the segment
/// about to be pushed); without one, warns that a centre word (`centre`,
/// the first I/J/K/R) means nothing on a G0 or G1.
fn corner_or_centre_warning(
    b: &Block,
    cx: &mut Ctx,
    mode: MotionCode,
    corner: Option<(&Word, CornerKind)>,
    centre: Option<&Word>,
) {
    match corner {
        Some((w, kind)) => cx.corners.push(Corner {
            segment: cx.segments.len(),
            kind,
            line: b.line,
            column: w.column,
        }),
        None => {
            if let Some(w) = centre {
                if matches!(mode, MotionCode::Rapid | MotionCode::Linear) {
                    cx.warnings.push(Warning::at(
                        b.line,
                        w.column,
                        format!(
                            "{}{} has no meaning on a G{} move and was ignored",
                            w.letter,
                            w.text,
                            mode.code()
                        ),
                    ));
                }
            }
        }
    }
}

/// The feed of a move in `mode`, mm/min: 0 for a rapid, the modal feed
/// (under G95 F × S, under G93 `length` × F with an F on the block; it
/// must be positive) for a cutting move.
pub(super) fn move_feed(
    b: &Block,
    st: &Modal,
    mode: MotionCode,
    first: &Word,
    length: f64,
) -> Result<f64, NcError> {
    let inverse = st.feed_mode == FeedMode::InverseTime;
    if st.spindle_sync && mode == MotionCode::Linear {
        return sync_feed(b, st, first);
    }
    match mode {
        MotionCode::Rapid => Ok(0.0),
        _ if inverse && b.word('F').is_none() => Err(err(
            b,
            first,
            format!("cutting move without a feed; {}", st.no_feed_reason()),
        )),
        _ => match st.feed_mm_min(length) {
            Some(f) if f > 0.0 => Ok(f),
            Some(_) => {
                let fw = b.word('F').or(b.word('S')).unwrap_or(first);
                Err(err(
                    b,
                    fw,
                    "feed is zero on a cutting move; expected F (and under G95 S) greater than 0",
                ))
            }
            None => Err(err(
                b,
                first,
                format!("cutting move without a feed; {}", st.no_feed_reason()),
            )),
        },
    }
}

/// The feed of a G33 move, mm/min: its K (the pitch: length per spindle
/// revolution, along the move, in program units) × the spindle speed S
/// (rpm), as LinuxCNC runs it (the axis motion only; the spindle's
/// position is not simulated).
fn sync_feed(b: &Block, st: &Modal, first: &Word) -> Result<f64, NcError> {
    let Some(k) = b.word('K').filter(|k| k.value > 0.0) else {
        return Err(err(
            b,
            first,
            "G33 move without a pitch: expected K (length per spindle revolution) greater than 0 on the block",
        ));
    };
    match st.spindle {
        Some(s) if s > 0.0 => Ok(k.value * super::block::length_scale(st) * s),
        _ => Err(err(
            b,
            k,
            "G33 needs the spindle speed: expected an S word (rpm, above 0) on this or an earlier block",
        )),
    }
}

/// The motion from `start` to `end` in `mode`: a rapid, a line, or the arc
/// of the block's centre words (I/J/K made incremental first under G90.1;
/// under G68 computed in the rotated frame and its centre turned back),
/// with the arc's radius-mismatch warning ([`super::arc::arc_warned`]).
fn move_motion(
    b: &Block,
    st: &Modal,
    mode: MotionCode,
    first: &Word,
    start: Pose,
    end: Pose,
    scale: f64,
) -> Result<(Motion, Option<String>), NcError> {
    Ok(match mode {
        MotionCode::Rapid => (Motion::Rapid, None),
        MotionCode::Linear => (Motion::Linear, None),
        MotionCode::Cw | MotionCode::Ccw => {
            let (start, end) = match st.rotation {
                Some(r) => (r.pose_to_program(start), r.pose_to_program(end)),
                None => (start, end),
            };
            let abs_block;
            let blk = if st.arc_center_absolute {
                abs_block = absolute_centre_block(b, start, scale, &st.offset);
                &abs_block
            } else {
                b
            };
            let (a, warning) = arc_warned(
                blk,
                first,
                st.plane,
                mode == MotionCode::Cw,
                start,
                end,
                scale,
            )?;
            (
                Motion::Arc(st.rotation.map_or(a, |r| r.arc_to_machine(a))),
                warning,
            )
        }
    })
}

/// The block's Fanuc corner word: `,R`/`,C`, a plain `C` that is a
/// chamfer (`chamfer_c`: the machine has no C axis), or a plain `R` on a
/// G01; its size in mm.
///
/// # Errors
/// A chamfer `C` or a corner word on a move other than G01, or two corner
/// words in the block.
fn corner_word<'a>(
    b: &'a Block,
    mode: MotionCode,
    chamfer_c: Option<&'a Word>,
    scale: f64,
) -> Result<Option<(&'a Word, CornerKind)>, NcError> {
    if let Some(c) = chamfer_c {
        if mode != MotionCode::Linear {
            return Err(err(
                b,
                c,
                format!(
                    "C{} on a G{} move: this machine has no C axis (set cAxis: true if it has one); a Fanuc chamfer C belongs on a G01 block",
                    c.text,
                    mode.code()
                ),
            ));
        }
    }
    let plain_r = b.word('R').filter(|_| mode == MotionCode::Linear);
    let mut corner: Option<(&Word, CornerKind)> = None;
    for w in b.comma_words.iter().chain(chamfer_c).chain(plain_r) {
        if corner.is_some() {
            return Err(err(
                b,
                w,
                "two corner words (R/C) in one block; expected one",
            ));
        }
        let v = w.value * scale;
        let kind = if w.letter == 'R' {
            CornerKind::Round(v)
        } else {
            CornerKind::Chamfer(v)
        };
        corner = Some((w, kind));
    }
    if let Some((w, _)) = corner {
        if mode != MotionCode::Linear {
            return Err(err(
                b,
                w,
                format!(
                    "corner word ,{}{} on a G{} move; corner rounding and chamfer belong on G01",
                    w.letter,
                    w.text,
                    mode.code()
                ),
            ));
        }
    }
    Ok(corner)
}

/// The end pose of a move with `axis_words` from `st` (G90/G91, G92 shift,
/// inch scale), in the un-rotated frame: under G68 the words are read in
/// the rotated frame ([`super::rotation`]).
pub(super) fn target(st: &Modal, axis_words: &[&Word], scale: f64) -> Pose {
    let from = match st.rotation {
        Some(r) => r.pose_to_program(st.pos),
        None => st.pos,
    };
    end_to_machine(st, st.pos, program_target(st, from, axis_words, scale))
}

/// The end pose of a move with `axis_words` from `from` in the program's
/// frame (G90/G91, G92 shift, inch scale).
fn program_target(st: &Modal, from: Pose, axis_words: &[&Word], scale: f64) -> Pose {
    let mut end = from;
    let origin = [st.offset[0], st.offset[1]];
    if let Some([x, y]) = super::polar::end_xy(axis_words, from, origin, st.incremental, scale) {
        end.set(0, x);
        end.set(1, y);
    }
    for w in axis_words
        .iter()
        .filter(|w| !super::polar::is_polar(w.letter))
    {
        let (i, v) = axis_value(w, scale);
        end.set(
            i,
            if st.incremental {
                end.get(i) + v
            } else {
                v + st.offset[i]
            },
        );
    }
    end
}

/// The pose index of an axis word and its value in mm (X/Y/Z, scaled by
/// the inch factor `scale`) or degrees (A/B/C, never scaled).
pub(super) fn axis_value(w: &Word, scale: f64) -> (usize, f64) {
    let i = AXES.iter().position(|&c| c == w.letter).unwrap_or(0);
    (i, if i < 3 { w.value * scale } else { w.value })
}

/// A copy of `b` whose I/J/K are made incremental from `start` (G90.1
/// absolute arc centres).
fn absolute_centre_block(b: &Block, start: Pose, scale: f64, off: &[f64; 6]) -> Block {
    let mut c = b.clone();
    for w in c.words.iter_mut() {
        let i = match w.letter {
            'I' => 0,
            'J' => 1,
            'K' => 2,
            _ => continue,
        };
        w.value = (w.value * scale + off[i] - start.get(i)) / scale;
    }
    c
}

#[cfg(test)]
mod flat_arc_tests {
    use crate::nc::program::parse;
    use crate::nc::segment::Motion;

    #[test]
    fn an_arc_flatter_than_its_centre_resolution_is_its_chord_with_a_warning() {
        let p = parse("G0 X0 Y0\nG2 X1 Y0 R999999999 F100").unwrap();
        let s = p.segments.last().unwrap();
        assert_eq!(s.motion, Motion::Linear);
        assert!((s.end.x - 1.0).abs() < 1e-12);
        assert!(p
            .warnings
            .iter()
            .any(|w| w.line == 2 && w.message.starts_with("flat arc")));
        // a real arc, small or large, is kept
        for text in [
            "G0 X0 Y0\nG2 X0.001 Y0 R0.5 F100",
            "G0 X0 Y0\nG3 X100 Y0 R1000 F100",
        ] {
            let p = parse(text).unwrap();
            assert!(
                matches!(p.segments.last().unwrap().motion, Motion::Arc(_)),
                "{text}"
            );
            assert!(p.warnings.is_empty(), "{text}");
        }
    }
}
