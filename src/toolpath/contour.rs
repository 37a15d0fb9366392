//! Contour error (qiu §4-2): the distance from the simulated point to the
//! commanded path — not to the commanded point at the same instant —
//! computed exactly for lines (clamped projection) and arcs (radial
//! distance inside the swept sector, else the nearer end point; for a
//! helical arc the normal offset is taken at the point's angle, which is
//! exact for planar arcs and a close approximation for helices).
//!
//! The contour error is the distance to the nearest point of the WHOLE
//! path. The search starts locally: it keeps the arc-length position of the
//! last nearest point and examines the elements within
//! `2·(last error + step) + 0.05 mm` of it (at least the neighbours), which
//! is almost always the answer and costs a few elements. The result is then
//! checked against the whole path through a bounding-volume hierarchy
//! ([`super::bvh`]): any element nearer by more than [`EXACT_SLACK`] wins
//! and the tracker moves on from there. So a path that revisits itself (a
//! return pass, a retract over the part, a reversal) is measured against
//! its nearest part, as an exhaustive search would, and a local search that
//! followed the wrong pass cannot inflate the error. When two elements are
//! equally near (a circle programmed twice) the one closer along the path
//! to the last nearest point on a cutting move wins, so the search moves
//! on and a return rapid crossing the contour does not carry it to another
//! pass. A simulation ([`super::simulate()`]) also follows the *commanded*
//! point along the path ([`Tracker::follow`], the local search only: the
//! command moves continuously) and breaks ties towards it
//! ([`Tracker::tie_towards`]), also against an equally near element the
//! exact check finds far along the path: where the tool passes a point
//! another pass shares and that pass is strictly nearer for a moment (a
//! retract rising through the upper layers' contours, which end at the
//! same corner), the tracker comes back to the commanded pass as soon as
//! the two tie again, instead of staying on the other pass. Without it the
//! CAMotics botomata pocket, whose second copy of the part (a `G10 L2`
//! work offset this model does not apply) repeats the first's path, had
//! every sample of the second copy counted on the first copy's segments
//! (the maximum error is the same; the per-segment statistics, which
//! reverse compensation corrects and judges by, were not).
//! Each element carries a bounding sphere; an element whose sphere is
//! farther than the best distance so far (+ 2 nm) cannot win and is skipped
//! without computing its nearest point — the result is the same as
//! examining it, at a few multiplications instead of square roots and an
//! `atan2`. An arc inside whose sphere the point lies is tested once more
//! against its cylinder band (radius `r`, the helix's height range) and
//! its end points, which rejects the points near a large arc's centre
//! (reverse compensation of LinuxCNC's `tort.ngc`: 7.7 → 4.1 s natively).
//! The hierarchy is not walked for every sample: the tracker keeps the
//! list of elements near where it last walked it, valid while the tool
//! stays well inside that neighbourhood (4.1 → about 2.5 s).
//!
//! Memory: a line's element holds no bounding sphere (it is computed
//! where it is read, by the same expressions and so to the same bits as
//! when it was stored) and an arc's geometry and sphere are boxed, so a
//! line's element is 88 B in wasm32 instead of 200 B (a 2 M-line program:
//! 220 MB less), and the hierarchy is built from the spheres as computed,
//! without a copy of them (its splits order the elements by their centres
//! alone, which for a line takes no square root: ordering them by the
//! whole sphere took 0.6 s more for 1 M elements in wasm).
//!
//! Units: mm.

use super::bvh::Bvh;
use crate::nc::program::{Motion, Segment};

/// One element of the reference path.
#[derive(Debug, Clone)]
pub struct Element {
    /// Index of the segment in the reference program.
    pub segment: usize,
    /// Arc length at the element's start, mm.
    pub s0: f64,
    /// Element length, mm.
    pub len: f64,
    /// Rapid move (excluded from the maximum error).
    pub rapid: bool,
    geo: Geo,
}

/// A line, or an arc with its bounding sphere (see [`Element::bound`]).
#[derive(Debug, Clone)]
enum Geo {
    Line(LineGeo),
    Arc(Box<(ArcGeo, Sphere)>),
}

