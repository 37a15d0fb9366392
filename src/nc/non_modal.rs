//! The non-modal codes that touch the position or the frame: G28/G30
//! (reference return via an intermediate point: the rapid to the point is
//! simulated, the return is not), G53 (a move in machine coordinates, not
//! simulated), G92/G92.1/G92.2 (coordinate shift, kept as an offset so
//! the path stays continuous) and G52 (local coordinate system: absolute
//! words are shifted by its values, always absolute and in the program's
//! units; axes it does not name keep their shift; G52 X0 Y0 Z0 cancels;
//! G92.1 cancels only the G92 part). Each is warned about with what was and was
//! not simulated. Under a G68 rotation all of them are refused before
//! they get here ([`super::rotation`]: Fanuc requires G69 first). The
//! readings are those of the interpreter's header ([`super::program`]).
//!
//! Units: mm, degrees for A/B/C.

use super::moves::{axis_value, target};
use super::program::{Ctx, Modal, Warning};
use super::segment::{Motion, Segment};
use super::{Block, NcError, Word};

/// G28/G30 (reference return via an intermediate point), G53 (machine
/// coordinates), G92 (coordinate shift).
pub(super) fn non_modal_move(
    b: &Block,
    st: &mut Modal,
    cx: &mut Ctx,
    w: &Word,
    g: i64,
    axis_words: &[&Word],
    scale: f64,
) -> Result<(), NcError> {
    let warn = |cx: &mut Ctx, m: String| cx.warnings.push(Warning::at(b.line, w.column, m));
    match g {
        280 | 300 => {
            if !axis_words.is_empty() {
                let end = target(st, axis_words, scale);
                cx.segments.push(Segment {
                    block: Some(cx.bi),
                    line: b.line,
                    motion: Motion::Rapid,
                    start: st.pos,
                    end,
                    feed: 0.0,
                    fixed: true,
                });
                st.pos = end;
            }
            warn(
                cx,
                format!(
                    "G{}: the rapid to the intermediate point is simulated; the return to the machine reference point is not (machine coordinates are unknown here, and it is not part of the contour); the tool is taken to stay at the intermediate point",
                    w.text
                ),
            );
        }
        530 => warn(
            cx,
            format!(
                "G{}: a move in machine coordinates is not part of the contour and is not simulated (the work offset is unknown); the tool is taken to stay at its last program position",
                w.text
            ),
        ),
        920 => {
            for aw in axis_words {
                let (i, v) = axis_value(aw, scale);
                st.offset[i] = st.pos.get(i) - v;
            }
            warn(
                cx,
                format!(
                    "G{}: coordinate shift by ({:.4}, {:.4}, {:.4}) mm; later absolute coordinates are shifted so the path stays continuous",
                    w.text, st.offset[0], st.offset[1], st.offset[2]
                ),
            );
        }
        921 | 922 => {
            st.offset = st.local;
            warn(cx, format!("G{}: the G92 coordinate shift is cancelled", w.text));
        }
        520 => {
            for aw in axis_words {
                let (i, v) = axis_value(aw, scale);
                st.offset[i] += v - st.local[i];
                st.local[i] = v;
            }
            let l = st.local;
            let m = if l.iter().all(|&v| v == 0.0) {
                format!("G{}: the local coordinate shift is cancelled", w.text)
            } else {
                format!(
                    "G{}: local coordinate system at ({:.4}, {:.4}, {:.4}) mm from the work origin; later absolute coordinates are shifted by it",
                    w.text, l[0], l[1], l[2]
                )
            };
            warn(cx, m);
        }
        _ => warn(cx, format!("G{} is not modelled and was ignored", w.text)),
    }
    Ok(())
}
