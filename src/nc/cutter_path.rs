//! Cutter radius compensation: the tool-centre path of each compensated
//! stretch whose tool radius r is known (G41/G42, the modal readings are in
//! [`super::cutter`]), computed from the programmed lines and arcs after the
//! run (Fanuc "cutter compensation C", ISO 6983 G41/G42).
//!
//! Readings chosen:
//! - Contour elements are the lines (G0/G1) with motion in the
//!   compensation plane and the arcs of that plane. A line is shifted by r
//!   along its normal, left of the direction of travel for G41, right for
//!   G42, seen from the positive plane normal (+Z in G17, +Y in G18, +X in
//!   G19: the view in which G3 is counter-clockwise); an arc keeps its centre and becomes R − r on the side of its
//!   centre, R + r on the other (G41 with G3, G42 with G2: R − r). An offset
//!   radius ≤ 0 is a located error.
//! - Inside corners: the two offset elements are trimmed to their
//!   intersection (the one nearest the programmed corner). Outside corners:
//!   an arc of radius r around the programmed corner point joins them (the
//!   rounded corner, as LinuxCNC makes it), for every outside angle, never
//!   the intersection (a Fanuc control joins shallow outside corners at the
//!   intersection, r/cos(φ/2) from the corner for a turn φ): so every point
//!   of an offset element and of a corner arc is at exactly r from the
//!   programmed contour. Between two rapids the
//!   corner is a rapid straight move. Nearly tangent inside joins whose
//!   offsets do not meet (numerically) but lie within 1 µm are joined by a
//!   straight move.
//! - Start-up (Fanuc type A): the first contour element after G41/G42 must
//!   be a line; it runs from the programmed (un-offset) point to the offset
//!   start of the next element (its normal at its start), or to its own end
//!   offset when no element follows. Moves of the stretch before it are not
//!   offset.
//! - Cancel (type A): the last element ends at its own end offset; the first
//!   move after the stretch (the move after G40) must be a line and runs from
//!   there to the programmed end point.
//! - The axis normal to the plane (Z in G17) and A/B/C pass through: each
//!   offset element keeps its programmed values, a helical arc its pitch.
//!   Moves without motion in the plane (a Z plunge) stay at the offset
//!   point; at an outside corner they come before the corner arc. One such
//!   move between two contour elements is fine; two in a row are refused
//!   (the offset at that corner needs the next element, and Fanuc's
//!   look-ahead is limited the same way).
//! - Refused, located: an arc as start-up or cancel move, an arc in another
//!   plane, an inside corner whose offset elements do not meet or meet
//!   outside them (an element too short for the radius: the tool would
//!   gouge), compensation restarted before its cancel move.
//!
//! Every segment of an offset stretch and its cancel move is `fixed`: its
//! end points are not words of the program.
//!
//! Units: mm, rad.

use std::f64::consts::PI;

use super::cutter::CutterStretch;
use super::segment::{Arc, Motion, Plane, Pose, Segment};
use super::{Block, NcError};

/// Points closer than this are one point, mm.
const EPS: f64 = 1e-9;

/// Largest gap a nearly tangent inside join may bridge with a line, mm.
const GAP: f64 = 1e-3;

/// A point or vector in the plane's (u, v) coordinates.
type V2 = [f64; 2];

