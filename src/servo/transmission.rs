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
//!   The command is converted with `s_m`: `θ_ref = s_m·x_s`, and the
//!   mechanism below is written in the *nominal table position*
//!   `x = θm/s_m`, so the same mapping serves the servo model (`x` = the
//!   motor encoder over `s_m`) and an ideal servo (`x` = the command).
//! - **Eq. 1 reading.** kato writes `R = R_all + Σ W_i sin(N_i R_all θm + φ_i)`
//!   with `R` the reduction (table per motor) and `N_i` peaks per *table*
//!   revolution, so kato's `R_all` is table-per-motor, i.e.
//!   `1/gear_ratio` here. `R` is read as the *local* ratio
//!   `dθ_table/dθm` (taking `θ_table = R·θm` literally would make the error
//!   grow without bound with θm). Integrating, with `g = gear_ratio` and
//!   `x = θm/g`:
//!   `θ_gear = x − Σ (W_i g/N_i)[cos(N_i x + φ_i) − cos φ_i]`,
//!   a periodic pitch error of amplitude `W_i·g/N_i` rad at the table
//!   (`N_i = 0` gives the constant ratio change `W_i sin φ_i`, i.e.
//!   `θ_gear = x + W_i g sin φ_i · x`). The phase reference is `x = 0`.
//!   Pitch error is honoured for rotary axes only.
//! - **Additive reading** (`pitchReading: 'additive'`): W is the angle
//!   amplitude at the table, `θ_gear = x + Σ W_i [sin(N_i x + φ_i) − sin φ_i]`
//!   (referenced to 0 at x = 0 like the default); a measured spectrum
//!   ([`super::pitch_identify`]) gives these amplitudes directly. Entering
//!   them under the default reading would scale them by g/N.
//! - **Backlash** (full width `b`, table units) sits between the gear and
//!   the table as a play: the table stays put until the gear side has
//!   crossed the gap, then follows at `θ_gear ∓ b/2`. It starts centred
//!   (`θ_table = θ_gear` at t = 0), so the first motion loses `b/2`.
//!
//! This file is the only implementation of the mechanism: the ideal drive of
//! the cone-frustum test (`cone_frustum::drive::ideal`) uses it too.
//!
//! [`DriveErrors`] are a machine's backlash and pitch errors per axis
//! letter, as a test sets them on top of each axis' own parameters (the
//! cone-frustum test's `drives`); they belong to the drives, not to the
//! geometric error model, which never sees them.
//!
//! # Units
//! Motor angle in rad; nominal and table positions in mm (linear) or rad
//! (rotary); `s_m` in motor rad per mm or per rad.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::{AxisKind, AxisParams, PitchReading, ServoError, WormHarmonic};

/// The nominal scale `s_m`: motor rad per table unit (mm or rad).
///
/// # Units
/// Motor rad per mm (linear) or per rad (rotary).
///
/// # Examples
/// ```
/// use mtmotion::servo::transmission::motor_scale;
/// let x = mtmotion::machine::preset("nmv5000").unwrap().axes["x"].clone();
/// // 16 mm lead: one motor turn per 16 mm
/// assert!((motor_scale(&x).unwrap() - std::f64::consts::TAU / 16.0).abs() < 1e-15);
/// ```
pub fn motor_scale(axis: &AxisParams) -> Result<f64, ServoError> {
    let gear = axis.gear_ratio.unwrap_or(1.0);
    match (axis.kind, axis.lead) {
        (AxisKind::Linear, Some(lead)) => Ok(gear * std::f64::consts::TAU / (lead * 1000.0)),
        (AxisKind::Linear, None) => Err(ServoError::MissingParameter {
            field: "lead",
            why: "a linear axis needs its ball-screw lead in m",
        }),
        (AxisKind::Rotary, _) => Ok(gear),
    }
}

/// The mechanism after the motor of one axis (worm-gear pitch error, then
/// backlash) and its backlash state, driven by the nominal table position.
#[derive(Debug, Clone)]
pub struct Transmission {
    /// `(W g / N, N, φ)` per harmonic (argument `N x`), or for N = 0
    /// `(W g sin φ, 0, 0)` (a ratio change, linear in `x`).
    harmonics: Vec<(f64, f64, f64)>,
    half_gap: f64,
    table: Option<f64>,
}

