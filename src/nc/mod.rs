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
mod block;
pub mod block_modes;
pub mod corner;
pub mod cutter;
pub mod cutter_path;
pub mod cycles;
pub mod dialect;
mod fadal;
pub mod files;
mod gcodes;
pub mod macro_exec;
pub mod macro_expr;
pub mod macro_line;
pub mod macro_vars;
pub mod modal_call;
mod moves;
mod non_modal;
pub mod num_style;
pub mod num_text;
pub mod nurbs;
pub mod patch;
pub mod polar;
pub mod program;
pub mod rotation;
mod run;
pub mod segment;
pub mod sequence;
pub mod spline;
pub mod stream;
pub mod summary;
pub mod units;
pub mod writer;

/// An error that names the line and column and says what was expected.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize)]
#[error("{}line {line}, column {column}: {message}", .file.as_ref().map(|f| format!("file {f}, ")).unwrap_or_default())]
pub struct NcError {
    /// 1-based line number.
    pub line: usize,
    /// 1-based column (characters).
    pub column: usize,
    /// What was found and what was expected.
    pub message: String,
    /// The file, when the line is in one of the extra files given to
    /// [`program::parse_files`] (none: the main program).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
}

impl NcError {
    /// An error at `line`, `column`.
    pub fn new(line: usize, column: usize, message: impl Into<String>) -> Self {
        Self {
            line,
            column,
            message: message.into(),
            file: None,
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
    pub text: num_text::NumText,
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
    /// Fanuc corner words written with a leading comma (`,R2.`, `,C1.`),
    /// letter `R` or `C`.
    pub comma_words: Vec<Word>,
    /// A named program `O<NAME>`, or a bare program name (`OCIRCLE`,
    /// `O7997A`, see [`Block::program_name_bare`]).
    pub program_name: Option<String>,
    /// The program name was written without brackets, as Mitsubishi and
    /// Fanuc 30i-series file names are (`OCIRCLE(CIRCLE)`); [`Block::write`]
    /// keeps that form.
    pub program_name_bare: bool,
    /// A macro statement (Fanuc Macro B or LinuxCNC o-word code); its
    /// `words` then hold only a literal `N` number.
    pub macro_line: Option<Box<macro_line::MacroLine>>,
    /// Index of the file the block came from (0: the main program; see
    /// [`program::parse_files`]).
    pub file: usize,
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
        self.words.is_empty()
            && self.comments.is_empty()
            && self.comma_words.is_empty()
            && self.program_name.is_none()
            && self.macro_line.is_none()
            && !self.percent
            && !self.block_delete
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
        if let Some(m) = &self.macro_line {
            return m.src.clone();
        }
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
        if let Some(n) = &self.program_name {
            if !s.is_empty() && !s.ends_with('/') {
                s.push(' ');
            }
            s.push_str(&if self.program_name_bare {
                format!("O{n}")
            } else {
                format!("O<{n}>")
            });
        }
        for w in &self.comma_words {
            s.push_str(&format!(",{}{}", w.letter, w.text));
        }
        if !s.is_empty() {
            parts.push(s);
        }
        for c in &self.comments {
            parts.push(format!("({c})"));
        }
        parts.join(" ")
    }
}

/// Every error of a program, in source order, up to [`MAX_ERRORS`].
#[derive(Debug, Clone, Default, PartialEq, thiserror::Error)]
pub struct NcErrors {
    /// The errors found (at most [`MAX_ERRORS`]).
    pub errors: Vec<NcError>,
    /// True when more errors were found than are listed.
    pub truncated: bool,
}

/// Longest number an address word may have, characters (sign and point
/// included): controls read about 12 significant digits.
pub const MAX_NUMBER_CHARS: usize = 24;

/// How many errors a program reports at most.
pub const MAX_ERRORS: usize = 100;

impl NcErrors {
    /// The first error (there is always one).
    pub fn first(&self) -> NcError {
        self.errors
            .first()
            .cloned()
            .unwrap_or_else(|| NcError::new(1, 1, "unknown error"))
    }

