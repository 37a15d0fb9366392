//! NC program interpreter: modal state over the lexer's [`Block`]s → a list
//! of motion [`Segment`]s with start and end poses (ISO 6983 / RS-274,
//! FANUC-style). Shared by the tool-path model ([`crate::toolpath`]), its
//! reverse compensation ([`crate::compensate::reverse`]) and the 5-axis
//! compensation ([`crate::compensate::nc5`]).
//!
//! What it understands:
//! - motion G0 (rapid), G1 (line), G2/G3 (arc CW/CCW, helical when the axis
//!   normal to the plane moves) with the centre as I/J/K (incremental from the
//!   start, FANUC default) or as R (R < 0: the arc over 180°). A full circle
//!   (end = start) needs I/J/K; R cannot define it.
//! - planes G17 (XY), G18 (ZX), G19 (YZ); G90/G91; G20 (inch; converted to
//!   mm here) and G21; modal F (mm/min or inch/min, stored in mm/min).
//! - rotary words A, B, C in degrees (G20 does not scale them), interpolated
//!   linearly with the segment, also on arcs.
//! - G4 dwell, non-modal: `X` or `U` in seconds (FANUC); `P` per
//!   [`DwellP`]: by default (`Auto`) a `P` with a decimal point is seconds
//!   (LinuxCNC, Haas `P1.5`) and one without is milliseconds (FANUC `P1500`).
//! - N sequence numbers, O program numbers, comments (kept by the lexer).
//!
//! - canned cycles G73, G74, G76, G81–G89 (G87 in the RS274/NGC form with
//!   I/J/K) and Fanuc's rigid tapping G84.2/G84.3 expanded into motion
//!   ([`super::cycles`]); Fanuc corner `,R`/`,C` ([`super::corner`]);
//!   subprograms `M98 P… (L…/K…)` to an `O…` block of the same text ended by
//!   `M99`, and Haas local subprograms `M97 P… (L…/K…)` to the block
//!   numbered `N…` of the calling O-program (usually after M30), nested in
//!   each other up to [`MAX_NESTING`] levels, every segment of a body
//!   `fixed`; `M99 P…` returns to the block numbered `N…` of the calling
//!   program (in the main program: a forward jump, or, backwards, warned
//!   and the run ends as for a plain M99; see `run.rs`); M2/M30 end the
//!   main program.
//! - Haas G187 (smoothness/accuracy, `P1`–`P3`, `E` corner tolerance) and
//!   G103 (look-ahead limit, `P`): one warning each that they are not
//!   modelled (the simulated acc/dec does not change); their words are
//!   theirs.
//! - G90.1/G91.1 arc-centre modes; G92 (and G92.1/G92.2) coordinate shift,
//!   kept as an offset so the path stays continuous; G10 data setting (no
//!   motion); G28/G30 (the rapid to the intermediate point is simulated, the
//!   return to the machine reference is not: warned); G53 (not simulated:
//!   warned); G54–G59/G54.1 (warned, program frame kept).
//! - Fanuc coordinate system rotation `G68 α β R` / G69 in G17, G18, G19
//!   ([`super::rotation`]): every point programmed in the plane (line and
//!   arc ends, arc centres, G91 increments, canned-cycle holes) is turned
//!   by R degrees about the centre; the segments are the un-rotated path.
//!   Refused with a located error: a plane change, G28/G30/G52/G53/
//!   G54–G59/G92 under G68, G68 (or a G69 that cancels one) under G41/G42,
//!   G68 in cycle mode, G68 with Z or I/J/K or without R, G68.1–G68.4.
//!
//! Readings chosen: the program starts at [`ParseOptions::start`] (the origin
//! by default) in G90 G21 G17 with no motion mode and no feed, so an axis
//! word before any G0–G3 is an error, not a silent rapid. M, S, T, H, D and
//! unknown letters are reported as [`Warning`]s and ignored (a D word on a
//! G41/G42 block is its tool-offset number). Cutter radius compensation
//! G40/G41/G42 (and LinuxCNC G41.1/G42.1): with a tool radius for the D
//! word ([`ParseOptions::tool_radii`]) the segments are the offset
//! tool-centre path ([`super::cutter`], [`super::cutter_path`]); without
//! one the simulated path is the programmed path, and one warning per
//! stretch says so. G43 length compensation is ignored (warned). What is not simulated and would change the path is a
//! located error: G84.1 and G84.4–G84.9, G33.2, the Fanuc G87 without I/J/K (G33 runs as a line at K × S, G33.1 there
//! and back, G88 with a rapid for its manual retract), G93/G95 feeds,
//! G66.1 and nested G66 modal calls (LinuxCNC's G5, G5.1 and G5.2/G5.3
//! splines run as chords of their curve, [`super::spline`]),
//! the G68 cases
//! above and G68.1–G68.4 (3D coordinate conversion); an `E` word (not on a
//! G187 block) stops the program as "this looks like a 3D-printer
//! program". (G65 macro calls, macro `#` variables and `[ ]` expressions
//! and LinuxCNC o-words run in [`super::macro_exec`].) Every error of a program is collected
//! ([`parse_all`]). Arc radius consistency: the end radius may differ from
//! the start radius by 0.005 mm + 1e-5·R, by LinuxCNC's tolerance with a
//! warning, and no more ([`super::arc`]); the arc radius is their mean.
//!
//! Where the parts live (files under `src/nc/`): the run over the blocks,
//! calls and returns in `run.rs` (sequence numbers in `sequence.rs`); one block's passes in `block.rs`, its G
//! codes by group in `gcodes.rs`, its move in `moves.rs`, G28/G30/G53/G92
//! in `non_modal.rs`, G68/G69 in `rotation.rs`; canned cycles in
//! [`super::cycles`].
//!
//! Units: mm, s, degrees for A/B/C, feed in mm/min.

