//! Source-preserving NC writer: gives back the program's own text with only
//! the words that must change to reach an edited list of [`Segment`]s, so
//! a line diff against the original shows just the edit (the compensation).
//!
//! What is kept, byte for byte, on every line that needs no change: the
//! text, the comments (`( … )` and `;`, also with parentheses inside), the
//! N numbers, the case and spacing, the line endings (LF, CRLF or CR), a
//! byte-order mark, a trailing Ctrl-Z and a missing final newline. On a
//! changed line only the changed numbers are replaced, in place.
//!
//! Readings:
//! - units and modes are the block's own: a G20 block gets inch values, a
//!   G91 block incremental values, a G90.1 block absolute centres, a G92
//!   shift is subtracted; feeds are never touched;
//! - under a G68 rotation ([`super::rotation`]) the segments (un-rotated,
//!   as simulated and corrected) are turned back into the block's rotated
//!   frame before its words are written: end points and absolute centres
//!   as points about the rotation centre, incremental I/J/K and G91
//!   increments as vectors, R unchanged; the read-back end is turned
//!   forward again, so the next block starts from what the control will
//!   compute;
//! - numbers follow the program's style ([`NumStyle`], in the block's
//!   own style where it shows one): its number of decimals (raised to 3
//!   in mm or 4 in inch — 1 µm, 2.5 µm — when the program is coarser, so
//!   a compensation is not rounded away), trailing zeros kept as it keeps
//!   them (`1.500`, `3.0`, `3.`), `.5` or `0.5`, `75.` or `75`; a number
//!   whose new value reads as the old one keeps its text byte for byte;
//! - each coordinate is written once and read back, and the next block is
//!   computed from the read-back value, so rounding never accumulates; an
//!   axis the edit leaves where the segment started (a full circle's end, a
//!   helix's plane coordinates) is written with the start's own written
//!   value, so a full circle stays a full circle in every plane;
//! - a segment without a source block (`block: None`) becomes a new line:
//!   a connecting `G1` just before the next source block (whose motion code
//!   is then written on it if it relied on a modal G2/G3/G0), or a dwell
//!   just after the previous one, in the dialect's safe dwell form
//!   ([`super::dialect::dwell_form`]: `G4 P<seconds>` in a LinuxCNC
//!   program, else the program's own `X`/`U` seconds or `P` seconds, else
//!   `P<whole milliseconds>`);
//! - in a program that numbers its blocks (N words on at least half of
//!   them) a new line gets the next free number after its predecessor's
//!   (`N21` between `N20` and `N30`, zero-padded like it), or none where
//!   the numbers leave no room;
//! - blocks with several segments (subprogram bodies, cycles, corners) and
//!   `fixed` segments are never edited.
//!
//! Units: mm, mm/min inside; the text in the program's own units.

use super::block::length_scale;
use super::dialect::{dwell_form, DwellForm, DwellTime};
use super::program::{FeedMode, Modal, Motion, Program, Segment};
use super::Block;

use super::num_style::same_number;
pub use super::num_style::NumStyle;

/// Position differences below this are no move, mm (below any written resolution).
const SAME: f64 = 1e-9;

/// The text split into lines that keep their terminators; concatenating
/// `head`, every `(content, end)` and `tail` gives the text back.
struct Lines<'a> {
    head: &'a str,
    lines: Vec<(&'a str, &'a str)>,
    tail: &'a str,
}

/// Splits as [`super::split_lines`] does (same line numbers).
fn split_keep(text: &str) -> Lines<'_> {
    let head_len = if text.starts_with('\u{feff}') { 3 } else { 0 };
    let body_all = &text[head_len..];
    let body = body_all.trim_end_matches(['\u{1a}', '\r', '\n']);
    let b = body.as_bytes();
    let mut lines = Vec::new();
    let (mut start, mut i) = (0, 0);
    while i < b.len() {
        let end = match b[i] {
            b'\n' => i + 1,
            b'\r' if b.get(i + 1) == Some(&b'\n') => i + 2,
            b'\r' => i + 1,
            _ => {
                i += 1;
                continue;
            }
        };
        lines.push((&body[start..i], &body[i..end]));
        start = end;
        i = end;
    }
    if start < body.len() || lines.is_empty() {
        lines.push((&body[start..], ""));
    }
    Lines {
        head: &text[..head_len],
        lines,
        tail: &body_all[body.len()..],
    }
}

