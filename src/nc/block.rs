//! One block's interpretation, in the order a FANUC-style control reads it:
//! the G codes by group ([`super::gcodes`]), the M codes that end the
//! program, the F word and the words the motion model ignores, cutter
//! compensation ([`super::cutter`]; refused around the moves it does not
//! simulate), the coordinate rotation G68/G69 ([`super::rotation`]: a G68
//! block does nothing else), then what
//! the block does: G10 data setting (nothing), a G4 dwell, a canned-cycle
//! block ([`super::cycles`]), a non-modal move ([`super::non_modal`]) or a
//! move ([`super::moves`]). The readings are those of the interpreter's
//! header ([`super::program`]).
//!
//! Units: mm, s, feed in mm/min (inch words scaled by 25.4).

use super::cutter::{cutter_word, refused_during};
use super::cycles::{canned_cycle, Cycle};
use super::fadal;
use super::gcodes::{code10, e_word_is_a_g_argument, read_g_words, GWords};
use super::moves::move_block;
use super::non_modal::non_modal_move;
use super::program::{
    err, Ctx, FeedMode, Modal, MotionCode, Warning, MAX_PLAUSIBLE_FEED, MIN_PLAUSIBLE_FEED,
};
use super::rotation::rotation_block;
use super::segment::{Motion, Segment};
use super::{Block, NcError, Word};

/// Millimetres per inch.
const INCH: f64 = 25.4;

/// The factor from the program's length unit to mm (G20: 25.4).
pub(super) fn length_scale(st: &Modal) -> f64 {
    if st.inch {
        INCH
    } else {
        1.0
    }
}

/// Interprets block `b` on the modal state `st`, adding its segments,
/// corners and warnings to `cx`.
///
/// # Errors
/// The block's first error, naming its column (an `E` word's error contains
/// "this looks like": the caller stops the program there).
pub(super) fn interpret_block(b: &Block, st: &mut Modal, cx: &mut Ctx) -> Result<(), NcError> {
    let gw = read_g_words(b, st, cx.warnings)?;
    reject_extruder(b, gw.motion.map(|(_, m)| m).or(st.motion))?;
    read_m_words(b, st);
    let scale = length_scale(st);
    if let Some((w, g)) = gw.cutter {
        cutter_word(b, st, cx, w, g)?;
    }
    read_other_words(b, st, &gw, cx.warnings)?;
    no_repeated_axis(b)?;
    super::polar::check(b, st.plane)?;
    if rotation_block(b, st, &gw, cx.stretches, scale)? {
        return Ok(());
    }
    if gw.is_g10() {
        if let Some((w, _)) = gw.non_modal {
            cx.warnings.push(Warning::at(
                b.line,
                w.column,
                "G10 sets offset/tool data and does not move; its words were not run as a move",
            ));
        }
        return Ok(());
    }
    if let Some(e) = super::spline::interrupted(b, &gw, cx) {
        return Err(e);
    }
    if let Some(dw) = gw.dwell {
        return dwell(b, st, cx, dw, &gw);
    }
    set_motion_or_cycle(b, st, &gw)?;
    let moving_code = match (gw.non_modal, gw.cycle) {
        (Some((w, _)), _) | (None, Some((w, _))) => Some(w),
        _ if st.cycle.is_some() => b.words.first(),
        _ => None,
    };
    if let Some(e) = refused_during(b, st, cx, moving_code) {
        return Err(e);
    }
    if st.cycle.is_some() && gw.non_modal.is_none() {
        return canned_cycle(b, st, cx, gw.cycle.map(|(w, _)| w), scale);
    }
    if let Some((w, g)) = gw.non_modal {
        if let Some(p) = super::polar::polar_word(b) {
            return Err(err(
                b,
                p,
                format!(
                    "polar word {}{} on a G{} block: write its point as X/Y",
                    p.letter, p.text, w.text
                ),
            ));
        }
        return non_modal_move(b, st, cx, w, g, &axis_words(b, cx), scale);
    }
    if let Some(w) = gw.nurbs_end {
        return super::spline::nurbs_end(b, st, cx, w);
    }
    if let Some(s) = st.spline {
        return super::spline::spline_block(b, st, cx, s, scale);
    }
    move_block(b, st, cx, scale)
}

/// The axis words of `b` (X Y Z A B, C when it is an axis, and the
/// polar `@`/`^` of [`super::polar`]).
pub(super) fn axis_words<'a>(b: &'a Block, cx: &Ctx) -> Vec<&'a Word> {
    b.words
        .iter()
        .filter(|w| {
            (super::segment::AXES.contains(&w.letter) && (w.letter != 'C' || cx.opt.c_axis))
                || super::polar::is_polar(w.letter)
        })
        .collect()
}

