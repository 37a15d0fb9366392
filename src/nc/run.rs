//! The interpreter's run over a program's blocks (FANUC-style execution
//! order): the program counter; the program end (M2/M30, the end of the
//! main file) and the blocks after it; block delete; the executed-block
//! budget; macro steps (Fanuc Macro B, LinuxCNC o-words, G65 calls with
//! their own local variables); subprogram calls and returns with repeat
//! counts and nesting up to [`super::program::MAX_NESTING`] levels. After
//! the last block it gives
//! every block its modal state, marks the segments of blocks run more than
//! once `fixed`, applies the Fanuc corners ([`super::corner`]) and then
//! the cutter-compensation offsets ([`super::cutter_path`], each segment
//! tagged with the G41/G42 stretch in force after its block). The
//! readings are those of the interpreter's header ([`super::program`]).
//!
//! Calls and returns (one machinery for both call targets, [`Target`]):
//! - `M98 P… (L…/K…)` calls the `O` program P (Fanuc: a P of more than
//!   four digits holds the repeat count before the program number);
//! - `M97 P… (L…/K…)` (Haas) calls the block numbered N P of the calling
//!   O-program, its "local subprogram" (usually after M30), which runs
//!   until M99; the repeat count, the budgets and the nesting limit are
//!   those of M98, and the two nest inside each other;
//! - `M99` repeats the called body while repeats are left, then returns to
//!   the block after the call;
//! - `M99 P n` in a called body returns, after the last repeat, to the
//!   block numbered N n of the calling program instead (Fanuc's operator's
//!   manual, "Subprogram call": control returns to the block with the
//!   sequence number P, not to the block after the call). The manual does
//!   not give the search order; the reading here is Fanuc's forward
//!   sequence-number search: from the block after the call to the end of
//!   the calling O-program, then from its start. A missing N is an error
//!   at the P word, and the run returns to the block after the call;
//! - `M99` in the main program restarts it endlessly on a control: warned
//!   and simulated once (the run ends there). `M99 P n` in the main program
//!   jumps to N n: forwards (N n after the M99) the run goes on there;
//!   backwards (N n at or before the M99) it would repeat endlessly, so it
//!   is warned about and the run ends, as for a plain M99.

use std::collections::HashMap;

use super::block::interpret_block;
use super::block_modes::BlockModes;
use super::fadal::Subroutines;
use super::gcodes::code10;
use super::macro_exec::{has_macros, Macros, Step};
use super::program::{
    err, Corner, Ctx, CutterStretch, Keep, Modal, ParseOptions, Program, Segment, Warning,
    MAX_NESTING,
};
use super::sequence::Sequences;
use super::{Block, NcError, NcErrors, Word};

/// The state of one run over a program's blocks.
pub(super) struct Run<'a> {
    /// Options, the C axis resolved.
    opt: &'a ParseOptions,
    /// The modal state now.
    st: Modal,
    segments: Vec<Segment>,
    warnings: Vec<Warning>,
    errors: NcErrors,
    corners: Vec<Corner>,
    /// Modal state after each block (`None`: not run yet); empty when the
    /// run keeps none ([`Keep::Motion`]).
    modal: Vec<Option<Modal>>,
    /// The writer's modes after each block (empty when the run keeps
    /// none, [`Keep::Motion`]).
    modes: BlockModes,
    /// What the program keeps for a writer.
    keep: Keep,
    /// Moves were made in mm (`[0]`) and in inch (`[1]`) units.
    moved_units: [bool; 2],
    /// The blocks after the program end have been warned about.
    after_end_warned: bool,
    /// O-number → index of its `O` block.
    subs: HashMap<u32, usize>,
    /// N numbers and program regions (M97 targets, M99 P returns).
    seqs: Sequences,
    /// Active subprogram and macro calls, innermost last.
    stack: Vec<Frame>,
    /// Blocks executed so far (repeats counted).
    executed: usize,
    /// Index of the next block to run.
    pub pc: usize,
    /// The macro interpreter, when the program holds macro code.
    mac: Option<Macros>,
    /// How often each block was run.
    runs: Vec<u32>,
    /// Cutter-compensation stretches so far.
    stretches: Vec<CutterStretch>,
    /// The stretch in force for each segment (same length as `segments`).
    tags: Vec<Option<usize>>,
    /// The G5.2 NURBS block open ([`super::spline`]).
    nurbs: Option<super::spline::OpenNurbs>,
    /// The Fadal subroutines the program defines.
    fadal: Subroutines,
}

