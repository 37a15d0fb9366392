//! The G codes of one block sorted by group (ISO 6983 / RS-274, FANUC
//! modal groups): the motion code (G0–G3), the G4 dwell, the modal codes
//! that set the plane, the units, the distance mode, the arc-centre mode and
//! the canned-cycle return level, the non-modal codes (G10, G28, G30, G53,
//! the G92 family), the canned-cycle codes, and the codes that are refused
//! (not simulated, and they would change the path) or warned about and
//! ignored, the cutter-compensation codes ([`super::cutter`]) and the
//! coordinate-rotation codes G68/G69 ([`super::rotation`]). The readings
//! are those of the interpreter's header
//! ([`super::program`]).
//!
//! A G code is handled as its value ×10, rounded (G91.1 → 911).

use super::program::{err, FeedMode, Modal, Warning};
use super::segment::{MotionCode, Plane};
use super::spline::Spline;
use super::{Block, NcError, Word};

/// The G words of one block that the rest of its interpretation needs.
#[derive(Default)]
pub(super) struct GWords<'a> {
    /// The motion code G0–G3, if any.
    pub motion: Option<(&'a Word, MotionCode)>,
    /// The G4 dwell word, if any.
    pub dwell: Option<&'a Word>,
    /// The non-modal code (G10, G28, G30, G53, G92, G92.1–G92.3) and its
    /// code ×10.
    pub non_modal: Option<(&'a Word, i64)>,
    /// The canned-cycle code (G73–G89) and its code ×10.
    pub cycle: Option<(&'a Word, i64)>,
    /// The cutter-compensation code (G40, G41, G42, G41.1, G42.1) and its
    /// code ×10.
    pub cutter: Option<(&'a Word, i64)>,
    /// The coordinate-rotation code (G68, G69) and its code ×10
    /// ([`super::rotation`]).
    pub rotation: Option<(&'a Word, i64)>,
    /// A Haas machining-setting code (G187 smoothness, G103 look-ahead),
    /// ×10: its `P` (and G187's `E`) words are its own, not ignored words.
    pub setting: Option<i64>,
    /// G5.3, the end of a NURBS block ([`super::spline`]).
    pub nurbs_end: Option<&'a Word>,
}

impl GWords<'_> {
    /// G10 data setting: the block does not move.
    pub fn is_g10(&self) -> bool {
        matches!(self.non_modal, Some((_, 100)))
    }
}

/// A word's value ×10, rounded: the integer form of a G or M code.
pub(super) fn code10(w: &Word) -> i64 {
    (w.value * 10.0).round() as i64
}

/// True for a word that ends the program: M2 or M30.
pub(super) fn is_program_end(w: &Word) -> bool {
    w.letter == 'M' && matches!(code10(w), 20 | 300)
}

/// Reads every G word of `b` in order: modal codes update `st` at once,
/// ignored codes are warned about, and the motion, dwell, non-modal and
/// cycle words are returned for the rest of the block.
///
/// # Errors
/// Two codes of one group in the block, or a refused code (see
/// [`refused`]).
pub(super) fn read_g_words<'a>(
    b: &'a Block,
    st: &mut Modal,
    warnings: &mut Vec<Warning>,
) -> Result<GWords<'a>, NcError> {
    let mut gw = GWords::default();
    let (mut sync, mut tap, mut spline) = (false, false, None);
    for w in b.words.iter().filter(|w| w.letter == 'G') {
        let g = code10(w);
        // G33: spindle-synchronised motion, a line at K × S; G33.1: rigid
        // tapping, there and back at K × S (LinuxCNC).
        let g33 = matches!(g, 330 | 331);
        sync |= g33;
        tap |= g == 331;
        // G5, G5.1, G5.2: spline feeds (LinuxCNC, super::spline).
        let curve = Spline::of(g);
        spline = spline.or(curve);
        if let Some(m) = motion_code(g).or((g33 || curve.is_some()).then_some(MotionCode::Linear)) {
            only_one(
                &mut gw.motion,
                b,
                w,
                m,
                "motion codes",
                "; expected one of G0, G1, G2, G3",
            )?;
        } else if g == 40 {
            gw.dwell = Some(w);
        } else if g == 53 {
            gw.nurbs_end = Some(w);
        } else if let Some(inch) = units_g70_g71(b, g) {
            st.inch = inch;
            warnings.push(Warning::at(
                b.line,
                w.column,
                format!(
                    "G{} read as {} units (older controls such as MillMaster's: G70 inch, G71 mm), since the block has no I/J/K/L words of a Haas bolt-hole pattern",
                    w.text,
                    if inch { "inch" } else { "mm" }
                ),
            ));
        } else if !set_modal(st, g) {
            grouped_or_other(b, w, g, &mut gw, warnings)?;
        }
    }
    let moving = gw.motion.is_some() || gw.cycle.is_some();
    if (moving || gw.non_modal.is_some()) && spline != Some(Spline::Cubic) {
        st.cubic_end_offset = None;
    }
    if moving {
        st.spindle_sync = sync;
        st.rigid_tap = tap;
        st.spline = spline;
    }
    Ok(gw)
}

/// G70 (inch) / G71 (mm) as units, as older controls use them (MillMaster,
/// Fanuc 0 lathes' alternative code system): detected by a block without
/// the I/J/K/L words of a Haas bolt-hole pattern (G70 I J L, G71 I J K L),
/// which stays a located error. `Some(true)`: inch.
pub(super) fn units_g70_g71(b: &Block, g: i64) -> Option<bool> {
    let pattern = b
        .words
        .iter()
        .any(|w| matches!(w.letter, 'I' | 'J' | 'K' | 'L'));
    match g {
        700 | 710 if !pattern => Some(g == 700),
        _ => None,
    }
}

/// The motion code of G0, G1, G2 or G3 (code ×10).
fn motion_code(g: i64) -> Option<MotionCode> {
    match g {
        0 => Some(MotionCode::Rapid),
        10 => Some(MotionCode::Linear),
        20 => Some(MotionCode::Cw),
        30 => Some(MotionCode::Ccw),
        _ => None,
    }
}

/// Stores the group's word in `slot`, or fails naming both words when the
/// group already has one in this block.
fn only_one<'a, T>(
    slot: &mut Option<(&'a Word, T)>,
    b: &Block,
    w: &'a Word,
    value: T,
    group: &str,
    hint: &str,
) -> Result<(), NcError> {
    if let Some((prev, _)) = slot {
        // The same code twice (`G0 G90 G0`) says one thing once more.
        if code10(prev) == code10(w) {
            return Ok(());
        }
        return Err(err(
            b,
            w,
            format!(
                "two {group} in one block (G{} and G{}){hint}",
                prev.text, w.text
            ),
        ));
    }
    *slot = Some((w, value));
    Ok(())
}

/// Applies a modal code that only sets state: plane (G17–G19), units
/// (G20/G21), distance mode (G90/G91), arc-centre mode (G90.1/G91.1), cycle
/// cancel (G80) and cycle return level (G98/G99). False for any other code.
fn set_modal(st: &mut Modal, g: i64) -> bool {
    match g {
        170 => st.plane = Plane::XY,
        180 => st.plane = Plane::ZX,
        190 => st.plane = Plane::YZ,
        200 => st.inch = true,
        210 => st.inch = false,
        900 => st.incremental = false,
        910 => st.incremental = true,
        930 | 940 | 950 => {
            let mode = match g {
                930 => FeedMode::InverseTime,
                940 => FeedMode::PerMinute,
                _ => FeedMode::PerRevolution,
            };
            if st.feed_mode != mode {
                st.feed_mode = mode;
                st.feed = None;
            }
        }
        901 => st.arc_center_absolute = true,
        911 => st.arc_center_absolute = false,
        800 => st.cycle = None,
        980 => st.cycle_return_r = false,
        990 => st.cycle_return_r = true,
        _ => return false,
    }
    true
}

/// A G code that is neither motion, dwell nor a plain modal code: a
/// non-modal or canned-cycle code is kept in `gw`; a refused code is an
/// error; anything else is ignored, with a warning unless it is harmless.
fn grouped_or_other<'a>(
    b: &Block,
    w: &'a Word,
    g: i64,
    gw: &mut GWords<'a>,
    warnings: &mut Vec<Warning>,
) -> Result<(), NcError> {
    match g {
        280 | 300 | 520 | 530 | 100 | 920 | 921 | 922 | 923 => {
            only_one(&mut gw.non_modal, b, w, g, "non-modal codes", "")
        }
        730 | 740 | 760 | 810 | 820 | 830 | 840 | 842 | 843 | 850 | 860 | 870 | 880 | 890 => {
            only_one(&mut gw.cycle, b, w, g, "canned cycles", "")
        }
        400 | 410 | 420 | 411 | 421 => only_one(
            &mut gw.cutter,
            b,
            w,
            g,
            "cutter-compensation codes",
            "; expected one of G40, G41, G42",
        ),
        680 | 690 => only_one(
            &mut gw.rotation,
            b,
            w,
            g,
            "coordinate-rotation codes",
            "; expected G68 or G69",
        ),
        640 if b.word('P').is_some() || b.word('Q').is_some() => {
            gw.setting = Some(g);
            warnings.push(Warning::at(b.line, w.column, setting_message(b, w, g)));
            Ok(())
        }
        1870 | 1030 => {
            gw.setting = Some(g);
            warnings.push(Warning::at(b.line, w.column, setting_message(b, w, g)));
            Ok(())
        }
        _ => {
            if let Some(e) = refused(b, w, g) {
                return Err(e);
            }
            if let Some(m) = warned(w, g) {
                warnings.push(Warning::at(b.line, w.column, m));
            }
            Ok(())
        }
    }
}

