//! Programs in other controls' languages, recognised so that they are
//! refused by name instead of at their first unreadable character:
//! Siemens Sinumerik (`CYCLE81(…)`, `MCALL`, `GOTOF`, `TRANS`, …) and
//! Heidenhain conversational (Klartext: `0 BEGIN PGM … MM`, `BLK FORM`,
//! `TOOL CALL`, `CYCL DEF`). A decimal comma (`X1,5`, European number
//! formatting) is named too. Okuma OSP is recognised in
//! [`super::macro_expr`] (its macro words overlap Fanuc Macro B's).
//!
//! Among the ISO dialects the reader takes, the one that matters to a
//! writer is how a dwell's time is read ([`dwell_form`]): the form a G4
//! that a compensation inserts is written in, so that the control reads
//! the time meant:
//! - a LinuxCNC program — `dwellP: 'seconds'`, or a word only LinuxCNC
//!   writes ([`linuxcnc_sign`]: o-words or `#<named>` parameters, polar
//!   `@`/`^` words, `G64 P`/`Q`, `G41.1`/`G42.1`, `G33.1`, a `(MSG,` /
//!   `(DEBUG,` / `(PRINT,` / `(LOG…` comment) — gets `G4 P<seconds>` with
//!   a decimal point, which LinuxCNC and Grbl read as seconds and so does
//!   the reader's `auto` (a LinuxCNC `G4 P2` already in it is not copied:
//!   without a point `auto` would read the copy as milliseconds);
//! - otherwise (Fanuc, Haas and their kind) the program's own first G4
//!   time word: `X`/`U` is seconds on Fanuc (written with a point, since
//!   without one it is counted in least input increments); a `P` with a
//!   point is seconds (Haas `P1.5`; the program shows the control takes
//!   it) and is copied; a `P` without one, or no G4 at all, gives
//!   `P<integer milliseconds>` — the form Fanuc (`P` takes no decimal
//!   point; `G04 P0.1` is an alarm or 0.1 ms) and Haas (no point:
//!   milliseconds) both read as meant. Under `dwellP: 'milliseconds'` a
//!   `P` is always whole milliseconds.
//!
//! The G word is the program's own first G4 (`G04`, `g4`) when it has
//! one. What the reader cannot tell: a Grbl program with a `G4 P3` meant
//! as 3 s (the reader warns that it reads 3 ms); there `dwellP` says it.

use super::program::{DwellP, Program};
use super::Block;

/// The time word of a dwell the writer inserts (see the module header).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DwellTime {
    /// `X` or `U` (the letter) in seconds with a decimal point.
    Seconds(char),
    /// `P` in seconds with a decimal point.
    SecondsP,
    /// `P` in whole milliseconds, without a point.
    MillisecondsP,
}

/// How a dwell the writer inserts is spelled.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DwellForm {
    /// The number of the program's own first G4 word (`04`, `4`), when it
    /// has one.
    pub g: Option<String>,
    /// The time word.
    pub time: DwellTime,
    /// True when nothing in the program or the options says how its
    /// control reads a dwell's P (no LinuxCNC-only word, no dwell of its
    /// own with X, U or a P with a point, `dwellP` 'auto'): the writer then
    /// takes the Fanuc/Haas reading, P in milliseconds, which a LinuxCNC or
    /// Grbl control reads as seconds (1000 × longer). The caller says so.
    pub guessed: bool,
}

/// The first word or comment of `blocks` that only LinuxCNC writes: its
/// line and what it is.
///
/// # Examples
/// ```
/// use mtmotion::nc::{dialect::linuxcnc_sign, lex};
/// let b = lex("G21\nG64 P0.01\nG1 X1 F100").unwrap();
/// assert_eq!(linuxcnc_sign(&b), Some((2, "G64 P (path blending)".to_string())));
/// assert_eq!(linuxcnc_sign(&lex("G21 G64\nG4 P2").unwrap()), None);
/// ```
pub fn linuxcnc_sign(blocks: &[Block]) -> Option<(usize, String)> {
    blocks
        .iter()
        .find_map(|b| block_sign(b).map(|s| (b.line, s)))
}

