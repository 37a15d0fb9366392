//! PID position loop of a feed drive (thasana-htm-nc-compensation §II-D 2,
//! Eq. 9, Fig. 8).
//!
//! Plant (Eq. 9, no disturbance torque `T_d`): `ω = K_t K_a u/(J s + B)`,
//! `x = (r_g/s) ω`, i.e. `x'' = k u − a x'` with `k = r_g K_t K_a/J` and
//! `a = B/J`. Controller (Fig. 8, Simulink's parallel PID with derivative
//! filter): `u = P e + I ∫e + D N (e − f)`, `f' = N (e − f)`, `e = r − x`,
//! i.e. `C(s) = P + I/s + D N s/(s + N)`. The paper's tuned gains are
//! P = 2, I = 2, D = 0.5, N = 100 ([`PidDrive::paper`]).
//!
//! # Reading: the plant
//! The paper takes its motor parameters from its reference \[37\] and does not
//! print them, so `k` and `a` are inputs. [`PidDrive::paper`] uses the unit
//! plant `k = 1 s⁻²`, `a = 1 s⁻¹`; every figure obtained with it (its
//! effect on the S-shape, `docs/readings.md`) holds for that reading only.
//!
//! # Discretisation
//! State `z = [x, x', ∫e, f]`, input `r` piecewise linear between samples
//! (first-order hold); one step is exact: `z₁ = Φ z₀ + Γ₀ r₀ + Γ₁ (r₁ − r₀)`
//! from the exponential of the augmented matrix `[[A, b, 0], [0, 0, 1],
//! [0, 0, 0]]·dt` (as [`super::discrete`] does for the cascaded loop).
//!
//! # Units
//! x and r in mm (linear) or rad (rotary); k per s² per unit of u; a, N in
//! 1/s; I in 1/s; D in s; dt in s.

use nalgebra::{Complex, SMatrix};
use serde::{Deserialize, Serialize};

use super::ServoError;

/// A PID feed drive.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct PidDrive {
    /// Proportional gain P.
    pub p: f64,
    /// Integral gain I, 1/s.
    pub i: f64,
    /// Derivative gain D, s.
    pub d: f64,
    /// Derivative filter coefficient N, 1/s.
    pub n: f64,
    /// Plant gain `k = r_g K_t K_a/J`, 1/s² per unit of u.
    pub k: f64,
    /// Plant damping `a = B/J`, 1/s.
    pub a: f64,
}

impl PidDrive {
    /// thasana's tuned gains (P 2, I 2, D 0.5, N 100) on the unit plant
    /// (the reading in the module header).
    pub fn paper() -> Self {
        Self {
            p: 2.0,
            i: 2.0,
            d: 0.5,
            n: 100.0,
            k: 1.0,
            a: 1.0,
        }
    }

    /// Checks every field.
    ///
    /// # Errors
    /// [`ServoError::BadParameter`] naming the field.
    pub fn validate(&self) -> Result<(), ServoError> {
        let bad = |field, value, expected| {
            Err(ServoError::BadParameter {
                field,
                value,
                expected,
            })
        };
        for (f, v) in [
            ("pid.p", self.p),
            ("pid.i", self.i),
            ("pid.d", self.d),
            ("pid.a", self.a),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(f, v, "must be a finite number ≥ 0");
            }
        }
        if !(self.n.is_finite() && self.n > 0.0) {
            return bad(
                "pid.n",
                self.n,
                "the derivative filter coefficient must be > 0 1/s",
            );
        }
        if !(self.k.is_finite() && self.k > 0.0) {
            return bad("pid.k", self.k, "the plant gain must be > 0");
        }
        Ok(())
    }

    fn matrices(&self) -> (SMatrix<f64, 4, 4>, SMatrix<f64, 4, 1>) {
        let (p, i, d, n, k, a) = (self.p, self.i, self.d, self.n, self.k, self.a);
        let pd = p + d * n;
        let am = SMatrix::<f64, 4, 4>::from_row_slice(&[
            0.0,
            1.0,
            0.0,
            0.0, //
            -k * pd,
            -a,
            k * i,
            -k * d * n, //
            -1.0,
            0.0,
            0.0,
            0.0, //
            -n,
            0.0,
            0.0,
            -n,
        ]);
        let b = SMatrix::<f64, 4, 1>::from_column_slice(&[0.0, k * pd, 1.0, n]);
        (am, b)
    }

    /// Closed-loop response `X/R` at `s = jω` (the independent check of
    /// [`simulate_pid`]).
    pub fn response(&self, omega: f64) -> Complex<f64> {
        let s = Complex::new(0.0, omega);
        let c = self.p + self.i / s + self.d * self.n * s / (s + self.n);
        let plant = self.k / (s * (s + self.a));
        c * plant / (1.0 + c * plant)
    }
}