    /// Appends `e` unless the cap is reached or the same error (line,
    /// column, message) is already listed (a block run many times by a
    /// loop or a subprogram reports its error once).
    pub fn push(&mut self, e: NcError) {
        if self.errors.contains(&e) {
            return;
        }
        if self.errors.len() < MAX_ERRORS {
            self.errors.push(e);
        } else {
            self.truncated = true;
        }
    }

    /// True when no error was recorded.
    pub fn is_empty(&self) -> bool {
        self.errors.is_empty()
    }
}

impl std::fmt::Display for NcErrors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = self.errors.len();
        if n == 1 && !self.truncated {
            return write!(f, "{}", self.errors[0]);
        }
        write!(
            f,
            "{n}{} error{} in the program:",
            if self.truncated { "+" } else { "" },
            if n == 1 { "" } else { "s" }
        )?;
        for e in &self.errors {
            write!(f, "\n{e}")?;
        }
        if self.truncated {
            write!(f, "\n(only the first {MAX_ERRORS} are listed)")?;
        }
        Ok(())
    }
}

impl From<NcError> for NcErrors {
    fn from(e: NcError) -> Self {
        Self {
            errors: vec![e],
            truncated: false,
        }
    }
}

/// Splits program text into lines: a UTF-8 byte-order mark is dropped,
/// line ends may be LF, CRLF or CR alone (old Macintosh/DNC files), and
/// trailing Ctrl-Z characters (U+001A, the DOS end-of-file mark some DNC
/// senders append) after the last line are dropped.
pub fn split_lines(text: &str) -> Vec<&str> {
    crate::trace::split_lines(text)
}

/// Lexes a whole program; the first error only (see [`lex_all`]).
///
/// # Errors
/// A letter without a number, a number without a letter, an unclosed `(`,
/// a macro `#` expression, a control character, or a character that is no
/// part of a word; each names its line and column.
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
    let (blocks, errors) = lex_all(text);
    match errors.errors.first() {
        Some(e) => Err(e.clone()),
        None => Ok(blocks),
    }
}

/// Lexes a whole program and collects every line's error (one per line,
/// up to [`MAX_ERRORS`]); a line with an error gives an empty block.
/// A text over the budget ([`crate::budget::check_texts`]: its bytes and
/// lines) or a binary file ([`crate::trace::binary_kind`]: an image, a PDF,
/// an archive) gives no blocks and one error at line 1, column 1, before
/// any work is done ([`unreadable`]); the words are counted as they are
/// lexed, and the line that takes them past [`crate::budget::MAX_NC_WORDS`]
/// stops the lexing with an error there.
pub fn lex_all(text: &str) -> (Vec<Block>, NcErrors) {
    let mut words = 0;
    lex_counting(text, &mut words)
}

/// As [`lex_all`], adding the words lexed to `words` (the count of the
/// texts lexed before, which share the budget).
pub(crate) fn lex_counting(text: &str, words: &mut usize) -> (Vec<Block>, NcErrors) {
    let (blocks, errors, _) = lex_noting_refusal(text, words);
    (blocks, errors)
}

/// As [`lex_counting`], and whether `text` was refused as a whole
/// ([`unreadable`]: its one error is then at line 1, column 1).
pub(crate) fn lex_noting_refusal(text: &str, words: &mut usize) -> (Vec<Block>, NcErrors, bool) {
    let mut errors = NcErrors {
        errors: Vec::new(),
        truncated: false,
    };
    if let Some(why) = unreadable(text) {
        errors.push(NcError::new(1, 1, why));
        return (Vec::new(), errors, true);
    }
    let lines = split_lines(text);
    let mut blocks = Vec::with_capacity(lines.len());
    if lex_lines(lines, 1, words, &mut blocks, &mut errors).is_err() {
        return (Vec::new(), errors, false);
    }
    (blocks, errors, false)
}

/// The word budget stopped the lexing (its error is in the list).
#[derive(Debug)]
pub(crate) struct WordsOverBudget;

