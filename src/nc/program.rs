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
//! Readings chosen: the program starts at [`ParseOptions::start`] (the origin
//! by default) in G90 G21 G17 with no motion mode and no feed, so an axis
//! word before any G0–G3 is an error, not a silent rapid. M, S, T, H, D and
//! unknown letters are reported as [`Warning`]s and ignored. Tool-radius
//! (G41/G42) and length (G43) compensation, work offsets and other G codes
//! that do not move are warned about and ignored; canned cycles (G73–G89),
//! G28/G30 reference returns and G92 are errors because ignoring them would
//! give a wrong path. Arc radius consistency: the end radius must match the
//! start radius within 0.005 mm + 1e-5·R; the arc radius is their mean.
//!
//! Units: mm, s, degrees for A/B/C, feed in mm/min.

use serde::{Deserialize, Serialize};

pub use super::segment::{dist, Arc, Motion, MotionCode, Plane, Pose, Segment, AXES};
use super::{arc::arc, lex, Block, NcError, Word};
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
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
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

/// Interpreter options.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct ParseOptions {
    /// Reading of G4 P.
    pub dwell_p: DwellP,
    /// Where the tool is before the first block.
    pub start: Pose,
}

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
    /// Modal feed, mm/min.
    pub feed: Option<f64>,
    /// Position, mm / degrees.
    pub pos: Pose,
}

/// An interpreted program.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    /// The lexed blocks (one per source line).
    pub blocks: Vec<Block>,
    /// Modal state after each block (same length as `blocks`).
    pub modal: Vec<Modal>,
    /// The motion segments in order; at most one per block.
    pub segments: Vec<Segment>,
    /// Ignored words and unmodelled modes.
    pub warnings: Vec<Warning>,
    /// The options it was read with.
    pub options: ParseOptions,
}

/// Parses and interprets a program with default options.
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

/// Parses and interprets a program with `options`.
///
/// # Errors
/// As [`parse`].
pub fn parse_with(text: &str, options: &ParseOptions) -> Result<Program, NcError> {
    interpret(lex(text)?, options)
}

const INCH: f64 = 25.4;

/// Interprets lexed blocks.
///
/// # Errors
/// As [`parse`].
pub fn interpret(blocks: Vec<Block>, options: &ParseOptions) -> Result<Program, NcError> {
    let mut st = Modal {
        pos: options.start,
        ..Modal::default()
    };
    let mut segments = Vec::new();
    let mut warnings = Vec::new();
    let mut modal = Vec::with_capacity(blocks.len());
    for (bi, b) in blocks.iter().enumerate() {
        if let Some(seg) = interpret_block(b, bi, &mut st, options, &mut warnings)? {
            segments.push(seg);
        }
        modal.push(st);
    }
    Ok(Program {
        blocks,
        modal,
        segments,
        warnings,
        options: *options,
    })
}

fn err(b: &Block, w: &Word, msg: impl Into<String>) -> NcError {
    NcError::new(b.line, w.column, msg)
}

