//! Parameter set of one feed-drive axis (suzuki-best-kffp Table 1;
//! kato-cone-frustum-ballbar Eq. 1 for the worm gear).
//!
//! The field names are the JS contract (`machinePreset('nmv5000').axes.c`).

use serde::{Deserialize, Serialize};

use super::ServoError;

/// Linear (ball screw) or rotary (direct drive or worm gear) axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AxisKind {
    /// Linear axis; position in mm.
    Linear,
    /// Rotary axis; position in rad.
    Rotary,
}

/// One harmonic of the worm-gear pitch error, kato Eq. 1:
/// `R = R_all + Σ W_i sin(N_i R_all θm + φ_i)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct WormHarmonic {
    /// Amplitude `W_i` of the ratio ripple (dimensionless, like `R`).
    pub w: f64,
    /// Order `N_i` (cycles per output revolution).
    pub n: f64,
    /// Phase `φ_i` in rad.
    pub phi: f64,
}

/// Parameters of one axis, in SI units (see the module header).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct AxisParams {
    /// Linear or rotary.
    pub kind: AxisKind,
    /// Equivalent inertia of the mechanism at the motor, kg·m².
    pub j: f64,
    /// Load inertia, kg·m² (Table 1: set per test; 0 when none).
    #[serde(default)]
    pub j1: f64,
    /// Viscous damping, N·m·s/rad.
    pub c: f64,
    /// Position proportional gain, 1/s.
    pub kpp: f64,
    /// Velocity proportional gain, N·m·s/rad.
    pub kvp: f64,
    /// Velocity integral gain (reading stated in `servo::response`).
    pub kvi: f64,
    /// Pre-Control feedforward coefficient, %.
    pub kffp: f64,
    /// Smoothing time constant (moving-average length), s.
    pub ts: f64,
    /// Averaging time constant of the feedforward, s.
    pub ta: f64,
    /// Preceding (read-ahead) time of the feedforward, s.
    pub tp: f64,
    /// Torque limit, N·m; `None` for no saturation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque_max: Option<f64>,
    /// Ball-screw lead, m (linear axes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lead: Option<f64>,
    /// Worm-gear reduction ratio `R_all` (motor rev per output rev); `None`
    /// for a direct drive.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gear_ratio: Option<f64>,
    /// Backlash (full width): mm for linear axes, rad for rotary axes.
    #[serde(default)]
    pub backlash: f64,
    /// Worm-gear pitch-error harmonics (kato Eq. 1); at most
    /// [`crate::budget::MAX_PITCH_HARMONICS`], refused by their count
    /// before any is read (1e6 took 5–7.7 s to refuse).
    #[serde(
        default,
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "crate::budget::at_most_pitch_harmonics"
    )]
    pub pitch_error: Vec<WormHarmonic>,
    /// How `pitch_error[i].w` is read (kato Eq. 1; see
    /// [`super::transmission`]); default `gearRatio`.
    #[serde(default, skip_serializing_if = "PitchReading::is_default")]
    pub pitch_reading: PitchReading,
    /// Coulomb friction torque F at the motor, N·m (kato Fig. 2, linear
    /// axes): `F·sign(ω)` opposes the motor speed at the start of each step.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub friction: f64,
    /// Constant load torque G at the motor, N·m (kato Fig. 2: gravity on
    /// the Z axis), positive opposing positive motion.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub gravity: f64,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// The reading of kato Eq. 1's amplitude `W_i`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum PitchReading {
    /// `R` is the local ratio `dθ_table/dθm`: the table error is
    /// `(W g/N)[…]`, W dimensionless like R.
    #[default]
    GearRatio,
    /// `θ_table = x + Σ W sin(N x + φ)` (referenced to 0 at x = 0): W is
    /// the angle amplitude in rad, as a measurement gives it.
    Additive,
}

impl PitchReading {
    fn is_default(&self) -> bool {
        *self == Self::GearRatio
    }
}

impl AxisParams {
    /// Total inertia `J + J1`, kg·m².
    pub fn inertia(&self) -> f64 {
        self.j + self.j1
    }

