//! Axis drives for the cone-frustum test: the per-axis servo model of
//! [`crate::servo::simulate`] (kato Fig. 2: ball-screw linear axes,
//! worm-gear rotary axes, backlash, pitch error of Eq. 1), or an ideal
//! servo.
//!
//! With `idealServo` the motor follows the command exactly; the mechanism
//! after the motor (worm-gear pitch error and backlash) still acts, through
//! the same [`Transmission`] as the servo model (one implementation, driven
//! by the command instead of the motor angle over `s_m`): pitch error
//! `θ = x − Σ (W_i g/N_i)[cos(N_i x + φ_i) − cos φ_i]` with `x = θ_cmd`;
//! backlash a play of full width `b` that starts centred.
//!
//! The two drives then differ only by the servo lag `x_cmd − θm/s_m`: the
//! pitch-error map is Lipschitz with constant `1 + max W_i g` and the play
//! is 1-Lipschitz in the sup norm, so `|ideal − servo| ≤ (1 + max W_i g)·
//! max|lag|` (tested).
//!
//! The servo runs on a sub-grid of at most 1 ms (the command is linearly
//! interpolated), sampled back at the path points.
//!
//! Units: mm (linear), rad (rotary), s.

use crate::servo::simulate::simulate_axis;
use crate::servo::transmission::Transmission;
use crate::servo::{AxisParams, ServoError};

/// Longest servo step, s.
pub const SERVO_STEP: f64 = 1e-3;

/// The table position of an ideal servo with `axis`'s transmission errors
/// (only the mechanism fields of `axis` are used and checked).
///
/// # Units
/// `command` and the result in mm (linear) or rad (rotary).
///
/// # Examples
/// ```
/// use mtmotion::cone_frustum::drive::ideal;
/// let mut c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
/// c.backlash = 1e-3;
/// let out = ideal(&c, &[0.0, 0.01, 0.0]).unwrap();
/// // forward: half the gap lost; back: the whole gap
/// assert!((out[1] - 0.0095).abs() < 1e-15 && (out[2] - 0.0005).abs() < 1e-15);
/// ```
pub fn ideal(axis: &AxisParams, command: &[f64]) -> Result<Vec<f64>, ServoError> {
    let mut t = Transmission::new(axis)?;
    Ok(command.iter().map(|&c| t.table(c)).collect())
}