fn sub(a: V2, b: V2) -> V2 {
    [a[0] - b[0], a[1] - b[1]]
}
fn add(a: V2, b: V2) -> V2 {
    [a[0] + b[0], a[1] + b[1]]
}
fn mul(a: V2, k: f64) -> V2 {
    [a[0] * k, a[1] * k]
}
fn dot(a: V2, b: V2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
fn cross(a: V2, b: V2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
fn len(a: V2) -> f64 {
    a[0].hypot(a[1])
}
fn unit(a: V2) -> V2 {
    mul(a, 1.0 / len(a))
}
/// `a` turned +90° (counter-clockwise seen from the plane normal).
fn left(a: V2) -> V2 {
    [-a[1], a[0]]
}
fn polar(c: V2, r: f64, th: f64) -> V2 {
    [c[0] + r * th.cos(), c[1] + r * th.sin()]
}
/// An angle wrapped into (−π, π].
fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(2.0 * PI);
    if w > PI {
        w - 2.0 * PI
    } else {
        w
    }
}

/// The in-plane coordinates of a pose.
fn uv(p: &Pose, plane: Plane) -> V2 {
    let (u, v, _) = plane.axes();
    let a = p.p();
    [a[u], a[v]]
}

/// `p` with its in-plane coordinates replaced by `q`.
fn with_uv(p: &Pose, plane: Plane, q: V2) -> Pose {
    let (u, v, _) = plane.axes();
    let mut r = *p;
    r.set(u, q[0]);
    r.set(v, q[1]);
    r
}

/// The offset of one contour element in the plane.
#[derive(Debug, Clone, Copy)]
enum Off {
    /// A line from `a` to `b`; `t` the programmed unit direction.
    Line { a: V2, b: V2, t: V2 },
    /// An arc about `c` of radius `r` from angle `th0` over `sweep`;
    /// `orig` the untrimmed sweep.
    Arc {
        c: V2,
        r: f64,
        th0: f64,
        sweep: f64,
        orig: f64,
    },
}

impl Off {
    fn start(&self) -> V2 {
        match *self {
            Off::Line { a, .. } => a,
            Off::Arc { c, r, th0, .. } => polar(c, r, th0),
        }
    }
    fn end(&self) -> V2 {
        match *self {
            Off::Line { b, .. } => b,
            Off::Arc {
                c, r, th0, sweep, ..
            } => polar(c, r, th0 + sweep),
        }
    }
    /// Moves the start to `x` (a point on the element's line or circle).
    fn trim_start(&mut self, x: V2) {
        match self {
            Off::Line { a, .. } => *a = x,
            Off::Arc { c, th0, sweep, .. } => {
                let th = (x[1] - c[1]).atan2(x[0] - c[0]);
                *sweep -= wrap(th - *th0);
                *th0 = th;
            }
        }
    }
    /// Moves the end to `x`.
    fn trim_end(&mut self, x: V2) {
        match self {
            Off::Line { b, .. } => *b = x,
            Off::Arc { c, th0, sweep, .. } => {
                let th = (x[1] - c[1]).atan2(x[0] - c[0]);
                *sweep += wrap(th - (*th0 + *sweep));
            }
        }
    }
    /// The element still runs the programmed way (trimming did not
    /// reverse or lengthen it).
    fn valid(&self) -> bool {
        match *self {
            Off::Line { a, b, t } => dot(sub(b, a), t) > -EPS,
            Off::Arc { sweep, orig, .. } => sweep * orig > 0.0 && sweep.abs() <= orig.abs() + 1e-9,
        }
    }
}

/// How the segments of a stretch take part in the offset.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// A line or arc with motion in the plane.
    Element,
    /// A move without motion in the plane.
    Flat,
    /// A dwell.
    Still,
}

/// The error at segment `s`'s block (its first word's column).
fn error_at(s: &Segment, blocks: &[Block], msg: String) -> NcError {
    let column = s
        .block
        .and_then(|bi| blocks.get(bi))
        .and_then(|b| b.words.first())
        .map_or(1, |w| w.column);
    NcError::new(s.line, column, msg)
}

/// `G41 D1 (line 5)`: how errors name a stretch.
fn name(st: &CutterStretch) -> String {
    format!(
        "cutter compensation {}{} (line {})",
        st.code,
        st.d.as_deref().map(|d| format!(" {d}")).unwrap_or_default(),
        st.line
    )
}

