//! Macro expressions of Fanuc Custom Macro B and LinuxCNC (RS-274/NGC
//! parameters): tokens, the expression tree and its evaluation.
//!
//! Sources: the Fanuc Series 0i operator's manual, "Custom macro"
//! (variables, vacant `#0`, arithmetic and functions), and the LinuxCNC
//! G-code reference, "Expressions" and "Parameters".
//!
//! Readings chosen:
//! - A value is `Option<f64>`: `None` is a vacant variable (Fanuc `#0`).
//!   In arithmetic a vacant value is 0; `EQ`/`NE` compare vacant with
//!   vacant only (vacant ≠ 0); `GT GE LT LE` read vacant as 0. A bare
//!   variable passes vacant on (so `#2=#1` copies vacant).
//! - Precedence, highest first: functions and unary sign, `**`,
//!   `* / MOD`, `+ -`, `EQ NE GT GE LT LE`, `AND OR XOR` (LinuxCNC's
//!   order; Fanuc programs bracket their comparisons, so both read alike).
//!   `AND OR XOR` are logical (non-zero is true) in LinuxCNC and bitwise on
//!   whole numbers in Fanuc, which agree on 0/1 truth values.
//! - Angles are degrees. `ATAN[a]/[b]` is the angle of (b, a): Fanuc gives
//!   0 to 360°, LinuxCNC −180 to 180°. `FIX`/`FUP`: Fanuc truncates
//!   toward / away from zero, LinuxCNC floors / ceils. `ROUND` rounds half
//!   away from zero.
//! - A result that is not finite (division by zero, `SQRT` of a negative,
//!   `LN` of a non-positive) is an error naming the operation and values.
//! - Nesting is limited to [`MAX_EXPR_DEPTH`] levels (each `[`, each `#`
//!   of `##…` and each `**` opens one), far above a real program (Fanuc
//!   allows 5 bracket levels) and far below what overflows the 1 MiB wasm
//!   stack: the parser and the evaluator recurse once per level, so a
//!   deeper expression is refused at the column of the level too many. A
//!   run of operators of one precedence (`1+1+…+1`) is kept as one flat
//!   [`Expr::Chain`], and a run of signs (`--…-1`) as one or no
//!   [`Expr::Neg`], so their length costs no stack at all.

use crate::numeric::compact;

/// One token of a macro line, with its 1-based column.
#[derive(Debug, Clone, PartialEq)]
pub struct Token {
    /// What it is.
    pub tok: Tok,
    /// 1-based column of its first character.
    pub col: usize,
}

/// Token kinds.
#[derive(Debug, Clone, PartialEq)]
pub enum Tok {
    /// A number, with its text.
    Num(f64, String),
    /// `#` (a numbered variable follows).
    Hash,
    /// `#<name>`: a LinuxCNC named parameter (lower case, no spaces).
    Named(String),
    /// `<name>` after `O`: a LinuxCNC named subroutine label.
    Label(String),
    /// `[`.
    Open,
    /// `]`.
    Close,
    /// `+ - * / **`.
    Op(&'static str),
    /// `=`.
    Assign,
    /// A run of letters, upper-cased.
    Word(String),
    /// A comment (`( … )` or after `;`), without delimiters.
    Comment(String),
    /// `/` at the start of the line: block delete.
    Slash,
    /// `%`.
    Percent,
}

/// The tokens of one line; `line` names errors as `(line, column,
/// message)`.
///
/// # Errors
/// An unclosed comment or `#<`, a malformed number, a character that is no
/// part of a macro line.
pub fn tokenize(src: &str) -> Result<Vec<Token>, (usize, String)> {
    let chars: Vec<char> = src.chars().collect();
    let mut out: Vec<Token> = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let col = i + 1;
        let push = |out: &mut Vec<Token>, tok| out.push(Token { tok, col });
        if c.is_whitespace() {
            i += 1;
        } else if c == '(' {
            let (text, next) = comment(&chars, i).ok_or((
                col,
                "comment opened with '(' is not closed with ')'".to_string(),
            ))?;
            push(&mut out, Tok::Comment(text));
            i = next;
        } else if c == ';' {
            let text: String = chars[i + 1..].iter().collect();
            push(&mut out, Tok::Comment(text.trim().to_string()));
            break;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            let text: String = chars[start..i].iter().collect();
            let v: f64 = text
                .parse()
                .map_err(|_| (col, format!("'{text}' is not a valid number")))?;
            push(&mut out, Tok::Num(v, text));
        } else if c == '#' || c == '<' {
            i = hash_or_label(&chars, i, &mut out)?;
        } else if c.is_ascii_alphabetic() {
            let start = i;
            while i < chars.len() && chars[i].is_ascii_alphabetic() {
                i += 1;
            }
            let run: String = chars[start..i].iter().collect::<String>();
            push(&mut out, Tok::Word(run.to_ascii_uppercase()));
        } else {
            let (tok, len) = match (c, chars.get(i + 1)) {
                ('*', Some('*')) => (Tok::Op("**"), 2),
                ('*', _) => (Tok::Op("*"), 1),
                ('+', _) => (Tok::Op("+"), 1),
                ('-', _) => (Tok::Op("-"), 1),
                ('/', _) if out.is_empty() => (Tok::Slash, 1),
                ('/', _) => (Tok::Op("/"), 1),
                ('[', _) => (Tok::Open, 1),
                (']', _) => (Tok::Close, 1),
                ('=', _) => (Tok::Assign, 1),
                ('%', _) => (Tok::Percent, 1),
                (',', Some(&l)) if matches!(l.to_ascii_uppercase(), 'R' | 'C') => {
                    return Err((
                        col,
                        format!(
                            "Fanuc corner word ',{}' in a macro line is not supported yet; write it on a block without macro code, with a number (,{}0.5)",
                            l.to_ascii_uppercase(),
                            l.to_ascii_uppercase()
                        ),
                    ))
                }
                _ => {
                    return Err((
                        col,
                        format!(
                            "unexpected character '{c}' (U+{:04X}) in a macro line",
                            c as u32
                        ),
                    ))
                }
            };
            push(&mut out, tok);
            i += len;
        }
    }
    Ok(out)
}

