//! A planar NURBS curve as LinuxCNC defines it, and its subdivision into
//! chords for the simulation: the curve of the G5 cubic (order 4 on four
//! points of weight 1: the cubic Bézier), of the G5.1 quadratic B-spline
//! and of the G5.2/G5.3 NURBS block ([`super::spline`] reads the blocks).
//!
//! Source: the LinuxCNC G-code manual (2.9, §11.5.8 "G5.1 Quadratic
//! Spline", §11.5.9 "G5.2 G5.3 NURBS Block"), and for what the manual does
//! not say, LinuxCNC's interpreter as `rs274` runs it (2.9.0~pre1,
//! `nurbs_additional_functions.cc`): a curve of order `k` (degree `k − 1`)
//! over `n + 1` control points `(x, y)` with weights `w > 0`, on the
//! clamped uniform knot vector `0 (k times), 1, 2, …, n − k + 1,
//! n − k + 2 (k times)`; the parameter runs over `[0, n − k + 2]`, the
//! curve starts at the first control point and ends at the last, tangent
//! to the control polygon there. A point is the rational sum
//! `Σ N_i,k(u) w_i P_i / Σ N_i,k(u) w_i`, evaluated here by de Boor's
//! algorithm on the homogeneous points `(w x, w y, w)` (the same curve;
//! LinuxCNC sums the Cox–de Boor basis).
//!
//! Subdivision: each knot span is bisected until every chord stays within
//! [`CHORD_TOLERANCE`] of the curve: a piece is accepted when its points
//! at the quarter, half and three-quarter parameters lie within
//! [`ACCEPT`] × the tolerance of its chord. For a quadratic polynomial
//! piece (G5.1) the half-parameter point is exactly the farthest; for a
//! cubic one the farthest is at most 1.094 × the farthest of the three
//! (the deviation `t (1 − t)(a + b t)`, worst case over a, b), so the
//! margin covers it; for rational and higher-order pieces, which bisection
//! makes nearly quadratic, the tests measure the real deviation densely
//! (at most the tolerance). The vertices lie on the curve. LinuxCNC's own motion path is a different approximation (biarcs
//! through `4 (n + 1)` curve points, `emccanon.cc`), so the simulated
//! path is the curve within the tolerance, not LinuxCNC's biarcs.
//!
//! Units: mm (the weights are pure numbers).

/// Largest distance, mm, of a chord from the curve it stands for (1 µm:
/// the least input increment of a metric control, IS-B, so a finer chord
/// could not be written back as NC either; well below the µm-level contour
/// errors the simulation reports).
pub const CHORD_TOLERANCE: f64 = 1e-3;

/// Most chords one curve may become (a curve this long at
/// [`CHORD_TOLERANCE`] is a typo in its numbers).
pub const MAX_CHORDS: usize = 100_000;

/// The share of [`CHORD_TOLERANCE`] a piece's checked points may deviate
/// (see the module header).
pub const ACCEPT: f64 = 0.8;

/// Deepest bisection of one knot span (2⁴⁰ pieces: never reached before
/// [`MAX_CHORDS`]).
const MAX_DEPTH: u32 = 40;

/// A control point: `x`, `y` in mm and its weight `w` (> 0).
pub type ControlPoint = [f64; 3];

/// A NURBS curve of `order` over `points`, on LinuxCNC's clamped uniform
/// knot vector.
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    points: Vec<ControlPoint>,
    order: usize,
    knots: Vec<f64>,
}

/// Why a curve cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NurbsError {
    /// Fewer control points than the order.
    #[error("{points} control points for a curve of order {order}; expected at least {order}")]
    TooFewPoints {
        /// Control points given.
        points: usize,
        /// The order.
        order: usize,
    },
    /// An order below 2.
    #[error("order {0}; expected 2 or more")]
    Order(usize),
    /// A weight that is not a positive finite number, or a point that is
    /// not finite.
    #[error("control point {0} has a weight that is not above 0 or a coordinate that is not a finite number")]
    Point(usize),
    /// The curve needs more than [`MAX_CHORDS`] chords.
    #[error("the curve needs more than {MAX_CHORDS} chords to stay within {CHORD_TOLERANCE} mm of it; check its numbers and units")]
    TooLong,
}