/// What a call runs: an `O` program (M98, G65) or the block numbered N…
/// of the calling program (Haas M97).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Target {
    /// The program `O` number.
    Program(u32),
    /// The local subprogram starting at block `N` number.
    Sequence(u32),
    /// The Fadal subroutine `nn` ([`super::fadal`]).
    Fadal(u32),
}

impl std::fmt::Display for Target {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Target::Program(n) => write!(f, "subprogram O{n}"),
            Target::Sequence(n) => write!(f, "local subprogram N{n} (M97)"),
            Target::Fadal(n) => write!(f, "Fadal subroutine {n}"),
        }
    }
}

/// An active subprogram or macro call.
struct Frame {
    /// Index of the block to return to.
    ret: usize,
    /// Index of the called body's first block (its `O` or `N` block).
    start: usize,
    /// Runs of the called program still to go, this one included.
    left: u32,
    /// What was called.
    target: Target,
    /// A G65 call: its own local variables, dropped at M99.
    locals: bool,
}

/// What the interpreter loop does after a macro step.
enum Flow {
    /// Run this block (evaluated words; true when they were computed).
    Run(Block, bool),
    /// Go on with the next block (the program counter is set).
    Next,
    /// Stop the run.
    Stop,
}

impl<'a> Run<'a> {
    /// A run at the first block of `blocks`, from `opt.start`.
    ///
    /// # Errors
    /// The macro code's structure errors ([`Macros::new`]) and the Fadal
    /// subroutine definitions' ([`Subroutines::new`]).
    pub fn new(blocks: &[Block], opt: &'a ParseOptions, keep: Keep) -> Result<Self, NcErrors> {
        let fadal = Subroutines::new(blocks).map_err(|es| {
            let mut errors = NcErrors {
                errors: Vec::new(),
                truncated: false,
            };
            for e in es {
                errors.push(e);
            }
            errors
        })?;
        Ok(Self {
            opt,
            st: Modal {
                pos: opt.start,
                inch: opt.units == super::program::Units::Inch,
                ..Modal::default()
            },
            // most blocks with words give one segment: one allocation, not
            // a doubling copy (2 M segments are 350 MB)
            segments: Vec::with_capacity(blocks.iter().filter(|b| !b.words.is_empty()).count()),
            warnings: Vec::new(),
            errors: NcErrors {
                errors: Vec::new(),
                truncated: false,
            },
            corners: Vec::new(),
            modal: match keep {
                Keep::All => vec![None; blocks.len()],
                Keep::Motion | Keep::Patch => Vec::new(),
            },
            modes: match keep {
                Keep::All | Keep::Patch => BlockModes::with_blocks(blocks.len()),
                Keep::Motion => BlockModes::default(),
            },
            keep,
            moved_units: [false; 2],
            after_end_warned: false,
            subs: subprogram_index(blocks),
            seqs: Sequences::new(blocks),
            stack: Vec::new(),
            executed: 0,
            pc: 0,
            mac: if needs_macros(blocks) {
                Some(Macros::new(blocks, opt.loop_iteration_budget())?)
            } else {
                None
            },
            runs: vec![0u32; blocks.len()],
            stretches: Vec::new(),
            tags: Vec::new(),
            nurbs: None,
            fadal,
        })
    }