use serde::{Deserialize, Serialize};

pub use super::cutter::{Cutter, CutterStretch, Side, ToolRadii};
use super::cycles::Cycle;
pub use super::files::{parse_files, NcFile};
pub use super::rotation::Rotation;
use super::run::{needs_macros, Run};
pub use super::segment::{dist, Arc, Motion, MotionCode, Plane, Pose, Segment, AXES};
use super::{Block, NcError, NcErrors, Word};

/// A non-fatal finding: a word that was ignored, a mode that is not
/// modelled.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Warning {
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
    /// What was ignored and why.
    pub message: String,
    /// The file, when the line is in one of the extra files given to
    /// [`parse_files`] (none: the main program).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
}

impl Warning {
    /// A warning in the main program at `line`, `column`.
    pub(crate) fn at(line: usize, column: usize, message: impl Into<String>) -> Self {
        Self {
            line,
            column,
            message: message.into(),
            file: None,
        }
    }
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let Some(name) = &self.file {
            write!(f, "file {name}, ")?;
        }
        write!(
            f,
            "line {}, column {}: {}",
            self.line, self.column, self.message
        )
    }
}

/// How a G4 `P` word is read (see the module header).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum DwellP {
    /// With a decimal point seconds, without milliseconds.
    #[default]
    Auto,
    /// Always milliseconds (FANUC).
    Milliseconds,
    /// Always seconds (LinuxCNC).
    Seconds,
}

impl DwellP {
    /// A dwell `P` word in seconds under this reading, and whether it was
    /// read as milliseconds.
    pub(crate) fn seconds(self, p: &Word) -> (f64, bool) {
        let ms = match self {
            DwellP::Milliseconds => true,
            DwellP::Seconds => false,
            DwellP::Auto => !p.text.contains('.'),
        };
        (if ms { p.value / 1000.0 } else { p.value }, ms)
    }
}

/// The length unit a program is read in until it states one (G20/G21):
/// a machine setting (Fanuc parameter 0000#2 INI sets the unit at power-on
/// and reset). Default mm.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Units {
    /// Millimetres (G21).
    #[default]
    Mm,
    /// Inches (G20).
    Inch,
}

