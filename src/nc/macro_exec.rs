//! Macro execution: runs the [`Stmt`]s of Fanuc Custom Macro B and
//! LinuxCNC o-word programs block by block over the lexed program with a
//! program counter, and hands each block with evaluated words to the modal
//! interpreter ([`super::program`]).
//!
//! Sources: the Fanuc Series 0i operator's manual, "Custom macro"
//! (`GOTO n`, `IF […] GOTO n`, `IF […] THEN`, `WHILE […] DO m` / `END m`,
//! `G65 P… L…` with argument specification I and II, `#3000` alarm,
//! `#3006` message stop), and the LinuxCNC G-code reference, "O Codes".
//!
//! Readings chosen:
//! - `GOTO n` looks for `N n` in the same program (between `O` headers,
//!   or from the start of a file; [`super::sequence`]) as the GOTO; a
//!   missing target is an error.
//! - Structure (WHILE/END, o-word pairs) is checked before the run; an
//!   unmatched or crossed pair is an error at its line.
//! - A vacant word value (`X#24` with #24 vacant) drops the word, as on a
//!   Fanuc control.
//! - Every backward jump (END, endwhile, endrepeat, a `do … while`, a
//!   backward GOTO, continue) counts as one loop iteration; more than
//!   [`MAX_LOOP_ITERATIONS`] in one run (or the smaller budget of
//!   [`ParseOptions::loop_iteration_budget`](super::program::ParseOptions::loop_iteration_budget))
//!   is an error naming the loop's line.
//! - `#3000=n (MSG)` stops the program with an error carrying the message
//!   at its line; `#3006=n (MSG)` is a warning (the operator restarts).

use std::collections::HashMap;

use super::macro_expr::{eval, key, Expr, VarKey, Vars};
use super::macro_line::{Assign, MWord, OKw, OLabel, Stmt};
use super::macro_vars::Variables;
use super::program::{Modal, Warning};
use super::sequence::Sequences;
use super::{Block, NcError, NcErrors, Word};

pub use crate::budget::MAX_LOOP_ITERATIONS;

/// Deepest o-call / G65 nesting (Fanuc allows 4 levels of G65, LinuxCNC
/// more; 30 catches runaway recursion with a clear message).
pub const MAX_CALL_DEPTH: usize = 30;

/// What the interpreter does after a macro step.
#[derive(Debug, Clone, PartialEq)]
pub enum Step {
    /// Control flow or assignments only.
    Done,
    /// Interpret this block; `computed` when a word was computed.
    Run(Block, bool),
    /// `G65 P… L…`: call O-number `number` `times` times with `args`
    /// (variable number, value) as its locals.
    Call {
        /// The O-number.
        number: u32,
        /// Repeat count (L).
        times: u32,
        /// Locals of the call.
        args: Vec<(u32, f64)>,
        /// The P word (for errors).
        p: Word,
        /// The calling code (`"G65"`, or `"G66"` for a modal call), for
        /// errors.
        via: &'static str,
    },
    /// `G66 P… L…`: register this modal call
    /// ([`super::modal_call`]).
    Modal {
        /// The O-number.
        number: u32,
        /// Repeat count (L).
        times: u32,
        /// Locals of each call.
        args: Vec<(u32, f64)>,
        /// The P word (for errors).
        p: Word,
    },
    /// `G67`: cancel the modal call.
    EndModal,
}

struct OFrame {
    ret: usize,
}

/// Matching structure of the program (computed once).
#[derive(Debug, Default)]
struct Index {
    /// Opener → closer (WHILE→END, sub→endsub, if→endif, while→endwhile,
    /// do→while, repeat→endrepeat) and closer → opener.
    close: HashMap<usize, usize>,
    open: HashMap<usize, usize>,
    /// if / elseif / else → the next branch of the same if.
    next_branch: HashMap<usize, usize>,
    /// break / continue → the loop opener they leave.
    enclosing: HashMap<usize, usize>,
    /// o-label → its `sub` block.
    subs: HashMap<OLabel, usize>,
    /// N numbers and program regions (for GOTO).
    seq: Sequences,
}

