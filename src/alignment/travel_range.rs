//! The travel-range simulation of takayama-alignment-travel-range §2.1
//! (Fig. 3 flow chart, steps 1–6) and §3.1: how far the least-squares
//! centre of a partial-range ball-bar locus is from the true rotation centre
//! when the rotary axis has harmonic motion errors.
//!
//! Geometry (B axis, rotating in the Z–X plane):
//! - angle origin: θ = 0 points along +Z; θ grows towards +X, i.e.
//!   θ = atan2(x, z). This is also the B-axis angle and the argument of the
//!   motion-error harmonics.
//! - the locus is computed over a full revolution at `samples` points,
//!   θᵢ = −180° + 360°·i/samples (the paper divides 360° by 1000, §3.1.2),
//!   then cut to each travel range W, *centred* on `centre_deg` (default 0):
//!   |θᵢ − centre| ≤ W/2, so 180° means −90°…90° and 90° means −45°…45°, as
//!   in the paper's Fig. 4 (b), (c).
//! - locus: p(θ) = c + (ρ + Δ(θ))·(cos(θ + α₀), sin(θ + α₀)) in (z, x), with
//!   Δ(θ) = Σ Aₙ sin(nθ + φₙ) (see [`crate::ballbar::harmonics`]).
//!
//! Two readings of step (1) are offered, because the paper's figures are
//! missing and its text supports both:
//! - `radius > 0` (default 100 mm): a ball bar of that length; ρ = radius,
//!   α₀ = 0. The fitted-centre error is then translation invariant, so it
//!   does not depend on the offset c (up to Δ²/ρ).
//! - `radius = 0`: the DBB5 set-up of the paper's Fig. 5, one ball at the
//!   nominal centre; the ball circles the true centre c at ρ = |c|, starting
//!   at the nominal centre (α₀ = direction from c to the origin; 0 when
//!   c = 0). The error then depends on the offset, as the paper's Figs. 7
//!   and 8 show two different curves.
//!
//! Step (5) "method of least squares" is the geometric circle fit of
//! [`crate::ballbar::fit_circle`]. Step (6): error = fitted centre − c.
//!
//! Units: mm for offsets, radius and amplitudes; degrees for ranges and
//! centre (the paper's units); rad for harmonic phases.

use serde::{Deserialize, Serialize};

use crate::ballbar::{fit_circle, harmonics::synthesize, FitError, Harmonic};

/// Errors of the alignment models.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AlignmentError {
    /// The sweep is over its work budget ([`crate::budget`]).
    #[error(transparent)]
    Budget(#[from] crate::budget::BudgetError),
    /// A configuration field is out of range.
    #[error("{field}: {message}")]
    BadField {
        /// The field, e.g. `ranges[2]`.
        field: String,
        /// What was expected.
        message: String,
    },
    /// The centre fit of one range or section failed.
    #[error("{what}: {source}")]
    Fit {
        /// Which range or section.
        what: String,
        /// The fit error.
        source: FitError,
    },
}

pub(crate) fn bad(field: impl Into<String>, message: impl Into<String>) -> AlignmentError {
    AlignmentError::BadField {
        field: field.into(),
        message: message.into(),
    }
}

/// An offset (centre position) of the rotary axis in the Z–X plane, mm.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Offset {
    /// Z, mm.
    pub z: f64,
    /// X, mm.
    pub x: f64,
}

/// The default ball-bar radius, mm (the paper's 100 mm bar).
pub(crate) fn default_radius() -> f64 {
    100.0
}
/// The default samples per revolution (the paper's 1000).
pub(crate) fn default_samples() -> usize {
    1000
}

/// The locus model shared by the offset and the angle sweeps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Locus {
    /// Motion-error harmonics Aₙ sin(nθ + φₙ), amplitudes in mm.
    #[serde(default)]
    pub harmonics: Vec<Harmonic>,
    /// Ball-bar radius ρ, mm; 0 selects the DBB5 centre-ball reading.
    #[serde(default = "default_radius")]
    pub radius: f64,
    /// Samples per full revolution (the paper: 1000).
    #[serde(default = "default_samples")]
    pub samples: usize,
    /// Centre of every travel range, degrees (default 0).
    #[serde(default)]
    pub centre_deg: f64,
}

