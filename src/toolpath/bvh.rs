//! Bounding-volume hierarchy over the elements of a commanded path, for the
//! exact nearest-element query of the contour error (qiu §4-2 defines the
//! contour error as the distance to the commanded path; the nearest point
//! on the whole path, not on the part near the tool's progress).
//!
//! Axis-aligned boxes around the elements' bounding spheres, split at the
//! median of the longest axis down to leaves of at most [`LEAF`] elements.
//! A query visits only the nodes whose box is nearer than the best distance
//! found so far, nearer child first, so a query that starts from a good
//! guess (the tracker's local result) costs a few box tests.
//!
//! Units: mm.

/// Most elements in a leaf.
pub const LEAF: usize = 4;

#[derive(Debug, Clone, Copy)]
struct Node {
    lo: [f64; 3],
    hi: [f64; 3],
    /// Leaf: `start..start + count` into `order`; inner: `start` is the
    /// right child (the left child is the next node), `count == 0`.
    start: u32,
    count: u32,
}

/// The hierarchy: nodes in depth-first order and the element order.
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

fn sq_box_distance(q: [f64; 3], lo: [f64; 3], hi: [f64; 3]) -> f64 {
    let mut d2 = 0.0;
    for a in 0..3 {
        let v = if q[a] < lo[a] {
            lo[a] - q[a]
        } else if q[a] > hi[a] {
            q[a] - hi[a]
        } else {
            0.0
        };
        d2 += v * v;
    }
    d2
}

/// The number of nodes [`Bvh::from_fn`] makes for `n` elements (halves
/// split until at most [`LEAF`] are left), so that the nodes are
/// allocated once: 2 n / LEAF was too few for 2 M elements (1,048,575
/// nodes), and the push past it doubled the room (112 MB in wasm).
fn node_count(n: usize) -> usize {
    // The sizes at one depth take at most two values, m and m + 1: count
    // the nodes of each size level by level.
    let (mut sizes, mut total) = ([(n, 1usize), (n + 1, 0usize)], 0);
    while sizes.iter().any(|&(m, k)| k > 0 && m > 0) {
        let mut next = [(usize::MAX, 0usize), (0usize, 0usize)];
        for (m, k) in sizes {
            if k == 0 || m == 0 {
                continue;
            }
            total += k;
            if m <= LEAF {
                continue;
            }
            for half in [m / 2, m - m / 2] {
                let slot = if next[0].1 == 0 || next[0].0 == half {
                    0
                } else {
                    1
                };
                next[slot] = (half, next[slot].1 + k);
            }
        }
        sizes = next;
    }
    total
}

impl Bvh {
    /// The hierarchy over spheres `(centre, radius)`, one per element.
    pub fn new(spheres: &[([f64; 3], f64)]) -> Self {
        Self::from_fn(spheres.len(), |i| spheres[i].0, |i| spheres[i])
    }

