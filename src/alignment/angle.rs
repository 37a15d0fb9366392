//! Rotary-axis offset per section and angle error from two sections:
//! takayama-alignment-travel-range §2.2, Fig. 2, §3.2 (Table 1) and §4.2
//! (Fig. 12).
//!
//! Fig. 2 definitions: the centre (Z_Bk, X_Bk) of the B axis is estimated in
//! each section Y = Y_k; the angle errors are
//! ΔBz = (Z_B1 − Z_B2)/(Y1 − Y2) and ΔBx = (X_B1 − X_B2)/(Y1 − Y2).
//!
//! Readings chosen:
//! - a measured section is a ball-bar trace: axis angle θ (deg, θ = 0 along
//!   +Z, towards +X, as in [`super::travel_range`]) and radial deviation Δ
//!   (mm) of a bar of nominal length `radius`; its points are
//!   (radius + Δ)·(cos θ, sin θ) and the section's offset is their
//!   least-squares circle centre;
//! - with exactly two sections the paper's formula is used; with more, the
//!   least-squares slope of Z_B (and X_B) against Y, which equals the
//!   formula for two sections;
//! - the paper's Table 1 is missing. §3.2 states an angle error of
//!   10 µm/350 mm in Z with a 10 µm Z offset and results in µm/700 mm, so
//!   the built-in example (see [`super::examples`]) takes Y0 = 0 with
//!   Z = 10 µm, Y1 = +350 mm with Z = 20 µm and Y2 = −350 mm with Z = 0.
//!
//! Units: y, offsets, radius and deviations in mm; angles in degrees at the
//! input; angle errors ΔBz, ΔBx in rad (= mm/mm; 1 µm/700 mm = 1.43 µrad).

use serde::{Deserialize, Serialize};

use super::travel_range::{bad, AlignmentError, Locus, Offset};
use crate::ballbar::fit_circle;

/// One measured section: its Y position and its ball-bar trace.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Section {
    /// Section position Y, mm.
    pub y: f64,
    /// Axis angles, degrees.
    pub angle_deg: Vec<f64>,
    /// Radial deviations, mm.
    pub deviation: Vec<f64>,
}

/// The estimated centre of one section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SectionEstimate {
    /// Section position Y, mm.
    pub y: f64,
    /// Estimated centre Z, mm.
    pub z: f64,
    /// Estimated centre X, mm.
    pub x: f64,
    /// RMS residual of the circle fit, mm.
    pub rms_residual: f64,
}

/// Offsets per section and, from two or more sections, the angle errors.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct AlignmentEstimate {
    /// One estimate per section, in input order.
    pub sections: Vec<SectionEstimate>,
    /// ΔBz, rad (None with one section).
    pub delta_bz: Option<f64>,
    /// ΔBx, rad (None with one section).
    pub delta_bx: Option<f64>,
    /// Z offset at Y = 0 of the fitted line Z = Z₀ + ΔBz·Y, mm (None with
    /// one section).
    pub intercept_z: Option<f64>,
    /// X offset at Y = 0 of the fitted line, mm (None with one section).
    pub intercept_x: Option<f64>,
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// Slope of v against y by least squares, Σ(y − ȳ)·v / Σ(y − ȳ)² (the
/// Fig. 2 formula for two sections); None when every y is the same.
fn slope(y: &[f64], v: &[f64]) -> Option<f64> {
    let my = mean(y);
    let syy: f64 = y.iter().map(|a| (a - my).powi(2)).sum();
    let syv: f64 = y.iter().zip(v).map(|(a, b)| (a - my) * b).sum();
    (syy > 0.0).then(|| syv / syy)
}

