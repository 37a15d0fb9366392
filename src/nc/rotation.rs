//! Fanuc coordinate system rotation G68/G69 (Fanuc Series 0i-MF/30i-B
//! operator's manuals, "coordinate system rotation"): after `G68 α_ β_ R_`
//! every point programmed in the plane is rotated by `R` degrees about the
//! centre (α, β) before the tool goes there; `G69` cancels. The
//! interpreter keeps the tool position in the un-rotated frame (the work
//! frame the tool-path model simulates); this module maps between that
//! frame and the program's rotated frame.
//!
//! The transform: a program point `p` (work coordinates, G92 shift
//! included) is the machine point `m = c + Rot(θ)·(p − c)` with `c` the
//! centre and `θ` the angle about the plane's normal, counter-clockwise
//! positive seen from the positive normal (G17 +Z, G18 +Y, G19 +X: the
//! arc convention of [`super::segment`]); vectors (arc centres I/J/K
//! relative to the start, G91 increments) turn by `Rot(θ)` without the
//! translation. The axis normal to the plane and A/B/C are unchanged.
//! Multiples of 90° are exact (cos and sin 0 or ±1).
//!
//! Readings chosen:
//! - the centre words are the plane's two axes (G17 X/Y, G18 Z/X, G19
//!   Y/Z), always absolute work coordinates (the manual: "absolute
//!   command"), also under G91, shifted by G92 like any absolute word; a
//!   centre word omitted is the current (un-rotated) position of that
//!   axis;
//! - `R` is the angle in degrees. Under G91, `R` is added to the rotation
//!   in force (parameter 5400#0 RIN = 1; none in force: added to 0); under
//!   G90 it replaces it. A G68 without `R` is refused (the angle would be
//!   parameter 5410, unknown here). A G68 while G68 is in force replaces
//!   the rotation (its centre words in the un-rotated frame);
//! - under G68 a programmed point is read in the rotated frame: an axis
//!   word omitted under G90 keeps the axis's rotated-frame coordinate (a
//!   lone `X` moves along the rotated X axis), a G91 increment is turned
//!   with the frame; a move whose plane coordinates stay where they were
//!   keeps the tool's exact position;
//! - arcs are computed in the rotated frame (I/J/K, R, G90.1 centres as
//!   programmed) and their centre rotated: radius and sweep are unchanged;
//! - canned-cycle hole positions are points in the plane and turn with it;
//!   the R level and the bottom lie on the normal axis and do not;
//! - a G68 block does not move: besides its centre words and `R` it may
//!   carry modal codes and F/S/T/M words; another axis word, I/J/K (the 3D
//!   conversion `G68 X Y Z I J K R`), a dwell, a cycle, a non-modal or a
//!   cutter-compensation code on it is refused (a G0–G3 on it only sets
//!   the motion mode). `G69` may share a block
//!   with a move, which is then un-rotated (the manual's example
//!   `G69 G90 X-500. Y-500. M02`);
//! - refused with a located error, as Fanuc alarms or as this model cannot
//!   do exactly: a plane change (G17/G18/G19) while G68 is in force; G68,
//!   or G69 cancelling a rotation, while cutter compensation G41/G42 is in
//!   force (a G69 with no rotation in force does nothing; compensation
//!   started under G68 is fine: the offset path of a rigidly rotated path
//!   is the rotated offset path); G68 in canned-cycle mode; the reference
//!   returns and frame changes G28, G30, G52, G53, G54–G59 and the G92
//!   family under G68 (the manual requires G69 before them); G68.1–G68.4
//!   (3D conversion, tilted working plane).
//!
//! Units: mm, degrees.

use serde::{Deserialize, Serialize};

use super::gcodes::{code10, GWords};
use super::program::{err, CutterStretch, Modal};
use super::segment::{Arc, Plane, Pose, AXES};
use super::{Block, NcError, Word};

