//! NC program writer: turns a [`Program`] and a (possibly edited) list of
//! [`Segment`]s back into NC text, keeping the source blocks' N numbers,
//! comments, M/S/T words and block order.
//!
//! Rules (so that `parse(write(p))` reproduces `p`'s segments):
//! - the output is absolute millimetres: `G20` is written as `G21`, `G91` as
//!   `G90`, and coordinates and feeds are converted; words whose value does
//!   not change keep their original text;
//! - a segment whose `block` is `Some(i)` replaces the coordinate and centre
//!   words of source block `i`; an axis is written when the source block had
//!   it or when it moves;
//! - a segment with `block == None` becomes a new block (e.g. a dwell or a
//!   connecting line inserted by a compensation); the motion code, plane and
//!   feed are repeated on the next source block whenever an inserted block
//!   changed the modal state, so modal meaning is preserved;
//! - arcs keep their form: R (negative for a sweep over 180°) when the source
//!   used R and the arc is not a full circle, I/J/K otherwise;
//! - dwells are written in the dialect the program was read with
//!   ([`DwellP`]): X/U stay seconds; P stays in the source's form; new
//!   dwells are `P` in integer milliseconds (`Auto`, `Milliseconds`) or
//!   seconds (`Seconds`).
//!
//! - a program whose blocks cannot be rewritten one by one is written flat,
//!   as the path it runs: one block per segment, in execution order. That
//!   is a program with macro code, with a G92 shift, with a G68 rotation
//!   (the segments are already in the un-rotated frame, so writing them
//!   as plain coordinates reads back to the same segments with no
//!   transform in between; G68 kept would turn every written, rounded
//!   number once more), or with `fixed`
//!   segments (a subprogram body — a `G91` body called twice moves from
//!   two different starts —, a canned cycle, a corner `,R`/`,C`). Blocks
//!   without motion keep their N numbers, comments and M/S/T/D/H words in
//!   place (not M98/M99), and so do the G codes that set the frame the
//!   coordinates are in (work offsets, tool length, and a cutter
//!   compensation whose radius is not known: `frame_code`); other G codes,
//!   O numbers and call words are dropped, and a `G21 G90 G94 G17` block
//!   ([`FLAT_MODES`]) comes first, so that a control left in inches,
//!   incremental, per-revolution feed or another plane reads the written
//!   millimetres as meant. [`write_expanded`] writes any program flat, and
//!   refuses one that the flat form would lose something of.
//!
//! Numbers are written with up to 4 decimals (0.1 µm) and always with a
//! decimal point, because FANUC reads `X10` without one as 10 µm when
//! "decimal point input" is off. Where 4 decimals would change what is read
//! back, more are written: a short arc whose end would round onto its start
//! (it would become a full circle), a feed that would round to zero; an R
//! arc whose centre would move by more than [`REREAD_MM`] (R close to half
//! the chord) is written with I/J/K.
//!
//! Units: mm, degrees for A/B/C, mm/min.

use super::arc::arc;
use super::macro_line::Stmt;
use super::program::{
    Arc, DwellP, FeedMode, Modal, Motion, MotionCode, Plane, Pose, Program, Segment, AXES,
};
use super::{Block, Word};
use std::collections::BTreeMap;

/// A number with up to 4 decimals and a decimal point, e.g. `10.`, `-0.5`.
///
/// # Examples
/// ```
/// use mtmotion::nc::writer::fmt_num;
/// assert_eq!(fmt_num(10.0), "10.");
/// assert_eq!(fmt_num(-0.50004), "-0.5");
/// assert_eq!(fmt_num(-0.00001), "0.");
/// ```
pub fn fmt_num(v: f64) -> String {
    let mut s = format!("{v:.4}");
    while s.ends_with('0') {
        s.pop();
    }
    if s == "-0." {
        s = "0.".into();
    }
    s
}

/// The value a reader gets from [`fmt_num`]`(v)`.
fn written(v: f64) -> f64 {
    fmt_num(v).parse().unwrap_or(v)
}

/// `v` exactly (the shortest decimal that reads back as `v`), with a
/// decimal point.
fn fmt_exact(v: f64) -> String {
    let mut s = format!("{v}");
    if !s.contains('.') {
        s.push('.');
    }
    s
}

/// An R arc whose centre, read back from the written (rounded) start, end
/// and R, moves by more than this (or whose end slides along the arc by
/// more) is written with I/J/K instead, mm: one
/// written digit (0.1 µm). R close to half the chord makes the centre
/// sensitive to the rounding (a 172° arc of R 3 mm moves it 0.3 µm).
pub const REREAD_MM: f64 = 1e-4;

/// Positions closer than this are the same point to the reader, mm (the
/// interpreter's full-circle test).
const SAME_POINT_MM: f64 = 1e-9;

fn word(letter: char, text: String) -> Word {
    Word {
        letter,
        value: text.parse().unwrap_or(0.0),
        text: text.into(),
        column: 0,
    }
}