/// A running macro program.
pub struct Macros {
    /// The variables.
    pub vars: Variables,
    idx: Index,
    ocalls: Vec<OFrame>,
    repeats: HashMap<usize, u64>,
    iterations: usize,
    /// Most loop iterations of the run (at most [`MAX_LOOP_ITERATIONS`]).
    max_iterations: usize,
    /// Set when the program must stop (alarm, budget).
    pub stop: bool,
    /// The G66 modal call in force.
    pub modal_call: Option<super::modal_call::ModalCall>,
}

struct Ev<'a>(&'a mut Variables);

impl Vars for Ev<'_> {
    fn read(&mut self, k: &VarKey) -> Result<Option<f64>, String> {
        self.0.read(k)
    }
    fn exists(&self, name: &str) -> bool {
        self.0.exists(name)
    }
    fn linuxcnc(&self) -> bool {
        self.0.linuxcnc
    }
}

/// True when any block holds macro code.
pub fn has_macros(blocks: &[Block]) -> bool {
    blocks.iter().any(|b| b.macro_line.is_some())
}

impl Macros {
    /// Prepares `blocks` for running with at most `max_iterations` loop
    /// iterations (capped at [`MAX_LOOP_ITERATIONS`]): checks the loop and
    /// o-word structure.
    ///
    /// # Errors
    /// Every unmatched or crossed WHILE/END or o-word pair, at its line.
    pub fn new(blocks: &[Block], max_iterations: usize) -> Result<Self, NcErrors> {
        let linuxcnc = blocks.iter().any(|b| {
            matches!(b.macro_line.as_deref().map(|m| &m.stmt), Some(Stmt::O(..)))
                || b.macro_line.as_ref().is_some_and(|m| m.src.contains("#<"))
        });
        let idx = index(blocks)?;
        Ok(Self {
            vars: Variables::new(linuxcnc),
            idx,
            ocalls: Vec::new(),
            repeats: HashMap::new(),
            iterations: 0,
            max_iterations: max_iterations.min(MAX_LOOP_ITERATIONS),
            stop: false,
            modal_call: None,
        })
    }

    /// Macro call depth (o-calls; G65 levels are counted by the caller).
    pub fn depth(&self) -> usize {
        self.ocalls.len()
    }

    /// Runs block `bi` (a macro line); `pc` is the index of the next
    /// block and may be changed by control flow.
    ///
    /// # Errors
    /// An expression that cannot be evaluated, a missing GOTO target or
    /// subroutine, an alarm, the loop budget; each at its line and column.
    pub fn step(
        &mut self,
        blocks: &[Block],
        bi: usize,
        pc: &mut usize,
        modal: &Modal,
        warnings: &mut Vec<Warning>,
    ) -> Result<Step, NcError> {
        let b = &blocks[bi];
        self.vars.line = b.line;
        let Some(m) = &b.macro_line else {
            return call_step(b.clone(), false);
        };
        self.vars.modal = *modal;
        let r = self.run_stmt(blocks, bi, &m.stmt, pc);
        warnings.append(&mut self.vars.warnings);
        r
    }

