//! Programs in other controls' languages, recognised so that they are
//! refused by name instead of at their first unreadable character:
//! Siemens Sinumerik (`CYCLE81(…)`, `MCALL`, `GOTOF`, `TRANS`, …) and
//! Heidenhain conversational (Klartext: `0 BEGIN PGM … MM`, `BLK FORM`,
//! `TOOL CALL`, `CYCL DEF`). A decimal comma (`X1,5`, European number
//! formatting) is named too. Okuma OSP is recognised in
//! [`super::macro_expr`] (its macro words overlap Fanuc Macro B's).

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