fn motion_code(s: &Segment) -> Option<MotionCode> {
    match s.motion {
        Motion::Rapid => Some(MotionCode::Rapid),
        Motion::Linear => Some(MotionCode::Linear),
        Motion::Arc(a) if a.sweep < 0.0 => Some(MotionCode::Cw),
        Motion::Arc(_) => Some(MotionCode::Ccw),
        Motion::Dwell { .. } => None,
    }
}

fn g_code(w: &Word) -> i64 {
    (w.value * 10.0).round() as i64
}

fn is_move_word(c: char) -> bool {
    super::polar::is_position(c) || matches!(c, 'I' | 'J' | 'K' | 'R')
}

impl Out {
    fn new(program: &Program) -> Self {
        Self {
            motion: None,
            plane: Plane::XY,
            feed: None,
            pos: program.options.start,
            lines: Vec::new(),
        }
    }
}

struct Out {
    motion: Option<MotionCode>,
    plane: Plane,
    feed: Option<f64>,
    pos: Pose,
    lines: Vec<String>,
}

impl Program {
    /// Writes the program's own segments back (see [`write()`]).
    ///
    /// # Examples
    /// ```
    /// let src = "N10 G91 G1 X1 Y2 F100 (inc)\nN20 X1";
    /// let p = mtmotion::nc::program::parse(src).unwrap();
    /// assert_eq!(p.write(), "N10 G90 G1 X1. Y2. F100 (inc)\nN20 X2.");
    /// ```
    pub fn write(&self) -> String {
        write(self, &self.segments)
    }
}

/// Writes `segments` as NC text, using `program`'s blocks for everything
/// that is not geometry. See the module header for the rules.
///
/// # Units
/// Segments in mm, degrees and mm/min; the text is G21 G90.
///
/// # Examples
/// ```
/// use mtmotion::nc::{program::parse, writer::write};
/// let p = parse("G0 X0 Y0\nN5 G2 X10 Y0 R5 F600 ; top").unwrap();
/// let mut segs = p.segments.clone();
/// segs[1].end.x = 12.0; // a wider arc, same form
/// if let mtmotion::nc::program::Motion::Arc(a) = &mut segs[1].motion {
///     a.radius = 6.0;
///     a.center = [6.0, 0.0, 0.0];
/// }
/// let text = write(&p, &segs);
/// assert_eq!(text.lines().nth(1), Some("N5 G2 X12. Y0 R6. F600 (top)"));
/// let q = parse(&text).unwrap();
/// assert!((q.segments[1].length() - 6.0 * std::f64::consts::PI).abs() < 1e-9);
/// ```
pub fn write(program: &Program, segments: &[Segment]) -> String {
    let mut out = Out::new(program);
    if needs_flat(program) {
        write_flat(program, segments, &mut out);
        return out.lines.join("\n");
    }
    let mut next = 0usize;
    for seg in segments {
        match seg.block {
            Some(bi) if bi >= next && bi < program.blocks.len() => {
                for j in next..bi {
                    write_plain(program, j, &mut out);
                }
                write_block(program, bi, seg, &mut out);
                next = bi + 1;
            }
            _ => write_new(program, seg, None, &mut out),
        }
    }
    for j in next..program.blocks.len() {
        write_plain(program, j, &mut out);
    }
    out.lines.join("\n")
}

fn modal_at(program: &Program, bi: usize) -> Modal {
    program.modal.get(bi).copied().unwrap_or_default()
}

/// The feed an F word gives under `m`, mm/min: inch scaled, and under G95
/// times the spindle speed (the flat program is written in G94). Without
/// a spindle speed under G95 the word is kept as it reads (the program's
/// moves then had no feed and did not parse). Under G93 F is no feed at
/// all: NaN, so that every move writes its own F (mm/min) after it.
fn feed_of_word(m: &Modal, w: &Word) -> f64 {
    let f = w.value * super::block::length_scale(m);
    match (m.feed_mode, m.spindle) {
        (FeedMode::PerRevolution, Some(s)) => f * s,
        (FeedMode::InverseTime, _) => f64::NAN,
        _ => f,
    }
}

/// Common word rewriting: G20→G21, G91→G90, G95→G94, feed to mm/min
/// (under G95 F × S), modal tracking.
fn rewrite_common(program: &Program, bi: usize, w: &Word, out: &mut Out) -> Option<Word> {
    let m = modal_at(program, bi);
    match w.letter {
        'G' => {
            let g = g_code(w);
            let mut w = w.clone();
            match g {
                200 => w = word('G', "21".into()),
                910 => w = word('G', "90".into()),
                930 | 950 => w = word('G', "94".into()),
                901 => w = word('G', "91.1".into()),
                0 | 10 | 20 | 30 => {
                    out.motion = Some(match g {
                        0 => MotionCode::Rapid,
                        10 => MotionCode::Linear,
                        20 => MotionCode::Cw,
                        _ => MotionCode::Ccw,
                    })
                }
                170 => out.plane = Plane::XY,
                180 => out.plane = Plane::ZX,
                190 => out.plane = Plane::YZ,
                _ => {}
            }
            Some(w)
        }
        'F' => {
            let f = feed_of_word(&m, w);
            out.feed = Some(f);
            if m.feed_mode == FeedMode::InverseTime {
                // written per move, in mm/min (`modal_words`)
                return None;
            }
            Some(if m.inch || m.feed_mode == FeedMode::PerRevolution {
                word('F', fmt_feed(f))
            } else {
                w.clone()
            })
        }
        _ => Some(w.clone()),
    }
}

