//! Several program files read as one program: the main program plus extra
//! files holding the subprograms (Fanuc `O…` … `M99`, G65 macros) and
//! LinuxCNC subroutines (`o<name> sub` … `endsub`) it calls, as a control
//! keeps them in its memory or subroutine folder.
//!
//! Readings chosen: the extra files are appended after the main program;
//! the run starts at the main program's first line and ends at its end (or
//! at M2/M30), so an extra file's blocks run only when called. Lines of an
//! extra file keep their own numbering; every error and warning in one
//! names the file (`file` field), and its segments carry their line in
//! that file. [`main_file`] picks the main program among dropped files:
//! the first that ends with M2/M30, else the first that is no subprogram
//! (no M99, no o-word `sub`), else the first.

use serde::{Deserialize, Serialize};

use super::macro_line::{OKw, Stmt};
use super::program::{interpret_keeping, Keep, ParseOptions, Program};
use super::{Block, NcError, NcErrors};

/// One extra program file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NcFile {
    /// File name, as shown in messages.
    pub name: String,
    /// Its text.
    pub text: String,
}

/// Parses the main program `text` with the subprogram files `files` and
/// reports every error, each naming its file (none for the main program),
/// line and column.
///
/// # Errors
/// As [`super::program::parse_all`], over all files.
///
/// # Examples
/// ```
/// use mtmotion::nc::files::{parse_files, NcFile};
/// use mtmotion::nc::program::ParseOptions;
/// let sub = NcFile { name: "O2000.nc".into(), text: "O2000\nG91 G1 X5 F100\nG90\nM99".into() };
/// let p = parse_files("G0 X0\nM98 P2000\nG0 X100\nM30", &[sub], &ParseOptions::default()).unwrap();
/// let x: Vec<f64> = p.segments.iter().map(|s| s.end.x).collect();
/// assert_eq!(x, vec![0.0, 5.0, 100.0]);
/// let bad = NcFile { name: "O3000.nc".into(), text: "O3000\nG1 X\nM99".into() };
/// let e = parse_files("M98 P3000", &[bad], &ParseOptions::default()).unwrap_err();
/// assert_eq!(e.errors[0].to_string(), "file O3000.nc, line 2, column 4: expected a number after address 'X'");
/// ```
pub fn parse_files(
    text: &str,
    files: &[NcFile],
    options: &ParseOptions,
) -> Result<Program, NcErrors> {
    parse_files_keeping(text, files, options, Keep::All)
}

/// As [`parse_files`], keeping what `keep` says ([`Keep::Motion`]: the
/// segments and warnings of a program that is simulated or checked, not
/// written back).
///
/// # Errors
/// As [`parse_files`].
pub fn parse_files_keeping(
    text: &str,
    files: &[NcFile],
    options: &ParseOptions,
    keep: Keep,
) -> Result<Program, NcErrors> {
    lex_files(text, files)
        .map_err(|(e, _)| e)?
        .interpret(options, keep)
}

/// As [`parse_files_keeping`], taking the texts and freeing them once they
/// are lexed, before the program runs: a caller that holds its own copy of
/// a large program (the wasm bindings' copy of the JS string) does not
/// hold it beside the segments (59 MB of the 2 M-line program of
/// `bench/node/large-program.bench.mjs`).
///
/// # Errors
/// As [`parse_files`].
pub fn parse_files_owned(
    text: String,
    files: Vec<NcFile>,
    options: &ParseOptions,
    keep: Keep,
) -> Result<Program, NcErrors> {
    parse_files_noting_refusal(text, files, options, keep).0
}

