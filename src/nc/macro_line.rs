//! Macro statements: one source line of Fanuc Custom Macro B or LinuxCNC
//! o-word code read into a [`Stmt`] (the lexer in [`super`] hands every
//! line with `#`, `[`, a Macro B keyword or an o-word keyword here).
//!
//! Sources: the Fanuc Series 0i operator's manual, "Custom macro"
//! (`#i=…`, `IF […] GOTO n`, `IF […] THEN`, `WHILE […] DO m` / `END m`,
//! `G65`), and the LinuxCNC G-code reference, "O Codes" (`sub`/`endsub`/
//! `call`, `if`/`elseif`/`else`/`endif`, `while`/`endwhile`, `do`/`while`,
//! `repeat`/`endrepeat`, `break`, `continue`, `return`).
//!
//! A plain block with computed words (`G1 X[#1/2] Y-#2 F#<feed>`) keeps
//! each word's value as an [`Expr`]; it is evaluated when the block runs.
//! Assignments on a line take effect after the line's words are evaluated
//! (LinuxCNC; Fanuc allows one assignment alone on its line).

use super::macro_expr::{
    is_okuma_word, okuma_message, show, tokenize, Cursor, Expr, Tok, Token, VarRef,
};
use super::{Block, NcError, Word, O_WORDS};

/// A macro line: the statement and the source text (written back as is).
#[derive(Debug, Clone, PartialEq)]
pub struct MacroLine {
    /// What the line does.
    pub stmt: Stmt,
    /// The line as written.
    pub src: String,
}

/// An address word whose value is computed (`X[#1/2]`).
#[derive(Debug, Clone, PartialEq)]
pub struct MWord {
    /// Upper-case address letter.
    pub letter: char,
    /// The value.
    pub value: Expr,
    /// The literal number text, when the value is a plain number.
    pub text: Option<String>,
    /// 1-based column of the letter.
    pub column: usize,
}

/// `#i = expr`.
#[derive(Debug, Clone, PartialEq)]
pub struct Assign {
    /// The variable written.
    pub var: VarRef,
    /// The value.
    pub expr: Expr,
    /// 1-based column of the `#`.
    pub column: usize,
}

/// LinuxCNC o-word keywords.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OKw {
    /// `sub`.
    Sub,
    /// `endsub`.
    EndSub,
    /// `call`.
    Call,
    /// `if`.
    If,
    /// `elseif`.
    ElseIf,
    /// `else`.
    Else,
    /// `endif`.
    EndIf,
    /// `while` (a loop head, or the end of a `do` loop).
    While,
    /// `endwhile`.
    EndWhile,
    /// `do`.
    Do,
    /// `repeat`.
    Repeat,
    /// `endrepeat`.
    EndRepeat,
    /// `break`.
    Break,
    /// `continue`.
    Continue,
    /// `return`.
    Return,
}

impl OKw {
    fn from_name(s: &str) -> Option<Self> {
        Some(match s {
            "SUB" => Self::Sub,
            "ENDSUB" => Self::EndSub,
            "CALL" => Self::Call,
            "IF" => Self::If,
            "ELSEIF" => Self::ElseIf,
            "ELSE" => Self::Else,
            "ENDIF" => Self::EndIf,
            "WHILE" => Self::While,
            "ENDWHILE" => Self::EndWhile,
            "DO" => Self::Do,
            "REPEAT" => Self::Repeat,
            "ENDREPEAT" => Self::EndRepeat,
            "BREAK" => Self::Break,
            "CONTINUE" => Self::Continue,
            "RETURN" => Self::Return,
            _ => return None,
        })
    }
}

/// An o-word label: `o100` or `o<name>`.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum OLabel {
    /// `o100`.
    Num(u32),
    /// `o<name>` (lower case).
    Name(String),
}

impl std::fmt::Display for OLabel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Num(n) => write!(f, "o{n}"),
            Self::Name(n) => write!(f, "o<{n}>"),
        }
    }
}

/// A macro statement.
#[derive(Debug, Clone, PartialEq)]
pub enum Stmt {
    /// Address words (some computed) and assignments.
    Block(Vec<MWord>, Vec<Assign>),
    /// `GOTO n` (Fanuc): jump to the block with sequence number n.
    Goto(Expr, usize),
    /// `IF [cond] GOTO n`.
    IfGoto(Expr, Expr, usize),
    /// `IF [cond] THEN #i=…`.
    IfThen(Expr, Vec<Assign>),
    /// `WHILE [cond] DO m`, with m and the column.
    While(Expr, u32, usize),
    /// `END m`.
    End(u32, usize),
    /// A LinuxCNC o-word with its label, keyword, `[ ]` arguments and the
    /// keyword's column.
    O(OLabel, OKw, Vec<Expr>, usize),
}