    /// Runs the block at the program counter and moves the counter on
    /// (past it, or to a call's target or return point). False when the
    /// run stops here.
    pub fn step(&mut self, blocks: &[Block]) -> bool {
        let bi = self.pc;
        let b = &blocks[bi];
        self.pc += 1;
        if let Some(e) = left_file(blocks, b, &self.stack, self.mac.as_ref()) {
            if let Some(e) = e {
                self.errors.push(e);
            }
            return false;
        }
        if self.st.ended {
            self.after_end(b, bi);
            return true;
        }
        if let Some(e) = self.entry_error(b, bi) {
            self.errors.push(e);
            return false;
        }
        if b.block_delete && self.opt.skip_block_delete {
            self.warnings.push(Warning::at(
                b.line,
                1,
                "block delete '/': this block is skipped (set skipBlockDelete: false to run it)",
            ));
            self.record(bi);
            return true;
        }
        self.runs[bi] = self.runs[bi].saturating_add(1);
        if self.fadal_call_or_definition(blocks, bi) {
            self.record(bi);
            return true;
        }
        let evaluated;
        let mut computed = false;
        let b = match self.macro_step(blocks, bi) {
            None => b,
            Some(Flow::Run(nb, c)) => {
                evaluated = nb;
                computed = c;
                &evaluated
            }
            Some(Flow::Next) => {
                self.record(bi);
                return true;
            }
            Some(Flow::Stop) => return false,
        };
        let without_m17;
        let b = if self.fadal_end(bi) {
            without_m17 = super::fadal::without_m17(b);
            &without_m17
        } else {
            b
        };
        let made = self.segments.len();
        if !self.run_block(b, bi, computed) {
            return false;
        }
        if self.segments.len() > made {
            self.moved_units[usize::from(self.st.inch)] = true;
        }
        self.record(bi);
        self.call_or_return(b, bi);
        if !self.modal_call_after(b) {
            return false;
        }
        if self.st.ended {
            self.stack.clear();
        }
        true
    }

    /// A block after M2/M30: not run; the first non-empty one (other than
    /// a program number, `%` or a block an M97 call ran) is warned about.
    fn after_end(&mut self, b: &Block, bi: usize) {
        if !self.after_end_warned && !b.is_empty() && !b.percent && self.runs[bi] == 0 {
            self.after_end_warned = true;
            if b.word('O').is_none() && b.program_name.is_none() {
                self.warnings.push(Warning::at(
                    b.line,
                    1,
                    "blocks after the program end (M2/M30) are not run",
                ));
            }
        }
        if let Some(m) = self.modal.get_mut(bi) {
            m.get_or_insert(self.st);
        }
        self.modes.record(bi, &self.st, true);
    }

    /// Records the modal state after block `bi` (when the run keeps them).
    fn record(&mut self, bi: usize) {
        if let Some(m) = self.modal.get_mut(bi) {
            *m = Some(self.st);
        }
        self.modes.record(bi, &self.st, false);
    }

    /// Counts the block against the executed-block budget; the error that
    /// stops the run when the budget is spent or a subprogram runs into the
    /// next program's `O` block without M99.
    fn entry_error(&mut self, b: &Block, bi: usize) -> Option<NcError> {
        self.executed += 1;
        let budget = self.opt.executed_block_budget();
        if self.executed > budget {
            return Some(NcError::new(
                b.line,
                1,
                format!(
                    "more than {budget} blocks executed: the subprogram calls, repeats or loops look endless; check the M97/M98 repeat counts, the M99 returns and the loop conditions"
                ),
            ));
        }
        let (f, o) = (
            self.stack.last()?,
            b.words.first().filter(|w| w.letter == 'O')?,
        );
        (bi != f.start).then(|| {
            err(
                b,
                o,
                format!(
                    "{} reaches the next program O{} without an M99; expected M99 at the end of each subprogram",
                    f.target, o.text
                ),
            )
        })
    }