    fn run_stmt(
        &mut self,
        blocks: &[Block],
        bi: usize,
        stmt: &Stmt,
        pc: &mut usize,
    ) -> Result<Step, NcError> {
        let b = &blocks[bi];
        match stmt {
            Stmt::Block(words, assigns) => self.block(b, words, assigns),
            Stmt::Goto(target, col) => {
                self.goto(blocks, bi, target, *col, pc)?;
                Ok(Step::Done)
            }
            Stmt::IfGoto(cond, target, col) => {
                if self.truth(b, cond, *col)? {
                    self.goto(blocks, bi, target, *col, pc)?;
                }
                Ok(Step::Done)
            }
            Stmt::IfThen(cond, assigns) => {
                if self.truth(b, cond, 1)? {
                    self.assign_all(b, assigns)?;
                }
                Ok(Step::Done)
            }
            Stmt::While(cond, _, col) => {
                if !self.truth(b, cond, *col)? {
                    *pc = self.idx.close[&bi] + 1;
                }
                Ok(Step::Done)
            }
            Stmt::End(_, col) => {
                let head = self.idx.open[&bi];
                self.jump_back(blocks, head, *col)?;
                *pc = head;
                Ok(Step::Done)
            }
            Stmt::O(label, kw, args, col) => {
                self.o_word(blocks, bi, label, *kw, args, *col, pc)?;
                Ok(Step::Done)
            }
        }
    }

    fn error(&mut self, b: &Block, col: usize, msg: impl Into<String>) -> NcError {
        NcError::new(b.line, col, msg)
    }

    /// Evaluates `e`; errors name `b`'s line and `col`.
    fn value(&mut self, b: &Block, e: &Expr, col: usize) -> Result<Option<f64>, NcError> {
        eval(e, &mut Ev(&mut self.vars)).map_err(|m| NcError::new(b.line, col, m))
    }

    fn truth(&mut self, b: &Block, e: &Expr, col: usize) -> Result<bool, NcError> {
        Ok(self.value(b, e, col)?.is_some_and(|v| v != 0.0))
    }

    fn block(&mut self, b: &Block, words: &[MWord], assigns: &[Assign]) -> Result<Step, NcError> {
        let mut out = Vec::with_capacity(words.len() + 1);
        out.extend(b.words.iter().cloned());
        let mut computed = false;
        for w in words {
            computed |= w.text.is_none();
            let Some(value) = self.value(b, &w.value, w.column)? else {
                continue;
            };
            let text = w.text.clone().unwrap_or_else(|| number_text(value));
            out.push(Word {
                letter: w.letter,
                value,
                text: text.into(),
                column: w.column,
            });
        }
        self.assign_all(b, assigns)?;
        let block = Block {
            words: out,
            macro_line: None,
            ..b.clone()
        };
        call_step(block, computed)
    }

    /// Evaluates every right-hand side first, then writes (LinuxCNC: the
    /// values of a line are read before any of its assignments).
    fn assign_all(&mut self, b: &Block, assigns: &[Assign]) -> Result<(), NcError> {
        let mut done = Vec::with_capacity(assigns.len());
        for a in assigns {
            let k = key(&a.var, &mut Ev(&mut self.vars))
                .map_err(|m| NcError::new(b.line, a.column, m))?;
            let v = self.value(b, &a.expr, a.column)?;
            done.push((k, v, a.column));
        }
        for (k, v, col) in done {
            if self.system_write(b, &k, v, col)? {
                continue;
            }
            self.vars
                .write(&k, v)
                .map_err(|m| NcError::new(b.line, col, m))?;
        }
        Ok(())
    }

    /// `#3000` alarm (an error that stops the program) and `#3006`
    /// message stop (a warning); true when handled.
    fn system_write(
        &mut self,
        b: &Block,
        k: &VarKey,
        v: Option<f64>,
        col: usize,
    ) -> Result<bool, NcError> {
        if self.vars.linuxcnc {
            return Ok(false);
        }
        let msg = b.comments.first().cloned().unwrap_or_default();
        let n = v.map_or(String::from("vacant"), number_text);
        match k {
            VarKey::Num(3000) => {
                self.stop = true;
                Err(self.error(
                    b,
                    col,
                    format!("macro alarm #3000={n}: {msg} (the program stops here on the control)"),
                ))
            }
            VarKey::Num(3006) => {
                self.vars.warnings.push(Warning {
 file: None,
                    line: b.line,
                    column: col,
                    message: format!("message stop #3006={n}: {msg} (the control stops until cycle start; simulated as continuing)"),
                });
                Ok(true)
            }
            _ => Ok(false),
        }
    }

