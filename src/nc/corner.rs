//! Fanuc corner rounding and chamfer between two G01 lines: `,R` (or a
//! plain `R` on G01) inserts a tangent arc of that radius, `,C` (or a plain
//! `C` on G01 when the machine has no C axis, see
//! [`super::program::ParseOptions::c_axis`]) cuts the corner with a
//! straight chamfer. Reading (Fanuc 0i/30i operator's manuals, "chamfering
//! and corner R"): C is the distance from the virtual corner to the chamfer's
//! start and end along each line; R is the radius of the arc tangent to both
//! lines, whose tangent points lie `d = R·tan(φ/2)` from the corner, φ the
//! turning angle between the lines. Both lines must lie in the active plane
//! and be long enough to hold `d`; the next move must be a G01 in the same
//! plane. Anything else is a located error, never a silent skip.
//!
//! The shortened line keeps its block and line; the inserted arc or chamfer
//! points to the same block and is marked `fixed` (its end points are not
//! words of the program).
//!
//! Units: mm, rad.

use super::program::{Arc, Corner, CornerKind, Motion, Plane, Segment};
use super::NcError;

/// Plane of a segment pair: the one whose normal axis does not move.
fn plane_of(a: &Segment, b: &Segment) -> Option<Plane> {
    [Plane::XY, Plane::ZX, Plane::YZ].into_iter().find(|p| {
        let (_, _, n) = p.axes();
        let d = |s: &Segment| (s.end.p()[n] - s.start.p()[n]).abs() < 1e-9;
        d(a) && d(b)
    })
}

