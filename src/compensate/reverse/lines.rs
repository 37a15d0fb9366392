//! The lines to compensate: `fromLine`, `toLine` of the reverse
//! compensation (issue 27; beyond the paper, which compensates the whole
//! path).
//!
//! Readings:
//! - the numbers are the program text's own line numbers, 1-based and
//!   inclusive — the numbers every `line` of the results (`firstLine`,
//!   `afterLine`, warnings) and the page's line links use — not N words;
//!   one left out is the first or the last line;
//! - a move belongs to the range when its block's line does. Only moves
//!   inside may change: a move outside is pinned as a fixed segment is
//!   ([`super::region`]: it splits regions, and an arc next to it keeps
//!   its radius, so no joint with it moves), so every line outside is
//!   written byte for byte ([`crate::nc::patch`]); new lines (dwells,
//!   connecting moves) go only after or before a line inside;
//! - the NC filter and the servo lag carry a change past the range's end
//!   when no rapid stops them there, so the written program is checked
//!   against the original on every cutting move outside too (as on fixed
//!   moves): where one's error rises, the nearest changed regions go back
//!   ([`super::reverse_compensate`]). The error outside is never made
//!   worse;
//! - a range outside the program (0, or past its last line) or reversed
//!   is refused naming the field; a range that holds no cutting move that
//!   can be rewritten gives the original program back, saying so.
//!
//! Units: line numbers.

use super::region::Regions;
use super::RegionNote;
use crate::nc::program::{Motion, Program, Segment};
use crate::toolpath::{Simulation, ToolpathError};

/// The lines to compensate, 1-based and inclusive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LineRange {
    /// First line.
    pub first: usize,
    /// Last line.
    pub last: usize,
    /// The range is the whole program (neither end given).
    pub whole: bool,
}

impl LineRange {
    /// Whether `line` is in the range.
    pub fn contains(&self, line: usize) -> bool {
        (self.first..=self.last).contains(&line)
    }
}

/// The range `from`–`to` of `program` (its main text), checked.
///
/// # Errors
/// A line 0 or past the program's last line, naming the field and the
/// program's line count; `fromLine` after `toLine`.
///
/// # Examples
/// ```
/// use mtmotion::compensate::reverse::lines::line_range;
/// let p = mtmotion::nc::program::parse("G0 X0\nG1 X1 F100\nG1 Y1\n").unwrap();
/// let r = line_range(&p, Some(2), None).unwrap();
/// assert_eq!((r.first, r.last, r.whole), (2, 3, false));
/// let e = line_range(&p, Some(3), Some(2)).unwrap_err().to_string();
/// assert!(e.starts_with("fromLine: "), "{e}");
/// let e = line_range(&p, None, Some(4)).unwrap_err().to_string();
/// assert!(e.starts_with("toLine: ") && e.contains("3 lines"), "{e}");
/// ```
pub fn line_range(
    program: &Program,
    from: Option<usize>,
    to: Option<usize>,
) -> Result<LineRange, ToolpathError> {
    let n = program
        .blocks
        .iter()
        .filter(|b| b.file == 0)
        .map(|b| b.line)
        .max()
        .unwrap_or(0)
        .max(1);
    let check = |field: &'static str, v: usize| {
        if (1..=n).contains(&v) {
            Ok(v)
        } else {
            Err(ToolpathError::Config {
                field,
                message: format!(
                    "expected a line of the program, from 1 to {n} (the program has {n} lines), got {v}"
                ),
            })
        }
    };
    let first = from.map_or(Ok(1), |v| check("fromLine", v))?;
    let last = to.map_or(Ok(n), |v| check("toLine", v))?;
    if first > last {
        return Err(ToolpathError::Config {
            field: "fromLine",
            message: format!(
                "line {first} comes after toLine {last}; expected fromLine at most toLine"
            ),
        });
    }
    Ok(LineRange {
        first,
        last,
        whole: from.is_none() && to.is_none(),
    })
}

/// The notes of the cutting moves outside `range`: one before it and one
/// after it (where there are any), with their largest error before and
/// after, so an error peak outside the range is never unexplained.
pub fn outside_notes(
    segs: &[Segment],
    rg: &Regions,
    range: &LineRange,
    before: &Simulation,
    after: &Simulation,
) -> Vec<RegionNote> {
    if range.whole {
        return Vec::new();
    }
    let side = |keep: &dyn Fn(usize) -> bool| -> Option<RegionNote> {
        let moves: Vec<usize> = (0..segs.len())
            .filter(|&i| segs[i].is_cutting() && rg.of[i].is_none() && keep(segs[i].line))
            .collect();
        let (first, last) = (*moves.first()?, *moves.last()?);
        let worst = |sim: &Simulation| {
            sim.segments
                .iter()
                .filter(|st| moves.binary_search(&st.segment).is_ok())
                .map(|st| st.max_error_um)
                .fold(0.0, f64::max)
        };
        let arcs = moves
            .iter()
            .filter(|&&i| matches!(segs[i].motion, Motion::Arc(_)))
            .count();
        Some(RegionNote {
            first_line: segs[first].line,
            last_line: segs[last].line,
            arcs,
            lines: moves.len() - arcs,
            before_um: worst(before),
            after_um: worst(after),
            changed: false,
            reason: format!(
                "outside the lines to compensate ({}–{}); left as written",
                range.first, range.last
            ),
        })
    };
    [
        side(&|l| l < range.first && l > 0),
        side(&|l| l > range.last),
    ]
    .into_iter()
    .flatten()
    .collect()
}
