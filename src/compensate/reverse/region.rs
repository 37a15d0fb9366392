//! Regions of a program for the reverse compensation: the runs of cutting
//! moves between rapids and fixed segments, judged one by one; and their
//! chunks, the parts of a long region whose best rounds are kept apart.
//!
//! A rapid ends in an exact stop (see [`crate::toolpath::simulate()`]), so
//! what happens before it does not reach the samples after it; a fixed
//! segment (subprogram body, canned-cycle expansion, Fanuc corner) cannot
//! move, so its joints are pinned. A region's error is the largest contour
//! error of the samples nearest to its segments — the same samples the
//! program's maximum error is taken over, so when no region's error rises
//! the program's maximum cannot rise either.
//!
//! What may move (the writer edits only blocks that carry exactly one
//! segment, and never a fixed one; with a line range, only moves on its
//! lines, [`super::lines`]):
//! - an arc's radius, unless it touches a fixed segment (a connecting
//!   line before a fixed block would change the modes it runs in);
//! - the vertex between two consecutive lines of one region.
//!
//! Units: mm.

use crate::nc::program::{Motion, Program, Segment};
use crate::toolpath::SegmentStats;

/// The regions of a program.
#[derive(Debug, Clone, Default)]
pub struct Regions {
    /// Region of each segment (`None`: a rapid, a dwell or a fixed segment).
    pub of: Vec<Option<usize>>,
    /// Segment indices of each region.
    pub members: Vec<Vec<usize>>,
    /// A region has something that may move.
    pub movable: Vec<bool>,
    /// The segment's block can be rewritten (exactly one segment, not fixed).
    pub editable: Vec<bool>,
    /// An arc whose radius may change.
    pub arc_free: Vec<bool>,
    /// Line–line joints `(i, k)` whose vertex may move.
    pub line_joints: Vec<(usize, usize)>,
}

/// Splits `program` into regions (see the module header).
pub fn regions(program: &Program) -> Regions {
    regions_in(program, &|_| true)
}

/// Splits `program` into regions of the moves on the source lines for
/// which `inside` holds; a move on another line is pinned as a fixed one
/// ([`super::lines`]).
pub fn regions_in(program: &Program, inside: &dyn Fn(usize) -> bool) -> Regions {
    let segs = &program.segments;
    let n = segs.len();
    let mut count = vec![0usize; program.blocks.len()];
    for s in segs {
        if let Some(c) = s.block.and_then(|b| count.get_mut(b)) {
            *c += 1;
        }
    }
    let editable: Vec<bool> = segs
        .iter()
        .map(|s| !s.fixed && s.block.is_some_and(|b| count.get(b) == Some(&1)) && inside(s.line))
        .collect();
    let mut rg = Regions {
        of: vec![None; n],
        editable,
        arc_free: vec![false; n],
        ..Regions::default()
    };
    let moves: Vec<usize> = (0..n)
        .filter(|&i| !matches!(segs[i].motion, Motion::Dwell { .. }))
        .collect();
    let mut cur: Option<usize> = None;
    for &i in &moves {
        let s = &segs[i];
        if !s.is_cutting() || s.fixed || !rg.editable[i] {
            cur = None;
            continue;
        }
        let r = *cur.get_or_insert_with(|| {
            rg.members.push(Vec::new());
            rg.members.len() - 1
        });
        rg.of[i] = Some(r);
        rg.members[r].push(i);
    }
    for (w, &i) in moves.iter().enumerate() {
        let prev = w.checked_sub(1).map(|p| moves[p]);
        let next = moves.get(w + 1).copied();
        let pinned = |j: Option<usize>| j.is_some_and(|j| segs[j].fixed || !rg.editable[j]);
        if matches!(segs[i].motion, Motion::Arc(_)) && rg.of[i].is_some() {
            rg.arc_free[i] = !pinned(prev) && !pinned(next);
        }
        if let Some(k) = next {
            let lines = matches!(segs[i].motion, Motion::Linear)
                && matches!(segs[k].motion, Motion::Linear);
            if lines && rg.of[i].is_some() && rg.of[i] == rg.of[k] {
                rg.line_joints.push((i, k));
            }
        }
    }
    rg.movable = rg
        .members
        .iter()
        .map(|m| m.iter().any(|&i| rg.arc_free[i]))
        .collect();
    for &(i, _) in &rg.line_joints {
        if let Some(r) = rg.of[i] {
            rg.movable[r] = true;
        }
    }
    rg
}