/// Lexes `lines`, the first numbered `first`, appending a block to
/// `blocks` for each (an empty one for a line with an error, which goes to
/// `errors`) and adding their words to `words`: the lexing of
/// [`lex_counting`], and of the NC stream ([`stream`]) run by run of
/// complete lines. A line whose letters could take the words past
/// [`crate::budget::MAX_NC_WORDS`] stops it, unlexed, with its error.
pub(crate) fn lex_lines<'a>(
    lines: impl IntoIterator<Item = &'a str>,
    first: usize,
    words: &mut usize,
    blocks: &mut Vec<Block>,
    errors: &mut NcErrors,
) -> Result<(), WordsOverBudget> {
    for (i, l) in lines.into_iter().enumerate() {
        let line = first + i;
        // Every word starts with a letter: a line whose letters could take
        // the words past the budget is refused before it is lexed (one
        // 64 MiB line of `X1X1…` would be 32 M words, 1.5 GB).
        let letters = l.bytes().filter(u8::is_ascii_alphabetic).count();
        if *words + letters > crate::budget::MAX_NC_WORDS {
            let e = crate::budget::BudgetError {
                what: "program",
                amount: (*words + letters) as u64,
                limit: crate::budget::MAX_NC_WORDS,
                unit: "address words by this line (its own counted by their letters)",
                advice: "each word is held in memory while the program runs; split the program into parts and run each",
            };
            errors.push(NcError::new(line, 1, e.to_string()));
            return Err(WordsOverBudget);
        }
        let b = lex_line(l, line).unwrap_or_else(|e| {
            errors.push(e);
            Block {
                line,
                ..Block::default()
            }
        });
        *words += b.words.len() + b.comma_words.len();
        blocks.push(b);
    }
    Ok(())
}

/// Why `text` is refused as a whole before any line is read, if it is: over
/// the text budget ([`crate::budget::check_texts`]: bytes and lines), or a binary file
/// ([`crate::trace::binary_kind`]: a PNG dropped on the program gave 100+
/// errors on its bytes; now one error says what the file is).
pub fn unreadable(text: &str) -> Option<String> {
    if let Err(e) = crate::budget::check_texts("program", [text]) {
        return Some(e.to_string());
    }
    crate::trace::binary_kind(text).map(not_text_message)
}

/// The refusal of a file that is `kind` (an image, a PDF, an archive; see
/// [`crate::trace::binary_kind`]), not program text.
pub(crate) fn not_text_message(kind: &str) -> String {
    format!("this file is {kind}, not an NC program (a text file): nothing was read")
}

/// Fanuc Macro B keywords: a letter run equal to one of these is a macro
/// statement, not an address word.
const MACRO_B: [&str; 26] = [
    "IF", "GOTO", "THEN", "WHILE", "DO", "END", "EQ", "NE", "GT", "GE", "LT", "LE", "AND", "OR",
    "XOR", "SIN", "COS", "TAN", "ATAN", "SQRT", "ABS", "ROUND", "FIX", "FUP", "BIN", "BCD",
];
/// LinuxCNC o-word keywords (the lexer's and the macro reader's).
pub(crate) const O_WORDS: [&str; 15] = [
    "SUB",
    "ENDSUB",
    "CALL",
    "IF",
    "ELSEIF",
    "ELSE",
    "ENDIF",
    "WHILE",
    "ENDWHILE",
    "DO",
    "REPEAT",
    "ENDREPEAT",
    "RETURN",
    "BREAK",
    "CONTINUE",
];

fn control_char(c: char) -> bool {
    c.is_control() && c != '\t'
}

/// The index of the first control character outside comments: one inside
/// `( … )` or after `;` or `//` (a C1 character of a Windows-1252 comment,
/// `(Ø 10 mm)` read as Latin-1) is the comment's and never refuses the
/// program.
fn control_outside_comments(chars: &[char]) -> Option<usize> {
    let mut depth = 0usize;
    for (k, &c) in chars.iter().enumerate() {
        match c {
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            ';' if depth == 0 => return None,
            '/' if depth == 0 && chars.get(k + 1) == Some(&'/') => return None,
            _ if depth == 0 && control_char(c) => return Some(k),
            _ => {}
        }
    }
    None
}