/// An axis or polar word given twice on one block is refused: LinuxCNC
/// refuses it, Fanuc controls differ (an alarm, or the last one taken), and
/// reading either silently would move somewhere the program may not mean.
fn no_repeated_axis(b: &Block) -> Result<(), NcError> {
    let words = b.words.iter().enumerate();
    for (k, w) in words.filter(|(_, w)| super::polar::is_position(w.letter)) {
        if let Some(first) = b.words[..k].iter().find(|v| v.letter == w.letter) {
            return Err(err(
                b,
                w,
                format!(
                    "{}{} repeats {}{} on one block: a block takes each axis once (LinuxCNC refuses it, Fanuc controls differ); keep the one meant",
                    w.letter, w.text, first.letter, first.text
                ),
            ));
        }
    }
    Ok(())
}

/// An `E` word stops the program: it drives a 3D printer's extruder
/// (except on a Haas G187 or G47 block, where it is that code's own, and a
/// Fadal fixture offset, [`super::fadal`]); `motion` is the block's motion.
/// (`#100=1E3`, an exponent, is named as one by the macro parser.)
fn reject_extruder(b: &Block, motion: Option<MotionCode>) -> Result<(), NcError> {
    match b.word('E') {
        Some(e) if !e_word_is_a_g_argument(b) && !fadal::is_fixture_offset(b, motion) => Err(err(
            b,
            e,
            format!(
                "E{}: this looks like a 3D-printer program (E words drive the extruder); mtmotion reads milling programs only",
                e.text
            ),
        )),
        _ => Ok(()),
    }
}

/// M2/M30 end the program (the calls and returns M97, M98, M99 are run
/// after the block, [`super::run`]).
fn read_m_words(b: &Block, st: &mut Modal) {
    if b.words.iter().any(super::gcodes::is_program_end) {
        st.ended = true;
    }
}

/// Reads the F word into `st` and warns about every word the motion model
/// does not use (a word some code of the block gives a meaning is silent).
fn read_other_words(
    b: &Block,
    st: &mut Modal,
    gw: &GWords,
    warnings: &mut Vec<Warning>,
) -> Result<(), NcError> {
    let g10 = gw.is_g10();
    let call = b
        .words
        .iter()
        .any(|w| w.letter == 'M' && matches!(code10(w), 970 | 980 | 990));
    for w in &b.words {
        let ignored = match w.letter {
            'F' => {
                read_feed(b, w, st, warnings)?;
                continue;
            }
            'S' => {
                if w.value < 0.0 {
                    return Err(err(
                        b,
                        w,
                        format!(
                            "S{}: a negative spindle speed; expected S in rpm, 0 or more (M3/M4 give the direction)",
                            w.text
                        ),
                    ));
                }
                st.spindle = Some(w.value);
                if st.feed_mode == FeedMode::PerRevolution {
                    continue;
                }
                format!(
                    "S{}: the spindle speed does not affect the motion model (it sets the feed only under G95, feed per revolution, and of G33 moves)",
                    w.text
                )
            }
            'G' | 'N' | 'O' | 'X' | 'Y' | 'Z' | 'A' | 'B' | 'I' | 'J' | 'K' | 'R' | '@' | '^' => {
                continue
            }
            'C' => continue,
            'P' | 'U' if gw.dwell.is_some() => continue,
            'L' | 'P' if g10 => continue,
            'P' | 'L' if call => continue,
            'P' | 'L' if st.spline == Some(super::spline::Spline::Nurbs) => continue,
            'P' | 'Q' if st.spline == Some(super::spline::Spline::Cubic) => continue,
            'P' if gw.setting.is_some() => continue,
            'E' if gw.setting == Some(1870) => continue,
            'E' if fadal::is_fixture_offset(b, gw.motion.map(|(_, m)| m).or(st.motion)) => format!(
                "E{}: a Fadal fixture offset (E1–E48, as G54–G59; E0 cancels): its offset values are unknown here, so the program frame is kept",
                w.text
            ),
            'Q' if gw.setting == Some(640) => continue,
            'M' if matches!(code10(w), 20 | 300 | 970 | 980 | 990) => continue,
            'L' | 'P' | 'Q' if st.cycle.is_some() || gw.cycle.is_some() => continue,
            'L' if fadal::is_subroutine_word(w) => return Err(fadal::subroutine_error(b, w)),
            'D' if gw.cutter.is_some_and(|(_, g)| g != 400) => continue,
            // A D word elsewhere is the modal offset number a later
            // G41/G42 without D uses.
            'D' if w.value >= 0.0 && w.value.fract() == 0.0 => {
                st.d = Some(w.value);
                continue;
            }
            'M' | 'T' | 'H' | 'D' => format!(
                "{}{} does not affect the motion model and was ignored",
                w.letter, w.text
            ),
            _ => format!("unknown word {}{} was ignored", w.letter, w.text),
        };
        warnings.push(Warning::at(b.line, w.column, ignored));
    }
    Ok(())
}