/// `block` with `words`; its comments in parentheses, or, from the first
/// one whose parentheses do not pair (a `;` comment such as `; see (1`),
/// as one `;` comment to the line end, so they read back as comments.
fn emit(block: &Block, words: Vec<Word>, out: &mut Out) {
    let b = Block {
        words,
        comments: Vec::new(),
        ..block.clone()
    };
    let mut line = b.write();
    for (k, c) in block.comments.iter().enumerate() {
        if !line.is_empty() {
            line.push(' ');
        }
        if !paired(c) {
            line.push_str("; ");
            line.push_str(&block.comments[k..].join(" "));
            break;
        }
        line.push_str(&format!("({c})"));
    }
    out.lines.push(line);
}

/// Every `)` of `c` closes an earlier `(` and every `(` is closed.
fn paired(c: &str) -> bool {
    let mut depth = 0usize;
    for ch in c.chars() {
        match ch {
            '(' => depth += 1,
            ')' if depth == 0 => return false,
            ')' => depth -= 1,
            _ => {}
        }
    }
    depth == 0
}

/// A source block without a segment in the output.
fn write_plain(program: &Program, bi: usize, out: &mut Out) {
    let Some(block) = program.blocks.get(bi) else {
        return;
    };
    let had_segment = program.segments.iter().any(|s| s.block == Some(bi));
    let dwell = block
        .words
        .iter()
        .any(|w| w.letter == 'G' && g_code(w) == 40);
    let mut words = Vec::new();
    for w in &block.words {
        if had_segment && (is_move_word(w.letter) || (dwell && matches!(w.letter, 'P' | 'U'))) {
            continue;
        }
        if had_segment && dwell && w.letter == 'G' && g_code(w) == 40 {
            continue;
        }
        if let Some(w) = rewrite_common(program, bi, w, out) {
            words.push(w);
        }
    }
    if had_segment && words.is_empty() && block.comments.is_empty() {
        return;
    }
    emit(block, words, out);
}

/// The axis words of `seg`'s end: an axis is written when the source block
/// had it or when it moves. An axis that stays where the segment started
/// (within [`SAME_POINT_MM`]) is written with the start's value, so a full
/// circle stays a full circle; a short arc whose end would round onto its
/// start is written exactly.
fn axis_words(block: Option<&Block>, plain: bool, seg: &Segment, out: &Out) -> Vec<Word> {
    let exact = match seg.motion {
        Motion::Arc(a) => {
            let (u, v, _) = a.plane.axes();
            let chord = |f: &dyn Fn(f64) -> f64| {
                (f(seg.end.get(u)) - f(seg.start.get(u)))
                    .hypot(f(seg.end.get(v)) - f(seg.start.get(v)))
            };
            chord(&|x| x) >= SAME_POINT_MM && chord(&written) < SAME_POINT_MM
        }
        _ => false,
    };
    let mut ws = Vec::new();
    for (i, &letter) in AXES.iter().enumerate() {
        let mut v = seg.end.get(i);
        let orig = block.and_then(|b| b.word(letter));
        if (v - out.pos.get(i)).abs() < SAME_POINT_MM {
            if orig.is_none() {
                continue;
            }
            v = out.pos.get(i);
        }
        match orig {
            Some(o) if plain && o.value == v => ws.push(o.clone()),
            _ if exact => ws.push(word(letter, fmt_exact(v))),
            _ => ws.push(word(letter, fmt_num(v))),
        }
    }
    ws
}

/// The pose a reader gets back from `pose` written with [`fmt_num`].
fn written_pose(pose: &Pose) -> Pose {
    let mut a = [0.0; 6];
    for (i, v) in a.iter_mut().enumerate() {
        *v = written(pose.get(i));
    }
    Pose::from_array(a)
}

