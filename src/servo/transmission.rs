//! Motor-to-table transmission: ball screw, direct drive or worm gear with
//! pitch error (kato-cone-frustum-ballbar Eq. 1, Fig. 2), then backlash.
//!
//! The loop is semi-closed (kato Fig. 2: the position is fed back from the
//! motor encoder), so the transmission sits *after* the loop: backlash and
//! pitch error reach the table but the servo neither sees nor corrects them,
//! and the load inertia `j1` is carried rigidly by the motor.
//!
//! - Nominal scale `s_m` (motor rad per table unit): `R_all = gear_ratio`
//!   (1 for a direct drive) for rotary axes; `gear_ratio·2π/(lead·1000)`
//!   for linear axes (table in mm, `lead` in m, `gear_ratio` 1 if absent).
//!   The command is converted with `s_m`: `θ_ref = s_m·x_s`.
//! - **Eq. 1 reading.** kato writes `R = R_all + Σ W_i sin(N_i R_all θm + φ_i)`
//!   with `R` the reduction (table per motor) and `N_i` peaks per *table*
//!   revolution, so kato's `R_all` is table-per-motor, i.e.
//!   `1/gear_ratio` here. `R` is read as the *local* ratio
//!   `dθ_table/dθm` (taking `θ_table = R·θm` literally would make the error
//!   grow without bound with θm). Integrating, with `g = gear_ratio`:
//!   `θ_gear = θm/g − Σ (W_i g/N_i)[cos(N_i θm/g + φ_i) − cos φ_i]`,
//!   a periodic pitch error of amplitude `W_i·g/N_i` rad at the table
//!   (`N_i = 0` gives the constant ratio change `W_i sin φ_i`).
//!   Pitch error is honoured for rotary axes only.
//! - **Backlash** (full width `b`, table units) sits between the gear and
//!   the table as a play: the table stays put until the gear side has
//!   crossed the gap, then follows at `θ_gear ∓ b/2`. It starts centred
//!   (`θ_table = θ_gear` at t = 0), so the first motion loses `b/2`.
//!
//! # Units
//! Motor angle in rad; table in mm (linear) or rad (rotary).

use super::{AxisKind, AxisParams, ServoError};

/// The transmission of one axis and its backlash state.
#[derive(Debug, Clone)]
pub(crate) struct Transmission {
    /// Motor rad per table unit (nominal).
    pub scale: f64,
    gear: f64,
    /// `(W g / N, N / g, φ)` per harmonic, or for N = 0 `(W sin φ, 0, 0)`.
    harmonics: Vec<(f64, f64, f64)>,
    half_gap: f64,
    table: Option<f64>,
}

impl Transmission {
    /// Builds the transmission; `axis` must already be valid.
    pub(crate) fn new(axis: &AxisParams) -> Result<Self, ServoError> {
        let gear = axis.gear_ratio.unwrap_or(1.0);
        let scale = match (axis.kind, axis.lead) {
            (AxisKind::Linear, Some(lead)) => gear * std::f64::consts::TAU / (lead * 1000.0),
            (AxisKind::Linear, None) => {
                return Err(ServoError::MissingParameter {
                    field: "lead",
                    why: "a linear axis needs its ball-screw lead in m",
                })
            }
            (AxisKind::Rotary, _) => gear,
        };
        if axis.kind == AxisKind::Linear && !axis.pitch_error.is_empty() {
            return Err(ServoError::BadParameter {
                field: "pitchError",
                value: axis.pitch_error.len() as f64,
                expected: "worm-gear pitch error applies to rotary axes only; remove it",
            });
        }
        let mut harmonics = Vec::with_capacity(axis.pitch_error.len());
        for h in &axis.pitch_error {
            for (field, v) in [("pitchError.w", h.w), ("pitchError.phi", h.phi)] {
                if !v.is_finite() {
                    return Err(ServoError::BadParameter {
                        field,
                        value: v,
                        expected: "must be a finite number",
                    });
                }
            }
            if !(h.n.is_finite() && h.n >= 0.0) {
                return Err(ServoError::BadParameter {
                    field: "pitchError.n",
                    value: h.n,
                    expected: "peaks per table revolution must be ≥ 0",
                });
            }
            if h.n == 0.0 {
                harmonics.push((h.w * h.phi.sin(), 0.0, 0.0));
            } else {
                harmonics.push((h.w * gear / h.n, h.n / gear, h.phi));
            }
        }
        Ok(Self {
            scale,
            gear,
            harmonics,
            half_gap: 0.5 * axis.backlash,
            table: None,
        })
    }