/// True when block `b` holds a G code whose `E` word is its own, not an
/// extruder's: Haas G187 (corner tolerance) or G47 (engraving plunge
/// feed; G47 itself is refused, [`refused`]).
pub(super) fn e_word_is_a_g_argument(b: &Block) -> bool {
    b.words
        .iter()
        .any(|w| w.letter == 'G' && matches!(code10(w), 1870 | 470))
}

/// The warning for Haas G187 (smoothness/accuracy: `P1` rough, `P2`
/// medium, `P3` finish, `E` corner tolerance) and G103 (block look-ahead
/// limit `P`, 0–15), and LinuxCNC's G64 with its path-blending tolerance
/// `P` and naive-CAM tolerance `Q`: the control's path smoothing and
/// look-ahead are not modelled, so the simulated acc/dec (tA, T) does not
/// change.
fn setting_message(b: &Block, w: &Word, g: i64) -> String {
    let letters: &[char] = match g {
        1870 => &['P', 'E'],
        640 => &['P', 'Q'],
        _ => &['P'],
    };
    let words: Vec<String> = letters
        .iter()
        .filter_map(|&c| b.word(c))
        .map(|x| format!("{}{}", x.letter, x.text))
        .collect();
    let what = match g {
        1870 => "Haas smoothness/accuracy setting",
        640 => "path-blending tolerance",
        _ => "Haas block look-ahead limit",
    };
    let with = if words.is_empty() {
        String::new()
    } else {
        format!(" {}", words.join(" "))
    };
    format!(
        "G{}{with} ({what}) is not modelled: the simulated acc/dec and servo lag do not change",
        w.text
    )
}