    /// After block `b`: the G66 modal call, when one is in force, `b`
    /// moves, and `b` runs at the level that set it
    /// ([`super::modal_call`]). False when the call stops the program.
    fn modal_call_after(&mut self, b: &Block) -> bool {
        let Some(m) = self.mac.as_mut() else {
            return true;
        };
        let step = match &m.modal_call {
            Some(mc)
                if mc.level == self.stack.len() + m.depth() && super::modal_call::is_move(b) =>
            {
                mc.step(b)
            }
            _ => return true,
        };
        // A missing program is reported at the move that calls it.
        m.vars.line = b.line;
        !matches!(
            macro_flow(
                Ok(step),
                m,
                &self.subs,
                &mut self.stack,
                &mut self.pc,
                &mut self.errors,
            ),
            Flow::Stop
        )
    }

    /// The macro interpreter's step on a macro or G65 block (`None` for any
    /// other block: it runs as written).
    fn macro_step(&mut self, blocks: &[Block], bi: usize) -> Option<Flow> {
        let b = &blocks[bi];
        let m = self
            .mac
            .as_mut()
            .filter(|_| b.macro_line.is_some() || has_call_code(b))?;
        let r = m.step(blocks, bi, &mut self.pc, &self.st, &mut self.warnings);
        Some(macro_flow(
            r,
            m,
            &self.subs,
            &mut self.stack,
            &mut self.pc,
            &mut self.errors,
        ))
    }

    /// Interprets block `b` (index `bi`; `computed`: its words came from
    /// macro expressions); its segments are `fixed` inside a call or when
    /// computed. False when its error stops the program.
    fn run_block(&mut self, b: &Block, bi: usize, computed: bool) -> bool {
        let before = self.segments.len();
        let mut ctx = Ctx {
            bi,
            opt: self.opt,
            warnings: &mut self.warnings,
            segments: &mut self.segments,
            corners: &mut self.corners,
            stretches: &mut self.stretches,
            nurbs: &mut self.nurbs,
        };
        let result = interpret_block(b, &mut self.st, &mut ctx);
        self.tags
            .resize(self.segments.len(), self.st.cutter.map(|c| c.stretch));
        if let Err(e) = result {
            let stop = e.message.contains("this looks like");
            self.errors.push(e);
            if stop {
                return false;
            }
        }
        if let Some(why) = self.segments[before..]
            .iter()
            .find_map(|s| s.out_of_range())
        {
            self.errors.push(NcError::new(
                b.line,
                1,
                format!("{why}: no machine moves there; check the units (G20/G21), the numbers and G91 increments"),
            ));
            return false;
        }
        let budget = self.opt.segment_budget();
        if self.segments.len() > budget {
            self.errors.push(NcError::new(
                b.line,
                1,
                format!(
                    "more than {budget} segments: the canned-cycle holes and pecks, subprogram calls or loops make too many moves; check the K/L hole counts, the Q peck depths, the M97/M98 repeat counts and the loop conditions (a program with more moves than that: split it into parts)"
                ),
            ));
            return false;
        }
        if !self.stack.is_empty() || computed || self.mac.as_ref().is_some_and(|m| m.depth() > 0) {
            for s in &mut self.segments[before..] {
                s.fixed = true;
            }
        }
        true
    }

    /// A Fadal definition reached by the run (skipped past its `M17`, and
    /// past the end-of-definitions `M30` that may follow) or a Fadal call
    /// (a frame pushed; a bad call is an error and the run goes on after
    /// it). False for any other block.
    fn fadal_call_or_definition(&mut self, blocks: &[Block], bi: usize) -> bool {
        if let Some(d) = self.fadal.starting_at(bi) {
            self.pc = d.skip_to;
            if let Some(m) = d.marker.map(|k| &blocks[k]) {
                self.warnings.push(Warning::at(
                    m.line,
                    m.words.iter().find(|w| w.letter == 'M').map_or(1, |w| w.column),
                    "M2/M30 right after the Fadal subroutine definitions ends the definitions; the main program runs from the block after it",
                ));
            }
            return true;
        }
        let b = &blocks[bi];
        let Some((w, n, times)) = super::fadal::call(b) else {
            return false;
        };
        match self.fadal_target(b, w, n) {
            Ok(start) => {
                self.stack.push(Frame {
                    ret: self.pc,
                    start,
                    left: times,
                    target: Target::Fadal(n),
                    locals: false,
                });
                self.pc = start;
            }
            Err(e) => self.errors.push(e),
        }
        true
    }