/// A sphere `(centre, radius)`, mm.
type Sphere = ([f64; 3], f64);

impl Element {
    /// The centre of [`Element::bound`], without its radius.
    #[inline]
    fn centre(&self) -> [f64; 3] {
        match self.geo {
            Geo::Line(ref line) => line_centre(line),
            Geo::Arc(ref arc) => arc.1 .0,
        }
    }

    /// Bounding sphere: every point of the element lies within `.1` mm of
    /// `.0` (`line_sphere`, `arc_sphere`).
    #[inline]
    pub fn bound(&self) -> Sphere {
        match self.geo {
            Geo::Line(ref line) => line_sphere(line),
            Geo::Arc(ref arc) => arc.1,
        }
    }
}

/// A line from `p0` along `d` (`l2 = |d|²`), mm.
#[derive(Debug, Clone, Copy)]
struct LineGeo {
    p0: [f64; 3],
    d: [f64; 3],
    l2: f64,
}

/// An arc (or helix) about `c` of radius `r` in the plane of `axes`
/// `(u, v, normal)`, from the angle whose `(sin, cos)` is `sc0` over
/// `sweep` rad, rising `dn` from `n0` along the normal; `p0`, `p1` are the
/// programmed end points. mm, rad.
#[derive(Debug, Clone, Copy)]
struct ArcGeo {
    c: [f64; 3],
    r: f64,
    sc0: (f64, f64),
    sweep: f64,
    axes: (usize, usize, usize),
    n0: f64,
    dn: f64,
    p0: [f64; 3],
    p1: [f64; 3],
}

/// The nearest point found for one sample.
#[derive(Debug, Clone, Copy)]
pub struct Nearest {
    /// Index into [`Path::elements`].
    pub element: usize,
    /// Distance, mm.
    pub dist: f64,
    /// The nearest path point, mm.
    pub point: [f64; 3],
    /// Signed deviation normal to the element in its plane (lines in XY:
    /// positive to the left of the direction of travel; arcs: the radius
    /// loss `R − ρ`, positive inside), mm; NaN at an element's end point.
    pub normal: f64,
    /// Arc length of the nearest point, mm.
    pub s: f64,
}

/// The commanded path as lines and arcs with their arc lengths.
#[derive(Debug, Clone)]
pub struct Path {
    /// Elements in path order (dwells and zero-length moves dropped).
    pub elements: Vec<Element>,
    /// Hierarchy over the elements' bounding spheres, for the exact check.
    bvh: Bvh,
}

/// Squared distance, mm².
fn d2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}

fn d3(a: [f64; 3], b: [f64; 3]) -> f64 {
    d2(a, b).sqrt()
}

/// A sphere around an element. Lines: about the midpoint, radius half the
/// length. Arcs: about the midpoint of the arc's own chord (in the plane;
/// at mid-height along a helix's axis), radius the half chord up to 180°
/// (such an arc lies inside the circle on its chord) or the sagitta
/// `R(1 − cos(φ/2))` past 180°, plus half a helix's rise, and at least the
/// distance to the programmed end points (which may sit off the radius by
/// the interpreter's tolerance); widened by 1e-12 relative and 1 nm against
/// rounding.
#[inline]
fn line_sphere(line: &LineGeo) -> Sphere {
    widened(line_centre(line), 0.5 * line.l2.sqrt())
}

/// The centre of [`line_sphere`]: the line's midpoint.
#[inline]
fn line_centre(&LineGeo { p0, d, .. }: &LineGeo) -> [f64; 3] {
    [p0[0] + 0.5 * d[0], p0[1] + 0.5 * d[1], p0[2] + 0.5 * d[2]]
}

