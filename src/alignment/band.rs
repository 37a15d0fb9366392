//! Alignment estimate from measured sections with an honest band:
//! takayama-alignment-travel-range §2.1 (Fig. 3) applied to the user's own
//! traces, §2.2 (Fig. 2) for the angle errors.
//!
//! The paper shows that a centre fitted to a partial-range locus is off the
//! true centre by an amount set by the motion-error harmonics (orders ≥ 2)
//! and the travel range W. A measured trace also carries noise. The band
//! keeps the two apart:
//! 1. each section's offset and the angle errors come from
//!    [`super::estimate_alignment`] (least-squares circle per section);
//! 2. [`super::section_fit::fit_section`] fits the section's radial
//!    deviation over its own span with the harmonic orders its data
//!    supports (a BIC rule, not a fixed order) and gives the systematic
//!    bias of the centre (takayama's term) and its standard error σ;
//! 3. the band of an offset is |bias| + e₂ + 3σ, with e₂ the second-order
//!    terms the first-order model leaves out: (ĉ·t(θ))²/R (ĉ the
//!    estimated centre, t the tangent, R the bar length) taken through the
//!    same least squares as the centre — half of it is in the trace when
//!    its angle is the axis angle rather than the angle about the pivot,
//!    half in the circle fit's own distance — plus max|Δ|²/R for the rest
//!    (Δ the section's radial deviation);
//! 4. the angle error is the least-squares slope Σ w_k·Z_k with
//!    w_k = (Y_k − Ȳ)/Σ(Y_j − Ȳ)² (for two sections, the paper's
//!    (Z₁ − Z₂)/(Y₁ − Y₂)); its band is Σ|w_k|·(|bias_k| + e₂,k) (the
//!    worst case of the biases) + 3·√(Σ w_k² σ_k²) (independent noise);
//! 5. an offset whose band is wider than the section's own peak-to-valley
//!    deviation (at least 1 nm) is *not determined*: the span cannot separate it from the
//!    motion error, and the result says so in words instead of a number.
//!    An angle error is not determined when an offset it uses is not.
//!
//! The travel range of a section is its measured angular span, never an
//! input. A section covering a full revolution has no bias (orders are
//! orthogonal there).
//!
//! Units: mm (Y, offsets, radius, deviations, biases, bands), degrees
//! (angles, spans), rad (angle errors and their bands).

use serde::{Deserialize, Serialize};

use super::angle::{estimate_alignment, AlignmentEstimate, Section};
use super::section_fit::{centre_projection, fit_section};
use super::travel_range::bad;
use super::AlignmentError;
use crate::ballbar::Harmonic;

/// The coverage factor of the statistical part of every band (3σ).
pub const COVERAGE: f64 = 3.0;

fn d_max_order() -> usize {
    10
}

/// Settings of [`estimate_alignment_band`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct BandConfig {
    /// Ball-bar length, mm.
    pub radius: f64,
    /// Highest harmonic order considered (default 10); the orders kept are
    /// those the data supports (see [`super::section_fit`]).
    #[serde(default = "d_max_order")]
    pub max_order: usize,
}

/// The band of one section's centre estimate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SectionBand {
    /// Section position Y, mm.
    pub y: f64,
    /// Travel range: the section's measured angular span, degrees.
    pub range_deg: f64,
    /// Mid angle of the section's trace, degrees.
    pub centre_deg: f64,
    /// Systematic error of the centre estimate from the selected
    /// harmonics (takayama §2.1), Z, mm.
    pub bias_z: f64,
    /// Systematic error, X, mm.
    pub bias_x: f64,
    /// Standard error of the centre from the noise, Z, mm.
    pub sigma_z: f64,
    /// Standard error, X, mm.
    pub sigma_x: f64,
    /// Second-order allowance of the Z offset (module header, step 3), mm.
    pub second_order_z: f64,
    /// Second-order allowance of the X offset, mm.
    pub second_order_x: f64,
    /// Half-width of the band of the Z offset, mm.
    pub band_z: f64,
    /// Half-width of the band of the X offset, mm.
    pub band_x: f64,
    /// Whether the span determines the Z offset (band ≤ peak-to-valley).
    pub determined_z: bool,
    /// Whether the span determines the X offset.
    pub determined_x: bool,
    /// Why an offset is not determined, in words (None when both are).
    pub note: Option<String>,
    /// Peak-to-valley of the section's deviation, mm.
    pub peak_to_valley: f64,
    /// Residual standard deviation of the selected model, mm.
    pub noise: f64,
    /// Highest harmonic order selected (1: none).
    pub order: usize,
    /// Highest order the section's span resolves.
    pub resolved_order: usize,
    /// Harmonics (orders ≥ 2) selected for the section, mm / rad.
    pub harmonics: Vec<Harmonic>,
}

