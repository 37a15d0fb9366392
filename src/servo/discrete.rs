//! Exact discretisation of the cascaded feed-drive loop (suzuki-best-kffp
//! Fig. 11 and Fig. 18) for a fixed step.
//!
//! State `z = [θ, ω, I]` at the motor: angle (rad), speed (rad/s) and the
//! velocity-error integral `I = ∫e dt` (rad). Inputs `u = [r, f]`: the
//! position reference `r` (motor rad) and the scaled feedforward
//! `f = k·v_ff` (rad/s). With `e = Kpp (r − θ) + f − ω` and
//! `τ = Kvp e + Kvi I`:
//!
//! - unsaturated: `θ' = ω`, `J ω' = τ − C ω`, `I' = e`, i.e.
//!   `z' = A z + B u`. The inputs are piecewise linear between samples
//!   (first-order hold, as [`super::precontrol`] builds them), so one step is
//!   `z₁ = Φ z₀ + Γ₀ u₀ + Γ₁ (u₁ − u₀)` with `Φ = e^{A dt}` and the Γ's read
//!   from the exponential of the augmented matrix `[[A, B, 0], [0, 0, I], [0, 0, 0]]·dt`.
//!   This is exact for the linear loop — no Euler.
//! - saturated (Fig. 18): `J ω' = ±τ_max − C ω` solved in closed form over
//!   the step; the integrator is **clamped** (held) while the torque command
//!   is beyond the limit, the anti-windup chosen here.
//!
//! The mode is decided from the torque command at the start of each step.
//!
//! # Units
//! J in kg·m², C in N·m·s/rad, Kvp in N·m·s/rad, Kvi in N·m/rad, Kpp in 1/s,
//! dt in s, torque in N·m.

use nalgebra::SMatrix;

use super::AxisParams;

/// One step of the loop, precomputed for a given `dt`.
#[derive(Debug, Clone)]
pub(crate) struct LoopStep {
    phi: [[f64; 3]; 3],
    g0: [[f64; 2]; 3],
    g1: [[f64; 2]; 3],
    kpp: f64,
    kvp: f64,
    kvi: f64,
    inertia: f64,
    /// `(1 − e^{−a dt})/a` and `(dt − φ1)/a`, `a = C/J`.
    phi1: f64,
    phi2: f64,
    decay: f64,
    /// State change over one step per N·m of constant load torque
    /// (friction, gravity: kato Fig. 2), `∫ e^{Aσ} b_d dσ`, `b_d = [0, −1/J, 0]`.
    gd: [f64; 3],
}

