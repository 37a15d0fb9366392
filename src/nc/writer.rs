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
//! Numbers are written with up to 4 decimals (0.1 µm) and always with a
//! decimal point, because FANUC reads `X10` without one as 10 µm when
//! "decimal point input" is off.
//!
//! Units: mm, degrees for A/B/C, mm/min.

use super::program::{DwellP, Modal, Motion, MotionCode, Plane, Pose, Program, Segment, AXES};
use super::{Block, Word};

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

fn word(letter: char, text: String) -> Word {
    Word {
        letter,
        value: text.parse().unwrap_or(0.0),
        text,
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
    AXES.contains(&c) || matches!(c, 'I' | 'J' | 'K' | 'R')
}

struct Out {
    motion: Option<MotionCode>,
    plane: Plane,
    feed: Option<f64>,
    pos: Pose,
    lines: Vec<String>,
}

impl Program {
    /// Writes the program's own segments back (see [`write`]).
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
    let mut out = Out {
        motion: None,
        plane: Plane::XY,
        feed: None,
        pos: program.options.start,
        lines: Vec::new(),
    };
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
            _ => write_new(program, seg, &mut out),
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

/// Common word rewriting: G20→G21, G91→G90, feed to mm/min, modal tracking.
fn rewrite_common(program: &Program, bi: usize, w: &Word, out: &mut Out) -> Option<Word> {
    let m = modal_at(program, bi);
    match w.letter {
        'G' => {
            let g = g_code(w);
            let mut w = w.clone();
            match g {
                200 => w = word('G', "21".into()),
                910 => w = word('G', "90".into()),
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
            let f = if m.inch { w.value * 25.4 } else { w.value };
            out.feed = Some(f);
            Some(if m.inch {
                word('F', fmt_num(f))
            } else {
                w.clone()
            })
        }
        _ => Some(w.clone()),
    }
}

fn emit(block: &Block, words: Vec<Word>, out: &mut Out) {
    let b = Block {
        words,
        ..block.clone()
    };
    out.lines.push(b.write());
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

fn coord_words(program: &Program, bi: Option<usize>, seg: &Segment, out: &Out) -> Vec<Word> {
    let block = bi.and_then(|i| program.blocks.get(i));
    let m = bi.map(|i| modal_at(program, i)).unwrap_or_default();
    let plain = !m.inch && !m.incremental;
    let mut ws = Vec::new();
    for (i, &letter) in AXES.iter().enumerate() {
        let v = seg.end.get(i);
        let orig = block.and_then(|b| b.word(letter));
        if orig.is_none() && (v - out.pos.get(i)).abs() < 1e-7 {
            continue;
        }
        match orig {
            Some(o) if plain && o.value == v => ws.push(o.clone()),
            _ => ws.push(word(letter, fmt_num(v))),
        }
    }
    if let Motion::Arc(a) = seg.motion {
        let full = a.sweep.abs() > std::f64::consts::TAU - 1e-9;
        if a.r_form && !full {
            let r = if a.sweep.abs() > std::f64::consts::PI {
                -a.radius
            } else {
                a.radius
            };
            match block.and_then(|b| b.word('R')) {
                Some(o) if !m.inch && o.value == r => ws.push(o.clone()),
                _ => ws.push(word('R', fmt_num(r))),
            }
        } else {
            let (u, v, _) = a.plane.axes();
            let letters = ['I', 'J', 'K'];
            let p0 = seg.start.p();
            for k in [u, v] {
                let val = a.center[k] - p0[k];
                match block.and_then(|b| b.word(letters[k])) {
                    Some(o) if !m.inch && o.value == val => ws.push(o.clone()),
                    _ => ws.push(word(letters[k], fmt_num(val))),
                }
            }
        }
    }
    ws
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
            return word(o.letter, fmt_num(seconds));
        }
    }
    let ms = seconds * 1000.0;
    match program.options.dwell_p {
        DwellP::Seconds => word('P', fmt_num(seconds)),
        DwellP::Milliseconds => word('P', format!("{}", ms.round() as i64)),
        DwellP::Auto if (ms - ms.round()).abs() < 1e-9 => {
            word('P', format!("{}", ms.round() as i64))
        }
        DwellP::Auto => word('P', fmt_num(seconds)),
    }
}

fn insert_front(words: &mut Vec<Word>, w: Word) {
    let at = usize::from(words.first().is_some_and(|f| f.letter == 'N'));
    words.insert(at, w);
}

/// A source block carrying `seg`.
fn write_block(program: &Program, bi: usize, seg: &Segment, out: &mut Out) {
    let Some(block) = program.blocks.get(bi) else {
        return;
    };
    if let Motion::Dwell { seconds } = seg.motion {
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
        return emit(block, words, out);
    }
    let want = motion_code(seg);
    let coords = coord_words(program, Some(bi), seg, out);
    let mut coords = Some(coords);
    let mut words = Vec::new();
    let mut had_motion = false;
    let mut had_plane = false;
    let mut had_feed = false;
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
                had_motion = true;
                if let Some(m) = want {
                    if g != 10 * m.code() as i64 {
                        w = word('G', m.code().to_string());
                    }
                }
            }
            had_plane |= matches!(g, 170 | 180 | 190);
        }
        if w.letter == 'F' {
            had_feed = true;
            let m = modal_at(program, bi);
            let f = if m.inch { w.value * 25.4 } else { w.value };
            if seg.is_cutting() && f != seg.feed {
                w = word('F', fmt_num(seg.feed));
            }
        }
        if let Some(w) = rewrite_common(program, bi, &w, out) {
            words.push(w);
        }
    }
    if let Some(c) = coords.take() {
        words.extend(c);
    }
    if let Motion::Arc(a) = seg.motion {
        if !had_plane && out.plane != a.plane {
            insert_front(&mut words, word('G', a.plane.code().to_string()));
            out.plane = a.plane;
        }
    }
    if !had_motion && want != out.motion {
        if let Some(m) = want {
            insert_front(&mut words, word('G', m.code().to_string()));
        }
    }
    out.motion = want.or(out.motion);
    if seg.is_cutting() && !had_feed && out.feed != Some(seg.feed) {
        words.push(word('F', fmt_num(seg.feed)));
        out.feed = Some(seg.feed);
    }
    out.pos = seg.end;
    emit(block, words, out);
}

/// A segment without a source block.
fn write_new(program: &Program, seg: &Segment, out: &mut Out) {
    let mut words = Vec::new();
    if let Motion::Dwell { seconds } = seg.motion {
        words.push(word('G', "04".into()));
        words.push(dwell_word(program, None, seconds));
        return emit(&Block::default(), words, out);
    }
    let want = motion_code(seg);
    if let Motion::Arc(a) = seg.motion {
        if out.plane != a.plane {
            words.push(word('G', a.plane.code().to_string()));
            out.plane = a.plane;
        }
    }
    if want != out.motion {
        if let Some(m) = want {
            words.push(word('G', m.code().to_string()));
        }
        out.motion = want;
    }
    words.extend(coord_words(program, None, seg, out));
    if seg.is_cutting() && out.feed != Some(seg.feed) {
        words.push(word('F', fmt_num(seg.feed)));
        out.feed = Some(seg.feed);
    }
    out.pos = seg.end;
    emit(&Block::default(), words, out);
}

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