/// A `( … )` comment starting at `chars[i]`: its trimmed text and the
/// index after it. Balanced parentheses nest (`(DRILL (5 HOLES))` is one
/// comment). A stray `(` inside a comment (`(G0 X#1+.25(move up)`) leaves
/// the nesting unclosed at the end of the line; Fanuc comments do not nest,
/// so the comment then ends at its first `)`, as the control reads it.
/// `None` when no `)` follows at all.
pub(crate) fn comment(chars: &[char], i: usize) -> Option<(String, usize)> {
    let mut depth = 0usize;
    let mut first_close = None;
    for (j, &c) in chars.iter().enumerate().skip(i) {
        match c {
            '(' => depth += 1,
            ')' => {
                first_close.get_or_insert(j);
                depth -= 1;
                if depth == 0 {
                    let text: String = chars[i + 1..j].iter().collect();
                    return Some((text.trim().to_string(), j + 1));
                }
            }
            _ => {}
        }
    }
    let j = first_close?;
    let text: String = chars[i + 1..j].iter().collect();
    Some((text.trim().to_string(), j + 1))
}

/// `#`, `#<name>` or `<name>` at `chars[i]`; returns the index after it.
fn hash_or_label(chars: &[char], i: usize, out: &mut Vec<Token>) -> Result<usize, (usize, String)> {
    let col = i + 1;
    let mut j = i;
    if chars[j] == '#' {
        j += 1;
        while j < chars.len() && chars[j].is_whitespace() {
            j += 1;
        }
        if chars.get(j) != Some(&'<') {
            out.push(Token {
                tok: Tok::Hash,
                col,
            });
            return Ok(i + 1);
        }
    }
    let close = chars[j..].iter().position(|&c| c == '>').ok_or((
        col,
        "a name opened with '<' is not closed with '>'".to_string(),
    ))?;
    let name: String = chars[j + 1..j + close]
        .iter()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_lowercase();
    if name.is_empty() {
        return Err((
            col,
            "empty name '<>'; expected a name such as #<depth>".into(),
        ));
    }
    let tok = if chars[i] == '#' {
        Tok::Named(name)
    } else {
        Tok::Label(name)
    };
    out.push(Token { tok, col });
    Ok(j + close + 1)
}

/// Deepest nesting of one expression: brackets (`[`, so also a function's
/// argument and `#[…]`), `#` of `##…#1`, and the right operand of `**`
/// each open a level. Real controls take a handful (Fanuc: 5 bracket
/// levels). The stack a level costs was measured (docs/nc-programs.md,
/// "Expression depth"): the costliest shape overflows the 1 MiB wasm stack
/// at about 1,100 levels in the release build and 136 in the debug build.
pub const MAX_EXPR_DEPTH: usize = 64;

/// Deepest expression tree [`eval`] takes. A level of nesting adds at most
/// seven nodes to a parsed tree (four operator chains, `**`, a sign, and a
/// function or variable), so a parsed expression stays below it; it guards
/// the evaluator against a tree built in code.
pub const MAX_TREE_DEPTH: usize = 8 * (MAX_EXPR_DEPTH + 1);