/// Applies every corner to `segments` (in place); `tags`, one per segment
/// (e.g. the cutter-compensation stretch of each), gets the tag of the
/// shortened line for each inserted segment.
///
/// # Errors
/// One per corner that cannot be made: no following G01, lines not in one
/// plane, collinear lines, or a corner larger than a line.
pub fn apply_corners<T: Clone>(
    segments: &mut Vec<Segment>,
    corners: &[Corner],
    tags: &mut Vec<T>,
) -> Result<(), Vec<NcError>> {
    let mut errors = Vec::new();
    for c in corners.iter().rev() {
        match apply(segments, c) {
            Ok(()) => {
                if let Some(t) = tags.get(c.segment).cloned() {
                    tags.insert(c.segment + 1, t);
                }
            }
            Err(e) => errors.push(e),
        }
    }
    errors.reverse();
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

/// The difference `x − y`.
fn sub(x: [f64; 3], y: [f64; 3]) -> [f64; 3] {
    [x[0] - y[0], x[1] - y[1], x[2] - y[2]]
}

/// The Euclidean length of `x`.
fn norm(x: [f64; 3]) -> f64 {
    (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
}

/// The geometry of one corner: where the first line now ends and the
/// second starts, the unit directions of both lines and the turning angle.
struct CornerCut {
    /// Start of the corner (on the first line), mm.
    p1: [f64; 3],
    /// End of the corner (on the second line), mm.
    p2: [f64; 3],
    /// Unit direction of the first line.
    u1: [f64; 3],
    /// Unit direction of the second line.
    u2: [f64; 3],
    /// Turning angle between the lines, rad.
    phi: f64,
}

/// Makes corner `c` on `segments[c.segment]` and the G01 after it: both
/// lines shortened, the chamfer or arc inserted between them.
fn apply(segments: &mut Vec<Segment>, c: &Corner) -> Result<(), NcError> {
    let e = |m: &str| NcError::new(c.line, c.column, m);
    let i = c.segment;
    let next = segments
        .get(i + 1)
        .filter(|s| matches!(s.motion, Motion::Linear))
        .ok_or_else(|| e("corner rounding/chamfer needs the next move to be a G01 line (an arc or rapid after it is not supported)"))?
        .clone();
    let cur = segments[i].clone();
    if cur.start.to_array()[3..] != cur.end.to_array()[3..]
        || next.start.to_array()[3..] != next.end.to_array()[3..]
    {
        return Err(e(
            "corner rounding/chamfer with a rotary-axis move is not supported",
        ));
    }
    let plane = plane_of(&cur, &next)
        .ok_or_else(|| e("corner rounding/chamfer needs both lines in one plane (G17/G18/G19)"))?;
    let cut = cut(c, &cur, &next)?;
    let mut e1 = cur.end;
    let mut s2 = next.start;
    for k in 0..3 {
        e1.set(k, cut.p1[k]);
        s2.set(k, cut.p2[k]);
    }
    let motion = match c.kind {
        CornerKind::Chamfer(_) => Motion::Linear,
        CornerKind::Round(r) => Motion::Arc(rounding(&cut, r, plane)),
    };
    segments[i].end = e1;
    segments[i].fixed = true;
    segments[i + 1].start = s2;
    let inserted = Segment {
        block: cur.block,
        line: cur.line,
        motion,
        start: e1,
        end: s2,
        feed: cur.feed,
        fixed: true,
    };
    segments.insert(i + 1, inserted);
    Ok(())
}

/// Where corner `c` cuts the lines `cur` and `next`: `d` from the virtual
/// corner along each (the chamfer C, or R·tan(φ/2) for a rounding).
///
/// # Errors
/// Zero-length or collinear lines, a corner that does not fit on a line.
fn cut(c: &Corner, cur: &Segment, next: &Segment) -> Result<CornerCut, NcError> {
    let e = |m: &str| NcError::new(c.line, c.column, m);
    let (a, p, b) = (cur.start.p(), cur.end.p(), next.end.p());
    let (d1, d2) = (sub(p, a), sub(b, p));
    let (l1, l2) = (norm(d1), norm(d2));
    if l1 < 1e-9 || l2 < 1e-9 {
        return Err(e("corner rounding/chamfer between zero-length lines"));
    }
    let u1 = d1.map(|x| x / l1);
    let u2 = d2.map(|x| x / l2);
    let cos = (u1[0] * u2[0] + u1[1] * u2[1] + u1[2] * u2[2]).clamp(-1.0, 1.0);
    let phi = cos.acos();
    if !(1e-9..=std::f64::consts::PI - 1e-9).contains(&phi) {
        return Err(e(
            "corner rounding/chamfer between collinear lines: there is no corner",
        ));
    }
    let d = match c.kind {
        CornerKind::Chamfer(v) => v,
        CornerKind::Round(r) => r * (phi / 2.0).tan(),
    };
    if d.is_nan() || d <= 0.0 || d >= l1 || d >= l2 {
        return Err(e(&format!(
            "corner of {d:.4} mm from the corner does not fit: the lines are {l1:.4} and {l2:.4} mm long"
        )));
    }
    let p1 = [p[0] - u1[0] * d, p[1] - u1[1] * d, p[2] - u1[2] * d];
    let p2 = [p[0] + u2[0] * d, p[1] + u2[1] * d, p[2] + u2[2] * d];
    Ok(CornerCut {
        p1,
        p2,
        u1,
        u2,
        phi,
    })
}

/// The rounding arc of radius `r` (mm) tangent to both lines at the cut's
/// ends, in `plane`, turning the way the lines turn.
fn rounding(cut: &CornerCut, r: f64, plane: Plane) -> Arc {
    let (u1, u2) = (cut.u1, cut.u2);
    let (u, v, _) = plane.axes();
    let turn = u1[u] * u2[v] - u1[v] * u2[u];
    // Centre: from p1, perpendicular to u1 toward the turn.
    let (nu, nv) = if turn > 0.0 {
        (-u1[v], u1[u])
    } else {
        (u1[v], -u1[u])
    };
    let mut center = cut.p1;
    center[u] += nu * r;
    center[v] += nv * r;
    Arc {
        center,
        radius: r,
        plane,
        sweep: if turn > 0.0 { cut.phi } else { -cut.phi },
        r_form: true,
    }
}