/// Interpreter options. Unknown keys are rejected when deserialised (a
/// misspelt key is an error naming it, never silently dropped).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default, deny_unknown_fields)]
pub struct ParseOptions {
    /// Reading of G4 P.
    pub dwell_p: DwellP,
    /// Where the tool is before the first block.
    pub start: Pose,
    /// Blocks that start with `/` are skipped (the block-delete switch is
    /// on); default true. Each skipped block gets a warning.
    pub skip_block_delete: bool,
    /// The machine has a C rotary axis, so `C` is an axis word. Default
    /// false: C is still read as an axis when the program is evidently
    /// multi-axis (an A or B word anywhere, or C on a G0/G2/G3 block);
    /// otherwise (a 3-axis program) `C` on a G01 block is a Fanuc chamfer
    /// and anywhere else an error. A and B are always rotary axes.
    pub c_axis: bool,
    /// Tool radius per D number, in program units, for cutter compensation
    /// G41/G42 (see [`super::cutter`]); JS `{ D1: 3 }` or `"D1=3, D8=0.25"`.
    /// Without a radius for a D the simulated path is the programmed path
    /// (warned).
    pub tool_radii: ToolRadii,
    /// The unit of a program that does not state one (no G20/G21 before
    /// its first move); a program that never states its units and whose
    /// numbers look like the other unit's is warned about
    /// ([`super::units`]).
    pub units: Units,
    /// Most blocks the run may execute, loops and repeats included; a
    /// macro loop may jump back a quarter of it, and the program may give
    /// as many segments. At most (and by default) the product's budgets
    /// [`MAX_EXECUTED_BLOCKS`] and [`crate::budget::MAX_SEGMENTS`]: a
    /// larger value is read as those, so this can only lower them.
    /// Rust-only (not serialised): for a caller that runs very many
    /// programs, such as the fuzz targets, which still run macros, loops
    /// and cycles up to it.
    #[serde(skip)]
    pub max_executed_blocks: usize,
}

impl ParseOptions {
    /// The keys of the serialised form (camelCase).
    pub const KEYS: [&'static str; 6] = [
        "dwellP",
        "start",
        "skipBlockDelete",
        "cAxis",
        "toolRadii",
        "units",
    ];
}

impl Default for ParseOptions {
    fn default() -> Self {
        Self {
            dwell_p: DwellP::default(),
            start: Pose::default(),
            skip_block_delete: true,
            c_axis: false,
            tool_radii: ToolRadii::default(),
            units: Units::default(),
            max_executed_blocks: MAX_EXECUTED_BLOCKS,
        }
    }
}

impl ParseOptions {
    /// The executed-block budget in force: [`Self::max_executed_blocks`],
    /// at most [`MAX_EXECUTED_BLOCKS`].
    pub fn executed_block_budget(&self) -> usize {
        self.max_executed_blocks.min(MAX_EXECUTED_BLOCKS)
    }

    /// The segment budget in force: [`Self::max_executed_blocks`], at
    /// most [`crate::budget::MAX_SEGMENTS`].
    pub fn segment_budget(&self) -> usize {
        self.max_executed_blocks.min(crate::budget::MAX_SEGMENTS)
    }

    /// The loop-iteration budget in force: a quarter of
    /// [`Self::executed_block_budget`] (by default
    /// [`crate::budget::MAX_LOOP_ITERATIONS`]), so that a loop meets it,
    /// and its error naming the loop's line, before the block budget.
    pub fn loop_iteration_budget(&self) -> usize {
        self.executed_block_budget() / 4
    }
}

/// Feeds above this (mm/min) are warned about as implausible for milling.
pub const MAX_PLAUSIBLE_FEED: f64 = 100_000.0;

/// Feeds per minute below this (mm/min) are warned about as implausibly
/// slow (a lead-in posted with `F1.`: a 1 mm move at 1 mm/min takes a
/// minute, and a long one can exceed the simulation's sample budget).
pub const MIN_PLAUSIBLE_FEED: f64 = 10.0;