    /// The first body block of Fadal subroutine `n`, called by `w` on
    /// block `b`: refused when it is not defined, calls itself or nests
    /// too deep.
    fn fadal_target(&self, b: &Block, w: &Word, n: u32) -> Result<usize, NcError> {
        let Some(d) = self.fadal.get(n) else {
            return Err(err(
                b,
                w,
                format!(
                    "L{} calls Fadal subroutine {n}, which this program does not define; define it before the main program (L{n:02}00, its blocks, M17)",
                    w.text
                ),
            ));
        };
        if self.stack.iter().any(|f| f.target == Target::Fadal(n)) {
            return Err(err(
                b,
                w,
                format!(
                    "L{} calls Fadal subroutine {n} from inside itself: the calls would never end on the control",
                    w.text
                ),
            ));
        }
        if self.stack.len() >= super::fadal::NESTING {
            return Err(err(
                b,
                w,
                format!(
                    "L{}: Fadal subroutine calls nested deeper than {} levels",
                    w.text,
                    super::fadal::NESTING
                ),
            ));
        }
        Ok(d.start + 1)
    }

    /// Block `bi` is the `M17` of the Fadal subroutine running now.
    fn fadal_end(&self, bi: usize) -> bool {
        match self.stack.last() {
            Some(Frame {
                target: Target::Fadal(n),
                ..
            }) => self.fadal.get(*n).is_some_and(|d| d.end == bi),
            _ => false,
        }
    }

    /// The Fadal subroutine's next run, or the return after its last.
    fn fadal_return(&mut self) {
        if let Some(f) = self.stack.last_mut() {
            if f.left > 1 {
                f.left -= 1;
                self.pc = f.start;
            } else {
                self.pc = f.ret;
                self.stack.pop();
            }
        }
    }

    /// M98 (an `O` program) and M97 (an N block) call a subprogram, M99
    /// returns from one (or repeats it), M17 ends a Fadal subroutine's run;
    /// `bi` is the block's index.
    fn call_or_return(&mut self, b: &Block, bi: usize) {
        if self.fadal_end(bi) {
            return self.fadal_return();
        }
        let m = |v: i64| b.words.iter().find(|w| w.letter == 'M' && code10(w) == v);
        if let Some(w) = m(980).or_else(|| m(970)) {
            match call(b, bi, w, &self.subs, &self.seqs, self.stack.len()) {
                Ok((start, target, times)) => {
                    if times > 0 {
                        self.stack.push(Frame {
                            ret: self.pc,
                            start,
                            left: times,
                            target,
                            locals: false,
                        });
                        self.pc = start;
                    }
                }
                Err(e) => self.errors.push(e),
            }
        } else if let Some(w) = m(990) {
            self.m99(b, bi, w);
        }
    }

    /// M99 (`P n`: to the block numbered N n, see the module header; a
    /// bad P is an error and the M99 acts as a plain one): the next repeat
    /// of the subprogram, or the return to the caller (a G65 call's locals
    /// dropped); in the main program it ends the run or jumps forwards.
    fn m99(&mut self, b: &Block, bi: usize, w: &Word) {
        let n = b
            .word('P')
            .and_then(|p| match sequence_number(b, p, "M99") {
                Ok(n) => Some((p, n)),
                Err(e) => {
                    self.errors.push(e);
                    None
                }
            });
        let Some(f) = self.stack.last_mut() else {
            return self.m99_main(b, bi, w, n);
        };
        if f.left > 1 {
            f.left -= 1;
            self.pc = f.start;
            return;
        }
        let (ret, locals) = (f.ret, f.locals);
        self.stack.pop();
        if locals {
            if let Some(m) = self.mac.as_mut() {
                m.vars.pop_level();
            }
        }
        self.pc = ret;
        if let Some((p, n)) = n {
            let caller = ret.saturating_sub(1);
            match self.seqs.forward_in_region(i64::from(n), caller, ret) {
                Some(t) => self.pc = t,
                None => self
                    .errors
                    .push(missing_sequence(b, p, n, "M99", "the calling program")),
            }
        }
    }