    fn jump_back(&mut self, blocks: &[Block], head: usize, col: usize) -> Result<(), NcError> {
        self.iterations += 1;
        let limit = self.max_iterations;
        if self.iterations > limit {
            self.stop = true;
            let b = &blocks[head];
            return Err(self.error(
                b,
                head_col(b, col),
                format!("the loop starting at line {} ran more than {limit} iterations; check its condition and the variable it changes", b.line),
            ));
        }
        Ok(())
    }

    fn goto(
        &mut self,
        blocks: &[Block],
        bi: usize,
        target: &Expr,
        col: usize,
        pc: &mut usize,
    ) -> Result<(), NcError> {
        let b = &blocks[bi];
        let n = self
            .value(b, target, col)?
            .ok_or_else(|| NcError::new(b.line, col, "GOTO to a vacant sequence number"))?;
        let r = n.round();
        let found = self.idx.seq.first_in_region(r as i64, bi);
        let Some(t) = found.filter(|_| (n - r).abs() < 1e-6) else {
            return Err(self.error(b, col, format!("GOTO {}: no block N{} in this program; expected a sequence number of a block in the same O-program", number_text(n), number_text(r))));
        };
        if t <= bi {
            self.jump_back(blocks, t, col)?;
        }
        *pc = t;
        Ok(())
    }
}

/// A computed value as word text: whole numbers without a point (so `G`,
/// `M`, `P` read as written), others with up to 6 decimals.
pub fn number_text(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        let s = format!("{v:.6}");
        s.trim_end_matches('0').to_string()
    }
}

/// The macro-call word of `b` (G65, G66 or G67), if any.
pub fn call_code(b: &Block) -> Option<&Word> {
    b.words
        .iter()
        .find(|w| w.letter == 'G' && matches!(w.value, 65.0 | 66.0 | 67.0))
}

/// The step of a block as written or evaluated: a G65 call, a G66
/// registration, a G67 cancel ([`super::modal_call`]), or a block to run.
fn call_step(block: Block, computed: bool) -> Result<Step, NcError> {
    let Some(g) = call_code(&block) else {
        return Ok(Step::Run(block, computed));
    };
    if g.value == 67.0 {
        super::modal_call::check_g67(&block)?;
        return Ok(Step::EndModal);
    }
    match macro_call(&block, g)? {
        Step::Call {
            number,
            times,
            args,
            p,
            ..
        } if g.value == 66.0 => Ok(Step::Modal {
            number,
            times,
            args,
            p,
        }),
        step => Ok(step),
    }
}

/// `G65 P… L… <arguments>` (and G66's, the same words): argument specification I (A→#1, B→#2, C→#3,
/// I→#4, J→#5, K→#6, D→#7, E→#8, F→#9, H→#11, M→#13, Q→#17, R→#18,
/// S→#19, T→#20, U→#21, V→#22, W→#23, X→#24, Y→#25, Z→#26); a repeated
/// I/J/K follows specification II (the k-th I, J, K → #4+3k, #5+3k,
/// #6+3k).
fn macro_call(b: &Block, g65: &Word) -> Result<Step, NcError> {
    let code = if g65.value == 66.0 { "G66" } else { "G65" };
    let p = b.word('P').ok_or_else(|| {
        NcError::new(
            b.line,
            g65.column,
            format!("{code} without P; expected {code} P<program number>"),
        )
    })?;
    if p.value < 0.0 || p.value.fract() != 0.0 || p.value > 99_999_999.0 {
        return Err(NcError::new(
            b.line,
            p.column,
            format!("{code} P{}: expected a whole program number", p.text),
        ));
    }
    let times = match b.word('L') {
        Some(l) if l.value >= 1.0 && l.value.fract() == 0.0 && l.value <= 9999.0 => l.value as u32,
        Some(l) => {
            return Err(NcError::new(
                b.line,
                l.column,
                format!("{code} L{}: expected a repeat count from 1 to 9999", l.text),
            ))
        }
        None => 1,
    };
    let args = call_args(b, g65, code)?;
    Ok(Step::Call {
        number: p.value as u32,
        times,
        args,
        p: p.clone(),
        via: code,
    })
}