/// The maximum error of each region from a simulation's per-segment
/// statistics, mm.
pub fn region_errors(rg: &Regions, stats: &[SegmentStats]) -> Vec<f64> {
    let mut e = vec![0.0f64; rg.members.len()];
    for st in stats {
        if let Some(Some(r)) = rg.of.get(st.segment) {
            e[*r] = e[*r].max(st.max_error_um * 1e-3);
        }
    }
    e
}

/// The maximum error of each segment from a simulation's per-segment
/// statistics (`n` segments), mm.
pub fn segment_errors(n: usize, stats: &[SegmentStats]) -> Vec<f64> {
    let mut e = vec![0.0f64; n];
    for st in stats {
        if let Some(x) = e.get_mut(st.segment) {
            *x = x.max(st.max_error_um * 1e-3);
        }
    }
    e
}

/// Kinds of segment a region holds, for its note: (arcs, lines).
pub fn kinds(rg: &Regions, r: usize, segs: &[Segment]) -> (usize, usize) {
    let arcs = rg.members[r]
        .iter()
        .filter(|&&i| matches!(segs[i].motion, Motion::Arc(_)))
        .count();
    (arcs, rg.members[r].len() - arcs)
}

/// Parts of the regions that keep their own best round
/// ([`super::rounds`]): a long region (a raster without rapids is one)
/// is cut at its joints into runs of at least `span` seconds of nominal
/// motion, so that a part the rounds improved keeps its round while
/// another part keeps another.
#[derive(Debug, Clone, Default)]
pub struct Chunks {
    /// Segment indices of each chunk: consecutive members of one region.
    pub members: Vec<Vec<usize>>,
    /// Region of each chunk.
    pub region: Vec<usize>,
    /// Chunk of each segment (`None` where the region is).
    pub of: Vec<Option<usize>>,
}

/// Cuts every region of `rg` into [`Chunks`] of at least `span` s of
/// nominal motion (the last of a region may be shorter) at feeds ×
/// `feed_override`.
pub fn chunks(rg: &Regions, segs: &[Segment], span: f64, feed_override: f64) -> Chunks {
    let mut c = Chunks {
        of: vec![None; segs.len()],
        ..Chunks::default()
    };
    for (r, m) in rg.members.iter().enumerate() {
        let mut time = f64::INFINITY;
        for &i in m {
            if time >= span {
                c.members.push(Vec::new());
                c.region.push(r);
                time = 0.0;
            }
            let k = c.members.len() - 1;
            c.members[k].push(i);
            c.of[i] = Some(k);
            time += segs[i].length() / (segs[i].feed * feed_override / 60.0);
        }
    }
    c
}

