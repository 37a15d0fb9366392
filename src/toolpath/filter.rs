//! Direct filtering of the whole command (qiu Eqs. 1–2).
//!
//! Eq. 1, the NC's linear acc/dec, is the moving average of the commanded
//! velocity over `tA`; integrated once it is the moving average of the
//! position, `p_a(t) = (Q(t) − Q(t − tA)) / tA`, evaluated exactly from the
//! timeline's closed-form integral `Q`. Eq. 2, the servo, is a first-order
//! lag `1/(Ts + 1)` on velocity and therefore on position (zero initial
//! state: the tool stands at the start). It is discretised exactly for an
//! input that is linear between samples (first-order hold):
//! `y₊ = u₊ − T·s + (y − u + T·s)·e^{−dt/T}`, `s = (u₊ − u)/dt`, so the
//! only discretisation error is the curvature of `p_a` within one sample
//! (≈ dt²·|p̈_a|/8, 0.1 µm at dt = 1 ms and 800 mm/s²). The servo velocity
//! output is `ou = (p_a − y)/T` exactly; with `T = 0` the servo is ideal.
//!
//! Units: mm, s, mm/s.

use super::sampler::Sampler;
use super::timeline::Timeline;

/// Per-sample series of one run, X/Y/Z each.
#[derive(Debug, Clone, Default)]
pub struct Filtered {
    /// Sample times, s.
    pub t: Vec<f64>,
    /// Commanded position, mm.
    pub cmd: [Vec<f64>; 3],
    /// Commanded velocity `f_b`, mm/s.
    pub vel_cmd: [Vec<f64>; 3],
    /// Simulated (servo output) position, mm.
    pub sim: [Vec<f64>; 3],
    /// Simulated velocity `ou`, mm/s.
    pub vel_sim: [Vec<f64>; 3],
}

/// The FOH coefficients of a first-order lag: `(e^{−dt/T}, T)`; `T = 0`
/// means no lag.
#[derive(Debug, Clone, Copy)]
pub struct Lag1 {
    a: f64,
    t: f64,
    /// `T/dt` and `1/T`, so the per-sample steps only multiply.
    t_dt: f64,
    inv_t: f64,
}

impl Lag1 {
    /// Lag `t` sampled at `dt`, s.
    pub fn new(t: f64, dt: f64) -> Self {
        let lag = t > 0.0;
        Self {
            a: if lag { (-dt / t).exp() } else { 0.0 },
            t,
            t_dt: if lag { t / dt } else { 0.0 },
            inv_t: if lag { 1.0 / t } else { 0.0 },
        }
    }
    /// One step: state `y` at the old sample, input `u0` → `u1`.
    #[inline]
    pub fn step(&self, y: f64, u0: f64, u1: f64) -> f64 {
        if self.t <= 0.0 {
            return u1;
        }
        let ts = (u1 - u0) * self.t_dt;
        u1 - ts + (y - u0 + ts) * self.a
    }
    /// Velocity output for input `u` and state `y`, given the input's
    /// derivative `du` (used when `T = 0`).
    #[inline]
    pub fn velocity(&self, y: f64, u: f64, du: f64) -> f64 {
        if self.t <= 0.0 {
            du
        } else {
            (u - y) * self.inv_t
        }
    }
}

/// Samples `n` points at `k·dt` of the command filtered by the moving
/// average `t_a` and the lags `t` (per axis).
///
/// # Units
/// `t_a`, `t`, `dt` in s; positions in mm.
///
/// # Examples
/// ```
/// use mtmotion::{nc::program::parse, toolpath::{filter::filter, timeline::Timeline}};
/// let p = parse("G1 X10 F600").unwrap();
/// let tl = Timeline::new(&p.segments, 2e4, 1.0);
/// let f = filter(&tl, 0.1, [0.02; 3], 1e-3, 2001);
/// // A ramp followed at 10 mm/s lags by tA/2 + T = 0.07 s → 0.7 mm.
/// let k = 500;
/// assert!((f.cmd[0][k] - f.sim[0][k] - 0.7).abs() < 1e-9);
/// assert!((f.sim[0][2000] - 10.0).abs() < 1e-9);
/// ```
pub fn filter(tl: &Timeline, t_a: f64, t: [f64; 3], dt: f64, n: usize) -> Filtered {
    let mut out = Filtered::with_capacity(n);
    let mut stepper = Stepper::new(tl, t_a, t, dt);
    for _ in 0..n {
        out.push(&stepper.next_sample());
    }
    out
}

/// One sample of the filtered command.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Sample time `k·dt`, s.
    pub t: f64,
    /// Commanded position, mm.
    pub cmd: [f64; 3],
    /// Commanded velocity `f_b`, mm/s.
    pub vel_cmd: [f64; 3],
    /// Simulated (servo output) position, mm.
    pub sim: [f64; 3],
    /// Simulated velocity `ou`, mm/s.
    pub vel_sim: [f64; 3],
}

/// The filter run sample by sample, so a caller can measure each sample
/// as it comes and keep only what it needs (a long program's simulation
/// holds no per-sample series it does not return).
pub struct Stepper<'a> {
    now: Sampler<'a>,
    back: Sampler<'a>,
    lags: [Lag1; 3],
    origin: [f64; 3],
    t_a: f64,
    inv_ta: f64,
    dt: f64,
    ring: Vec<([f64; 3], [f64; 3])>,
    slot: usize,
    y: [f64; 3],
    u_prev: [f64; 3],
    k: usize,
}