/// Configuration of [`travel_range_sweep`]. Read through a flat mirror
/// (`SweepConfigIn`): serde reads a flattened field as a map and drops
/// the keys no part names, so a misspelt `harmonic` would be ignored.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", from = "SweepConfigIn")]
pub struct SweepConfig {
    /// True centre c of the rotary axis, mm.
    #[serde(default)]
    pub offset: Offset,
    /// Travel ranges W, degrees, each in (0, 360].
    pub ranges: Vec<f64>,
    /// The locus model.
    #[serde(flatten)]
    pub locus: Locus,
}

/// [`SweepConfig`] as read: every key named, no other key accepted.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
struct SweepConfigIn {
    #[serde(default)]
    offset: Offset,
    ranges: Vec<f64>,
    #[serde(default)]
    harmonics: Vec<Harmonic>,
    #[serde(default = "default_radius")]
    radius: f64,
    #[serde(default = "default_samples")]
    samples: usize,
    #[serde(default)]
    centre_deg: f64,
}

impl From<SweepConfigIn> for SweepConfig {
    fn from(c: SweepConfigIn) -> Self {
        Self {
            offset: c.offset,
            ranges: c.ranges,
            locus: Locus {
                harmonics: c.harmonics,
                radius: c.radius,
                samples: c.samples,
                centre_deg: c.centre_deg,
            },
        }
    }
}

/// One point of the sweep: the centre-estimate error at one range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SweepPoint {
    /// Travel range W, degrees.
    pub range_deg: f64,
    /// Estimated − true centre, Z, mm.
    pub error_z: f64,
    /// Estimated − true centre, X, mm.
    pub error_x: f64,
}

impl Locus {
    /// Checks the fields; `prefix` names the argument in messages.
    pub fn validate(&self, prefix: &str) -> Result<(), AlignmentError> {
        if !(self.radius.is_finite() && self.radius >= 0.0) {
            return Err(bad(
                format!("{prefix}radius"),
                format!(
                    "expected a length ≥ 0 mm, got {}",
                    crate::numeric::compact(self.radius)
                ),
            ));
        }
        if !(3..=10_000_000).contains(&self.samples) {
            return Err(bad(
                format!("{prefix}samples"),
                format!(
                    "expected 3 … 10000000 samples per revolution, got {}",
                    self.samples
                ),
            ));
        }
        if !self.centre_deg.is_finite() {
            return Err(bad(
                format!("{prefix}centreDeg"),
                "expected a finite angle in degrees",
            ));
        }
        crate::budget::HARMONICS_LIST.check("harmonics", self.harmonics.len())?;
        for (i, h) in self.harmonics.iter().enumerate() {
            if !(h.amplitude.is_finite() && h.phase.is_finite()) {
                return Err(bad(
                    format!("{prefix}harmonics[{i}]"),
                    "amplitude and phase must be finite numbers",
                ));
            }
        }
        Ok(())
    }