/// The message for an expression nested deeper than [`MAX_EXPR_DEPTH`].
pub fn depth_message() -> String {
    format!(
        "expression nested deeper than {MAX_EXPR_DEPTH} levels (each '[', '#' of '##' and '**' opens one); simplify it, e.g. compute parts into #variables first"
    )
}

/// A variable reference.
#[derive(Debug, Clone, PartialEq)]
pub enum VarRef {
    /// `#n`, `#[expr]` or `##n`: the number is computed.
    Num(Expr),
    /// `#<name>` (LinuxCNC).
    Named(String),
}

/// Built-in functions of one argument.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Func {
    /// SIN, degrees.
    Sin,
    /// COS, degrees.
    Cos,
    /// TAN, degrees.
    Tan,
    /// ASIN, degrees.
    Asin,
    /// ACOS, degrees.
    Acos,
    /// ATAN of one argument, degrees.
    Atan,
    /// SQRT.
    Sqrt,
    /// ABS.
    Abs,
    /// ROUND (half away from zero).
    Round,
    /// FIX (see the module header).
    Fix,
    /// FUP (see the module header).
    Fup,
    /// EXP.
    Exp,
    /// LN.
    Ln,
}

impl Func {
    fn from_name(s: &str) -> Option<Self> {
        Some(match s {
            "SIN" => Self::Sin,
            "COS" => Self::Cos,
            "TAN" => Self::Tan,
            "ASIN" => Self::Asin,
            "ACOS" => Self::Acos,
            "ATAN" => Self::Atan,
            "SQRT" => Self::Sqrt,
            "ABS" => Self::Abs,
            "ROUND" => Self::Round,
            "FIX" => Self::Fix,
            "FUP" => Self::Fup,
            "EXP" => Self::Exp,
            "LN" => Self::Ln,
            _ => return None,
        })
    }
}

/// Binary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `*`.
    Mul,
    /// `/`.
    Div,
    /// `MOD`.
    Mod,
    /// `**`.
    Pow,
    /// `EQ`.
    Eq,
    /// `NE`.
    Ne,
    /// `GT`.
    Gt,
    /// `GE`.
    Ge,
    /// `LT`.
    Lt,
    /// `LE`.
    Le,
    /// `AND`.
    And,
    /// `OR`.
    Or,
    /// `XOR`.
    Xor,
}

/// An expression tree.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    /// A literal number.
    Num(f64),
    /// A variable's value (may be vacant).
    Var(Box<VarRef>),
    /// Unary minus.
    Neg(Box<Expr>),
    /// A function of one argument.
    Func(Func, Box<Expr>),
    /// `ATAN[a]/[b]`: the angle of (b, a), degrees.
    Atan2(Box<Expr>, Box<Expr>),
    /// A binary operation (the parser gives it for `**`, right to left:
    /// `a**b**c` is `a**[b**c]`).
    Bin(BinOp, Box<Expr>, Box<Expr>),
    /// Operators of one precedence, left to right: `a-b+c` is the first
    /// operand, then (`-`, b) and (`+`, c). A list rather than a tree, so a
    /// long sum costs no stack to evaluate or drop.
    Chain(Box<Expr>, Vec<(BinOp, Expr)>),
    /// `EXISTS[#<name>]` (LinuxCNC).
    Exists(String),
}

/// A parse error: 1-based column and message.
pub type PErr = (usize, String);

/// A cursor over a line's tokens.
pub struct Cursor<'a> {
    /// The tokens.
    pub toks: &'a [Token],
    /// Index of the next token.
    pub i: usize,
    /// Column just past the line (for errors at its end).
    pub end_col: usize,
    /// Levels of nesting open (at most [`MAX_EXPR_DEPTH`]).
    depth: usize,
}