fn block_sign(b: &Block) -> Option<String> {
    if let Some(m) = &b.macro_line {
        if matches!(m.stmt, super::macro_line::Stmt::O(..)) {
            return Some("an o-word".into());
        }
        if m.src.contains("#<") {
            return Some("a #<named> parameter".into());
        }
    }
    if let Some(w) = b.words.iter().find(|w| matches!(w.letter, '@' | '^')) {
        return Some(format!("the polar word {}", w.letter));
    }
    let g = |code: i64| {
        b.words
            .iter()
            .any(|w| w.letter == 'G' && (w.value * 10.0).round() as i64 == code)
    };
    if g(640) && (b.word('P').is_some() || b.word('Q').is_some()) {
        return Some("G64 P (path blending)".into());
    }
    for (code, name) in [(411, "G41.1"), (421, "G42.1"), (331, "G33.1")] {
        if g(code) {
            return Some(name.into());
        }
    }
    b.comments.iter().find_map(|c| {
        let c = c.trim_start().to_ascii_uppercase();
        [
            "MSG,",
            "DEBUG,",
            "PRINT,",
            "LOGOPEN,",
            "LOGAPPEND,",
            "LOG,",
            "PROBEOPEN",
        ]
        .iter()
        .find(|k| c.starts_with(*k))
        .map(|k| format!("a ({k} comment"))
    })
}

/// The form of a dwell the writer inserts into `program` (see the module
/// header).
///
/// # Examples
/// ```
/// use mtmotion::nc::{dialect::{dwell_form, DwellTime}, program::parse};
/// let t = |src: &str| dwell_form(&parse(src).unwrap()).time;
/// assert_eq!(t("G0 X0\nG1 X1 F100"), DwellTime::MillisecondsP);
/// assert_eq!(t("G0 X0\nG04 X0.5\nG1 X1 F100"), DwellTime::Seconds('X'));
/// assert_eq!(t("G0 X0\nG64 P0.01\nG1 X1 F100"), DwellTime::SecondsP);
/// // nothing says how P is read: milliseconds, and said to be a guess
/// assert!(dwell_form(&parse("G0 X0\nG1 X1 F100").unwrap()).guessed);
/// assert!(!dwell_form(&parse("G0 X0\nG04 X0.5\nG1 X1 F100").unwrap()).guessed);
/// ```
pub fn dwell_form(program: &Program) -> DwellForm {
    let first = program.blocks.iter().find_map(|b| {
        let g = b.words.iter().find(|w| w.letter == 'G' && w.value == 4.0)?;
        let t = b
            .words
            .iter()
            .find(|w| matches!(w.letter, 'P' | 'X' | 'U'))?;
        Some((g.text.to_string(), t.letter, t.text.contains('.')))
    });
    let g = first.as_ref().map(|(text, ..)| text.clone());
    let linuxcnc =
        program.options.dwell_p == DwellP::Seconds || linuxcnc_sign(&program.blocks).is_some();
    let mut guessed = false;
    let time = if linuxcnc {
        DwellTime::SecondsP
    } else {
        match first {
            Some((_, l @ ('X' | 'U'), _)) => DwellTime::Seconds(l),
            Some((_, 'P', true)) if program.options.dwell_p == DwellP::Auto => DwellTime::SecondsP,
            _ => {
                guessed = program.options.dwell_p == DwellP::Auto;
                DwellTime::MillisecondsP
            }
        }
    };
    DwellForm { g, time, guessed }
}

