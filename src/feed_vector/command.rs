//! Commanded motion of the constant-feed-speed-vector test
//! (suzuki-best-kffp §2.3, §3, Fig. 3, Eqs. 1–3).
//!
//! The tool centre runs on the circle of radius `R_W` about the machine
//! origin while the C table turns at the same angular velocity
//! `ω = F/R_W = F_C/R_C` (Eq. 3), both through the angle `θ(t)`:
//! `X = R_W cos θ`, `Y = R_W sin θ`, `C = θ`. The motion starts from rest at
//! `θ = 0` (X = R_W, Y = 0, C = 0) with a linear acc/dec: the angular
//! velocity rises linearly from 0 to ω over `accel_time` (the paper's
//! `dω/dt = ω/0.064 s`), so
//! `θ = ω t²/(2 T_acc)` for `t < T_acc` and `θ = ω (t − T_acc/2)` after.
//! This is the interpolator's command; each axis then applies its own
//! smoothing `Ts` and Pre-Control ([`crate::servo::simulate`]).
//!
//! # Units
//! t, T_acc in s; ω in rad/s; θ and C in rad; X, Y and R_W in mm.

/// Commanded angle `θ(t)` in rad.
///
/// # Units
/// `t`, `accel_time` in s; `omega` in rad/s.
///
/// # Examples
/// ```
/// use mtmotion::feed_vector::command::angle;
/// // half of the ramp time is lost: θ(1) = ω (1 − 0.064/2)
/// assert!((angle(1.0, 3.0, 0.064) - 3.0 * 0.968).abs() < 1e-12);
/// assert!((angle(0.032, 3.0, 0.064) - 3.0 * 0.032 * 0.032 / 0.128).abs() < 1e-15);
/// ```
pub fn angle(t: f64, omega: f64, accel_time: f64) -> f64 {
    if t <= 0.0 {
        0.0
    } else if t < accel_time {
        omega * t * t / (2.0 * accel_time)
    } else {
        omega * (t - 0.5 * accel_time)
    }
}

/// The sampled command of the three axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Command {
    /// Time, s.
    pub t: Vec<f64>,
    /// Commanded angle θ, rad (also the C command).
    pub theta: Vec<f64>,
    /// X command, mm.
    pub x: Vec<f64>,
    /// Y command, mm.
    pub y: Vec<f64>,
}

/// Samples the command at `t_i = i·dt`, `i < n`.
pub fn sample(n: usize, dt: f64, rw: f64, omega: f64, accel_time: f64) -> Command {
    let t: Vec<f64> = (0..n).map(|i| i as f64 * dt).collect();
    let theta: Vec<f64> = t.iter().map(|&t| angle(t, omega, accel_time)).collect();
    let x = theta.iter().map(|th| rw * th.cos()).collect();
    let y = theta.iter().map(|th| rw * th.sin()).collect();
    Command { t, theta, x, y }
}