/// The R word of `a`, when a reader gets `a`'s centre back from it and the
/// written end point within [`REREAD_MM`].
fn r_word(orig: Option<&Word>, inch: bool, seg: &Segment, a: &Arc, end: &[Word]) -> Option<Word> {
    let r = if a.sweep.abs() > std::f64::consts::PI {
        -a.radius
    } else {
        a.radius
    };
    let w = match orig {
        Some(o) if !inch && o.value == r => o.clone(),
        _ => word('R', fmt_num(r)),
    };
    let start = written_pose(&seg.start);
    let mut e = written_pose(&seg.end);
    for ew in end {
        if let Some(i) = AXES.iter().position(|&c| c == ew.letter) {
            e.set(i, ew.value);
        }
    }
    let b = Block {
        words: vec![w.clone()],
        ..Block::default()
    };
    let back = arc(&b, &w, a.plane, a.sweep < 0.0, start, e, 1.0).ok()?;
    let moved = (0..3)
        .map(|k| (back.center[k] - a.center[k]).abs())
        .fold(0.0, f64::max);
    // the end read back may also slide along the arc: near 180° a centre
    // shift of 0.08 µm turned a 0.43 mm corner arc by 0.2 µm of its length
    let slid = (back.sweep - a.sweep).abs() * a.radius;
    (moved <= REREAD_MM && slid <= REREAD_MM).then_some(w)
}

/// The centre words I/J/K of `a`, from the written start point (so only
/// their own rounding counts); exact when they would round to zero.
fn centre_words(block: Option<&Block>, inch: bool, seg: &Segment, a: &Arc) -> Vec<Word> {
    let (u, v, _) = a.plane.axes();
    let letters = ['I', 'J', 'K'];
    let p0 = written_pose(&seg.start).p();
    let vals = [a.center[u] - p0[u], a.center[v] - p0[v]];
    let tiny = vals.iter().all(|&x| written(x) == 0.0);
    let mut ws = Vec::new();
    for (k, val) in [u, v].into_iter().zip(vals) {
        match block.and_then(|b| b.word(letters[k])) {
            Some(o) if !inch && o.value == val => ws.push(o.clone()),
            _ if tiny => ws.push(word(letters[k], fmt_exact(val))),
            _ => ws.push(word(letters[k], fmt_num(val))),
        }
    }
    ws
}

fn coord_words(program: &Program, bi: Option<usize>, seg: &Segment, out: &Out) -> Vec<Word> {
    let block = bi.and_then(|i| program.blocks.get(i));
    let m = bi.map(|i| modal_at(program, i)).unwrap_or_default();
    let plain = !m.inch && !m.incremental;
    let mut ws = axis_words(block, plain, seg, out);
    if let Motion::Arc(a) = seg.motion {
        let full = a.sweep.abs() > std::f64::consts::TAU - 1e-9;
        let orig_r = block.and_then(|b| b.word('R'));
        match (a.r_form && !full)
            .then(|| r_word(orig_r, m.inch, seg, &a, &ws))
            .flatten()
        {
            Some(r) => ws.push(r),
            None => ws.extend(centre_words(block, m.inch, seg, &a)),
        }
    }
    ws
}

/// A feed with up to 4 decimals, or exactly when that would change it by
/// more than 1e-7 of itself (a feed below 0.001 mm/min).
fn fmt_feed(f: f64) -> String {
    if (written(f) - f).abs() <= 1e-7 * f.abs() {
        fmt_num(f)
    } else {
        fmt_exact(f)
    }
}

fn dwell_word(program: &Program, orig: Option<&Word>, seconds: f64) -> Word {
    if let Some(o) = orig {
        let ms = o.letter == 'P'
            && match program.options.dwell_p {
                DwellP::Milliseconds => true,
                DwellP::Seconds => false,
                DwellP::Auto => !o.text.contains('.'),
            };
        let orig_s = if ms { o.value / 1000.0 } else { o.value };
        if orig_s == seconds {
            return o.clone();
        }
        if o.letter != 'P' || !ms {
            return word(o.letter, fmt_feed(seconds));
        }
    }
    let ms = seconds * 1000.0;
    let whole = (ms - ms.round()).abs() < 1e-9;
    match program.options.dwell_p {
        DwellP::Seconds => word('P', fmt_feed(seconds)),
        DwellP::Milliseconds if whole => word('P', whole_ms(ms)),
        DwellP::Milliseconds => word('P', fmt_feed(ms)),
        DwellP::Auto if whole => word('P', whole_ms(ms)),
        DwellP::Auto => word('P', fmt_feed(seconds)),
    }
}

/// A whole number of milliseconds without a decimal point, every digit
/// written (an `i64` would saturate above 9.2e18 ms and change the dwell
/// read back); `-0` is written `0`.
fn whole_ms(ms: f64) -> String {
    format!("{:.0}", ms.round() + 0.0)
}

fn insert_front(words: &mut Vec<Word>, w: Word) {
    let at = usize::from(words.first().is_some_and(|f| f.letter == 'N'));
    words.insert(at, w);
}

/// A source block carrying the dwell `seconds`.
fn write_dwell_block(program: &Program, bi: usize, block: &Block, seconds: f64, out: &mut Out) {
    let orig = block.word('X').or(block.word('U')).or(block.word('P'));
    let mut words = Vec::new();
    let mut placed = false;
    for w in &block.words {
        if matches!(w.letter, 'X' | 'U' | 'P') {
            if !placed {
                words.push(dwell_word(program, orig, seconds));
                placed = true;
            }
            continue;
        }
        if let Some(w) = rewrite_common(program, bi, w, out) {
            words.push(w);
        }
    }
    if !placed {
        words.push(dwell_word(program, None, seconds));
    }
    emit(block, words, out);
}

