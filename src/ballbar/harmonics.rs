//! Least-squares harmonic (Fourier) fit of a radial deviation Δr(θ).
//!
//! Source: takayama-alignment-travel-range §2.1 and §4.1.4 (Fig. 10: amplitude
//! and phase of each order of the motion-error trace, orders up to 10).
//!
//! Model: Δr(θ) = Σₙ Aₙ sin(nθ + φₙ), n = 0 … N. Order 0 is the mean
//! (reported signed as A₀ with φ₀ = π/2, so that A₀ sin φ₀ = mean), order 1 is the
//! eccentricity (centre offset), orders ≥ 2 are the "motion-error
//! components" of the paper ("n-th component" = n cycles per revolution).
//!
//! Reading chosen: the paper's "Fourier analysis" is done here as a
//! least-squares fit of the 2N+1 coefficients (QR on the design matrix),
//! so it is exact on partial ranges and unevenly spaced samples, where a
//! plain FFT is not. On a full, evenly sampled revolution it equals the DFT.
//! Phase convention: *sine* with +φ, as in kato Eq. 1 (worm-gear pitch
//! error W sin(Nθ + φ), used by `servo`), so (a cos nθ + b sin nθ) gives
//! A = √(a² + b²), φ = atan2(a, b). With all phases 0 (the paper's Fig. 6
//! setting) this convention is the one under which the paper's Fig. 7
//! magnitudes are reproduced best (see `docs/ballbar.md`).
//!
//! Units: θ in rad; Aₙ in the unit of Δr (mm in the core); φₙ in rad.

use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

/// Errors of the harmonic fit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HarmonicsError {
    /// Angle and deviation arrays differ in length.
    #[error(
        "angle has {angle} values but deviation has {deviation}: give one deviation per angle"
    )]
    LengthMismatch {
        /// Length of the angle array.
        angle: usize,
        /// Length of the deviation array.
        deviation: usize,
    },
    /// Not enough samples for the requested order.
    #[error("{points} samples cannot determine harmonics up to order {order} ({needed} coefficients); lower maxOrder or give more samples")]
    TooFewPoints {
        /// Samples given.
        points: usize,
        /// Requested maximum order.
        order: usize,
        /// Coefficients to determine.
        needed: usize,
    },
    /// A value is NaN or infinite.
    #[error("sample {index} is not finite (angle {angle}, deviation {deviation})")]
    NotFinite {
        /// 0-based sample index.
        index: usize,
        /// Its angle.
        angle: f64,
        /// Its deviation.
        deviation: f64,
    },
    /// A value is finite but outside its range ([`MAX_ANGLE`],
    /// [`MAX_DEVIATION`]).
    #[error("sample {index}: {what} {} is outside ±{}{unit}; check the trace's units", crate::numeric::compact(*.value), crate::numeric::compact(*.limit))]
    OutOfRange {
        /// 0-based sample index.
        index: usize,
        /// "angle" or "deviation".
        what: &'static str,
        /// The value.
        value: f64,
        /// The largest magnitude allowed.
        limit: f64,
        /// " rad" or "".
        unit: &'static str,
    },
    /// The order is too high for the angular span (columns nearly dependent).
    #[error(
        "harmonics up to order {order} cannot be separated over this angular span; lower maxOrder"
    )]
    IllConditioned {
        /// Requested maximum order.
        order: usize,
    },
    /// Order above the supported maximum.
    #[error("maxOrder {0} is too large: at most 1000")]
    OrderTooLarge(usize),
    /// The design matrix would not fit in memory.
    #[error("{points} samples × {coefficients} coefficients is too large (at most 2e7): decimate the trace or lower maxOrder")]
    TooLarge {
        /// Samples given.
        points: usize,
        /// Coefficients to determine.
        coefficients: usize,
    },
}

/// One harmonic component A sin(nθ + φ).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Harmonic {
    /// Order n (cycles per revolution).
    pub order: u32,
    /// Amplitude A (unit of the deviation).
    pub amplitude: f64,
    /// Phase φ, rad.
    #[serde(default)]
    pub phase: f64,
}

impl Harmonic {
    /// Value A sin(nθ + φ) at `theta` (rad).
    pub fn eval(&self, theta: f64) -> f64 {
        self.amplitude * (f64::from(self.order) * theta + self.phase).sin()
    }
}

/// Σ of the harmonics at `theta` (rad).
pub fn synthesize(harmonics: &[Harmonic], theta: f64) -> f64 {
    harmonics.iter().map(|h| h.eval(theta)).sum()
}

/// Largest |angle| of a fitted sample, rad (160,000 turns).
pub const MAX_ANGLE: f64 = 1e6;
/// Largest |deviation| of a fitted sample, in its unit: 1 km in µm; far
/// larger values overflow the fit's sums (1e308 gave an infinite amplitude).
pub const MAX_DEVIATION: f64 = 1e9;

/// Every sample finite, its angle within ±[`MAX_ANGLE`] rad and its
/// deviation within ±[`MAX_DEVIATION`].
fn check_samples(angle: &[f64], deviation: &[f64]) -> Result<(), HarmonicsError> {
    for (i, (&a, &d)) in angle.iter().zip(deviation).enumerate() {
        if !a.is_finite() || !d.is_finite() {
            return Err(HarmonicsError::NotFinite {
                index: i,
                angle: a,
                deviation: d,
            });
        }
        for (what, value, limit, unit) in [
            ("angle", a, MAX_ANGLE, " rad"),
            ("deviation", d, MAX_DEVIATION, ""),
        ] {
            if value.abs() > limit {
                return Err(HarmonicsError::OutOfRange {
                    index: i,
                    what,
                    value,
                    limit,
                    unit,
                });
            }
        }
    }
    Ok(())
}