/// The kind of each segment of a stretch in `st`'s plane.
///
/// # Errors
/// An arc in another plane.
fn kinds(segs: &[Segment], st: &CutterStretch, blocks: &[Block]) -> Result<Vec<Kind>, NcError> {
    segs.iter()
        .map(|s| match s.motion {
            Motion::Dwell { .. } => Ok(Kind::Still),
            Motion::Arc(a) if a.plane != st.plane => Err(error_at(
                s,
                blocks,
                format!(
                    "arc in G{} during {} in G{}: not simulated; cancel compensation with G40 first",
                    a.plane.code(),
                    name(st),
                    st.plane.code()
                ),
            )),
            Motion::Arc(_) => Ok(Kind::Element),
            _ if len(sub(uv(&s.end, st.plane), uv(&s.start, st.plane))) > EPS => {
                Ok(Kind::Element)
            }
            _ => Ok(Kind::Flat),
        })
        .collect()
}

/// The programmed unit tangent of element `s` at its start (`at_end`
/// false) or end, in the plane.
fn tangent(s: &Segment, plane: Plane, at_end: bool) -> V2 {
    let (p0, p1) = (uv(&s.start, plane), uv(&s.end, plane));
    match s.motion {
        Motion::Arc(a) => {
            let (u, v, _) = plane.axes();
            let c = [a.center[u], a.center[v]];
            let p = if at_end { p1 } else { p0 };
            mul(left(unit(sub(p, c))), a.sweep.signum())
        }
        _ => unit(sub(p1, p0)),
    }
}

/// The offset of element `s` by `r` on `side`.
///
/// # Errors
/// An arc whose offset radius would be ≤ 0.
fn offset_of(s: &Segment, st: &CutterStretch, r: f64, blocks: &[Block]) -> Result<Off, NcError> {
    let plane = st.plane;
    let k = st.side.sign() * r;
    let (p0, p1) = (uv(&s.start, plane), uv(&s.end, plane));
    let Motion::Arc(a) = s.motion else {
        let t = unit(sub(p1, p0));
        let n = mul(left(t), k);
        return Ok(Off::Line {
            a: add(p0, n),
            b: add(p1, n),
            t,
        });
    };
    let (u, v, _) = plane.axes();
    let c = [a.center[u], a.center[v]];
    let radius = a.radius - k * a.sweep.signum();
    if radius <= EPS {
        return Err(error_at(
            s,
            blocks,
            format!(
                "{}: the offset of this arc (radius {:.4} mm) would have radius {:.4} mm ≤ 0 with tool radius {r:.4} mm; use a smaller tool or a larger arc",
                name(st),
                a.radius,
                radius
            ),
        ));
    }
    Ok(Off::Arc {
        c,
        r: radius,
        th0: (p0[1] - c[1]).atan2(p0[0] - c[0]),
        sweep: a.sweep,
        orig: a.sweep,
    })
}

/// How two offset elements meet at a corner.
#[derive(Debug, Clone, Copy)]
enum Join {
    /// They meet (tangent, or trimmed to their intersection).
    None,
    /// An arc about the programmed corner `p` over `sweep` (outside).
    Arc { p: V2, sweep: f64 },
    /// A straight move (nearly tangent inside join, or between rapids).
    Line,
}

/// The intersections of a line through `p` with unit direction `t` and
/// the circle about `c` of radius `r`.
fn line_circle(p: V2, t: V2, c: V2, r: f64) -> Vec<V2> {
    let d = sub(p, c);
    let b = dot(t, d);
    let disc = b * b - (dot(d, d) - r * r);
    if disc < 0.0 {
        return Vec::new();
    }
    let q = disc.sqrt();
    vec![add(p, mul(t, -b - q)), add(p, mul(t, -b + q))]
}

/// The intersections of two circles.
fn circle_circle(c1: V2, r1: f64, c2: V2, r2: f64) -> Vec<V2> {
    let d = sub(c2, c1);
    let l = len(d);
    if l < EPS {
        return Vec::new();
    }
    let a = (r1 * r1 - r2 * r2 + l * l) / (2.0 * l);
    let h2 = r1 * r1 - a * a;
    if h2 < 0.0 {
        return Vec::new();
    }
    let e = unit(d);
    let m = add(c1, mul(e, a));
    let h = h2.sqrt();
    vec![add(m, mul(left(e), h)), sub(m, mul(left(e), h))]
}

