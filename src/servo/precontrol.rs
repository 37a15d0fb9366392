//! Command smoothing `Ts` and FANUC-style Pre-Control feedforward
//! (suzuki-best-kffp Fig. 10(b), Table 1) on a sampled command.
//!
//! The sampled interpolator command is read as its piecewise-linear
//! interpolant `c(t)` (held at the first sample before the start and at the
//! last sample after the end: the NC stands still there). Then, exactly for
//! that interpolant:
//!
//! - `x_s(t) = (1/Ts) ∫_{t−Ts}^{t} c` — linear acc/dec as a moving average
//!   of length `Ts` (`x_s = c` when `Ts = 0`);
//! - `v_ff(t) = (x_s(t+Tp) − x_s(t+Tp−Ta))/Ta` — the velocity of the
//!   smoothed command read ahead by `Tp` and averaged over `Ta` (the average
//!   of a velocity over `Ta` is the position increment over `Ta` divided by
//!   `Ta`).
//!
//! # Reading
//! - The feedforward is taken from the smoothed command `x_s` (the NC
//!   differentiates what it sends to the position loop); with `Tp = Ta/2` it
//!   is then a centred difference and `G(s) → A_Ts(s)` as the loops stiffen.
//! - When `Ta` is shorter than one step the averaging window is one step,
//!   centred where the continuous window is centred (the NC cannot average
//!   over less than one interpolation period); the frequency response keeps
//!   the continuous `Ta`, the difference is `O((ω·dt)²)`.
//! - Window integrals are exact differences of the running integral
//!   `Q(t) = ∫_0^t c`, evaluated once per sample: the same result as a
//!   running-sum ring buffer, without its round-off drift.
//!
//! # Units
//! Times in s; the command in any unit (mm or rad); `v_ff` in that unit per s.

/// The running integral of the piecewise-linear interpolant of a sampled
/// signal, in sample units (`u = t/dt`).
pub(crate) struct Interpolant<'a> {
    c: &'a [f64],
    /// `q[i] = ∫_0^i c(u) du` (trapezoids).
    q: Vec<f64>,
}

impl<'a> Interpolant<'a> {
    /// `c` must not be empty.
    pub(crate) fn new(c: &'a [f64]) -> Self {
        let mut q = Vec::with_capacity(c.len());
        let mut acc = 0.0;
        q.push(0.0);
        for w in c.windows(2) {
            acc += 0.5 * (w[0] + w[1]);
            q.push(acc);
        }
        Self { c, q }
    }

    fn last(&self) -> usize {
        self.c.len() - 1
    }

    /// `c(u)`.
    pub(crate) fn value(&self, u: f64) -> f64 {
        let last = self.last();
        // A NaN takes this branch too: it must not reach the indexing.
        if u <= 0.0 || u.is_nan() {
            self.c[0]
        } else if u >= last as f64 {
            self.c[last]
        } else {
            let i = u as usize; // 0 ≤ u < last
            let f = u - i as f64;
            self.c[i] + f * (self.c[i + 1] - self.c[i])
        }
    }

    /// `Q(u) = ∫_0^u c` (negative for u < 0).
    pub(crate) fn integral(&self, u: f64) -> f64 {
        let last = self.last();
        if u <= 0.0 || u.is_nan() {
            self.c[0] * u
        } else if u >= last as f64 {
            self.q[last] + self.c[last] * (u - last as f64)
        } else {
            let i = u as usize;
            let f = u - i as f64;
            self.q[i] + f * self.c[i] + 0.5 * f * f * (self.c[i + 1] - self.c[i])
        }
    }

    /// `x_s(u)`: the moving average over `w` samples ending at `u`
    /// (`c(u)` itself when `w` = 0). The tests' oracle of [`shape`].
    #[cfg(test)]
    pub(crate) fn smoothed(&self, u: f64, w: f64) -> f64 {
        if w <= 0.0 {
            self.value(u)
        } else {
            (self.integral(u) - self.integral(u - w)) / w
        }
    }
}

/// The position reference and feedforward velocity, one per sample.
pub(crate) enum Shaped {
    /// Whole-step times: `x_s` on an extended grid, `v_ff` read from it.
    Grid {
        /// `x_s` at samples `−window … n−1+e`; sample 0 at index `window`.
        grid: Vec<f64>,
        /// End offset of the feedforward window, samples.
        e: usize,
        /// Feedforward window, samples.
        window: usize,
        /// `1/(window·dt)`.
        scale: f64,
    },
    /// General times: both per sample.
    Samples {
        /// `x_s` at each sample.
        xs: Vec<f64>,
        /// `v_ff` at each sample, per s.
        vff: Vec<f64>,
    },
}

impl Shaped {
    /// `(x_s, v_ff)` at sample `i` (< the command length); the simulation
    /// inlines the same reads.
    #[cfg(test)]
    pub(crate) fn at(&self, i: usize) -> (f64, f64) {
        match self {
            Shaped::Grid {
                grid,
                e,
                window,
                scale,
            } => (
                grid[window + i],
                (grid[window + i + e] - grid[i + e]) * scale,
            ),
            Shaped::Samples { xs, vff } => (xs[i], vff[i]),
        }
    }
}