    /// Checks every field for a physically meaningful value.
    ///
    /// # Examples
    /// ```
    /// let mut c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
    /// assert!(c.validate().is_ok());
    /// c.kpp = -1.0;
    /// assert!(c.validate().unwrap_err().to_string().contains("kpp"));
    /// ```
    pub fn validate(&self) -> Result<(), ServoError> {
        self.check_ranges()?;
        if self.kvp == 0.0 && self.kvi == 0.0 {
            return Err(ServoError::BadParameter {
                field: "kvp",
                value: 0.0,
                expected: "kvp or kvi must be > 0 for the velocity loop to act",
            });
        }
        if let Some(t) = self.torque_max {
            if !(t.is_finite() && (1e-6..=1e7).contains(&t)) {
                return Err(ServoError::BadParameter {
                    field: "torqueMax",
                    value: t,
                    expected: "must be between 1e-6 and 1e7 N·m (omit it for no limit)",
                });
            }
        }
        if !(self.gravity.is_finite() && self.gravity.abs() <= 1e6) {
            return Err(ServoError::BadParameter {
                field: "gravity",
                value: self.gravity,
                expected: "the load torque must be between −1e6 and 1e6 N·m",
            });
        }
        self.validate_mechanism()?;
        match (self.kind, self.lead) {
            (AxisKind::Linear, None) => Err(ServoError::MissingParameter {
                field: "lead",
                why: "a linear axis needs its ball-screw lead in m",
            }),
            (_, Some(l)) if !(l.is_finite() && (1e-6..=100.0).contains(&l)) => {
                Err(ServoError::BadParameter {
                    field: "lead",
                    value: l,
                    expected: "must be between 1e-6 and 100 m",
                })
            }
            _ => Ok(()),
        }
    }

    /// The drive's numbers within their physical ranges, with no
    /// subnormal values.
    fn check_ranges(&self) -> Result<(), ServoError> {
        // Physical ranges: wide enough for any machine tool, narrow enough
        // that no later step overflows, divides by a subnormal or allocates
        // for a window longer than any servo setting (a delay or average
        // above 10 s is not a servo parameter).
        let ranges: [(&'static str, f64, f64, f64, &'static str); 11] = [
            ("j", self.j, 1e-9, 1e4, "must be between 1e-9 and 1e4 kg·m²"),
            (
                "kpp",
                self.kpp,
                1e-3,
                1e4,
                "must be between 1e-3 and 1e4 1/s",
            ),
            ("j1", self.j1, 0.0, 1e4, "must be between 0 and 1e4 kg·m²"),
            ("c", self.c, 0.0, 1e6, "must be between 0 and 1e6 N·m·s/rad"),
            ("kvp", self.kvp, 0.0, 1e9, "must be between 0 and 1e9"),
            ("kvi", self.kvi, 0.0, 1e12, "must be between 0 and 1e12"),
            ("ts", self.ts, 0.0, 10.0, "must be between 0 and 10 s"),
            ("ta", self.ta, 0.0, 10.0, "must be between 0 and 10 s"),
            ("tp", self.tp, 0.0, 10.0, "must be between 0 and 10 s"),
            (
                "kffp",
                self.kffp,
                -1000.0,
                1000.0,
                "must be between −1000 and 1000 %",
            ),
            (
                "friction",
                self.friction,
                0.0,
                1e6,
                "the Coulomb friction torque must be between 0 and 1e6 N·m",
            ),
        ];
        for (field, value, lo, hi, expected) in ranges {
            // Subnormal numbers (|v| < 2.2e-308, not 0) are refused: they
            // are never a setting and turn into infinities when divided by.
            let ok = value.is_finite()
                && value >= lo
                && value <= hi
                && (value == 0.0 || value.is_normal());
            if !ok {
                return Err(ServoError::BadParameter {
                    field,
                    value,
                    expected,
                });
            }
        }
        Ok(())
    }

    /// Checks the fields of the mechanism after the motor (gear ratio,
    /// backlash, worm-gear pitch error), the only ones an ideal servo uses;
    /// [`Self::validate`] includes these checks.
    ///
    /// # Examples
    /// ```
    /// let mut c = mtmotion::machine::preset("nmv5000").unwrap().axes["c"].clone();
    /// c.kpp = -1.0; // a loop gain: not part of the mechanism
    /// assert!(c.validate_mechanism().is_ok());
    /// c.backlash = -1e-4;
    /// assert!(c.validate_mechanism().unwrap_err().to_string().contains("backlash"));
    /// ```
    pub fn validate_mechanism(&self) -> Result<(), ServoError> {
        if !(self.backlash.is_finite() && self.backlash >= 0.0) {
            return Err(ServoError::BadParameter {
                field: "backlash",
                value: self.backlash,
                expected: "must be a finite number ≥ 0",
            });
        }
        if let Some(r) = self.gear_ratio {
            if !(r.is_finite() && r > 0.0) {
                return Err(ServoError::BadParameter {
                    field: "gearRatio",
                    value: r,
                    expected: "must be > 0 (omit it for a direct drive)",
                });
            }
        }
        if self.kind == AxisKind::Linear && !self.pitch_error.is_empty() {
            return Err(ServoError::BadParameter {
                field: "pitchError",
                value: self.pitch_error.len() as f64,
                expected: "worm-gear pitch error applies to rotary axes only; remove it",
            });
        }
        if self.pitch_error.len() > crate::budget::MAX_PITCH_HARMONICS {
            return Err(ServoError::BadParameter {
                field: "pitchError",
                value: self.pitch_error.len() as f64,
                expected: "at most 64 harmonics (the work budget; a worm gear shows a handful)",
            });
        }
        for h in &self.pitch_error {
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
        }
        Ok(())
    }
}