fn interpret_block(
    b: &Block,
    bi: usize,
    st: &mut Modal,
    opt: &ParseOptions,
    warnings: &mut Vec<Warning>,
) -> Result<Option<Segment>, NcError> {
    let warn = |warnings: &mut Vec<Warning>, w: &Word, m: String| {
        warnings.push(Warning {
            line: b.line,
            column: w.column,
            message: m,
        })
    };
    // Pass 1: G codes and the words that set modes.
    let mut motion_word: Option<(&Word, MotionCode)> = None;
    let mut dwell: Option<&Word> = None;
    for w in b.words.iter().filter(|w| w.letter == 'G') {
        let g = (w.value * 10.0).round() as i64;
        let code = match g {
            0 => Some(MotionCode::Rapid),
            10 => Some(MotionCode::Linear),
            20 => Some(MotionCode::Cw),
            30 => Some(MotionCode::Ccw),
            _ => None,
        };
        if let Some(m) = code {
            if let Some((prev, _)) = motion_word {
                return Err(err(
                    b,
                    w,
                    format!(
                        "two motion codes in one block (G{} and G{}); expected one of G0, G1, G2, G3",
                        prev.text, w.text
                    ),
                ));
            }
            motion_word = Some((w, m));
            continue;
        }
        match g {
            40 => dwell = Some(w),
            170 => st.plane = Plane::XY,
            180 => st.plane = Plane::ZX,
            190 => st.plane = Plane::YZ,
            200 => st.inch = true,
            210 => st.inch = false,
            900 => st.incremental = false,
            910 => st.incremental = true,
            280 | 300 | 920 | 530 => {
                return Err(err(
                    b,
                    w,
                    format!(
                        "G{} (reference return / coordinate setting) is not supported; expected plain G0–G3 moves in one work coordinate system",
                        w.text
                    ),
                ))
            }
            730 | 740 | 760 | 810..=890 => {
                return Err(err(
                    b,
                    w,
                    format!("canned cycle G{} is not supported; post the program with cycles expanded", w.text),
                ))
            }
            400 | 490 | 800 | 940 | 150 | 690 | 610 | 640 | 901 | 540..=590 => {}
            410 | 420 => warn(
                warnings,
                w,
                format!("G{}: cutter radius compensation is not modelled; the programmed path is used", w.text),
            ),
            430 | 440 => warn(
                warnings,
                w,
                format!("G{}: tool length compensation is ignored (Z is the programmed Z)", w.text),
            ),
            _ => warn(warnings, w, format!("G{} is not modelled and was ignored", w.text)),
        }
    }
    // Pass 2: feed and ignored words.
    let scale = if st.inch { INCH } else { 1.0 };
    for w in &b.words {
        match w.letter {
            'F' => {
                if w.value < 0.0 {
                    return Err(err(
                        b,
                        w,
                        format!(
                            "negative feed F{}; expected a positive feed in mm/min",
                            w.text
                        ),
                    ));
                }
                st.feed = Some(w.value * scale);
            }
            'G' | 'N' | 'O' | 'X' | 'Y' | 'Z' | 'A' | 'B' | 'C' | 'I' | 'J' | 'K' | 'R' => {}
            'P' | 'U' if dwell.is_some() => {}
            'M' | 'S' | 'T' | 'H' | 'D' => warn(
                warnings,
                w,
                format!(
                    "{}{} does not affect the motion model and was ignored",
                    w.letter, w.text
                ),
            ),
            _ => warn(
                warnings,
                w,
                format!("unknown word {}{} was ignored", w.letter, w.text),
            ),
        }
    }
    if let Some(dw) = dwell {
        if motion_word.is_some() {
            return Err(err(
                b,
                dw,
                "G4 dwell together with a motion code; expected the dwell in its own block",
            ));
        }
        let (w, seconds) = if let Some(w) = b.word('X').or(b.word('U')) {
            (w, w.value)
        } else if let Some(w) = b.word('P') {
            let ms = match opt.dwell_p {
                DwellP::Milliseconds => true,
                DwellP::Seconds => false,
                DwellP::Auto => !w.text.contains('.'),
            };
            (w, if ms { w.value / 1000.0 } else { w.value })
        } else {
            return Err(err(
                b,
                dw,
                "G4 dwell without a time; expected X (seconds) or P",
            ));
        };
        if seconds < 0.0 || !seconds.is_finite() {
            return Err(err(b, w, "dwell time must be zero or positive"));
        }
        return Ok(Some(Segment {
            block: Some(bi),
            line: b.line,
            motion: Motion::Dwell { seconds },
            start: st.pos,
            end: st.pos,
            feed: 0.0,
            fixed: false,
        }));
    }
    if let Some((_, m)) = motion_word {
        st.motion = Some(m);
    }
    // Pass 3: the move.
    let axis_words: Vec<&Word> = b
        .words
        .iter()
        .filter(|w| AXES.contains(&w.letter))
        .collect();
    let centre_words: Vec<&Word> = b
        .words
        .iter()
        .filter(|w| matches!(w.letter, 'I' | 'J' | 'K' | 'R'))
        .collect();
    if axis_words.is_empty() && centre_words.is_empty() {
        return Ok(None);
    }
    let first = axis_words
        .first()
        .or(centre_words.first())
        .copied()
        .ok_or_else(|| NcError::new(b.line, 1, "internal: empty move"))?;
    let Some(mode) = st.motion else {
        return Err(err(
            b,
            first,
            "axis words but no motion mode has been programmed; expected G0, G1, G2 or G3 first",
        ));
    };
    let start = st.pos;
    let mut end = start;
    for w in &axis_words {
        let i = AXES.iter().position(|&c| c == w.letter).unwrap_or(0);
        let v = if i < 3 { w.value * scale } else { w.value };
        end.set(i, if st.incremental { end.get(i) + v } else { v });
    }
    let feed = match mode {
        MotionCode::Rapid => 0.0,
        _ => match st.feed {
            Some(f) if f > 0.0 => f,
            Some(_) => {
                let fw = b.word('F').unwrap_or(first);
                return Err(err(b, fw, "feed is zero on a cutting move; expected F greater than 0 (mm/min)"));
            }
            None => {
                return Err(err(b, first, "cutting move without a feed; expected an F word (mm/min) on this or an earlier block"))
            }
        },
    };
    let motion = match mode {
        MotionCode::Rapid => Motion::Rapid,
        MotionCode::Linear => Motion::Linear,
        MotionCode::Cw | MotionCode::Ccw => Motion::Arc(arc(
            b,
            first,
            st.plane,
            mode == MotionCode::Cw,
            start,
            end,
            scale,
        )?),
    };
    if matches!(mode, MotionCode::Rapid | MotionCode::Linear) {
        if let Some(w) = centre_words.first() {
            warn(
                warnings,
                w,
                format!(
                    "{}{} has no meaning on a G{} move and was ignored",
                    w.letter,
                    w.text,
                    mode.code()
                ),
            );
        }
    }
    st.pos = end;
    Ok(Some(Segment {
        block: Some(bi),
        line: b.line,
        motion,
        start,
        end,
        feed,
        fixed: false,
    }))
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
        assert_eq!(p.warnings.len(), 4);
        assert!(p.warnings[3].message.contains("unknown word Q2"));
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