impl Nurbs {
    /// The curve of `order` (`k`; 3 for a quadratic) over `points`.
    ///
    /// # Errors
    /// An order below 2, fewer points than the order, a weight that is
    /// not above 0, a coordinate that is not finite.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::nc::nurbs::Nurbs;
    /// // a quadratic B-spline (G5.1): from (0,0) with control point (5,5) to (10,0)
    /// let c = Nurbs::new(vec![[0.0, 0.0, 1.0], [5.0, 5.0, 1.0], [10.0, 0.0, 1.0]], 3).unwrap();
    /// let [x, y] = c.point(0.5);
    /// assert!((x - 5.0).abs() < 1e-12 && (y - 2.5).abs() < 1e-12);
    /// ```
    pub fn new(points: Vec<ControlPoint>, order: usize) -> Result<Self, NurbsError> {
        if order < 2 {
            return Err(NurbsError::Order(order));
        }
        if points.len() < order {
            return Err(NurbsError::TooFewPoints {
                points: points.len(),
                order,
            });
        }
        if let Some(i) = points
            .iter()
            .position(|p| !(p[2] > 0.0 && p.iter().all(|v| v.is_finite())))
        {
            return Err(NurbsError::Point(i));
        }
        let knots = knot_vector(points.len(), order);
        Ok(Self {
            points,
            order,
            knots,
        })
    }

    /// The largest parameter, `n − k + 2` (the number of knot spans).
    pub fn u_max(&self) -> f64 {
        (self.points.len() + 1 - self.order) as f64
    }

    /// The curve's point at parameter `u` ∈ [0, [`Self::u_max`]] (clamped
    /// to it), mm.
    pub fn point(&self, u: f64) -> [f64; 2] {
        let p = self.order - 1;
        let u = u.clamp(0.0, self.u_max());
        // the span: the last non-empty one for u at the end
        let spans = self.points.len() - p;
        let j = p + ((u.floor() as usize).min(spans - 1));
        let mut d: Vec<[f64; 3]> = (0..=p)
            .map(|i| {
                let [x, y, w] = self.points[j - p + i];
                [x * w, y * w, w]
            })
            .collect();
        for r in 1..=p {
            for i in (r..=p).rev() {
                let lo = self.knots[i + j - p];
                let hi = self.knots[i + 1 + j - r];
                let a = (u - lo) / (hi - lo);
                let prev = d[i - 1];
                for (v, q) in d[i].iter_mut().zip(prev) {
                    *v = (1.0 - a) * q + a * *v;
                }
            }
        }
        let [x, y, w] = d[p];
        [x / w, y / w]
    }

    /// The chords' end points in order, from the first chord's end to the
    /// last control point (the start, the first control point, left out),
    /// each chord within [`CHORD_TOLERANCE`] of the curve (see the module
    /// header).
    ///
    /// # Errors
    /// [`NurbsError::TooLong`]: more than [`MAX_CHORDS`] chords.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::nc::nurbs::{Nurbs, CHORD_TOLERANCE};
    /// let c = Nurbs::new(vec![[0.0, 0.0, 1.0], [5.0, 5.0, 1.0], [10.0, 0.0, 1.0]], 3).unwrap();
    /// let v = c.chords().unwrap();
    /// assert_eq!(*v.last().unwrap(), [10.0, 0.0]);
    /// // the parabola's second difference is (0, -10): a chord of n equal
    /// // ones deviates by |P0 - 2 P1 + P2| / (4 n²)
    /// let n = v.len() as f64;
    /// assert!(10.0 / (4.0 * n * n) <= CHORD_TOLERANCE);
    /// ```
    pub fn chords(&self) -> Result<Vec<[f64; 2]>, NurbsError> {
        let mut out = Vec::new();
        let spans = self.u_max() as usize;
        for s in 0..spans {
            let (a, b) = (s as f64, (s + 1) as f64);
            let (pa, pb) = (self.point(a), self.point(b));
            self.bisect(a, b, pa, pb, 0, &mut out)?;
        }
        let [x, y, _] = self.points[self.points.len() - 1];
        if let Some(last) = out.last_mut() {
            *last = [x, y];
        }
        Ok(out)
    }

