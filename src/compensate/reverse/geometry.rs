//! Rebuilding a compensated path (qiu §4-3(2)): arcs keep their centres and
//! take new radii, line vertices move, and the joints between segments are
//! recomputed.
//!
//! Joint rules, for the original joint `J` between segments `i` and `i+1`:
//! - arc–arc: the intersection of the two new circles nearest `J` when it
//!   lies within `4·max(|Δrᵢ|, |Δrᵢ₊₁|) + 1 µm` of `J` (a corner moves a
//!   little); otherwise — tangent arcs, whose circles no longer meet or meet
//!   far away — each arc ends at its radial point through `J`
//!   (`c + r'·(J − c)/|J − c|`) and a short connecting line (normally a few
//!   µm along the common normal) joins them;
//! - arc–line: the line's end follows the arc's radial point; with
//!   [`Edit::tangent_lines`] (beyond the paper), a line meeting the arc
//!   tangentially (within 1°) keeps its end and a connecting line joins it
//!   to the arc's radial point, as between tangent arcs: a long line no
//!   longer tilts by the arc's correction (the Fusion 360 facing program
//!   `cncsprayer_fusion-output`, R 387 mm lead-in and lead-out arcs at
//!   1075 mm/s off 1981 mm lines, 388 → 114 µm at its worst joint);
//! - line–line: the vertex moves by the vertex shift;
//! - the program's first start and last end never move.
//!
//! An arc keeps its direction; its sweep is the one closest to the original.
//! Dwells are placed at the new joint.
//!
//! Units: mm, rad, s.

use crate::nc::program::{dist, Arc, Motion, Segment};

/// The edit to apply to each original segment.
#[derive(Debug, Clone, Default)]
pub struct Edit {
    /// New radius per segment (arcs only; ignored elsewhere), mm.
    pub radius: Vec<f64>,
    /// Shift of the end vertex of each segment (line–line joints), mm.
    pub vertex_shift: Vec<[f64; 3]>,
    /// Dwell inserted after each segment, s (0 = none).
    pub dwell_after: Vec<f64>,
    /// Corner spike after each segment: the vector from the joint to the
    /// spike's tip, mm (zero = none).
    pub spike: Vec<[f64; 3]>,
    /// A line meeting an arc tangentially keeps its end; a connecting
    /// line joins it to the arc's new end (see the module header).
    pub tangent_lines: bool,
}

fn radial(a: &Arc, r: f64, j: [f64; 3]) -> [f64; 3] {
    let (u, v, _) = a.plane.axes();
    let (x, y) = (j[u] - a.center[u], j[v] - a.center[v]);
    let rho = x.hypot(y);
    let mut p = j;
    if rho > 0.0 {
        p[u] = a.center[u] + r * x / rho;
        p[v] = a.center[v] + r * y / rho;
    }
    p
}

/// Intersection of two coplanar circles nearest `j`.
fn intersect(a: &Arc, ra: f64, b: &Arc, rb: f64, j: [f64; 3]) -> Option<[f64; 3]> {
    if a.plane != b.plane {
        return None;
    }
    let (u, v, _) = a.plane.axes();
    let (dx, dy) = (b.center[u] - a.center[u], b.center[v] - a.center[v]);
    let d = dx.hypot(dy);
    if d < 1e-9 || d > ra + rb || d < (ra - rb).abs() {
        return None;
    }
    let along = (ra * ra - rb * rb + d * d) / (2.0 * d);
    let h = (ra * ra - along * along).max(0.0).sqrt();
    let (mx, my) = (a.center[u] + along * dx / d, a.center[v] + along * dy / d);
    let mut best = None;
    let mut best_d = f64::MAX;
    for s in [-1.0, 1.0] {
        let mut p = j;
        p[u] = mx - s * h * dy / d;
        p[v] = my + s * h * dx / d;
        let dd = dist(p, j);
        if dd < best_d {
            best_d = dd;
            best = Some(p);
        }
    }
    best
}

fn arc_of(s: &Segment) -> Option<Arc> {
    match s.motion {
        Motion::Arc(a) => Some(a),
        _ => None,
    }
}

fn is_move(s: &Segment) -> bool {
    !matches!(s.motion, Motion::Dwell { .. })
}

/// The compensated segment list: edited originals (keeping their `block`),
/// connecting lines and dwells (with `block: None`).
pub fn rebuild(orig: &[Segment], edit: &Edit) -> Vec<Segment> {
    rebuild_indexed(orig, edit).0
}

/// As [`rebuild`], with the index in the output of each original
/// segment's own (after a connector before it, before a dwell after it).
pub fn rebuild_indexed(orig: &[Segment], edit: &Edit) -> (Vec<Segment>, Vec<usize>) {
    // Counted, then filled, by the same loop: sized exactly (grown by
    // doubling, the command of a 1 M-segment program with a few spikes
    // would reserve 2 M segments, 368 MB).
    let mut n = 0;
    rebuild_each(orig, edit, &mut |_, _| n += 1);
    let mut out = Vec::with_capacity(n);
    let mut at = Vec::with_capacity(orig.len());
    rebuild_each(orig, edit, &mut |s, own| {
        if own {
            at.push(out.len());
        }
        out.push(s);
    });
    (out, at)
}