/// Fanuc Macro B statement keywords that make a line a macro line.
const STMT_WORDS: [&str; 6] = ["IF", "WHILE", "GOTO", "END", "DO", "THEN"];

/// True when `src` holds macro code: a `#` or `[` outside comments, a
/// Macro B statement keyword, or an o-word (`o100 sub`, `o<x> call`).
pub fn is_macro_line(src: &str) -> bool {
    if !might_be_macro(src) {
        return false;
    }
    let Ok(toks) = tokenize(src) else {
        return src.contains('#') || src.contains('[');
    };
    let code: Vec<&Tok> = toks
        .iter()
        .map(|t| &t.tok)
        .filter(|t| !matches!(t, Tok::Comment(_)))
        .collect();
    code.iter().enumerate().any(|(i, t)| match t {
        Tok::Hash | Tok::Named(_) | Tok::Open => true,
        Tok::Word(w) if STMT_WORDS.contains(&w.as_str()) => true,
        Tok::Word(w) if O_WORDS.contains(&w.as_str()) && i >= 1 => {
            let numbered = i >= 2
                && matches!(code[i - 2], Tok::Word(o) if o == "O")
                && matches!(code[i - 1], Tok::Num(..));
            numbered || matches!(code[i - 1], Tok::Label(_))
        }
        _ => false,
    })
}

/// Fast pre-check (most lines of a large CAM program are plain words): a
/// macro line has a `#`, a `[` or a run of two letters somewhere.
fn might_be_macro(src: &str) -> bool {
    let mut run = 0;
    for c in src.bytes() {
        if c == b'#' || c == b'[' {
            return true;
        }
        run = if c.is_ascii_alphabetic() { run + 1 } else { 0 };
        if run >= 2 {
            return true;
        }
    }
    false
}

/// Reads a macro line into a [`Block`] holding its [`MacroLine`]. The
/// block's `words` hold only a literal `N` sequence number (for `GOTO`).
///
/// # Errors
/// A malformed statement or expression, with line and column.
pub fn lex_macro(src: &str, line: usize) -> Result<Block, NcError> {
    let at = |(col, msg): (usize, String)| NcError::new(line, col, msg);
    let toks = tokenize(src).map_err(at)?;
    let mut block = Block {
        line,
        ..Block::default()
    };
    let mut code: Vec<Token> = Vec::new();
    for t in toks {
        match t.tok {
            Tok::Comment(c) => block.comments.push(c),
            Tok::Slash if code.is_empty() => block.block_delete = true,
            Tok::Percent if code.is_empty() => block.percent = true,
            _ => code.push(t),
        }
    }
    let end_col = src.chars().count() + 1;
    let mut c = Cursor::new(&code, end_col);
    if matches!(c.peek(), Some(Tok::Word(w)) if w == "N") {
        if let Some(Token {
            tok: Tok::Num(v, text),
            ..
        }) = code.get(1)
        {
            block.words.push(Word {
                letter: 'N',
                value: *v,
                text: text.as_str().into(),
                column: code[0].col,
            });
            c.i = 2;
        }
    }
    let stmt = statement(&mut c).map_err(at)?;
    if c.i < code.len() {
        return Err(at((
            c.col(),
            format!("unexpected {} after the statement", show(&code[c.i].tok)),
        )));
    }
    block.macro_line = Some(Box::new(MacroLine {
        stmt,
        src: src.trim_end().to_string(),
    }));
    Ok(block)
}

type PResult<T> = Result<T, (usize, String)>;