    /// Appends the chords of the curve over `[a, b]` (from `pa` to `pb`).
    fn bisect(
        &self,
        a: f64,
        b: f64,
        pa: [f64; 2],
        pb: [f64; 2],
        depth: u32,
        out: &mut Vec<[f64; 2]>,
    ) -> Result<(), NurbsError> {
        let m = 0.5 * (a + b);
        let pm = self.point(m);
        let off = [0.25, 0.75]
            .iter()
            .map(|f| distance_to_chord(self.point(a + f * (b - a)), pa, pb))
            .fold(distance_to_chord(pm, pa, pb), f64::max);
        // (a NaN never passes `<=`: it is split until the depth runs out)
        if off <= ACCEPT * CHORD_TOLERANCE || depth >= MAX_DEPTH {
            if out.len() >= MAX_CHORDS {
                return Err(NurbsError::TooLong);
            }
            out.push(pb);
            return Ok(());
        }
        self.bisect(a, m, pa, pm, depth + 1, out)?;
        self.bisect(m, b, pm, pb, depth + 1, out)
    }
}

/// LinuxCNC's clamped uniform knot vector for `count` control points and
/// `order` (`knot_vector_creator`): `order` zeros, `1 … count − order`,
/// then `count − order + 1` `order` times.
pub fn knot_vector(count: usize, order: usize) -> Vec<f64> {
    let n = count - 1;
    (0..=n + order)
        .map(|i| {
            if i < order {
                0.0
            } else if i <= n {
                (i + 1 - order) as f64
            } else {
                (n + 2 - order) as f64
            }
        })
        .collect()
}