/// The line terminator of `text` (its first), LF when it has none.
fn newline(text: &str) -> &'static str {
    match text.find(['\r', '\n']) {
        Some(i) if text[i..].starts_with("\r\n") => "\r\n",
        Some(i) if text[i..].starts_with('\r') => "\r",
        _ => "\n",
    }
}

/// Program-wide spelling of new words and lines.
struct Dialect {
    mm: NumStyle,
    inch: NumStyle,
    lower: bool,
    space: &'static str,
    g_pad: bool,
    dwell: DwellForm,
}

impl Dialect {
    fn of(p: &Program, raw: &[(&str, &str)]) -> Self {
        let inch_used = p.modes.any_inch();
        let g_pad = p
            .blocks
            .iter()
            .flat_map(|b| &b.words)
            .any(|w| w.letter == 'G' && w.text.len() == 2 && w.text.starts_with('0'));
        // Spacing and case from the first block with two words.
        let (mut spaced, mut lower) = (true, false);
        if let Some(b) = p.blocks.iter().find(|b| b.words.len() >= 2) {
            let (w0, w1) = (&b.words[0], &b.words[1]);
            let line: Vec<char> = raw
                .get(b.line.saturating_sub(1))
                .map(|(s, _)| s.chars().collect())
                .unwrap_or_default();
            spaced = line
                .get(w1.column.saturating_sub(2))
                .is_some_and(|c| c.is_whitespace());
            lower = line
                .get(w0.column.saturating_sub(1))
                .is_some_and(|c| c.is_ascii_lowercase());
        }
        Self {
            mm: NumStyle::of(&p.blocks, false),
            inch: NumStyle::of(&p.blocks, inch_used),
            lower,
            space: if spaced { " " } else { "" },
            g_pad,
            dwell: dwell_form(p),
        }
    }

    fn style(&self, m: &Modal) -> &NumStyle {
        if m.inch {
            &self.inch
        } else {
            &self.mm
        }
    }

    fn letter(&self, c: char) -> char {
        if self.lower {
            c.to_ascii_lowercase()
        } else {
            c
        }
    }

    fn g(&self, code: u32) -> String {
        if self.g_pad {
            format!("{}{code:02}", self.letter('G'))
        } else {
            format!("{}{code}", self.letter('G'))
        }
    }

    /// A dwell of `seconds` in the dialect's form
    /// ([`super::dialect::dwell_form`]).
    fn dwell_line(&self, seconds: f64) -> String {
        let sec = NumStyle {
            decimals: 3,
            min_decimals: 0,
            lead_zero: self.mm.lead_zero,
            int_point: true,
        };
        let g = match &self.dwell.g {
            Some(t) => format!("{}{t}", self.letter('G')),
            None => self.g(4),
        };
        let (letter, v) = match self.dwell.time {
            DwellTime::Seconds(l) => (l, sec.format(seconds)),
            DwellTime::SecondsP => ('P', sec.format(seconds)),
            DwellTime::MillisecondsP => {
                let ms = (seconds * 1e3).round();
                let ms = if seconds > 0.0 { ms.max(1.0) } else { ms };
                ('P', format!("{ms:.0}"))
            }
        };
        format!("{g}{}{}{v}", self.space, self.letter(letter))
    }
}

/// A replacement of characters `at..at + len` of a line, or an insertion
/// (`len` 0).
#[derive(Default)]
struct Splice {
    at: usize,
    len: usize,
    text: String,
}

/// Where the number of `block.words[j]` lies in `chars` (start, length).
fn number_span(chars: &[char], col: usize, text: &str) -> Option<(usize, usize)> {
    let mut p = col;
    while p < chars.len() && chars[p].is_whitespace() {
        p += 1;
    }
    let n = text.chars().count();
    let got: String = chars.get(p..p + n)?.iter().collect();
    (got == text).then_some((p, n))
}

