//! Alignment estimate from measured sections with its travel-range bias
//! band: takayama-alignment-travel-range §2.1 (Fig. 3) applied to the
//! user's own traces, §2.2 (Fig. 2) for the angle errors.
//!
//! The paper shows that a centre fitted to a partial-range locus is off the
//! true centre by an amount set by the motion-error harmonics (orders ≥ 2)
//! and the travel range W. This file turns that simulation into the
//! honesty bound of an estimate made from measured traces:
//! 1. each section's offset and the angle errors come from
//!    [`super::estimate_alignment`] (least-squares circle per section);
//! 2. each section's motion-error harmonics Aₙ sin(nθ + φₙ), n = 2 … N, are
//!    fitted to its own radial deviation over its own span
//!    ([`crate::ballbar::fit_harmonics`], orders 0 and 1 absorb the radius
//!    and the offset);
//! 3. the §2.1 simulation ([`super::travel_range_sweep`]) with those
//!    harmonics at the travel range W, centred on the section's mid angle,
//!    gives the bias b_k = (b_z, b_x) of that section's centre estimate;
//! 4. the band of a section's offset is ±(|b_z| + e₂), ±(|b_x| + e₂), with
//!    e₂ = max|Δ|²/R the second-order term the first-order §2.1 model
//!    leaves out (Δ the section's radial deviation, R the bar length);
//!    the angle error is
//!    the least-squares slope Σ w_k·Z_k with w_k = (Y_k − Ȳ)/Σ(Y_j − Ȳ)²
//!    (for two sections, the paper's (Z₁ − Z₂)/(Y₁ − Y₂)), so its band is
//!    Σ |w_k|·(|b_z,k| + e₂,k) (and the same for X): the worst case of the biases.
//!
//! Readings chosen: the band is the predicted bias magnitude, not a
//! statistical interval (noise is not in the paper's model); N is the
//! largest order ≤ `max_order` that the section's span resolves (the
//! harmonic fit reports which orders are ill-conditioned); a section that
//! covers a full revolution has no bias (the paper's 360° case).
//!
//! Units: mm (Y, offsets, radius, deviations, biases), degrees (angles,
//! travel range), rad (angle errors and their band).

use serde::{Deserialize, Serialize};

use super::angle::{estimate_alignment, AlignmentEstimate, Section};
use super::travel_range::{bad, travel_range_sweep, Locus, Offset, SweepConfig};
use super::AlignmentError;
use crate::ballbar::{fit_harmonics, Harmonic};

fn d_max_order() -> usize {
    10
}

/// Settings of [`estimate_alignment_band`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct BandConfig {
    /// Ball-bar length, mm.
    pub radius: f64,
    /// Travel range W of the rotary axis, degrees in (0, 360]; `None`
    /// takes each section's own angular span.
    #[serde(default)]
    pub travel_range_deg: Option<f64>,
    /// Highest harmonic order fitted for the bias (default 10).
    #[serde(default = "d_max_order")]
    pub max_order: usize,
}

/// The bias of one section's centre estimate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SectionBand {
    /// Section position Y, mm.
    pub y: f64,
    /// Travel range used, degrees.
    pub range_deg: f64,
    /// Mid angle of the section's trace, degrees.
    pub centre_deg: f64,
    /// Predicted bias of the centre estimate, Z, mm.
    pub bias_z: f64,
    /// Predicted bias of the centre estimate, X, mm.
    pub bias_x: f64,
    /// Half-width of the band of the section's Z offset, mm.
    pub band_z: f64,
    /// Half-width of the band of the section's X offset, mm.
    pub band_x: f64,
    /// Harmonics (orders ≥ 2) fitted to the section's deviation, mm / rad.
    pub harmonics: Vec<Harmonic>,
}

/// Estimate and its travel-range bias band.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct AlignmentBand {
    /// Offsets per section and angle errors.
    pub estimate: AlignmentEstimate,
    /// Bias per section (band of its offset: ±|bias|).
    pub sections: Vec<SectionBand>,
    /// Half-width of the ΔBz band, rad (None with one section).
    pub band_bz: Option<f64>,
    /// Half-width of the ΔBx band, rad (None with one section).
    pub band_bx: Option<f64>,
}