/// Letter runs (at the start of a multi-letter word) that only Siemens
/// Sinumerik programs use.
pub fn is_siemens_word(run: &str) -> bool {
    [
        "CYCLE",
        "MCALL",
        "GOTOF",
        "GOTOB",
        "GOTOC",
        "ATRANS",
        "TRANS",
        "AROT",
        "ROT",
        "ASCALE",
        "SCALE",
        "AMIRROR",
        "MIRROR",
        "TRAORI",
        "TRAFOOF",
        "SUPA",
        "DIAMON",
        "DIAMOF",
        "CFTCP",
        "BRISK",
        "SOFT",
        "POCKET",
        "SLOT",
        "LONGHOLE",
        "HOLES",
        "REPEAT",
        "PROC",
        "DEF",
        "ENDLOOP",
        "LOOP",
        "STOPRE",
        "WORKPIECE",
    ]
    .iter()
    .any(|k| run.starts_with(k))
}

/// The refusal of a Siemens Sinumerik program.
pub fn siemens_message(found: &str) -> String {
    format!(
        "'{found}': this looks like a Siemens Sinumerik program (CYCLE… calls, MCALL, GOTOF, TRANS/ROT frames); mtmotion reads ISO/Fanuc, Haas and LinuxCNC programs: post the part for a Fanuc-compatible control"
    )
}

/// A Heidenhain conversational line: a block number, then `BEGIN PGM`,
/// `END PGM`, `BLK FORM`, `TOOL CALL` or `CYCL DEF`. The refusal, or
/// `None`.
pub fn heidenhain_line(line: &str) -> Option<String> {
    let t = line.trim_start();
    let rest = t.trim_start_matches(|c: char| c.is_ascii_digit());
    if rest.len() == t.len() || !rest.starts_with(' ') {
        return None;
    }
    let rest = rest.trim_start().to_ascii_uppercase();
    ["BEGIN PGM", "END PGM", "BLK FORM", "TOOL CALL", "CYCL DEF"]
        .iter()
        .find(|k| rest.starts_with(*k))
        .map(|k| {
            format!(
                "'{k}': this looks like a Heidenhain conversational (Klartext) program; mtmotion reads ISO/Fanuc, Haas and LinuxCNC programs: post the part in ISO G-code (Heidenhain controls read ISO programs too)"
            )
        })
}

/// The refusal of a decimal comma between the digits of `chars` at `at`
/// (the comma), or `None` when it is not one.
pub fn decimal_comma(chars: &[char], at: usize) -> Option<String> {
    let digit = |k: Option<usize>| {
        k.and_then(|k| chars.get(k))
            .is_some_and(char::is_ascii_digit)
    };
    if !(digit(at.checked_sub(1)) && digit(Some(at + 1))) {
        return None;
    }
    let start = chars[..at]
        .iter()
        .rposition(|c| c.is_ascii_alphabetic())
        .unwrap_or(at);
    let end = (at + 1..chars.len())
        .find(|&k| !chars[k].is_ascii_digit())
        .unwrap_or(chars.len());
    let found: String = chars[start..end].iter().collect();
    Some(format!(
        "'{found}': a decimal comma; NC programs use a decimal point ('{}')",
        found.replace(',', ".")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dialects_are_recognised_and_iso_lines_are_not() {
        assert!(is_siemens_word("CYCLE") && is_siemens_word("MCALL") && !is_siemens_word("IF"));
        assert!(heidenhain_line("0 BEGIN PGM TEST MM").is_some());
        assert!(heidenhain_line("  12 tool call 1 Z S3000").is_some());
        for iso in ["N10 G0 X1", "10 G0 X1", "BEGIN PGM", "0BEGIN PGM", ""] {
            assert!(heidenhain_line(iso).is_none(), "{iso}");
        }
        let c = |s: &str| decimal_comma(&s.chars().collect::<Vec<_>>(), s.find(',').unwrap());
        assert_eq!(
            c("G1 X1,5 Y2").as_deref(),
            Some("'X1,5': a decimal comma; NC programs use a decimal point ('X1.5')")
        );
        assert!(c("G1 X1 ,R2").is_none() && c("G1 X1,R2").is_none());
    }
}