/// As [`parse_files_owned`], and whether the text was refused as a whole,
/// before any line was read (`checkNc`'s `notRead`): its one error says
/// the program, or the program and its files together, are over the text
/// budget ([`crate::budget::check_texts`]), or that the program is no text
/// file (an image, a PDF, an archive; [`super::unreadable`]).
///
/// # Examples
/// ```
/// use mtmotion::nc::files::parse_files_noting_refusal;
/// use mtmotion::nc::program::{Keep, ParseOptions};
/// let o = ParseOptions::default();
/// let png = "\u{fffd}PNG\r\n\u{1a}\n\0\0\0\rIHDR".to_string();
/// let (read, whole) = parse_files_noting_refusal(png, vec![], &o, Keep::Motion);
/// assert!(whole && read.unwrap_err().errors.len() == 1);
/// let (read, whole) = parse_files_noting_refusal("G1 X".into(), vec![], &o, Keep::Motion);
/// assert!(!whole && read.is_err());
/// ```
pub fn parse_files_noting_refusal(
    text: String,
    files: Vec<NcFile>,
    options: &ParseOptions,
    keep: Keep,
) -> (Result<Program, NcErrors>, bool) {
    let lexed = match lex_files(&text, &files) {
        Ok(lexed) => lexed,
        Err((e, whole)) => return (Err(e), whole),
    };
    drop(text);
    drop(files);
    let refused = lexed.refused;
    let read = lexed.interpret(options, keep);
    // the program's refusal alone: no file's error beside it
    let whole = refused && read.as_ref().is_err_and(|e| e.errors.len() == 1);
    (read, whole)
}

/// A program and its files lexed into one list of blocks: the errors
/// found, and where each extra file's blocks start with its name.
struct Lexed {
    blocks: Vec<Block>,
    errors: NcErrors,
    spans: Vec<(usize, String)>,
    /// The program's text was refused as a whole ([`super::unreadable`]).
    refused: bool,
}

/// Lexes `text` and then `files` into one list of blocks (the budgets
/// checked over all of them); `Err` for the texts refused together (over
/// the budget: `true`) or for the dialect refusal (`false`).
fn lex_files(text: &str, files: &[NcFile]) -> Result<Lexed, (NcErrors, bool)> {
    if !files.is_empty() {
        // one budget spans the program and its files (20 files of 100,000
        // lines took 1.25 GB when every block kept its modal state)
        let texts = std::iter::once(text).chain(files.iter().map(|f| f.text.as_str()));
        if let Err(e) = crate::budget::check_texts("program and its files", texts) {
            let mut errors = NcErrors {
                errors: Vec::new(),
                truncated: false,
            };
            errors.push(NcError::new(1, 1, e.to_string()));
            return Err((errors, true));
        }
    }
    let mut words = 0;
    let (mut blocks, mut errors, refused) = super::lex_noting_refusal(text, &mut words);
    let mut spans = Vec::new();
    let mut offset = blocks.len();
    for (k, f) in files.iter().enumerate() {
        let (bs, es) = super::lex_counting(&f.text, &mut words);
        for mut e in es.errors {
            e.file = Some(f.name.clone());
            errors.push(e);
        }
        spans.push((offset, f.name.clone()));
        let n = bs.len();
        blocks.extend(bs.into_iter().map(|b| Block {
            file: k + 1,
            line: b.line + offset,
            ..b
        }));
        offset += n;
    }
    let lexed = Lexed::checked(blocks, errors, spans).map_err(|e| (e, false))?;
    Ok(Lexed { refused, ..lexed })
}

/// Interprets the main program's `blocks`, lexed with `errors`, exactly
/// as [`parse_files_owned`] does with no extra files: the NC stream
/// (`super::stream`) ends with it.
pub(crate) fn interpret_lexed(
    blocks: Vec<Block>,
    errors: NcErrors,
    options: &ParseOptions,
    keep: Keep,
) -> Result<Program, NcErrors> {
    Lexed::checked(blocks, errors, Vec::new())?.interpret(options, keep)
}

/// The lexing's errors as the program's result when the lexing stops it:
/// the one that says the text looks like another control's language
/// (Heidenhain, Okuma), alone; `None` when the program runs.
pub(crate) fn dialect_refusal(errors: &NcErrors) -> Option<NcErrors> {
    errors
        .errors
        .iter()
        .find(|e| e.message.contains("this looks like"))
        .map(|e| NcErrors::from(e.clone()))
}

impl Lexed {
    /// The lexed program, or its dialect refusal ([`dialect_refusal`]).
    fn checked(
        blocks: Vec<Block>,
        errors: NcErrors,
        spans: Vec<(usize, String)>,
    ) -> Result<Lexed, NcErrors> {
        if let Some(e) = dialect_refusal(&errors) {
            return Err(e);
        }
        Ok(Lexed {
            blocks,
            errors,
            spans,
            refused: false,
        })
    }