/// Lexes one line; `line` is its 1-based number.
///
/// Comments: `( … )` may nest (`(DRILL (5 HOLES))` is one comment; a stray
/// `(` inside one, `(X1+.25(move up)`, ends at the first `)` as on a Fanuc
/// control) and `;` runs to the end of the line. A bare program name
/// alone on its line (`OCIRCLE(CIRCLE)`, `O7997A`) sets
/// [`Block::program_name`]. A Fanuc `:0097` program number is read as
/// `O0097`; a named program `O<NAME>` sets [`Block::program_name`]. Fanuc
/// `,R` / `,C` (corner rounding / chamfer on G01) are kept in
/// [`Block::comma_words`]. An Okuma OSP file header (`$OKUMA.SSB%`, see
/// [`macro_expr::okuma_file_header`]) is refused as an Okuma program.
pub fn lex_line(src: &str, line: usize) -> Result<Block, NcError> {
    let chars: Vec<char> = src.chars().collect();
    let control = control_outside_comments(&chars);
    if macro_line::is_macro_line(src) && control.is_none() {
        return macro_line::lex_macro(src, line);
    }
    let mut block = Block {
        line,
        ..Block::default()
    };
    if let Some(i) = control {
        return Err(NcError::new(
            line,
            i + 1,
            format!(
                "control character U+{:04X} is not allowed in an NC program; remove it (only tab, line ends and a final Ctrl-Z are accepted)",
                chars[i] as u32
            ),
        ));
    }
    let mut i = skip_ws(&chars, 0);
    if let Some(header) = macro_expr::okuma_file_header(src) {
        return Err(NcError::new(line, i + 1, macro_expr::okuma_message(header)));
    }
    if let Some(m) = dialect::heidenhain_line(src) {
        return Err(NcError::new(line, i + 1, m));
    }
    if i < chars.len() && chars[i] == '%' {
        block.percent = true;
        i += 1;
        // Text after `%` on its line (a program title, `% MillMaster`) is
        // no block: kept as a comment.
        let rest: String = chars[i..].iter().collect();
        let rest = rest
            .trim()
            .trim_start_matches(['(', ';'])
            .trim_end_matches(')');
        if !rest.trim().is_empty() {
            block.comments.push(rest.trim().to_string());
        }
        return Ok(block);
    } else if i < chars.len() && chars[i] == '/' && chars.get(i + 1) != Some(&'/') {
        block.block_delete = true;
        i += 1;
    }
    i = skip_ws(&chars, i);
    if i < chars.len() && chars[i] == ':' {
        lex_colon_number(&chars, &mut i, line, &mut block)?;
    } else if let Some(end) = bare_program_name(&chars, i) {
        block.program_name = Some(chars[i + 1..end].iter().collect());
        block.program_name_bare = true;
        i = end;
    }
    while i < chars.len() {
        if !lex_item(&chars, &mut i, line, &mut block)? {
            break;
        }
    }
    Ok(block)
}

/// The index of the first non-whitespace character at or after `i`.
fn skip_ws(chars: &[char], mut i: usize) -> usize {
    while i < chars.len() && chars[i].is_whitespace() {
        i += 1;
    }
    i
}

/// The end of the run of ASCII letters starting at `i`.
fn letters_end(chars: &[char], mut i: usize) -> usize {
    while i < chars.len() && chars[i].is_ascii_alphabetic() {
        i += 1;
    }
    i
}

/// The letters after `i` (whitespace skipped), upper-cased, with the
/// index of their first letter; `None` when no letter follows.
fn keyword_after(chars: &[char], i: usize) -> Option<(usize, String)> {
    let k = skip_ws(chars, i);
    let e = letters_end(chars, k);
    (e > k).then(|| {
        (
            k,
            chars[k..e].iter().collect::<String>().to_ascii_uppercase(),
        )
    })
}

/// The end of a bare program name at `chars[i]` (the `O`): `OCIRCLE` or
/// `O7997A` alone on its line (only a comment may follow), as Mitsubishi
/// and Fanuc 30i-series controls name programs. The name is a letter then
/// letters, digits or `_`, or digits then letters; a LinuxCNC o-word
/// keyword (`o100sub`) and anything else (`O1000M30`) is not a name.
fn bare_program_name(chars: &[char], i: usize) -> Option<usize> {
    if !matches!(chars.get(i), Some('O' | 'o')) {
        return None;
    }
    let start = i + 1;
    let mut end = start;
    while end < chars.len() && (chars[end].is_ascii_alphanumeric() || chars[end] == '_') {
        end += 1;
    }
    let name: String = chars[start..end].iter().collect();
    let digits = name.chars().take_while(char::is_ascii_digit).count();
    let tail = &name[digits..];
    let named = match name.chars().next() {
        Some(c) if c.is_ascii_alphabetic() || c == '_' => true,
        Some(_) => !tail.is_empty() && tail.chars().all(|c| c.is_ascii_alphabetic() || c == '_'),
        None => false,
    };
    let rest = skip_ws(chars, end);
    let alone = rest == chars.len() || matches!(chars[rest], '(' | ';');
    let keyword = O_WORDS.contains(&tail.to_ascii_uppercase().as_str());
    (named && alone && !keyword).then_some(end)
}