/// A coordinate system rotation in force (modal, G68 until G69).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Rotation {
    /// The plane rotated (the plane in force at G68).
    pub plane: Plane,
    /// Centre `[x, y, z]` in the un-rotated work frame, mm; only the
    /// plane's two coordinates are used.
    pub center: [f64; 3],
    /// Angle, degrees, counter-clockwise seen from the plane's positive
    /// normal.
    pub angle: f64,
    /// Source line of the G68.
    pub line: usize,
}

/// `(cos, sin)` of `deg` degrees, exact at multiples of 90°.
fn cos_sin(deg: f64) -> (f64, f64) {
    let quarter = deg / 90.0;
    if quarter.fract() == 0.0 && quarter.abs() < 1e15 {
        return match quarter.rem_euclid(4.0) as u8 {
            0 => (1.0, 0.0),
            1 => (0.0, 1.0),
            2 => (-1.0, 0.0),
            _ => (0.0, -1.0),
        };
    }
    let (s, c) = deg.to_radians().sin_cos();
    (c, s)
}

/// Vector `v` (`[x, y, z]`) turned by `deg` degrees about the normal of
/// `plane` (counter-clockwise seen from the positive normal); the normal
/// component is unchanged.
///
/// # Examples
/// ```
/// use mtmotion::nc::rotation::rotate_vector;
/// use mtmotion::nc::program::Plane;
/// let v = rotate_vector([1.0, 0.0, 5.0], Plane::XY, 30.0);
/// assert!((v[0] - 0.75f64.sqrt()).abs() < 1e-15 && (v[1] - 0.5).abs() < 1e-15);
/// assert_eq!(v[2], 5.0);
/// // G18: +Z turns towards +X.
/// assert_eq!(rotate_vector([0.0, 0.0, 1.0], Plane::ZX, 90.0), [1.0, 0.0, 0.0]);
/// ```
pub fn rotate_vector(v: [f64; 3], plane: Plane, deg: f64) -> [f64; 3] {
    let (u, w, _) = plane.axes();
    let (c, s) = cos_sin(deg);
    let mut out = v;
    out[u] = c * v[u] - s * v[w];
    out[w] = s * v[u] + c * v[w];
    out
}

/// Point `p` turned by `deg` degrees about `center` in `plane` (see
/// [`rotate_vector`]); the normal coordinate is unchanged.
///
/// # Units
/// mm, degrees.
///
/// # Examples
/// ```
/// use mtmotion::nc::rotation::rotate_point;
/// use mtmotion::nc::program::Plane;
/// let p = rotate_point([20.0, 10.0, -3.0], [10.0, 10.0, 0.0], Plane::XY, 90.0);
/// assert_eq!(p, [10.0, 20.0, -3.0]);
/// ```
pub fn rotate_point(p: [f64; 3], center: [f64; 3], plane: Plane, deg: f64) -> [f64; 3] {
    let (u, w, _) = plane.axes();
    let mut rel = p;
    rel[u] -= center[u];
    rel[w] -= center[w];
    let mut out = rotate_vector(rel, plane, deg);
    out[u] += center[u];
    out[w] += center[w];
    out
}

/// `pose` with its X/Y/Z replaced by `p`.
fn with_xyz(pose: Pose, p: [f64; 3]) -> Pose {
    Pose {
        x: p[0],
        y: p[1],
        z: p[2],
        ..pose
    }
}

impl Rotation {
    /// A program (rotated-frame) point in the machine (un-rotated) frame.
    pub fn to_machine(&self, p: [f64; 3]) -> [f64; 3] {
        rotate_point(p, self.center, self.plane, self.angle)
    }

    /// A machine (un-rotated) point in the program (rotated) frame.
    pub fn to_program(&self, p: [f64; 3]) -> [f64; 3] {
        rotate_point(p, self.center, self.plane, -self.angle)
    }

    /// A machine-frame vector (I/J/K, an increment) in the program frame.
    pub fn vector_to_program(&self, v: [f64; 3]) -> [f64; 3] {
        rotate_vector(v, self.plane, -self.angle)
    }

    /// [`Self::to_machine`] of a pose (A/B/C unchanged).
    pub fn pose_to_machine(&self, pose: Pose) -> Pose {
        with_xyz(pose, self.to_machine(pose.p()))
    }