/// The bounding sphere of an arc (see [`line_sphere`]).
fn arc_sphere(arc: &ArcGeo) -> Sphere {
    let ArcGeo {
        c,
        r,
        sc0: (s0, c0),
        sweep,
        axes: (u, v, n),
        n0,
        dn,
        p0,
        p1,
    } = *arc;
    let half = 0.5 * sweep.abs();
    // Direction of the arc's midpoint: the start direction turned by half
    // the sweep.
    let (sh, ch) = (0.5 * sweep).sin_cos();
    let (sm, cm) = (s0 * ch + c0 * sh, c0 * ch - s0 * sh);
    let (planar, off) = if half <= std::f64::consts::FRAC_PI_2 {
        (r * half.sin(), r * half.cos())
    } else {
        (r * (1.0 - half.cos()), r * half.cos())
    };
    let mut m = [0.0; 3];
    m[u] = c[u] + off * cm;
    m[v] = c[v] + off * sm;
    m[n] = n0 + 0.5 * dn;
    widened(m, (planar + 0.5 * dn.abs()).max(d3(p0, m)).max(d3(p1, m)))
}

/// The sphere about `m` of radius `rad` widened by 1e-12 relative and
/// 1 nm.
#[inline]
fn widened(m: [f64; 3], rad: f64) -> Sphere {
    (m, rad * (1.0 + 1e-12) + 1e-9)
}

impl Path {
    /// The path of `segments`.
    pub fn new(segments: &[Segment]) -> Self {
        let mut elements = Vec::with_capacity(segments.len());
        let mut s = 0.0;
        for (i, seg) in segments.iter().enumerate() {
            let len = seg.length();
            if len <= 0.0 {
                continue;
            }
            let p0 = seg.start.p();
            let p1 = seg.end.p();
            let geo = match seg.motion {
                Motion::Arc(a) => {
                    let (u, v, n) = a.plane.axes();
                    let arc = ArcGeo {
                        c: a.center,
                        r: a.radius,
                        sc0: (p0[v] - a.center[v]).atan2(p0[u] - a.center[u]).sin_cos(),
                        sweep: a.sweep,
                        axes: (u, v, n),
                        n0: p0[n],
                        dn: p1[n] - p0[n],
                        p0,
                        p1,
                    };
                    Geo::Arc(Box::new((arc, arc_sphere(&arc))))
                }
                Motion::Dwell { .. } => continue,
                _ => {
                    let d = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
                    Geo::Line(LineGeo {
                        p0,
                        d,
                        l2: d[0] * d[0] + d[1] * d[1] + d[2] * d[2],
                    })
                }
            };
            elements.push(Element {
                segment: i,
                s0: s,
                len,
                rapid: matches!(seg.motion, Motion::Rapid),
                geo,
            });
            s += len;
        }
        let bvh = Bvh::from_fn(
            elements.len(),
            |i| elements[i].centre(),
            |i| elements[i].bound(),
        );
        Self { elements, bvh }
    }

    /// Whether every point of element `i` is farther than `d` from `q`
    /// (a conservative test on the bounding sphere).
    #[inline]
    pub fn farther_than(&self, i: usize, q: [f64; 3], d: f64) -> bool {
        let e = &self.elements[i];
        let (m, rad) = e.bound();
        let reach = rad + d;
        if d2(q, m) > reach * reach {
            return true;
        }
        match e.geo {
            Geo::Arc(ref arc) => arc.0.farther_than(q, d),
            Geo::Line(_) => false,
        }
    }

    /// A lower bound of the distance from `q` to every point
    /// [`Path::nearest_on`] can return on element `i`, mm: a line's exact
    /// distance (its clamped projection), an arc's distance to the
    /// cylinder band its interior points lie on or to its nearer end point
    /// (as `ArcGeo::farther_than`). Both are distances to a fixed set, so
    /// from another point `p` the bound falls by at most `|p − q|`.
    #[inline]
    pub fn lower_bound(&self, i: usize, q: [f64; 3]) -> f64 {
        let e = &self.elements[i];
        match e.geo {
            Geo::Line(ref line) => line.nearest(i, e, q).dist,
            Geo::Arc(ref arc) => arc.0.lower_bound(q),
        }
    }

    /// Exact nearest point on element `i` to `q`. `hint` is the arc length
    /// the caller expects; it only resolves where on a full circle a point
    /// just behind the start lies (at its start when the hint is in the
    /// circle's first quarter and the point in its last).
    #[inline]
    pub fn nearest_on(&self, i: usize, q: [f64; 3], hint: f64) -> Nearest {
        let e = &self.elements[i];
        match e.geo {
            Geo::Line(ref line) => line.nearest(i, e, q),
            Geo::Arc(ref arc) => arc.0.nearest(i, e, q, hint),
        }
    }
}

