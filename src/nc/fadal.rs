//! Fadal (format 2) words that a Fanuc reading would get wrong: the `L`
//! subroutine word and the `E` fixture offset.
//!
//! The reading (Fadal VMC programming manual, format 2, "Subroutines";
//! the manual is not among the searchable public documents, so the
//! reading is stated here as taken): an `L` word of four digits `Lnnrr`
//! names subroutine `nn` (01–99) and a count `rr`. `rr = 00` starts the
//! *definition* of subroutine `nn` (`L0100`, often written `L100`); its
//! blocks run to `M17`, and the definitions come before the main program.
//! `rr` from 01 to 99 *calls* subroutine `nn` `rr` times (`L0101`, `L101`:
//! subroutine 1 once; `L0205`: subroutine 2 five times). `E1`…`E48` select
//! a fixture offset (as G54–G59 do on a Fanuc control; `E0` cancels it).
//!
//! What mtmotion does ([`Subroutines`], run by `run.rs` with the M98/M99
//! call machinery, so a called body's moves are `fixed` like any
//! subprogram's):
//! - a definition is a block holding only its `Lnn00` word (and an `N`
//!   number): the run skips from it past its `M17` block; its blocks run
//!   only when called. Where the main program begins: after the
//!   definitions, at the first block the run reaches that is not one.
//!   Fadal programs also end the definitions with an `M30` block before the
//!   main program; an `M2`/`M30` block whose previous block with words is a
//!   definition's `M17`, and that has blocks with words after it, is read
//!   as that marker: it is skipped with a warning instead of ending the
//!   program (ending there would leave the whole main program unrun);
//! - a call is a block holding only its `Lnnrr` word (`rr` 01–99, and an
//!   `N` number): it runs subroutine `nn` `rr` times, each run from the
//!   block after the definition to the `M17` block (whose other words run
//!   before the return), then goes on after the call;
//! - refused, each at its `L` word: a definition inside a definition, a
//!   definition with no `M17` before the program end (`M2`/`M30`), the end
//!   of its file or the end of the text, a subroutine defined twice, a call
//!   of a subroutine the program does not define, a subroutine calling
//!   itself (directly or through another: it never ends on the control),
//!   and calls nested deeper than [`NESTING`] levels (the nesting depth
//!   allowed is read as 4, as on the Fanuc controls Fadal's format 2
//!   follows; a deeper program is refused, never cut short). An `Lnnrr`
//!   word that no code of its block claims (a canned cycle's, G10's or
//!   M98's repeat count) on a block with other words is refused too: a
//!   definition or call goes on a block of its own.
//!
//! An `E` word of the fixture-offset form is warned like G54–G59 (the
//! program frame is kept), not refused as a 3D printer's extruder word.

use std::collections::HashMap;

use super::gcodes::{code10, is_program_end};
use super::program::{err, MotionCode};
use super::{Block, NcError, Word};

/// Fadal subroutine calls nested at most this deep (a call from a
/// subroutine called from the main program is level 2).
pub(super) const NESTING: usize = 4;

/// True when `w` (an `L` word no code of its block uses) has the Fadal
/// subroutine form: a whole number of three or four digits, 100 or more.
pub(super) fn is_subroutine_word(w: &Word) -> bool {
    w.letter == 'L'
        && w.text.chars().all(|c| c.is_ascii_digit())
        && (3..=4).contains(&w.text.len())
        && w.value >= 100.0
}

/// The subroutine number `nn` and count `rr` of a subroutine word.
fn number_and_count(w: &Word) -> (u32, u32) {
    let v = w.value as u32;
    (v / 100, v % 100)
}

/// The block's `L` word when the block holds nothing but it (and an `N`
/// number) and it has the subroutine form: `(word, nn, rr)`.
fn lone_l_word(b: &Block) -> Option<(&Word, u32, u32)> {
    if b.macro_line.is_some() || b.words.iter().any(|w| !matches!(w.letter, 'L' | 'N')) {
        return None;
    }
    let mut ls = b.words_of('L');
    let l = ls.next().filter(|l| is_subroutine_word(l))?;
    if ls.next().is_some() {
        return None;
    }
    let (n, count) = number_and_count(l);
    Some((l, n, count))
}

/// A call block: `(L word, subroutine nn, count rr)`, `rr` ≥ 1.
pub(super) fn call(b: &Block) -> Option<(&Word, u32, u32)> {
    lone_l_word(b).filter(|&(_, _, rr)| rr > 0)
}

/// A definition block: `(L word, subroutine nn)`.
fn definition(b: &Block) -> Option<(&Word, u32)> {
    lone_l_word(b)
        .filter(|&(_, _, rr)| rr == 0)
        .map(|(w, n, _)| (w, n))
}

/// The block ends a subroutine body (it holds `M17`).
fn is_m17(b: &Block) -> bool {
    b.words.iter().any(|w| w.letter == 'M' && code10(w) == 170)
}

/// Block `b` without its `M17` word (the rest of an `M17` block runs
/// before the subroutine returns).
pub(super) fn without_m17(b: &Block) -> Block {
    let mut rest = b.clone();
    rest.words
        .retain(|w| !(w.letter == 'M' && code10(w) == 170));
    rest
}

/// The block has words (not only comments, `%` or nothing).
fn has_words(b: &Block) -> bool {
    !b.words.is_empty() || b.macro_line.is_some()
}

