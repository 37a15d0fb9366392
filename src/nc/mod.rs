//! NC program lexer (ISO 6983 / RS-274 word-address format), shared by the
//! tool-path model ([`crate::toolpath`]) and the 5-axis compensation
//! ([`crate::compensate::nc5`]).
//!
//! It turns text into [`Block`]s of [`Word`]s (a letter and a number) and
//! keeps everything a writer needs to give the program back: the number as
//! written, comments in `( )` and after `;`, block delete `/`, and `%`
//! program delimiters. Interpretation (modes, arcs, feeds) belongs to the
//! consumer. Why not the `gcode` crate: we need the number text preserved for
//! round-trip writing, 1-based line *and* column on every error, and `;`
//! comments as written by FANUC and Heidenhain-ISO posts.
//!
//! Lines and columns are 1-based; a column counts characters, not bytes.
//!
//! [`program`] interprets the blocks (modes, arcs, feeds, dwells) into motion
//! segments; [`writer`] writes segments back as NC text.

pub mod arc;
pub mod program;
pub mod segment;
pub mod writer;

/// An error that names the line and column and says what was expected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("line {line}, column {column}: {message}")]
pub struct NcError {
    /// 1-based line number.
    pub line: usize,
    /// 1-based column (characters).
    pub column: usize,
    /// What was found and what was expected.
    pub message: String,
}

impl NcError {
    /// An error at `line`, `column`.
    pub fn new(line: usize, column: usize, message: impl Into<String>) -> Self {
        Self {
            line,
            column,
            message: message.into(),
        }
    }
}

/// One address word, e.g. `X-12.5`.
#[derive(Debug, Clone, PartialEq)]
pub struct Word {
    /// Upper-case address letter.
    pub letter: char,
    /// Numeric value.
    pub value: f64,
    /// The number exactly as written (for round-trip output).
    pub text: String,
    /// 1-based column of the letter.
    pub column: usize,
}

/// One line of the program.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Block {
    /// 1-based line number in the source text.
    pub line: usize,
    /// The words, in order.
    pub words: Vec<Word>,
    /// Comments, without their delimiters, in order.
    pub comments: Vec<String>,
    /// The line starts with `/` (optional block skip).
    pub block_delete: bool,
    /// The line is a `%` program delimiter.
    pub percent: bool,
}

impl Block {
    /// The first word with `letter`, if any.
    pub fn word(&self, letter: char) -> Option<&Word> {
        self.words.iter().find(|w| w.letter == letter)
    }

    /// All words with `letter`.
    pub fn words_of(&self, letter: char) -> impl Iterator<Item = &Word> {
        self.words.iter().filter(move |w| w.letter == letter)
    }

    /// True when the line has nothing but whitespace.
    pub fn is_empty(&self) -> bool {
        self.words.is_empty() && self.comments.is_empty() && !self.percent && !self.block_delete
    }

    /// Writes the block back in canonical form: words separated by one
    /// space, numbers as written, comments in `( )`.
    ///
    /// # Examples
    /// ```
    /// let b = &mtmotion::nc::lex("N10 G01 X-1.50 F2000 (cut)").unwrap()[0];
    /// assert_eq!(b.write(), "N10 G01 X-1.50 F2000 (cut)");
    /// ```
    pub fn write(&self) -> String {
        let mut parts: Vec<String> = Vec::new();
        if self.percent {
            parts.push("%".into());
        }
        let mut s = String::from(if self.block_delete { "/" } else { "" });
        let words: Vec<String> = self
            .words
            .iter()
            .map(|w| format!("{}{}", w.letter, w.text))
            .collect();
        s.push_str(&words.join(" "));
        if !s.is_empty() {
            parts.push(s);
        }
        for c in &self.comments {
            parts.push(format!("({c})"));
        }
        parts.join(" ")
    }
}

/// Lexes a whole program.
///
/// # Errors
/// A letter without a number, a number without a letter, an unclosed `(`,
/// a macro `#` expression, or a character that is no part of a word; each
/// names its line and column.
///
/// # Examples
/// ```
/// let blocks = mtmotion::nc::lex("G90 G17\nG02 X10 Y0 R5. F1000 ; arc").unwrap();
/// assert_eq!(blocks[1].word('R').unwrap().value, 5.0);
/// assert_eq!(blocks[1].comments, vec!["arc".to_string()]);
/// let e = mtmotion::nc::lex("G01 X").unwrap_err();
/// assert_eq!((e.line, e.column), (1, 5));
/// ```
pub fn lex(text: &str) -> Result<Vec<Block>, NcError> {
    text.lines()
        .enumerate()
        .map(|(i, l)| lex_line(l, i + 1))
        .collect()
}

