//! Analysis of an X/Y/C trace of the constant-feed-speed-vector test
//! (suzuki-best-kffp §4.1–4.2, Eqs. 4–11), simulated or measured.
//!
//! With the tool on the circle of radius `R_W` about the origin and the
//! cutting point at the tool's left edge (Fig. 8):
//! - the cutting point carried by the rotary axis is
//!   `X_R = R_W cos C + R_C`, `Y_R = R_W sin C` (Eq. 7's `X_Rth`), and the
//!   one carried by the linear axes `X_L = X + R_C`, `Y_L = Y`;
//! - error vector (Eq. 4) `ε = (X_L − X_R, Y_L − Y_R)`;
//! - shape error (Eq. 5, solved exactly):
//!   `ΔR_C = R_C − √((R_C − ε_X)² + ε_Y²)` (≈ ε_X, Eq. 6);
//! - α = θ_cmd − C (Eq. 8), β = θ_cmd − atan2(Y, X) (Eq. 9),
//!   α − β = atan2(Y, X) − C (Eq. 10), each wrapped to (−π, π];
//! - ΔR = √(X² + Y²) − R_W (Eq. 11; negative when the radius shrinks).
//!
//! Summary over the steady state `t ≥ t_ss`, cut to whole periods `2π/ω`
//! (the whole window when shorter than one period): the mean of α − β; the mean
//! half amplitude `(max − min)/2` of ΔR_C over each whole period `2π/ω`
//! (over the whole window if it is shorter than one period); the radius
//! decrease `−mean(ΔR)` (Eq. 12's sign: > 0 when the circle shrinks); the
//! peak |torque| over the whole run.
//!
//! # Units
//! mm, rad, s, N·m.

use serde::{Deserialize, Serialize};

/// Time series of one test (simulated or measured), one value per sample.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    /// Time, s (0 at the start of the commanded motion).
    pub t: Vec<f64>,
    /// Commanded X, Y (mm) and C (rad).
    pub x_cmd: Vec<f64>,
    /// Commanded Y, mm.
    pub y_cmd: Vec<f64>,
    /// Commanded C, rad.
    pub c_cmd: Vec<f64>,
    /// X, mm.
    pub x: Vec<f64>,
    /// Y, mm.
    pub y: Vec<f64>,
    /// C, rad.
    pub c: Vec<f64>,
    /// C-axis torque, N·m (empty when a trace has none).
    pub torque_c: Vec<f64>,
    /// Shape error ΔR_C (Eq. 5), mm.
    pub shape_error: Vec<f64>,
    /// α (Eq. 8), rad.
    pub alpha: Vec<f64>,
    /// β (Eq. 9), rad.
    pub beta: Vec<f64>,
    /// α − β (Eq. 10), rad.
    pub angle_diff: Vec<f64>,
    /// ΔR (Eq. 11), mm.
    pub radius_error: Vec<f64>,
    /// Angular velocity of C, rad/s.
    pub omega_c: Vec<f64>,
    /// Angular velocity of the linear axes about the origin, rad/s.
    pub omega_l: Vec<f64>,
}

/// Steady-state figures of one test.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Summary {
    /// Mean of α − β over the steady state, rad.
    pub mean_angle_diff: f64,
    /// Mean half amplitude of the steady-state shape error, mm.
    pub half_amplitude: f64,
    /// Radius decrease `−mean(ΔR)` over the steady state, mm.
    pub radius_decrease: f64,
    /// Peak |C torque| over the run, N·m (0 without a torque column).
    pub peak_torque: f64,
    /// Whether the C torque command reached its limit.
    pub saturated: bool,
    /// Start of the steady-state window, s.
    pub steady_from: f64,
    /// Whole periods used for the half amplitude (0: the window was shorter).
    pub periods: usize,
}

use crate::numeric::wrap_angle as wrap;

/// Central-difference derivative (one-sided at the ends).
fn derivative(t: &[f64], y: &[f64]) -> Vec<f64> {
    let n = y.len();
    (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            if b > a {
                (y[b] - y[a]) / (t[b] - t[a])
            } else {
                0.0
            }
        })
        .collect()
}

/// Fills the derived series (Eqs. 4–11) from t, commands, X, Y, C.
/// All input vectors have the same non-zero length.
pub fn derive(s: &mut Series, rw: f64, rc: f64) {
    let n = s.t.len();
    s.shape_error = Vec::with_capacity(n);
    s.alpha = Vec::with_capacity(n);
    s.beta = Vec::with_capacity(n);
    s.angle_diff = Vec::with_capacity(n);
    s.radius_error = Vec::with_capacity(n);
    let mut phi_l = Vec::with_capacity(n);
    for i in 0..n {
        let (x, y, c, th) = (s.x[i], s.y[i], s.c[i], s.c_cmd[i]);
        let ex = x - rw * c.cos();
        let ey = y - rw * c.sin();
        s.shape_error
            .push(rc - ((rc - ex).powi(2) + ey * ey).sqrt());
        let phi = y.atan2(x);
        s.alpha.push(th - c);
        s.beta.push(wrap(th - phi));
        s.angle_diff.push(wrap(phi - c));
        s.radius_error.push(x.hypot(y) - rw);
        phi_l.push(phi);
    }
    // unwrap the linear axes' angle before differentiating
    for i in 1..n {
        let d = wrap(phi_l[i] - phi_l[i - 1]);
        phi_l[i] = phi_l[i - 1] + d;
    }
    s.omega_c = derivative(&s.t, &s.c);
    s.omega_l = derivative(&s.t, &phi_l);
}