/// Modal state after a block.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Modal {
    /// Motion mode, `None` until the first G0–G3.
    pub motion: Option<MotionCode>,
    /// Arc plane.
    pub plane: Plane,
    /// G91 in force.
    pub incremental: bool,
    /// G20 in force.
    pub inch: bool,
    /// Modal feed: mm/min; under G95 mm per revolution; under G93 the
    /// inverse of the block's time, 1/min.
    pub feed: Option<f64>,
    /// G93 / G94 / G95 (a change clears `feed`, as on FANUC controls: the
    /// F of one mode means something else in the other).
    pub feed_mode: FeedMode,
    /// The last spindle speed S, rpm (the feed of a G95 move is F × S).
    pub spindle: Option<f64>,
    /// Position, mm / degrees.
    pub pos: Pose,
    /// G90.1 in force: arc centres I/J/K are absolute (G91.1, the default,
    /// makes them incremental from the arc start).
    pub arc_center_absolute: bool,
    /// G92 shift, mm / degrees: an absolute word `w` is the pose `w +
    /// offset` of the continuous path (see the module header).
    pub offset: [f64; 6],
    /// The G52 local coordinate shift, mm / degrees: the part of `offset`
    /// that G52 set (a new G52 replaces it axis by axis).
    pub local: [f64; 6],
    /// M2/M30 has ended the program.
    pub ended: bool,
    /// The active canned cycle (G73–G89 until G80 or a G0–G3).
    pub cycle: Option<Cycle>,
    /// G99 in force: canned cycles return to the R level (G98, the
    /// default, returns to the initial level).
    pub cycle_return_r: bool,
    /// Cutter radius compensation in force (G41/G42 until G40).
    pub cutter: Option<Cutter>,
    /// Coordinate system rotation in force (G68 until G69,
    /// [`super::rotation`]); `pos` stays in the un-rotated frame.
    pub rotation: Option<Rotation>,
    /// The modal tool-offset number D (the last D word outside a
    /// G41.1/G42.1 block): a G41/G42 without D uses it, as the control
    /// does.
    #[serde(default)]
    pub d: Option<f64>,
    /// G33 (spindle-synchronised motion, LinuxCNC) in force: a G1-like
    /// move whose feed is its K (pitch, length per revolution) × S.
    #[serde(default)]
    pub spindle_sync: bool,
    /// G33.1 (rigid tapping, LinuxCNC) in force: a G33 move to the end
    /// point and back to the start at the same K × S.
    #[serde(default)]
    pub rigid_tap: bool,
    /// A LinuxCNC spline mode in force (G5.1, or G5.2 until G5.3), with
    /// `motion` G1 ([`super::spline`]).
    #[serde(default)]
    pub spline: Option<super::spline::Spline>,
    /// The last G5 cubic's P Q, mm (its second control point's offset from
    /// its end), while the next G5 may continue its series without I J;
    /// a block with another motion, cycle or non-modal move code ends the
    /// series ([`super::spline`]).
    #[serde(default)]
    pub cubic_end_offset: Option<[f64; 2]>,
}

/// An interpreted program.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    /// The lexed blocks (one per source line).
    pub blocks: Vec<Block>,
    /// Modal state after each block (same length as `blocks`); read with
    /// [`Keep::Motion`] or [`Keep::Patch`], only the state at the end (one
    /// entry).
    pub modal: Vec<Modal>,
    /// What the source-preserving writer ([`super::patch`]) reads of the
    /// modal state after each block, compactly ([`super::block_modes`]);
    /// empty when read with [`Keep::Motion`].
    pub modes: super::block_modes::BlockModes,
    /// The program moved in mm (`[0]`) and in inch (`[1]`) units (the
    /// units in force after each block that gave a segment).
    pub moved_units: [bool; 2],
    /// The motion segments in order; at most one per block.
    pub segments: Vec<Segment>,
    /// Ignored words and unmodelled modes.
    pub warnings: Vec<Warning>,
    /// The cutter-compensation stretches (G41/G42 … G40), in order, with
    /// the radius each used (`None`: the programmed path, warned).
    pub cutter: Vec<CutterStretch>,
    /// The options it was read with.
    pub options: ParseOptions,
}