/// The table position of `axis` following `command` sampled every `dt`
/// through the servo model.
pub fn servo(axis: &AxisParams, dt: f64, command: &[f64]) -> Result<Vec<f64>, ServoError> {
    let m = (dt / SERVO_STEP).ceil().max(1.0) as usize;
    if m == 1 || command.len() < 2 {
        return Ok(simulate_axis(axis, dt, command)?.position);
    }
    let mut fine = Vec::with_capacity((command.len() - 1) * m + 1);
    for w in command.windows(2) {
        for s in 0..m {
            fine.push(w[0] + (w[1] - w[0]) * s as f64 / m as f64);
        }
    }
    fine.push(command[command.len() - 1]);
    let r = simulate_axis(axis, dt / m as f64, &fine)?;
    Ok(r.position.iter().step_by(m).copied().collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::servo::WormHarmonic;

    #[test]
    fn ideal_play_loses_half_the_gap_then_follows() {
        let mut a = crate::machine::preset("nmv5000").unwrap().axes["c"].clone();
        a.backlash = 0.2;
        let cmd = [0.0, 0.05, 0.3, 0.5, 0.4, 0.2];
        let out = ideal(&a, &cmd).unwrap();
        let want = [0.0, 0.0, 0.2, 0.4, 0.4, 0.3];
        for (o, w) in out.iter().zip(want) {
            assert!((o - w).abs() < 1e-15, "{out:?}");
        }
    }

    #[test]
    fn ideal_matches_the_servo_model_on_a_slow_move() {
        // A slow C move (≤ 0.02 rad/s) that starts and ends at rest and
        // reverses: one period of x = A(1 − cos ωt) (reversal at π/ω = 31.4 s),
        // with the command smoothing (Ts, Ta, Tp) off. Rest at both ends
        // matters: a velocity step (at the start, or at the end where the NC
        // holds the last sample) would ask 90·0.02 rad/s of the motor at once
        // and saturate the 725 N·m limit (see `a_velocity_step_saturates`).
        let mut a = crate::machine::preset("nmv5000").unwrap().axes["c"].clone();
        (a.ts, a.ta, a.tp) = (0.0, 0.0, 0.0);
        a.backlash = 1e-3;
        a.gear_ratio = Some(90.0);
        let (w, g) = (2e-6, 90.0);
        a.pitch_error = vec![WormHarmonic {
            w,
            n: 4.0,
            phi: 0.3,
        }];
        let (dt, amp, om) = (1e-3, 0.2, 0.1);
        let samples = (std::f64::consts::TAU / om / dt).round() as usize + 1;
        let t: Vec<f64> = (0..samples).map(|i| i as f64 * dt).collect();
        let cmd: Vec<f64> = t.iter().map(|t| amp * (1.0 - (om * t).cos())).collect();
        let id = ideal(&a, &cmd).unwrap();
        let r = simulate_axis(&a, dt, &cmd).unwrap();
        assert!(!r.saturated);
        // Predicted lag (table rad): full feedforward and Kvi ≈ 0 over 63 s
        // (integral time Kvp/Kvi = 17 000 s) leave the torque for inertia and
        // viscous friction to the proportional terms, Kvp·Kpp·δm = J θm'' + C θm';
        // the gear ratio cancels at the table: δ = (J r'' + C r')/(Kvp Kpp).
        let lag = |t: f64| {
            let (v, acc) = (amp * om * (om * t).sin(), amp * om * om * (om * t).cos());
            (a.inertia() * acc + a.c * v) / (a.kvp * a.kpp)
        };
        let mut rigid = a.clone();
        (rigid.backlash, rigid.pitch_error) = (0.0, Vec::new());
        let nom = simulate_axis(&rigid, dt, &cmd).unwrap().position;
        // The lag of the loop itself, to the next order (δ'/Kpp ≈ 6e-10 rad).
        // The axis starts at rest with no lag while the formula gives
        // J r''(0)/(Kvp Kpp) = 4.2e-8 rad; that start transient decays with
        // the slow closed-loop pole (≈ 65 1/s), gone (< 1e-10) after 0.3 s.
        let n = cmd.len();
        for i in 0..n {
            let d = cmd[i] - nom[i] - lag(t[i]);
            let tol = if t[i] < 0.3 { lag(0.0) + 2e-9 } else { 2e-9 };
            assert!(
                d.abs() < tol,
                "lag at {i}: {} vs {}",
                cmd[i] - nom[i],
                lag(t[i])
            );
        }
        let max_lag = (0..n).map(|i| lag(t[i]).abs()).fold(0.0, f64::max);
        assert!(max_lag > 3e-7 && max_lag < 4e-7, "{max_lag}");
        // Same transmission on both paths: they differ by at most the lag
        // carried through the Lipschitz pitch map and the play, and by the
        // lag itself where both are in contact (at the peak speed).
        let worst = (0..n)
            .map(|i| (id[i] - r.position[i]).abs())
            .fold(0.0, f64::max);
        assert!(
            worst <= (1.0 + w * g) * (max_lag + 2e-9),
            "ideal vs servo: {worst} > lag {max_lag}"
        );
        assert!((worst - max_lag).abs() < 2e-9, "{worst} vs lag {max_lag}");
        // The mechanism is visible: half the gap lost going out, then the whole
        // gap at the reversal, on top of the pitch error.
        let err: Vec<f64> = id.iter().zip(&cmd).map(|(x, y)| x - y).collect();
        let spread = err.iter().fold(f64::MIN, |m, &v| m.max(v))
            - err.iter().fold(f64::MAX, |m, &v| m.min(v));
        assert!(spread > 9e-4, "{spread}");
    }

    #[test]
    fn a_velocity_step_saturates() {
        // The root cause of an earlier 7e-5 rad ideal/servo discrepancy: a
        // 0.02 rad/s velocity step from rest through a 90:1 gear asks the
        // motor for ω_m = 1.8 rad/s at once; it accelerates at τ_max/J and
        // falls behind by ω_m²J/(2 τ_max) motor rad, 1.47e-4 rad at the table.
        let mut a = crate::machine::preset("nmv5000").unwrap().axes["c"].clone();
        (a.ts, a.ta, a.tp) = (0.0, 0.0, 0.0);
        a.gear_ratio = Some(90.0);
        let dt = 1e-3;
        let cmd: Vec<f64> = (0..200).map(|i| 0.02 * i as f64 * dt).collect();
        let r = simulate_axis(&a, dt, &cmd).unwrap();
        assert!(r.saturated);
        let peak = cmd
            .iter()
            .zip(&r.position)
            .map(|(c, p)| c - p)
            .fold(0.0, f64::max);
        let wm = 0.02 * 90.0;
        let want = wm * wm * a.inertia() / (2.0 * a.torque_max.unwrap()) / 90.0;
        // 0.4 % measured: the half-speed feedforward of the first sample and
        // the short unsaturated tail of the acceleration
        assert!((peak / want - 1.0).abs() < 0.01, "{peak} vs {want}");
    }
}