impl LineGeo {
    /// Nearest point to `q` on this line, element `i` of the path: the
    /// clamped projection.
    #[inline]
    fn nearest(&self, i: usize, e: &Element, q: [f64; 3]) -> Nearest {
        let (p0, d, l2) = (&self.p0, &self.d, self.l2);
        let w = [q[0] - p0[0], q[1] - p0[1], q[2] - p0[2]];
        let f = ((w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / l2).clamp(0.0, 1.0);
        let pt = [p0[0] + d[0] * f, p0[1] + d[1] * f, p0[2] + d[2] * f];
        let normal = if f > 0.0 && f < 1.0 {
            let l = l2.sqrt();
            (d[0] * w[1] - d[1] * w[0]) / l
        } else {
            f64::NAN
        };
        Nearest {
            element: i,
            dist: d3(q, pt),
            point: pt,
            normal,
            s: e.s0 + f * e.len,
        }
    }
}

impl ArcGeo {
    /// Whether every point [`ArcGeo::nearest`] can return is farther than
    /// `d` from `q`: its interior points lie on the cylinder of radius `r`
    /// between the heights `n0` and `n0 + dn`, so their distance is at
    /// least √((ρ − r)² + axial gap²); its end points are tested as they
    /// are (they may sit off the radius by the interpreter's tolerance).
    /// A sphere around a large arc holds many points near its centre that
    /// this test rejects at one square root instead of an `atan2`.
    #[inline]
    fn farther_than(&self, q: [f64; 3], d: f64) -> bool {
        let (u, v, n) = self.axes;
        let reach = d + 1e-9;
        let r2 = reach * reach;
        let (x, y) = (q[u] - self.c[u], q[v] - self.c[v]);
        let radial = (x * x + y * y).sqrt() - self.r;
        let axial = ((q[n] - self.n0 - 0.5 * self.dn).abs() - 0.5 * self.dn.abs()).max(0.0);
        radial * radial + axial * axial > r2 && d2(q, self.p0) > r2 && d2(q, self.p1) > r2
    }

    /// The distance from `q` to the cylinder band of this arc's interior
    /// points or to its nearer end point, whichever is less (see
    /// [`ArcGeo::farther_than`]), mm.
    #[inline]
    fn lower_bound(&self, q: [f64; 3]) -> f64 {
        let (u, v, n) = self.axes;
        let (x, y) = (q[u] - self.c[u], q[v] - self.c[v]);
        let radial = (x * x + y * y).sqrt() - self.r;
        let axial = ((q[n] - self.n0 - 0.5 * self.dn).abs() - 0.5 * self.dn.abs()).max(0.0);
        let band = (radial * radial + axial * axial).sqrt();
        let ends = d3(q, self.p0).min(d3(q, self.p1));
        if band < ends {
            band
        } else {
            ends
        }
    }

