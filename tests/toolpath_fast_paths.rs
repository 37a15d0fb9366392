//! The simulator's fast paths equal the straightforward computation:
//! the sampler's rotation recurrence for the sine and cosine along an arc
//! matches a direct `sin_cos` at every sample of long, slow, large arcs
//! (position, velocity and the Eq. 1 moving average to < 1e-9 mm), and the
//! whole filter matches a plain re-implementation of Eqs. 1–2 that
//! evaluates the timeline directly and divides where the fast one
//! multiplies by reciprocals (< 1e-9 mm on the built-in examples).
//! `simulate_stats` (the series-free simulation of reverse compensation's
//! rounds) gives bit for bit the statistics `simulate` gives.
#![allow(clippy::needless_range_loop)]

use mtmotion::nc::program::parse;
use mtmotion::toolpath::{example, filter::filter, sampler::Sampler, timeline::Timeline};

#[path = "support/corpus.rs"]
mod corpus;

/// Three turns of R 100 mm at F 1000 (≈ 113 s, 1.1 M samples at 0.1 ms),
/// then a clockwise R 5 mm half circle and a helix.
const LONG_ARCS: &str = "G0 X100 Y0\nG3 X100 Y0 I-100 J0 F1000\nG3 X100 Y0 I-100 J0\n\
    G3 X100 Y0 I-100 J0\nG2 X110 Y0 R5 F2000\nG3 X-90 Y0 Z30 I-100 J0 F3000\n";

/// The largest deviations (position mm, velocity mm/s, Eq. 1 average mm) of
/// the sampler from `reference` over the whole program.
fn deviations(
    text: &str,
    dt: f64,
    t_a: f64,
    reference: impl Fn(&Timeline, f64, &mut usize) -> ([f64; 3], [f64; 3], [f64; 3]),
) -> [f64; 3] {
    let p = parse(text).unwrap();
    let tl = Timeline::new(&p.segments, 20_000.0, 1.0);
    let n = (tl.end_time / dt) as usize + 50;
    let mut now = Sampler::new(&tl, dt, 0.0);
    let mut back = Sampler::new(&tl, dt, t_a);
    let (mut h1, mut h2) = (0, 0);
    let mut dev = [0.0f64; 3];
    for k in 0..n {
        let t = k as f64 * dt;
        let (p, v, q1) = now.at(k);
        let (_, _, q0) = back.at(k);
        let (pd, vd, q1d) = reference(&tl, t, &mut h1);
        let (_, _, q0d) = reference(&tl, t - t_a, &mut h2);
        for ax in 0..3 {
            dev[0] = dev[0].max((p[ax] - pd[ax]).abs());
            dev[1] = dev[1].max((v[ax] - vd[ax]).abs());
            // Eq. 1's averaged position (Q(t) − Q(t − tA)) / tA.
            dev[2] = dev[2].max(((q1[ax] - q0[ax]) - (q1d[ax] - q0d[ax])).abs() / t_a);
        }
    }
    dev
}

#[test]
fn recurrence_matches_direct_sin_cos_on_long_arcs() {
    for (dt, t_a) in [(1e-4, 0.04), (1e-3, 0.0137), (3.7e-4, 0.1)] {
        let [dp, dv, du] = deviations(LONG_ARCS, dt, t_a, |tl, t, h| tl.eval(t, h));
        assert!(dp < 1e-9, "dt {dt}: position {dp:e} mm");
        assert!(dv < 1e-9, "dt {dt}: velocity {dv:e} mm/s");
        assert!(du < 1e-9, "dt {dt}: averaged position {du:e} mm");
    }
}

#[test]
fn sampler_handles_jumps_and_restarts() {
    let p = parse(LONG_ARCS).unwrap();
    let tl = Timeline::new(&p.segments, 20_000.0, 1.0);
    let dt = 1e-3;
    let mut s = Sampler::new(&tl, dt, 0.0);
    let mut h = 0;
    // Forwards with gaps, backwards, and repeated indices.
    for k in [
        0, 1, 2, 7, 8, 9, 5000, 4999, 4999, 5000, 5001, 70_000, 3, 4, 200_000, 300_000,
    ] {
        let (p, v, q) = s.at(k);
        let (pd, vd, qd) = tl.eval(k as f64 * dt, &mut h);
        for ax in 0..3 {
            assert!((p[ax] - pd[ax]).abs() < 1e-12, "k {k}");
            assert!((v[ax] - vd[ax]).abs() < 1e-12, "k {k}");
            assert!((q[ax] - qd[ax]).abs() < 1e-9, "k {k}");
        }
    }
}

/// Eqs. 1–2 written out plainly: direct timeline evaluation at `t` and
/// `t − tA`, the FOH lag step with divisions.
fn plain_filter(tl: &Timeline, t_a: f64, t: [f64; 3], dt: f64, n: usize) -> [Vec<f64>; 3] {
    let o = tl.origin;
    let mut out = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let (mut h1, mut h2) = (0, 0);
    let mut y = o;
    let mut u_prev = o;
    for k in 0..n {
        let tk = k as f64 * dt;
        let (p, _, q1) = tl.eval(tk, &mut h1);
        let mut u = p;
        if t_a > 0.0 {
            let (_, _, q0) = tl.eval(tk - t_a, &mut h2);
            for ax in 0..3 {
                u[ax] = o[ax] + (q1[ax] - q0[ax]) / t_a;
            }
        }
        for ax in 0..3 {
            if k > 0 {
                y[ax] = if t[ax] > 0.0 {
                    let a = (-dt / t[ax]).exp();
                    let ts = t[ax] * (u[ax] - u_prev[ax]) / dt;
                    u[ax] - ts + (y[ax] - u_prev[ax] + ts) * a
                } else {
                    u[ax]
                };
            }
            out[ax][k] = y[ax];
        }
        u_prev = u;
    }
    out
}