/// The arguments of a G65/G66 block `b` (call word `g65`, `code` its
/// name for errors): specification I, and II for repeated I/J/K.
fn call_args(b: &Block, g65: &Word, code: &str) -> Result<Vec<(u32, f64)>, NcError> {
    let mut args: Vec<(u32, f64)> = Vec::new();
    let mut ijk = [0u32; 3];
    for w in &b.words {
        let n = match w.letter {
            'G' if w.value == g65.value => continue,
            'G' => {
                return Err(NcError::new(
                    b.line,
                    w.column,
                    format!(
                        "G{} on a {code} block: a macro-call block takes only P, L and arguments; put G{} on its own block",
                        w.text, w.text
                    ),
                ))
            }
            'P' | 'L' | 'N' | 'O' => continue,
            'I' | 'J' | 'K' => {
                let k = (w.letter as u8 - b'I') as usize;
                let n = 4 + k as u32 + 3 * ijk[k];
                ijk[k] += 1;
                n
            }
            c => match "ABC".find(c) {
                Some(i) => i as u32 + 1,
                None => match "DEF_H_M___QRSTUVWXYZ".find(c) {
                    Some(i) if c != '_' => i as u32 + 7,
                    _ => {
                        return Err(NcError::new(
                            b.line,
                            w.column,
                            format!(
                            "{}{} is not a {code} argument (arguments are A–Z except G, L, N, O, P)",
                            w.letter, w.text
                        ),
                        ))
                    }
                },
            },
        };
        if n > 33 {
            return Err(NcError::new(
                b.line,
                w.column,
                "too many I/J/K arguments (argument specification II allows 10 sets)",
            ));
        }
        args.push((n, w.value));
    }
    Ok(args)
}

impl Macros {
    #[allow(clippy::too_many_arguments)]
    fn o_word(
        &mut self,
        blocks: &[Block],
        bi: usize,
        label: &OLabel,
        kw: OKw,
        args: &[Expr],
        col: usize,
        pc: &mut usize,
    ) -> Result<(), NcError> {
        let b = &blocks[bi];
        let close = |s: &Self| s.idx.close.get(&bi).copied().unwrap_or(bi);
        let arg0 = |s: &mut Self| match args.first() {
            Some(e) => s.value(b, e, col).map(|v| v.unwrap_or(0.0)),
            None => Err(NcError::new(
                b.line,
                col,
                format!(
                    "{label} {}: expected a condition or count in [ ]",
                    kw_name(kw)
                ),
            )),
        };
        match kw {
            OKw::Sub => *pc = close(self) + 1,
            OKw::EndSub | OKw::Return => self.o_return(b, args, col, pc)?,
            OKw::Call => self.o_call(blocks, bi, label, args, col, pc)?,
            OKw::If => {
                if arg0(self)? == 0.0 {
                    self.next_branch(blocks, bi, pc)?;
                }
            }
            OKw::ElseIf | OKw::Else => *pc = self.endif_of(bi) + 1,
            OKw::EndIf | OKw::Do => {}
            OKw::While if self.idx.open.contains_key(&bi) => {
                // The end of a do … while loop.
                if arg0(self)? != 0.0 {
                    let head = self.idx.open[&bi];
                    self.jump_back(blocks, head, col)?;
                    *pc = head + 1;
                }
            }
            OKw::While => {
                if arg0(self)? == 0.0 {
                    *pc = close(self) + 1;
                }
            }
            OKw::EndWhile => {
                let head = self.idx.open[&bi];
                self.jump_back(blocks, head, col)?;
                *pc = head;
            }
            OKw::Repeat => {
                let n = arg0(self)?;
                if n >= 1.0 {
                    self.repeats.insert(bi, n.floor() as u64);
                } else {
                    *pc = close(self) + 1;
                }
            }
            OKw::EndRepeat => self.end_repeat(blocks, bi, col, pc)?,
            OKw::Break | OKw::Continue => self.leave_loop(blocks, bi, kw, col, pc)?,
        }
        Ok(())
    }