    /// Nearest point to `q` on this arc, element `i` of the path: radial
    /// inside the swept sector, else the nearer end point. `hint` as in
    /// [`Path::nearest_on`].
    #[inline]
    fn nearest(&self, i: usize, e: &Element, q: [f64; 3], hint: f64) -> Nearest {
        let (c, r, sweep) = (&self.c, self.r, self.sweep);
        let (u, v, n) = self.axes;
        let (x, y) = (q[u] - c[u], q[v] - c[v]);
        let rho = (x * x + y * y).sqrt();
        // Angle of q from the start, in the sweep's direction.
        let (s0, c0) = self.sc0;
        let mut phi = (c0 * y - s0 * x).atan2(c0 * x + s0 * y);
        if sweep < 0.0 {
            phi = -phi;
        }
        if phi < 0.0 {
            phi += std::f64::consts::TAU;
        }
        let mut f = phi / sweep.abs();
        if sweep.abs() >= std::f64::consts::TAU - 1e-9 && f > 0.75 && hint < e.s0 + 0.25 * e.len {
            f = 0.0;
        }
        if f <= 1.0 && rho > 0.0 {
            let mut pt = [0.0; 3];
            pt[u] = c[u] + r * x / rho;
            pt[v] = c[v] + r * y / rho;
            // `if` rather than `f64::min`, which is a call in wasm.
            let g = phi / sweep.abs();
            pt[n] = self.n0 + self.dn * if g > 1.0 { 1.0 } else { g };
            Nearest {
                element: i,
                dist: d3(q, pt),
                point: pt,
                normal: r - rho,
                s: e.s0 + f * e.len,
            }
        } else {
            let (da, db) = (d3(q, self.p0), d3(q, self.p1));
            if da <= db {
                Nearest {
                    element: i,
                    dist: da,
                    point: self.p0,
                    normal: f64::NAN,
                    s: e.s0,
                }
            } else {
                Nearest {
                    element: i,
                    dist: db,
                    point: self.p1,
                    normal: f64::NAN,
                    s: e.s0 + e.len,
                }
            }
        }
    }
}

/// How much nearer than the local result another element must be for the
/// exact check to take it, mm (1 nm: ties — a path programmed twice — stay
/// with the element closer along the path).
pub const EXACT_SLACK: f64 = 1e-6;

/// A nearest-point search that follows the tool along the path and checks
/// its result against the whole path.
#[derive(Debug, Clone)]
pub struct Tracker {
    cur: usize,
    s: f64,
    /// Arc length of the last nearest point on a cutting move: ties are
    /// broken towards it, so a rapid that crosses a contour cut several
    /// times does not carry the tracker over to another pass.
    s_cut: f64,
    /// Arc length ties are broken towards instead of `s_cut`, when set
    /// ([`Tracker::tie_towards`]: the commanded point's).
    s_tie: Option<f64>,
    err: f64,
    last: Option<[f64; 3]>,
    /// The elements that may lie within `near_r` of `near_q` (ascending):
    /// while a query point has moved less than `near_r − d` from
    /// `near_q`, no other element can be nearer than `d`, so the exact
    /// check scans this short list instead of the whole hierarchy.
    near: Vec<u32>,
    /// Per element of `near`, [`Path::lower_bound`] from `near_q`: from a
    /// query point `q` the element is at least `near_lb − |q − near_q|`
    /// away, so the exact check skips, at one comparison, the elements
    /// that cannot be nearer than its bound (the same result: such an
    /// element is never taken).
    near_lb: Vec<f64>,
    near_q: [f64; 3],
    near_r: f64,
}

/// How far beyond the distance it must cover the exact check's element
/// list reaches, as a fraction of that distance plus mm: a wider list is
/// rebuilt less often but scanned longer. Reverse compensation of tort,
/// cds and arcspiral (the shared NC corpus) natively, of (0.25, 0.05),
/// (0.5, 0.2), (1, 0.5), (0.5, 1) and (2, 2 mm): (1, 0.5) and (0.5, 1)
/// fastest (2.2–2.5 s each), the narrowest slowest (3.6–4.2 s), on a
/// machine too loaded to resolve less than about 20 %. Since the scan
/// skips most of the list at one comparison (`near_lb`), a wider list
/// pays: the reverse compensation of the CAMotics botomata pocket, the
/// UGS Gates program and the CNCjs pocket (dt 2 ms), CPU s at (1, 0.5),
/// (1, 1) and (1, 1.5 mm): 5.7/3.4/2.6, 5.0/3.6/2.7, 4.7/3.8/3.0; (1, 3)
/// 4.6 and 4.8 s for the first two. Results are the same for any margin
/// (the list only decides what is scanned).
const NEAR_MARGIN: (f64, f64) = (1.0, 1.0);

impl Default for Tracker {
    fn default() -> Self {
        Self {
            cur: 0,
            s: 0.0,
            s_cut: 0.0,
            s_tie: None,
            err: 0.0,
            last: None,
            near: Vec::new(),
            near_lb: Vec::new(),
            near_q: [0.0; 3],
            near_r: -1.0,
        }
    }
}

impl Tracker {
    /// A tracker whose last nearest point is the start of element
    /// `element` of `path` (a window of a longer run starts there, not at
    /// the path's start; [`super::locality`]).
    pub fn at(path: &Path, element: usize) -> Self {
        let s = path.elements.get(element).map_or(0.0, |e| e.s0);
        Self {
            cur: element.min(path.elements.len().saturating_sub(1)),
            s,
            s_cut: s,
            ..Self::default()
        }
    }

