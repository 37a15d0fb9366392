//! Fixed-step time simulation of one feed-drive axis with Pre-Control and
//! torque saturation (suzuki-best-kffp Fig. 11 and Fig. 18), with the
//! worm-gear pitch error and backlash of kato-cone-frustum-ballbar Eq. 1 and
//! Fig. 2.
//!
//! Pipeline per axis:
//! 1. the sampled command (table units) is smoothed by `Ts` and the
//!    Pre-Control feedforward is read ahead by `Tp` and averaged over `Ta`
//!    ([`super::precontrol`], exact for the piecewise-linear command);
//! 2. both are scaled to the motor (`s_m`, [`super::transmission`]) and drive
//!    the cascaded loop, discretised exactly ([`super::discrete`]:
//!    first-order-hold matrix exponential; closed-form constant-torque step
//!    with a clamped integrator while saturated);
//! 3. the motor angle is mapped to the table through the gear (Eq. 1) and
//!    the backlash.
//!
//! Load torques of kato Fig. 2: gravity `G` (constant) and Coulomb friction
//! `F·sign(ω)` (sign of the motor speed at the start of each step, 0 at
//! rest: no stiction) enter as a torque held over the step, added exactly by
//! superposition ([`super::discrete`]); kato's velocity-loop integration
//! time `T_i` is `Kvp/Kvi` in this parameter set.
//!
//! The axis starts at rest on `command[0]`. Outputs are sampled at the same
//! instants as the command. Without saturation, backlash and pitch error the
//! steady state agrees with [`super::response::frequency_response`] (tested
//! to 0.5 % and 0.5 mrad).
//!
//! # Units
//! `dt` in s; command and position in mm (linear) or rad at the table
//! (rotary); velocity in mm/s or rad/s (motor speed over the nominal scale);
//! torque in N·m at the motor (applied torque, clipped at `torque_max`).

use super::discrete::LoopStep;
use super::precontrol;
use super::transmission::{motor_scale, Transmission};
use super::{AxisParams, ServoError};

/// Time response of one axis, one sample per command sample.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AxisResponse {
    /// Table position: mm (linear) or rad (rotary).
    pub position: Vec<f64>,
    /// Velocity: mm/s or rad/s.
    pub velocity: Vec<f64>,
    /// Motor torque applied (clipped at `torque_max`), N·m.
    pub torque: Vec<f64>,
    /// Whether the torque command exceeded `torque_max` at any sample.
    pub saturated: bool,
}

/// Shortest time step, s: a servo sampled faster than 10 MHz is not a
/// setting, and smaller steps only turn the window lengths into overflow.
pub const MIN_DT: f64 = 1e-7;

/// Largest |position command|, mm or rad (1 km; 160,000 turns): a 1e308
/// command gave positions of NaN.
pub const MAX_COMMAND: f64 = 1e6;

/// Checks `dt` and the command samples.
fn check_input(dt: f64, command: &[f64]) -> Result<(), ServoError> {
    if !(dt.is_finite() && (MIN_DT..=1.0).contains(&dt)) {
        return Err(ServoError::BadParameter {
            field: "dt",
            value: dt,
            expected: "the time step must be between 1e-7 and 1 s",
        });
    }
    if command.is_empty() {
        return Err(ServoError::BadCommand {
            index: 0,
            why: "the command is empty; give at least one position sample",
        });
    }
    if let Some(i) = command.iter().position(|v| !v.is_finite()) {
        return Err(ServoError::BadCommand {
            index: i,
            why: "the position command must be a finite number",
        });
    }
    if let Some(i) = command.iter().position(|v| v.abs() > MAX_COMMAND) {
        return Err(ServoError::BadCommand {
            index: i,
            why: "the position command must be within ±1e6 mm or rad; check its units",
        });
    }
    Ok(())
}