#[test]
fn filter_matches_plain_equations() {
    for text in [
        example::arc_example(),
        example::line_example(),
        LONG_ARCS.to_string(),
    ] {
        let p = parse(&text).unwrap();
        let tl = Timeline::new(&p.segments, 20_000.0, 1.0);
        for (t_a, lag, dt) in [
            (0.04, [0.015; 3], 1e-3),
            (0.013, [0.02, 0.03, 0.0], 3.7e-4),
            (0.0, [0.01; 3], 1e-3),
        ] {
            let n = ((tl.end_time + 0.5) / dt) as usize;
            let fast = filter(&tl, t_a, lag, dt, n);
            let plain = plain_filter(&tl, t_a, lag, dt, n);
            for ax in 0..3 {
                for k in 0..n {
                    let d = (fast.sim[ax][k] - plain[ax][k]).abs();
                    assert!(d < 1e-9, "tA {t_a} dt {dt} axis {ax} k {k}: {d:e} mm");
                }
            }
        }
    }
}

/// The statistics-only simulation equals the full one bit for bit on the
/// built-in examples and a corpus program that revisits itself, and
/// records none of the series.
#[test]
fn statistics_only_simulation_equals_the_full_one() {
    use mtmotion::toolpath::{simulate, simulate_stats, SimConfig};
    for text in [example::arc_example(), example::line_example()]
        .into_iter()
        .chain(tort())
    {
        let p = parse(&text).unwrap();
        let cfg = SimConfig::default();
        let full = simulate(&p.segments, &p.segments, &cfg).unwrap();
        let lean = simulate_stats(&p.segments, &p.segments, &cfg).unwrap();
        same_statistics(&lean, &full);
        assert_eq!((lean.samples, full.samples), (full.t.len(), full.t.len()));
        assert_eq!(full.series_stride, 1);
        assert!(
            lean.t.is_empty()
                && lean.error.is_empty()
                && lean.sim[0].is_empty()
                && lean.cmd[1].is_empty()
                && lean.near[0].is_empty()
                && lean.vel_sim[2].is_empty()
        );
    }
}

/// A run longer than its series budget keeps, of each group of `stride`
/// consecutive samples, exactly the sample of the full run with the
/// largest error (the first of equals), every series at that sample; the
/// statistics are bit for bit the full run's. Oracle: the same run with
/// every sample kept. Budgets that divide the run evenly and unevenly, and
/// a budget of 1 (one group).
#[test]
fn a_thinned_run_keeps_the_largest_error_of_each_group_and_the_same_statistics() {
    use mtmotion::toolpath::{simulate, simulate_thinned, SimConfig};
    for text in [example::arc_example()].into_iter().chain(tort()) {
        let p = parse(&text).unwrap();
        let cfg = SimConfig::default();
        let full = simulate(&p.segments, &p.segments, &cfg).unwrap();
        let n = full.samples;
        for budget in [n, n / 2, n / 7 + 3, 1000, 1] {
            let thin = simulate_thinned(&p.segments, &p.segments, &cfg, budget).unwrap();
            same_statistics(&thin, &full);
            let stride = n.div_ceil(budget);
            assert_eq!(thin.series_stride, stride, "budget {budget}");
            assert_eq!(thin.t.len(), n.div_ceil(stride), "budget {budget}");
            for (j, group) in (0..n).step_by(stride).enumerate() {
                let end = (group + stride).min(n);
                let mut k = group;
                for i in group..end {
                    if full.error[i] > full.error[k] {
                        k = i;
                    }
                }
                let pairs = [
                    (&thin.t, &full.t),
                    (&thin.error, &full.error),
                    (&thin.sim[0], &full.sim[0]),
                    (&thin.sim[2], &full.sim[2]),
                    (&thin.cmd[1], &full.cmd[1]),
                    (&thin.near[1], &full.near[1]),
                    (&thin.vel_cmd[0], &full.vel_cmd[0]),
                    (&thin.vel_sim[1], &full.vel_sim[1]),
                ];
                for (a, b) in pairs {
                    assert_eq!(a[j].to_bits(), b[k].to_bits(), "budget {budget}, group {j}");
                }
            }
        }
    }
}

/// LinuxCNC's tort.ngc from the shared corpus (none, said on stderr,
/// without the corpus).
fn tort() -> Option<String> {
    corpus::text("linuxcnc_tort.ngc")
}

fn same_statistics(a: &mtmotion::toolpath::Simulation, b: &mtmotion::toolpath::Simulation) {
    assert_eq!(a.segments, b.segments);
    assert_eq!(a.max_error.to_bits(), b.max_error.to_bits());
    assert_eq!(a.max_error_time.to_bits(), b.max_error_time.to_bits());
    assert_eq!(a.max_error_line, b.max_error_line);
    assert_eq!(a.motion_time.to_bits(), b.motion_time.to_bits());
    assert_eq!(a.nominal_time.to_bits(), b.nominal_time.to_bits());
    assert_eq!(a.samples, b.samples);
}