/// A Fanuc `:0097` program number at `chars[*i]` (the colon), read as the
/// word `O0097`.
fn lex_colon_number(
    chars: &[char],
    i: &mut usize,
    line: usize,
    block: &mut Block,
) -> Result<(), NcError> {
    let col = *i + 1;
    *i += 1;
    let start = *i;
    while *i < chars.len() && chars[*i].is_ascii_digit() {
        *i += 1;
    }
    let text: String = chars[start..*i].iter().collect();
    let value = text.parse().map_err(|_| {
        NcError::new(
            line,
            col,
            "':' starts a program number; expected digits such as ':0097'",
        )
    })?;
    block.words.push(Word {
        letter: 'O',
        value,
        text: text.into(),
        column: col,
    });
    Ok(())
}

/// Lexes what starts at `chars[*i]`: whitespace, a comment, a corner word
/// or an address word, and advances `*i` past it. False after a `;`
/// comment (the rest of the line).
fn lex_item(
    chars: &[char],
    i: &mut usize,
    line: usize,
    block: &mut Block,
) -> Result<bool, NcError> {
    let c = chars[*i];
    let col = *i + 1;
    if c.is_whitespace() || c == '%' {
        *i += 1;
    } else if c == '(' {
        lex_comment(chars, i, line, block)?;
    } else if c == ')' {
        return Err(NcError::new(
            line,
            col,
            "')' without an opening '('; expected a comment as '( … )'",
        ));
    } else if c == ';' || (c == '/' && chars.get(*i + 1) == Some(&'/')) {
        let skip = if c == ';' { 1 } else { 2 };
        block.comments.push(
            chars[*i + skip..]
                .iter()
                .collect::<String>()
                .trim()
                .to_string(),
        );
        return Ok(false);
    } else if c == ',' {
        let letter = chars.get(*i + 1).map(|c| c.to_ascii_uppercase());
        if !matches!(letter, Some('R' | 'C')) {
            let m = dialect::decimal_comma(chars, *i).unwrap_or_else(|| {
                "',' must start a corner word ',R' (rounding) or ',C' (chamfer)".into()
            });
            return Err(NcError::new(line, col, m));
        }
        *i += 1;
        let w = lex_word(chars, i, line)?;
        block.comma_words.push(Word { column: col, ..w });
    } else if c.is_ascii_alphabetic() {
        lex_address(chars, i, line, block)?;
    } else if polar::is_polar(c) {
        let w = lex_word(chars, i, line)?;
        block.words.push(w);
    } else {
        return Err(stray_char_error(c, line, col));
    }
    Ok(true)
}

/// A `( … )` comment at `chars[*i]` (see [`macro_expr::comment`]); `*i`
/// moves past its `)`.
fn lex_comment(
    chars: &[char],
    i: &mut usize,
    line: usize,
    block: &mut Block,
) -> Result<(), NcError> {
    let (text, next) = macro_expr::comment(chars, *i).ok_or_else(|| {
        NcError::new(
            line,
            *i + 1,
            "comment opened with '(' is not closed with ')'",
        )
    })?;
    block.comments.push(text);
    *i = next;
    Ok(())
}