    fn end_repeat(
        &mut self,
        blocks: &[Block],
        bi: usize,
        col: usize,
        pc: &mut usize,
    ) -> Result<(), NcError> {
        let head = self.idx.open[&bi];
        let left = self.repeats.get(&head).copied().unwrap_or(1);
        if left > 1 {
            self.repeats.insert(head, left - 1);
            self.jump_back(blocks, head, col)?;
            *pc = head + 1;
        } else {
            self.repeats.remove(&head);
        }
        Ok(())
    }

    fn leave_loop(
        &mut self,
        blocks: &[Block],
        bi: usize,
        kw: OKw,
        col: usize,
        pc: &mut usize,
    ) -> Result<(), NcError> {
        let head = self.idx.enclosing[&bi];
        let end = self.idx.close[&head];
        if kw == OKw::Break {
            self.repeats.remove(&head);
            *pc = end + 1;
            return Ok(());
        }
        let head_kw = o_kw(&blocks[head]);
        if head_kw == Some(OKw::While) {
            self.jump_back(blocks, head, col)?;
            *pc = head;
        } else {
            // do … while and repeat: the closing block decides.
            *pc = end;
        }
        Ok(())
    }

    /// From a false `if`/`elseif` at `bi`: on to the next branch whose
    /// condition holds, an `else`, or past the `endif`.
    fn next_branch(
        &mut self,
        blocks: &[Block],
        mut bi: usize,
        pc: &mut usize,
    ) -> Result<(), NcError> {
        loop {
            let Some(&j) = self.idx.next_branch.get(&bi) else {
                *pc = bi + 1;
                return Ok(());
            };
            let b = &blocks[j];
            match b.macro_line.as_deref().map(|m| &m.stmt) {
                Some(Stmt::O(_, OKw::ElseIf, args, col)) => {
                    let cond = args.first().ok_or_else(|| {
                        NcError::new(b.line, *col, "elseif: expected a condition in [ ]")
                    })?;
                    if self.truth(b, cond, *col)? {
                        *pc = j + 1;
                        return Ok(());
                    }
                    bi = j;
                }
                _ => {
                    *pc = j + 1;
                    return Ok(());
                }
            }
        }
    }

    fn endif_of(&self, mut bi: usize) -> usize {
        while let Some(&j) = self.idx.next_branch.get(&bi) {
            bi = j;
        }
        bi
    }

    fn o_call(
        &mut self,
        blocks: &[Block],
        bi: usize,
        label: &OLabel,
        args: &[Expr],
        col: usize,
        pc: &mut usize,
    ) -> Result<(), NcError> {
        let b = &blocks[bi];
        let Some(&sub) = self.idx.subs.get(label) else {
            return Err(self.error(b, col, format!("{label} call: subroutine {label} is not in this program; paste its '{label} sub … endsub' before the call, or drop its file together with the program")));
        };
        if self.ocalls.len() >= MAX_CALL_DEPTH {
            self.stop = true;
            return Err(self.error(b, col, format!("{label} call: subroutine calls nested deeper than {MAX_CALL_DEPTH} levels (endless recursion?)")));
        }
        let mut values = Vec::with_capacity(args.len());
        for (i, e) in args.iter().enumerate() {
            let v = self.value(b, e, col)?.unwrap_or(0.0);
            values.push((i as u32 + 1, v));
        }
        if values.len() > 30 {
            return Err(self.error(b, col, "more than 30 call arguments (#1–#30)"));
        }
        self.vars.push_level(&values);
        self.ocalls.push(OFrame { ret: bi + 1 });
        *pc = sub + 1;
        Ok(())
    }