    /// The locus points (z, x) of a full revolution about centre `c`, with
    /// their angles θ (rad, in −π … π).
    pub fn points(&self, c: Offset) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let (rho, a0) = if self.radius > 0.0 {
            (self.radius, 0.0)
        } else {
            let e = c.z.hypot(c.x);
            (e, if e > 0.0 { (-c.x).atan2(-c.z) } else { 0.0 })
        };
        let n = self.samples;
        let mut th = Vec::with_capacity(n);
        let mut z = Vec::with_capacity(n);
        let mut x = Vec::with_capacity(n);
        for i in 0..n {
            let t = (-180.0 + 360.0 * i as f64 / n as f64).to_radians();
            let r = rho + synthesize(&self.harmonics, t);
            th.push(t);
            z.push(c.z + r * (t + a0).cos());
            x.push(c.x + r * (t + a0).sin());
        }
        (th, z, x)
    }

    /// Fits the centre to the part of a full-revolution locus within the
    /// travel range `range_deg` centred on `centre_deg`; returns the
    /// fitted centre.
    pub fn fit_range(
        &self,
        pts: &(Vec<f64>, Vec<f64>, Vec<f64>),
        range_deg: f64,
    ) -> Result<Offset, FitError> {
        let half = range_deg / 2.0 + 1e-9;
        let (mut zs, mut xs) = (Vec::new(), Vec::new());
        for ((t, z), x) in pts.0.iter().zip(&pts.1).zip(&pts.2) {
            // Angle from the range centre, wrapped to (−180°, 180°].
            let d = (t.to_degrees() - self.centre_deg).rem_euclid(360.0);
            let d = if d > 180.0 { d - 360.0 } else { d };
            if d.abs() <= half || range_deg >= 360.0 {
                zs.push(*z);
                xs.push(*x);
            }
        }
        let c = fit_circle(&zs, &xs)?;
        Ok(Offset { z: c.cx, x: c.cy })
    }
}