    /// Table position before the backlash for motor angle `theta_m`.
    pub(crate) fn gear_side(&self, theta_m: f64) -> f64 {
        let mut out = theta_m / self.scale;
        for &(amp, rate, phi) in &self.harmonics {
            if rate == 0.0 {
                out += amp * theta_m;
            } else {
                out -= amp * ((rate * theta_m + phi).cos() - phi.cos());
            }
        }
        out
    }

    /// Table position for motor angle `theta_m`, advancing the backlash state.
    pub(crate) fn table(&mut self, theta_m: f64) -> f64 {
        let g = self.gear_side(theta_m);
        let t = match self.table {
            None => g,
            Some(p) if g - p > self.half_gap => g - self.half_gap,
            Some(p) if p - g > self.half_gap => g + self.half_gap,
            Some(p) => p,
        };
        self.table = Some(t);
        t
    }

    /// Whether the transmission is the identity up to `scale`.
    pub(crate) fn is_rigid(&self) -> bool {
        self.harmonics.is_empty() && self.half_gap == 0.0
    }

    /// The nominal gear ratio `R_all` (motor per table), 1 for direct drive.
    #[allow(dead_code)]
    pub(crate) fn gear(&self) -> f64 {
        self.gear
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::servo::WormHarmonic;

    fn worm() -> AxisParams {
        let mut a = crate::machine::preset("nmv5000").unwrap().axes["c"].clone();
        a.gear_ratio = Some(90.0);
        a
    }

    #[test]
    fn local_ratio_is_eq_1() {
        let mut a = worm();
        a.pitch_error = vec![WormHarmonic {
            w: 1e-5,
            n: 4.0,
            phi: 0.3,
        }];
        let t = Transmission::new(&a).unwrap();
        // dθ_table/dθm = 1/R_all' + W sin(N θm/g + φ) (central difference)
        for tm in [0.0, 1.0, 50.0, 300.0] {
            let h = 1e-4;
            let d = (t.gear_side(tm + h) - t.gear_side(tm - h)) / (2.0 * h);
            let want = 1.0 / 90.0 + 1e-5 * (4.0 * tm / 90.0 + 0.3).sin();
            assert!((d - want).abs() < 1e-10, "{d} vs {want}");
        }
        assert!(t.gear_side(0.0).abs() < 1e-18);
    }

    #[test]
    fn backlash_loses_the_gap_on_reversal() {
        let mut a = worm();
        a.backlash = 0.002;
        let mut t = Transmission::new(&a).unwrap();
        let p0 = t.table(0.0);
        let p1 = t.table(0.09 * 90.0); // +0.09 rad at the gear side
        let p2 = t.table(0.0885 * 90.0); // back 0.0015: inside the gap
        let p3 = t.table(0.0); // back to 0
        assert_eq!(p0, 0.0);
        assert!((p1 - 0.089).abs() < 1e-12);
        assert!((p2 - 0.089).abs() < 1e-12);
        assert!((p3 - 0.001).abs() < 1e-12);
    }

    #[test]
    fn linear_scale_is_the_lead() {
        let x = crate::machine::preset("nmv5000").unwrap().axes["x"].clone();
        let t = Transmission::new(&x).unwrap();
        // one motor turn = one lead = 16 mm
        assert!((t.gear_side(std::f64::consts::TAU) - 16.0).abs() < 1e-12);
    }
}