/// The modal words a block writing `seg` needs in front (plane, motion
/// code) and behind (feed) when it does not carry them itself.
fn modal_words(seg: &Segment, had: [bool; 3], words: &mut Vec<Word>, out: &mut Out) {
    let [had_motion, had_plane, had_feed] = had;
    let want = motion_code(seg);
    if let Motion::Arc(a) = seg.motion {
        if !had_plane && out.plane != a.plane {
            insert_front(words, word('G', a.plane.code().to_string()));
            out.plane = a.plane;
        }
    }
    if !had_motion && want != out.motion {
        if let Some(m) = want {
            insert_front(words, word('G', m.code().to_string()));
        }
    }
    out.motion = want.or(out.motion);
    if seg.is_cutting() && !had_feed && out.feed != Some(seg.feed) {
        words.push(word('F', fmt_feed(seg.feed)));
        out.feed = Some(seg.feed);
    }
}

/// A source block carrying `seg`.
fn write_block(program: &Program, bi: usize, seg: &Segment, out: &mut Out) {
    let Some(block) = program.blocks.get(bi) else {
        return;
    };
    if let Motion::Dwell { seconds } = seg.motion {
        return write_dwell_block(program, bi, block, seconds, out);
    }
    let want = motion_code(seg);
    let mut coords = Some(coord_words(program, Some(bi), seg, out));
    let mut words = Vec::new();
    let mut had = [false; 3];
    for w in &block.words {
        if is_move_word(w.letter) {
            if let Some(c) = coords.take() {
                words.extend(c);
            }
            continue;
        }
        let mut w = w.clone();
        if w.letter == 'G' {
            let g = g_code(&w);
            if matches!(g, 0 | 10 | 20 | 30) {
                had[0] = true;
                if let Some(m) = want {
                    if g != 10 * m.code() as i64 {
                        w = word('G', m.code().to_string());
                    }
                }
            }
            had[1] |= matches!(g, 170 | 180 | 190);
        }
        // Under G93 the F is dropped and the move's mm/min written after it.
        let m = modal_at(program, bi);
        if w.letter == 'F' && m.feed_mode != FeedMode::InverseTime {
            had[2] = true;
            let f = feed_of_word(&m, &w);
            if seg.is_cutting() && f != seg.feed {
                w = word('F', fmt_feed(seg.feed));
            }
        }
        if let Some(w) = rewrite_common(program, bi, &w, out) {
            words.push(w);
        }
    }
    if let Some(c) = coords.take() {
        words.extend(c);
    }
    modal_words(seg, had, &mut words, out);
    out.pos = seg.end;
    emit(block, words, out);
}

/// A segment without a source block, or (`passive`) with its source
/// block's passive words and comments in front.
fn write_new(program: &Program, seg: &Segment, passive: Option<&Block>, out: &mut Out) {
    let mut words: Vec<Word> = passive.map_or_else(Vec::new, |b| passive_words(program, b));
    let host = Block {
        comments: passive.map_or_else(Vec::new, |b| b.comments.clone()),
        ..Block::default()
    };
    if let Motion::Dwell { seconds } = seg.motion {
        insert_front(&mut words, word('G', "04".into()));
        words.push(dwell_word(program, None, seconds));
        return emit(&host, words, out);
    }
    let want = motion_code(seg);
    let at = words.len();
    let coords = coord_words(program, None, seg, out);
    if seg.block.is_some() && !coords.iter().any(|w| AXES.contains(&w.letter)) {
        // A source move that ends where it starts still needs an axis word
        // to be a move when read back (an inserted one moves nothing).
        words.push(word('X', fmt_num(out.pos.x)));
    }
    words.extend(coords);
    let mut front = Vec::new();
    if let Motion::Arc(a) = seg.motion {
        if out.plane != a.plane {
            front.push(word('G', a.plane.code().to_string()));
            out.plane = a.plane;
        }
    }
    if want != out.motion {
        if let Some(m) = want {
            front.push(word('G', m.code().to_string()));
        }
        out.motion = want;
    }
    words.splice(at..at, front);
    if seg.is_cutting() && out.feed != Some(seg.feed) {
        words.push(word('F', fmt_feed(seg.feed)));
        out.feed = Some(seg.feed);
    }
    out.pos = seg.end;
    emit(&host, words, out);
}