    /// [`Self::to_program`] of a pose (A/B/C unchanged).
    pub fn pose_to_program(&self, pose: Pose) -> Pose {
        with_xyz(pose, self.to_program(pose.p()))
    }

    /// An arc computed in the program frame, in the machine frame: its
    /// centre rotated (radius, sweep and plane unchanged).
    pub fn arc_to_machine(&self, a: Arc) -> Arc {
        Arc {
            center: self.to_machine(a.center),
            ..a
        }
    }
}

/// The machine-frame end of a move whose program-frame end is `end` from
/// the machine pose `from`: `from`'s own plane coordinates when the move
/// leaves them where they were in the program frame (no rounding drift),
/// else the rotated point. Without a rotation `end` itself.
pub(super) fn end_to_machine(st: &Modal, from: Pose, end: Pose) -> Pose {
    let Some(r) = st.rotation else {
        return end;
    };
    let start = r.to_program(from.p());
    let (u, v, _) = r.plane.axes();
    let p = end.p();
    if p[u] == start[u] && p[v] == start[v] {
        let mut m = end;
        m.set(u, from.get(u));
        m.set(v, from.get(v));
        return m;
    }
    r.pose_to_machine(end)
}

/// The G68/G69 of block `b` and what the rotation in force refuses.
/// Returns true for a G68 block (its words set the rotation; it does not
/// move).
///
/// # Errors
/// See the module header: a plane change, G68/G69 under cutter
/// compensation, G68 in cycle mode or beside another action, a G68 word
/// that is not a centre or `R`, a frame code under G68.
pub(super) fn rotation_block(
    b: &Block,
    st: &mut Modal,
    gw: &GWords,
    stretches: &[CutterStretch],
    scale: f64,
) -> Result<bool, NcError> {
    let turns = match gw.rotation {
        Some((_, 690)) => st.rotation.is_some(),
        other => other.is_some(),
    };
    if let (Some((w, _)), Some(c), true) = (gw.rotation, st.cutter, turns) {
        let (code, line) = stretches
            .get(c.stretch)
            .map_or(("G41/G42", 0), |s| (s.code.as_str(), s.line));
        return Err(err(
            b,
            w,
            format!(
                "G{} while cutter compensation {code} (line {line}) is in force: turning the frame during compensation is not simulated; cancel it with G40 (and a move) first",
                w.text
            ),
        ));
    }
    if let Some((_, 690)) = gw.rotation {
        st.rotation = None;
    }
    if let Some(r) = st.rotation {
        refused_under(b, st, &r)?;
    }
    match gw.rotation {
        Some((w, 680)) => {
            g68(b, st, gw, w, scale)?;
            Ok(true)
        }
        _ => Ok(false),
    }
}

/// Under rotation `r`: a plane change, or a reference return or frame
/// code (G28, G30, G52, G53, G54–G59, G92 family).
fn refused_under(b: &Block, st: &Modal, r: &Rotation) -> Result<(), NcError> {
    if st.plane != r.plane {
        let w = b
            .words_of('G')
            .find(|w| matches!(code10(w), 170 | 180 | 190));
        return Err(NcError::new(
            b.line,
            w.map_or(1, |w| w.column),
            format!(
                "plane change to G{} while the coordinate rotation G68 of line {} is in force in G{} (Fanuc alarms); cancel it with G69 first",
                st.plane.code(),
                r.line,
                r.plane.code()
            ),
        ));
    }
    let frame = b
        .words_of('G')
        .find(|w| matches!(code10(w), 280 | 300 | 520..=599 | 920..=923));
    match frame {
        Some(w) => Err(err(
            b,
            w,
            format!(
                "G{} while the coordinate rotation G68 of line {} is in force: reference returns and coordinate-system changes are not allowed in G68 mode (Fanuc); cancel it with G69 first",
                w.text, r.line
            ),
        )),
        None => Ok(()),
    }
}