/// Estimates the centre of every section and the angle errors ΔBz, ΔBx.
///
/// # Units
/// `y`, `radius`, deviations in mm; angles in degrees; ΔBz, ΔBx in rad.
///
/// # Errors
/// [`AlignmentError::BadField`] for unequal array lengths, equal Y of all
/// sections, or a bad radius; [`AlignmentError::Fit`] naming the section
/// whose trace cannot be fitted.
///
/// # Examples
/// ```
/// use mtmotion::alignment::{estimate_alignment, Section};
/// // Two sections 700 mm apart whose centres differ by 20 µm in Z.
/// let sec = |y: f64, cz: f64| {
///     let a: Vec<f64> = (0..=90).map(|i| -45.0 + i as f64).collect();
///     // Deviation of a 100 mm bar about the origin when the centre is (cz, 0).
///     let d = a.iter().map(|t: &f64| {
///         let t = t.to_radians();
///         let (pz, px) = (cz + 100.0 * t.cos(), 100.0 * t.sin());
///         pz.hypot(px) - 100.0
///     });
///     Section { y, angle_deg: a.clone(), deviation: d.collect() }
/// };
/// let e = estimate_alignment(&[sec(350.0, 0.020), sec(-350.0, 0.0)], 100.0).unwrap();
/// // To the bar's second-order error e²/R (0.014 µm / 700 mm here).
/// assert!((e.delta_bz.unwrap() - 0.020 / 700.0).abs() < 2e-8);
/// assert!(e.delta_bx.unwrap().abs() < 1e-10);
/// ```
pub fn estimate_alignment(
    sections: &[Section],
    radius: f64,
) -> Result<AlignmentEstimate, AlignmentError> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(bad(
            "radius",
            format!(
                "expected the ball-bar length in mm (> 0), got {}",
                crate::numeric::compact(radius)
            ),
        ));
    }
    if sections.is_empty() {
        return Err(bad(
            "sections",
            "give at least one section (two for the angle errors)",
        ));
    }
    crate::budget::SECTIONS_LIST.check("sections", sections.len())?;
    let mut out = Vec::with_capacity(sections.len());
    for (k, s) in sections.iter().enumerate() {
        if s.angle_deg.len() != s.deviation.len() {
            return Err(bad(
                format!("sections[{k}]"),
                format!(
                    "angleDeg has {} values but deviation has {}",
                    s.angle_deg.len(),
                    s.deviation.len()
                ),
            ));
        }
        if !s.y.is_finite() {
            return Err(bad(
                format!("sections[{k}].y"),
                "expected a finite Y position in mm",
            ));
        }
        let (z, x): (Vec<f64>, Vec<f64>) = s
            .angle_deg
            .iter()
            .zip(&s.deviation)
            .map(|(a, d)| {
                let t = a.to_radians();
                ((radius + d) * t.cos(), (radius + d) * t.sin())
            })
            .unzip();
        let c = fit_circle(&z, &x).map_err(|e| AlignmentError::Fit {
            what: format!("sections[{k}] (y = {} mm)", s.y),
            source: e,
        })?;
        out.push(SectionEstimate {
            y: s.y,
            z: c.cx,
            x: c.cy,
            rms_residual: c.rms_residual,
        });
    }
    let ys: Vec<f64> = out.iter().map(|s| s.y).collect();
    let zs: Vec<f64> = out.iter().map(|s| s.z).collect();
    let xs: Vec<f64> = out.iter().map(|s| s.x).collect();
    let (delta_bz, delta_bx) = if out.len() >= 2 {
        let bz = slope(&ys, &zs).ok_or_else(|| {
            bad(
                "sections",
                "all sections have the same y: give sections at different Y",
            )
        })?;
        (Some(bz), slope(&ys, &xs))
    } else {
        (None, None)
    };
    let my = mean(&ys);
    Ok(AlignmentEstimate {
        delta_bz,
        delta_bx,
        intercept_z: delta_bz.map(|b| mean(&zs) - b * my),
        intercept_x: delta_bx.map(|b| mean(&xs) - b * my),
        sections: out,
    })
}

/// A simulated section: Y position and true centre.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionOffset {
    /// Section position Y, mm.
    pub y: f64,
    /// True centre in this section, mm.
    pub offset: Offset,
}

/// Configuration of [`angle_sweep`]. Read through a flat mirror
/// (`AngleSweepConfigIn`): serde reads a flattened field as a map and
/// drops the keys no part names.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", from = "AngleSweepConfigIn")]
pub struct AngleSweepConfig {
    /// Two or more sections with their true centres.
    pub sections: Vec<SectionOffset>,
    /// Travel ranges, degrees.
    pub ranges: Vec<f64>,
    /// The locus model (same motion error in every section).
    #[serde(flatten)]
    pub locus: Locus,
}