impl Program {
    /// True when the program holds macro code (Macro B, o-words, G65): its
    /// text cannot be rewritten block by block, because a block may run
    /// several times or with computed words (its segments are `fixed`).
    pub fn has_macros(&self) -> bool {
        needs_macros(&self.blocks)
    }
}

/// What an interpreted [`Program`] keeps besides its segments.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Keep {
    /// The modal state after every block: what the writers
    /// ([`super::writer`], [`super::patch`]) need to give a program back.
    #[default]
    All,
    /// Only what the source-preserving writer ([`super::patch`]) reads
    /// of each block's modal state ([`Program::modes`], 4 bytes a block
    /// and the distinct states), and the state at the end: for a caller
    /// that writes the program back in place but never flat
    /// ([`super::writer`]).
    Patch,
    /// Only the state at the end: for a caller that simulates or checks
    /// the motion and never writes the program back. A block's modal
    /// state is 368 bytes, so a 2 M-line program saves 740 MB (1.5 GB
    /// while the run's copy is turned into the program's).
    Motion,
}

/// How F is read: G94 mm/min (the default), G95 mm per revolution, G93
/// inverse time (the block takes 1/F minutes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum FeedMode {
    /// G94.
    #[default]
    PerMinute,
    /// G95.
    PerRevolution,
    /// G93.
    InverseTime,
}

impl Modal {
    /// The feed of a cutting move of `length` (mm; for a move of the rotary
    /// axes only, its largest rotary move in degrees), mm/min (deg/min):
    /// F; under G95 F × S; under G93 `length` × F. `None` without F (or,
    /// under G95, without S).
    pub fn feed_mm_min(&self, length: f64) -> Option<f64> {
        let f = self.feed?;
        match self.feed_mode {
            FeedMode::PerMinute => Some(f),
            FeedMode::PerRevolution => self.spindle.map(|s| f * s),
            FeedMode::InverseTime => Some(f * length),
        }
    }

    /// Why a cutting move has no feed (for the error at the move).
    pub(super) fn no_feed_reason(&self) -> &'static str {
        match self.feed_mode {
            FeedMode::PerRevolution if self.feed.is_some() => "G95 (feed per revolution) needs the spindle speed: expected an S word (rpm) on this or an earlier block",
            FeedMode::PerRevolution => "expected an F word (mm per revolution) after G95",
            FeedMode::InverseTime => "under G93 (inverse time) every cutting move needs its own F word (1/min)",
            FeedMode::PerMinute => "expected an F word (mm/min) on this or an earlier block",
        }
    }
}

/// Parses and interprets a program with default options; the first error
/// only (see [`parse_all`] for every error).
///
/// # Errors
/// Lexer errors, and interpretation errors naming line and column: an arc
/// without a centre, an inconsistent radius, a missing or zero feed on a
/// cutting move, axis words before any motion mode, two motion codes in one
/// block, unsupported cycles.
///
/// # Examples
/// ```
/// use mtmotion::nc::program::{parse, Motion};
/// let p = parse("G90 G17 G21\nG0 X10 Y0\nG3 X-10 Y0 R10 F2000 (half circle)").unwrap();
/// assert_eq!(p.segments.len(), 2);
/// let Motion::Arc(a) = p.segments[1].motion else { panic!() };
/// assert!((a.sweep - std::f64::consts::PI).abs() < 1e-9);
/// assert!((p.segments[1].length() - 10.0 * std::f64::consts::PI).abs() < 1e-9);
/// let e = parse("G1 X1").unwrap_err();
/// assert!(e.message.contains("feed"));
/// ```
pub fn parse(text: &str) -> Result<Program, NcError> {
    parse_with(text, &ParseOptions::default())
}

/// Parses and interprets a program with `options`; the first error only.
///
/// # Errors
/// As [`parse`].
pub fn parse_with(text: &str, options: &ParseOptions) -> Result<Program, NcError> {
    parse_all(text, options).map_err(|e| e.first())
}