/// The loop over the samples; `input(i)` gives `(x_s, v_ff)` in table units.
/// Returns nominal positions (motor angle over `s_m`), velocities, applied
/// torques and the saturation flag.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn run(
    step: &LoopStep,
    sm: f64,
    kf: f64,
    limit: f64,
    load: (f64, f64),
    n: usize,
    input: impl Fn(usize) -> (f64, f64),
) -> (Vec<f64>, Vec<f64>, Vec<f64>, bool) {
    let mut position = vec![0.0; n];
    let mut velocity = vec![0.0; n];
    let mut torque = vec![0.0; n];
    let mut saturated = false;
    let inv = 1.0 / sm;
    let (x0, v0) = input(0);
    let mut z = [sm * x0, 0.0, 0.0];
    let mut u0 = [sm * x0, kf * v0];
    let outputs = position
        .iter_mut()
        .zip(velocity.iter_mut())
        .zip(torque.iter_mut());
    for (i, ((p, v), t)) in outputs.enumerate() {
        let tau = step.torque(&z, u0[0], u0[1]);
        let sat = tau.abs() > limit;
        let applied = if sat { limit.copysign(tau) } else { tau };
        saturated |= sat;
        *p = z[0] * inv;
        *v = z[1] * inv;
        *t = applied;
        if i + 1 == n {
            break;
        }
        let (x1, v1) = input(i + 1);
        let u1 = [sm * x1, kf * v1];
        // load torque (kato Fig. 2): gravity G plus Coulomb friction F
        // against the motor speed at the start of the step
        let (gravity, friction) = load;
        let d = gravity + friction * z[1].signum() * f64::from(u8::from(z[1] != 0.0));
        if sat {
            step.saturated(&mut z, applied - d);
        } else {
            step.linear(&mut z, u0, u1);
            if d != 0.0 {
                step.load(&mut z, d);
            }
        }
        u0 = u1;
    }
    (position, velocity, torque, saturated)
}

/// Simulates one axis following the sampled `command`, one sample per `dt`.
///
/// # Units
/// `dt` in s; `command` and the returned position in mm (linear axes) or rad
/// at the table (rotary axes); velocity per s; torque in N·m.
///
/// # Examples
/// ```
/// use mtmotion::servo::simulate::simulate_axis;
/// let c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
/// // 1 s at 1 ms of a constant 1 rad/s ramp: the steady lag is α_th.
/// let cmd: Vec<f64> = (0..1000).map(|i| i as f64 * 1e-3).collect();
/// let r = simulate_axis(&c, 1e-3, &cmd).unwrap();
/// assert_eq!(r.position.len(), 1000);
/// let lag = cmd[900] - r.position[900];
/// let alpha = mtmotion::servo::response::alpha_th(&c, 1.0).unwrap();
/// assert!((lag - alpha).abs() < 1e-4);
/// assert!(!r.saturated);
/// ```
pub fn simulate_axis(
    axis: &AxisParams,
    dt: f64,
    command: &[f64],
) -> Result<AxisResponse, ServoError> {
    axis.validate()?;
    check_input(dt, command)?;
    crate::budget::check(
        "axis simulation",
        (command.len() as u64).saturating_mul(1 + axis.pitch_error.len() as u64),
        crate::budget::MAX_AXIS_SIM_TERMS,
        "terms (samples × (1 + pitch-error harmonics))",
        "use fewer samples or fewer pitch-error harmonics",
    )?;
    let sm = motor_scale(axis)?;
    let mut trans = Transmission::new(axis)?;
    let shaped = precontrol::shape(command, dt, axis.ts, axis.ta, axis.tp);
    let step = LoopStep::new(axis, dt);
    let kf = sm * axis.kffp / 100.0;
    let n = command.len();
    let limit = axis.torque_max.unwrap_or(f64::INFINITY);
    let load = (axis.gravity, axis.friction);
    let (mut position, velocity, torque, saturated) = match &shaped {
        precontrol::Shaped::Grid {
            grid,
            e,
            window,
            scale,
        } => {
            let (e, w, scale) = (*e, *window, *scale);
            // x_s(i) and v_ff(i) read from the grid (precontrol::Shaped::at)
            run(&step, sm, kf, limit, load, n, |i| {
                (grid[w + i], (grid[w + i + e] - grid[i + e]) * scale)
            })
        }
        precontrol::Shaped::Samples { xs, vff } => {
            run(&step, sm, kf, limit, load, n, |i| (xs[i], vff[i]))
        }
    };
    diverged(dt, command, &position, &torque)?;
    if !trans.is_rigid() {
        // position is the motor angle over s_m; map it through gear and backlash
        for p in position.iter_mut() {
            *p = trans.table(*p);
        }
    }
    Ok(AxisResponse {
        position,
        velocity,
        torque,
        saturated,
    })
}