fn statement(c: &mut Cursor) -> PResult<Stmt> {
    let col = c.col();
    if c.eat_word("IF") {
        let cond = c.bracketed()?;
        if c.eat_word("GOTO") {
            return Ok(Stmt::IfGoto(cond, c.unary()?, col));
        }
        if matches!(c.peek(), Some(Tok::Word(w)) if w == "N") {
            return Err((c.col(), okuma_message("IF […] N…")));
        }
        if let Some(Tok::Word(w)) = c
            .peek()
            .filter(|t| matches!(t, Tok::Word(w) if matches!(w.as_str(), "AND" | "OR" | "XOR")))
        {
            return Err((
                c.col(),
                format!("'{w}' after IF […]: Fanuc Macro B takes one bracketed condition; write IF[[…] {w} […]] GOTO n"),
            ));
        }
        if c.eat_word("THEN") {
            let assigns = assignments(c)?;
            if assigns.is_empty() {
                return Err((c.col(), "expected an assignment #i=… after THEN".into()));
            }
            return Ok(Stmt::IfThen(cond, assigns));
        }
        return Err((c.col(), "expected GOTO n or THEN #i=… after IF […]".into()));
    }
    if c.eat_word("WHILE") {
        let cond = c.bracketed()?;
        if !c.eat_word("DO") {
            return Err((c.col(), "expected DO m after WHILE […]".into()));
        }
        return Ok(Stmt::While(cond, loop_id(c)?, col));
    }
    if c.eat_word("END") {
        return Ok(Stmt::End(loop_id(c)?, col));
    }
    if c.eat_word("GOTO") {
        if matches!(c.peek(), Some(Tok::Word(w)) if w == "N") {
            return Err((col, okuma_message("GOTO N…")));
        }
        return Ok(Stmt::Goto(c.unary()?, col));
    }
    if let Some(o) = o_word(c)? {
        return Ok(o);
    }
    let mut words = Vec::new();
    let mut assigns = Vec::new();
    while let Some(t) = c.peek() {
        match t {
            Tok::Hash | Tok::Named(_) => assigns.push(assignment(c)?),
            Tok::Word(w) if w.len() == 1 => words.push(word(c)?),
            Tok::Word(w) => return Err((c.col(), keyword_message(w))),
            Tok::Op(o) if !words.is_empty() => {
                return Err((c.col(), unbracketed_message(&words, o)));
            }
            t => {
                return Err((
                    c.col(),
                    format!("unexpected {}; expected an address word or #i=…", show(t)),
                ))
            }
        }
    }
    Ok(Stmt::Block(words, assigns))
}

fn loop_id(c: &mut Cursor) -> PResult<u32> {
    match c.peek() {
        Some(Tok::Num(v, _)) if *v >= 1.0 && v.fract() == 0.0 && *v <= 99.0 => {
            let v = *v as u32;
            c.i += 1;
            Ok(v)
        }
        _ => Err((
            c.col(),
            "expected a loop number after DO/END (1 to 99; Fanuc allows 1 to 3)".into(),
        )),
    }
}

fn assignments(c: &mut Cursor) -> PResult<Vec<Assign>> {
    let mut out = Vec::new();
    while matches!(c.peek(), Some(Tok::Hash | Tok::Named(_))) {
        out.push(assignment(c)?);
    }
    Ok(out)
}

fn assignment(c: &mut Cursor) -> PResult<Assign> {
    let column = c.col();
    let var = c.var()?;
    if c.peek() != Some(&Tok::Assign) {
        return Err((
            c.col(),
            "a variable at the start of a statement must be assigned: expected '=' (e.g. #1=2.5)"
                .into(),
        ));
    }
    c.i += 1;
    let expr = c.expr()?;
    exponent(c)?;
    Ok(Assign { var, expr, column })
}

/// An `E…` word written straight after a number (`#100=1E3`) is an
/// exponent, which NC numbers do not take: named as one (it used to stop
/// the program as "a 3D-printer program", E being the extruder's word).
fn exponent(c: &Cursor) -> PResult<()> {
    let (Some(prev), Some(next)) = (
        c.i.checked_sub(1).and_then(|i| c.toks.get(i)),
        c.toks.get(c.i),
    ) else {
        return Ok(());
    };
    match (&prev.tok, &next.tok) {
        (Tok::Num(_, text), Tok::Word(w)) if w == "E" && prev.col + text.chars().count() == next.col => {
            Err((
                next.col,
                format!("{text}E…: NC numbers take no exponent; write the number out in full (1E3 as 1000)"),
            ))
        }
        _ => Ok(()),
    }
}

fn word(c: &mut Cursor) -> PResult<MWord> {
    let column = c.col();
    let letter = match c.peek() {
        Some(Tok::Word(w)) => w.chars().next().unwrap_or('?'),
        _ => '?',
    };
    c.i += 1;
    let sign = match c.peek() {
        Some(Tok::Op(o)) if *o == "-" || *o == "+" => Some(*o),
        _ => None,
    };
    let lit = c.toks.get(c.i + usize::from(sign.is_some()));
    let text = match lit.map(|t| &t.tok) {
        Some(Tok::Num(_, t)) => Some(format!("{}{t}", if sign == Some("-") { "-" } else { "" })),
        _ => None,
    };
    if c.peek().is_none() {
        return Err((column, format!("expected a value after address '{letter}'")));
    }
    let value = c.unary()?;
    let text =
        text.filter(|_| matches!(value, Expr::Num(_) | Expr::Neg(_)) && !is_computed(&value));
    Ok(MWord {
        letter,
        value,
        text,
        column,
    })
}