/// True when `program`'s blocks cannot be rewritten one by one (see the
/// module header): macro code, a G92 block (even one that shifts nothing),
/// a G68 rotation, `fixed`
/// segments, or segments out of block order.
fn needs_flat(program: &Program) -> bool {
    let mut last = None;
    let out_of_order = program.segments.iter().any(|s| {
        let before = last;
        last = s.block;
        s.block.is_none() || s.block <= before
    });
    program.has_macros()
        || out_of_order
        || program.segments.iter().any(|s| s.fixed)
        || program
            .modal
            .iter()
            .any(|m| m.offset.iter().any(|&o| o != 0.0) || m.rotation.is_some())
        // a G92 that happens to shift nothing (it names the current
        // position) still holds words in the source's units, which the
        // block writer would keep as they are under G21
        || program.blocks.iter().any(|b| {
            b.words_of('G')
                .any(|g| matches!((g.value * 10.0).round() as i64, 920..=923))
        })
}

/// The words of `block` that move nothing but must stay with it: N, S, T,
/// D, H and M (not the subprogram calls and returns [`CALL_M`]), and the
/// G codes that choose the frame the written coordinates are in
/// ([`frame_code`]), with the P of a G54.1/G154 extended work offset.
fn passive_words(program: &Program, block: &Block) -> Vec<Word> {
    let extended = block.words_of('G').any(|g| matches!(g_code(g), 541 | 1540));
    block
        .words
        .iter()
        .filter(|w| passive(program, block, w, extended))
        .cloned()
        .collect()
}

/// M codes that call or return from a subprogram: a flat program runs
/// the body in place and writes none of them.
const CALL_M: [i64; 4] = [97, 98, 99, 198];

/// `w` of `block` is a word [`passive_words`] keeps (`extended`: the block
/// selects a G54.1/G154 work offset, whose P is kept).
fn passive(program: &Program, block: &Block, w: &Word, extended: bool) -> bool {
    match w.letter {
        'N' | 'S' | 'T' | 'D' | 'H' => true,
        'M' => !CALL_M.contains(&(w.value as i64)),
        'G' => frame_code(program, block, w),
        'P' => extended,
        _ => false,
    }
}

/// G codes a flat program keeps, because the written coordinates mean
/// something else without them: the work offsets G54–G59 (G54.1, G59.x,
/// Haas G110–G129 and G154: mtmotion does not simulate their values, so
/// the segments are in the offset's frame), the tool length offset
/// G43/G44/G49 (the Z words are the tool tip's), and the cutter
/// compensation G40 and a G41/G42 whose stretch was simulated on the
/// programmed path (no known radius: the segments are the contour, not the
/// tool centre; a stretch with a known radius is written as the tool
/// centre and its G41/G42 goes).
fn frame_code(program: &Program, block: &Block, g: &Word) -> bool {
    match g_code(g) {
        540..=599 | 1100..=1290 | 1540 | 430 | 434 | 440 | 490 | 400 => true,
        410 | 411 | 420 | 421 => program.cutter.iter().any(|c| {
            c.line == block.line && c.file.is_none() == (block.file == 0) && c.radius.is_none()
        }),
        _ => false,
    }
}

/// A block without motion, flat: its passive words and comments.
fn write_passive(program: &Program, bi: usize, out: &mut Out) {
    let Some(block) = program.blocks.get(bi) else {
        return;
    };
    let words = passive_words(program, block);
    if words.is_empty() && block.comments.is_empty() && !block.percent {
        return;
    }
    let host = Block {
        comments: block.comments.clone(),
        percent: block.percent,
        block_delete: block.block_delete,
        ..Block::default()
    };
    emit(&host, words, out);
}

/// The program written flat: the segments in order, each a block; the
/// blocks of the main program (not a Fadal definition's) without motion in
/// place, up to its end
/// (its first M2/M30 in the text, else where the run ended), so a
/// subprogram body after it is not read as main program — also when the
/// run ended inside a subprogram (an M30 in a body called before the main
/// program's own M30: the body's segments are not main-program blocks).
fn write_flat(program: &Program, segments: &[Segment], out: &mut Out) {
    let ends = |b: &Block| {
        b.file == 0 && !b.block_delete && b.words.iter().any(super::gcodes::is_program_end)
    };
    // Fadal subroutine definitions (before the main program) are not main
    // program blocks either, nor is the M30 that ends them.
    let fadal = super::fadal::Subroutines::new(&program.blocks).unwrap_or_default();
    let main = |j: usize| !fadal.in_definitions(j);
    let end = program
        .blocks
        .iter()
        .enumerate()
        .position(|(j, b)| main(j) && ends(b))
        .or_else(|| program.modal.iter().position(|m| m.ended))
        .unwrap_or(program.blocks.len().saturating_sub(1));
    // The last segment of each block: a block that makes several (a canned
    // cycle) and ends the program has its M2/M30 written after its last
    // segment, not with its first, or the rest would not be read back.
    let mut last_of = std::collections::HashMap::new();
    for (k, seg) in segments.iter().enumerate() {
        if let Some(bi) = seg.block {
            last_of.insert(bi, k);
        }
    }
    let mut held: Option<(usize, Vec<Word>)> = None;
    let mut next = 0usize;
    for (k, seg) in segments.iter().enumerate() {
        match seg.block {
            Some(bi) if bi >= next && bi <= end && main(bi) => {
                for j in (next..bi).filter(|&j| main(j)) {
                    write_passive(program, j, out);
                }
                next = bi + 1;
                let block = program.blocks.get(bi);
                match block.filter(|b| last_of.get(&bi) != Some(&k) && ends(b)) {
                    Some(b) => {
                        let (stop, rest): (Vec<Word>, Vec<Word>) = b
                            .words
                            .iter()
                            .cloned()
                            .partition(super::gcodes::is_program_end);
                        held = Some((bi, stop));
                        let kept = Block {
                            words: rest,
                            ..b.clone()
                        };
                        write_new(program, seg, Some(&kept), out);
                    }
                    None => write_new(program, seg, block, out),
                }
            }
            _ => write_new(program, seg, None, out),
        }
        if let Some((_, stop)) = held.take_if(|(bi, _)| last_of.get(bi) == Some(&k)) {
            emit(&Block::default(), stop, out);
        }
    }
    for j in (next..=end.min(program.blocks.len())).filter(|&j| main(j)) {
        write_passive(program, j, out);
    }
    // The modes every written number assumes, after a leading `%`: a
    // control left in G20, G91, G95 or another plane would read the flat
    // program's millimetres otherwise (the source's own G20/G91/G95 words
    // are not written).
    let at = out.lines.iter().take_while(|l| l.starts_with('%')).count();
    out.lines.insert(at, FLAT_MODES.to_string());
}