/// `Err(Unstable)` when the simulated position leaves every bound a
/// stable loop keeps: a non-finite sample (position or torque), or a
/// position beyond 1000 × the largest command (+ 1 mm or rad). A loop whose
/// gains are too high for `dt` otherwise returned ±2e9 mm and Infinity.
fn diverged(dt: f64, command: &[f64], position: &[f64], torque: &[f64]) -> Result<(), ServoError> {
    let command_max = command.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
    let bound = 1e3 * (command_max + 1.0);
    let reached = position.iter().fold(0.0_f64, |m, p| {
        if p.is_finite() && m.is_finite() {
            m.max(p.abs())
        } else {
            f64::INFINITY
        }
    });
    if reached > bound || torque.iter().any(|t| !t.is_finite()) {
        return Err(ServoError::Unstable {
            dt,
            reached,
            command: command_max,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine;
    use crate::servo::response::frequency_response;

    fn axis(name: &str) -> AxisParams {
        machine::preset("nmv5000").unwrap().axes[name].clone()
    }

    /// Fits a·sin + b·cos at ω over the samples from `from`; returns (|.|, ∠).
    fn fit(t: &[f64], y: &[f64], w: f64, from: usize) -> (f64, f64) {
        let (mut ss, mut sc, mut cc, mut ys, mut yc) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for i in from..t.len() {
            let (s, c) = (w * t[i]).sin_cos();
            ss += s * s;
            sc += s * c;
            cc += c * c;
            ys += y[i] * s;
            yc += y[i] * c;
        }
        let det = ss * cc - sc * sc;
        let a = (ys * cc - yc * sc) / det;
        let b = (yc * ss - ys * sc) / det;
        ((a * a + b * b).sqrt(), b.atan2(a))
    }

    #[test]
    fn steady_sine_matches_the_frequency_response() {
        for name in ["x", "y", "c"] {
            let a = axis(name);
            let w = 2.0 * std::f64::consts::PI;
            let dt = 1e-3;
            let t: Vec<f64> = (0..6000).map(|i| i as f64 * dt).collect();
            let cmd: Vec<f64> = t.iter().map(|t| (w * t).sin()).collect();
            let r = simulate_axis(&a, dt, &cmd).unwrap();
            let (mag, ph) = fit(&t, &r.position, w, 3000);
            let fr = frequency_response(&a, &[w]).unwrap();
            assert!(
                (mag / fr.magnitude[0] - 1.0).abs() < 5e-3,
                "{name}: {mag} vs {}",
                fr.magnitude[0]
            );
            assert!(
                (ph - fr.phase[0]).abs() < 5e-4,
                "{name}: {ph} vs {}",
                fr.phase[0]
            );
        }
    }

    #[test]
    fn saturation_clips_and_is_reported() {
        let mut c = axis("c");
        c.torque_max = Some(50.0);
        let cmd: Vec<f64> = (0..500).map(|i| (i as f64 * 1e-3) * 5.0).collect();
        let r = simulate_axis(&c, 1e-3, &cmd).unwrap();
        assert!(r.saturated);
        assert!(r.torque.iter().all(|t| t.abs() <= 50.0));
    }

    #[test]
    fn bad_inputs_name_the_field() {
        let c = axis("c");
        assert!(simulate_axis(&c, 0.0, &[0.0])
            .unwrap_err()
            .to_string()
            .contains("dt"));
        assert!(simulate_axis(&c, 1e-3, &[])
            .unwrap_err()
            .to_string()
            .contains("empty"));
        let e = simulate_axis(&c, 1e-3, &[0.0, f64::NAN])
            .unwrap_err()
            .to_string();
        assert!(e.contains("sample 1"), "{e}");
    }
}

#[cfg(test)]
mod unstable_tests {
    use super::*;

    #[test]
    fn a_diverging_loop_is_refused_in_words_not_returned_as_infinity() {
        let mut x = crate::machine::preset("trunnion-ac").unwrap().axes["x"].clone();
        x.kvi = 1e9;
        let cmd: Vec<f64> = (0..2000).map(|i| (i as f64 * 1e-3).sin()).collect();
        let e = simulate_axis(&x, 1e-3, &cmd).unwrap_err().to_string();
        assert!(e.starts_with("the axis loop is unstable"), "{e}");
        // the preset itself is stable
        x.kvi = crate::machine::preset("trunnion-ac").unwrap().axes["x"].kvi;
        assert!(simulate_axis(&x, 1e-3, &cmd).is_ok());
    }
}