/// Half-widths of an angle error's band, rad.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct AngleBand {
    /// Σ|w_k|·(|bias_k| + e₂,k), rad.
    pub systematic: f64,
    /// 3·√(Σ w_k² σ_k²), rad.
    pub statistical: f64,
    /// Their sum, rad.
    pub band: f64,
    /// False when an offset it is computed from is not determined.
    pub determined: bool,
}

/// Estimate and its band.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct AlignmentBand {
    /// Offsets per section and angle errors.
    pub estimate: AlignmentEstimate,
    /// Band per section.
    pub sections: Vec<SectionBand>,
    /// Band of ΔBz (None with one section).
    pub band_bz: Option<AngleBand>,
    /// Band of ΔBx (None with one section).
    pub band_bx: Option<AngleBand>,
    /// The coverage factor of the statistical parts (3).
    pub coverage: f64,
}

/// Estimates offsets and angle errors from measured sections and the band
/// around them (see the module header).
///
/// # Errors
/// Those of [`estimate_alignment`]; [`AlignmentError::BadField`] naming
/// `maxOrder` (1 … 50) or a section whose span cannot fit a centre;
/// [`AlignmentError::Budget`] over [`crate::budget::MAX_ALIGNMENT_WORK`].
///
/// # Examples
/// ```
/// use mtmotion::alignment::{estimate_alignment_band, BandConfig, Section};
/// // A pure circle about (10 µm, 0) seen over 180°: no harmonics, no noise.
/// let a: Vec<f64> = (0..=180).map(|i| -90.0 + i as f64).collect();
/// let d = a.iter().map(|t: &f64| {
///     let t = t.to_radians();
///     (0.010 + 100.0 * t.cos()).hypot(100.0 * t.sin()) - 100.0
/// }).collect();
/// let s = Section { y: 0.0, angle_deg: a, deviation: d };
/// let b = estimate_alignment_band(&[s], &BandConfig { radius: 100.0, max_order: 10 }).unwrap();
/// let (e, s) = (&b.estimate.sections[0], &b.sections[0]);
/// assert!((e.z - 0.010).abs() <= s.band_z && s.band_z < 1e-5 && s.determined_z);
/// assert_eq!(s.range_deg, 180.0);
/// ```
pub fn estimate_alignment_band(
    sections: &[Section],
    cfg: &BandConfig,
) -> Result<AlignmentBand, AlignmentError> {
    if !(1..=50).contains(&cfg.max_order) {
        return Err(bad(
            "maxOrder",
            format!(
                "expected the highest harmonic order to consider, 1 … 50, got {}",
                cfg.max_order
            ),
        ));
    }
    let samples: u64 = sections.iter().map(|s| s.deviation.len() as u64).sum();
    crate::budget::check(
        "alignment band",
        samples.saturating_mul(((2 * cfg.max_order + 1) as u64).pow(2)),
        crate::budget::MAX_ALIGNMENT_WORK,
        "units of work (samples over all sections × (2·maxOrder + 1)²)",
        "decimate the traces or lower maxOrder",
    )?;
    let estimate = estimate_alignment(sections, cfg.radius)?;
    let bands = sections
        .iter()
        .enumerate()
        .zip(&estimate.sections)
        .map(|((k, s), e)| section_band(k, s, (e.z, e.x), cfg))
        .collect::<Result<Vec<_>, _>>()?;
    let (band_bz, band_bx) = if estimate.delta_bz.is_some() {
        (
            Some(angle_band(&bands, |b| {
                (b.bias_z.abs() + b.second_order_z, b.sigma_z, b.determined_z)
            })),
            Some(angle_band(&bands, |b| {
                (b.bias_x.abs() + b.second_order_x, b.sigma_x, b.determined_x)
            })),
        )
    } else {
        (None, None)
    };
    Ok(AlignmentBand {
        estimate,
        sections: bands,
        band_bz,
        band_bx,
        coverage: COVERAGE,
    })
}