/// Simulates the drive following `command` (one sample per `dt`, starting
/// at rest on `command[0]`); returns the position at each sample.
///
/// # Errors
/// Bad parameters, a bad `dt` or a non-finite command sample.
///
/// # Examples
/// ```
/// use mtmotion::servo::pid::{simulate_pid, PidDrive};
/// // a step of 1 mm settles on 1 mm (slowest poles −0.146 ± 1.28j:
/// // e^{−0.146·200} ≈ 2e-13 after 200 s)
/// let mut c = vec![1.0; 200_000];
/// c[0] = 0.0;
/// let x = simulate_pid(&PidDrive::paper(), 1e-3, &c).unwrap();
/// assert!((x[199_999] - 1.0).abs() < 1e-9);
/// ```
pub fn simulate_pid(drive: &PidDrive, dt: f64, command: &[f64]) -> Result<Vec<f64>, ServoError> {
    drive.validate()?;
    if !(dt.is_finite() && dt > 0.0) {
        return Err(ServoError::BadParameter {
            field: "dt",
            value: dt,
            expected: "the time step must be a finite number > 0 s",
        });
    }
    if let Some(i) = command.iter().position(|v| !v.is_finite()) {
        return Err(ServoError::BadCommand {
            index: i,
            why: "the position command must be a finite number",
        });
    }
    let Some(&r0) = command.first() else {
        return Ok(Vec::new());
    };
    let (am, b) = drive.matrices();
    let mut m = SMatrix::<f64, 6, 6>::zeros();
    m.fixed_view_mut::<4, 4>(0, 0).copy_from(&am);
    m.fixed_view_mut::<4, 1>(0, 4).copy_from(&b);
    m[(4, 5)] = 1.0;
    let e = super::discrete::expm(&(m * dt));
    let phi = e.fixed_view::<4, 4>(0, 0).into_owned();
    let g0 = e.fixed_view::<4, 1>(0, 4).into_owned();
    let g1 = e.fixed_view::<4, 1>(0, 5).into_owned() / dt;
    // at rest on the first sample: x = r0, f = e = 0
    let mut z = SMatrix::<f64, 4, 1>::from_column_slice(&[r0, 0.0, 0.0, 0.0]);
    let mut out = Vec::with_capacity(command.len());
    out.push(r0);
    for w in command.windows(2) {
        z = phi * z + g0 * w[0] + g1 * (w[1] - w[0]);
        out.push(z[0]);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The step's exponential (`discrete::expm`, scaling and squaring of a
    /// Taylor series) agrees with nalgebra's Padé to 1e-13 of its norm for
    /// the paper's gains and for stiff ones, at 0.1 ms to 10 ms.
    #[test]
    fn step_exponential_agrees_with_nalgebra_pade() {
        let stiff = PidDrive {
            p: 400.0,
            i: 50.0,
            d: 3.0,
            n: 2000.0,
            k: 50.0,
            a: 20.0,
        };
        for drive in [PidDrive::paper(), stiff] {
            let (am, b) = drive.matrices();
            let mut m = SMatrix::<f64, 6, 6>::zeros();
            m.fixed_view_mut::<4, 4>(0, 0).copy_from(&am);
            m.fixed_view_mut::<4, 1>(0, 4).copy_from(&b);
            m[(4, 5)] = 1.0;
            for dt in [1e-4, 1e-3, 1e-2] {
                let ours = crate::servo::discrete::expm(&(m * dt));
                let pade = (m * dt).exp();
                let err = (ours - pade).norm() / pade.norm();
                assert!(err < 1e-13, "dt {dt}: {err:e}");
            }
        }
    }
}