impl<'a> Cursor<'a> {
    /// A cursor at the first of `toks`; `end_col` is the column just past
    /// the line.
    pub fn new(toks: &'a [Token], end_col: usize) -> Self {
        Self {
            toks,
            i: 0,
            end_col,
            depth: 0,
        }
    }
    /// Opens a level of nesting at the next token (the error names its
    /// column), or refuses one level too many.
    fn enter(&mut self) -> Result<(), PErr> {
        if self.depth >= MAX_EXPR_DEPTH {
            return Err((self.col(), depth_message()));
        }
        self.depth += 1;
        Ok(())
    }
    fn leave(&mut self) {
        self.depth -= 1;
    }
    /// The next token, if any.
    pub fn peek(&self) -> Option<&'a Tok> {
        self.toks.get(self.i).map(|t| &t.tok)
    }
    /// The column of the next token (or the end of the line).
    pub fn col(&self) -> usize {
        self.toks.get(self.i).map_or(self.end_col, |t| t.col)
    }
    /// Takes the next token if it is a keyword `w`.
    pub fn eat_word(&mut self, w: &str) -> bool {
        if matches!(self.peek(), Some(Tok::Word(x)) if x == w) {
            self.i += 1;
            true
        } else {
            false
        }
    }
    fn expect_close(&mut self) -> Result<(), PErr> {
        if self.peek() == Some(&Tok::Close) {
            self.i += 1;
            Ok(())
        } else {
            Err((self.col(), "expected ']' to close the expression".into()))
        }
    }
    /// `[ expr ]`.
    pub fn bracketed(&mut self) -> Result<Expr, PErr> {
        if self.peek() != Some(&Tok::Open) {
            return Err((self.col(), "expected '[' to start an expression".into()));
        }
        self.enter()?;
        self.i += 1;
        let e = self.expr()?;
        self.expect_close()?;
        self.leave();
        Ok(e)
    }
    /// A full expression (lowest precedence: AND OR XOR). Its operands
    /// and operators are read in one loop, then grouped by precedence
    /// (`group`), so a level of nesting costs the parser one frame of
    /// this function, not one per precedence level.
    pub fn expr(&mut self) -> Result<Expr, PErr> {
        let first = self.power()?;
        let mut more = Vec::new();
        while let Some((op, rank)) = self.peek().and_then(binary_op) {
            self.i += 1;
            more.push((op, rank, self.power()?));
        }
        Ok(group(first, more))
    }
    fn power(&mut self) -> Result<Expr, PErr> {
        let lhs = self.unary()?;
        if self.peek() == Some(&Tok::Op("**")) {
            self.i += 1;
            self.enter()?;
            let rhs = self.power()?;
            self.leave();
            return Ok(Expr::Bin(BinOp::Pow, Box::new(lhs), Box::new(rhs)));
        }
        Ok(lhs)
    }
    /// A signed primary: the value of an address word (`X-#1`, `X[…]`).
    /// A run of signs is read in a loop: an even number of `-` cancels.
    pub fn unary(&mut self) -> Result<Expr, PErr> {
        let mut negate = false;
        loop {
            match self.peek() {
                Some(Tok::Op("-")) => negate = !negate,
                Some(Tok::Op("+")) => {}
                _ => break,
            }
            self.i += 1;
        }
        let e = self.primary()?;
        Ok(if negate { Expr::Neg(Box::new(e)) } else { e })
    }
    fn primary(&mut self) -> Result<Expr, PErr> {
        let col = self.col();
        match self.peek() {
            Some(Tok::Num(v, _)) => {
                self.i += 1;
                Ok(Expr::Num(*v))
            }
            Some(Tok::Open) => self.bracketed(),
            Some(Tok::Hash | Tok::Named(_)) => Ok(Expr::Var(Box::new(self.var()?))),
            Some(Tok::Word(w)) => {
                let w = w.clone();
                self.i += 1;
                self.function(&w, col)
            }
            Some(t) => Err((
                col,
                format!(
                    "expected a number, '#', '[' or a function, found {}",
                    show(t)
                ),
            )),
            None => Err((col, "expected a value; the line ends here".into())),
        }
    }
    fn function(&mut self, name: &str, col: usize) -> Result<Expr, PErr> {
        if name == "EXISTS" {
            if self.peek() != Some(&Tok::Open) {
                return Err((self.col(), "expected EXISTS[#<name>]".into()));
            }
            self.i += 1;
            let Some(Tok::Named(n)) = self.peek() else {
                return Err((
                    self.col(),
                    "expected a named parameter #<name> inside EXISTS[ ]".into(),
                ));
            };
            let n = n.clone();
            self.i += 1;
            self.expect_close()?;
            return Ok(Expr::Exists(n));
        }
        let Some(f) = Func::from_name(name) else {
            if is_okuma_word(name) {
                return Err((col, okuma_message(name)));
            }
            return Err((
                col,
                format!("'{name}' is not a macro function; expected SIN, COS, TAN, ASIN, ACOS, ATAN, SQRT, ABS, ROUND, FIX, FUP, EXP, LN or EXISTS"),
            ));
        };
        let arg = self.bracketed()?;
        if f == Func::Atan && self.peek() == Some(&Tok::Op("/")) {
            let save = self.i;
            self.i += 1;
            if self.peek() == Some(&Tok::Open) {
                let b = self.bracketed()?;
                return Ok(Expr::Atan2(Box::new(arg), Box::new(b)));
            }
            self.i = save;
        }
        Ok(Expr::Func(f, Box::new(arg)))
    }
    /// A variable after `#`: `#12`, `#[expr]`, `##1`, `#<name>`.
    pub fn var(&mut self) -> Result<VarRef, PErr> {
        match self.peek() {
            Some(Tok::Named(n)) => {
                let n = n.clone();
                self.i += 1;
                Ok(VarRef::Named(n))
            }
            Some(Tok::Hash) => {
                self.i += 1;
                let col = self.col();
                match self.peek() {
                    Some(Tok::Num(v, _)) => {
                        let v = *v;
                        self.i += 1;
                        Ok(VarRef::Num(Expr::Num(v)))
                    }
                    Some(Tok::Open) => Ok(VarRef::Num(self.bracketed()?)),
                    Some(Tok::Hash) => {
                        self.enter()?;
                        let inner = self.var()?;
                        self.leave();
                        Ok(VarRef::Num(Expr::Var(Box::new(inner))))
                    }
                    _ => Err((
                        col,
                        "expected a variable number after '#' (e.g. #1, #[#2+1], #<name>)".into(),
                    )),
                }
            }
            _ => Err((self.col(), "expected a variable '#'".into())),
        }
    }
}

