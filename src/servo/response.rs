//! Exact frequency response of the feed drive (suzuki-best-kffp Fig. 11,
//! Eqs. 12–19).
//!
//! The loop (suzuki-best-kffp Fig. 11 with Pre-Control of Fig. 10(b)):
//!
//! - `x_s = A_Ts · x` — the interpolator command `x` after the smoothing
//!   `Ts`, a moving average of length `Ts`: `A_T(s) = (1 − e^{−sT})/(sT)`;
//! - `v_ff = s · e^{s·Tp} · A_Ta · x_s` — the feedforward velocity: the
//!   smoothed command read ahead by `Tp` and averaged over `Ta`;
//! - `v_ref = Kpp (x_s − y) + k v_ff`, `k = K_FFP/100`;
//! - velocity loop `T_v = P V/(1 + P V)`, `P = 1/((J+J1) s + C)`,
//!   `V = Kvp + Kvi/s`.
//!
//! Hence `G(s) = A_Ts · T_v (Kpp + k s e^{sTp} A_Ta)/(s + Kpp T_v)`, which
//! for `Ts = Ta = Tp = 0` is exactly the issue's
//! `G = T_v (Kpp + k s)/(s + Kpp T_v)`. Delays and moving averages are kept
//! as exact exponentials (no Padé).
//!
//! # Readings where the paper is ambiguous
//! - **Kvi**: Table 1 prints "Nms/rad" for both Kvp and Kvi, which cannot be
//!   right for an integral gain. Kvi is read as the SI integral gain in
//!   N·m/rad in `τ = Kvp e + Kvi ∫e dt` (e in rad/s), values as printed
//!   (0.198, 0.274). The integral corner `Kvi/Kvp` is then ≈ 6·10⁻⁵ rad/s:
//!   the integral action shapes only the limit s → 0 of Eq. 17 and is
//!   invisible in a test lasting seconds (see `docs/servo.md`).
//! - **Ramp error α (Eq. 17)**: `α_th = ω · lim_{s→0}(1 − G(s))/s`
//!   `= ω (Ts/2 + (1/T_v(0) − k)/Kpp)`, with `T_v(0) = 1` when `Kvi > 0`
//!   and `Kvp/(Kvp + C)` otherwise. `Ta` and `Tp` do not enter (the
//!   feedforward is exact for a ramp).
//! - **β (Eq. 18)**: `β_th = −∠G_L(jω)` per linear axis; the phase is the
//!   continuous one (`−ω Ts/2` plus the principal phase of the rest), not
//!   wrapped to (−π, π].
//!
//! # Units
//! ω in rad/s, times in s, gains as in [`AxisParams`]; G is dimensionless
//! (same unit in and out), phase in rad, α and β in rad, ΔR in mm.

use nalgebra::Complex;

use super::{AxisParams, ServoError};

type C64 = Complex<f64>;