/// The error for a code that is not simulated and would change the path:
/// threading, the cycles without a model (G74.1, G80.1–G89.9 other
/// than the modelled ones), G95.1 (G93 inverse time and G95 feed
/// per revolution are read),
/// 3D coordinate conversion (G68.1–G68.4),
/// Okuma `G15 H`, modal macro calls. `None` for any other code.
fn refused(b: &Block, w: &Word, g: i64) -> Option<NcError> {
    let msg = match g {
        332 | 741 | 801..=879 | 881..=899 => format!(
            "G{}: {} is not simulated yet; post the program with the cycle expanded into G0/G1 moves",
            w.text,
            match g {
                // no manual at hand defines it: LinuxCNC has G33 and G33.1
                // (both simulated), its rs274 calls G33.2 unknown
                332 => "spindle-synchronised tapping (a code of neither LinuxCNC, whose G33 and G33.1 are simulated, nor Fanuc, whose rigid tapping G84.2/G84.3 is)",
                _ => "this canned cycle",
            }
        ),
        951 => format!(
            "G{}: feed per revolution changes the meaning of F and is not simulated; expected G94 (feed per minute) or G95",
            w.text
        ),
        681..=684 => format!(
            "G{}: 3D coordinate conversion / tilted working plane is not simulated; post the program in work coordinates (G68 in the plane is simulated)",
            w.text
        ),
        150 if b.word('H').is_some() => super::macro_expr::okuma_message("G15 H"),
        661 => format!(
            "G{}: a macro call after every block is not supported; use G66 (a call after each move) or G65 at each position",
            w.text
        ),
        _ => return moves_not_modelled(w, g).map(|m| err(b, w, m)),
    };
    Some(err(b, w, msg))
}