/// The intersection of the lines or circles of `x` and `y` nearest `near`.
fn intersect(x: &Off, y: &Off, near: V2) -> Option<V2> {
    let points = match (*x, *y) {
        (Off::Line { a, t, .. }, Off::Line { a: a2, t: t2, .. }) => {
            let den = cross(t, t2);
            if den.abs() < 1e-12 {
                Vec::new()
            } else {
                vec![add(a, mul(t, cross(sub(a2, a), t2) / den))]
            }
        }
        (Off::Line { a, t, .. }, Off::Arc { c, r, .. })
        | (Off::Arc { c, r, .. }, Off::Line { a, t, .. }) => line_circle(a, t, c, r),
        (Off::Arc { c, r, .. }, Off::Arc { c: c2, r: r2, .. }) => circle_circle(c, r, c2, r2),
    };
    points
        .into_iter()
        .min_by(|p, q| len(sub(*p, near)).total_cmp(&len(sub(*q, near))))
}

/// Joins offset elements `offs[q]` and `offs[q + 1]` (programmed `a` then
/// `b`) at the programmed corner: trims them at an inside corner, gives
/// the corner arc at an outside one.
///
/// # Errors
/// An inside corner whose offsets do not meet.
fn join(
    offs: &mut [Off],
    q: usize,
    (a, b): (&Segment, &Segment),
    st: &CutterStretch,
    blocks: &[Block],
) -> Result<Join, NcError> {
    let plane = st.plane;
    let (e1, e2) = (offs[q].end(), offs[q + 1].start());
    if len(sub(e1, e2)) < EPS {
        return Ok(Join::None);
    }
    let p = uv(&a.end, plane);
    let (t1, t2) = (tangent(a, plane, true), tangent(b, plane, false));
    let phi = cross(t1, t2).atan2(dot(t1, t2));
    let side = st.side.sign();
    if side * phi > 0.0 && phi.abs() < PI - 1e-9 {
        return match intersect(&offs[q], &offs[q + 1], p) {
            Some(x) => {
                offs[q].trim_end(x);
                offs[q + 1].trim_start(x);
                Ok(Join::None)
            }
            None if len(sub(e1, e2)) < GAP => Ok(Join::Line),
            None => Err(error_at(
                b,
                blocks,
                format!(
                    "{}: at this inside corner the offset elements do not meet; the element is too short or too tightly curved for the tool radius (the tool would gouge)",
                    name(st)
                ),
            )),
        };
    }
    if !a.is_cutting() && !b.is_cutting() {
        return Ok(Join::Line);
    }
    let sweep = if phi.abs() >= PI - 1e-9 {
        -side * PI
    } else {
        phi
    };
    Ok(Join::Arc { p, sweep })
}

/// The segments of one stretch with tool radius `r`, from the tool's pose
/// `cur`; true when the tool ends off the programmed path (a cancel move
/// must follow).
///
/// # Errors
/// See the module header.
fn stretch_path(
    segs: &[Segment],
    st: &CutterStretch,
    r: f64,
    blocks: &[Block],
) -> Result<(Vec<Segment>, bool), NcError> {
    let kinds = kinds(segs, st, blocks)?;
    let els: Vec<usize> = (0..segs.len())
        .filter(|&i| kinds[i] == Kind::Element)
        .collect();
    let Some(&first) = els.first() else {
        return Ok((segs.to_vec(), false));
    };
    look_ahead(segs, &kinds, &els, st, blocks)?;
    if matches!(segs[first].motion, Motion::Arc(_)) {
        return Err(error_at(
            &segs[first],
            blocks,
            format!(
                "{}: the start-up move (the first move in G{} after it) is an arc; expected a line (G0/G1) to start compensation",
                name(st),
                st.plane.code()
            ),
        ));
    }
    let mut offs = els[1..]
        .iter()
        .map(|&e| offset_of(&segs[e], st, r, blocks))
        .collect::<Result<Vec<Off>, NcError>>()?;
    let mut joins = Vec::with_capacity(offs.len());
    for q in 0..offs.len().saturating_sub(1) {
        let pair = (&segs[els[q + 1]], &segs[els[q + 2]]);
        joins.push(join(&mut offs, q, pair, st, blocks)?);
    }
    for (q, o) in offs.iter().enumerate() {
        if !o.valid() {
            return Err(error_at(
                &segs[els[q + 1]],
                blocks,
                format!(
                    "{}: with tool radius {r:.4} mm the offset of this element runs backwards (it is shorter than its inside corners need); the tool would gouge the contour — use a smaller tool or change the contour",
                    name(st)
                ),
            ));
        }
    }
    let start_up = match offs.first() {
        Some(o) => o.start(),
        None => {
            let s = &segs[first];
            let n = mul(left(tangent(s, st.plane, true)), st.side.sign() * r);
            add(uv(&s.end, st.plane), n)
        }
    };
    Ok((
        emit(segs, &kinds, &els, &offs, &joins, start_up, st.plane),
        true,
    ))
}