    /// M99 in the main program: `P n` jumps forwards to N n; a plain M99,
    /// or a jump back, repeats the program endlessly on the control, so it
    /// is warned about and the run ends.
    fn m99_main(&mut self, b: &Block, bi: usize, w: &Word, n: Option<(&Word, u32)>) {
        let Some((p, n)) = n else {
            self.warnings.push(Warning::at(
                b.line,
                w.column,
                "M99 in the main program repeats it endlessly on the control; it is simulated once",
            ));
            self.st.ended = true;
            return;
        };
        match self.seqs.forward_in_region(i64::from(n), bi, bi + 1) {
            Some(t) if t > bi => self.pc = t,
            Some(_) => {
                self.warnings.push(Warning::at(
                    b.line,
                    p.column,
                    format!("M99 P{}: in the main program it jumps back to N{n} and repeats from there endlessly on the control; it is simulated once (the run ends here)", p.text),
                ));
                self.st.ended = true;
            }
            None => self
                .errors
                .push(missing_sequence(b, p, n, "M99", "this program")),
        }
    }

    /// The program after the run: a call left open is an error; every
    /// block gets a modal state (a block not run keeps the one before it);
    /// the segments of blocks run more than once are `fixed`; the corners
    /// are applied.
    ///
    /// # Errors
    /// Every error of the run, in the order found.
    pub fn finish(self, blocks: Vec<Block>) -> Result<Program, NcErrors> {
        let Run {
            opt,
            mut segments,
            warnings,
            mut errors,
            corners,
            modal,
            mut modes,
            stack,
            runs,
            stretches,
            mut tags,
            keep,
            moved_units,
            st,
            nurbs,
            ..
        } = self;
        if let Some(open) = &nurbs {
            errors.push(super::spline::unclosed(open));
        }
        if let (Some(f), true) = (stack.last(), errors.is_empty()) {
            errors.push(NcError::new(
                blocks.last().map_or(1, |b| b.line),
                1,
                format!("{} ends without M99", f.target),
            ));
        }
        let last_start = Modal {
            pos: opt.start,
            inch: opt.units == super::program::Units::Inch,
            ..Modal::default()
        };
        let mut last = last_start;
        let modal: Vec<Modal> = match keep {
            Keep::All => modal
                .into_iter()
                .map(|m| {
                    if let Some(m) = m {
                        last = m;
                    }
                    last
                })
                .collect(),
            Keep::Motion | Keep::Patch => vec![st],
        };
        modes.fill(&last_start);
        for s in &mut segments {
            if s.block
                .is_some_and(|bi| runs.get(bi).is_some_and(|&n| n > 1))
            {
                s.fixed = true;
            }
        }
        if let Err(es) = super::corner::apply_corners(&mut segments, &corners, &mut tags) {
            for e in es {
                errors.push(e);
            }
        }
        if errors.is_empty() {
            if let Err(es) =
                super::cutter_path::offset_path(&mut segments, &tags, &stretches, &blocks)
            {
                for e in es {
                    errors.push(e);
                }
            }
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        Ok(Program {
            blocks,
            modal,
            modes,
            moved_units,
            segments,
            warnings,
            cutter: stretches,
            options: opt.clone(),
        })
    }
}

/// The run reaching a block of another file: the end of the main program
/// (`Some(None)`) when no call is active, or an error when a called
/// subprogram runs past the end of its file without M99.
fn left_file(
    blocks: &[Block],
    b: &Block,
    stack: &[Frame],
    mac: Option<&Macros>,
) -> Option<Option<NcError>> {
    match stack.last() {
        Some(f) if blocks[f.start].file != b.file => Some(Some(NcError::new(
            blocks[f.start].line,
            1,
            format!(
                "{} runs to the end of its file without M99; expected M99 at its end",
                f.target
            ),
        ))),
        None if b.file != 0 && mac.is_none_or(|m| m.depth() == 0) => Some(None),
        _ => None,
    }
}

/// The block calls a macro (G65) or sets or cancels a modal call
/// (G66/G67).
fn has_call_code(b: &Block) -> bool {
    super::macro_exec::call_code(b).is_some()
}

/// The program needs the macro interpreter: macro statements, o-words,
/// G65 calls or G66 modal calls.
pub(super) fn needs_macros(blocks: &[Block]) -> bool {
    has_macros(blocks) || blocks.iter().any(has_call_code)
}

/// Applies a macro step's outcome: a G65 call pushes a frame with its own
/// locals; an error is recorded (and stops the run after an alarm or the
/// loop budget).
fn macro_flow(
    r: Result<Step, NcError>,
    m: &mut Macros,
    subs: &HashMap<u32, usize>,
    stack: &mut Vec<Frame>,
    pc: &mut usize,
    errors: &mut NcErrors,
) -> Flow {
    let call = match r {
        Ok(Step::Run(b, computed)) => return Flow::Run(b, computed),
        Ok(Step::Done) => return Flow::Next,
        Err(e) => {
            errors.push(e);
            return if m.stop { Flow::Stop } else { Flow::Next };
        }
        Ok(Step::Modal {
            number,
            times,
            args,
            p,
        }) => {
            let call = super::modal_call::ModalCall {
                number,
                times,
                args,
                p,
                level: stack.len() + m.depth(),
            };
            register_modal(m, call, errors);
            return Flow::Next;
        }
        Ok(Step::EndModal) => {
            m.modal_call = None;
            return Flow::Next;
        }
        Ok(Step::Call {
            number,
            times,
            args,
            p,
            via,
        }) => (number, times, args, p, via),
    };
    let (number, times, args, p, via) = call;
    if stack.len() + m.depth() >= MAX_NESTING {
        errors.push(NcError::new(
            m.vars.line,
            p.column,
            format!(
                "{via} P{}: macro calls nested deeper than {MAX_NESTING} levels",
                p.text
            ),
        ));
        m.stop = true;
        return Flow::Stop;
    }
    let Some(&start) = subs.get(&number) else {
        errors.push(NcError::new(
            m.vars.line,
            p.column,
            format!("{via} P{}: macro program O{number:04} is not in this program; paste it (O{number:04} … M99) after M30, or drop its file together with the program", p.text),
        ));
        return Flow::Next;
    };
    m.vars.push_level(&args);
    stack.push(Frame {
        ret: *pc,
        start,
        left: times,
        target: Target::Program(number),
        locals: true,
    });
    *pc = start;
    Flow::Next
}

/// G66: `call` becomes the modal call in force, unless one already is
/// (nested modal calls are refused, located at the new P word).
fn register_modal(m: &mut Macros, call: super::modal_call::ModalCall, errors: &mut NcErrors) {
    if let Some(old) = &m.modal_call {
        errors.push(NcError::new(
            m.vars.line,
            call.p.column,
            format!(
                "G66 P{} while G66 P{} is in force: nested modal calls are not modelled; cancel the first with G67",
                call.p.text, old.p.text
            ),
        ));
        return;
    }
    m.modal_call = Some(call);
}

/// O-number → index of its `O` block.
fn subprogram_index(blocks: &[Block]) -> HashMap<u32, usize> {
    let mut m = HashMap::new();
    for (i, b) in blocks.iter().enumerate() {
        if let Some(o) = b.words.first().filter(|w| w.letter == 'O') {
            if o.value >= 0.0 && o.value.fract() == 0.0 {
                m.entry(o.value as u32).or_insert(i);
            }
        }
    }
    m
}

/// The target of `M98 P… (L…/K…)` or `M97 P… (L…/K…)` (block `bi`, call
/// word `m`): its first block, what it is and how often it runs. M98:
/// Fanuc `P` with more than four digits holds the repeat count before the
/// four-digit program number (`P30010` = O0010 three times). M97: `P` is
/// the sequence number of a block of the calling O-program. `L` or `K`
/// gives the count otherwise.
fn call(
    b: &Block,
    bi: usize,
    m: &Word,
    subs: &HashMap<u32, usize>,
    seqs: &Sequences,
    depth: usize,
) -> Result<(usize, Target, u32), NcError> {
    let local = code10(m) == 970;
    let (name, what) = if local {
        ("M97", "sequence number")
    } else {
        ("M98", "program number")
    };
    let Some(p) = b.word('P') else {
        return Err(err(
            b,
            m,
            format!("{name} without P; expected {name} P<{what}>"),
        ));
    };
    let (mut times, target) = if local {
        (1, Target::Sequence(sequence_number(b, p, name)?))
    } else {
        program_number(b, p)?
    };
    if let Some(l) = b.word('L').or(b.word('K')) {
        if l.value < 0.0 || l.value.fract() != 0.0 || l.value > 9999.0 {
            return Err(err(
                b,
                l,
                format!(
                    "repeat count {}{}: expected a whole number from 0 to 9999",
                    l.letter, l.text
                ),
            ));
        }
        times = l.value as u32;
    }
    if depth >= MAX_NESTING {
        return Err(err(
            b,
            m,
            format!("subprogram nesting deeper than {MAX_NESTING} levels"),
        ));
    }
    let start = match target {
        Target::Program(n) => subs.get(&n).copied().ok_or_else(|| {
            err(
                b,
                p,
                format!(
                    "M98 P{}: subprogram O{n:04} is not in this program; paste the subprogram (O{n:04} … M99) after M30, or drop its file together with the program",
                    p.text
                ),
            )
        }),
        // (M97/M98 never make a Fadal target: only `fadal_target` does)
        Target::Sequence(n) | Target::Fadal(n) => seqs
            .first_in_region(i64::from(n), bi)
            .ok_or_else(|| missing_sequence(b, p, n, "M97", "this program")),
    }?;
    Ok((start, target, times))
}

/// The program and repeat count of M98 `p` (see [`call`]).
fn program_number(b: &Block, p: &Word) -> Result<(u32, Target), NcError> {
    if p.value < 0.0 || p.value.fract() != 0.0 {
        return Err(err(
            b,
            p,
            format!("M98 P{}: expected a whole program number", p.text),
        ));
    }
    let digits = p.text.trim_start_matches('+');
    Ok(if digits.len() > 4 {
        let (rep, num) = digits.split_at(digits.len() - 4);
        (
            rep.parse::<u32>().unwrap_or(1).max(1),
            Target::Program(num.parse::<u32>().unwrap_or(0)),
        )
    } else {
        (1, Target::Program(p.value as u32))
    })
}

/// Largest sequence number (N) accepted in an M97 or M99 `P` word (Haas
/// allows N99999, Fanuc N99999 or N99999999 by option).
const MAX_SEQUENCE: f64 = 99_999_999.0;

/// The sequence number of `name`'s (M97, M99) `P` word: whole, from 0 to
/// [`MAX_SEQUENCE`].
fn sequence_number(b: &Block, p: &Word, name: &str) -> Result<u32, NcError> {
    if p.value < 0.0 || p.value.fract() != 0.0 || p.value > MAX_SEQUENCE {
        return Err(err(
            b,
            p,
            format!(
                "{name} P{}: expected a whole sequence number (the N number of a block) from 0 to 99999999",
                p.text
            ),
        ));
    }
    Ok(p.value as u32)
}

/// The error for `name`'s (M97, M99) `P` word naming a sequence number
/// N `n` that `whose` (this program, the calling program) does not have.
fn missing_sequence(b: &Block, p: &Word, n: u32, name: &str, whose: &str) -> NcError {
    let hint = if name == "M97" {
        format!("a local subprogram starts at a block numbered N{n} in the same O-program as the M97 (usually after M30) and ends with M99; add that block or correct the P number")
    } else {
        format!("expected a block numbered N{n} in {whose} (the same O-program); add it or correct the P number")
    };
    err(
        b,
        p,
        format!("{name} P{}: no block N{n} in {whose}; {hint}", p.text),
    )
}