/// The binary operator of `t` (not `**`) and its precedence rank: 0 for
/// `AND OR XOR` (lowest), 1 for `EQ NE GT GE LT LE`, 2 for `+ -`, 3 for
/// `* / MOD`.
fn binary_op(t: &Tok) -> Option<(BinOp, u8)> {
    Some(match t {
        Tok::Op("+") => (BinOp::Add, 2),
        Tok::Op("-") => (BinOp::Sub, 2),
        Tok::Op("*") => (BinOp::Mul, 3),
        Tok::Op("/") => (BinOp::Div, 3),
        Tok::Word(w) => match w.as_str() {
            "MOD" => (BinOp::Mod, 3),
            "EQ" => (BinOp::Eq, 1),
            "NE" => (BinOp::Ne, 1),
            "GT" => (BinOp::Gt, 1),
            "GE" => (BinOp::Ge, 1),
            "LT" => (BinOp::Lt, 1),
            "LE" => (BinOp::Le, 1),
            "AND" => (BinOp::And, 0),
            "OR" => (BinOp::Or, 0),
            "XOR" => (BinOp::Xor, 0),
            _ => return None,
        },
        _ => return None,
    })
}

/// `first op₁ e₁ op₂ e₂ …` grouped by precedence, each rank left to right:
/// the operands between two operators of the lowest rank present form one
/// operand of that rank's [`Expr::Chain`], and so on up. The recursion is
/// at most four ranks deep, whatever the length.
fn group(first: Expr, more: Vec<(BinOp, u8, Expr)>) -> Expr {
    let Some(rank) = more.iter().map(|&(_, r, _)| r).min() else {
        return first;
    };
    let mut lead = None;
    let mut list: Vec<(BinOp, Expr)> = Vec::new();
    // the operator of this rank before `head`, and the higher-rank tail
    // after it
    let mut op_before = None;
    let mut head = first;
    let mut run = Vec::new();
    for (op, r, e) in more {
        if r != rank {
            run.push((op, r, e));
            continue;
        }
        let operand = group(head, std::mem::take(&mut run));
        match op_before {
            None => lead = Some(operand),
            Some(p) => list.push((p, operand)),
        }
        op_before = Some(op);
        head = e;
    }
    let operand = group(head, run);
    match (lead, op_before) {
        (Some(lead), Some(p)) => {
            list.push((p, operand));
            Expr::Chain(Box::new(lead), list)
        }
        // not reached: `rank` is the rank of an operator in `more`
        _ => operand,
    }
}

/// Letter runs that only Okuma OSP programs use: common variables
/// `VC1`, system variables `VS…`, `CALL O…`, `NIF`, `RTS`, `MSG`.
pub fn is_okuma_word(run: &str) -> bool {
    ["VC", "VS", "CALL", "NIF", "RTS", "MSG"]
        .iter()
        .any(|k| run.starts_with(k))
}

/// The Okuma OSP file header alone on its line, `$OKUMA.SSB%` or
/// `$FLANGE.MIN%`: `$`, a file name (letters, digits, `_`, `-`), a dot, an
/// extension of one to four letters or digits (MIN, SUB, SSB, LIB, …) and
/// `%`. The header without its surrounding whitespace, or `None`. Grbl
/// `$` commands (`$H`, `$J=…`) have no dot and `%` and are not headers.
pub fn okuma_file_header(line: &str) -> Option<&str> {
    let t = line.trim();
    let body = t.strip_prefix('$')?.strip_suffix('%')?;
    let (name, ext) = body.rsplit_once('.')?;
    let name_ok = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    let ext_ok = (1..=4).contains(&ext.len()) && ext.chars().all(|c| c.is_ascii_alphanumeric());
    (name_ok && ext_ok).then_some(t)
}