/// Refuses two moves without motion in the plane in a row between two
/// contour elements.
fn look_ahead(
    segs: &[Segment],
    kinds: &[Kind],
    els: &[usize],
    st: &CutterStretch,
    blocks: &[Block],
) -> Result<(), NcError> {
    for w in els.windows(2) {
        let flats: Vec<usize> = (w[0] + 1..w[1])
            .filter(|&i| kinds[i] == Kind::Flat)
            .collect();
        if flats.len() >= 2 {
            return Err(error_at(
                &segs[flats[1]],
                blocks,
                format!(
                    "{}: two moves without motion in G{} in a row (lines {} and {}); the offset at the corner needs the next contour element — put the moves before G41/G42 or after G40",
                    name(st),
                    st.plane.code(),
                    segs[flats[0]].line,
                    segs[flats[1]].line
                ),
            ));
        }
    }
    Ok(())
}

/// The segments of a stretch from its offsets: the moves before the
/// start-up as programmed, the start-up line to `start_up`, each element
/// along its offset after the join before it, the moves without motion in
/// the plane at the tool's offset point.
fn emit(
    segs: &[Segment],
    kinds: &[Kind],
    els: &[usize],
    offs: &[Off],
    joins: &[Join],
    start_up: V2,
    plane: Plane,
) -> Vec<Segment> {
    let mut out: Vec<Segment> = Vec::with_capacity(segs.len() + joins.len());
    let mut cur = segs[0].start;
    let mut k = 0;
    let mut prev_feed = 0.0;
    for (i, s) in segs.iter().enumerate() {
        let moved = if i < els[0] {
            s.clone()
        } else if kinds[i] != Kind::Element {
            moved(s, cur, with_uv(&s.end, plane, uv(&cur, plane)))
        } else if k == 0 {
            k += 1;
            moved(s, cur, with_uv(&s.end, plane, start_up))
        } else {
            let o = &offs[k - 1];
            if k >= 2 {
                if let Some(j) = join_segment(joins[k - 2], cur, o.start(), s, prev_feed, plane) {
                    cur = j.end;
                    out.push(j);
                }
            }
            k += 1;
            element(s, cur, o, plane)
        };
        if kinds[i] == Kind::Element {
            prev_feed = s.feed;
        }
        cur = moved.end;
        let a = moved.start.to_array();
        let b = moved.end.to_array();
        let still = a.iter().zip(&b).all(|(x, y)| (x - y).abs() < EPS);
        if !(still && matches!(moved.motion, Motion::Linear | Motion::Rapid)) {
            out.push(moved);
        }
    }
    out
}

/// `s` moved to run from `start` to `end` (a straight or still move).
fn moved(s: &Segment, start: Pose, end: Pose) -> Segment {
    Segment {
        start,
        end,
        fixed: true,
        ..s.clone()
    }
}