/// The band of a least-squares slope over the sections: `part` gives each
/// section's (systematic allowance, σ, determined) of the component.
fn angle_band(bands: &[SectionBand], part: impl Fn(&SectionBand) -> (f64, f64, bool)) -> AngleBand {
    let n = bands.len() as f64;
    let my = bands.iter().map(|b| b.y).sum::<f64>() / n;
    let syy: f64 = bands.iter().map(|b| (b.y - my).powi(2)).sum();
    let (mut systematic, mut var, mut determined) = (0.0, 0.0, true);
    for b in bands {
        let w = (b.y - my) / syy;
        let (allowance, sigma, det) = part(b);
        systematic += w.abs() * allowance;
        var += (w * sigma).powi(2);
        determined &= det;
    }
    let statistical = COVERAGE * var.sqrt();
    AngleBand {
        systematic,
        statistical,
        band: systematic + statistical,
        determined,
    }
}

/// Section `k`'s band (module header, steps 2, 3 and 5).
fn section_band(
    k: usize,
    s: &Section,
    centre: (f64, f64),
    cfg: &BandConfig,
) -> Result<SectionBand, AlignmentError> {
    let (lo, hi) = min_max(&s.angle_deg);
    let span = (hi - lo).min(360.0);
    let rad: Vec<f64> = s.angle_deg.iter().map(|a| a.to_radians()).collect();
    let fit = fit_section(&rad, &s.deviation, cfg.max_order)
        .map_err(|e| bad(format!("sections[{k}]"), format!("{e} (span {span:.1}°)")))?;
    let (dlo, dhi) = min_max(&s.deviation);
    let peak_to_valley = dhi - dlo;
    // The tangential term (ĉ·t)²/R through the centre fit, plus max|Δ|²/R
    // for the rest.
    let (cz, cx) = centre;
    let tangential: Vec<f64> = rad
        .iter()
        .map(|t| (cx * t.cos() - cz * t.sin()).powi(2) / cfg.radius)
        .collect();
    let moved = centre_projection(&rad, &tangential);
    let rest = dlo.abs().max(dhi.abs()).powi(2) / cfg.radius;
    let second_order = [moved[0].abs() + rest, moved[1].abs() + rest];
    let band = |i: usize| fit.bias[i].abs() + second_order[i] + COVERAGE * fit.sigma[i];
    let (band_z, band_x) = (band(0), band(1));
    // Floored at 1 nm, below any instrument, so a flawless trace of a
    // centred axis (peak-to-valley 0) is not called undetermined by rounding.
    let limit = peak_to_valley.max(1e-6);
    let (determined_z, determined_x) = (band_z <= limit, band_x <= limit);
    let note = (!(determined_z && determined_x)).then(|| {
        let which = match (determined_z, determined_x) {
            (false, false) => "the offsets are",
            (false, true) => "the first-axis offset is",
            _ => "the second-axis offset is",
        };
        let cause = if fit.order >= 2 {
            format!("from the order-{} motion error it carries", fit.order)
        } else {
            "from the trace's radius and noise".to_string()
        };
        format!(
            "{which} not determined: a {span:.0}° span cannot separate the centre {cause} \
             (the band would be wider than the trace's own {:.2} µm peak-to-valley); \
             measure a longer arc",
            peak_to_valley * 1e3
        )
    });
    Ok(SectionBand {
        y: s.y,
        range_deg: span,
        centre_deg: (lo + hi) / 2.0,
        bias_z: fit.bias[0],
        bias_x: fit.bias[1],
        sigma_z: fit.sigma[0],
        sigma_x: fit.sigma[1],
        second_order_z: second_order[0],
        second_order_x: second_order[1],
        band_z,
        band_x,
        determined_z,
        determined_x,
        note,
        peak_to_valley,
        noise: fit.noise,
        order: fit.order,
        resolved_order: fit.resolved,
        harmonics: fit.harmonics,
    })
}