/// Parses and interprets a program with `options` and reports every error
/// (one per block, up to [`super::MAX_ERRORS`]), in source order.
///
/// # Errors
/// As [`parse`], all of them.
///
/// # Examples
/// ```
/// use mtmotion::nc::program::{parse_all, ParseOptions};
/// let e = parse_all("G1 X1\nG0 X(open\nG1 X2 F100\nG2 X3", &ParseOptions::default()).unwrap_err();
/// let lines: Vec<usize> = e.errors.iter().map(|e| e.line).collect();
/// assert_eq!(lines, vec![1, 2, 4]);
/// ```
pub fn parse_all(text: &str, options: &ParseOptions) -> Result<Program, NcErrors> {
    parse_files(text, &[], options)
}

/// Interprets lexed blocks; the first error only.
///
/// # Errors
/// As [`parse`].
pub fn interpret(blocks: Vec<Block>, options: &ParseOptions) -> Result<Program, NcError> {
    interpret_all(blocks, options).map_err(|e| e.first())
}

/// Interprets lexed blocks and collects every block's error.
///
/// # Errors
/// As [`parse_all`].
pub fn interpret_all(blocks: Vec<Block>, options: &ParseOptions) -> Result<Program, NcErrors> {
    interpret_keeping(blocks, options, Keep::All)
}

/// As [`interpret_all`], keeping what `keep` says.
///
/// # Errors
/// As [`parse_all`].
pub fn interpret_keeping(
    blocks: Vec<Block>,
    options: &ParseOptions,
    keep: Keep,
) -> Result<Program, NcErrors> {
    let effective = ParseOptions {
        c_axis: options.c_axis || multi_axis(&blocks),
        ..options.clone()
    };
    let mut run = Run::new(&blocks, &effective, keep)?;
    while run.pc < blocks.len() {
        if !run.step(&blocks) {
            break;
        }
    }
    let mut p = run.finish(blocks)?;
    super::units::check(&mut p);
    Ok(p)
}

/// True when the program is evidently multi-axis, so C is a rotary axis
/// even without [`ParseOptions::c_axis`]: an A or B word on any block but
/// a G4 dwell, or a C
/// word in a block with G0, G2 or G3 or with an A/B word. (A 3-axis Fanuc
/// program writes C only on G01 blocks, as a chamfer.)
fn multi_axis(blocks: &[Block]) -> bool {
    let dwell = |b: &Block| {
        b.words_of('G')
            .any(|g| (g.value * 10.0).round() as i64 == 40)
    };
    blocks.iter().any(|b| {
        // an A/B word on a G4 block moves nothing (it is warned about and
        // not written back), so it says nothing about the machine
        (!dwell(b) && (b.word('A').is_some() || b.word('B').is_some()))
            || (b.word('C').is_some()
                && b.words_of('G')
                    .any(|g| matches!((g.value * 10.0).round() as i64, 0 | 20 | 30)))
    })
}

/// Blocks a program may execute (subprogram repeats included) before it
/// is stopped as endless (the work budget
/// [`crate::budget::MAX_EXECUTED_BLOCKS`]).
pub const MAX_EXECUTED_BLOCKS: usize = crate::budget::MAX_EXECUTED_BLOCKS;

/// Deepest subprogram nesting (Fanuc allows 10 levels from the main
/// program... controls differ; 10 is the common Fanuc limit).
pub const MAX_NESTING: usize = 10;

/// Where one block's interpretation puts its results.
pub(super) struct Ctx<'a> {
    /// Index of the block.
    pub bi: usize,
    /// The interpreter options (C axis resolved).
    pub opt: &'a ParseOptions,
    /// Warnings of the program so far.
    pub warnings: &'a mut Vec<Warning>,
    /// Segments of the program so far.
    pub segments: &'a mut Vec<Segment>,
    /// Corner words waiting for the next move.
    pub corners: &'a mut Vec<Corner>,
    /// Cutter-compensation stretches so far.
    pub stretches: &'a mut Vec<CutterStretch>,
    /// The G5.2 NURBS block open, if any ([`super::spline`]).
    pub nurbs: &'a mut Option<super::spline::OpenNurbs>,
}