/// Estimates offsets and angle errors from measured sections and the
/// travel-range bias band around them (see the module header).
///
/// # Errors
/// Those of [`estimate_alignment`]; [`AlignmentError::BadField`] naming
/// `travelRangeDeg` outside (0, 360] or a section whose span resolves no
/// harmonic of order 2.
///
/// # Examples
/// ```
/// use mtmotion::alignment::{estimate_alignment_band, BandConfig, Section};
/// // A pure circle about (10 µm, 0) seen over 180°: no harmonics, no bias.
/// let a: Vec<f64> = (0..=180).map(|i| -90.0 + i as f64).collect();
/// let d = a.iter().map(|t: &f64| {
///     let t = t.to_radians();
///     (0.010 + 100.0 * t.cos()).hypot(100.0 * t.sin()) - 100.0
/// }).collect();
/// let s = Section { y: 0.0, angle_deg: a, deviation: d };
/// let cfg = BandConfig { radius: 100.0, travel_range_deg: Some(180.0), max_order: 6 };
/// let b = estimate_alignment_band(&[s], &cfg).unwrap();
/// // Within its band (here only the second-order term max|Δ|²/R = 1 nm).
/// assert!((b.estimate.sections[0].z - 0.010).abs() <= b.sections[0].band_z);
/// assert!(b.sections[0].bias_z.abs() < 1e-6 && b.band_bz.is_none());
/// ```
pub fn estimate_alignment_band(
    sections: &[Section],
    cfg: &BandConfig,
) -> Result<AlignmentBand, AlignmentError> {
    let estimate = estimate_alignment(sections, cfg.radius)?;
    if let Some(w) = cfg.travel_range_deg {
        if !(w > 0.0 && w <= 360.0) {
            return Err(bad(
                "travelRangeDeg",
                format!("expected a travel range in (0, 360] degrees, got {w}"),
            ));
        }
    }
    let bands = sections
        .iter()
        .enumerate()
        .map(|(k, s)| section_band(k, s, cfg))
        .collect::<Result<Vec<_>, _>>()?;
    let (band_bz, band_bx) = if estimate.delta_bz.is_some() {
        let n = bands.len() as f64;
        let my = bands.iter().map(|b| b.y).sum::<f64>() / n;
        let syy: f64 = bands.iter().map(|b| (b.y - my).powi(2)).sum();
        let w = |b: &SectionBand| (b.y - my).abs() / syy;
        (
            Some(bands.iter().map(|b| w(b) * b.band_z).sum()),
            Some(bands.iter().map(|b| w(b) * b.band_x).sum()),
        )
    } else {
        (None, None)
    };
    Ok(AlignmentBand {
        estimate,
        sections: bands,
        band_bz,
        band_bx,
    })
}

