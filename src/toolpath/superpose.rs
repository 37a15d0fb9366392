//! The paper's superposition (qiu §4-2): each segment's command is filtered
//! on its own — its displacement ramps from 0 to the segment's chord `Δᵢ`
//! during the segment and stays there — and the per-segment servo outputs
//! are added at every sampling instant, plus the start point.
//!
//! Because Eqs. 1–2 are linear and [`super::filter`]'s discretisation is
//! linear in the input samples, this equals filtering the whole command
//! (tested to 1e-9 mm); [`super::filter`] is the fast path the simulator
//! uses. A segment's response is followed until it has settled to within
//! 1e-14·(1 + |Δᵢ|) of `Δᵢ`, then `Δᵢ` is carried as a constant.
//!
//! Units: mm, s.

use super::filter::Lag1;
use super::timeline::{Item, Timeline};

fn disp_integral(it: &Item, t: f64) -> [f64; 3] {
    let u = t - it.t0;
    if u <= 0.0 {
        return [0.0; 3];
    }
    if u <= it.tau {
        return it.displacement_integral(u);
    }
    let q = it.displacement_integral(it.tau);
    let e = u - it.tau;
    [
        q[0] + (it.p1[0] - it.p0[0]) * e,
        q[1] + (it.p1[1] - it.p0[1]) * e,
        q[2] + (it.p1[2] - it.p0[2]) * e,
    ]
}

fn disp(it: &Item, t: f64) -> [f64; 3] {
    let u = (t - it.t0).clamp(0.0, it.tau);
    let p = it.pos(u);
    [p[0] - it.p0[0], p[1] - it.p0[1], p[2] - it.p0[2]]
}

/// Simulated X/Y/Z positions at `k·dt`, `k < n`, by superposing the
/// segments' responses.
///
/// # Units
/// s in, mm out.
///
/// # Examples
/// ```
/// use mtmotion::{nc::program::parse, toolpath::{filter::filter, superpose::superpose, timeline::Timeline}};
/// let p = parse("G1 X5 F600\nG3 X10 Y5 R5\nG1 Y10").unwrap();
/// let tl = Timeline::new(&p.segments, 2e4, 1.0);
/// let a = superpose(&tl, 0.05, [0.02, 0.03, 0.01], 1e-3, 4000);
/// let b = filter(&tl, 0.05, [0.02, 0.03, 0.01], 1e-3, 4000);
/// for k in (0..4000).step_by(97) {
///     assert!((a[1][k] - b.sim[1][k]).abs() < 1e-9);
/// }
/// ```
pub fn superpose(tl: &Timeline, t_a: f64, t: [f64; 3], dt: f64, n: usize) -> [Vec<f64>; 3] {
    let mut out = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let mut settled = [vec![0.0; n + 1], vec![0.0; n + 1], vec![0.0; n + 1]];
    let lags = [
        Lag1::new(t[0], dt),
        Lag1::new(t[1], dt),
        Lag1::new(t[2], dt),
    ];
    for it in &tl.items {
        let delta = [
            it.p1[0] - it.p0[0],
            it.p1[1] - it.p0[1],
            it.p1[2] - it.p0[2],
        ];
        let k0 = ((it.t0 / dt).floor() as usize).min(n);
        let input = |tk: f64| -> [f64; 3] {
            if t_a > 0.0 {
                let a = disp_integral(it, tk);
                let b = disp_integral(it, tk - t_a);
                [
                    (a[0] - b[0]) / t_a,
                    (a[1] - b[1]) / t_a,
                    (a[2] - b[2]) / t_a,
                ]
            } else {
                disp(it, tk)
            }
        };
        let mut y = [0.0; 3];
        let mut u_prev = input(k0 as f64 * dt);
        let t_quiet = it.t0 + it.tau + t_a;
        let mut k = k0;
        while k + 1 < n {
            k += 1;
            let tk = k as f64 * dt;
            let u = input(tk);
            let mut done = tk >= t_quiet;
            for ax in 0..3 {
                y[ax] = lags[ax].step(y[ax], u_prev[ax], u[ax]);
                out[ax][k] += y[ax];
                done &= (y[ax] - delta[ax]).abs() <= 1e-14 * (1.0 + delta[ax].abs());
            }
            u_prev = u;
            if done {
                for ax in 0..3 {
                    out[ax][k] -= y[ax];
                    settled[ax][k] += delta[ax];
                }
                break;
            }
        }
    }
    for ax in 0..3 {
        let mut acc = tl.origin[ax];
        for k in 0..n {
            acc += settled[ax][k];
            out[ax][k] += acc;
        }
    }
    out
}