/// A G68 block (word `w`): checks that it does nothing else and sets the
/// rotation (centre, angle; see the module header).
fn g68(b: &Block, st: &mut Modal, gw: &GWords, w: &Word, scale: f64) -> Result<(), NcError> {
    if st.cycle.is_some() {
        return Err(err(
            b,
            w,
            "G68 in canned-cycle mode is not simulated; cancel the cycle with G80 first",
        ));
    }
    let other = [gw.dwell, gw.non_modal.map(|x| x.0), gw.cycle.map(|x| x.0)]
        .into_iter()
        .chain([gw.cutter.map(|x| x.0)])
        .flatten()
        .next();
    if let Some(o) = other {
        return Err(err(
            b,
            o,
            format!(
                "G{} together with G68; expected G68 in a block of its own",
                o.text
            ),
        ));
    }
    if let Some((_, m)) = gw.motion {
        st.motion = Some(m);
    }
    let (u, v, _) = st.plane.axes();
    check_g68_words(b, st.plane, u, v)?;
    let Some(rw) = b.word('R') else {
        return Err(err(
            b,
            w,
            "G68 without R: expected R, the rotation angle in degrees (the control's default angle, parameter 5410, is unknown here)",
        ));
    };
    let mut center = [0.0; 3];
    for k in [u, v] {
        center[k] = match b.word(AXES[k]) {
            Some(cw) => cw.value * scale + st.offset[k],
            None => st.pos.get(k),
        };
    }
    let before = st.rotation.map_or(0.0, |r| r.angle);
    let angle = if st.incremental {
        before + rw.value
    } else {
        rw.value
    };
    if !angle.is_finite() || !center.iter().all(|c| c.is_finite()) {
        return Err(err(
            b,
            rw,
            "G68: the rotation's angle or centre is not a finite number",
        ));
    }
    st.rotation = Some(Rotation {
        plane: st.plane,
        center,
        angle,
        line: b.line,
    });
    Ok(())
}

/// The words of a G68 block besides its G codes: the centre words of the
/// plane (axes `u`, `v`) and R; I/J/K (3D conversion) and any other axis
/// word are refused.
fn check_g68_words(b: &Block, plane: Plane, u: usize, v: usize) -> Result<(), NcError> {
    for x in &b.words {
        let msg = if matches!(x.letter, 'I' | 'J' | 'K') {
            format!(
                "{}{} on a G68 block: the 3D coordinate conversion (G68 X Y Z I J K R) is not simulated; expected G68 with the two centre words of G{} and R",
                x.letter,
                x.text,
                plane.code()
            )
        } else if AXES.contains(&x.letter) && x.letter != AXES[u] && x.letter != AXES[v] {
            format!(
                "{}{} on a G68 block: in G{} the centre words are {} and {}; expected the move in a block of its own",
                x.letter,
                x.text,
                plane.code(),
                AXES[u],
                AXES[v]
            )
        } else {
            continue;
        };
        return Err(err(b, x, msg));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_and_vector_rotations_are_inverse_and_rigid() {
        let r = Rotation {
            plane: Plane::YZ,
            center: [0.0, 3.0, -4.0],
            angle: 37.5,
            line: 1,
        };
        let p = [7.0, -2.0, 11.0];
        let m = r.to_machine(p);
        assert_eq!(m[0], 7.0, "the normal axis X is unchanged in G19");
        let back = r.to_program(m);
        for k in 0..3 {
            assert!((back[k] - p[k]).abs() < 1e-12, "{back:?}");
        }
        let d0 = ((p[1] - 3.0).powi(2) + (p[2] + 4.0).powi(2)).sqrt();
        let d1 = ((m[1] - 3.0).powi(2) + (m[2] + 4.0).powi(2)).sqrt();
        assert!((d0 - d1).abs() < 1e-12);
        // G19: +Y turns towards +Z.
        let v = rotate_vector([0.0, 1.0, 0.0], Plane::YZ, 90.0);
        assert_eq!(v, [0.0, 0.0, 1.0]);
        assert_eq!(cos_sin(-270.0), (0.0, 1.0));
    }
}