/// Where the writer is in the edit's segments ([`Writer::push`]).
#[derive(Default)]
struct Walk {
    /// The position written so far (the first segment's start before any).
    pos: Option<[f64; 3]>,
    /// The motion code in force when it may differ from the one the next
    /// block relies on (after a new G1 line, or a block whose code the
    /// edit changed).
    restore: Option<u32>,
    /// The source line of the last source block.
    last_line: Option<usize>,
    /// New segments (`block: None`) waiting for the next source block.
    pending: Vec<Segment>,
}

struct Writer<'a> {
    p: &'a Program,
    /// The source lines (content, terminator).
    raw: &'a [(&'a str, &'a str)],
    d: Dialect,
    nl: &'static str,
    /// Replacement content per line (None = unchanged).
    content: Vec<Option<String>>,
    before: Vec<Vec<String>>,
    after: Vec<Vec<String>>,
    /// The segment of each block (None when it has none or several).
    seg_of: Vec<Option<usize>>,
}

/// Writes `text` back with `segments` in place of `program`'s (see the module header).
///
/// `program` must be `text` parsed; `segments` its segments edited in
/// place (same `block`) plus new ones with `block: None`.
///
/// # Units
/// Segments in mm and mm/min; the text in the program's units.
///
/// # Examples
/// ```
/// use mtmotion::nc::{patch::write_source, program::{parse, Motion}};
/// let src = "G20 G0 X0 Y0\r\nN5 G2 X.5 Y0 R.25 F20 ; top (arc)\r\n";
/// let p = parse(src).unwrap();
/// let mut segs = p.segments.clone();
/// segs[1].end.x = 0.6 * 25.4;
/// if let Motion::Arc(a) = &mut segs[1].motion { a.radius = 0.3 * 25.4; }
/// let out = write_source(src, &p, &segs);
/// assert_eq!(out, "G20 G0 X0 Y0\r\nN5 G2 X.6 Y0 R.3 F20 ; top (arc)\r\n");
/// ```
pub fn write_source(text: &str, program: &Program, segments: &[Segment]) -> String {
    write_source_each(text, program, |put| segments.iter().for_each(put))
}

/// As [`write_source`], with the segments given one at a time in order
/// (`each` calls `put` on every one): the caller need not hold them all,
/// so a compensation can write its edit as it rebuilds it (a 1 M-segment
/// command is 176 MB beside the blocks the writer reads).
pub fn write_source_each(
    text: &str,
    program: &Program,
    each: impl FnOnce(&mut dyn FnMut(&Segment)),
) -> String {
    let lines = split_keep(text);
    let nb = lines.lines.len();
    let mut count = vec![0usize; program.blocks.len()];
    let mut seg_of = vec![None; program.blocks.len()];
    for (i, s) in program.segments.iter().enumerate() {
        if let Some(b) = s.block.filter(|&b| b < count.len()) {
            count[b] += 1;
            seg_of[b] = Some(i);
        }
    }
    for (b, c) in count.iter().enumerate() {
        if *c != 1 {
            seg_of[b] = None;
        }
    }
    drop(count);
    let raw = &lines.lines[..];
    let mut w = Writer {
        p: program,
        d: Dialect::of(program, raw),
        raw,
        nl: newline(text),
        content: vec![None; nb],
        before: vec![Vec::new(); nb],
        after: vec![Vec::new(); nb],
        seg_of,
    };
    let mut walk = Walk::default();
    each(&mut |seg| w.push(&mut walk, seg));
    w.flush(&mut walk, None);
    number_new_lines(program, &w.d, &mut w.before, &mut w.after);
    // Measured, then written: a text grown by doubling would hold twice
    // its size (a 30 MB program's 60 MB, and 90 MB while it grows).
    let emit = |put: &mut dyn FnMut(&str)| {
        put(lines.head);
        for (i, (c, end)) in lines.lines.iter().enumerate() {
            for l in &w.before[i] {
                put(l);
                put(w.nl);
            }
            put(w.content[i].as_deref().unwrap_or(c));
            let extra = &w.after[i];
            if !extra.is_empty() {
                put(if end.is_empty() { w.nl } else { end });
                for (k, l) in extra.iter().enumerate() {
                    put(l);
                    if k + 1 < extra.len() || !end.is_empty() {
                        put(w.nl);
                    }
                }
            } else {
                put(end);
            }
        }
        put(lines.tail);
    };
    let mut len = 0;
    emit(&mut |s| len += s.len());
    let mut out = String::with_capacity(len);
    emit(&mut |s| out.push_str(s));
    out
}