/// Distance of `p` from the chord `a`–`b` (the segment, not its line).
pub fn distance_to_chord(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest distance of the curve from its chords, sampled at
    /// 5,000 points per knot span, each measured to the nearest chord
    /// (looked for first around the last nearest one: curve and chords
    /// advance together).
    fn worst(c: &Nurbs) -> f64 {
        let v = c.chords().unwrap();
        let mut poly = vec![[c.points[0][0], c.points[0][1]]];
        poly.extend(v);
        let n = 5_000 * c.u_max() as usize;
        let mut j = 0usize;
        (0..=n)
            .map(|i| {
                let p = c.point(c.u_max() * i as f64 / n as f64);
                let near = |r: std::ops::Range<usize>| {
                    r.map(|k| (k, distance_to_chord(p, poly[k], poly[k + 1])))
                        .fold((j, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a })
                };
                let (mut k, mut d) = near(j.saturating_sub(2)..(j + 8).min(poly.len() - 1));
                if d > CHORD_TOLERANCE {
                    // the curve came back near an earlier chord: all of them
                    (k, d) = near(0..poly.len() - 1);
                }
                j = k;
                d
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn the_knot_vector_is_linuxcncs() {
        assert_eq!(knot_vector(3, 3), vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
        assert_eq!(
            knot_vector(5, 3),
            vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0]
        );
        assert_eq!(
            knot_vector(5, 4),
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0]
        );
    }

    #[test]
    fn a_quadratic_b_spline_is_the_bezier_parabola_with_its_end_tangents() {
        let (p0, p1, p2) = ([1.0, 2.0], [4.0, 7.0], [9.0, -3.0]);
        let c = Nurbs::new(
            vec![
                [p0[0], p0[1], 1.0],
                [p1[0], p1[1], 1.0],
                [p2[0], p2[1], 1.0],
            ],
            3,
        )
        .unwrap();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let q = c.point(t);
            for k in 0..2 {
                let b = (1.0 - t) * (1.0 - t) * p0[k] + 2.0 * t * (1.0 - t) * p1[k] + t * t * p2[k];
                assert!((q[k] - b).abs() < 1e-12, "{t} {q:?}");
            }
        }
        // end tangents along P1 − P0 and P2 − P1 (derivative 2 (P1 − P0))
        let h = 1e-6;
        let (a, b) = (c.point(0.0), c.point(h));
        assert!(((b[0] - a[0]) / h - 2.0 * (p1[0] - p0[0])).abs() < 1e-4);
        assert!(((b[1] - a[1]) / h - 2.0 * (p1[1] - p0[1])).abs() < 1e-4);
        let (a, b) = (c.point(1.0 - h), c.point(1.0));
        assert!(((b[0] - a[0]) / h - 2.0 * (p2[0] - p1[0])).abs() < 1e-4);
        assert!(((b[1] - a[1]) / h - 2.0 * (p2[1] - p1[1])).abs() < 1e-4);
        assert_eq!(c.point(0.0), p0);
        assert_eq!(c.point(1.0), p2);
        assert!(worst(&c) <= CHORD_TOLERANCE);
    }

    #[test]
    fn a_rational_quadratic_reproduces_an_exact_circle() {
        // a quarter circle of radius 25 about (3, −4): one span of order 3
        // over (r, 0) weight 1, (r, r) weight √2/2, (0, r) weight 1 (a
        // G5.2 L3 block of three points) is exactly the arc
        let (r, cx, cy) = (25.0, 3.0, -4.0);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let c = Nurbs::new(
            vec![[cx + r, cy, 1.0], [cx + r, cy + r, s], [cx, cy + r, 1.0]],
            3,
        )
        .unwrap();
        for i in 0..=100 {
            let [x, y] = c.point(i as f64 / 100.0);
            assert!(((x - cx).hypot(y - cy) - r).abs() < 1e-12, "{i}");
        }
        let v = c.chords().unwrap();
        // every chord's sagitta within the tolerance: a chord of the
        // circle with sagitta ≤ t spans at most 2 acos(1 − t/r)
        let mut at = [cx + r, cy];
        for p in &v {
            let chord = (p[0] - at[0]).hypot(p[1] - at[1]);
            let sagitta = r - (r * r - chord * chord / 4.0).sqrt();
            assert!(sagitta <= CHORD_TOLERANCE * (1.0 + 1e-9), "{sagitta}");
            at = *p;
        }
        // and not needlessly many: at most twice the fewest equal chords
        let fewest =
            (std::f64::consts::FRAC_PI_2 / (2.0 * (1.0 - CHORD_TOLERANCE / r).acos())).ceil();
        assert!(v.len() as f64 <= 2.0 * fewest, "{} {fewest}", v.len());
    }

    #[test]
    fn chords_stay_within_the_tolerance_on_varied_curves() {
        // deterministic pseudo-random curves: orders 3–5, weights 0.2–5
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..60 {
            let order = 3 + case % 3;
            let count = order + (case % 4);
            let scale = [0.5, 5.0, 50.0][case % 3];
            let pts: Vec<ControlPoint> = (0..count)
                .map(|_| {
                    [
                        scale * (rnd() - 0.5),
                        scale * (rnd() - 0.5),
                        if case % 2 == 0 {
                            1.0
                        } else {
                            0.2 + 4.8 * rnd()
                        },
                    ]
                })
                .collect();
            let c = Nurbs::new(pts, order).unwrap();
            let w = worst(&c);
            assert!(w <= CHORD_TOLERANCE, "case {case}: {w}");
        }
    }

    #[test]
    fn bad_curves_are_refused_by_name() {
        let p = [0.0, 0.0, 1.0];
        assert_eq!(
            Nurbs::new(vec![p, p], 3),
            Err(NurbsError::TooFewPoints {
                points: 2,
                order: 3
            })
        );
        assert_eq!(Nurbs::new(vec![p, p, p], 1), Err(NurbsError::Order(1)));
        assert_eq!(
            Nurbs::new(vec![p, [1.0, 1.0, 0.0], p], 3),
            Err(NurbsError::Point(1))
        );
        assert_eq!(
            Nurbs::new(vec![p, [f64::NAN, 1.0, 1.0], p], 3),
            Err(NurbsError::Point(1))
        );
        let huge = Nurbs::new(vec![p, [1e7, 1e7, 1.0], [2e7, 0.0, 1.0]], 3).unwrap();
        assert_eq!(huge.chords(), Err(NurbsError::TooLong));
        // w·x overflows: the curve's points are not numbers, so no chord is
        // ever accepted; the depth limit still ends the bisection
        let inf = Nurbs::new(vec![p, [1e300, 1e300, 1e10], [2e300, 0.0, 1.0]], 3).unwrap();
        assert_eq!(inf.chords(), Err(NurbsError::TooLong));
    }

    #[test]
    fn a_straight_curve_is_one_chord_per_span() {
        let c = Nurbs::new(vec![[0.0, 0.0, 1.0], [1.0, 1.0, 1.0], [2.0, 2.0, 1.0]], 3).unwrap();
        assert_eq!(c.chords().unwrap(), vec![[2.0, 2.0]]);
        let c = Nurbs::new(
            vec![
                [0.0, 0.0, 1.0],
                [1.0, 0.0, 2.0],
                [2.0, 0.0, 1.0],
                [3.0, 0.0, 1.0],
            ],
            3,
        )
        .unwrap();
        let v = c.chords().unwrap();
        assert_eq!((v.len(), v[1]), (2, [3.0, 0.0]));
        assert!(v[0][1] == 0.0 && v[0][0] > 0.0 && v[0][0] < 3.0);
    }
}