    fn o_return(
        &mut self,
        b: &Block,
        args: &[Expr],
        col: usize,
        pc: &mut usize,
    ) -> Result<(), NcError> {
        let value = match args.first() {
            Some(e) => self.value(b, e, col)?,
            None => None,
        };
        let Some(f) = self.ocalls.pop() else {
            return Err(self.error(b, col, "endsub/return outside a called subroutine"));
        };
        self.vars.pop_level();
        if let Some(v) = value {
            let _ = self.vars.write(&VarKey::Named("_value".into()), Some(v));
        }
        *pc = f.ret;
        Ok(())
    }
}

/// The column of a loop head's keyword (`WHILE`, `while`, `do`,
/// `repeat`), or `col` for a GOTO target.
fn head_col(b: &Block, col: usize) -> usize {
    match b.macro_line.as_deref().map(|m| &m.stmt) {
        Some(Stmt::While(_, _, c) | Stmt::O(_, _, _, c)) => *c,
        Some(Stmt::Block(..)) | None => b.words.first().map_or(1, |w| w.column),
        _ => col,
    }
}

fn kw_name(kw: OKw) -> String {
    format!("{kw:?}").to_ascii_lowercase()
}

fn o_kw(b: &Block) -> Option<OKw> {
    match b.macro_line.as_deref().map(|m| &m.stmt) {
        Some(Stmt::O(_, kw, _, _)) => Some(*kw),
        _ => None,
    }
}

/// An open structure while indexing: block index, label or loop number,
/// keyword.
struct Open {
    at: usize,
    label: Option<OLabel>,
    kw: OKw,
}

/// Builds the [`Index`]; every structure error is collected.
fn index(blocks: &[Block]) -> Result<Index, NcErrors> {
    let mut idx = Index::default();
    let mut errors = NcErrors {
        errors: Vec::new(),
        truncated: false,
    };
    let mut stack: Vec<Open> = Vec::new();
    idx.seq = Sequences::new(blocks);
    for (i, b) in blocks.iter().enumerate() {
        let Some(m) = &b.macro_line else { continue };
        let r = match &m.stmt {
            Stmt::While(_, id, _) => {
                stack.push(Open {
                    at: i,
                    label: Some(OLabel::Num(*id)),
                    kw: OKw::While,
                });
                Ok(())
            }
            Stmt::End(id, col) => close_fanuc(&mut idx, &mut stack, blocks, i, *id, *col),
            Stmt::O(label, kw, _, col) => {
                index_o(&mut idx, &mut stack, blocks, i, label, *kw, *col)
            }
            _ => Ok(()),
        };
        if let Err(e) = r {
            errors.push(e);
        }
    }
    for o in stack {
        let b = &blocks[o.at];
        let what = match (&o.label, o.kw) {
            (Some(OLabel::Num(n)), OKw::While)
                if !matches!(&b.macro_line.as_deref().map(|m| &m.stmt), Some(Stmt::O(..))) =>
            {
                format!("WHILE … DO{n} has no END{n}")
            }
            (Some(l), kw) => format!("{l} {} is never closed", kw_name(kw)),
            (None, kw) => format!("{} is never closed", kw_name(kw)),
        };
        errors.push(NcError::new(b.line, 1, what));
    }
    if errors.is_empty() {
        Ok(idx)
    } else {
        errors.errors.sort_by_key(|e| (e.line, e.column));
        Err(errors)
    }
}

fn close_fanuc(
    idx: &mut Index,
    stack: &mut Vec<Open>,
    blocks: &[Block],
    i: usize,
    id: u32,
    col: usize,
) -> Result<(), NcError> {
    let line = blocks[i].line;
    match stack.last() {
        Some(o) if o.kw == OKw::While && o.label == Some(OLabel::Num(id)) && o_kw(&blocks[o.at]).is_none() => {
            let o = stack.pop().map_or(i, |o| o.at);
            idx.close.insert(o, i);
            idx.open.insert(i, o);
            Ok(())
        }
        _ => Err(NcError::new(line, col, format!("END{id} without a matching WHILE … DO{id} (loops must nest: the innermost WHILE ends first)"))),
    }
}