/// Applies `Ts`, `Ta`, `Tp` to the sampled command (see the module header).
/// `command` must not be empty; `dt > 0`.
pub(crate) fn shape(command: &[f64], dt: f64, ts: f64, ta: f64, tp: f64) -> Shaped {
    let c = Interpolant::new(command);
    let ns = ts / dt;
    let np = tp / dt;
    let na = ta / dt;
    let window = na.max(1.0);
    // The window [end − window, end] is centred at u + np − na/2.
    let end_offset = np - 0.5 * na + 0.5 * window;
    let n = command.len();
    let integral = |v: f64| (v - v.round()).abs() < 1e-9;
    if integral(ns) && integral(end_offset) && integral(window) {
        return shape_on_grid(
            &c,
            dt,
            ns.round() as usize,
            end_offset.round(),
            window.round() as usize,
        );
    }
    // The six window ends sit at fixed offsets from the sample, so each
    // keeps one fractional position and its integral is read without a
    // float-to-index conversion per sample (`Offset::at`).
    let at = |a: f64| Offset::new(a);
    let (x1, x0) = (at(0.0), at(-ns));
    let (e1, e0) = (at(end_offset), at(end_offset - ns));
    let (w1, w0) = (at(end_offset - window), at(end_offset - window - ns));
    let smooth = |i: usize, hi: &Offset, lo: &Offset| {
        if ns <= 0.0 {
            c.value(i as f64 + hi.a)
        } else {
            (hi.integral(&c, i) - lo.integral(&c, i)) / ns
        }
    };
    let mut xs = Vec::with_capacity(n);
    let mut vff = Vec::with_capacity(n);
    for i in 0..n {
        xs.push(smooth(i, &x1, &x0));
        vff.push((smooth(i, &e1, &e0) - smooth(i, &w1, &w0)) / (window * dt));
    }
    Shaped::Samples { xs, vff }
}

/// A fixed offset `a` (in samples) from the sample index, split once into
/// its whole part `k` and fraction `f` (0 ≤ f < 1).
struct Offset {
    a: f64,
    k: i64,
    f: f64,
}

impl Offset {
    fn new(a: f64) -> Self {
        let k = a.floor();
        Self {
            a,
            k: k as i64,
            f: a - k,
        }
    }

    /// `Q(i + a)`: inside the command the piecewise-quadratic running
    /// integral at index `i + k` and fraction `f` (as
    /// [`Interpolant::integral`], without rounding `i + a` first); before
    /// the start or past the end, `Interpolant::integral` itself.
    #[inline]
    fn integral(&self, c: &Interpolant, i: usize) -> f64 {
        let j = i as i64 + self.k;
        if j >= 0 && (j as usize) < c.last() {
            let j = j as usize;
            let f = self.f;
            c.q[j] + f * c.c[j] + 0.5 * f * f * (c.c[j + 1] - c.c[j])
        } else {
            c.integral(i as f64 + self.a)
        }
    }
}

