//! Built-in test paths resembling qiu Fig. 2 (the figure itself is not in
//! the text; its description is): a left–right symmetric contour
//! A → B → C → D → E in the XY plane at F = 2000 mm/min. A–B and D–E are
//! straight lines along +X; B–D is
//! - [`arc_example`]: 43 tangent arcs (21 + 1 + 21 mirrored), radii
//!   3.213–77.683 mm and lengths 0.42–16.09 mm (paper: 43 arcs,
//!   3.213–77.683 mm, 0.419–16.087 mm), short small-radius arcs clustered
//!   at B and D as in the paper's "B and D regions";
//! - [`line_example`]: the same curve as 83 chords of 1.1–3.9 mm (paper:
//!   83 lines of 1.095–3.916 mm), chord length growing with the local radius.
//!
//! The shape (our reading): from B the path turns up through a cluster of
//! short arcs (R 3.2–9.5 mm), climbs a long gentle flank (R 20–78 mm),
//! rounds a shoulder, and dips into a shallow valley whose lowest point is C.
//! A–B and D–E are 100 mm long, so the path is about 360 mm and takes about 11 s like the paper's (11.018 s).
//!
//! Units: mm, degrees in the design table, mm/min.

use crate::nc::writer::fmt_num;

/// Left half B → C: (radius mm, turn in degrees, + = CCW). The last turn
/// is adjusted so that the middle arc is symmetric about C.
const LEFT: [(f64, f64); 21] = [
    (3.213, 7.5),
    (3.5, 8.0),
    (3.9, 9.0),
    (4.5, 10.0),
    (5.5, 10.0),
    (7.0, 10.0),
    (9.5, 8.0),
    (20.0, 4.0),
    (77.683, -11.865),
    (70.0, -10.0),
    (55.0, -9.0),
    (40.0, -7.0),
    (25.0, -8.0),
    (18.0, -8.0),
    (12.0, -7.0),
    (10.0, -6.0),
    (15.0, -8.0),
    (30.0, -6.0),
    (70.0, 8.0),
    (55.0, 5.0),
    (25.0, 0.0),
];
/// The middle arc at C: radius, total turn (degrees).
const MIDDLE: (f64, f64) = (60.0, 6.0);
/// Length of A–B and D–E, mm.
const LEAD: f64 = 100.0;
/// Feed, mm/min.
pub const FEED: f64 = 2000.0;

/// The B–D curve as (radius, signed turn in rad) arcs, 43 of them.
pub fn bd_arcs() -> Vec<(f64, f64)> {
    let mut left: Vec<(f64, f64)> = LEFT.iter().map(|&(r, d)| (r, d.to_radians())).collect();
    let sum: f64 = left[..20].iter().map(|a| a.1).sum();
    if let Some(last) = left.last_mut() {
        last.1 = -MIDDLE.1.to_radians() / 2.0 - sum;
    }
    let mut all = left.clone();
    all.push((MIDDLE.0, MIDDLE.1.to_radians()));
    all.extend(left.iter().rev());
    all
}

struct Pen {
    p: [f64; 2],
    h: f64,
}

impl Pen {
    /// Walks an arc; returns (end, centre).
    fn arc(&mut self, r: f64, turn: f64) -> ([f64; 2], [f64; 2]) {
        let s = turn.signum();
        let c = [
            self.p[0] - s * r * self.h.sin(),
            self.p[1] + s * r * self.h.cos(),
        ];
        let a0 = (self.p[1] - c[1]).atan2(self.p[0] - c[0]);
        let a1 = a0 + turn;
        self.p = [c[0] + r * a1.cos(), c[1] + r * a1.sin()];
        self.h += turn;
        (self.p, c)
    }
}

fn header(title: &str) -> Vec<String> {
    vec![
        "%".into(),
        format!("O0002 ({title})"),
        "N10 G90 G17 G21 G40 G49 G80".into(),
        "N20 G0 X0 Y0 (A)".into(),
        format!("N30 G1 X{} Y0 F{} (B)", fmt_num(LEAD), fmt_num(FEED)),
    ]
}

/// The arc version of the test path as NC text.
///
/// # Examples
/// ```
/// let p = mtmotion::nc::program::parse(&mtmotion::toolpath::example::arc_example()).unwrap();
/// let arcs = p.segments.iter().filter(|s| matches!(s.motion, mtmotion::nc::program::Motion::Arc(_))).count();
/// assert_eq!(arcs, 43);
/// ```
pub fn arc_example() -> String {
    let mut lines = header("qiu Fig. 2-like test path, B-D as 43 arcs");
    let mut pen = Pen {
        p: [LEAD, 0.0],
        h: 0.0,
    };
    let arcs = bd_arcs();
    let mid = arcs.len() / 2;
    let mut n = 40;
    for (i, &(r, turn)) in arcs.iter().enumerate() {
        let start = pen.p;
        let (end, c) = pen.arc(r, turn);
        let g = if turn < 0.0 { "G2" } else { "G3" };
        let tag = if i == mid {
            " (C)"
        } else if i + 1 == arcs.len() {
            " (D)"
        } else {
            ""
        };
        lines.push(format!(
            "N{n} {g} X{} Y{} I{} J{}{tag}",
            fmt_num(end[0]),
            fmt_num(end[1]),
            fmt_num(c[0] - start[0]),
            fmt_num(c[1] - start[1])
        ));
        n += 10;
    }
    lines.push(format!("N{n} G1 X{} (E)", fmt_num(pen.p[0] + LEAD)));
    lines.push(format!("N{} M30", n + 10));
    lines.push("%".into());
    lines.join("\n")
}