/// The refusal of an Okuma OSP program.
pub fn okuma_message(found: &str) -> String {
    format!(
        "'{found}': this looks like an Okuma OSP program ($NAME.MIN% header, VC variables, NIF, CALL O…, GOTO N…, G15 H); mtmotion reads ISO/Fanuc, Haas and LinuxCNC programs: post the part for a Fanuc-compatible control"
    )
}

/// A token as shown in a message.
pub fn show(t: &Tok) -> String {
    match t {
        Tok::Num(_, s) => format!("the number '{s}'"),
        Tok::Hash => "'#'".into(),
        Tok::Named(n) => format!("'#<{n}>'"),
        Tok::Label(n) => format!("'<{n}>'"),
        Tok::Open => "'['".into(),
        Tok::Close => "']'".into(),
        Tok::Op(o) => format!("'{o}'"),
        Tok::Assign => "'='".into(),
        Tok::Word(w) => format!("'{w}'"),
        Tok::Comment(_) => "a comment".into(),
        Tok::Slash => "'/'".into(),
        Tok::Percent => "'%'".into(),
    }
}

/// A variable key after its number is computed.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum VarKey {
    /// `#n`.
    Num(u32),
    /// `#<name>`.
    Named(String),
}

impl std::fmt::Display for VarKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Num(n) => write!(f, "#{n}"),
            Self::Named(n) => write!(f, "#<{n}>"),
        }
    }
}

/// What an expression reads: the variables and the dialect.
pub trait Vars {
    /// The value of `key` (`None`: vacant), or an error message.
    ///
    /// # Errors
    /// A variable that cannot be read (e.g. an undefined named parameter).
    fn read(&mut self, key: &VarKey) -> Result<Option<f64>, String>;
    /// True when the named parameter exists.
    fn exists(&self, name: &str) -> bool;
    /// LinuxCNC readings (FIX/FUP, ATAN range, logical AND/OR/XOR).
    fn linuxcnc(&self) -> bool;
}

/// Largest variable number accepted.
pub const MAX_VAR: f64 = 99_999.0;

/// The key of a variable reference.
///
/// # Errors
/// A variable number that is vacant, negative, not whole or too large.
pub fn key(v: &VarRef, vars: &mut dyn Vars) -> Result<VarKey, String> {
    key_at(v, vars, 0)
}

/// [`key`] of a reference `depth` nodes down a tree.
fn key_at(v: &VarRef, vars: &mut dyn Vars, depth: usize) -> Result<VarKey, String> {
    match v {
        VarRef::Named(n) => Ok(VarKey::Named(n.clone())),
        VarRef::Num(e) => {
            let n = eval_at(e, vars, depth)?
                .ok_or_else(|| "a variable number is vacant (#[#n] with #n vacant)".to_string())?;
            let r = n.round();
            if !(0.0..=MAX_VAR).contains(&r) || (n - r).abs() > 1e-6 {
                return Err(format!(
                    "variable number {} is not a whole number from 0 to {MAX_VAR}",
                    compact(n)
                ));
            }
            Ok(VarKey::Num(r as u32))
        }
    }
}

/// Evaluates `e` (`None`: vacant).
///
/// # Errors
/// A non-finite result, an unreadable variable, a tree deeper than
/// [`MAX_TREE_DEPTH`].
pub fn eval(e: &Expr, vars: &mut dyn Vars) -> Result<Option<f64>, String> {
    eval_at(e, vars, 0)
}

/// [`eval`] of a node `depth` nodes down a tree: it recurses once per
/// node, so the depth is bounded (an operator chain is a loop).
fn eval_at(e: &Expr, vars: &mut dyn Vars, depth: usize) -> Result<Option<f64>, String> {
    if depth >= MAX_TREE_DEPTH {
        return Err(format!(
            "expression tree deeper than {MAX_TREE_DEPTH} nodes; simplify it"
        ));
    }
    let d = depth + 1;
    let num = |e: &Expr, vars: &mut dyn Vars| eval_at(e, vars, d).map(|v| v.unwrap_or(0.0));
    let v = match e {
        Expr::Num(v) => *v,
        Expr::Var(r) => {
            let k = key_at(r, vars, d)?;
            return vars.read(&k);
        }
        Expr::Neg(x) => match eval_at(x, vars, d)? {
            None => return Ok(None),
            Some(v) => -v,
        },
        Expr::Func(f, x) => func(*f, num(x, vars)?, vars.linuxcnc())?,
        Expr::Atan2(a, b) => {
            let deg = num(a, vars)?.atan2(num(b, vars)?).to_degrees();
            if vars.linuxcnc() || deg >= 0.0 {
                deg
            } else {
                deg + 360.0
            }
        }
        Expr::Bin(op, a, b) => {
            let (x, y) = (eval_at(a, vars, d)?, eval_at(b, vars, d)?);
            binary(*op, x, y, vars.linuxcnc())?
        }
        Expr::Chain(first, more) => return chain(first, more, vars, d),
        Expr::Exists(n) => f64::from(u8::from(vars.exists(n))),
    };
    if v.is_finite() {
        Ok(Some(v))
    } else {
        Err(NOT_FINITE.into())
    }
}