/// [`AngleSweepConfig`] as read: every key named, no other key accepted.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
struct AngleSweepConfigIn {
    sections: Vec<SectionOffset>,
    ranges: Vec<f64>,
    #[serde(default)]
    harmonics: Vec<crate::ballbar::Harmonic>,
    #[serde(default = "super::travel_range::default_radius")]
    radius: f64,
    #[serde(default = "super::travel_range::default_samples")]
    samples: usize,
    #[serde(default)]
    centre_deg: f64,
}

impl From<AngleSweepConfigIn> for AngleSweepConfig {
    fn from(c: AngleSweepConfigIn) -> Self {
        Self {
            sections: c.sections,
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

/// One point of the angle sweep.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct AngleSweepPoint {
    /// Travel range, degrees.
    pub range_deg: f64,
    /// Estimated ΔBz, rad.
    pub delta_bz: f64,
    /// Estimated ΔBx, rad.
    pub delta_bx: f64,
    /// Estimated − true ΔBz, rad.
    pub error_bz: f64,
    /// Estimated − true ΔBx, rad.
    pub error_bx: f64,
}

/// The §2.2 simulation: per range, the centre of each section from the cut
/// locus, the angle errors from them, and their error against the truth.
///
/// # Units
/// mm for y, offsets, radius, amplitudes; degrees for ranges; rad for the
/// angle errors.
///
/// # Errors
/// As [`super::travel_range_sweep`], plus fewer than two sections or all at
/// the same Y.
///
/// # Examples
/// ```
/// use mtmotion::alignment::{angle_sweep, AngleSweepConfig, Locus, Offset, SectionOffset};
/// let s = |y, z| SectionOffset { y, offset: Offset { z, x: 0.0 } };
/// let cfg = AngleSweepConfig {
///     sections: vec![s(350.0, 0.020), s(-350.0, 0.0)],
///     ranges: vec![90.0, 360.0],
///     locus: Locus { harmonics: vec![], radius: 100.0, samples: 1000, centre_deg: 0.0 },
/// };
/// let r = angle_sweep(&cfg).unwrap();
/// assert!((r[0].delta_bz - 0.020 / 700.0).abs() < 1e-12 && r[0].error_bz.abs() < 1e-12);
/// ```
pub fn angle_sweep(cfg: &AngleSweepConfig) -> Result<Vec<AngleSweepPoint>, AlignmentError> {
    cfg.locus.validate("")?;
    crate::budget::check(
        "angle sweep",
        (cfg.ranges.len() as u64 + cfg.locus.harmonics.len() as u64)
            .saturating_mul(cfg.sections.len() as u64)
            .saturating_mul(cfg.locus.samples as u64),
        crate::budget::MAX_SWEEP_POINTS,
        "points ((ranges + harmonics) × sections × samples per revolution)",
        "use fewer ranges, harmonics, sections or samples per revolution",
    )?;
    crate::budget::SECTIONS_LIST.check("sections", cfg.sections.len())?;
    if cfg.sections.len() < 2 {
        return Err(bad(
            "sections",
            "give at least two sections at different Y for the angle errors",
        ));
    }
    let ys: Vec<f64> = cfg.sections.iter().map(|s| s.y).collect();
    let truth_z: Vec<f64> = cfg.sections.iter().map(|s| s.offset.z).collect();
    let truth_x: Vec<f64> = cfg.sections.iter().map(|s| s.offset.x).collect();
    let (Some(bz0), Some(bx0)) = (slope(&ys, &truth_z), slope(&ys, &truth_x)) else {
        return Err(bad(
            "sections",
            "all sections have the same y: give sections at different Y",
        ));
    };
    let loci: Vec<_> = cfg
        .sections
        .iter()
        .map(|s| cfg.locus.points(s.offset))
        .collect();
    let mut out = Vec::with_capacity(cfg.ranges.len());
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
        let (mut zs, mut xs) = (Vec::new(), Vec::new());
        for (k, pts) in loci.iter().enumerate() {
            let c = cfg
                .locus
                .fit_range(pts, w)
                .map_err(|e| AlignmentError::Fit {
                    what: format!("sections[{k}] at travel range {w}°"),
                    source: e,
                })?;
            zs.push(c.z);
            xs.push(c.x);
        }
        let (bz, bx) = (
            slope(&ys, &zs).unwrap_or(f64::NAN),
            slope(&ys, &xs).unwrap_or(f64::NAN),
        );
        out.push(AngleSweepPoint {
            range_deg: w,
            delta_bz: bz,
            delta_bx: bx,
            error_bz: bz - bz0,
            error_bx: bx - bx0,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ballbar::Harmonic;

    /// A 100 mm bar's trace over `span`° from `from`° when the axis centre
    /// is at (cz, cx): angle = axis angle about the pivot, exact geometry.
    fn bar_section(y: f64, (cz, cx): (f64, f64), from: f64, span: f64) -> Section {
        let angle_deg: Vec<f64> = (0..=400).map(|i| from + span * i as f64 / 400.0).collect();
        let deviation = angle_deg
            .iter()
            .map(|a| {
                let t = a.to_radians();
                let (pz, px) = (cz + 100.0 * t.cos(), cx + 100.0 * t.sin());
                pz.hypot(px) - 100.0
            })
            .collect();
        Section {
            y,
            angle_deg,
            deviation,
        }
    }

    #[test]
    fn three_sections_at_user_heights_give_the_slope_and_intercept() {
        // Heights 100/200/300 mm (not centred on 0), centres on the lines
        // Z = 4 µm + 0.05 µm/mm·Y, X = −2 µm − 0.03 µm/mm·Y, full circles
        // (no bias): the least-squares slope and intercept are exact to the
        // bar's second order (about 1 nm here).
        let line = |y: f64| (0.004 + 5e-5 * y, -0.002 - 3e-5 * y);
        let secs: Vec<Section> = [100.0, 200.0, 300.0]
            .iter()
            .map(|&y| bar_section(y, line(y), 13.0, 360.0))
            .collect();
        let e = estimate_alignment(&secs, 100.0).unwrap();
        for (s, &y) in e.sections.iter().zip(&[100.0, 200.0, 300.0]) {
            let (z, x) = line(y);
            assert!((s.z - z).abs() < 5e-9 && (s.x - x).abs() < 5e-9, "{s:?}");
        }
        assert!((e.delta_bz.unwrap() - 5e-5).abs() < 5e-11, "{e:?}");
        assert!((e.delta_bx.unwrap() + 3e-5).abs() < 5e-11, "{e:?}");
        assert!((e.intercept_z.unwrap() - 0.004).abs() < 1e-8, "{e:?}");
        assert!((e.intercept_x.unwrap() + 0.002).abs() < 1e-8, "{e:?}");
        // One section: no angle errors, no line.
        let one = estimate_alignment(&secs[..1], 100.0).unwrap();
        assert_eq!(
            (one.delta_bz, one.delta_bx, one.intercept_z, one.intercept_x),
            (None, None, None, None)
        );
    }

    #[test]
    fn angle_sweep_checks_its_sections_and_ranges_and_reports_both_errors() {
        let s = |y, z, x| SectionOffset {
            y,
            offset: Offset { z, x },
        };
        let locus = Locus {
            harmonics: vec![],
            radius: 100.0,
            samples: 720,
            centre_deg: 30.0,
        };
        let two = vec![s(120.0, 0.004, -0.002), s(420.0, 0.010, 0.007)];
        let mut cfg = AngleSweepConfig {
            sections: two.clone(),
            ranges: vec![360.0, 90.0],
            locus,
        };
        // No motion error: every range recovers ΔBz = 6 µm/300 mm and
        // ΔBx = 9 µm/300 mm; the errors are estimate − truth.
        for p in angle_sweep(&cfg).unwrap() {
            assert!(
                (p.delta_bz - 2e-5).abs() < 1e-12 && (p.delta_bx - 3e-5).abs() < 1e-12,
                "{p:?}"
            );
            assert!((p.error_bz - (p.delta_bz - 2e-5)).abs() < 1e-18, "{p:?}");
            assert!((p.error_bx - (p.delta_bx - 3e-5)).abs() < 1e-18, "{p:?}");
        }
        // The work budget counts (ranges + harmonics) × sections × samples.
        let mut big = cfg.clone();
        big.ranges = vec![90.0, 180.0, 270.0];
        big.locus.harmonics = vec![
            Harmonic {
                order: 2,
                amplitude: 0.001,
                phase: 0.0
            };
            2
        ];
        big.locus.samples = 1_000_001;
        let e = angle_sweep(&big).unwrap_err().to_string();
        assert!(e.starts_with("angle sweep: 10000010 points"), "{e}");
        cfg.sections.truncate(1);
        let e = angle_sweep(&cfg).unwrap_err().to_string();
        assert!(e.starts_with("sections: give at least two"), "{e}");
        cfg.sections = two;
        for bad in [0.0, -5.0, 400.0, f64::NAN] {
            cfg.ranges = vec![90.0, bad];
            let e = angle_sweep(&cfg).unwrap_err().to_string();
            assert!(
                e.starts_with("ranges[1]: expected a travel range in (0, 360]"),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn sections_at_one_height_and_bad_radii_are_refused() {
        let s = bar_section(50.0, (0.01, 0.0), 0.0, 180.0);
        let e = estimate_alignment(&[s.clone(), s.clone()], 100.0).unwrap_err();
        assert!(
            e.to_string().contains("all sections have the same y"),
            "{e}"
        );
        for r in [0.0, -5.0, f64::INFINITY, f64::NAN] {
            let e = estimate_alignment(std::slice::from_ref(&s), r).unwrap_err();
            assert!(e.to_string().starts_with("radius:"), "{r}: {e}");
        }
        let e = estimate_alignment(&[], 100.0).unwrap_err();
        assert!(e.to_string().starts_with("sections:"), "{e}");
        let mut bad = s;
        bad.y = f64::NAN;
        let e = estimate_alignment(&[bad], 100.0).unwrap_err();
        assert!(e.to_string().starts_with("sections[0].y"), "{e}");
    }

    #[test]
    fn dbb5_reading_gives_an_angle_bias_the_bar_reading_does_not() {
        let s = |y, z| SectionOffset {
            y,
            offset: Offset { z, x: 0.0 },
        };
        let harmonics = vec![
            Harmonic {
                order: 2,
                amplitude: 0.005,
                phase: 0.0,
            },
            Harmonic {
                order: 3,
                amplitude: 0.003,
                phase: 0.0,
            },
        ];
        let mut cfg = AngleSweepConfig {
            sections: vec![s(350.0, 0.020), s(-350.0, 0.001)],
            ranges: vec![90.0, 360.0],
            locus: Locus {
                harmonics,
                radius: 100.0,
                samples: 1000,
                centre_deg: 0.0,
            },
        };
        // Long bar: the same motion error biases both centres alike, so the
        // angle estimate is unbiased to ~(Δ/ρ)·Δ.
        for p in angle_sweep(&cfg).unwrap() {
            assert!(p.error_bz.abs() * 700.0 < 1e-6, "{p:?}");
        }
        // DBB5 centre ball: the bias depends on |c|, so it does not cancel
        // at 90°, and is much smaller at 360° (not zero: the locus is not
        // a circle plus small terms when |c| ~ Δ).
        cfg.locus.radius = 0.0;
        let r = angle_sweep(&cfg).unwrap();
        assert!(r[0].error_bz.abs() * 700.0 > 5e-3, "{:?}", r[0]);
        assert!(r[1].error_bz.abs() < r[0].error_bz.abs() / 3.0, "{r:?}");
    }

    #[test]
    fn section_errors_are_named() {
        let sec = Section {
            y: 0.0,
            angle_deg: vec![0.0, 1.0],
            deviation: vec![0.0],
        };
        let e = estimate_alignment(&[sec], 100.0).unwrap_err().to_string();
        assert!(e.starts_with("sections[0]: angleDeg has 2"), "{e}");
        let sec = Section {
            y: 5.0,
            angle_deg: vec![0.0, 1.0],
            deviation: vec![0.0, 0.0],
        };
        let e = estimate_alignment(&[sec], 100.0).unwrap_err().to_string();
        assert!(
            e.contains("sections[0] (y = 5 mm)") && e.contains("at least 3 points"),
            "{e}"
        );
    }
}