/// The steady-state summary of derived series `s` (see the module header).
pub fn summarize(s: &Series, omega: f64, steady_from: f64, saturated: bool) -> Summary {
    let start = s.t.partition_point(|&t| t < steady_from);
    let span = |r: std::ops::Range<usize>| {
        let (lo, hi) = s.shape_error[r]
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        if hi >= lo {
            0.5 * (hi - lo)
        } else {
            0.0
        }
    };
    // whole periods 2π/ω from the steady start
    let period = std::f64::consts::TAU / omega.abs();
    let mut halves = Vec::new();
    let mut a = start;
    // A period shorter than two samples (at the extreme ω so large that
    // t + period == t) or not finite has no whole periods to average: the
    // whole window is used instead (and the search cannot stay in place).
    let n_win = s.t.len().saturating_sub(start);
    let sample = if n_win > 1 {
        (s.t[s.t.len() - 1] - s.t[start]) / (n_win - 1) as f64
    } else {
        f64::INFINITY
    };
    let resolvable = period.is_finite() && period >= 2.0 * sample;
    while resolvable && a < s.t.len() {
        let end_t = s.t[a] + period;
        let b = s.t.partition_point(|&t| t < end_t);
        if b >= s.t.len() || b <= a {
            break;
        }
        halves.push(span(a..b + 1));
        a = b;
    }
    // means over the whole periods (the 2ω ripple of an elliptic X/Y path
    // averages out), over the whole window when it is shorter than a period
    let window = if halves.is_empty() {
        start..s.t.len()
    } else {
        start..a
    };
    let count = window.len().max(1) as f64;
    let mean_angle_diff = s.angle_diff[window.clone()].iter().sum::<f64>() / count;
    let radius_decrease = -s.radius_error[window.clone()].iter().sum::<f64>() / count;
    let peak_torque = s.torque_c.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let half_amplitude = if halves.is_empty() {
        span(window)
    } else {
        halves.iter().sum::<f64>() / halves.len() as f64
    };
    Summary {
        mean_angle_diff,
        half_amplitude,
        radius_decrease,
        peak_torque,
        saturated,
        steady_from,
        periods: halves.len(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ω = 1e18 makes the period 6e-18 s, so `t + period == t`: the period
    /// search once stayed in place and grew a Vec until wasm ran out of
    /// memory. It must end, with no whole periods counted.
    #[test]
    fn a_period_below_one_sample_ends() {
        let mut s = Series::default();
        for i in 0..1000 {
            s.t.push(i as f64 * 1e-3);
            s.shape_error.push((i as f64).sin());
            s.angle_diff.push(0.0);
            s.radius_error.push(0.0);
        }
        for omega in [1e18, f64::INFINITY, f64::NAN, 0.0] {
            let sum = summarize(&s, omega, 0.0, false);
            assert_eq!(sum.periods, 0, "ω = {omega}");
            assert!(sum.half_amplitude.is_finite(), "ω = {omega}");
        }
    }

    /// Eq. 7: with X/Y lagging by β and shrunk by ΔR, C lagging by α,
    /// ΔR_C ≈ −(α − β) R_W sin ωt − ΔR cos ωt.
    #[test]
    fn shape_error_follows_eq_7() {
        let (rw, rc, w) = (8.0, 5.0, 3.0);
        let (alpha, beta, dr) = (2e-3, 1.2e-3, 4e-3);
        let n = 4000;
        let mut s = Series::default();
        for i in 0..n {
            let t = i as f64 * 1e-3;
            let th = w * t;
            s.t.push(t);
            s.c_cmd.push(th);
            s.x_cmd.push(rw * th.cos());
            s.y_cmd.push(rw * th.sin());
            s.x.push((rw - dr) * (th - beta).cos());
            s.y.push((rw - dr) * (th - beta).sin());
            s.c.push(th - alpha);
        }
        derive(&mut s, rw, rc);
        for i in [100, 1234, 3999] {
            let th = s.c_cmd[i];
            let eq7 = -(alpha - beta) * rw * th.sin() - dr * th.cos();
            assert!((s.shape_error[i] - eq7).abs() < 2e-5, "{i}");
            assert!((s.angle_diff[i] - (alpha - beta)).abs() < 1e-12);
            assert!((s.radius_error[i] + dr).abs() < 1e-12);
            assert!((s.omega_l[i] - w).abs() < 1e-6 && (s.omega_c[i] - w).abs() < 1e-6);
        }
        let sum = summarize(&s, w, 0.5, false);
        assert!((sum.mean_angle_diff - 8e-4).abs() < 1e-12);
        assert!((sum.radius_decrease - dr).abs() < 1e-12);
        let amp = ((alpha - beta) * rw).hypot(dr);
        assert!(
            (sum.half_amplitude - amp).abs() < 2e-5,
            "{}",
            sum.half_amplitude
        );
        assert_eq!(sum.periods, 1);
    }
}
