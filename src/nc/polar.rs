//! LinuxCNC polar coordinates: `@` (distance) and `^` (angle, degrees) give
//! the X and Y of a move's end point (LinuxCNC G-code reference, "Polar
//! Coordinates"; its bolt-circle and spiral examples are in the corpus,
//! `hole-circle.ngc` and `spiral.ngc`).
//!
//! Readings chosen:
//! - The pole is the origin of the program's X/Y (after G92 and under a
//!   G68 rotation, the rotated frame), in every distance mode. Under G90,
//!   `@r ^θ` is the point (r cos θ, r sin θ). Under G91 the words add to
//!   the current point's own polar distance and angle about that origin:
//!   `G91 ^60` turns the point 60° about the origin at the same distance
//!   (the bolt circle), `G91 @-0.0025 ^4.5` spirals inwards. A word left
//!   out keeps the current point's distance or angle (both modes).
//! - `@` is a length (scaled by G20); `^` is in degrees, positive
//!   counter-clockwise seen from +Z.
//! - Refused with line and column, as LinuxCNC refuses them: X or Y with
//!   `@`/`^` on one block, and polar words outside the G17 plane. Also
//!   refused here: polar words on the non-modal moves and shifts (G28,
//!   G30, G53, G92, …). On a G10 block they are not run, like its other
//!   words (the G10 warning says so).
//! - A polar end point is not a literal X/Y word, so the segment is
//!   `fixed` (reverse compensation does not move it); the writer writes it
//!   as X/Y.
//!
//! Units: mm, degrees in the words, rad inside.

use super::segment::{Plane, Pose};
use super::{Block, NcError, Word};

/// True when `c` is a polar address (`@` distance, `^` angle).
pub(super) fn is_polar(c: char) -> bool {
    matches!(c, '@' | '^')
}

/// True when `c` gives an end-point coordinate: an axis letter (X Y Z A B
/// C) or a polar one.
pub(super) fn is_position(c: char) -> bool {
    super::segment::AXES.contains(&c) || is_polar(c)
}

/// The first polar word of `b`, if any.
pub(super) fn polar_word(b: &Block) -> Option<&Word> {
    b.words.iter().find(|w| is_polar(w.letter))
}

/// Checks the polar words of `b` (see the module header): none with X or
/// Y, and only in the G17 plane.
///
/// # Errors
/// A located [`NcError`] at the offending word.
pub(super) fn check(b: &Block, plane: Plane) -> Result<(), NcError> {
    let Some(p) = polar_word(b) else {
        return Ok(());
    };
    if let Some(xy) = b.words.iter().find(|w| matches!(w.letter, 'X' | 'Y')) {
        return Err(super::program::err(
            b,
            xy,
            format!(
                "{}{} with the polar word {}{}: a LinuxCNC end point is either X/Y or @ (distance) / ^ (angle), not both",
                xy.letter, xy.text, p.letter, p.text
            ),
        ));
    }
    if plane != Plane::XY {
        return Err(super::program::err(
            b,
            p,
            format!(
                "polar word {}{} outside the G17 plane: LinuxCNC polar coordinates give X and Y only; select G17 or write the end point as X/Y/Z",
                p.letter, p.text
            ),
        ));
    }
    Ok(())
}

/// The X and Y of a polar end point from `from` (program frame), with the
/// program's X/Y origin at `origin` in that frame, in G90 or G91
/// (`incremental`); `scale` turns `@` into mm. `None` without polar words.
pub(super) fn end_xy(
    words: &[&Word],
    from: Pose,
    origin: [f64; 2],
    incremental: bool,
    scale: f64,
) -> Option<[f64; 2]> {
    let r_word = words.iter().find(|w| w.letter == '@');
    let a_word = words.iter().find(|w| w.letter == '^');
    if r_word.is_none() && a_word.is_none() {
        return None;
    }
    let (x, y) = (from.get(0) - origin[0], from.get(1) - origin[1]);
    let (r0, a0) = (x.hypot(y), y.atan2(x));
    let r = r_word.map_or(r0, |w| w.value * scale + if incremental { r0 } else { 0.0 });
    let a = a_word.map_or(a0, |w| {
        w.value.to_radians() + if incremental { a0 } else { 0.0 }
    });
    Some([origin[0] + r * a.cos(), origin[1] + r * a.sin()])
}