/// An address word at `chars[*i]` (a letter), or a named program
/// `O<NAME>`. A run of several letters (a keyword) is an error, and so is
/// a LinuxCNC o-word keyword after an `O` number or name.
fn lex_address(
    chars: &[char],
    i: &mut usize,
    line: usize,
    block: &mut Block,
) -> Result<(), NcError> {
    let col = *i + 1;
    let j = letters_end(chars, *i);
    let run: String = chars[*i..j].iter().collect::<String>().to_ascii_uppercase();
    if run.len() > 1 {
        return Err(keyword_error(&run, line, col, block));
    }
    if run == "O" && chars.get(*i + 1) == Some(&'<') {
        let close = chars[*i + 2..]
            .iter()
            .position(|&c| c == '>')
            .ok_or_else(|| NcError::new(line, col, "named program 'O<' is not closed with '>'"))?;
        let name: String = chars[*i + 2..*i + 2 + close].iter().collect();
        *i += close + 3;
        block.program_name = Some(name);
        if let Some((k, kw)) = keyword_after(chars, *i) {
            return Err(keyword_error(&kw, line, k + 1, block));
        }
        return Ok(());
    }
    let w = lex_word(chars, i, line)?;
    if w.letter == 'O' {
        if let Some((k, kw)) = keyword_after(chars, *i) {
            if O_WORDS.contains(&kw.as_str()) {
                block.words.push(w);
                return Err(keyword_error(&kw, line, k + 1, block));
            }
        }
    }
    block.words.push(w);
    Ok(())
}

/// The error for a character that cannot start anything here: a macro
/// `#`/`[`, a number without a letter, or any other character.
fn stray_char_error(c: char, line: usize, col: usize) -> NcError {
    let msg = if c == '#' || c == '[' {
        format!(
            "macro {} ('{c}') is not supported yet; expand the macro in the post-processor (the simulator reads plain word-address programs)",
            if c == '#' { "variable" } else { "expression" }
        )
    } else if c.is_ascii_digit() || c == '.' || c == '-' || c == '+' {
        format!("number '{c}…' has no address letter; expected a word such as X{c}")
    } else {
        format!(
            "unexpected character '{c}' (U+{:04X}); expected an address word, '(' or ';'",
            c as u32
        )
    };
    NcError::new(line, col, msg)
}

fn keyword_error(run: &str, line: usize, col: usize, block: &Block) -> NcError {
    let o_word =
        block.words.last().is_some_and(|w| w.letter == 'O') || block.program_name.is_some();
    if o_word && O_WORDS.contains(&run) {
        NcError::new(
            line,
            col,
            format!(
                "LinuxCNC o-word '{}' (subroutines and control flow) is not supported yet; expand it in the CAM post-processor",
                run.to_ascii_lowercase()
            ),
        )
    } else if macro_expr::is_okuma_word(run) {
        NcError::new(line, col, macro_expr::okuma_message(run))
    } else if dialect::is_siemens_word(run) {
        NcError::new(line, col, dialect::siemens_message(run))
    } else if MACRO_B.contains(&run) {
        NcError::new(
            line,
            col,
            format!(
                "'{run}' is a Fanuc Macro B statement; macros are not supported yet, expand them in the post-processor"
            ),
        )
    } else if let Some(m) = macro_b_abbreviation_message(run) {
        NcError::new(line, col, m)
    } else {
        let letter = run.chars().next().unwrap_or('?');
        NcError::new(
            line,
            col,
            format!("expected a number after address '{letter}', found the letters '{run}'"),
        )
    }
}

/// The Macro B keyword that `run` abbreviates (`WH` → `WHILE`), which
/// the lexer names rather than reads: Fanuc's macro syntax is `WHILE
/// […] DO n`, and its program editor expands `WH`, `GO`, `TH` as they are
/// keyed in; a file that still has them is refused at the abbreviation.
pub(crate) fn macro_b_abbreviation_message(run: &str) -> Option<String> {
    let full = match run {
        "WH" => "WHILE",
        "GO" => "GOTO",
        "TH" => "THEN",
        _ => return None,
    };
    Some(format!(
        "'{run}' reads as {full} abbreviated: a Fanuc control stores and runs the full keyword (its editor expands abbreviations as they are keyed in), so '{run}' is not read as {full} here; write '{full}'"
    ))
}