    /// Runs the lexed program: the program, or every error of the lexing
    /// and the run in source order.
    fn interpret(self, options: &ParseOptions, keep: Keep) -> Result<Program, NcErrors> {
        let Lexed {
            blocks,
            mut errors,
            spans,
            ..
        } = self;
        match interpret_keeping(blocks, options, keep) {
            Ok(mut p) if errors.is_empty() => {
                relocate_program(&mut p, &spans);
                Ok(p)
            }
            Ok(_) => Err(errors),
            Err(e) => {
                for mut x in e.errors {
                    relocate_error(&mut x, &spans);
                    errors.push(x);
                }
                errors
                    .errors
                    .sort_by(|a, b| (&a.file, a.line, a.column).cmp(&(&b.file, b.line, b.column)));
                Err(errors)
            }
        }
    }
}

/// The file and the line in it of a line of the joined program.
fn locate(line: usize, spans: &[(usize, String)]) -> (Option<String>, usize) {
    match spans.iter().rev().find(|(off, _)| line > *off) {
        Some((off, name)) => (Some(name.clone()), line - off),
        None => (None, line),
    }
}

fn relocate_error(e: &mut NcError, spans: &[(usize, String)]) {
    if e.file.is_none() {
        (e.file, e.line) = locate(e.line, spans);
    }
}

fn relocate_program(p: &mut Program, spans: &[(usize, String)]) {
    if spans.is_empty() {
        return;
    }
    for w in &mut p.warnings {
        (w.file, w.line) = locate(w.line, spans);
    }
    for c in &mut p.cutter {
        (c.file, c.line) = locate(c.line, spans);
    }
    for s in &mut p.segments {
        s.line = locate(s.line, spans).1;
    }
    for b in &mut p.blocks {
        b.line = locate(b.line, spans).1;
    }
}

/// Index of the main program among `texts` (see the module header).
///
/// # Examples
/// ```
/// use mtmotion::nc::files::main_file;
/// assert_eq!(main_file(&["O2000\nG1 X1\nM99", "G0 X0\nM98 P2000\nM30"]), 1);
/// assert_eq!(main_file(&["o<a> sub\nG0 X1\no<a> endsub", "o<a> call"]), 1);
/// ```
pub fn main_file(texts: &[&str]) -> usize {
    let lexed: Vec<Vec<Block>> = texts.iter().map(|t| super::lex_all(t).0).collect();
    let has_m = |bs: &[Block], codes: &[f64]| {
        bs.iter().any(|b| {
            b.words
                .iter()
                .any(|w| w.letter == 'M' && codes.contains(&w.value))
        })
    };
    let is_sub = |bs: &[Block]| {
        has_m(bs, &[99.0])
            || bs.iter().any(|b| {
                matches!(
                    b.macro_line.as_deref().map(|m| &m.stmt),
                    Some(Stmt::O(_, OKw::Sub, _, _))
                )
            }) && !bs.iter().any(|b| {
                matches!(
                    b.macro_line.as_deref().map(|m| &m.stmt),
                    Some(Stmt::O(_, OKw::Call, _, _))
                ) && !inside_sub(bs, b)
            })
    };
    lexed
        .iter()
        .position(|bs| has_m(bs, &[2.0, 30.0]))
        .or_else(|| lexed.iter().position(|bs| !is_sub(bs)))
        .unwrap_or(0)
}

/// True when `b` lies between an o-word `sub` and its `endsub` in `bs`.
fn inside_sub(bs: &[Block], b: &Block) -> bool {
    let mut depth = 0i32;
    for x in bs {
        if std::ptr::eq(x, b) {
            return depth > 0;
        }
        match x.macro_line.as_deref().map(|m| &m.stmt) {
            Some(Stmt::O(_, OKw::Sub, _, _)) => depth += 1,
            Some(Stmt::O(_, OKw::EndSub, _, _)) => depth -= 1,
            _ => {}
        }
    }
    false
}