/// The N number of each source line of the main file (value and the
/// width of a zero-padded one, else 0), when the program numbers its
/// blocks: at least half of its blocks with words carry an N word.
fn line_numbers(program: &Program, lines: usize) -> Option<Vec<Option<(u64, usize)>>> {
    let main = program
        .blocks
        .iter()
        .filter(|b| b.file == 0 && !b.words.is_empty());
    let (mut blocks, mut numbered) = (0usize, 0usize);
    let mut n_of = vec![None; lines];
    for b in main {
        blocks += 1;
        let Some(w) = b.word('N') else { continue };
        numbered += 1;
        if let Some(slot) = n_of.get_mut(b.line.wrapping_sub(1)) {
            let digits = w.text.trim_start_matches('+');
            let width = if digits.starts_with('0') {
                digits.len()
            } else {
                0
            };
            if w.value >= 0.0 && w.value.fract() == 0.0 {
                *slot = Some((w.value as u64, width));
            }
        }
    }
    (numbered > 0 && 2 * numbered >= blocks).then_some(n_of)
}

/// Gives the new lines of a program that numbers its blocks an N number
/// of their own: a run of new lines between the source lines numbered `a`
/// and `b` gets `a + 1`, `a + 2`, … (the width of a zero-padded `a`) when
/// they fit below `b` and no block of the program already carries one of
/// them (an `M97 P`, `M99 P` or `GOTO` finds its block by the number, so
/// it must stay unique), so no number repeats and the order is kept; a run
/// that does not fit, or comes before the first numbered line, stays
/// without N numbers (an N number is optional on every control).
fn number_new_lines(
    program: &Program,
    d: &Dialect,
    before: &mut [Vec<String>],
    after: &mut [Vec<String>],
) {
    let Some(n_of) = line_numbers(program, before.len()) else {
        return;
    };
    let used: std::collections::HashSet<u64> = program
        .blocks
        .iter()
        .filter_map(|b| b.word('N'))
        .filter(|w| w.value >= 0.0 && w.value.fract() == 0.0)
        .map(|w| w.value as u64)
        .collect();
    let mut prev: Option<(u64, usize)> = None;
    let mut run: Vec<(bool, usize, usize)> = Vec::new();
    for (i, n) in n_of.iter().enumerate() {
        run.extend((0..before[i].len()).map(|j| (false, i, j)));
        if let Some(n) = *n {
            number_run(d, &mut run, (prev, Some(n.0)), &used, before, after);
            prev = Some(n);
        }
        run.extend((0..after[i].len()).map(|j| (true, i, j)));
    }
    number_run(d, &mut run, (prev, None), &used, before, after);
}

/// Numbers one run of new lines (see [`number_new_lines`]) and empties it.
fn number_run(
    d: &Dialect,
    run: &mut Vec<(bool, usize, usize)>,
    (prev, next): (Option<(u64, usize)>, Option<u64>),
    used: &std::collections::HashSet<u64>,
    before: &mut [Vec<String>],
    after: &mut [Vec<String>],
) {
    if let Some((a, width)) = prev {
        let n = run.len() as u64;
        let free = (1..=n).all(|k| !used.contains(&a.saturating_add(k)));
        if next.unwrap_or(u64::MAX).saturating_sub(a) > n && free {
            for (k, &(is_after, i, j)) in run.iter().enumerate() {
                let line = if is_after {
                    &mut after[i][j]
                } else {
                    &mut before[i][j]
                };
                *line = format!(
                    "{}{:0width$}{}{line}",
                    d.letter('N'),
                    a + 1 + k as u64,
                    d.space
                );
            }
        }
    }
    run.clear();
}