/// `program` written flat whatever its form (see the module header), for a
/// caller that must move words the source computes (macro code, cycles,
/// subprogram bodies), checked before it is given out:
/// - it has no cutter compensation (a flat program would carry the
///   G41/G42 over moves that are no longer the ones it was programmed on)
///   and no G10 (offsets it sets would be in the source's units);
/// - every word that moves nothing but matters (M, S, T, D, H and the
///   frame codes: work offsets, tool length, cutter compensation) is in it as often as in the source:
///   one in a macro-computed word, in a subprogram body or in a block the
///   run skipped would be lost;
/// - read back, it gives the same moves, each end within 1 µm.
///
/// Returns the text and the program it reads back as (with `program`'s
/// options).
///
/// # Errors
/// The first reason it cannot be given out, with its line where it has one.
pub fn write_expanded(program: &Program) -> Result<(String, Program), String> {
    if let Some(c) = program.cutter.first() {
        return Err(format!(
            "line {}: cutter compensation ({}) would apply to moves it was not programmed on",
            c.line, c.code
        ));
    }
    let want = flat_words(program)?;
    let mut out = Out::new(program);
    write_flat(program, &program.segments, &mut out);
    let text = out.lines.join("\n");
    let back = keeps_all(program, &text, &want)?;
    // (end, source line) of each move
    let moved = |p: &Program| {
        p.segments
            .iter()
            .filter(|s| !matches!(s.motion, Motion::Dwell { .. }))
            .map(|s| (s.end, s.line))
            .collect::<Vec<_>>()
    };
    let (a, b) = (moved(program), moved(&back));
    if a.len() != b.len() {
        return Err(format!(
            "written flat it reads back as {} moves instead of {}",
            b.len(),
            a.len()
        ));
    }
    let far = |p: &Pose, q: &Pose| {
        p.to_array()
            .iter()
            .zip(q.to_array())
            .any(|(u, v)| (u - v).abs() > 1e-3)
    };
    if let Some(k) = (0..a.len()).find(|&k| far(&a[k].0, &b[k].0)) {
        return Err(format!(
            "written flat, move {} (line {}) reads back more than 1 µm away",
            k + 1,
            a[k].1
        ));
    }
    Ok((text, back))
}

/// [`write()`], refusing a program written flat (as the module header says) that
/// would lose a word that moves nothing but matters, as
/// [`write_expanded`] does (a macro-computed `S#1 M3`, an M8 in a
/// subprogram body, a G10); the segments may be edited.
///
/// # Errors
/// What would be lost, with its line.
pub fn write_checked(program: &Program, segments: &[Segment]) -> Result<String, String> {
    if !needs_flat(program) {
        return Ok(write(program, segments));
    }
    let want = flat_words(program)?;
    let text = write(program, segments);
    keeps_all(program, &text, &want)?;
    Ok(text)
}

/// (letter, text) → (first line, count) of the words a flat program keeps
/// ([`keeps`]).
type Kept = BTreeMap<(char, String), (usize, usize)>;