const NOT_FINITE: &str = "the expression has no finite value";

/// An [`Expr::Chain`] at `depth`, left to right, in a loop.
fn chain(
    first: &Expr,
    more: &[(BinOp, Expr)],
    vars: &mut dyn Vars,
    depth: usize,
) -> Result<Option<f64>, String> {
    let mut x = eval_at(first, vars, depth)?;
    for (op, b) in more {
        let y = eval_at(b, vars, depth)?;
        let v = binary(*op, x, y, vars.linuxcnc())?;
        if !v.is_finite() {
            return Err(NOT_FINITE.into());
        }
        x = Some(v);
    }
    Ok(x)
}

fn func(f: Func, x: f64, linuxcnc: bool) -> Result<f64, String> {
    let bad = |what: &str| Err(format!("{what} of {} is not defined", compact(x)));
    Ok(match f {
        Func::Sin => x.to_radians().sin(),
        Func::Cos => x.to_radians().cos(),
        Func::Tan => x.to_radians().tan(),
        Func::Asin | Func::Acos if x.abs() > 1.0 => {
            return bad(if f == Func::Asin { "ASIN" } else { "ACOS" })
        }
        Func::Asin => x.asin().to_degrees(),
        Func::Acos => x.acos().to_degrees(),
        Func::Atan => x.atan().to_degrees(),
        Func::Sqrt if x < 0.0 => return bad("SQRT"),
        Func::Sqrt => x.sqrt(),
        Func::Abs => x.abs(),
        Func::Round => x.round(),
        Func::Fix if linuxcnc => x.floor(),
        Func::Fix => x.trunc(),
        Func::Fup if linuxcnc => x.ceil(),
        Func::Fup => x.abs().ceil().copysign(x),
        Func::Exp => x.exp(),
        Func::Ln if x <= 0.0 => return bad("LN"),
        Func::Ln => x.ln(),
    })
}

