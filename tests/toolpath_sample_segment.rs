//! Each kept sample of a tool-path simulation names the reference segment
//! it was measured against (`Simulation::segment`), and that segment is
//! the nearest one: checked against a nearest-segment search written here
//! from the segments' own geometry (clamped projection on lines and
//! rapids, the swept sector of an XY arc, else its nearer end), not the
//! core's `contour` module. On an asymmetric program of rapids, lines and
//! arcs (both directions), in a full run and in thinned runs, whose
//! mapping must follow the same kept samples as every other series.
#![cfg(not(target_arch = "wasm32"))]

use std::f64::consts::TAU;

use mtmotion::nc::program::{parse, Motion, Plane, Segment};
use mtmotion::toolpath::{simulate, simulate_thinned, SimConfig, Simulation};

/// Rapids in, over and out; lines in X, Y, Z and slanted; a clockwise
/// quarter, a counter-clockwise three-quarter arc and an R-form arc; no
/// symmetry that would make two segments equally near over a stretch; a
/// dwell, so segment indices are not the path's element indices.
const PROGRAM: &str = "G21 G90 G17
G0 X0 Y0 Z2
G1 Z0 F600
G1 X30 F1500
G2 X40 Y-10 I0 J-10
G1 Y-25
G4 P0.2
G3 X25 Y-40 I-15 J0 F1200
G1 X5 Y-30
G0 Z5
G0 X55 Y8
G1 Z-1 F400
G1 X62 Y8 F1800
G2 X70 Y0 R8
G1 X73 Y-17 F900
G0 Z10
";

/// Distance from `q` to segment `g`, or `None` for one without a path
/// (a dwell).
fn distance(g: &Segment, q: [f64; 3]) -> Option<f64> {
    let (a, b) = (g.start.p(), g.end.p());
    match g.motion {
        Motion::Dwell { .. } => None,
        Motion::Rapid | Motion::Linear => {
            let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if l2 == 0.0 {
                return None;
            }
            let w = [q[0] - a[0], q[1] - a[1], q[2] - a[2]];
            let f = ((w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / l2).clamp(0.0, 1.0);
            Some(dist(q, [a[0] + f * d[0], a[1] + f * d[1], a[2] + f * d[2]]))
        }
        Motion::Arc(arc) => {
            assert_eq!(arc.plane, Plane::XY, "the test's arcs are in XY");
            assert!((a[2] - b[2]).abs() < 1e-12, "the test's arcs are flat");
            let c = arc.center;
            let start = (a[1] - c[1]).atan2(a[0] - c[0]);
            let at = (q[1] - c[1]).atan2(q[0] - c[0]);
            // Angle of q from the start in the arc's direction, 0 … 2π.
            let phi = (arc.sweep.signum() * (at - start)).rem_euclid(TAU);
            if phi <= arc.sweep.abs() {
                let rho = (q[0] - c[0]).hypot(q[1] - c[1]);
                Some((rho - arc.radius).hypot(q[2] - a[2]))
            } else {
                Some(dist(q, a).min(dist(q, b)))
            }
        }
    }
}

fn dist(p: [f64; 3], q: [f64; 3]) -> f64 {
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

/// Checks every kept sample of `s` against the search over `segments`;
/// returns how many had one segment nearer than all others by 0.1 µm
/// (the others tie at a joint), per kind (rapid, line, arc).
fn check(s: &Simulation, segments: &[Segment], what: &str) -> [usize; 3] {
    assert_eq!(
        s.segment.len(),
        s.t.len(),
        "{what}: one segment per kept sample"
    );
    let mut clear = [0; 3];
    for (j, &mapped) in s.segment.iter().enumerate() {
        let q = [s.sim[0][j], s.sim[1][j], s.sim[2][j]];
        let near = [s.near[0][j], s.near[1][j], s.near[2][j]];
        let mapped = mapped as usize;
        let g = &segments[mapped];
        // The mapped segment holds the sample's nearest point, and its
        // distance is the sample's contour error.
        let on = distance(g, near).expect("a segment with a path");
        assert!(
            on < 1e-9,
            "{what}, sample {j}: near point {on} mm off segment {mapped}"
        );
        let d = distance(g, q).unwrap();
        assert!(
            (d - s.error[j]).abs() < 1e-9,
            "{what}, sample {j}: {d} vs error {}",
            s.error[j]
        );
        // And no other segment is nearer.
        let mut all: Vec<(f64, usize)> = segments
            .iter()
            .enumerate()
            .filter_map(|(i, g)| distance(g, q).map(|d| (d, i)))
            .collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert!(
            d <= all[0].0 + 1e-6,
            "{what}, sample {j}: segment {mapped} at {d} mm, segment {} at {} mm",
            all[0].1,
            all[0].0
        );
        if all[1].0 - all[0].0 > 1e-4 {
            assert_eq!(mapped, all[0].1, "{what}, sample {j} at t = {}", s.t[j]);
            clear[match g.motion {
                Motion::Rapid => 0,
                Motion::Arc(_) => 2,
                _ => 1,
            }] += 1;
        }
    }
    clear
}

#[test]
fn every_sample_maps_to_its_nearest_segment() {
    let p = parse(PROGRAM).unwrap();
    let s = simulate(&p.segments, &p.segments, &SimConfig::default()).unwrap();
    assert_eq!(s.series_stride, 1);
    let clear = check(&s, &p.segments, "full run");
    // Most samples have a clear nearest segment, on every kind of move.
    assert!(
        clear.iter().sum::<usize>() > s.samples / 2,
        "{clear:?} of {}",
        s.samples
    );
    assert!(clear.iter().all(|&n| n > 50), "{clear:?}");
    eprintln!(
        "{} samples, clearly nearest to a rapid, line, arc: {clear:?}",
        s.samples
    );
    // The mapping counts the samples each segment's statistics count.
    let mut count = vec![0; p.segments.len()];
    for &g in &s.segment {
        count[g as usize] += 1;
    }
    for st in &s.segments {
        assert_eq!(
            count[st.segment], st.samples,
            "segment {} (line {})",
            st.segment, st.line
        );
    }
    assert_eq!(count.iter().sum::<usize>(), s.samples);
}

#[test]
fn a_thinned_run_maps_the_samples_it_keeps() {
    let p = parse(PROGRAM).unwrap();
    let cfg = SimConfig::default();
    let full = simulate(&p.segments, &p.segments, &cfg).unwrap();
    let n = full.samples;
    for budget in [n / 7 + 3, 500] {
        let thin = simulate_thinned(&p.segments, &p.segments, &cfg, budget).unwrap();
        let stride = n.div_ceil(budget);
        assert_eq!(thin.series_stride, stride);
        check(&thin, &p.segments, &format!("budget {budget}"));
        // The kept sample of each group is the full run's largest error of
        // the group, and so is its segment.
        for (j, group) in (0..n).step_by(stride).enumerate() {
            let k = (group..(group + stride).min(n))
                .reduce(|k, i| if full.error[i] > full.error[k] { i } else { k })
                .unwrap();
            assert_eq!(
                thin.segment[j], full.segment[k],
                "budget {budget}, group {j}"
            );
            assert_eq!(thin.t[j].to_bits(), full.t[k].to_bits());
        }
    }
}