/// The end of what was put so far: the last segment, and the feed of
/// the last cutting one (what a connector and a dwell are made from).
#[derive(Default)]
struct Tail {
    last: Option<Segment>,
    cut_feed: Option<f64>,
}

impl Tail {
    fn put(&mut self, put: &mut dyn FnMut(Segment, bool), s: Segment, own: bool) {
        if s.is_cutting() {
            self.cut_feed = Some(s.feed);
        }
        self.last = Some(s.clone());
        put(s, own);
    }

    /// Where the rebuilt program so far ends, as a point (`pen` when empty).
    fn end(&self, pen: [f64; 3]) -> [f64; 3] {
        self.last.as_ref().map_or(pen, |x| x.end.p())
    }
}

/// The segments of [`rebuild`], in order, each given to `put` with
/// whether it is an original segment's own (not a connector, a spike's
/// line or a dwell), without holding them: a writer can take them one by
/// one ([`crate::nc::patch::write_source_each`]).
pub fn rebuild_each(orig: &[Segment], edit: &Edit, put: &mut dyn FnMut(Segment, bool)) {
    let mut tail = Tail::default();
    let mut pen = orig.first().map_or([0.0; 3], |s| s.start.p());
    // The new start of the next move, from its joint with the move before
    // it (none before the first move: the program's first start is kept).
    let (starts, ends) = joints(orig, edit);
    for (i, s) in orig.iter().enumerate() {
        let mut seg = s.clone();
        if !is_move(s) {
            seg.start.x = pen[0];
            seg.start.y = pen[1];
            seg.start.z = pen[2];
            seg.end = seg.start;
            tail.put(put, seg, true);
            continue;
        }
        let (start, end) = (starts[i], ends[i]);
        if dist(pen, start) > 1e-6 {
            let c = connector(&tail, s, pen, start);
            tail.put(put, c, false);
        }
        seg.start.x = start[0];
        seg.start.y = start[1];
        seg.start.z = start[2];
        seg.end.x = end[0];
        seg.end.y = end[1];
        seg.end.z = end[2];
        if let Motion::Arc(a) = s.motion {
            seg.motion = refit_arc(a, edit_radius(edit, i), start, end);
        }
        pen = end;
        tail.put(put, seg, true);
        let sp = edit.spike.get(i).copied().unwrap_or([0.0; 3]);
        if sp != [0.0; 3] {
            let tip = [pen[0] + sp[0], pen[1] + sp[1], pen[2] + sp[2]];
            for to in [tip, pen] {
                let c = connector(&tail, s, tail.end(pen), to);
                tail.put(put, c, false);
            }
        }
        let dw = edit.dwell_after.get(i).copied().unwrap_or(0.0);
        if dw > 0.0 {
            let mut d = tail.last.clone().unwrap_or_else(|| s.clone());
            d.block = None;
            d.line = 0;
            d.motion = Motion::Dwell { seconds: dw };
            d.start = d.end;
            d.feed = 0.0;
            tail.put(put, d, false);
        }
    }
}

/// The new radius of segment `i` (0 when the edit has none), mm.
fn edit_radius(edit: &Edit, i: usize) -> f64 {
    edit.radius.get(i).copied().unwrap_or(0.0)
}

/// The new start and end point of every segment: each joint between
/// consecutive moves placed by the rules of the module header, dwells
/// skipped, the program's first start and last end kept. mm.
fn joints(orig: &[Segment], edit: &Edit) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let n = orig.len();
    let r_new = |i: usize| edit_radius(edit, i);
    let mut starts: Vec<[f64; 3]> = orig.iter().map(|s| s.start.p()).collect();
    let mut ends: Vec<[f64; 3]> = orig.iter().map(|s| s.end.p()).collect();
    let moves: Vec<usize> = (0..n).filter(|&i| is_move(&orig[i])).collect();
    for w in moves.windows(2) {
        let (i, k) = (w[0], w[1]);
        let jp = orig[i].end.p();
        let (ai, ak) = (arc_of(&orig[i]), arc_of(&orig[k]));
        let (p, q) = match (ai, ak) {
            (Some(a), Some(b)) => {
                let (ra, rb) = (r_new(i), r_new(k));
                let p = radial(&a, ra, jp);
                let q = radial(&b, rb, jp);
                let lim = 4.0 * (ra - a.radius).abs().max((rb - b.radius).abs()) + 1e-3;
                match intersect(&a, ra, &b, rb, jp) {
                    Some(x) if dist(x, jp) <= lim => (x, x),
                    _ => (p, q),
                }
            }
            (Some(a), None) => {
                let p = radial(&a, r_new(i), jp);
                if edit.tangent_lines && tangent_joint(&orig[i], &orig[k]) {
                    (p, jp)
                } else {
                    (p, p)
                }
            }
            (None, Some(b)) => {
                let q = radial(&b, r_new(k), jp);
                if edit.tangent_lines && tangent_joint(&orig[i], &orig[k]) {
                    (jp, q)
                } else {
                    (q, q)
                }
            }
            (None, None) => {
                let s = edit.vertex_shift.get(i).copied().unwrap_or([0.0; 3]);
                let x = [jp[0] + s[0], jp[1] + s[1], jp[2] + s[2]];
                (x, x)
            }
        };
        ends[i] = p;
        starts[k] = q;
    }
    (starts, ends)
}