    /// The hierarchy over `n` spheres, `sphere(i)` the `(centre, radius)`
    /// of element `i` and `centre(i)` its centre, for a caller that
    /// computes them rather than holds them (the path of a 2 M-segment
    /// program would hold 64 MB of them in wasm while the hierarchy is
    /// built); `centre` orders the elements at each split, so it should
    /// be cheap.
    pub fn from_fn(
        n: usize,
        centre: impl Fn(usize) -> [f64; 3],
        sphere: impl Fn(usize) -> ([f64; 3], f64),
    ) -> Self {
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(node_count(n)),
            order: (0..n as u32).collect(),
        };
        if n > 0 {
            bvh.build(&centre, &sphere, 0, n);
        }
        bvh
    }

    fn build(
        &mut self,
        centre: &impl Fn(usize) -> [f64; 3],
        sphere: &impl Fn(usize) -> ([f64; 3], f64),
        start: usize,
        end: usize,
    ) -> usize {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &i in &self.order[start..end] {
            let (c, r) = sphere(i as usize);
            for a in 0..3 {
                lo[a] = lo[a].min(c[a] - r);
                hi[a] = hi[a].max(c[a] + r);
            }
        }
        let me = self.nodes.len();
        self.nodes.push(Node {
            lo,
            hi,
            start: start as u32,
            count: (end - start) as u32,
        });
        if end - start <= LEAF {
            return me;
        }
        let axis = (0..3)
            .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
            .unwrap_or(0);
        let mid = (start + end) / 2;
        self.order[start..end].select_nth_unstable_by(mid - start, |&i, &j| {
            centre(i as usize)[axis].total_cmp(&centre(j as usize)[axis])
        });
        self.build(centre, sphere, start, mid);
        let right = self.build(centre, sphere, mid, end);
        self.nodes[me].start = right as u32;
        self.nodes[me].count = 0;
        me
    }

    /// Calls `visit(element)` for every element whose box is nearer to `q`
    /// than `bound()` (re-read after each visit, so the caller tightens it
    /// as it finds nearer elements). Nearer children are visited first.
    pub fn visit_near(
        &self,
        q: [f64; 3],
        mut bound: impl FnMut() -> f64,
        mut visit: impl FnMut(usize),
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack: [u32; 64] = [0; 64];
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let node = self.nodes[stack[top] as usize];
            let b = bound();
            if sq_box_distance(q, node.lo, node.hi) > b * b {
                continue;
            }
            if node.count > 0 {
                let s = node.start as usize;
                for &e in &self.order[s..s + node.count as usize] {
                    visit(e as usize);
                }
                continue;
            }
            let (l, r) = (stack[top] + 1, node.start);
            let dl = sq_box_distance(q, self.nodes[l as usize].lo, self.nodes[l as usize].hi);
            let dr = sq_box_distance(q, self.nodes[r as usize].lo, self.nodes[r as usize].hi);
            // Depth is at most log2(n / LEAF) + 1 (median splits): 64 slots
            // cover any path that fits in memory.
            let (first, second) = if dl <= dr { (l, r) } else { (r, l) };
            stack[top] = second;
            stack[top + 1] = first;
            top += 2;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn visits_every_sphere_within_the_bound_and_prunes_the_rest() {
        // Spheres on a 20 x 20 grid, 1 mm apart, radius 0.2 mm.
        let spheres: Vec<([f64; 3], f64)> = (0..400)
            .map(|i| ([(i % 20) as f64, (i / 20) as f64, 0.0], 0.2))
            .collect();
        let bvh = Bvh::new(&spheres);
        let q = [7.3, 11.6, 0.5];
        let bound = 1.5;
        let mut seen = Vec::new();
        bvh.visit_near(q, || bound, |e| seen.push(e));
        for (i, (c, r)) in spheres.iter().enumerate() {
            let d =
                ((q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2) + (q[2] - c[2]).powi(2)).sqrt() - r;
            if d < bound {
                assert!(seen.contains(&i), "sphere {i} at {d} mm was not visited");
            }
        }
        assert!(seen.len() < 60, "visited {} of 400", seen.len());
    }

    /// The nodes are allocated once: their count is the one the build
    /// makes, for every size up to 700, and for 1 M and 2 M elements the
    /// count of the same recursion written out in Python
    /// (`n ≤ 4: 1, else 1 + f(n // 2) + f(n − n // 2)`).
    #[test]
    fn node_count_is_the_count_built() {
        for n in 0..700 {
            let spheres: Vec<([f64; 3], f64)> = (0..n)
                .map(|i| ([(i * 7 % 13) as f64, (i % 5) as f64, i as f64], 0.1))
                .collect();
            let bvh = Bvh::new(&spheres);
            assert_eq!(bvh.nodes.len(), node_count(n), "{n}");
            assert_eq!(bvh.nodes.capacity(), bvh.nodes.len(), "{n}");
        }
        assert_eq!(node_count(1_000_000), 524_287);
        assert_eq!(node_count(1_996_001), 1_048_575);
    }

    #[test]
    fn empty_and_single() {
        let mut n = 0;
        Bvh::new(&[]).visit_near([0.0; 3], || 1.0, |_| n += 1);
        Bvh::new(&[([5.0, 0.0, 0.0], 1.0)]).visit_near([0.0; 3], || 10.0, |_| n += 1);
        assert_eq!(n, 1);
    }
}