/// A block of only `M2`/`M30` (and an `N` number).
fn is_end_only(b: &Block) -> bool {
    b.macro_line.is_none()
        && b.words.iter().any(is_program_end)
        && b.words.iter().all(|w| w.letter == 'N' || is_program_end(w))
}

/// One defined subroutine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Definition {
    /// Index of its `Lnn00` block.
    pub start: usize,
    /// Index of its `M17` block.
    pub end: usize,
    /// Index of the block the main program goes on at when the run
    /// reaches the definition: after the `M17`, or after the `M30` that
    /// marks the end of the definitions.
    pub skip_to: usize,
    /// Index of that end-of-definitions `M30` block, when there is one.
    pub marker: Option<usize>,
}

/// The Fadal subroutines a program defines.
#[derive(Debug, Default)]
pub(super) struct Subroutines {
    /// Subroutine number → its definition.
    by_number: HashMap<u32, Definition>,
    /// Index of a definition block → its number.
    by_start: HashMap<usize, u32>,
}

impl Subroutines {
    /// Finds the definitions of `blocks` (see the module header).
    ///
    /// # Errors
    /// Every malformed definition, each at its `L` word.
    pub fn new(blocks: &[Block]) -> Result<Self, Vec<NcError>> {
        let mut s = Self::default();
        let mut errors = Vec::new();
        let mut open: Option<(usize, u32)> = None;
        for (i, b) in blocks.iter().enumerate() {
            if let Some((os, on)) = open {
                let left_file = b.file != blocks[os].file;
                if left_file || b.words.iter().any(is_program_end) {
                    errors.push(no_m17(&blocks[os], on, (!left_file).then_some(b)));
                    open = None;
                }
            }
            if let Some((w, n)) = definition(b) {
                if let Some((os, on)) = open {
                    errors.push(err(
                        b,
                        w,
                        format!(
                            "L{} starts the definition of Fadal subroutine {n} inside the definition of subroutine {on} (line {}); end subroutine {on} with M17 first: definitions do not nest",
                            w.text, blocks[os].line
                        ),
                    ));
                } else if let Some(d) = s.by_number.get(&n) {
                    errors.push(err(
                        b,
                        w,
                        format!(
                            "L{} defines Fadal subroutine {n} again (it is defined on line {}); give each subroutine its own number",
                            w.text, blocks[d.start].line
                        ),
                    ));
                } else {
                    open = Some((i, n));
                }
            } else if let (Some((os, on)), true) = (open, is_m17(b)) {
                let (skip_to, marker) = after_definition(blocks, i);
                s.by_number.insert(
                    on,
                    Definition {
                        start: os,
                        end: i,
                        skip_to,
                        marker,
                    },
                );
                s.by_start.insert(os, on);
                open = None;
            }
        }
        if let Some((os, on)) = open {
            errors.push(no_m17(&blocks[os], on, None));
        }
        if errors.is_empty() {
            Ok(s)
        } else {
            Err(errors)
        }
    }

    /// The definition starting at block `bi`, when one does.
    pub fn starting_at(&self, bi: usize) -> Option<Definition> {
        self.by_number.get(self.by_start.get(&bi)?).copied()
    }

    /// Block `bi` belongs to a definition, from its `Lnn00` block to its
    /// `M17` block and the end-of-definitions `M30` after it: not a block
    /// of the main program.
    pub fn in_definitions(&self, bi: usize) -> bool {
        self.by_number
            .values()
            .any(|d| (d.start..d.skip_to).contains(&bi))
    }

    /// The definition of subroutine `n`.
    pub fn get(&self, n: u32) -> Option<Definition> {
        self.by_number.get(&n).copied()
    }
}

/// Where the run goes on after the definition ending at block `end`: the
/// block after it, or after the end-of-definitions `M30` (returned too)
/// when one follows.
fn after_definition(blocks: &[Block], end: usize) -> (usize, Option<usize>) {
    let next = (end + 1..blocks.len()).find(|&k| has_words(&blocks[k]));
    let marker = next.filter(|&k| {
        is_end_only(&blocks[k])
            && blocks[k].file == blocks[end].file
            && blocks[k + 1..]
                .iter()
                .any(|b| has_words(b) && b.file == blocks[k].file)
    });
    match marker {
        Some(k) => (k + 1, Some(k)),
        None => (end + 1, None),
    }
}

/// The refusal of subroutine `n`'s definition (block `def`) that reaches
/// `end` (the program end `M2`/`M30`; `None`: the end of its file) with no
/// `M17`.
fn no_m17(def: &Block, n: u32, end: Option<&Block>) -> NcError {
    let (column, text) = def
        .word('L')
        .map_or((1, ""), |l| (l.column, l.text.as_str()));
    let reach = match end {
        Some(e) => format!("reaches the program end on line {}", e.line),
        None => "reaches the end of its file".to_string(),
    };
    NcError::new(
        def.line,
        column,
        format!(
            "L{text}: the definition of Fadal subroutine {n} {reach} without M17; end each subroutine with M17"
        ),
    )
}

/// The located refusal of a Fadal subroutine word `w` on a block that
/// holds other words: a definition (`L0100`) or a call (`L0101`) goes on
/// a block of its own.
pub(super) fn subroutine_error(b: &Block, w: &Word) -> NcError {
    let (n, count) = number_and_count(w);
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
            "L{} {what}, on a block with other words: put the L word on a block of its own (N and the L word only), as Fadal programs do",
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