/// Segments `a` and `b` meet tangentially (within 1°).
pub fn tangent_joint(a: &Segment, b: &Segment) -> bool {
    match (
        super::corner::tangent(a, true),
        super::corner::tangent(b, false),
    ) {
        (Some(u), Some(v)) => u[0] * v[0] + u[1] * v[1] + u[2] * v[2] > (1.0f64).to_radians().cos(),
        _ => false,
    }
}

/// The line from the pen (where the rebuilt program so far, `tail`, ends)
/// to `to`, the new start of `s`: at `s`'s feed, or the last cutting feed
/// when `s` is a rapid.
fn connector(tail: &Tail, s: &Segment, pen: [f64; 3], to: [f64; 3]) -> Segment {
    let mut c = s.clone();
    c.block = None;
    c.line = 0;
    c.motion = Motion::Linear;
    c.start = tail.last.as_ref().map_or(s.start, |x| x.end);
    c.start.x = pen[0];
    c.start.y = pen[1];
    c.start.z = pen[2];
    c.end = c.start;
    c.end.x = to[0];
    c.end.y = to[1];
    c.end.z = to[2];
    c.feed = if s.is_cutting() {
        s.feed
    } else {
        tail.cut_feed.unwrap_or(s.feed)
    };
    c
}

/// Arc `a` with radius `r`, from `start` to `end`: same centre and
/// direction, the sweep nearest the original; a line when no sweep of the
/// arc's direction remains.
fn refit_arc(mut a: Arc, r: f64, start: [f64; 3], end: [f64; 3]) -> Motion {
    a.radius = r;
    let (u, v, _) = a.plane.axes();
    let th0 = (start[v] - a.center[v]).atan2(start[u] - a.center[u]);
    let th1 = (end[v] - a.center[v]).atan2(end[u] - a.center[u]);
    let tau = std::f64::consts::TAU;
    let mut sw = if a.sweep > 0.0 {
        (th1 - th0).rem_euclid(tau)
    } else {
        -(th0 - th1).rem_euclid(tau)
    };
    if (sw - a.sweep).abs() > std::f64::consts::PI {
        sw += if a.sweep > sw { tau } else { -tau };
    }
    if a.sweep.abs() > tau - 1e-9 && sw.abs() < 1e-9 {
        sw = a.sweep;
    }
    if sw == 0.0 || sw.signum() != a.sweep.signum() {
        Motion::Linear
    } else {
        a.sweep = sw;
        Motion::Arc(a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compensate::reverse::rounds::identity;
    use crate::nc::program::parse;

    #[test]
    fn a_tangent_line_keeps_its_end_with_tangent_lines() {
        // A line into a tangent R10 quarter arc (start (10, 0), centre
        // (10, 10)), then a line at a corner (not tangent).
        let p = parse("G21 G90\nG0 X0 Y0\nG1 X10 F1000\nG3 X20 Y10 I0 J10\nG1 X30 Y10\n").unwrap();
        let o = &p.segments;
        assert!(tangent_joint(&o[1], &o[2]));
        assert!(!tangent_joint(&o[2], &o[3]));
        let mut e = identity(o, vec![0.0; o.len()]);
        e.radius[2] = 10.5;
        // Default: the line's end follows the arc's radial point (10, -0.5).
        let plain = rebuild(o, &e);
        assert_eq!(plain.len(), o.len());
        assert!((plain[1].end.y + 0.5).abs() < 1e-12, "{:?}", plain[1].end);
        // Tangent lines: the line ends where it did, a connector of 0.5 mm
        // joins the arc's new start; the corner after the arc is not
        // tangent, so the next line starts at the arc's new end.
        e.tangent_lines = true;
        let t = rebuild(o, &e);
        assert_eq!(t.len(), o.len() + 1);
        assert_eq!(t[1].end.p(), [10.0, 0.0, 0.0]);
        assert_eq!(t[2].block, None);
        assert!((t[2].end.y + 0.5).abs() < 1e-12 && (t[2].end.x - 10.0).abs() < 1e-12);
        assert!((t[3].end.x - 20.5).abs() < 1e-12 && (t[4].start.x - 20.5).abs() < 1e-12);
    }
}