/// The line version: the same B–D curve as 83 chords.
///
/// # Examples
/// ```
/// let p = mtmotion::nc::program::parse(&mtmotion::toolpath::example::line_example()).unwrap();
/// assert_eq!(p.segments.len(), 1 + 1 + 83 + 1);
/// ```
pub fn line_example() -> String {
    let pts = chord_points(83);
    let mut lines = header("qiu Fig. 2-like test path, B-D as 83 lines");
    let mut n = 40;
    let last = pts.len() - 1;
    for (i, p) in pts.iter().enumerate().skip(1) {
        let tag = if i == last { " (D)" } else { "" };
        lines.push(format!(
            "N{n} G1 X{} Y{}{tag}",
            fmt_num(p[0]),
            fmt_num(p[1])
        ));
        n += 10;
    }
    let end_x = pts.last().map_or(0.0, |p| p[0]) + LEAD;
    lines.push(format!("N{n} G1 X{} (E)", fmt_num(end_x)));
    lines.push(format!("N{} M30", n + 10));
    lines.push("%".into());
    lines.join("\n")
}

/// Points on the B–D curve: `count` chords whose nominal length is
/// `k·√R` clamped to 1.1–3.9 mm (R the local radius), with `k` found by
/// bisection and the stations then stretched to end exactly at D.
fn chord_points(count: usize) -> Vec<[f64; 2]> {
    let arcs = bd_arcs();
    let lens: Vec<f64> = arcs.iter().map(|(r, t)| r * t.abs()).collect();
    let total: f64 = lens.iter().sum();
    let radius_at = |s: f64| -> f64 {
        let mut acc = 0.0;
        for (i, l) in lens.iter().enumerate() {
            acc += l;
            if s < acc {
                return arcs[i].0;
            }
        }
        arcs[arcs.len() - 1].0
    };
    let stations = |k: f64| -> Vec<f64> {
        let mut st = vec![0.0];
        let mut s = 0.0;
        while s < total {
            s += (k * radius_at(s).sqrt()).clamp(1.1, 3.9);
            st.push(s);
        }
        st
    };
    let (mut lo, mut hi) = (0.01, 5.0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if stations(mid).len() - 1 > count {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let st = stations(hi);
    let last = st.last().copied().unwrap_or(total);
    // Points at the stretched stations, by walking the arcs.
    let mut pts = Vec::with_capacity(st.len());
    for &sj in &st {
        let target = sj * total / last;
        let mut pen = Pen {
            p: [LEAD, 0.0],
            h: 0.0,
        };
        let mut left = target;
        for (i, &(r, t)) in arcs.iter().enumerate() {
            if left <= lens[i] {
                pen.arc(r, t.signum() * left / r);
                break;
            }
            pen.arc(r, t);
            left -= lens[i];
        }
        pts.push(pen.p);
    }
    pts
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::program::{parse, Motion};

    #[test]
    fn arc_example_matches_the_papers_description() {
        let p = parse(&arc_example()).unwrap();
        let arcs: Vec<_> = p
            .segments
            .iter()
            .filter(|s| matches!(s.motion, Motion::Arc(_)))
            .collect();
        assert_eq!(arcs.len(), 43);
        let (mut rmin, mut rmax, mut lmin, mut lmax) = (f64::MAX, 0.0f64, f64::MAX, 0.0f64);
        for s in &arcs {
            let Motion::Arc(a) = s.motion else {
                unreachable!()
            };
            rmin = rmin.min(a.radius);
            rmax = rmax.max(a.radius);
            lmin = lmin.min(s.length());
            lmax = lmax.max(s.length());
        }
        assert!(
            (rmin - 3.213).abs() < 1e-3 && (rmax - 77.683).abs() < 1e-3,
            "{rmin} {rmax}"
        );
        assert!(
            lmin > 0.4 && lmin < 0.5 && (lmax - 16.087).abs() < 0.01,
            "{lmin} {lmax}"
        );
        // Symmetric: D at the same height as B, E level with A.
        let d = arcs.last().unwrap().end;
        assert!(d.y.abs() < 1e-3, "{d:?}");
    }

    #[test]
    fn line_example_matches_the_papers_description() {
        let p = parse(&line_example()).unwrap();
        let bd = &p.segments[2..p.segments.len() - 1];
        assert_eq!(bd.len(), 83);
        let (lmin, lmax) = bd.iter().fold((f64::MAX, 0.0f64), |(a, b), s| {
            (a.min(s.length()), b.max(s.length()))
        });
        assert!(lmin >= 1.0 && lmax <= 3.95, "{lmin} {lmax}");
    }
}