/// The F word: the modal feed in mm/min (inch/min scaled under G20); a
/// negative feed is an error, an implausibly high one a warning.
fn read_feed(
    b: &Block,
    w: &Word,
    st: &mut Modal,
    warnings: &mut Vec<Warning>,
) -> Result<(), NcError> {
    if w.value < 0.0 {
        return Err(err(
            b,
            w,
            format!(
                "negative feed F{}; expected a positive feed in mm/min",
                w.text
            ),
        ));
    }
    // Under G93 F is 1/min, whatever the length unit.
    let inverse = st.feed_mode == FeedMode::InverseTime;
    let f = w.value * if inverse { 1.0 } else { length_scale(st) };
    if f > MAX_PLAUSIBLE_FEED && st.feed_mode == FeedMode::PerMinute {
        warnings.push(Warning::at(
            b.line,
            w.column,
            format!(
                "F{} {} = {:.0} mm/min is implausible for a milling feed (above {} mm/min); check the units (G20/G21) and the F word",
                w.text,
                if st.inch { "inch/min" } else { "mm/min" },
                f,
                MAX_PLAUSIBLE_FEED
            ),
        ));
    }
    if f < MIN_PLAUSIBLE_FEED && st.feed_mode == FeedMode::PerMinute {
        warnings.push(Warning::at(
            b.line,
            w.column,
            format!(
                "F{} {} = {f:.3} mm/min is implausibly slow for a milling feed (below {MIN_PLAUSIBLE_FEED} mm/min: a 1 mm move takes {:.0} s or more); check the F word (a lead-in posted with F1.?) and the units (G20/G21)",
                w.text,
                if st.inch { "inch/min" } else { "mm/min" },
                60.0 / MIN_PLAUSIBLE_FEED
            ),
        ));
    }
    st.feed = Some(f);
    Ok(())
}

/// G4 dwell: `X`/`U` in seconds or `P` per [`super::program::DwellP`]; one
/// dwell segment at the current pose.
fn dwell(b: &Block, st: &Modal, cx: &mut Ctx, dw: &Word, gw: &GWords) -> Result<(), NcError> {
    if gw.motion.is_some() {
        return Err(err(
            b,
            dw,
            "G4 dwell together with a motion code; expected the dwell in its own block",
        ));
    }
    let (w, seconds) = if let Some(w) = b.word('X').or(b.word('U')) {
        (w, w.value)
    } else if let Some(w) = b.word('P') {
        let (seconds, ms) = cx.opt.dwell_p.seconds(w);
        if cx.opt.dwell_p == super::program::DwellP::Auto && ms {
            cx.warnings.push(Warning::at(
                b.line,
                w.column,
                format!(
                    "G4 P{} read as {} ms (Fanuc: P without a decimal point is milliseconds); LinuxCNC and Grbl read it as {} s — set dwellP to 'seconds' for those controls",
                    w.text, w.text, w.text
                ),
            ));
        }
        (w, seconds)
    } else {
        return Err(err(
            b,
            dw,
            "G4 dwell without a time; expected X (seconds) or P",
        ));
    };
    if seconds < 0.0 || !seconds.is_finite() {
        return Err(err(b, w, "dwell time must be zero or positive"));
    }
    cx.segments.push(Segment {
        block: Some(cx.bi),
        line: b.line,
        motion: Motion::Dwell { seconds },
        start: st.pos,
        end: st.pos,
        feed: 0.0,
        fixed: false,
    });
    Ok(())
}

/// A motion code sets the motion mode and cancels the canned cycle (a
/// cycle code beside it is an error); a cycle code starts the cycle mode at
/// the current drilling-axis level or changes the active cycle's code.
fn set_motion_or_cycle(b: &Block, st: &mut Modal, gw: &GWords) -> Result<(), NcError> {
    if let Some((_, m)) = gw.motion {
        st.motion = Some(m);
        st.cycle = None;
        if let Some((w, _)) = gw.cycle {
            return Err(err(
                b,
                w,
                format!(
                    "G{} together with a motion code G0–G3 (which cancels canned cycles)",
                    w.text
                ),
            ));
        }
    }
    if let Some((_, g)) = gw.cycle {
        match st.cycle.as_mut() {
            Some(c) => c.code = g,
            None => {
                let (_, _, n) = st.plane.axes();
                st.cycle = Some(Cycle {
                    code: g,
                    initial: st.pos.get(n),
                    r: None,
                    bottom: None,
                    depth: None,
                    q: 0.0,
                    dwell: 0.0,
                    shift: [0.0; 3],
                    back: None,
                })
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod exponent_tests {
    #[test]
    fn an_exponent_in_a_macro_statement_is_named_as_one_not_as_a_3d_printer() {
        let e = crate::nc::program::parse("#100=1E3\nG1 X#100 F100").unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("NC numbers take no exponent") && !m.contains("3D"),
            "{m}"
        );
        let e = crate::nc::program::parse("G1 X1 E0.5 F100").unwrap_err();
        assert!(e.to_string().contains("3D-printer"));
    }
}