/// `A_T(s) = (1 − e^{−sT})/(sT)` without its pure delay `e^{−sT/2}`:
/// the real factor `sin(ωT/2)/(ωT/2)` at `s = jω`.
fn sinc_half(omega: f64, t: f64) -> f64 {
    let x = 0.5 * omega * t;
    if x.abs() < 1e-8 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// Full moving average `A_T(jω)`, complex.
fn moving_average(omega: f64, t: f64) -> C64 {
    C64::from_polar(sinc_half(omega, t), -0.5 * omega * t)
}

/// Velocity-loop closed-loop response `T_v(jω) = PV/(1+PV)`, ω > 0.
fn velocity_loop(axis: &AxisParams, omega: f64) -> C64 {
    let s = C64::new(0.0, omega);
    // PV = (Kvp s + Kvi) / (s ((J+J1) s + C)); T_v = num/(den + num).
    let num = s * axis.kvp + axis.kvi;
    let den = s * (s * axis.inertia() + axis.c);
    num / (den + num)
}

/// The response without the smoothing delay `e^{−jωTs/2}`:
/// `sinc(ωTs/2) · T_v (Kpp + k jω e^{jωTp} A_Ta)/(jω + Kpp T_v)`.
fn response_without_smoothing_delay(axis: &AxisParams, omega: f64) -> C64 {
    let s = C64::new(0.0, omega);
    let k = axis.kffp / 100.0;
    let tv = velocity_loop(axis, omega);
    let ff = s * k * C64::from_polar(1.0, omega * axis.tp) * moving_average(omega, axis.ta);
    sinc_half(omega, axis.ts) * tv * (ff + axis.kpp) / (s + tv * axis.kpp)
}

/// `G(jω)` from the interpolator command to the axis position.
///
/// Returns `G(0) = 1` at ω = 0.
///
/// # Units
/// ω in rad/s (≥ 0); the result is dimensionless.
///
/// # Examples
/// ```
/// use mtmotion::servo::response::closed_loop;
/// let c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
/// let g = closed_loop(&c, 1e-9).unwrap();
/// assert!((g.norm() - 1.0).abs() < 1e-9);
/// ```
pub fn closed_loop(axis: &AxisParams, omega: f64) -> Result<C64, ServoError> {
    axis.validate()?;
    check_omega(omega)?;
    if omega == 0.0 {
        return Ok(C64::new(1.0, 0.0));
    }
    Ok(
        response_without_smoothing_delay(axis, omega)
            * C64::from_polar(1.0, -0.5 * omega * axis.ts),
    )
}

/// Highest angular frequency, rad/s (1.6 MHz, far above any feed drive's
/// bandwidth; at 1e308 the delay terms' phase was no longer a number).
pub const MAX_OMEGA: f64 = 1e7;

fn check_omega(omega: f64) -> Result<(), ServoError> {
    if (0.0..=MAX_OMEGA).contains(&omega) {
        Ok(())
    } else {
        Err(ServoError::BadParameter {
            field: "omega",
            value: omega,
            expected: "angular frequencies must be from 0 to 1e7 rad/s",
        })
    }
}

/// Magnitude and continuous phase (rad) of `G(jω)` at every ω.
#[derive(Debug, Clone, PartialEq)]
pub struct FrequencyResponse {
    /// `|G(jω)|`.
    pub magnitude: Vec<f64>,
    /// `∠G(jω)` in rad: `−ω Ts/2` plus the principal phase of the rest.
    pub phase: Vec<f64>,
}

/// `G(jω)` at each ω of `omegas` (the JS `frequencyResponse`).
///
/// # Units
/// ω in rad/s; magnitude dimensionless; phase in rad.
///
/// # Examples
/// ```
/// use mtmotion::servo::response::frequency_response;
/// let mut x = mtmotion::machine::preset("nmv5000").unwrap().axes["x"].clone();
/// x.ts = 0.0; x.ta = 0.0; x.tp = 0.0; x.kffp = 0.0; x.kvi = 0.0;
/// // Far above the loop bandwidth the response rolls off.
/// let r = frequency_response(&x, &[1.0, 1e4]).unwrap();
/// assert!((r.magnitude[0] - 1.0).abs() < 1e-3 && r.magnitude[1] < 1e-3);
/// ```
pub fn frequency_response(
    axis: &AxisParams,
    omegas: &[f64],
) -> Result<FrequencyResponse, ServoError> {
    axis.validate()?;
    let mut magnitude = Vec::with_capacity(omegas.len());
    let mut phase = Vec::with_capacity(omegas.len());
    for &w in omegas {
        check_omega(w)?;
        if w == 0.0 {
            magnitude.push(1.0);
            phase.push(0.0);
            continue;
        }
        let rest = response_without_smoothing_delay(axis, w);
        magnitude.push(rest.norm());
        phase.push(rest.arg() - 0.5 * w * axis.ts);
    }
    Ok(FrequencyResponse { magnitude, phase })
}

/// Steady ramp error per unit speed, `lim_{s→0}(1 − G(s))/s`, in s:
/// `Ts/2 + (1/T_v(0) − k)/Kpp` (see the module header).
fn ramp_lag_time(axis: &AxisParams) -> f64 {
    let tv0 = if axis.kvi > 0.0 {
        1.0
    } else {
        axis.kvp / (axis.kvp + axis.c)
    };
    0.5 * axis.ts + (1.0 / tv0 - axis.kffp / 100.0) / axis.kpp
}

/// Eq. 17: steady-state lag of the rotary axis under a ramp of speed ω,
/// `α_th = ω (Ts/2 + (1/T_v(0) − K_FFP/100)/Kpp)`.
///
/// # Units
/// ω in rad/s; α in rad.
///
/// # Examples
/// ```
/// use mtmotion::servo::response::alpha_th;
/// let mut c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
/// c.ts = 0.0; c.kffp = 80.0;
/// // With integral action α = ω (1 − K_FFP/100)/Kpp.
/// assert!((alpha_th(&c, 2.0).unwrap() - 2.0 * 0.2 / 60.0).abs() < 1e-15);
/// ```
pub fn alpha_th(axis: &AxisParams, omega: f64) -> Result<f64, ServoError> {
    axis.validate()?;
    if !omega.is_finite() {
        return Err(ServoError::BadParameter {
            field: "omega",
            value: omega,
            expected: "must be a finite angular velocity in rad/s",
        });
    }
    Ok(omega * ramp_lag_time(axis))
}

/// Eq. 18: phase lag `β_th = −∠G_L(jω)` of a linear axis on a circle.
///
/// # Units
/// ω in rad/s; β in rad.
///
/// # Examples
/// ```
/// use mtmotion::servo::response::beta_th;
/// let mut y = mtmotion::machine::preset("nmv5000").unwrap().axes["y"].clone();
/// y.ta = 0.0; y.tp = 0.0; y.kffp = 100.0;
/// // With full feedforward and a stiff velocity loop the lag is ≈ the smoothing delay Ts/2.
/// assert!((beta_th(&y, 1.0).unwrap() - 0.032).abs() < 1e-4);
/// ```
pub fn beta_th(axis: &AxisParams, omega: f64) -> Result<f64, ServoError> {
    let r = frequency_response(axis, &[omega])?;
    Ok(-r.phase[0])
}

/// Eq. 12: theoretical radius decrease `ΔR_th = (1 − |G_L(jω)|) R_W`.
///
/// # Units
/// ω in rad/s; `rw` and the result in mm (the paper's Eq. 12 reports µm).
///
/// # Examples
/// ```
/// use mtmotion::servo::response::radius_decrease_th;
/// let mut y = mtmotion::machine::preset("nmv5000").unwrap().axes["y"].clone();
/// y.ts = 0.0; y.ta = 0.0; y.tp = 0.0; y.kffp = 0.0; y.c = 0.0;
/// // Low ω, no feedforward: 1 − |G| ≈ ω² (1/(2 Kpp²) − J/(Kvp Kpp)).
/// let dr = radius_decrease_th(&y, 1.0, 8.0).unwrap();
/// let want = 8.0 * (1.0 / 7200.0 - 5.0 / (4700.0 * 60.0));
/// assert!((dr - want).abs() < 1e-6);
/// ```
pub fn radius_decrease_th(axis: &AxisParams, omega: f64, rw: f64) -> Result<f64, ServoError> {
    let r = frequency_response(axis, &[omega])?;
    Ok((1.0 - r.magnitude[0]) * rw)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine;

    fn c_axis() -> AxisParams {
        machine::preset("nmv5000").unwrap().axes["c"].clone()
    }

    /// Independent evaluation of the issue's G with polynomials in s
    /// (no Ts/Ta/Tp): G = N/D with N = (Kvp s + Kvi)(Kpp + k s),
    /// D = s² (J s + C) + (Kvp s + Kvi)(s + Kpp).
    fn g_polynomial(a: &AxisParams, w: f64) -> C64 {
        let s = C64::new(0.0, w);
        let k = a.kffp / 100.0;
        let pv_num = s * a.kvp + a.kvi;
        let n = pv_num * (s * k + a.kpp);
        let d = s * s * (s * a.inertia() + a.c) + pv_num * (s + a.kpp);
        n / d
    }

    #[test]
    fn matches_the_polynomial_form_without_delays() {
        for (name, kffp) in [("x", 0.0), ("y", 100.0), ("c", 73.0)] {
            let mut a = machine::preset("nmv5000").unwrap().axes[name].clone();
            a.ts = 0.0;
            a.ta = 0.0;
            a.tp = 0.0;
            a.kffp = kffp;
            for w in [0.1, 1.0, 10.0, 60.0, 300.0, 3000.0] {
                let g = closed_loop(&a, w).unwrap();
                let h = g_polynomial(&a, w);
                assert!(
                    (g - h).norm() < 1e-12 * (1.0 + h.norm()),
                    "{name} {w}: {g} vs {h}"
                );
            }
        }
    }

    #[test]
    fn smoothing_is_an_exact_moving_average() {
        let mut a = c_axis();
        let g0 = closed_loop(
            &AxisParams {
                ts: 0.0,
                ..a.clone()
            },
            7.0,
        )
        .unwrap();
        a.ts = 0.064;
        let g = closed_loop(&a, 7.0).unwrap();
        // A_Ts(j7) = (1 − e^{−j7·0.064})/(j7·0.064)
        let s = C64::new(0.0, 7.0);
        let avg = (C64::new(1.0, 0.0) - (-s * 0.064).exp()) / (s * 0.064);
        assert!((g - g0 * avg).norm() < 1e-14);
    }

    #[test]
    fn phase_is_continuous_past_minus_pi() {
        let mut a = c_axis();
        a.ts = 0.2;
        a.kffp = 0.0;
        // −ω Ts/2 = −3 and the position loop adds ≈ −atan(30/60)
        let r = frequency_response(&a, &[30.0]).unwrap();
        let g = closed_loop(&a, 30.0).unwrap();
        assert!(r.phase[0] < -3.2, "{}", r.phase[0]);
        assert!((C64::from_polar(r.magnitude[0], r.phase[0]) - g).norm() < 1e-12);
    }

    #[test]
    fn alpha_is_the_derivative_of_g_at_zero() {
        // 1 − G(jw) ≈ jw·lag for w far below every corner of the loop.
        for kvi in [0.0, 2000.0] {
            let mut a = c_axis();
            a.kffp = 85.0;
            a.kvi = kvi;
            let w = 1e-6;
            let g = closed_loop(&a, w).unwrap();
            let lag = (C64::new(1.0, 0.0) - g).im / w;
            let want = alpha_th(&a, 1.0).unwrap();
            assert!(
                (lag - want).abs() < 1e-4 * want,
                "kvi {kvi}: {lag} vs {want}"
            );
        }
    }

    #[test]
    fn bad_omega_is_rejected() {
        let e = frequency_response(&c_axis(), &[1.0, f64::NAN]).unwrap_err();
        assert!(e.to_string().contains("omega"));
    }
}