/// An error at word `w` of block `b`.
pub(super) fn err(b: &Block, w: &Word, msg: impl Into<String>) -> NcError {
    NcError::new(b.line, w.column, msg)
}

/// A Fanuc corner word waiting for the next move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corner {
    /// Index of the G01 segment whose end is the corner.
    pub segment: usize,
    /// Rounding or chamfer.
    pub kind: CornerKind,
    /// Source line and column of the word.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

/// `,R` / `R` (rounding radius) or `,C` / `C` (chamfer), mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CornerKind {
    /// Corner rounding radius, mm.
    Round(f64),
    /// Chamfer: distance from the virtual corner along each line, mm.
    Chamfer(f64),
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn arc_of(p: &Program, i: usize) -> Arc {
        match p.segments[i].motion {
            Motion::Arc(a) => a,
            m => panic!("not an arc: {m:?}"),
        }
    }

    #[test]
    fn r_sign_selects_minor_or_major_arc() {
        let p = parse("G0 X0 Y0\nG2 X10 Y0 R5 F100\nG0 X0 Y0\nG2 X10 Y10 R-10 F100\nG3 X0 Y0 R10")
            .unwrap();
        let a = arc_of(&p, 1);
        assert!((a.sweep + PI).abs() < 1e-9, "{}", a.sweep);
        assert!((a.center[0] - 5.0).abs() < 1e-9 && a.center[1].abs() < 1e-9);
        let a = arc_of(&p, 3);
        assert!((a.sweep + 1.5 * PI).abs() < 1e-9, "{}", a.sweep);
        assert!(
            a.center[0].abs() < 1e-9 && (a.center[1] - 10.0).abs() < 1e-9,
            "{:?}",
            a.center
        );
        let a = arc_of(&p, 4);
        assert!((a.sweep - 0.5 * PI).abs() < 1e-9);
    }

    #[test]
    fn full_circle_planes_and_inch() {
        let p = parse("G18 G0 X10 Z0\nG2 X10 Z0 I-10 F500\nG20 G19 G91 G3 Y1 Z1 K1 F10").unwrap();
        let a = arc_of(&p, 1);
        assert!((a.sweep + 2.0 * PI).abs() < 1e-12);
        assert!((p.segments[1].length() - 20.0 * PI).abs() < 1e-9);
        let s = &p.segments[2];
        assert!((s.end.y - 25.4).abs() < 1e-12 && (s.end.z - 25.4).abs() < 1e-12);
        assert!((s.feed - 254.0).abs() < 1e-12);
        let a = arc_of(&p, 2);
        assert_eq!(a.plane, Plane::YZ);
        assert!((a.radius - 25.4).abs() < 1e-9);
        assert!((a.sweep - 0.5 * PI).abs() < 1e-9);
    }

    #[test]
    fn dwell_forms_rotary_and_warnings() {
        let p = parse("N1 G4 P1500\nG4 X0.5\nG04 P0.25\nG1 X1 A90 F100 M8 S1000 T1 Q2").unwrap();
        let secs: Vec<f64> = p.segments[..3]
            .iter()
            .map(|s| match s.motion {
                Motion::Dwell { seconds } => seconds,
                _ => -1.0,
            })
            .collect();
        assert_eq!(secs, vec![1.5, 0.5, 0.25]);
        assert_eq!(p.segments[3].end.a, 90.0);
        assert_eq!(p.warnings.len(), 5);
        assert!(p.warnings[0].message.contains("read as 1500 ms"));
        assert!(p.warnings[4].message.contains("unknown word Q2"));
        let p = parse_with(
            "G4 P2",
            &ParseOptions {
                dwell_p: DwellP::Seconds,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(matches!(p.segments[0].motion, Motion::Dwell { seconds } if seconds == 2.0));
    }
}