impl Transmission {
    /// Builds the mechanism of `axis`, checking the fields it uses
    /// ([`AxisParams::validate_mechanism`]); the backlash starts centred.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::servo::transmission::Transmission;
    /// let mut c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
    /// c.backlash = 1e-3;
    /// let mut t = Transmission::new(&c).unwrap();
    /// assert_eq!(t.table(0.0), 0.0);
    /// // the first move loses half the gap
    /// assert!((t.table(0.01) - 0.0095).abs() < 1e-15);
    /// ```
    pub fn new(axis: &AxisParams) -> Result<Self, ServoError> {
        axis.validate_mechanism()?;
        let gear = axis.gear_ratio.unwrap_or(1.0);
        let harmonics = axis
            .pitch_error
            .iter()
            .map(|h| match axis.pitch_reading {
                PitchReading::GearRatio if h.n == 0.0 => (h.w * gear * h.phi.sin(), 0.0, 0.0),
                PitchReading::GearRatio => (h.w * gear / h.n, h.n, h.phi),
                // W sin(N x + φ) − W sin φ = −W[cos(N x + φ + π/2) − cos(φ + π/2)];
                // N = 0 is a constant, removed by the reference at x = 0
                PitchReading::Additive if h.n == 0.0 => (0.0, 0.0, 0.0),
                PitchReading::Additive => (h.w, h.n, h.phi + std::f64::consts::FRAC_PI_2),
            })
            .collect();
        Ok(Self {
            harmonics,
            half_gap: 0.5 * axis.backlash,
            table: None,
        })
    }

    /// Table position before the backlash (gear side) for the nominal
    /// table position `x = θm/s_m`.
    ///
    /// # Units
    /// `x` and the result in mm (linear) or rad (rotary).
    ///
    /// # Examples
    /// ```
    /// use mtmotion::servo::{transmission::Transmission, WormHarmonic};
    /// let mut c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
    /// c.gear_ratio = Some(90.0);
    /// c.pitch_error = vec![WormHarmonic { w: 1e-6, n: 2.0, phi: 0.0 }];
    /// let t = Transmission::new(&c).unwrap();
    /// // a quarter period (N x = π/2): −(W g/N)(cos(π/2) − 1) = +45 µrad
    /// let x = std::f64::consts::FRAC_PI_4;
    /// assert!((t.gear_side(x) - x - 4.5e-5).abs() < 1e-15);
    /// ```
    pub fn gear_side(&self, x: f64) -> f64 {
        let mut out = x;
        for &(amp, n, phi) in &self.harmonics {
            if n == 0.0 {
                out += amp * x;
            } else {
                out -= amp * ((n * x + phi).cos() - phi.cos());
            }
        }
        out
    }

    /// Table position for the nominal table position `x`, advancing the
    /// backlash state: the table stays put inside the gap, then follows the
    /// gear side at `∓b/2`.
    ///
    /// # Units
    /// `x` and the result in mm (linear) or rad (rotary).
    ///
    /// # Examples
    /// ```
    /// use mtmotion::servo::transmission::Transmission;
    /// let mut c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
    /// c.backlash = 0.2;
    /// let mut t = Transmission::new(&c).unwrap();
    /// let out: Vec<f64> = [0.0, 0.05, 0.3, 0.5, 0.4, 0.2].iter().map(|&x| t.table(x)).collect();
    /// for (o, w) in out.iter().zip([0.0, 0.0, 0.2, 0.4, 0.4, 0.3]) {
    ///     assert!((o - w).abs() < 1e-15, "{out:?}");
    /// }
    /// ```
    pub fn table(&mut self, x: f64) -> f64 {
        let g = self.gear_side(x);
        let t = match self.table {
            None => g,
            Some(p) if g - p > self.half_gap => g - self.half_gap,
            Some(p) if p - g > self.half_gap => g + self.half_gap,
            Some(p) => p,
        };
        self.table = Some(t);
        t
    }

    /// Whether the mechanism is the identity (no pitch error, no backlash).
    pub fn is_rigid(&self) -> bool {
        self.harmonics.is_empty() && self.half_gap == 0.0
    }
}

/// A machine's drive errors per axis letter (kato Eq. 1, Fig. 2): backlash
/// and worm-gear pitch error. They depend on the motion history, so they
/// act through each axis' [`Transmission`], not through the static
/// geometry. Keys are axis letters (`x` … `c`, either case).
///
/// # Units
/// Backlash (full width) in mm on a linear axis, rad on a rotary one;
/// pitch-error harmonics as [`WormHarmonic`].
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct DriveErrors {
    /// Backlash per axis letter (full width; mm or rad).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub backlash: BTreeMap<String, f64>,
    /// Worm-gear pitch-error harmonics per rotary axis (kato Eq. 1).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub pitch_error: BTreeMap<String, Vec<WormHarmonic>>,
}

impl DriveErrors {
    /// True when nothing is set.
    pub fn is_zero(&self) -> bool {
        self.backlash.values().all(|v| *v == 0.0) && self.pitch_error.values().all(|v| v.is_empty())
    }