    /// Nearer, or as near (within 1 nm, e.g. a path that repeats itself)
    /// and closer along the path to the arc length set by
    /// [`Tracker::tie_towards`], else to the last nearest point on a
    /// cutting move.
    #[inline]
    fn better(&self, cand: &Nearest, best: &Nearest) -> bool {
        let s = self.s_tie.unwrap_or(self.s_cut);
        cand.dist < best.dist - 1e-9
            || (cand.dist <= best.dist + 1e-9 && (cand.s - s).abs() < (best.s - s).abs())
    }

    /// Breaks the ties of the following searches towards arc length `s`
    /// (a simulation sets the commanded point's, [`Tracker::follow`]).
    #[inline]
    pub fn tie_towards(&mut self, s: f64) {
        self.s_tie = Some(s);
    }

    /// Follows a point that moves continuously along the path (the
    /// commanded point) by the local search alone, and returns the arc
    /// length of its nearest point (`None` for an empty path).
    #[inline]
    pub fn follow(&mut self, path: &Path, q: [f64; 3]) -> Option<f64> {
        let best = self.local(path, q)?;
        self.settle(path, q, &best);
        Some(best.s)
    }

    /// Moves the tracker to `best`, the nearest point of `path` to `q`.
    #[inline]
    fn settle(&mut self, path: &Path, q: [f64; 3], best: &Nearest) {
        self.cur = best.element;
        self.s = best.s;
        if !path.elements[best.element].rapid {
            self.s_cut = best.s;
        }
        self.err = best.dist;
        self.last = Some(q);
    }

    /// The nearest point of `path` to `q`, searched around the last one.
    /// `None` for an empty path.
    pub fn nearest(&mut self, path: &Path, q: [f64; 3]) -> Option<Nearest> {
        self.nearest_within(path, q, f64::INFINITY)
    }

    /// As [`Tracker::nearest`]. The local search gives a candidate; the
    /// whole path is then searched through the bounding-volume hierarchy
    /// for anything nearer by more than [`EXACT_SLACK`], so the distance
    /// equals an exhaustive nearest-point search to within that slack
    /// wherever the path revisits itself (a return pass, a retract over
    /// the part, a reversal), and the tracker moves on to the element it
    /// finds. `known` (a distance from `q` to some point of the path, e.g.
    /// the commanded point) is kept for callers; the exact check makes it
    /// unnecessary.
    pub fn nearest_within(&mut self, path: &Path, q: [f64; 3], known: f64) -> Option<Nearest> {
        let _ = known;
        let mut best = self.local(path, q)?;
        if best.dist > EXACT_SLACK {
            let need = best.dist - EXACT_SLACK;
            // With a tie target, equally near elements count too.
            let reach = if self.s_tie.is_some() {
                best.dist + 2e-9
            } else {
                need
            };
            self.cover(path, q, reach);
            // Among the elements nearer than `need`, the nearest; of equally
            // near ones (a pass programmed twice) the one closer along the
            // path, as in the local search, whatever the list's order. With
            // a tie target, also an element as near as the local one and
            // closer to the target along the path (the commanded pass).
            let mut found: Option<Nearest> = None;
            let moved = d3(q, self.near_q);
            for (&i, &lb) in self.near.iter().zip(&self.near_lb) {
                let i = i as usize;
                let bound = found.map_or(reach, |f| f.dist + 2e-9);
                // 1 nm against rounding (the bound is a distance in mm).
                if lb - moved > bound + 1e-9 {
                    continue;
                }
                if !path.farther_than(i, q, bound) {
                    let cand = path.nearest_on(i, q, self.s);
                    let takes = cand.dist < need
                        || (self.s_tie.is_some()
                            && cand.element != best.element
                            && self.better(&cand, &best));
                    if takes && found.is_none_or(|f| self.better(&cand, &f)) {
                        found = Some(cand);
                    }
                }
            }
            if let Some(f) = found {
                best = f;
            }
        }
        self.settle(path, q, &best);
        Some(best)
    }