impl<'a> Stepper<'a> {
    /// The filter of `tl` by the moving average `t_a` and the lags `t`
    /// (per axis), sampled at `dt`; all in s.
    pub fn new(tl: &'a Timeline, t_a: f64, t: [f64; 3], dt: f64) -> Self {
        Self::with_phase(tl, t_a, t, dt, 0.0)
    }

    /// As [`Stepper::new`], sampling at `k·dt + phase` (`0 ≤ phase < dt`,
    /// s): a window of a longer command on the longer command's sample
    /// grid ([`super::locality`]). The tool stands at the start until
    /// `t = 0`, so the ring's start values stay exact.
    pub fn with_phase(tl: &'a Timeline, t_a: f64, t: [f64; 3], dt: f64, phase: f64) -> Self {
        let o = tl.origin;
        Self {
            now: Sampler::new(tl, dt, -phase),
            back: Sampler::new(tl, dt, t_a - phase),
            lags: [
                Lag1::new(t[0], dt),
                Lag1::new(t[1], dt),
                Lag1::new(t[2], dt),
            ],
            origin: o,
            t_a,
            inv_ta: if t_a > 0.0 { 1.0 / t_a } else { 0.0 },
            dt,
            ring: delay_ring(o, t_a, dt),
            slot: 0,
            y: o,
            u_prev: o,
            k: 0,
        }
    }

    /// The next sample (the first is at t = 0).
    pub fn next_sample(&mut self) -> Sample {
        let k = self.k;
        self.k += 1;
        let (p, vb, q1) = self.now.at(k);
        let (u, fa) = if self.t_a > 0.0 {
            let (pb, q0) = self.back_end(k, p, q1);
            let mut u = [0.0; 3];
            let mut fa = [0.0; 3];
            for ax in 0..3 {
                u[ax] = self.origin[ax] + (q1[ax] - q0[ax]) * self.inv_ta;
                fa[ax] = (p[ax] - pb[ax]) * self.inv_ta;
            }
            (u, fa)
        } else {
            (p, vb)
        };
        let mut vel_sim = [0.0; 3];
        for ax in 0..3 {
            if k > 0 {
                self.y[ax] = self.lags[ax].step(self.y[ax], self.u_prev[ax], u[ax]);
            }
            vel_sim[ax] = self.lags[ax].velocity(self.y[ax], u[ax], fa[ax]);
        }
        self.u_prev = u;
        Sample {
            t: k as f64 * self.dt,
            cmd: p,
            vel_cmd: vb,
            sim: self.y,
            vel_sim,
        }
    }

    /// Position and `Q` at `t − tA` for sample `k`, whose own are `p`, `q1`:
    /// from the delay ring when `tA` is a whole number of samples (before
    /// the first m samples it holds the start: t − tA < 0, origin, Q = 0),
    /// else from the timeline.
    #[inline]
    fn back_end(&mut self, k: usize, p: [f64; 3], q1: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        match self.ring.get_mut(self.slot) {
            Some(held) => {
                let back_value = *held;
                *held = (p, q1);
                self.slot += 1;
                if self.slot == self.ring.len() {
                    self.slot = 0;
                }
                back_value
            }
            None => {
                let (pb, _, q0) = self.back.at(k);
                (pb, q0)
            }
        }
    }
}

impl Filtered {
    /// Empty series with room for `n` samples each.
    pub fn with_capacity(n: usize) -> Self {
        let mut out = Filtered::default();
        out.t.reserve_exact(n);
        for ax in 0..3 {
            out.cmd[ax].reserve_exact(n);
            out.sim[ax].reserve_exact(n);
            out.vel_cmd[ax].reserve_exact(n);
            out.vel_sim[ax].reserve_exact(n);
        }
        out
    }

    /// Appends one sample to every series.
    #[inline]
    pub fn push(&mut self, s: &Sample) {
        self.t.push(s.t);
        for ax in 0..3 {
            self.cmd[ax].push(s.cmd[ax]);
            self.sim[ax].push(s.sim[ax]);
            self.vel_cmd[ax].push(s.vel_cmd[ax]);
            self.vel_sim[ax].push(s.vel_sim[ax]);
        }
    }
}

/// The ring of `(position, Q)` that gives Eq. 1's moving average its far
/// end, the command at t − tA, without evaluating the timeline twice per
/// sample: when `t_a` is a whole number m of samples `dt` (to within 1e-15
/// relative) the value at t − tA is the one computed m samples earlier, so
/// the last m are kept, starting as the tool standing at `origin` (Q = 0).
/// Empty otherwise (and without a moving average); the caller then
/// evaluates the timeline at t − tA.
fn delay_ring(origin: [f64; 3], t_a: f64, dt: f64) -> Vec<([f64; 3], [f64; 3])> {
    let m = (t_a / dt).round();
    if t_a > 0.0 && (1.0..1e6).contains(&m) && (m * dt - t_a).abs() <= 1e-15 * t_a {
        vec![(origin, [0.0; 3]); m as usize]
    } else {
        Vec::new()
    }
}