/// The codes that move the tool or transform the path in ways the
/// interpreter does not model: ignoring them (as an unknown code is, with
/// a warning) would simulate a different path, so they are refused.
/// Their cancels (G50 scaling, G50.1 and Haas G100 mirror, G13.1) are harmless
/// and pass ([`warned`]).
fn moves_not_modelled(w: &Word, g: i64) -> Option<String> {
    let (what, instead) = match g {
        120 | 130 => ("circular pocket milling (Haas)", "post the pocket as G1/G2/G3 moves"),
        470 => (
            "text engraving (Haas; it cuts the text of the comment in the control's own font)",
            "post the engraving as G1/G2/G3 moves, or remove the block",
        ),
        700 | 710 | 720 => (
            "a bolt-hole pattern (Haas: circle, arc, line of holes; G70/G71 without I/J/K/L are read as inch/mm units)",
            "program each hole's X/Y after the canned cycle (and G20/G21 for the units)",
        ),
        1500 => ("general-purpose pocket milling (Haas)", "post the pocket as G1/G2/G3 moves"),
        510 => ("scaling", "post the program at its final size"),
        511 | 1010 => ("mirror imaging", "post the mirrored moves themselves"),
        310..=314 | 382..=385 => (
            "a probing move (it stops where the probe touches, which the simulation cannot know)",
            "remove the probing blocks from the program you simulate",
        ),
        360 | 370 => (
            "automatic tool measurement (the move stops at the sensor)",
            "remove the measuring blocks from the program you simulate",
        ),
        1410 => ("3D cutter compensation (Haas)", "post the program with the tool path compensated"),
        1070 | 71 => ("cylindrical mapping", "post the program in X/Y/Z and the rotary axis"),
        121 => ("polar coordinate interpolation", "post the program in X/Y and the rotary axis"),
        160 => (
            "the polar coordinate command (FANUC G16: X is then a radius and Y an angle)",
            "post the program in X/Y, or use LinuxCNC's @/^ words",
        ),
        62 => ("NURBS interpolation", "post the program with lines and arcs (G1/G2/G3)"),
        _ => return None,
    };
    Some(format!("G{}: {what} is not simulated; {instead}", w.text))
}

/// The warning for an ignored code: work offsets (G54–G59, G54.1, Haas
/// G110–G129 and G154), tool length compensation (G43, G44, G43.1,
/// G43.4) and any code not modelled. `None` for the codes that do not
/// affect the path (G49, G94, G15, G61–G64, and the cancels G50, G50.1,
/// G100, G13.1 of the refused scaling, mirror and polar codes).
fn warned(w: &Word, g: i64) -> Option<String> {
    Some(match g {
        540..=590 | 1100..=1290 | 1540 => format!(
            "work offset G{}: its offset values are unknown here, so the program frame is kept (all work offsets coincide)",
            w.text
        ),
        490 | 150 | 610..=649 | 500 | 501 | 1000 | 131 => return None,
        430 | 440 | 431 | 434 => format!(
            "G{}: tool length compensation is ignored (Z is the programmed Z)",
            w.text
        ),
        _ => format!("G{} is not modelled and was ignored", w.text),
    })
}