fn binary(op: BinOp, x: Option<f64>, y: Option<f64>, linuxcnc: bool) -> Result<f64, String> {
    let truth = |b: bool| f64::from(u8::from(b));
    if matches!(op, BinOp::Eq | BinOp::Ne) {
        let same = match (x, y) {
            (None, None) => true,
            (Some(a), Some(b)) => a == b,
            _ => false,
        };
        return Ok(truth(same == (op == BinOp::Eq)));
    }
    let (a, b) = (x.unwrap_or(0.0), y.unwrap_or(0.0));
    let bits = |v: f64| v.round() as i64;
    Ok(match op {
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        BinOp::Mul => a * b,
        BinOp::Div | BinOp::Mod if b == 0.0 => {
            return Err(format!(
                "division by zero ({} {} 0)",
                compact(a),
                if op == BinOp::Div { "/" } else { "MOD" }
            ))
        }
        BinOp::Div => a / b,
        BinOp::Mod => a - b * (a / b).floor(),
        BinOp::Pow => a.powf(b),
        BinOp::Gt => truth(a > b),
        BinOp::Ge => truth(a >= b),
        BinOp::Lt => truth(a < b),
        BinOp::Le => truth(a <= b),
        BinOp::And if linuxcnc => truth(a != 0.0 && b != 0.0),
        BinOp::Or if linuxcnc => truth(a != 0.0 || b != 0.0),
        BinOp::Xor if linuxcnc => truth((a != 0.0) != (b != 0.0)),
        BinOp::And => (bits(a) & bits(b)) as f64,
        BinOp::Or => (bits(a) | bits(b)) as f64,
        BinOp::Xor => (bits(a) ^ bits(b)) as f64,
        BinOp::Eq | BinOp::Ne => 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    struct V(HashMap<u32, f64>, bool);
    impl Vars for V {
        fn read(&mut self, k: &VarKey) -> Result<Option<f64>, String> {
            match k {
                VarKey::Num(n) => Ok(self.0.get(n).copied()),
                VarKey::Named(n) => Err(format!("#<{n}> undefined")),
            }
        }
        fn exists(&self, _: &str) -> bool {
            false
        }
        fn linuxcnc(&self) -> bool {
            self.1
        }
    }

    fn ev(src: &str, linuxcnc: bool) -> Result<Option<f64>, String> {
        let toks = tokenize(src).map_err(|e| e.1)?;
        let mut c = Cursor::new(&toks, src.len() + 1);
        let e = c.expr().map_err(|e| e.1)?;
        assert_eq!(c.i, toks.len(), "{src}: unparsed tail");
        eval(&e, &mut V(HashMap::from([(1, 2.0), (2, -3.5)]), linuxcnc))
    }

    #[test]
    fn precedence_functions_and_vacant() {
        assert_eq!(ev("1+2*3", false), Ok(Some(7.0)));
        assert_eq!(ev("[1+2]*3", false), Ok(Some(9.0)));
        assert_eq!(ev("2**3**2", true), Ok(Some(512.0)));
        assert_eq!(ev("#1*#2", false), Ok(Some(-7.0)));
        assert_eq!(ev("7 MOD 3", false), Ok(Some(1.0)));
        assert_eq!(ev("FIX[-1.5]", false), Ok(Some(-1.0)));
        assert_eq!(ev("FIX[-1.5]", true), Ok(Some(-2.0)));
        assert_eq!(ev("FUP[-1.2]", false), Ok(Some(-2.0)));
        assert_eq!(ev("FUP[-1.2]", true), Ok(Some(-1.0)));
        assert_eq!(ev("ATAN[-1]/[-1]", false), Ok(Some(225.0)));
        assert_eq!(ev("ATAN[-1]/[-1]", true), Ok(Some(-135.0)));
        assert!((ev("SIN[30]", false).unwrap().unwrap() - 0.5).abs() < 1e-15);
        // Vacant #3: 0 in arithmetic, but not EQ 0; EQ #0 is true.
        assert_eq!(ev("#3", false), Ok(None));
        assert_eq!(ev("#3+1", false), Ok(Some(1.0)));
        assert_eq!(ev("#3 EQ 0", false), Ok(Some(0.0)));
        assert_eq!(ev("#3 EQ #0", false), Ok(Some(1.0)));
        assert_eq!(ev("#3 LT 1", false), Ok(Some(1.0)));
        assert_eq!(ev("#1 GT 1 AND #2 LT 0", true), Ok(Some(1.0)));
        assert_eq!(ev("#[#1-1]", false), Ok(Some(2.0)));
    }

    #[test]
    fn operators_group_by_precedence_left_to_right() {
        assert_eq!(ev("2-3-4", false), Ok(Some(-5.0)));
        assert_eq!(ev("8/2/2", false), Ok(Some(2.0)));
        assert_eq!(ev("1+2*3-4/2", false), Ok(Some(5.0)));
        assert_eq!(ev("1+1 EQ 2", false), Ok(Some(1.0)));
        assert_eq!(ev("1 EQ 1 AND 2 GT 1+3", true), Ok(Some(0.0)));
        assert_eq!(ev("3 OR 4 AND 1", false), Ok(Some(1.0)));
        assert_eq!(ev("2*3**2", false), Ok(Some(18.0)));
        assert_eq!(ev("--#1", false), Ok(Some(2.0)));
        assert_eq!(ev("-+-#3", false), Ok(None));
    }

    #[test]
    fn the_evaluator_refuses_a_tree_deeper_than_its_limit() {
        let tower = |n: usize| (0..n).fold(Expr::Num(1.0), |e, _| Expr::Neg(Box::new(e)));
        let mut vars = V(HashMap::new(), false);
        assert_eq!(eval(&tower(MAX_TREE_DEPTH - 1), &mut vars), Ok(Some(-1.0)));
        let e = eval(&tower(MAX_TREE_DEPTH), &mut vars).unwrap_err();
        assert!(e.contains(&format!("deeper than {MAX_TREE_DEPTH}")), "{e}");
    }

    #[test]
    fn errors_name_the_operation() {
        assert!(ev("1/[#1-2]", false)
            .unwrap_err()
            .contains("division by zero"));
        assert!(ev("SQRT[-4]", false).unwrap_err().contains("SQRT of -4"));
        assert!(ev("#[-1]", false)
            .unwrap_err()
            .contains("not a whole number"));
        assert!(ev("FOO[1]", false)
            .unwrap_err()
            .contains("not a macro function"));
    }
}