impl LoopStep {
    /// `axis` must be valid and `dt > 0`.
    pub(crate) fn new(axis: &AxisParams, dt: f64) -> Self {
        let jt = axis.inertia();
        let (kpp, kvp, kvi, c) = (axis.kpp, axis.kvp, axis.kvi, axis.c);
        let m = augmented(axis);
        // The load-torque input (friction, gravity): a fourth column that
        // enters the velocity row with −1/J.
        let mut md = SMatrix::<f64, 4, 4>::zeros();
        md.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&m.fixed_view::<3, 3>(0, 0));
        md[(1, 3)] = -1.0 / jt;
        let ed = expm(&(md * dt));
        let gd = [ed[(0, 3)], ed[(1, 3)], ed[(2, 3)]];
        let e = expm(&(m * dt));
        let mut phi = [[0.0; 3]; 3];
        let mut g0 = [[0.0; 2]; 3];
        let mut g1 = [[0.0; 2]; 3];
        for i in 0..3 {
            for j in 0..3 {
                phi[i][j] = e[(i, j)];
            }
            for j in 0..2 {
                g0[i][j] = e[(i, 3 + j)];
                // e[(i, 5 + j)] = ∫ e^{A(dt−σ)} B σ dσ; per unit of (u₁ − u₀)/dt
                g1[i][j] = e[(i, 5 + j)] / dt;
            }
        }
        let a = c / jt;
        let x = a * dt;
        let (phi1, phi2) = if x < 1e-4 {
            (
                dt * (1.0 - x / 2.0 + x * x / 6.0),
                dt * dt * (0.5 - x / 6.0 + x * x / 24.0),
            )
        } else {
            let p1 = -(-x).exp_m1() / a;
            (p1, (dt - p1) / a)
        };
        Self {
            phi,
            g0,
            g1,
            kpp,
            kvp,
            kvi,
            inertia: jt,
            phi1,
            phi2,
            decay: (-x).exp(),
            gd,
        }
    }

    /// Torque command `τ = Kvp e + Kvi I` for state `z` and inputs `r`, `f`.
    #[inline]
    pub(crate) fn torque(&self, z: &[f64; 3], r: f64, f: f64) -> f64 {
        let e = self.kpp * (r - z[0]) + f - z[1];
        self.kvp * e + self.kvi * z[2]
    }

    /// Unsaturated step from inputs `u0` to `u1`.
    ///
    /// Written out row by row so the state stays in registers and the
    /// dependency chain from `z` to the next `z` is one multiply and two
    /// adds: the input terms, which do not depend on `z`, are summed first.
    #[inline]
    pub(crate) fn linear(&self, z: &mut [f64; 3], u0: [f64; 2], u1: [f64; 2]) {
        let (r0, f0) = (u0[0], u0[1]);
        let (dr, df) = (u1[0] - r0, u1[1] - f0);
        let (p, a, b) = (&self.phi, &self.g0, &self.g1);
        let row = |i: usize| (a[i][0] * r0 + a[i][1] * f0) + (b[i][0] * dr + b[i][1] * df);
        let (w0, w1, w2) = (row(0), row(1), row(2));
        let [z0, z1, z2] = *z;
        *z = [
            (p[0][0] * z0 + p[0][1] * z1) + (p[0][2] * z2 + w0),
            (p[1][0] * z0 + p[1][1] * z1) + (p[1][2] * z2 + w1),
            (p[2][0] * z0 + p[2][1] * z1) + (p[2][2] * z2 + w2),
        ];
    }

    /// Adds the effect of a load torque `d` (N·m, opposing positive motion)
    /// held constant over the unsaturated step just taken (superposition).
    #[inline]
    pub(crate) fn load(&self, z: &mut [f64; 3], d: f64) {
        for (zi, g) in z.iter_mut().zip(&self.gd) {
            *zi += g * d;
        }
    }

    /// Saturated step with constant motor torque `tau` (net of any load
    /// torque); the integrator is held.
    #[inline]
    pub(crate) fn saturated(&self, z: &mut [f64; 3], tau: f64) {
        let acc = tau / self.inertia;
        let (th, om) = (z[0], z[1]);
        z[0] = th + om * self.phi1 + acc * self.phi2;
        z[1] = om * self.decay + acc * self.phi1;
    }
}

/// The augmented matrix `[[A, B, 0], [0, 0, I], [0, 0, 0]]` (per second).
fn augmented(axis: &AxisParams) -> SMatrix<f64, 7, 7> {
    let jt = axis.inertia();
    let (kpp, kvp, kvi, c) = (axis.kpp, axis.kvp, axis.kvi, axis.c);
    let mut m = SMatrix::<f64, 7, 7>::zeros();
    // A
    m[(0, 1)] = 1.0;
    m[(1, 0)] = -kvp * kpp / jt;
    m[(1, 1)] = -(kvp + c) / jt;
    m[(1, 2)] = kvi / jt;
    m[(2, 0)] = -kpp;
    m[(2, 1)] = -1.0;
    // B (columns r, f)
    m[(1, 3)] = kvp * kpp / jt;
    m[(1, 4)] = kvp / jt;
    m[(2, 3)] = kpp;
    m[(2, 4)] = 1.0;
    // input slopes
    m[(3, 5)] = 1.0;
    m[(4, 6)] = 1.0;
    m
}