/// The source's [`Kept`] words, macro lines' literal ones included;
/// refuses a G10 and such a word computed by macro code.
fn flat_words(program: &Program) -> Result<Kept, String> {
    let mut want = Kept::new();
    for b in &program.blocks {
        if b.words_of('G').any(|g| g_code(g) == 100) {
            return Err(format!(
                "line {}: G10 sets offsets in the source's units",
                b.line
            ));
        }
        let mut kept = passive_words(program, b);
        if let Some(Stmt::Block(words, _)) = b.macro_line.as_ref().map(|m| &m.stmt) {
            for w in words
                .iter()
                .filter(|w| matches!(w.letter, 'M' | 'S' | 'T' | 'D' | 'H' | 'G'))
            {
                let Some(text) = &w.text else {
                    return Err(format!(
                        "line {}, column {}: its {} word is computed by macro code, which a flat program cannot carry",
                        b.line, w.column, w.letter
                    ));
                };
                kept.push(word(w.letter, text.clone()));
            }
        }
        for w in kept.into_iter().filter(|w| keeps(program, b, w)) {
            want.entry((w.letter, String::from(w.text)))
                .or_insert((b.line, 0))
                .1 += 1;
        }
    }
    Ok(want)
}

/// `text` (`program` written flat) read back, when it holds every word of
/// `want` as often.
fn keeps_all(program: &Program, text: &str, want: &Kept) -> Result<Program, String> {
    let back = super::program::parse_with(text, &program.options)
        .map_err(|e| format!("written flat it does not read back ({e})"))?;
    let mut got: BTreeMap<(char, String), usize> = BTreeMap::new();
    for b in &back.blocks {
        for w in passive_words(&back, b)
            .into_iter()
            .filter(|w| keeps(&back, b, w))
        {
            *got.entry((w.letter, String::from(w.text))).or_default() += 1;
        }
    }
    if let Some(((letter, t), (line, _))) = want
        .iter()
        .find(|(k, (_, n))| got.get(*k).copied().unwrap_or(0) < *n)
    {
        return Err(format!(
            "line {line}: its {letter}{t} is in a subprogram body, a macro line or a block \
             the run skips, where a flat program would lose it"
        ));
    }
    Ok(back)
}

/// The words [`write_expanded`] counts: those [`passive_words`] keeps,
/// but not N numbers (a flat program numbers nothing it adds).
fn keeps(program: &Program, b: &Block, w: &Word) -> bool {
    w.letter != 'N' && passive(program, b, w, true)
}

/// The block that starts a flat program's motion: millimetres, absolute,
/// feed per minute, XY plane.
pub const FLAT_MODES: &str = "G21 G90 G94 G17";

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::program::parse;

    #[test]
    fn inserted_blocks_restore_modal_motion() {
        let p = parse("G0 X0 Y0\nG2 X10 Y0 R5 F600\nX20 R5").unwrap();
        let mut segs = p.segments.clone();
        let mut line = segs[1].clone();
        line.block = None;
        line.motion = Motion::Linear;
        line.start = segs[1].end;
        line.end = segs[1].end;
        segs.insert(2, line);
        let text = write(&p, &segs);
        assert_eq!(text, "G0 X0 Y0\nG2 X10 Y0 R5 F600\nG1\nG2 X20 R5");
        let q = parse(&text).unwrap();
        assert_eq!(q.segments.len(), 3, "a zero-length G1 block moves nothing");
        assert_eq!(q.segments[2].motion, p.segments[2].motion);
    }

    #[test]
    fn flat_programs_keep_their_frame() {
        // G92 forces the flat form; G55, G43 H2, G41 D1 (radius unknown:
        // the moves are the contour) and G40 stay where they were.
        let src = "G20 G90 G55\nG92 X0 Y0\nG0 G43 H2 Z1.\nG41 D1 G1 X1. Y0.5 F10.\nY1.\nG40 G0 X0 Y0\nG49 M30";
        let p = parse(src).unwrap();
        let text = write(&p, &p.segments);
        assert_eq!(
            text,
            "G21 G90 G94 G17\nG55\nG43 H2 G0 Z25.4\nG41 D1 G1 X25.4 Y12.7 F254.\nY25.4\nG40 G0 X0. Y0.\nG49 M30"
        );
        // With the radius known the moves are the tool centre: G41 goes.
        let mut opts = crate::nc::program::ParseOptions::default();
        opts.tool_radii.insert("D1", 0.1).unwrap();
        let q = crate::nc::program::parse_with(src, &opts).unwrap();
        let text = write(&q, &q.segments);
        assert!(!text.contains("G41") && text.contains("D1 G1"), "{text}");
        // G54.1 P3 keeps its P.
        let p = parse("G90 G54.1 P3\nG92 X0\nG1 X1 F100").unwrap();
        assert_eq!(
            write(&p, &p.segments),
            "G21 G90 G94 G17\nG54.1 P3\nG1 X1. F100."
        );
    }

    #[test]
    fn dwells_keep_their_dialect() {
        let p = parse("G4 X0.5\nG4 P200\nG4 P0.3").unwrap();
        let mut segs = p.segments.clone();
        for s in &mut segs {
            if let Motion::Dwell { seconds } = &mut s.motion {
                *seconds *= 2.0;
            }
        }
        segs.push(Segment {
            block: None,
            line: 0,
            ..segs[0].clone()
        });
        assert_eq!(write(&p, &segs), "G4 X1.\nG4 P400\nG4 P0.6\nG04 P1000");
    }
}