/// One address word at `chars[*i]` (the letter); advances `*i` past it.
fn lex_word(chars: &[char], i: &mut usize, line: usize) -> Result<Word, NcError> {
    let col = *i + 1;
    let letter = chars[*i].to_ascii_uppercase();
    *i += 1;
    while *i < chars.len() && chars[*i].is_whitespace() {
        *i += 1;
    }
    let start = *i;
    if *i < chars.len() && (chars[*i] == '+' || chars[*i] == '-') {
        *i += 1;
    }
    while *i < chars.len() && (chars[*i].is_ascii_digit() || chars[*i] == '.') {
        *i += 1;
    }
    let text: String = chars[start..*i].iter().collect();
    // E is an address in NC (`F600E41`, `V0.2E41`: the word E41), so only
    // a signed exponent (`X1E-3`) is refused as exponent notation.
    if *i + 1 < chars.len()
        && !text.is_empty()
        && matches!(chars[*i], 'e' | 'E')
        && matches!(chars[*i + 1], '+' | '-')
        && chars.get(*i + 2).is_some_and(char::is_ascii_digit)
    {
        return Err(NcError::new(
            line,
            start + 1,
            format!(
                "'{text}{}…' after address '{letter}': exponent notation is not valid in an NC program; write the number out",
                chars[*i]
            ),
        ));
    }
    if *i < chars.len() && (chars[*i] == '#' || chars[*i] == '[') && text.len() <= 1 {
        return Err(NcError::new(
            line,
            *i + 1,
            format!(
                "macro {} after address '{letter}' is not supported yet; expand the macro in the post-processor",
                if chars[*i] == '#' { "variable" } else { "expression" }
            ),
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
            format!(
                "'{}' after address '{letter}' is not a valid number",
                crate::budget::clip(&text, 24)
            ),
        )
    })?;
    // A control reads at most about 12 digits; a longer number is a
    // corrupted file, and one of 309 digits would be ∞.
    if text.len() > MAX_NUMBER_CHARS || !value.is_finite() {
        return Err(NcError::new(
            line,
            start + 1,
            format!(
                "'{}' after address '{letter}' has {} characters; an NC number has at most {MAX_NUMBER_CHARS}",
                crate::budget::clip(&text, 24),
                text.chars().count()
            ),
        ));
    }
    Ok(Word {
        letter,
        value,
        text: text.into(),
        column: col,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_word_budget_refuses_the_line_that_would_pass_it_before_lexing_it() {
        use crate::budget::MAX_NC_WORDS;
        // One line of MAX_NC_WORDS / 2 + 1 words passes (with the one
        // before it); a line that would take the words past the budget is
        // named, and nothing is lexed for it.
        let half = "X1".repeat(MAX_NC_WORDS / 2 + 1);
        let (blocks, errors) = lex_all(&format!("G0 X0\n{half}"));
        assert!(errors.is_empty(), "{:?}", errors.errors.first());
        assert_eq!(blocks[1].words.len(), MAX_NC_WORDS / 2 + 1);
        let (blocks, errors) = lex_all(&format!("G0 X0\n{half}\nG1 X2 F1\n{half}"));
        assert!(blocks.is_empty());
        let e = &errors.errors[0];
        assert_eq!((e.line, e.column), (4, 1), "{e}");
        let want = format!(
            "program: {} address words by this line (its own counted by their letters), more than the limit of {MAX_NC_WORDS}",
            2 + 2 * (MAX_NC_WORDS / 2 + 1) + 3
        );
        assert!(e.message.starts_with(&want), "{e}");
        // The words of the program and its files share the budget.
        let mut words = MAX_NC_WORDS - 2;
        let (_, errors) = lex_counting("G1 X1", &mut words);
        assert!(errors.is_empty());
        let (_, errors) = lex_counting("Y1", &mut words);
        assert_eq!(errors.errors[0].line, 1);
    }

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
        let b = lex("G1 X#1").unwrap();
        assert!(b[0].macro_line.is_some());
        let e = lex("G1 5").unwrap_err();
        assert_eq!(e.column, 4);
        let e = lex("G1 X1 $").unwrap_err();
        assert!(e.message.contains("unexpected character '$' (U+0024)"));
    }

    #[test]
    fn an_okuma_file_header_is_refused_as_okuma_and_grbl_dollar_lines_are_not() {
        // The first line of an Okuma OSP file (GCodeWorkShop's OSP5020M
        // example starts with `$OKUMA.SSB%`, its lathe one `$FLANGE.MIN%`).
        for (src, col) in [
            ("$BRACKET.SSB%\r\nOMAIN", 1),
            ("  $PLATE.MIN% \nG0 X1", 3),
            ("$O1234-A_2.MIN%", 1),
        ] {
            let e = lex(src).unwrap_err();
            assert_eq!((e.line, e.column), (1, col), "{src}: {e}");
            assert!(
                e.message.contains("this looks like an Okuma OSP program"),
                "{e}"
            );
        }
        // Grbl system commands and a stray `$` keep the plain error.
        for src in ["$H", "$J=G91 X1 F100", "$OKUMA.SSB", "$.MIN%", "$A.LONGX%"] {
            let e = lex(src).unwrap_err();
            assert!(e.message.contains("unexpected character '$'"), "{src}: {e}");
        }
    }

    #[test]
    fn nested_comments_program_numbers_and_line_ends() {
        let b = lex_line("G81 (DRILL (5 HOLES)) X1", 1).unwrap();
        assert_eq!(b.comments, vec!["DRILL (5 HOLES)"]);
        assert_eq!(b.word('X').unwrap().value, 1.0);
        let b = lex_line(":0097 (SUB)", 1).unwrap();
        let o = b.word('O').unwrap();
        assert_eq!((o.value, o.text.as_str(), o.column), (97.0, "0097", 1));
        let b = lex_line("O<FACE_MILL> (named)", 1).unwrap();
        assert_eq!(b.program_name.as_deref(), Some("FACE_MILL"));
        // LF, CRLF and CR alone; BOM; trailing Ctrl-Z.
        for text in [
            "\u{feff}G0 X1\r\nG0 X2\r\n\u{1a}",
            "G0 X1\rG0 X2\r",
            "G0 X1\nG0 X2",
        ] {
            let blocks = lex(text).unwrap();
            assert_eq!(blocks.len(), 2, "{text:?}");
            assert_eq!(blocks[1].word('X').unwrap().value, 2.0);
            assert_eq!(blocks[1].line, 2);
        }
        let b = lex_line("G1 X1 ,R2. Y3", 1).unwrap();
        assert_eq!(b.comma_words[0].letter, 'R');
        assert_eq!(b.comma_words[0].value, 2.0);
        assert_eq!(b.write(), "G1 X1 Y3,R2.");
    }

    #[test]
    fn misleading_messages_are_fixed() {
        // Ctrl-Z inside the text, BEL: named as U+XXXX at their column.
        let e = lex("G0 X1\nG0\u{1a} X2\nG1").unwrap_err();
        assert_eq!((e.line, e.column), (2, 3));
        assert!(e.message.contains("control character U+001A"), "{e}");
        let e = lex("G0 X\u{7}1").unwrap_err();
        assert!(e.message.contains("U+0007"), "{e}");
        // IF [ is a macro statement, not address I; o100 sub an o-word.
        for src in ["IF [#1 GT 5] GOTO 10", "o100 sub"] {
            assert!(lex(src).unwrap()[0].macro_line.is_some(), "{src}");
        }
        let e = lex("IF [#1 GT] GOTO 10").unwrap_err();
        assert_eq!(e.column, 10, "{e}");
        let e = lex("G1 X1 )").unwrap_err();
        assert_eq!(e.column, 7);
    }

    #[test]
    fn every_line_error_is_collected() {
        let (blocks, errors) = lex_all("G1 X\nG0 X1\nG1 (open\nG1 Y1..2");
        assert_eq!(blocks.len(), 4);
        let at: Vec<(usize, usize)> = errors.errors.iter().map(|e| (e.line, e.column)).collect();
        assert_eq!(at, vec![(1, 4), (3, 4), (4, 5)]);
        let many = "G1 X\n".repeat(150);
        let (_, errors) = lex_all(&many);
        assert_eq!(errors.errors.len(), MAX_ERRORS);
        assert!(errors.truncated);
        assert!(errors.to_string().starts_with("100+ errors"));
    }

    #[test]
    fn write_round_trips_canonical_text() {
        for src in ["%", "N10 G90 G17 (setup)", "/G01 X1.000 Y-2 F2000", ""] {
            assert_eq!(lex_line(src, 1).unwrap().write(), src);
        }
    }
}