    /// Makes `near` hold every element that may be within `d` of `q`:
    /// kept while `q` is within `near_r − d` of where it was gathered
    /// (every element left out is farther than `near_r` from there), else
    /// gathered again through the hierarchy with a margin.
    fn cover(&mut self, path: &Path, q: [f64; 3], d: f64) {
        if d + 1e-9 <= self.near_r - d3(q, self.near_q) {
            return;
        }
        let r = d * (1.0 + NEAR_MARGIN.0) + NEAR_MARGIN.1;
        let mut near = std::mem::take(&mut self.near);
        near.clear();
        path.bvh.visit_near(
            q,
            || r,
            |i| {
                if !path.farther_than(i, q, r) {
                    near.push(i as u32);
                }
            },
        );
        near.sort_unstable();
        let mut lb = std::mem::take(&mut self.near_lb);
        lb.clear();
        lb.extend(near.iter().map(|&i| path.lower_bound(i as usize, q)));
        self.near_lb = lb;
        self.near = near;
        self.near_q = q;
        self.near_r = r;
    }

    /// The nearest point within the window around the last one.
    fn local(&self, path: &Path, q: [f64; 3]) -> Option<Nearest> {
        let n = path.elements.len();
        if n == 0 {
            return None;
        }
        let step = self.last.map_or(0.0, |l| d3(l, q));
        let w = 2.0 * (self.err + step) + 0.05;
        let (lo, hi) = (self.s - w, self.s + w);
        let cur = self.cur.min(n - 1);
        let mut best = path.nearest_on(cur, q, self.s);
        // An element entirely farther than best + 1 nm can neither be
        // nearer nor tie (see `better`); 2 nm leaves room for rounding.
        let mut consider = |i: usize| {
            if !path.farther_than(i, q, best.dist + 2e-9) {
                let cand = path.nearest_on(i, q, self.s);
                if self.better(&cand, &best) {
                    best = cand;
                }
            }
        };
        let mut i = cur;
        while i > 0 {
            i -= 1;
            consider(i);
            if path.elements[i].s0 < lo {
                break;
            }
        }
        let mut i = cur + 1;
        while i < n {
            consider(i);
            let e = &path.elements[i];
            if e.s0 + e.len > hi {
                break;
            }
            i += 1;
        }
        Some(best)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::program::parse;

    /// A line and a rapid, short and long arcs both ways, a full circle,
    /// helices in three planes and a tiny arc.
    fn mixed_path() -> Path {
        let p = parse(
            "G0 X10 Y0 Z0\nG1 X12 Y3 Z1 F1000\nG3 X22 Y3 R5\nG2 X32 Y3 R-5\n\
             G3 X32 Y3 I-7 J0\nG3 X40 Y-4 Z4 R8\nG2 X30 Y-10 Z2 R-9\nG18 G2 X40 Z6 I5 K2\n\
             G19 G3 Y-2 Z6 J4 K0\nG17 G3 X40.3 Y-2.2 R0.2",
        )
        .unwrap();
        Path::new(&p.segments)
    }

    /// The exact check's lower bound is below the distance of every point
    /// `nearest_on` returns, also from a point moved off (the bound falls
    /// by at most the move), equals it for lines and often for arcs:
    /// lines, arcs both ways, a full circle,
    /// helices in three planes, and a point at an arc's centre.
    #[test]
    fn lower_bounds_hold_from_anywhere_and_are_tight() {
        let path = mixed_path();
        // A fixed pseudo-random cloud around the path (no symmetry).
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut tight, mut lines) = (0, 0);
        for i in 0..path.elements.len() {
            let (m, rad) = path.elements[i].bound();
            for _ in 0..400 {
                let q = [0, 1, 2].map(|a| m[a] + (2.0 * rnd() - 1.0) * 1.5 * (rad + 1.0));
                let lb = path.lower_bound(i, q);
                let d = path.nearest_on(i, q, 0.0).dist;
                assert!(lb <= d + 1e-12, "element {i} at {q:?}: {lb} > {d}");
                // A line's bound is its distance.
                if matches!(path.elements[i].geo, Geo::Line(_)) {
                    assert!((d - lb).abs() < 1e-9, "line {i}: {lb} vs {d}");
                    lines += 1;
                } else if (d - lb).abs() < 1e-9 {
                    tight += 1;
                }
                // From a point moved by up to 2 mm: at most the move less.
                let p2 = [0, 1, 2].map(|a| q[a] + (2.0 * rnd() - 1.0) * 1.2);
                let moved = d3(q, p2);
                assert!(
                    lb - moved <= path.nearest_on(i, p2, 0.0).dist + 1e-12,
                    "element {i}: {q:?} → {p2:?}"
                );
            }
            // At a circle's centre the band is the radius away.
            if let Geo::Arc(ref arc) = path.elements[i].geo {
                let c = arc.0.c;
                let lb = path.lower_bound(i, c);
                assert!(lb <= path.nearest_on(i, c, 0.0).dist + 1e-12, "{i}");
            }
        }
        // Arcs often touch too (off their sector the band is nearer than
        // the ends): 1,355 of the arcs' 3,200 points here.
        assert_eq!(lines, 800);
        assert!(tight > 1000, "{tight} of 3200");
    }