/// A source block being edited to carry `seg` (originally `o`) from `pos`.
struct Edit<'a> {
    block: &'a Block,
    line: &'a [char],
    m: Modal,
    seg: &'a Segment,
    o: &'a Segment,
    pos: [f64; 3],
    same_start: bool,
    /// The number style of the block.
    st: NumStyle,
}

impl Writer<'_> {
    fn line_of(&self, block: usize) -> Option<usize> {
        self.p
            .blocks
            .get(block)
            .map(|b| b.line.saturating_sub(1))
            .filter(|&l| l < self.content.len())
    }

    /// The modes after `block` the writer reads ([`Program::modes`]).
    fn modal(&self, block: usize) -> Modal {
        self.p.modes.get(block).unwrap_or_default()
    }

    /// Takes the next segment of the edit: a source block's is written at
    /// once, a new one (`block: None`) when the next source block is known
    /// (a connecting line goes just before it, in the modes in force there).
    fn push(&mut self, w: &mut Walk, seg: &Segment) {
        if w.pos.is_none() {
            w.pos = Some(seg.start.p());
        }
        let Some(b) = seg.block else {
            w.pending.push(seg.clone());
            return;
        };
        self.flush(w, Some(b));
        if let Some(l) = self.line_of(b) {
            w.last_line = Some(l);
        }
        if matches!(seg.motion, Motion::Dwell { .. }) {
            return;
        }
        let pos = w.pos.unwrap_or(self.p.options.start.p());
        let (p, changed_mode) = self.block(b, seg, pos, w.restore.take());
        w.pos = Some(p);
        w.restore = changed_mode;
    }

    /// Writes the new segments waiting for the next source block, `next`
    /// (`None`: there is none).
    fn flush(&mut self, w: &mut Walk, next: Option<usize>) {
        let mut pending = std::mem::take(&mut w.pending);
        for seg in &pending {
            if let Motion::Dwell { seconds } = seg.motion {
                let at = w.last_line.unwrap_or(0);
                let l = self.d.dwell_line(seconds);
                if let Some(v) = self.after.get_mut(at) {
                    v.push(l);
                }
                continue;
            }
            let pos = w.pos.unwrap_or(self.p.options.start.p());
            let Some((text, new_pos)) = self.new_line(seg, pos, next) else {
                continue;
            };
            w.pos = Some(new_pos);
            match next.and_then(|b| self.line_of(b)) {
                Some(l) => self.before[l].push(text),
                None => {
                    let at = w.last_line.unwrap_or(0);
                    self.after[at].push(text);
                }
            }
            w.restore = Some(1);
        }
        pending.clear();
        w.pending = pending;
    }

    /// A new G1 line to `seg.end` from `pos`, in the modes in force before
    /// `next`; `None` when no axis moves at the written resolution (a
    /// connecting line of less than a digit is left out, not written as a
    /// bare `G1`).
    fn new_line(
        &self,
        seg: &Segment,
        pos: [f64; 3],
        next: Option<usize>,
    ) -> Option<(String, [f64; 3])> {
        let m = match next {
            Some(b) if b > 0 => self.modal(b - 1),
            Some(_) => Modal::default(),
            None => self.p.modes.last().unwrap_or_default(),
        };
        let mut parts = vec![self.d.g(1)];
        let (to, pos) = (program_point(&m, seg.end.p()), program_point(&m, pos));
        let mut out = pos;
        for (k, letter) in ['X', 'Y', 'Z'].into_iter().enumerate() {
            if (to[k] - pos[k]).abs() <= SAME {
                continue;
            }
            let (t, v) = self.coord(&m, self.d.style(&m), to[k], pos[k], k);
            if (v - pos[k]).abs() > SAME {
                parts.push(format!("{}{t}", self.d.letter(letter)));
                out[k] = v;
            }
        }
        if parts.len() == 1 {
            return None;
        }
        let out = machine_point(&m, out);
        let length = seg.timed_length();
        let inverse = m.feed_mode == FeedMode::InverseTime;
        let differs = m
            .feed_mm_min(length)
            .is_none_or(|f| (f - seg.feed).abs() > 1e-9);
        if (differs || inverse) && seg.feed > 0.0 {
            // mm/min; under G95 mm per revolution (F × S is the feed); under
            // G93 1/min, on every move (F × length is the feed)
            let u = match m.feed_mode {
                FeedMode::PerMinute => length_scale(&m),
                FeedMode::PerRevolution => length_scale(&m) * m.spindle.unwrap_or(1.0),
                FeedMode::InverseTime => length.max(f64::MIN_POSITIVE),
            };
            parts.push(format!(
                "{}{}",
                self.d.letter('F'),
                NumStyle {
                    decimals: if inverse { 6 } else { 3 },
                    min_decimals: 0,
                    lead_zero: true,
                    int_point: false
                }
                .format(seg.feed / u)
            ));
        }
        Some((parts.join(self.d.space), out))
    }

    /// The text of coordinate `target` (mm) on axis `k` from `pos` in mode
    /// `m`, and the position it is read back as.
    fn coord(&self, m: &Modal, st: &NumStyle, target: f64, pos: f64, k: usize) -> (String, f64) {
        let u = length_scale(m);
        let v = if m.incremental {
            (target - pos) / u
        } else {
            (target - m.offset[k]) / u
        };
        let t = st.format(v);
        let back: f64 = t.parse().unwrap_or(v);
        let mm = if m.incremental {
            pos + back * u
        } else {
            back * u + m.offset[k]
        };
        (t, mm)
    }

    /// Patches source block `b` to carry `seg` from `pos`, with motion
    /// code `restore` in force before it when that may differ from the
    /// original's; returns the position read back and the block's new
    /// motion code when it differs from the original's (the next block
    /// must then state its own).
    fn block(
        &mut self,
        b: usize,
        seg: &Segment,
        pos: [f64; 3],
        restore: Option<u32>,
    ) -> ([f64; 3], Option<u32>) {
        let Some(oi) = self.seg_of.get(b).copied().flatten() else {
            return (seg.end.p(), None);
        };
        let o = &self.p.segments[oi];
        if o.fixed {
            return (seg.end.p(), None);
        }
        let (Some(block), Some(l)) = (self.p.blocks.get(b), self.line_of(b)) else {
            return (seg.end.p(), None);
        };
        // A block that relies on the code now in force needs nothing.
        let restore = restore.is_some_and(|c| Some(c) != motion_code(&o.motion));
        let same_start = pos == o.start.p();
        if same_start && seg.end == o.end && seg.motion == o.motion && !restore {
            return (o.end.p(), None);
        }
        let m = self.modal(b);
        let st = self.d.style(&m).in_block(block, m.inch);
        let line: Vec<char> = match &self.content[l] {
            Some(c) => c.chars().collect(),
            None => self.p_line(l),
        };
        let e = Edit {
            block,
            line: &line,
            m,
            seg,
            o,
            pos,
            same_start,
            st,
        };
        let mut splices = Vec::new();
        let end = self.axis_splices(&e, &mut splices);
        if let (Motion::Arc(a), Motion::Arc(oa)) = (seg.motion, o.motion) {
            self.arc_words(
                block,
                &line,
                &m,
                &st,
                (&a, &oa),
                pos,
                same_start,
                &mut splices,
            );
        }
        let changed = self.motion_splices(&e, restore, &mut splices);
        if !splices.is_empty() {
            self.content[l] = Some(apply(&line, splices));
        }
        (end, changed.then(|| motion_code(&seg.motion)).flatten())
    }

    /// The splices of the X/Y/Z words of an edited block, worked out in
    /// the block's program frame (under G68 the rotated one); returns the
    /// end position read back, in the un-rotated frame.
    fn axis_splices(&self, e: &Edit, splices: &mut Vec<Splice>) -> [f64; 3] {
        let m = &e.m;
        let pos = program_point(m, e.pos);
        let mut end = pos;
        let (t1, s0, o1) = (
            program_point(m, e.seg.end.p()),
            program_point(m, e.seg.start.p()),
            program_point(m, e.o.end.p()),
        );
        for (k, letter) in ['X', 'Y', 'Z'].into_iter().enumerate() {
            // An axis the segment does not move is written as the start's
            // written value (full circles, helix plane axes).
            let target = if (t1[k] - s0[k]).abs() <= SAME {
                pos[k]
            } else {
                t1[k]
            };
            match e.block.word(letter) {
                Some(wd) => {
                    let keep = t1[k] == o1[k] && (!m.incremental || e.same_start);
                    if keep {
                        end[k] = o1[k];
                    } else {
                        let (t, v) = self.coord(m, &e.st, target, pos[k], k);
                        end[k] = v;
                        if !same_number(&t, &wd.text) {
                            if let Some((at, len)) = number_span(e.line, wd.column, &wd.text) {
                                splices.push(Splice { at, len, text: t });
                            }
                        }
                    }
                }
                None => {
                    if (target - pos[k]).abs() > SAME {
                        let (t, v) = self.coord(m, &e.st, target, pos[k], k);
                        if (v - pos[k]).abs() > SAME {
                            end[k] = v;
                            splices.push(self.insert_word(e.block, e.line, letter, t));
                        }
                    }
                }
            }
        }
        if m.rotation.is_some() && end == o1 {
            // The original end exactly, not its image through two rotations.
            return e.o.end.p();
        }
        machine_point(m, end)
    }

    /// The splices of the motion code of an edited block: a changed G0–G3,
    /// the centre words of an arc that became a line, the code written on
    /// a block that relied on a modal one the edit changed. Returns whether
    /// the modal motion now differs from the original's.
    fn motion_splices(&self, e: &Edit, restore: bool, splices: &mut Vec<Splice>) -> bool {
        let (block, line) = (e.block, e.line);
        let code_word = block
            .words
            .iter()
            .find(|w| w.letter == 'G' && w.value.fract() == 0.0 && (0.0..=3.0).contains(&w.value));
        let old_code = motion_code(&e.o.motion);
        let new_code = motion_code(&e.seg.motion);
        if let (Some(cw), Some(code)) = (code_word, new_code) {
            if old_code != new_code {
                if let Some((at, len)) = number_span(line, cw.column, &cw.text) {
                    let t = self.d.g(code);
                    splices.push(Splice {
                        at,
                        len,
                        text: t[1..].to_string(),
                    });
                }
            }
        }
        if matches!(e.seg.motion, Motion::Linear) && matches!(e.o.motion, Motion::Arc(_)) {
            for wd in block
                .words
                .iter()
                .filter(|w| matches!(w.letter, 'I' | 'J' | 'K' | 'R'))
            {
                if let Some((at, len)) = number_span(line, wd.column, &wd.text) {
                    let from = wd.column - 1;
                    splices.push(Splice {
                        at: from,
                        len: at + len - from,
                        text: String::new(),
                    });
                }
            }
        }
        let restore = restore || (code_word.is_none() && old_code != new_code);
        if let (true, None, Some(code)) = (restore, code_word, new_code) {
            let at = block
                .words
                .iter()
                .find(|w| w.letter != 'N')
                .map_or(line.len(), |w| w.column - 1);
            splices.push(Splice {
                at,
                len: 0,
                text: format!(
                    "{}{}",
                    self.d.g(code),
                    line_space(block, line, self.d.space)
                ),
            });
        }
        old_code != new_code
    }

    fn p_line(&self, l: usize) -> Vec<char> {
        self.raw
            .get(l)
            .map(|(s, _)| s.chars().collect())
            .unwrap_or_default()
    }

    /// A new word after the block's last word (before its comments).
    fn insert_word(&self, block: &Block, line: &[char], letter: char, t: String) -> Splice {
        let at = block
            .words
            .iter()
            .filter_map(|w| number_span(line, w.column, &w.text).map(|(a, n)| a + n))
            .max()
            .unwrap_or(0);
        Splice {
            at,
            len: 0,
            text: format!(
                "{}{}{t}",
                line_space(block, line, self.d.space),
                self.d.letter(letter)
            ),
        }
    }

    /// The centre words of an arc: R, or I/J/K from the written start.
    #[allow(clippy::too_many_arguments)]
    fn arc_words(
        &self,
        block: &Block,
        line: &[char],
        m: &Modal,
        st: &NumStyle,
        (a, oa): (&super::program::Arc, &super::program::Arc),
        pos: [f64; 3],
        same_start: bool,
        splices: &mut Vec<Splice>,
    ) {
        let u = length_scale(m);
        if let Some(wd) = block.word('R') {
            if a.radius == oa.radius {
                return;
            }
            let r = if a.sweep.abs() > std::f64::consts::PI {
                -a.radius
            } else {
                a.radius
            };
            let t = st.format(r / u);
            if !same_number(&t, &wd.text) {
                if let Some((at, len)) = number_span(line, wd.column, &wd.text) {
                    splices.push(Splice { at, len, text: t });
                }
            }
            return;
        }
        let (pu, pv, _) = a.plane.axes();
        let (c, oc) = (program_point(m, a.center), program_point(m, oa.center));
        let rel = [0, 1, 2].map(|k| a.center[k] - pos[k]);
        let rel = m.rotation.map_or(rel, |r| r.vector_to_program(rel));
        for k in [pu, pv] {
            let letter = ['I', 'J', 'K'][k];
            let keep = c[k] == oc[k] && (m.arc_center_absolute || same_start);
            if keep {
                continue;
            }
            let v = if m.arc_center_absolute {
                (c[k] - m.offset[k]) / u
            } else {
                rel[k] / u
            };
            let t = st.format(v);
            match block.word(letter) {
                Some(wd) if !same_number(&t, &wd.text) => {
                    if let Some((at, len)) = number_span(line, wd.column, &wd.text) {
                        splices.push(Splice { at, len, text: t });
                    }
                }
                Some(_) => {}
                None if t.trim_start_matches(['-', '0', '.']).is_empty() => {}
                None => splices.push(self.insert_word(block, line, letter, t)),
            }
        }
    }
}