/// Lexes one line; `line` is its 1-based number.
pub fn lex_line(src: &str, line: usize) -> Result<Block, NcError> {
    let chars: Vec<char> = src.chars().collect();
    let mut block = Block {
        line,
        ..Block::default()
    };
    let mut i = 0;
    let skip_ws = |i: &mut usize| {
        while *i < chars.len() && chars[*i].is_whitespace() {
            *i += 1;
        }
    };
    skip_ws(&mut i);
    if i < chars.len() && chars[i] == '%' {
        block.percent = true;
        i += 1;
    } else if i < chars.len() && chars[i] == '/' {
        block.block_delete = true;
        i += 1;
    }
    while i < chars.len() {
        let c = chars[i];
        let col = i + 1;
        if c.is_whitespace() {
            i += 1;
        } else if c == '(' {
            let start = i + 1;
            let end = chars[start..]
                .iter()
                .position(|&ch| ch == ')')
                .ok_or_else(|| {
                    NcError::new(line, col, "comment opened with '(' is not closed with ')'")
                })?;
            block.comments.push(
                chars[start..start + end]
                    .iter()
                    .collect::<String>()
                    .trim()
                    .to_string(),
            );
            i = start + end + 1;
        } else if c == ';' {
            block
                .comments
                .push(chars[i + 1..].iter().collect::<String>().trim().to_string());
            break;
        } else if c.is_ascii_alphabetic() {
            let letter = c.to_ascii_uppercase();
            i += 1;
            skip_ws(&mut i);
            let start = i;
            if i < chars.len() && (chars[i] == '+' || chars[i] == '-') {
                i += 1;
            }
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            let text: String = chars[start..i].iter().collect();
            if i < chars.len() && chars[i] == '#' {
                return Err(NcError::new(
                    line,
                    i + 1,
                    "macro variables ('#') are not supported; expand the macro in the post-processor",
                ));
            }
            if text.is_empty() || text == "+" || text == "-" {
                return Err(NcError::new(
                    line,
                    col,
                    format!("expected a number after address '{letter}'"),
                ));
            }
            let value: f64 = text.parse().map_err(|_| {
                NcError::new(
                    line,
                    start + 1,
                    format!("'{text}' after address '{letter}' is not a valid number"),
                )
            })?;
            block.words.push(Word {
                letter,
                value,
                text,
                column: col,
            });
        } else if c == '#' {
            return Err(NcError::new(
                line,
                col,
                "macro variables ('#') are not supported; expand the macro in the post-processor",
            ));
        } else if c.is_ascii_digit() || c == '.' || c == '-' || c == '+' {
            return Err(NcError::new(
                line,
                col,
                format!("number '{c}…' has no address letter; expected a word such as X{c}"),
            ));
        } else if c == '%' {
            i += 1;
        } else {
            return Err(NcError::new(
                line,
                col,
                format!("unexpected character '{c}'; expected an address word, '(' or ';'"),
            ));
        }
    }
    Ok(block)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_comments_and_columns() {
        let b = lex_line("/N20 g2 x1. y-.5 i+2 (ARC 1) ; tail", 7).unwrap();
        assert!(b.block_delete);
        let letters: String = b.words.iter().map(|w| w.letter).collect();
        assert_eq!(letters, "NGXYI");
        assert_eq!(b.word('Y').unwrap().value, -0.5);
        assert_eq!(b.word('X').unwrap().column, 9);
        assert_eq!(b.comments, vec!["ARC 1", "tail"]);
    }

    #[test]
    fn errors_name_line_and_column() {
        let e = lex("G1 X1\nG1 X1..2").unwrap_err();
        assert_eq!((e.line, e.column), (2, 5));
        assert!(e.message.contains("not a valid number"));
        let e = lex("G1 (open").unwrap_err();
        assert_eq!((e.line, e.column), (1, 4));
        let e = lex("G1 X#1").unwrap_err();
        assert!(e.message.contains("macro"));
        let e = lex("G1 5").unwrap_err();
        assert_eq!(e.column, 4);
        let e = lex("G1 X1 @").unwrap_err();
        assert!(e.message.contains("unexpected character '@'"));
    }

    #[test]
    fn write_round_trips_canonical_text() {
        for src in ["%", "N10 G90 G17 (setup)", "/G01 X1.000 Y-2 F2000", ""] {
            assert_eq!(lex_line(src, 1).unwrap().write(), src);
        }
    }
}