fn min_max(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &a| {
            (l.min(a), h.max(a))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ballbar::{synthetic_trace, SyntheticConfig};

    /// A section generated by the ball-bar synthetic generator (a second
    /// model: exact geometry) with centre (z, x) and harmonics, over
    /// `range` degrees centred on `mid` degrees.
    fn section(y: f64, z: f64, x: f64, harmonics: &[Harmonic], range: f64, mid: f64) -> Section {
        let t = synthetic_trace(&SyntheticConfig {
            radius: 100.0,
            range_deg: range,
            centre_deg: mid,
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

    const CFG: BandConfig = BandConfig {
        radius: 100.0,
        max_order: 10,
    };

    #[test]
    fn known_offset_and_angle_are_recovered_within_the_band() {
        // ΔBz = 20 µm / 700 mm, ΔBx = −10 µm / 700 mm; Z₀ = 10 µm, X₀ = 5 µm
        // at Y = 0; sections at Y = 150 and 850 (not symmetric about 0).
        let (bz, bx) = (0.020 / 700.0, -0.010 / 700.0);
        let hs = [h(2, 5.0, 0.3), h(3, 3.0, 1.0), h(5, 2.5, 0.0)];
        let secs =
            [150.0, 850.0].map(|y| section(y, 0.010 + bz * y, 0.005 + bx * y, &hs, 180.0, 20.0));
        let b = estimate_alignment_band(&secs, &CFG).unwrap();
        // The harmonics bias each offset by µm over 180° (the paper's point).
        let s0 = &b.sections[0];
        assert!(s0.bias_z.hypot(s0.bias_x) > 1e-3, "{s0:?}");
        assert_eq!(s0.order, 5, "{s0:?}");
        for (s, e) in b.sections.iter().zip(&b.estimate.sections) {
            let (tz, tx) = (0.010 + bz * s.y, 0.005 + bx * s.y);
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
            // The bias is the actual error, to the bar's second order Δ²/R.
            assert!((e.z - tz - s.bias_z).abs() < 2e-5, "{s:?}");
            assert!((e.x - tx - s.bias_x).abs() < 2e-5, "{s:?}");
            // No noise: the band is the bias and the second-order term.
            assert!(s.band_z - s.bias_z.abs() - s.second_order_z < 1e-6, "{s:?}");
            assert!(s.determined_z && s.determined_x && s.note.is_none());
            assert!((s.range_deg - 180.0).abs() < 0.5 && (s.centre_deg - 20.0).abs() < 0.5);
        }
        let (ebz, ebx) = (b.estimate.delta_bz.unwrap(), b.estimate.delta_bx.unwrap());
        let (gz, gx) = (b.band_bz.unwrap(), b.band_bx.unwrap());
        assert!((ebz - bz).abs() <= gz.band, "{ebz} vs {bz} ± {gz:?}");
        assert!((ebx - bx).abs() <= gx.band, "{ebx} vs {bx} ± {gx:?}");
        // Two sections: the systematic band is the paper's formula applied
        // to the worst case, (|b₁| + e₁ + |b₂| + e₂)/|Y₁ − Y₂|.
        let (s1, s2) = (&b.sections[0], &b.sections[1]);
        let want =
            (s1.bias_z.abs() + s1.second_order_z + s2.bias_z.abs() + s2.second_order_z) / 700.0;
        assert!((gz.systematic - want).abs() < 1e-15, "{gz:?} vs {want}");
        let want =
            (s1.bias_x.abs() + s1.second_order_x + s2.bias_x.abs() + s2.second_order_x) / 700.0;
        assert!((gx.systematic - want).abs() < 1e-15, "{gx:?} vs {want}");
        let want = COVERAGE * s1.sigma_x.hypot(s2.sigma_x) / 700.0;
        assert!((gx.statistical - want).abs() < 1e-15, "{gx:?} vs {want}");
        // Peak-to-valley is the section's own max − min deviation.
        let (lo, hi) = min_max(&secs[0].deviation);
        assert_eq!(s1.peak_to_valley, hi - lo);
        assert_eq!(gz.band, gz.systematic + gz.statistical);
        assert!(gz.determined && b.coverage == 3.0);
    }

    #[test]
    fn full_revolution_has_no_bias() {
        let hs = [h(2, 5.0, 0.3), h(4, 2.0, 0.0)];
        let s = section(40.0, 0.010, -0.004, &hs, 360.0, 0.0);
        let b = estimate_alignment_band(&[s], &CFG).unwrap();
        let s = &b.sections[0];
        // The generator's closed 360° repeats its end point, so the
        // sampling is not quite even: a sub-µm bias remains, and it is the
        // actual error of the estimate.
        assert!(s.bias_z.abs() < 1e-6 && s.bias_x.abs() < 1e-9, "{s:?}");
        let e = &b.estimate.sections[0];
        // Up to the bar's second-order term Δ²/R (2.5 nm here).
        assert!(
            (e.z - 0.010 - s.bias_z).abs() < s.second_order_z,
            "{e:?} {s:?}"
        );
        assert!(
            (e.x + 0.004 - s.bias_x).abs() < s.second_order_x,
            "{e:?} {s:?}"
        );
        assert!(b.band_bz.is_none() && b.band_bx.is_none());
        // The harmonics are found (second method: the generator's input).
        let a2 = s.harmonics.iter().find(|c| c.order == 2).unwrap();
        assert!((a2.amplitude - 0.005).abs() < 1e-6, "{a2:?}");
        assert_eq!(s.order, 4);
    }

    #[test]
    fn a_short_span_with_a_strong_harmonic_is_not_determined() {
        // 40° with 8 µm of order 2 and 0.5 µm of order 7 (beyond what 40°
        // resolves against the centre): the band would exceed the trace.
        let hs = [h(2, 8.0, 0.7), h(7, 0.5, 0.0)];
        let s = section(10.0, 0.004, 0.002, &hs, 40.0, 65.0);
        let good = section(300.0, 0.004, 0.002, &[], 180.0, 65.0);
        let b = estimate_alignment_band(&[s, good], &CFG).unwrap();
        // An angle error built on an undetermined offset is undetermined.
        assert!(b.sections[1].determined_z && b.sections[1].determined_x);
        let (gz, gx) = (b.band_bz.unwrap(), b.band_bx.unwrap());
        assert!(!(gz.determined && gx.determined), "{gz:?} {gx:?}");
        let s = &b.sections[0];
        assert!(!(s.determined_z && s.determined_x), "{s:?}");
        assert_eq!(gz.determined, s.determined_z);
        assert_eq!(gx.determined, s.determined_x);
        let note = s.note.as_deref().unwrap();
        assert!(
            note.contains("not determined") && note.contains("40° span"),
            "{note}"
        );
        // Its cause: the motion error of the order kept.
        assert!(note.contains("from the order-"), "{note}");
    }

    #[test]
    fn the_second_order_term_of_a_large_offset_is_covered_not_ignored() {
        // A 50 µm offset over 180° from −85°, the angle being the axis
        // angle (as a ball bar on a rotary axis reads it): the centre is off
        // by a second-order amount that max|Δ|²/R alone (25 nm) does not
        // cover.
        let (cz, cx) = (0.050, -0.002);
        let angle_deg: Vec<f64> = (0..=1800).map(|i| -85.0 + 0.1 * i as f64).collect();
        let deviation = angle_deg
            .iter()
            .map(|a| {
                let t = a.to_radians();
                (cz + 100.0 * t.cos()).hypot(cx + 100.0 * t.sin()) - 100.0
            })
            .collect();
        let s = Section {
            y: 35.0,
            angle_deg,
            deviation,
        };
        let b = estimate_alignment_band(&[s], &CFG).unwrap();
        let (e, s) = (&b.estimate.sections[0], &b.sections[0]);
        let (ez, ex) = ((e.z - cz).abs(), (e.x - cx).abs());
        let rest = cz.hypot(cx).powi(2) / 100.0;
        assert!(
            ez.max(ex) > 1.05 * rest,
            "{e:?}: the case must need the term"
        );
        assert!(ez <= s.band_z && ex <= s.band_x, "{e:?} {s:?}");
        // And the allowance is of the size of the error, not far above it.
        assert!(
            s.band_z < 4.0 * ez.max(rest) && s.band_x < 4.0 * ex.max(rest),
            "{e:?} {s:?}"
        );
    }

    #[test]
    fn one_undetermined_axis_is_named_with_its_cause() {
        // Noise only (0.3 µm) over 30° around 0°: the first-axis (Z)
        // offset is confounded with the radius, X is not; around 90° over
        // 25° it is the other way round. The cause is the radius and the
        // noise (no harmonic kept).
        for (span, mid, which, det) in [
            (
                30.0,
                0.0,
                "the first-axis offset is not determined",
                (false, true),
            ),
            (
                25.0,
                90.0,
                "the second-axis offset is not determined",
                (true, false),
            ),
        ] {
            let mut s = section(10.0, 0.004, 0.002, &[], span, mid);
            let e = crate::numeric::gaussian(3, s.deviation.len());
            for (d, n) in s.deviation.iter_mut().zip(&e) {
                *d += 3e-4 * n;
            }
            let b = estimate_alignment_band(&[s], &CFG).unwrap();
            let s = &b.sections[0];
            assert_eq!((s.determined_z, s.determined_x), det, "{s:?}");
            let note = s.note.as_deref().unwrap();
            assert!(note.starts_with(which), "{note}");
            assert!(note.contains("from the trace's radius and noise"), "{note}");
        }
    }

    #[test]
    fn both_offsets_undetermined_are_named_together() {
        // 40° with 8 and 4 µm of orders 2 and 3: neither offset is
        // determined, and the note says so of both.
        let hs = [h(2, 8.0, 0.7), h(3, 4.0, 1.9), h(7, 0.5, 0.0)];
        let s = section(10.0, 0.004, 0.002, &hs, 40.0, 65.0);
        let b = estimate_alignment_band(&[s], &CFG).unwrap();
        let s = &b.sections[0];
        assert_eq!((s.determined_z, s.determined_x), (false, false), "{s:?}");
        let note = s.note.as_deref().unwrap();
        assert!(note.starts_with("the offsets are not determined"), "{note}");
    }

    #[test]
    fn the_tangential_term_predicts_the_second_order_error() {
        // Offset (35, 35) µm over 120° from 5°, exact geometry read at the
        // axis angle, no motion error: the centre's error is the
        // tangential term (ĉ·t)²/R through the fit (module header, step
        // 3) to 2 % (0.06 % measured), in both components.
        let (cz, cx) = (0.035, 0.035);
        let angle_deg: Vec<f64> = (0..=1200).map(|i| 5.0 + 0.1 * i as f64).collect();
        let deviation: Vec<f64> = angle_deg
            .iter()
            .map(|a| {
                let t = a.to_radians();
                (cz + 100.0 * t.cos()).hypot(cx + 100.0 * t.sin()) - 100.0
            })
            .collect();
        // The allowance's other part, max|Δ|²/R.
        let rest = deviation.iter().fold(0.0f64, |m, d| m.max(d.abs())).powi(2) / 100.0;
        let s = Section {
            y: 5.0,
            angle_deg,
            deviation,
        };
        let b = estimate_alignment_band(&[s], &CFG).unwrap();
        let (e, s) = (&b.estimate.sections[0], &b.sections[0]);
        for (err, allowance) in [(e.z - cz, s.second_order_z), (e.x - cx, s.second_order_x)] {
            let moved = allowance - rest;
            assert!(
                (err.abs() - moved).abs() < 0.02 * moved,
                "error {err}, tangential {moved}: {s:?}"
            );
        }
    }

    #[test]
    fn a_flawless_centred_axis_is_determined_at_zero() {
        // Every deviation 0 over 90° from 100°: the offsets are 0 and
        // determined (the limit is floored at 1 nm, not at the trace's 0).
        let angle_deg: Vec<f64> = (0..=90).map(|i| 100.0 + i as f64).collect();
        let s = Section {
            y: 12.0,
            deviation: vec![0.0; angle_deg.len()],
            angle_deg,
        };
        let b = estimate_alignment_band(&[s], &CFG).unwrap();
        let (e, s) = (&b.estimate.sections[0], &b.sections[0]);
        assert!(e.z.abs() < 1e-12 && e.x.abs() < 1e-12, "{e:?}");
        assert!(
            s.determined_z && s.determined_x && s.note.is_none(),
            "{s:?}"
        );
        assert!(s.band_z < 1e-9 && s.peak_to_valley == 0.0, "{s:?}");
    }

    #[test]
    fn the_default_order_and_the_work_budget() {
        // maxOrder left out is 10.
        let c: BandConfig = serde_json::from_str(r#"{"radius": 100}"#).unwrap();
        assert_eq!(c, CFG);
        // 2.3 M samples × (2·10 + 1)² is over 1e9: refused before any work,
        // naming the amount.
        let n = 2_300_000;
        let s = Section {
            y: 0.0,
            angle_deg: vec![0.0; n],
            deviation: vec![0.0; n],
        };
        let e = estimate_alignment_band(&[s], &CFG).unwrap_err().to_string();
        assert!(
            e.starts_with("alignment band: 1014300000 units of work"),
            "{e}"
        );
    }

    #[test]
    fn bad_max_order_and_short_sections_are_named() {
        let s = section(0.0, 0.0, 0.0, &[], 180.0, 0.0);
        let cfg = BandConfig {
            radius: 100.0,
            max_order: 0,
        };
        let e = estimate_alignment_band(std::slice::from_ref(&s), &cfg)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("maxOrder:") && e.contains("got 0"), "{e}");
        let cfg = BandConfig {
            radius: 100.0,
            max_order: 51,
        };
        assert!(estimate_alignment_band(&[s], &cfg)
            .unwrap_err()
            .to_string()
            .starts_with("maxOrder:"));
    }
}