/// Fits Δr(θ) = Σₙ₌₀ᴺ Aₙ sin(nθ + φₙ) by least squares and returns orders
/// 0 … `max_order`.
///
/// # Units
/// `angle` in rad, `deviation` in any unit (mm in the core); amplitudes in
/// that unit, phases in rad.
///
/// # Errors
/// [`HarmonicsError`] for unequal lengths, non-finite or out-of-range values, too few
/// samples, or an order that the angular span cannot resolve.
///
/// # Examples
/// ```
/// use mtmotion::ballbar::fit_harmonics;
/// // 5 µm of order 2 with phase 0.3 rad, seen only over 180°.
/// let th: Vec<f64> = (0..181).map(|i| (i as f64 - 90.0).to_radians()).collect();
/// let dr: Vec<f64> = th.iter().map(|t| 0.005 * (2.0 * t + 0.3).sin()).collect();
/// let h = fit_harmonics(&th, &dr, 5).unwrap();
/// assert!((h[2].amplitude - 0.005).abs() < 1e-12 && (h[2].phase - 0.3).abs() < 1e-9);
/// assert!(h[3].amplitude < 1e-12);
/// ```
pub fn fit_harmonics(
    angle: &[f64],
    deviation: &[f64],
    max_order: usize,
) -> Result<Vec<Harmonic>, HarmonicsError> {
    if angle.len() != deviation.len() {
        return Err(HarmonicsError::LengthMismatch {
            angle: angle.len(),
            deviation: deviation.len(),
        });
    }
    if max_order > 1000 {
        return Err(HarmonicsError::OrderTooLarge(max_order));
    }
    let (n, m) = (angle.len(), 2 * max_order + 1);
    if n < m {
        return Err(HarmonicsError::TooFewPoints {
            points: n,
            order: max_order,
            needed: m,
        });
    }
    if n.saturating_mul(m) > 20_000_000 {
        return Err(HarmonicsError::TooLarge {
            points: n,
            coefficients: m,
        });
    }
    check_samples(angle, deviation)?;
    let design = DMatrix::from_fn(n, m, |i, j| {
        let k = j.div_ceil(2) as f64;
        match j {
            0 => 1.0,
            _ if j % 2 == 1 => (k * angle[i]).cos(),
            _ => (k * angle[i]).sin(),
        }
    });
    let qr = design.qr();
    let r = qr.r();
    let diag_max = (0..m).map(|k| r[(k, k)].abs()).fold(0.0, f64::max);
    if (0..m).any(|k| r[(k, k)].abs() <= 1e-10 * diag_max) {
        return Err(HarmonicsError::IllConditioned { order: max_order });
    }
    let qtb = qr.q().transpose() * nalgebra::DVector::from_column_slice(deviation);
    let coef = r
        .solve_upper_triangular(&qtb)
        .ok_or(HarmonicsError::IllConditioned { order: max_order })?;
    let mut out = vec![Harmonic {
        order: 0,
        amplitude: coef[0],
        phase: std::f64::consts::FRAC_PI_2,
    }];
    for k in 1..=max_order {
        let (a, b) = (coef[2 * k - 1], coef[2 * k]);
        out.push(Harmonic {
            order: k as u32,
            amplitude: a.hypot(b),
            phase: a.atan2(b),
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_revolution_equals_the_dft() {
        // Evenly sampled 360°: the LS coefficients are the DFT ones.
        let n = 64;
        let th: Vec<f64> = (0..n)
            .map(|i| i as f64 * std::f64::consts::TAU / n as f64)
            .collect();
        let dr: Vec<f64> = th
            .iter()
            .map(|t| 0.3 + 0.01 * (3.0 * t).sin() + 0.002 * t.cos() + 0.004 * (7.0 * t).cos())
            .collect();
        let h = fit_harmonics(&th, &dr, 10).unwrap();
        for (k, hk) in h.iter().enumerate() {
            let (mut a, mut b) = (0.0, 0.0);
            for (t, d) in th.iter().zip(&dr) {
                a += d * (k as f64 * t).cos();
                b += d * (k as f64 * t).sin();
            }
            let s = if k == 0 { 1.0 } else { 2.0 } / n as f64;
            let amp = (a * s).hypot(b * s);
            assert!((hk.amplitude.abs() - amp).abs() < 1e-12, "order {k}");
        }
        assert!((h[0].amplitude - 0.3).abs() < 1e-12);
        assert!((h[3].amplitude - 0.01).abs() < 1e-12);
        // sin 3θ: φ = 0; cos θ = sin(θ + π/2): φ = π/2.
        assert!(h[3].phase.abs() < 1e-9);
        assert!((h[1].phase - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
        let back: f64 = h.iter().map(|c| c.eval(th[5])).sum();
        assert!((back - dr[5]).abs() < 1e-12);
    }

    #[test]
    fn rejects_what_it_cannot_resolve() {
        let th = [0.0, 0.1, 0.2];
        assert!(matches!(
            fit_harmonics(&th, &[0.0; 3], 2),
            Err(HarmonicsError::TooFewPoints { needed: 5, .. })
        ));
        assert!(matches!(
            fit_harmonics(&th, &[0.0; 2], 1),
            Err(HarmonicsError::LengthMismatch { .. })
        ));
        let big = vec![0.0; 30_000];
        assert!(matches!(
            fit_harmonics(&big, &big, 500),
            Err(HarmonicsError::TooLarge { .. })
        ));
        // Order 30 over a 5° span: columns are numerically dependent.
        let th: Vec<f64> = (0..200).map(|i| (i as f64 * 0.025).to_radians()).collect();
        assert_eq!(
            fit_harmonics(&th, &vec![0.0; 200], 30),
            Err(HarmonicsError::IllConditioned { order: 30 })
        );
    }
}