fn is_computed(e: &Expr) -> bool {
    match e {
        Expr::Num(_) => false,
        Expr::Neg(x) => is_computed(x),
        _ => true,
    }
}

fn o_word(c: &mut Cursor) -> PResult<Option<Stmt>> {
    let save = c.i;
    let label = match (c.peek(), c.toks.get(c.i + 1).map(|t| &t.tok)) {
        (Some(Tok::Word(o)), Some(Tok::Num(v, _))) if o == "O" && v.fract() == 0.0 => {
            c.i += 2;
            OLabel::Num(*v as u32)
        }
        (Some(Tok::Label(n)), _) => {
            c.i += 1;
            OLabel::Name(n.clone())
        }
        (Some(Tok::Word(o)), Some(Tok::Label(n))) if o == "O" => {
            c.i += 2;
            OLabel::Name(n.clone())
        }
        _ => return Ok(None),
    };
    let col = c.col();
    let kw = match c.peek() {
        Some(Tok::Word(w)) => OKw::from_name(w),
        _ => None,
    };
    let Some(kw) = kw else {
        c.i = save;
        return Err((col, format!("expected an o-word keyword after {label} (sub, endsub, call, if, elseif, else, endif, while, endwhile, do, repeat, endrepeat, break, continue, return)")));
    };
    c.i += 1;
    let mut args = Vec::new();
    while c.peek() == Some(&Tok::Open) {
        args.push(c.bracketed()?);
    }
    Ok(Some(Stmt::O(label, kw, args, col)))
}

/// The message for an operator right after a word's value (`X#140/2`):
/// Fanuc Macro B computes a word's value only inside brackets.
fn unbracketed_message(words: &[MWord], op: &str) -> String {
    let letter = words.last().map_or('?', |w| w.letter);
    format!(
        "'{op}' after the value of address '{letter}': an address takes one number, #i or [expression]; put the arithmetic in brackets ({letter}[#1{op}2])"
    )
}

/// The message for a letter run that is no keyword.
fn keyword_message(run: &str) -> String {
    if is_okuma_word(run) {
        return okuma_message(run);
    }
    if let Some(m) = super::macro_b_abbreviation_message(run) {
        return m;
    }
    let letter = run.chars().next().unwrap_or('?');
    format!("expected a number after address '{letter}', found the letters '{run}'")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stmt(src: &str) -> Stmt {
        lex_macro(src, 1).unwrap().macro_line.unwrap().stmt
    }

    #[test]
    fn statements_are_recognised() {
        assert!(matches!(stmt("N10 IF[#1GT#2]GOTO20"), Stmt::IfGoto(..)));
        assert!(matches!(
            stmt("IF [#1 EQ #0] THEN #3000=1 (NO ARG)"),
            Stmt::IfThen(..)
        ));
        assert!(matches!(stmt("WHILE[#1LE5]DO1"), Stmt::While(_, 1, 1)));
        assert!(matches!(stmt("END1"), Stmt::End(1, 1)));
        assert!(
            matches!(stmt("o100 call [1] [-2]"), Stmt::O(OLabel::Num(100), OKw::Call, ref a, 6) if a.len() == 2)
        );
        assert!(
            matches!(stmt("O<mill> sub"), Stmt::O(OLabel::Name(ref n), OKw::Sub, _, _) if n == "mill")
        );
        let Stmt::Block(w, a) = stmt("#1=2 #<x> = [#1*2] G1 X-#1 Y[#2] F100.") else {
            panic!()
        };
        assert_eq!(a.len(), 2);
        let letters: String = w.iter().map(|w| w.letter).collect();
        assert_eq!(letters, "GXYF");
        assert_eq!(w[3].text.as_deref(), Some("100."));
        assert_eq!(w[1].text, None);
        let b = lex_macro("N40 #1=1", 4).unwrap();
        assert_eq!(b.word('N').unwrap().value, 40.0);
    }

    #[test]
    fn detection_and_errors() {
        assert!(is_macro_line("G1 X#1"));
        assert!(is_macro_line("o100 endwhile"));
        assert!(is_macro_line("IF [1 EQ 1] GOTO 5"));
        assert!(!is_macro_line("G1 X1 (IF [A])"));
        assert!(!is_macro_line("O1000"));
        let e = lex_macro("#1=", 3).unwrap_err();
        assert_eq!((e.line, e.column), (3, 4));
        let e = lex_macro("G1 X[#1+1", 1).unwrap_err();
        assert!(e.message.contains("']'"), "{e}");
        let e = lex_macro("GOTO N100", 1).unwrap_err();
        assert!(e.message.contains("Okuma"), "{e}");
    }
}