/// The same as the general path when `Ts`, the window and its end offset
/// are whole numbers of steps: `x_s` is evaluated once per sample on an
/// extended grid and `v_ff` is a difference of two of its samples.
fn shape_on_grid(c: &Interpolant, dt: f64, ns: usize, end_offset: f64, window: usize) -> Shaped {
    let n = c.c.len();
    let e = end_offset as usize; // ≥ 0: the window ends at or after its centre
                                 // grid index j ↔ sample k = j − window, k ∈ [−window, n − 1 + e]
    let len = n + e + window;
    let last = n - 1;
    let q_at = |k: i64| -> f64 {
        if k <= 0 {
            c.c[0] * k as f64
        } else if k as usize >= last {
            c.q[last] + c.c[last] * (k as usize - last) as f64
        } else {
            c.q[k as usize]
        }
    };
    let c_at = |k: i64| -> f64 { c.c[k.clamp(0, last as i64) as usize] };
    let inv = if ns == 0 { 0.0 } else { 1.0 / ns as f64 };
    let grid: Vec<f64> = (0..len)
        .map(|j| {
            let k = j as i64 - window as i64;
            if ns == 0 {
                c_at(k)
            } else {
                (q_at(k) - q_at(k - ns as i64)) * inv
            }
        })
        .collect();
    Shaped::Grid {
        grid,
        e,
        window,
        scale: 1.0 / (window as f64 * dt),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_path_equals_the_general_path() {
        let dt = 1e-3;
        let c: Vec<f64> = (0..700)
            .map(|i| (i as f64 * 0.01).sin() * 3.0 + 0.002 * (i * i) as f64)
            .collect();
        let cases: [(f64, f64, f64); 5] = [
            (0.064, 0.015, 0.005),
            (0.0, 0.0, 0.0),
            (0.05, 0.015, 0.0155),
            (0.01, 0.0, 0.003),
            (0.02, 0.004, 0.0),
        ];
        for (ts, ta, tp) in cases {
            let it = Interpolant::new(&c);
            let (ns, np, na) = (ts / dt, tp / dt, ta / dt);
            let window = na.max(1.0);
            let end_offset = np - 0.5 * na + 0.5 * window;
            let g = shape(&c, dt, ts, ta, tp);
            for i in 0..c.len() {
                let (gx, gv) = g.at(i);
                let u = i as f64;
                let xs = it.smoothed(u, ns);
                let end = u + end_offset;
                let v = (it.smoothed(end, ns) - it.smoothed(end - window, ns)) / (window * dt);
                assert!(
                    (gx - xs).abs() < 1e-9 && (gv - v).abs() < 1e-6,
                    "{ts} {ta} {tp} @{i}"
                );
            }
        }
    }

    /// The general (non-grid) path, whose six window ends are read at
    /// fixed fractional offsets, equals the per-sample `smoothed` reading
    /// of the module header to 1e-12 of the command's size (x_s) and its
    /// rate (v_ff): times that are not whole steps, with and without Ts,
    /// windows reaching before the start and past the end.
    #[test]
    fn general_path_equals_per_sample_reading() {
        let dt = 0.7e-3;
        let c: Vec<f64> = (0..900)
            .map(|i| 40.0 * (i as f64 * 0.013).sin() + 0.001 * (i * i) as f64)
            .collect();
        let size = 850.0; // |c| stays below this
        for (ts, ta, tp) in [
            (0.0643, 0.0151, 0.0077),
            (0.0, 0.0151, 0.0077),
            (0.0643, 0.0, 0.0),
            (0.2, 0.03, 0.4),
            (0.00035, 0.0002, 0.0001),
        ] {
            let Shaped::Samples { xs, vff } = shape(&c, dt, ts, ta, tp) else {
                panic!("{ts} {ta} {tp}: expected the general path");
            };
            let it = Interpolant::new(&c);
            let (ns, np, na) = (ts / dt, tp / dt, ta / dt);
            let window = na.max(1.0);
            let end_offset = np - 0.5 * na + 0.5 * window;
            for i in 0..c.len() {
                let u = i as f64;
                let want_x = it.smoothed(u, ns);
                let end = u + end_offset;
                let want_v = (it.smoothed(end, ns) - it.smoothed(end - window, ns)) / (window * dt);
                assert!(
                    (xs[i] - want_x).abs() < 1e-12 * size,
                    "{ts} {ta} {tp} x @{i}"
                );
                assert!(
                    (vff[i] - want_v).abs() < 1e-12 * size / (window * dt),
                    "{ts} {ta} {tp} v @{i}: {} vs {want_v}",
                    vff[i]
                );
            }
        }
    }

    #[test]
    fn integral_of_a_ramp_is_exact_at_fractional_points() {
        let c: Vec<f64> = (0..10).map(|i| 2.0 * i as f64 + 1.0).collect();
        let it = Interpolant::new(&c);
        for u in [0.0, 0.3, 4.75, 8.999, 9.0, 12.5] {
            let want = if u <= 9.0 {
                u * u + u
            } else {
                90.0 + 19.0 * (u - 9.0)
            };
            assert!((it.integral(u) - want).abs() < 1e-12, "{u}");
        }
        assert!((it.integral(-2.0) + 2.0).abs() < 1e-15);
    }

    #[test]
    fn moving_average_of_a_ramp_lags_by_half_the_window() {
        let dt = 1e-3;
        let c: Vec<f64> = (0..2000).map(|i| 3.0 * i as f64 * dt).collect();
        let s = shape(&c, dt, 0.064, 0.015, 0.0075);
        // after the start-up, x_s(t) = 3 (t − Ts/2) and v_ff = 3 exactly
        for i in [200, 1000, 1900] {
            let t = i as f64 * dt;
            let (xs, vff) = s.at(i);
            assert!((xs - 3.0 * (t - 0.032)).abs() < 1e-12);
            assert!((vff - 3.0).abs() < 1e-9);
        }
        // at the end the command stops: the feedforward reads ahead and falls
        assert!(s.at(1999).1 < 3.0);
    }

    #[test]
    fn fractional_times_average_a_sine_exactly_enough() {
        // x_s of sin at ω through a window Ts: sinc(ωTs/2)·sin(ω(t − Ts/2)).
        let dt = 1e-4;
        let w = 10.0;
        let c: Vec<f64> = (0..20000).map(|i| (w * i as f64 * dt).sin()).collect();
        let ts = 0.03333;
        let s = shape(&c, dt, ts, 0.0, 0.0);
        let g = (0.5 * w * ts).sin() / (0.5 * w * ts);
        for i in [5000, 12345] {
            let t = i as f64 * dt;
            let want = g * (w * (t - 0.5 * ts)).sin();
            // piecewise-linear interpolation error ~ (ω dt)²/8
            assert!((s.at(i).0 - want).abs() < 2e-6, "{} vs {want}", s.at(i).0);
        }
    }
}