    /// Every point of lines, short and long arcs (both directions), a full
    /// circle and helices lies inside the element's bounding sphere, and
    /// the sphere is not needlessly large (it touches the element).
    #[test]
    fn bounding_spheres_contain_their_elements() {
        let path = mixed_path();
        assert_eq!(path.elements.len(), 10);
        for (i, e) in path.elements.iter().enumerate() {
            let (m, rad) = e.bound();
            let mut far: f64 = 0.0;
            for j in 0..=2000 {
                let a = j as f64 / 2000.0;
                let pt = match e.geo {
                    Geo::Line(LineGeo { p0, d, .. }) => {
                        [p0[0] + a * d[0], p0[1] + a * d[1], p0[2] + a * d[2]]
                    }
                    Geo::Arc(ref arc) => {
                        let ArcGeo {
                            c,
                            r,
                            sc0: (s0, c0),
                            sweep,
                            axes: (u, v, n),
                            n0,
                            dn,
                            ..
                        } = arc.0;
                        let th = s0.atan2(c0) + a * sweep;
                        let mut pt = [0.0; 3];
                        pt[u] = c[u] + r * th.cos();
                        pt[v] = c[v] + r * th.sin();
                        pt[n] = n0 + a * dn;
                        pt
                    }
                };
                far = far.max(d3(pt, m));
            }
            assert!(far <= rad, "element {i}: {far} > {rad}");
            // Tight: within the helix's half rise (0 when planar) + 1 µm.
            let rise = match e.geo {
                Geo::Arc(ref arc) => 0.5 * arc.0.dn.abs(),
                _ => 0.0,
            };
            assert!(rad - far <= rise + 1e-6, "element {i}: {rad} vs {far}");
        }
    }

    /// The bound's early exit gives the same nearest point as examining
    /// every element: on the built-in examples the tracked distance equals
    /// the global minimum over all elements at every sample.
    #[test]
    fn tracker_equals_exhaustive_search_on_examples() {
        for text in [
            crate::toolpath::example::arc_example(),
            crate::toolpath::example::line_example(),
        ] {
            let p = parse(&text).unwrap();
            let s = crate::toolpath::simulate_program(&p, &crate::toolpath::SimConfig::default())
                .unwrap();
            let path = Path::new(&p.segments);
            for k in 0..s.t.len() {
                let q = [s.sim[0][k], s.sim[1][k], s.sim[2][k]];
                let all = (0..path.elements.len())
                    .map(|i| path.nearest_on(i, q, 0.0).dist)
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    (s.error[k] - all).abs() < 1e-12,
                    "k {k}: {} vs {all}",
                    s.error[k]
                );
            }
        }
    }
}