/// `e^M` by scaling and squaring with a truncated Taylor series: `M` is
/// scaled by `2^-s` until its 1-norm is at most ½, the series of `e^A − I`
/// is summed until a term no longer changes the sum (at most 30 terms; the
/// remainder after k terms is below `½^k/k!`), and squared `s` times in the
/// form `(I + X)² = I + 2X + X²` (Higham's accurate squaring of `e^A − I`).
/// Replaces nalgebra's general `Matrix::exp` (a 13th-order Padé with an LU
/// solve), which alone took about 60 KB of the wasm; the unit test checks the
/// two agree to 1e-13 of the result's norm.
pub(crate) fn expm<const N: usize>(m: &SMatrix<f64, N, N>) -> SMatrix<f64, N, N> {
    let norm = (0..N)
        .map(|j| m.column(j).iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut s = 0;
    while norm / f64::powi(2.0, s) > 0.5 && s < 1000 {
        s += 1;
    }
    let a = m / f64::powi(2.0, s);
    // X = e^A − I (no identity in the sum, so small entries keep their
    // precision), then squared as (I + X)² = I + (2X + X²).
    let mut x = SMatrix::<f64, N, N>::zeros();
    let mut term = SMatrix::<f64, N, N>::identity();
    for k in 1..=30 {
        term = term * a / k as f64;
        let before = x;
        x += term;
        if x == before {
            break;
        }
    }
    for _ in 0..s {
        x = x * 2.0 + x * x;
    }
    x + SMatrix::<f64, N, N>::identity()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine;

    #[test]
    fn expm_agrees_with_nalgebra_pade() {
        // The loop's augmented matrix for every preset axis at 0.1 ms and
        // 10 ms, against nalgebra's Padé exponential (a second method).
        for name in machine::names() {
            let m = machine::preset(name).unwrap();
            for axis in m.axes.values() {
                for dt in [1e-4, 1e-2] {
                    let a = augmented(axis);
                    let ours = expm(&(a * dt));
                    let pade = (a * dt).exp();
                    let err = (ours - pade).abs().max();
                    assert!(err <= 1e-13 * pade.abs().max(), "{name}: {err}");
                }
            }
        }
        // Analytic: a rotation generator, e^{[[0, -t], [t, 0]]} = R(t).
        let t = 2.5;
        let r = expm(&SMatrix::<f64, 2, 2>::new(0.0, -t, t, 0.0));
        let exact = SMatrix::<f64, 2, 2>::new(t.cos(), -t.sin(), t.sin(), t.cos());
        assert!((r - exact).abs().max() < 1e-14);
    }

    #[test]
    fn saturated_step_matches_the_closed_form() {
        let mut c = machine::preset("nmv5000").unwrap().axes["c"].clone();
        c.j1 = 1.7;
        let dt = 0.01;
        let s = LoopStep::new(&c, dt);
        let mut z = [0.1, 2.0, 0.3];
        s.saturated(&mut z, 725.0);
        // ω(t) = ω∞ + (ω0 − ω∞) e^{−at}, ω∞ = τ/C
        let (a, winf) = (5.0 / 5.9, 725.0 / 5.0);
        let w = winf + (2.0 - winf) * (-a * dt).exp();
        let th = 0.1 + winf * dt + (2.0 - winf) * (1.0 - (-a * dt).exp()) / a;
        assert!((z[1] - w).abs() < 1e-12 && (z[0] - th).abs() < 1e-12 && z[2] == 0.3);
    }

    #[test]
    fn linear_step_holds_a_steady_state() {
        // At rest on the reference, with no feedforward, nothing moves.
        let y = machine::preset("nmv5000").unwrap().axes["y"].clone();
        let s = LoopStep::new(&y, 1e-3);
        let mut z = [2.0, 0.0, 0.0];
        for _ in 0..100 {
            s.linear(&mut z, [2.0, 0.0], [2.0, 0.0]);
        }
        assert!((z[0] - 2.0).abs() < 1e-12 && z[1].abs() < 1e-12);
    }
}