/// Runs the §2.1 simulation: for each travel range, the least-squares
/// centre of the cut locus minus the true centre.
///
/// # Units
/// Offsets, radius, amplitudes and errors in mm; ranges and centre in
/// degrees; phases in rad.
///
/// # Errors
/// [`AlignmentError::BadField`] naming the field for ranges outside
/// (0°, 360°], bad sample counts or non-finite values;
/// [`AlignmentError::Fit`] when a range holds fewer than 3 samples.
///
/// # Examples
/// ```
/// use mtmotion::alignment::{travel_range_sweep, Locus, Offset, SweepConfig};
/// use mtmotion::ballbar::Harmonic;
/// let cfg = SweepConfig {
///     offset: Offset { z: 0.0, x: 0.010 },
///     ranges: vec![180.0, 360.0],
///     locus: Locus {
///         harmonics: vec![Harmonic { order: 2, amplitude: 0.005, phase: 0.0 }],
///         radius: 100.0, samples: 1000, centre_deg: 0.0,
///     },
/// };
/// let s = travel_range_sweep(&cfg).unwrap();
/// assert!(s[0].error_x.abs() > 1e-3);               // 180°: biased by µm
/// assert!(s[1].error_x.abs() < 1e-9 && s[1].error_z.abs() < 1e-9); // 360°: none
/// ```
pub fn travel_range_sweep(cfg: &SweepConfig) -> Result<Vec<SweepPoint>, AlignmentError> {
    cfg.locus.validate("")?;
    // each range fits the samples it spans, and the locus evaluates every
    // harmonic at every sample once
    crate::budget::check(
        "travel-range sweep",
        (cfg.ranges.len() as u64 + cfg.locus.harmonics.len() as u64)
            .saturating_mul(cfg.locus.samples as u64),
        crate::budget::MAX_SWEEP_POINTS,
        "points ((ranges + harmonics) × samples per revolution)",
        "use fewer ranges, harmonics or samples per revolution",
    )?;
    if !(cfg.offset.z.is_finite() && cfg.offset.x.is_finite()) {
        return Err(bad("offset", "z and x must be finite numbers (mm)"));
    }
    for (i, &w) in cfg.ranges.iter().enumerate() {
        if !(w > 0.0 && w <= 360.0) {
            return Err(bad(
                format!("ranges[{i}]"),
                format!(
                    "expected a travel range in (0, 360] degrees, got {}",
                    crate::numeric::compact(w)
                ),
            ));
        }
    }
    let pts = cfg.locus.points(cfg.offset);
    cfg.ranges
        .iter()
        .map(|&w| {
            let c = cfg
                .locus
                .fit_range(&pts, w)
                .map_err(|e| AlignmentError::Fit {
                    what: format!("travel range {w}°"),
                    source: e,
                })?;
            Ok(SweepPoint {
                range_deg: w,
                error_z: c.z - cfg.offset.z,
                error_x: c.x - cfg.offset.x,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cfg(offset: Offset, radius: f64, harmonics: Vec<Harmonic>) -> SweepConfig {
        SweepConfig {
            offset,
            ranges: (0..10)
                .map(|k| 90.0 + 30.0 * k as f64)
                .filter(|w| *w <= 360.0)
                .collect(),
            locus: Locus {
                harmonics,
                radius,
                samples: 1000,
                centre_deg: 0.0,
            },
        }
    }

    #[test]
    fn no_motion_error_no_bias() {
        // A pure circle: every range recovers the centre exactly.
        for radius in [100.0, 0.0] {
            let s = travel_range_sweep(&cfg(Offset { z: 0.01, x: -0.02 }, radius, vec![])).unwrap();
            for p in s {
                assert!(p.error_z.abs() < 1e-10 && p.error_x.abs() < 1e-10, "{p:?}");
            }
        }
    }

    #[test]
    fn linearised_half_range_bias_matches_the_analytic_value() {
        // Δ = A sin 2θ over −90°…90° with a long bar: to first order the
        // fitted centre error is the LS projection of Δ on {1, cos θ, sin θ}:
        // e_x = ∫ A sin2θ sinθ / ∫ sin²θ = A·(4/3)/(π/2) = 8A/(3π).
        let a = 0.005;
        let c = SweepConfig {
            ranges: vec![180.0],
            locus: Locus {
                samples: 100_000,
                ..cfg(
                    Offset::default(),
                    1000.0,
                    vec![Harmonic {
                        order: 2,
                        amplitude: a,
                        phase: 0.0,
                    }],
                )
                .locus
            },
            ..cfg(Offset::default(), 1000.0, vec![])
        };
        let s = travel_range_sweep(&c).unwrap();
        let want = 8.0 * a / (3.0 * std::f64::consts::PI);
        assert!(
            (s[0].error_x - want).abs() < 1e-6,
            "{} vs {want}",
            s[0].error_x
        );
        // Second order: Δ²/ρ = 2.5e-8 mm.
        assert!(s[0].error_z.abs() < 1e-7, "{}", s[0].error_z);
    }

    #[test]
    fn defaults_and_locus_checks() {
        // radius and samples left out are the paper's 100 mm and 1000.
        let c: SweepConfig = serde_json::from_str(r#"{"ranges": [180]}"#).unwrap();
        assert_eq!((c.locus.radius, c.locus.samples), (100.0, 1000));
        // A negative or infinite radius, a harmonic with one non-finite
        // part: each refused by name.
        let mut l = c.locus.clone();
        for r in [-1.0, f64::INFINITY] {
            l.radius = r;
            assert!(
                l.validate("")
                    .unwrap_err()
                    .to_string()
                    .starts_with("radius:"),
                "{r}"
            );
        }
        l.radius = 0.0;
        assert!(l.validate("").is_ok());
        for (a, p) in [(f64::NAN, 0.0), (0.001, f64::INFINITY)] {
            l.harmonics = vec![Harmonic {
                order: 2,
                amplitude: a,
                phase: p,
            }];
            let e = l.validate("").unwrap_err().to_string();
            assert!(e.starts_with("harmonics[0]:"), "{e}");
        }
    }

    #[test]
    fn bad_fields_are_named() {
        let mut c = cfg(Offset::default(), 100.0, vec![]);
        c.ranges = vec![90.0, 400.0];
        let e = travel_range_sweep(&c).unwrap_err().to_string();
        assert!(e.starts_with("ranges[1]:"), "{e}");
        c.ranges = vec![0.1];
        let e = travel_range_sweep(&c).unwrap_err().to_string();
        assert!(
            e.contains("travel range 0.1°") && e.contains("at least 3 points"),
            "{e}"
        );
        c.locus.samples = 2;
        assert!(travel_range_sweep(&c)
            .unwrap_err()
            .to_string()
            .starts_with("samples"));
    }
}