/// Indexes o-word block `i` (`label`, keyword `kw`, at column `col`):
/// opens a sub/if/do/while/repeat, links an elseif/else/endif to the
/// branch before it, pairs an end keyword with its opener, links a
/// break/continue to its loop.
///
/// # Errors
/// A subroutine defined twice, a break/continue outside a loop of its
/// label, an end keyword that closes nothing open (blocks must nest).
fn index_o(
    idx: &mut Index,
    stack: &mut Vec<Open>,
    blocks: &[Block],
    i: usize,
    label: &OLabel,
    kw: OKw,
    col: usize,
) -> Result<(), NcError> {
    let line = blocks[i].line;
    let top_is = |stack: &Vec<Open>, kws: &[OKw]| {
        stack.last().is_some_and(|o| {
            o.label.as_ref() == Some(label) && kws.contains(&o.kw) && o_kw(&blocks[o.at]).is_some()
        })
    };
    let open = |stack: &mut Vec<Open>| {
        stack.push(Open {
            at: i,
            label: Some(label.clone()),
            kw,
        });
        Ok(())
    };
    match kw {
        OKw::Sub => {
            if idx.subs.insert(label.clone(), i).is_some() {
                return Err(NcError::new(
                    line,
                    col,
                    format!("{label} sub: the subroutine is defined twice"),
                ));
            }
            open(stack)
        }
        OKw::If | OKw::Do | OKw::Repeat => open(stack),
        OKw::While if top_is(stack, &[OKw::Do]) => pair(idx, stack, i),
        OKw::While => open(stack),
        OKw::ElseIf | OKw::Else if top_is(stack, &[OKw::If, OKw::ElseIf]) => {
            let prev = stack.pop().map_or(i, |o| o.at);
            idx.next_branch.insert(prev, i);
            open(stack)
        }
        OKw::EndIf if top_is(stack, &[OKw::If, OKw::ElseIf, OKw::Else]) => {
            let prev = stack.pop().map_or(i, |o| o.at);
            idx.next_branch.insert(prev, i);
            Ok(())
        }
        OKw::EndSub if top_is(stack, &[OKw::Sub]) => pair(idx, stack, i),
        OKw::EndWhile if top_is(stack, &[OKw::While]) => pair(idx, stack, i),
        OKw::EndRepeat if top_is(stack, &[OKw::Repeat]) => pair(idx, stack, i),
        OKw::Break | OKw::Continue => enclosing_loop(idx, stack, i, label).ok_or_else(|| {
            NcError::new(
                line,
                col,
                format!(
                    "{label} {}: no enclosing {label} while/do/repeat loop",
                    kw_name(kw)
                ),
            )
        }),
        OKw::Return | OKw::Call => Ok(()),
        _ => Err(NcError::new(
            line,
            col,
            format!(
                "{label} {} does not close an open {label} block (o-word blocks must nest)",
                kw_name(kw)
            ),
        )),
    }
}

/// Links an o-word `break`/`continue` (block `i`) to the innermost open
/// while/do/repeat loop of the same label; `None` when there is none.
fn enclosing_loop(idx: &mut Index, stack: &[Open], i: usize, label: &OLabel) -> Option<()> {
    let head = stack.iter().rev().find(|o| {
        o.label.as_ref() == Some(label) && matches!(o.kw, OKw::While | OKw::Do | OKw::Repeat)
    })?;
    idx.enclosing.insert(i, head.at);
    Some(())
}

fn pair(idx: &mut Index, stack: &mut Vec<Open>, i: usize) -> Result<(), NcError> {
    let o = stack.pop().map_or(i, |o| o.at);
    idx.close.insert(o, i);
    idx.open.insert(i, o);
    Ok(())
}