/// The offset element of `s` from the tool's pose `cur` along `o`.
fn element(s: &Segment, cur: Pose, o: &Off, plane: Plane) -> Segment {
    let end = with_uv(&s.end, plane, o.end());
    let motion = match (s.motion, *o) {
        (Motion::Arc(a), Off::Arc { c, r, sweep, .. }) => {
            let (u, v, n) = plane.axes();
            let mut center = cur.p();
            center[u] = c[0];
            center[v] = c[1];
            center[n] = cur.p()[n];
            Motion::Arc(Arc {
                center,
                radius: r,
                sweep,
                ..a
            })
        }
        (m, _) => m,
    };
    Segment {
        motion,
        ..moved(s, cur, end)
    }
}

/// The corner move from `cur` to `to` before element `next` (whose
/// predecessor had feed `prev_feed`), if the join has one.
fn join_segment(
    j: Join,
    cur: Pose,
    to: V2,
    next: &Segment,
    prev_feed: f64,
    plane: Plane,
) -> Option<Segment> {
    let end = with_uv(&cur, plane, to);
    let feed = if next.is_cutting() {
        next.feed
    } else {
        prev_feed
    };
    let motion = match j {
        Join::None => return None,
        Join::Line if feed > 0.0 => Motion::Linear,
        Join::Line => Motion::Rapid,
        Join::Arc { p, sweep } => {
            let (u, v, _) = plane.axes();
            let mut center = cur.p();
            center[u] = p[0];
            center[v] = p[1];
            Motion::Arc(Arc {
                center,
                radius: len(sub(uv(&cur, plane), p)),
                plane,
                sweep,
                r_form: false,
            })
        }
    };
    Some(Segment {
        block: next.block,
        line: next.line,
        motion,
        start: cur,
        end,
        feed: if matches!(motion, Motion::Rapid) {
            0.0
        } else {
            feed
        },
        fixed: true,
    })
}

/// The tool-centre path: every stretch with a known radius offset (see the
/// module header), its cancel move from the offset point; the other
/// segments unchanged. `tags` gives each segment's stretch.
///
/// # Errors
/// The first stretch that cannot be offset (see the module header).
pub(super) fn offset_path(
    segments: &mut Vec<Segment>,
    tags: &[Option<usize>],
    stretches: &[CutterStretch],
    blocks: &[Block],
) -> Result<(), Vec<NcError>> {
    if stretches.iter().all(|s| s.radius.is_none()) {
        return Ok(());
    }
    let tag = |i: usize| tags.get(i).copied().flatten();
    let mut out: Vec<Segment> = Vec::with_capacity(segments.len());
    let mut off_path = false;
    let mut i = 0;
    while i < segments.len() {
        let s = &segments[i];
        if let Some(k) = tag(i) {
            if off_path {
                return Err(vec![restarted(&stretches[k])]);
            }
            if let Some(r) = stretches[k].radius {
                let j = (i..segments.len())
                    .find(|&j| tag(j) != Some(k))
                    .unwrap_or(segments.len());
                let (segs, off) =
                    stretch_path(&segments[i..j], &stretches[k], r, blocks).map_err(|e| vec![e])?;
                out.extend(segs);
                off_path = off;
                i = j;
                continue;
            }
        }
        let cur = out.last().map_or(s.start, |o| o.end);
        out.push(match s.motion {
            _ if !off_path => s.clone(),
            Motion::Dwell { .. } => moved(s, cur, cur),
            Motion::Arc(_) => return Err(vec![error_at(s, blocks, "the move after G40 cancels cutter compensation and is an arc; expected a line (G0/G1) from the offset point".into())]),
            _ => {
                off_path = false;
                moved(s, cur, s.end)
            }
        });
        i += 1;
    }
    *segments = out;
    Ok(())
}

/// The error for a stretch that starts while the tool is still offset.
fn restarted(st: &CutterStretch) -> NcError {
    NcError::new(
        st.line,
        st.column,
        format!(
            "{}: compensation starts again before the move that cancels the previous one (the first move after G40); put a move between G40 and {}",
            name(st),
            st.code
        ),
    )
}