/// Machine-frame point `p` in the program frame of the modal state `m`:
/// under G68 turned back into the rotated frame ([`super::rotation`]).
fn program_point(m: &Modal, p: [f64; 3]) -> [f64; 3] {
    m.rotation.map_or(p, |r| r.to_program(p))
}

/// Program-frame point `p` of the modal state `m` in the machine frame.
fn machine_point(m: &Modal, p: [f64; 3]) -> [f64; 3] {
    m.rotation.map_or(p, |r| r.to_machine(p))
}

/// The separator between words on this line: a space when its first two
/// words are apart, none when they touch, else the program's.
fn line_space(block: &Block, line: &[char], default: &'static str) -> &'static str {
    match block.words.get(1) {
        Some(w)
            if line
                .get(w.column.saturating_sub(2))
                .is_some_and(|c| c.is_whitespace()) =>
        {
            " "
        }
        Some(_) => "",
        None => default,
    }
}

fn motion_code(m: &Motion) -> Option<u32> {
    match m {
        Motion::Rapid => Some(0),
        Motion::Linear => Some(1),
        Motion::Arc(a) if a.sweep < 0.0 => Some(2),
        Motion::Arc(_) => Some(3),
        Motion::Dwell { .. } => None,
    }
}

/// `line` with `splices` applied (right to left, so positions stay valid).
fn apply(line: &[char], mut splices: Vec<Splice>) -> String {
    let mut order: Vec<usize> = (0..splices.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse((splices[i].at, splices[i].len, i)));
    let mut out: Vec<char> = line.to_vec();
    for s in order.into_iter().map(|i| std::mem::take(&mut splices[i])) {
        let at = s.at.min(out.len());
        let end = (at + s.len).min(out.len());
        out.splice(at..end, s.text.chars());
    }
    out.into_iter().collect()
}