/// A rapid lies between regions `r` and `q` (in either order): from the
/// last move of the earlier one to the first of the later one.
pub fn rapid_between(orig: &[Segment], rg: &Regions, r: usize, q: usize) -> bool {
    let (a, b) = (r.min(q), r.max(q));
    let (Some(&from), Some(&to)) = (
        rg.members.get(a).and_then(|m| m.last()),
        rg.members.get(b).and_then(|m| m.first()),
    ) else {
        return false;
    };
    orig.get(from..to)
        .is_some_and(|s| s.iter().any(|s| matches!(s.motion, Motion::Rapid)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::program::parse;

    #[test]
    fn rapid_between_regions() {
        // Regions: 0 = lines 2–3; 1 = lines 5–7, after a rapid (a dwell
        // does not part regions); 2 = line 10, after a dwell and a rapid.
        let p = parse(
            "G0 X0 Y0\nG1 X5 F600\nY3\nG0 X7\nG1 Y6\nG4 P0.2\nG3 X4 Y9 R3\nG4 P0.1\nG0 Z2\nG1 Z-1\nM30",
        )
        .unwrap();
        let rg = regions_in(&p, &|_| true);
        assert_eq!(rg.members, vec![vec![1, 2], vec![4, 6], vec![9]]);
        let o = &p.segments;
        assert!(rapid_between(o, &rg, 0, 1));
        assert!(rapid_between(o, &rg, 1, 0), "either order");
        assert!(rapid_between(o, &rg, 1, 2));
        assert!(rapid_between(o, &rg, 0, 2), "one rapid anywhere between");
        assert!(!rapid_between(o, &rg, 1, 1), "none within a region");
        assert!(!rapid_between(o, &rg, 0, 9), "no such region");
        // Two regions parted by a fixed move (a subprogram body) and a
        // dwell, no rapid: not stopped between.
        let p = parse("G0 X0 Y0\nG1 X5 F600\nM98 P100\nG4 P0.1\nG1 X9 Y2\nM30\nO100\nG1 X6\nM99")
            .unwrap();
        let rg = regions_in(&p, &|_| true);
        assert_eq!(rg.members.len(), 2, "{:?}", rg.members);
        assert!(!rapid_between(&p.segments, &rg, 0, 1));
        assert!(!rapid_between(&p.segments, &rg, 1, 0));
    }

    #[test]
    fn line_joints_and_region_errors() {
        // Segments: 0 rapid, 1 rapid (rapid–rapid: no joint), 2–3 lines
        // (a joint), 4 arc (line–arc and arc–line: none), 5 line, 6 rapid
        // (line–rapid: none), 7 line, 8 line in another region after the
        // rapid (a joint of their own), 9 rapid.
        let p = parse(
            "G0 X1 Y2\nX3\nG1 X7 F600\nY5\nG2 X10 Y8 R3\nG1 X13\nG0 Z4\nG1 Z-1\nX15 Y9\nG0 Z5\nM30",
        )
        .unwrap();
        let rg = regions_in(&p, &|_| true);
        assert_eq!(rg.members, vec![vec![2, 3, 4, 5], vec![7, 8]]);
        assert_eq!(rg.line_joints, vec![(2, 3), (7, 8)]);
        assert_eq!(rg.movable, vec![true, true]);
        assert_eq!(kinds(&rg, 0, &p.segments), (1, 3), "one arc, three lines");
        assert_eq!(kinds(&rg, 1, &p.segments), (0, 2));
        // The errors, mm, of a simulation's statistics (in µm).
        let cfg = crate::toolpath::SimConfig {
            dt: 0.002,
            ..crate::toolpath::SimConfig::default()
        };
        let sim = crate::toolpath::simulate(&p.segments, &p.segments, &cfg).unwrap();
        let e = region_errors(&rg, &sim.segments);
        let by_seg = segment_errors(p.segments.len(), &sim.segments);
        for (r, m) in rg.members.iter().enumerate() {
            let want = m.iter().map(|&i| by_seg[i]).fold(0.0, f64::max);
            assert!(want > 1e-3, "region {r}: {want} mm");
            assert_eq!(e[r], want, "region {r}");
        }
        let st = &sim.segments[3];
        assert_eq!(by_seg[st.segment], st.max_error_um * 1e-3);
    }

    #[test]
    fn chunks_cut_a_region_by_nominal_time() {
        // Lines of 10, 2, 18, 1 and 4 mm at F600 with a feed override of
        // 2: 0.5, 0.1, 0.9, 0.05 and 0.2 s. Cut at 0.55 s: a chunk closes
        // once it holds 0.55 s or more (0.6 s, 0.9 s), the last is shorter.
        let p = parse("G0 X0 Y0\nG1 X10 F600\nX12\nX30\nX31\nX35\nG0 Z3\nM30").unwrap();
        let rg = regions_in(&p, &|_| true);
        let c = chunks(&rg, &p.segments, 0.55, 2.0);
        assert_eq!(c.members, vec![vec![1, 2], vec![3], vec![4, 5]]);
        assert_eq!(c.region, vec![0, 0, 0]);
        assert_eq!(c.of[0], None);
        assert_eq!(c.of[3], Some(1));
        assert_eq!(c.of[6], None);
        // At the programmed feed (override 1) the times double: 1, 0.2,
        // 1.8, 0.1 and 0.4 s; cut at 1.1 s.
        let c = chunks(&rg, &p.segments, 1.1, 1.0);
        assert_eq!(c.members, vec![vec![1, 2], vec![3], vec![4, 5]]);
    }
}
