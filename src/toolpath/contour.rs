//! Contour error (qiu §4-2): the distance from the simulated point to the
//! commanded path — not to the commanded point at the same instant —
//! computed exactly for lines (clamped projection) and arcs (radial
//! distance inside the swept sector, else the nearer end point; for a
//! helical arc the normal offset is taken at the point's angle, which is
//! exact for planar arcs and a close approximation for helices).
//!
//! The search is local along the path: it keeps the arc-length position of
//! the last nearest point and examines the path elements within
//! `2·(last error + step) + 0.05 mm` of it (at least the neighbours), so a
//! path that comes back near itself far along its length is not mistaken
//! for the local path, and the cost per sample stays a few elements. When
//! two elements are equally near (a circle programmed twice) the one closer
//! along the path to the last nearest point wins, so the search moves on.
//!
//! Units: mm.

use crate::nc::program::{Motion, Segment};

/// One element of the reference path.
#[derive(Debug, Clone, Copy)]
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

#[derive(Debug, Clone, Copy)]
enum Geo {
    Line {
        p0: [f64; 3],
        d: [f64; 3],
        l2: f64,
    },
    Arc {
        c: [f64; 3],
        r: f64,
        sc0: (f64, f64),
        sweep: f64,
        axes: (usize, usize, usize),
        n0: f64,
        dn: f64,
        p0: [f64; 3],
        p1: [f64; 3],
    },
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
}

fn d3(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

impl Path {
    /// The path of `segments`.
    pub fn new(segments: &[Segment]) -> Self {
        let mut elements = Vec::new();
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
                    Geo::Arc {
                        c: a.center,
                        r: a.radius,
                        sc0: (p0[v] - a.center[v]).atan2(p0[u] - a.center[u]).sin_cos(),
                        sweep: a.sweep,
                        axes: (u, v, n),
                        n0: p0[n],
                        dn: p1[n] - p0[n],
                        p0,
                        p1,
                    }
                }
                Motion::Dwell { .. } => continue,
                _ => {
                    let d = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
                    Geo::Line {
                        p0,
                        d,
                        l2: d[0] * d[0] + d[1] * d[1] + d[2] * d[2],
                    }
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
        Self { elements }
    }

    /// Exact nearest point on element `i` to `q`. `hint` is the arc length
    /// the caller expects; it only resolves where on a full circle a point
    /// just behind the start lies (at its start when the hint is in the
    /// circle's first quarter and the point in its last).
    #[inline]
    pub fn nearest_on(&self, i: usize, q: [f64; 3], hint: f64) -> Nearest {
        let e = &self.elements[i];
        match e.geo {
            Geo::Line { p0, d, l2 } => {
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
            Geo::Arc {
                c,
                r,
                sc0,
                sweep,
                axes: (u, v, n),
                n0,
                dn,
                p0,
                p1,
            } => {
                let (x, y) = (q[u] - c[u], q[v] - c[v]);
                let rho = x.hypot(y);
                // Angle of q from the start, in the sweep's direction.
                let (s0, c0) = sc0;
                let mut phi = (c0 * y - s0 * x).atan2(c0 * x + s0 * y);
                if sweep < 0.0 {
                    phi = -phi;
                }
                if phi < 0.0 {
                    phi += std::f64::consts::TAU;
                }
                let mut f = phi / sweep.abs();
                if sweep.abs() >= std::f64::consts::TAU - 1e-9
                    && f > 0.75
                    && hint < e.s0 + 0.25 * e.len
                {
                    f = 0.0;
                }
                if f <= 1.0 && rho > 0.0 {
                    let mut pt = [0.0; 3];
                    pt[u] = c[u] + r * x / rho;
                    pt[v] = c[v] + r * y / rho;
                    pt[n] = n0 + dn * (phi / sweep.abs()).min(1.0);
                    Nearest {
                        element: i,
                        dist: d3(q, pt),
                        point: pt,
                        normal: r - rho,
                        s: e.s0 + f * e.len,
                    }
                } else {
                    let (da, db) = (d3(q, p0), d3(q, p1));
                    if da <= db {
                        Nearest {
                            element: i,
                            dist: da,
                            point: p0,
                            normal: f64::NAN,
                            s: e.s0,
                        }
                    } else {
                        Nearest {
                            element: i,
                            dist: db,
                            point: p1,
                            normal: f64::NAN,
                            s: e.s0 + e.len,
                        }
                    }
                }
            }
        }
    }
}

/// A local nearest-point search that follows the tool along the path.
#[derive(Debug, Clone)]
pub struct Tracker {
    cur: usize,
    s: f64,
    err: f64,
    last: Option<[f64; 3]>,
}

impl Default for Tracker {
    fn default() -> Self {
        Self {
            cur: 0,
            s: 0.0,
            err: 0.0,
            last: None,
        }
    }
}

impl Tracker {
    /// Nearer, or as near (within 1 nm, e.g. a path that repeats itself)
    /// and closer along the path to the last nearest point.
    #[inline]
    fn better(&self, cand: &Nearest, best: &Nearest) -> bool {
        cand.dist < best.dist - 1e-9
            || (cand.dist <= best.dist + 1e-9 && (cand.s - self.s).abs() < (best.s - self.s).abs())
    }

    /// The nearest point of `path` to `q`, searched around the last one.
    /// `None` for an empty path.
    pub fn nearest(&mut self, path: &Path, q: [f64; 3]) -> Option<Nearest> {
        let n = path.elements.len();
        if n == 0 {
            return None;
        }
        let step = self.last.map_or(0.0, |l| d3(l, q));
        let w = 2.0 * (self.err + step) + 0.05;
        let (lo, hi) = (self.s - w, self.s + w);
        let cur = self.cur.min(n - 1);
        let mut best = path.nearest_on(cur, q, self.s);
        let mut i = cur;
        while i > 0 {
            i -= 1;
            let e = &path.elements[i];
            let cand = path.nearest_on(i, q, self.s);
            if self.better(&cand, &best) {
                best = cand;
            }
            if e.s0 < lo {
                break;
            }
        }
        let mut i = cur + 1;
        while i < n {
            let e = &path.elements[i];
            let cand = path.nearest_on(i, q, self.s);
            if self.better(&cand, &best) {
                best = cand;
            }
            if e.s0 + e.len > hi {
                break;
            }
            i += 1;
        }
        self.cur = best.element;
        self.s = best.s;
        self.err = best.dist;
        self.last = Some(q);
        Some(best)
    }
}
