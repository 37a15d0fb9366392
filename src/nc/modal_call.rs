//! Fanuc modal macro call G66/G67 (Fanuc Custom Macro B, "modal call";
//! Haas reads it the same way).
//!
//! Readings chosen:
//! - `G66 P<program> [L<repeats>] <arguments>` moves nothing and registers
//!   the call; its arguments (specification I and II, as G65) are
//!   evaluated once, on the G66 block. After every following block of the
//!   same call level that commands axis motion (X Y Z A B C, or LinuxCNC
//!   polar `@`/`^`), the move is executed first and then the program is
//!   called as by G65 with those arguments, L times, with its own local
//!   variables. Blocks without axis words (M, S, F alone, macro
//!   statements, dwells) do not call it.
//! - Moves inside the called program, or in any subprogram deeper than
//!   the level of the G66, do not call it again (Fanuc calls the modal
//!   macro from the level that set it only).
//! - `G67` cancels it. A G67 block holding anything but N and G67 is
//!   refused (its other words would be dropped), and so is a G66 while
//!   another is in force (cancel it with G67 first): Fanuc nests modal
//!   calls, which is not modelled. G66.1 (a call on every block) stays
//!   refused (`gcodes`).
//! - The called program's moves are `fixed` (inside a call), as for G65.
//!
//! Units: the arguments are the words' values as written (a G20 program's
//! arguments stay in inches, as G65's do).

use super::macro_exec::Step;
use super::{Block, NcError, Word};

/// A registered G66 call.
#[derive(Debug, Clone)]
pub struct ModalCall {
    /// O-number of the called program.
    pub number: u32,
    /// Calls per triggering move (L).
    pub times: u32,
    /// The locals of each call (variable number, value).
    pub args: Vec<(u32, f64)>,
    /// The G66 block's P word (for errors).
    pub p: Word,
    /// Call level (subprogram and macro depth) of the G66 block.
    pub level: usize,
}

impl ModalCall {
    /// The G65-like call this registration makes after the move `b`: an
    /// error of the call (a missing program, too deep) is located at the
    /// move's first axis word.
    pub(super) fn step(&self, b: &Block) -> Step {
        let column = first_move_word(b).map_or(1, |w| w.column);
        Step::Call {
            number: self.number,
            times: self.times,
            args: self.args.clone(),
            p: Word {
                column,
                ..self.p.clone()
            },
            via: "G66",
        }
    }
}

/// The first word of `b` that commands axis motion (X, Y, Z, A, B, C or
/// a polar `@`/`^`), if any: the blocks after which a G66 call runs.
fn first_move_word(b: &Block) -> Option<&Word> {
    b.words.iter().find(|w| super::polar::is_position(w.letter))
}

/// True when `b` commands axis motion (see [`first_move_word`]).
pub(super) fn is_move(b: &Block) -> bool {
    first_move_word(b).is_some()
}

/// A G67 block must hold nothing but N and G67.
///
/// # Errors
/// The first other word, located.
pub(super) fn check_g67(b: &Block) -> Result<(), NcError> {
    match b
        .words
        .iter()
        .find(|w| !(w.letter == 'N' || (w.letter == 'G' && w.value == 67.0)))
    {
        Some(w) => Err(NcError::new(
            b.line,
            w.column,
            format!(
                "{}{} on a G67 block: G67 cancels the modal call and takes no other word; write G67 on its own block",
                w.letter, w.text
            ),
        )),
        None => Ok(()),
    }
}