    /// Checks the keys and values against the axes the machine has
    /// (`present`, lower-case letters): backlash widths ≥ 0 on those axes,
    /// pitch errors on its rotary axes with finite harmonics. Errors name
    /// the key, e.g. `backlash.q`.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::servo::transmission::DriveErrors;
    /// let mut d = DriveErrors::default();
    /// d.backlash.insert("c".into(), 1e-4);
    /// assert!(d.validate(&["x", "y", "z", "a", "c"]).is_ok());
    /// d.backlash.insert("b".into(), 1e-4);
    /// let e = d.validate(&["x", "y", "z", "a", "c"]).unwrap_err().to_string();
    /// assert!(e.contains("backlash.b") && e.contains("no B axis"), "{e}");
    /// ```
    pub fn validate(&self, present: &[&str]) -> Result<(), ServoError> {
        for (key, v) in &self.backlash {
            let field = format!("backlash.{key}");
            let axis = crate::axes::index(key)
                .ok_or_else(|| bad(&field, "expected an axis letter x, y, z, a, b or c"))?;
            check_axis(present, &field, axis)?;
            if !(v.is_finite() && *v >= 0.0) {
                return Err(bad(
                    &field,
                    "must be a finite width ≥ 0 (mm for linear, rad for rotary axes)",
                ));
            }
        }
        for (key, hs) in &self.pitch_error {
            let field = format!("pitchError.{key}");
            let axis = crate::axes::index(key)
                .filter(|a| *a >= 3)
                .ok_or_else(|| bad(&field, "expected a rotary axis letter a, b or c"))?;
            check_axis(present, &field, axis)?;
            for (i, h) in hs.iter().enumerate() {
                if !(h.w.is_finite() && h.n.is_finite() && h.phi.is_finite()) {
                    return Err(bad(
                        &format!("{field}[{i}]"),
                        "w, n and phi must be finite numbers",
                    ));
                }
            }
        }
        Ok(())
    }

    /// `params` of the axis `letter` with this set's backlash and pitch
    /// error in place of its own, where the set gives them (keys in either
    /// case).
    ///
    /// # Examples
    /// ```
    /// use mtmotion::servo::transmission::DriveErrors;
    /// let c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
    /// let mut d = DriveErrors::default();
    /// d.backlash.insert("C".into(), 2e-4);
    /// assert_eq!(d.applied_to("c", c.clone()).backlash, 2e-4);
    /// assert_eq!(d.applied_to("x", c).backlash, 0.0);
    /// ```
    pub fn applied_to(&self, letter: &str, mut params: AxisParams) -> AxisParams {
        let mine = |k: &String| k.eq_ignore_ascii_case(letter);
        if let Some((_, b)) = self.backlash.iter().find(|(k, _)| mine(k)) {
            params.backlash = *b;
        }
        if let Some((_, h)) = self.pitch_error.iter().find(|(k, _)| mine(k)) {
            params.pitch_error = h.clone();
        }
        params
    }
}

fn bad(key: &str, why: &str) -> ServoError {
    ServoError::BadDriveError {
        key: key.to_string(),
        why: why.to_string(),
    }
}

/// A drive error on an axis the machine does not have is refused, naming the key.
fn check_axis(present: &[&str], key: &str, axis: usize) -> Result<(), ServoError> {
    crate::axes::require(present, axis).map_err(|why| bad(key, &why))
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
        let sm = motor_scale(&a).unwrap();
        for tm in [0.0, 1.0, 50.0, 300.0] {
            let h = 1e-4;
            let d = (t.gear_side((tm + h) / sm) - t.gear_side((tm - h) / sm)) / (2.0 * h);
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
        let p1 = t.table(0.09); // +0.09 rad at the gear side
        let p2 = t.table(0.0885); // back 0.0015: inside the gap
        let p3 = t.table(0.0); // back to 0
        assert_eq!(p0, 0.0);
        assert!((p1 - 0.089).abs() < 1e-12);
        assert!((p2 - 0.089).abs() < 1e-12);
        assert!((p3 - 0.001).abs() < 1e-12);
    }

    #[test]
    fn linear_scale_is_the_lead() {
        let x = crate::machine::preset("nmv5000").unwrap().axes["x"].clone();
        // one motor turn = one lead = 16 mm
        assert!((std::f64::consts::TAU / motor_scale(&x).unwrap() - 16.0).abs() < 1e-12);
        let mut t = Transmission::new(&x).unwrap();
        assert!(t.is_rigid());
        assert_eq!(t.table(16.0), 16.0);
    }
}