/// Section `k`'s band: the bias of its centre estimate at the travel range
/// (takayama §2.1 with its own harmonics of order ≥ 2, centred on its mid
/// angle) plus the second-order term max|Δ|²/R.
fn section_band(k: usize, s: &Section, cfg: &BandConfig) -> Result<SectionBand, AlignmentError> {
    let (lo, hi) = s
        .angle_deg
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &a| {
            (l.min(a), h.max(a))
        });
    let span = (hi - lo).min(360.0);
    let range = cfg.travel_range_deg.unwrap_or(span);
    let centre = (lo + hi) / 2.0;
    let rad: Vec<f64> = s.angle_deg.iter().map(|a| a.to_radians()).collect();
    // The highest order the section's span resolves, down to 2.
    let harmonics = (2..=cfg.max_order.max(2))
        .rev()
        .find_map(|n| fit_harmonics(&rad, &s.deviation, n).ok())
        .ok_or_else(|| {
            bad(
                format!("sections[{k}]"),
                format!(
                    "its span of {span:.1}° and {} points resolve no harmonic of order 2: \
                     measure a longer arc",
                    s.angle_deg.len()
                ),
            )
        })?;
    let motion: Vec<Harmonic> = harmonics.into_iter().filter(|h| h.order >= 2).collect();
    let sweep = travel_range_sweep(&SweepConfig {
        offset: Offset::default(),
        ranges: vec![range],
        locus: Locus {
            harmonics: motion.clone(),
            radius: cfg.radius,
            samples: 3600,
            centre_deg: centre,
        },
    })
    .map_err(|e| match e {
        AlignmentError::Fit { source, .. } => AlignmentError::Fit {
            what: format!("sections[{k}] bias at travel range {range}°"),
            source,
        },
        other => other,
    })?;
    let e2 = s
        .deviation
        .iter()
        .fold(0.0_f64, |m, d| m.max(d.abs()))
        .powi(2)
        / cfg.radius;
    Ok(SectionBand {
        y: s.y,
        range_deg: range,
        centre_deg: centre,
        bias_z: sweep[0].error_z,
        bias_x: sweep[0].error_x,
        band_z: sweep[0].error_z.abs() + e2,
        band_x: sweep[0].error_x.abs() + e2,
        harmonics: motion,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ballbar::{synthetic_trace, SyntheticConfig};

    /// A section generated by the ball-bar synthetic generator (a second
    /// model: exact geometry) with centre (z, x) and harmonics, over 180°.
    fn section(y: f64, z: f64, x: f64, harmonics: &[Harmonic], range: f64) -> Section {
        let t = synthetic_trace(&SyntheticConfig {
            radius: 100.0,
            range_deg: range,
            both_directions: false,
            offset_x: z,
            offset_y: x,
            harmonics: harmonics.to_vec(),
            ..SyntheticConfig::default()
        })
        .unwrap();
        let r = &t.runs[0];
        Section {
            y,
            angle_deg: r.angle.iter().map(|a| a.to_degrees()).collect(),
            deviation: r.deviation.clone(),
        }
    }

    fn h(order: u32, um: f64, phase: f64) -> Harmonic {
        Harmonic {
            order,
            amplitude: um * 1e-3,
            phase,
        }
    }

    #[test]
    fn known_offset_and_angle_are_recovered_within_the_band() {
        // ΔBz = 20 µm / 700 mm, ΔBx = −10 µm / 700 mm; Z₀ = 10 µm, X₀ = 5 µm.
        let (bz, bx) = (0.020 / 700.0, -0.010 / 700.0);
        let hs = [h(2, 5.0, 0.3), h(3, 3.0, 1.0), h(5, 2.5, 0.0)];
        let secs = [350.0, -350.0].map(|y| section(y, 0.010 + bz * y, 0.005 + bx * y, &hs, 180.0));
        let cfg = BandConfig {
            radius: 100.0,
            travel_range_deg: Some(180.0),
            max_order: 8,
        };
        let b = estimate_alignment_band(&secs, &cfg).unwrap();
        // The harmonics bias each offset by µm over 180° (the paper's point).
        let bias = b.sections[0].bias_z.hypot(b.sections[0].bias_x);
        assert!(bias > 1e-3, "bias {bias} mm");
        for (s, e) in b.sections.iter().zip(&b.estimate.sections) {
            let (tz, tx) = (0.010 + bz * s.y, 0.005 + bx * s.y);
            // Within the band, and the bias is the actual error to first
            // order (the residual is the bar's second-order Δ²/R).
            assert!(
                (e.z - tz).abs() <= s.band_z,
                "{} vs {tz} ± {}",
                e.z,
                s.band_z
            );
            assert!(
                (e.x - tx).abs() <= s.band_x,
                "{} vs {tx} ± {}",
                e.x,
                s.band_x
            );
            // The second-order allowance is small against the bias.
            assert!(s.band_z - s.bias_z.abs() < 2e-5, "{s:?}");
            assert!(
                (e.z - tz - s.bias_z).abs() < 2e-5,
                "bias predicted {} actual {}",
                s.bias_z,
                e.z - tz
            );
        }
        let (ebz, ebx) = (b.estimate.delta_bz.unwrap(), b.estimate.delta_bx.unwrap());
        assert!(
            (ebz - bz).abs() <= b.band_bz.unwrap(),
            "{ebz} vs {bz} ± {:?}",
            b.band_bz
        );
        assert!(
            (ebx - bx).abs() <= b.band_bx.unwrap(),
            "{ebx} vs {bx} ± {:?}",
            b.band_bx
        );
    }

    #[test]
    fn full_revolution_has_no_bias() {
        let hs = [h(2, 5.0, 0.3), h(4, 2.0, 0.0)];
        let s = section(0.0, 0.010, -0.004, &hs, 360.0);
        let cfg = BandConfig {
            radius: 100.0,
            travel_range_deg: None,
            max_order: 6,
        };
        let b = estimate_alignment_band(&[s], &cfg).unwrap();
        assert!(b.sections[0].bias_z.abs() < 1e-9 && b.sections[0].bias_x.abs() < 1e-9);
        assert!((b.estimate.sections[0].z - 0.010).abs() < 1e-6);
        // The harmonics are found (second method: the generator's input).
        let a2 = b.sections[0]
            .harmonics
            .iter()
            .find(|c| c.order == 2)
            .unwrap();
        assert!((a2.amplitude - 0.005).abs() < 1e-6, "{a2:?}");
    }

    #[test]
    fn bad_travel_range_is_named() {
        let s = section(0.0, 0.0, 0.0, &[], 180.0);
        let cfg = BandConfig {
            radius: 100.0,
            travel_range_deg: Some(400.0),
            max_order: 4,
        };
        let e = estimate_alignment_band(&[s], &cfg).unwrap_err().to_string();
        assert!(e.starts_with("travelRangeDeg:") && e.contains("400"), "{e}");
    }
}
