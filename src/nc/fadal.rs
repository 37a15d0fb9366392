//! Fadal (format 2) words that a Fanuc reading would get wrong: the `L`
//! subroutine word and the `E` fixture offset.
//!
//! The reading (Fadal VMC programming manual, format 2; not found in the
//! searchable public documents, so stated here as read): an `L` word of
//! four digits `Lnnrr` names subroutine `nn` (01–99) and a count `rr`.
//! `rr = 00` starts the *definition* of subroutine `nn` (`L0100`, often
//! written `L100`); its blocks run to `M17`, and the definitions come
//! before the main program. `rr` from 01 to 99 *calls* subroutine `nn`
//! `rr` times (`L0101`, `L101`: subroutine 1 once; `L0205`: subroutine 2
//! five times). `E1`…`E48` select a fixture offset (as G54–G59 do on a
//! Fanuc control; `E0` cancels it).
//!
//! What mtmotion does: an `L` word of that form that no code of its block
//! claims (a canned cycle's, G10's or M98's repeat count) is a located
//! error. Skipping it, as an unknown word is skipped with a warning, would
//! simulate the program without its subroutines: a job that drills its
//! holes in subroutines would show no drilling and look complete. An `E`
//! word of the fixture-offset form is warned like G54–G59 (the program
//! frame is kept), not refused as a 3D printer's extruder word.

use super::program::{err, MotionCode};
use super::{Block, NcError, Word};

/// True when `w` (an `L` word no code of its block uses) has the Fadal
/// subroutine form: a whole number of three or four digits, 100 or more.
pub(super) fn is_subroutine_word(w: &Word) -> bool {
    w.letter == 'L'
        && w.text.chars().all(|c| c.is_ascii_digit())
        && (3..=4).contains(&w.text.len())
        && w.value >= 100.0
}

/// The located refusal of a Fadal subroutine word `w`: a definition
/// (`L0100`) or a call (`L0101`).
pub(super) fn subroutine_error(b: &Block, w: &Word) -> NcError {
    let n = (w.value / 100.0).floor() as u32;
    let count = (w.value % 100.0) as u32;
    let what = if count == 0 {
        format!("starts the definition of Fadal subroutine {n} (its blocks run to M17)")
    } else {
        format!(
            "calls Fadal subroutine {n} {count} time{}",
            if count == 1 { "" } else { "s" }
        )
    };
    err(
        b,
        w,
        format!(
            "L{} {what}; Fadal L subroutines are not simulated, and skipping them would leave their moves out: post the program for a Fanuc-compatible control (M98/M99 subprograms) or expand the subroutines",
            w.text
        ),
    )
}

/// True when the block's `E` word is a Fadal fixture offset rather than a
/// 3D printer's extruder word: a whole number 0–48 written without a point
/// or sign, on a block that does not cut (no G1/G2/G3 in force with axis
/// words, no G92 — a printer's `G92 E0` resets its extruder). `motion` is
/// the motion the block runs (its own code, else the modal one).
pub(super) fn is_fixture_offset(b: &Block, motion: Option<MotionCode>) -> bool {
    let Some(e) = b.word('E') else { return false };
    let whole = !e.text.is_empty() && e.text.chars().all(|c| c.is_ascii_digit());
    let g92 = b.words_of('G').any(|g| g.value == 92.0);
    let axes = b.words.iter().any(|w| "XYZABC".contains(w.letter));
    let cuts = axes && !matches!(motion, None | Some(MotionCode::Rapid));
    whole && e.value <= 48.0 && !g92 && !cuts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subroutine_words_and_fixture_offsets_are_recognised() {
        let b = &crate::nc::lex("L0205").unwrap()[0];
        let l = b.word('L').unwrap();
        assert!(is_subroutine_word(l));
        let e = subroutine_error(b, l);
        assert!(
            e.message.contains("calls Fadal subroutine 2 5 times"),
            "{e}"
        );
        let b = &crate::nc::lex("L100").unwrap()[0];
        assert!(subroutine_error(b, b.word('L').unwrap())
            .message
            .contains("definition of Fadal subroutine 1"));
        for l in ["L5", "L1.5", "L-100"] {
            let b = &crate::nc::lex(l).unwrap()[0];
            assert!(!is_subroutine_word(b.word('L').unwrap()), "{l}");
        }
        let fx = |s: &str, m| is_fixture_offset(&crate::nc::lex(s).unwrap()[0], m);
        assert!(fx("G0 X1 Y2 E1", Some(MotionCode::Rapid)));
        assert!(fx("E0", Some(MotionCode::Linear)));
        assert!(!fx("G1 X1 E1", Some(MotionCode::Linear)));
        assert!(!fx("G92 E0", None));
        assert!(!fx("G0 X1 E0.5", Some(MotionCode::Rapid)));
        assert!(!fx("E49", None));
    }
}
