//! One section's centre estimate and what its data can say about it:
//! takayama-alignment-travel-range §2.1 (the bias of a partial-range
//! least-squares centre from the motion-error harmonics) applied to a
//! measured trace, with the harmonic orders chosen by a stated
//! significance rule and the noise treated statistically.
//!
//! Model (first order in Δ/R, the same linearisation as §2.1): the radial
//! deviation of a section is
//! d(θ) = a₀ + a₁ cos θ + b₁ sin θ + Σₙ₌₂ᴺ (aₙ cos nθ + bₙ sin nθ) + ε,
//! (a₁, b₁) the centre (Z, X), orders ≥ 2 the motion error, ε noise.
//!
//! Readings chosen (the paper's model has no noise; a measured trace does):
//! - the reported offset is the paper's: the least-squares centre (orders
//!   0 and 1 only). Its systematic error (takayama's term) is the part of
//!   the motion error that the span cannot tell from a centre shift:
//!   bias = (a₁, b₁)₀…₁ − (a₁, b₁)₀…N, the identity of nested least squares
//!   (the §2.1 simulation with the fitted harmonics gives the same to first
//!   order; a test checks it against [`super::travel_range_sweep`]);
//! - the order N is chosen by the Bayesian information criterion
//!   BIC(n) = m′·ln(RSSₙ/m) + (2n + 1)·ln m′ over n = 1 … the highest order
//!   the span resolves (≤ `max_order`): harmonics are kept only where they
//!   explain more than noise does. m′ = m/f is the effective number of
//!   samples, f = (1 + ρ)/(1 − ρ) with ρ the lag-1 autocorrelation of the
//!   residuals of the largest resolved model (a 1 kHz capture's noise is
//!   not white); RSS/m is floored at (1 nm)², below any instrument, so a
//!   noise-free trace selects its true orders;
//! - an order n is resolved when every pivot of the triangular factor up to
//!   its columns is above 1e-7 of the first (the columns of higher orders
//!   over a short span are numerically dependent);
//! - the statistical part is the standard error of the centre in the
//!   selected model: σ²·f·[(RᵀR)⁻¹]ⱼⱼ, σ² = RSS_N/(m − 2N − 1). It
//!   includes the loss when the span confuses the centre with a harmonic.
//!
//! The fit is a streaming Householder QR over blocks of rows, so memory is
//! O(N²) for traces of any length, and every nested model's residual sum
//! of squares comes from the one factorisation.
//!
//! Units: θ in rad, deviations and results in mm.

use nalgebra::{DMatrix, DVector};

use crate::ballbar::Harmonic;

/// Rows per block of the streaming QR.
const BLOCK: usize = 512;
/// Relative pivot below which an order is not resolved by the span.
const PIVOT_TOL: f64 = 1e-7;
/// Floor of the residual mean square, mm² (1 nm)².
const RMS_FLOOR_SQ: f64 = 1e-12;

/// The centre estimate of one section with its systematic and statistical
/// parts.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionFit {
    /// Highest harmonic order selected (1: no motion-error harmonic).
    pub order: usize,
    /// Highest order the section's span resolves (≤ the maximum asked).
    pub resolved: usize,
    /// Selected harmonics, orders 2 … `order`, amplitude mm, phase rad.
    pub harmonics: Vec<Harmonic>,
    /// Least-squares centre (orders 0–1), (Z, X), mm.
    pub centre: [f64; 2],
    /// Systematic error of that centre: its value minus the centre of the
    /// selected model, (Z, X), mm.
    pub bias: [f64; 2],
    /// Standard error of the centre in the selected model, (Z, X), mm.
    pub sigma: [f64; 2],
    /// Residual standard deviation of the selected model, mm.
    pub noise: f64,
    /// Variance factor f = (1 + ρ)/(1 − ρ) of correlated residuals (≥ 1).
    pub correlation_factor: f64,
}

/// Errors of the section fit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SectionFitError {
    /// Not enough samples for orders 0 and 1 plus one degree of freedom.
    #[error("{0} samples: at least 4 are needed to fit a centre")]
    TooFew(usize),
    /// The span is too short to fit a centre at all.
    #[error("the samples span too small an arc to fit a centre: measure a longer arc")]
    NoCentre,
    /// A sample is NaN or infinite.
    #[error("sample {0} is not a finite number")]
    NotFinite(usize),
}

/// The upper-triangular factor R, Qᵀd (first p entries) and the residual
/// sum of squares of the full model, accumulated block by block.
struct Factor {
    r: DMatrix<f64>,
    qty: DVector<f64>,
    rss: f64,
}

fn row(theta: f64, p: usize, out: &mut [f64]) {
    out[0] = 1.0;
    for k in 1..=p / 2 {
        let (s, c) = (k as f64 * theta).sin_cos();
        out[2 * k - 1] = c;
        out[2 * k] = s;
    }
}

fn factor(theta: &[f64], dev: &[f64], p: usize) -> Factor {
    let mut r = DMatrix::<f64>::zeros(p, p);
    let mut qty = DVector::<f64>::zeros(p);
    let mut rss = 0.0;
    let mut buf = vec![0.0; p];
    for (ts, ds) in theta.chunks(BLOCK).zip(dev.chunks(BLOCK)) {
        let rows = p + ts.len();
        let mut m = DMatrix::<f64>::zeros(rows, p);
        let mut v = DVector::<f64>::zeros(rows);
        m.view_mut((0, 0), (p, p)).copy_from(&r);
        v.rows_mut(0, p).copy_from(&qty);
        for (i, (&t, &d)) in ts.iter().zip(ds).enumerate() {
            row(t, p, &mut buf);
            for (j, b) in buf.iter().enumerate() {
                m[(p + i, j)] = *b;
            }
            v[p + i] = d;
        }
        let qr = m.qr();
        qr.q_tr_mul(&mut v);
        r = qr.r();
        qty = v.rows(0, p).into_owned();
        rss += v.rows(p, rows - p).norm_squared();
    }
    Factor { r, qty, rss }
}

/// Solves the leading p×p block: coefficients and the diagonal of (RᵀR)⁻¹
/// for the columns 1 and 2 (the centre).
fn leading(f: &Factor, p: usize) -> Option<(DVector<f64>, [f64; 2])> {
    let r = f.r.view((0, 0), (p, p)).upper_triangle();
    let b = r.solve_upper_triangular(&f.qty.rows(0, p).into_owned())?;
    let inv = r.solve_upper_triangular(&DMatrix::identity(p, p))?;
    let var = [inv.row(1).norm_squared(), inv.row(2).norm_squared()];
    Some((b, var))
}

/// Fits one section (see the module header): `theta` in rad, `dev` in mm,
/// candidate orders up to `max_order` (at least 1).
///
/// # Errors
/// [`SectionFitError`] for fewer than 4 samples, a non-finite sample, or a
/// span too short to fit a centre.
///
/// # Examples
/// ```
/// use mtmotion::alignment::section_fit::fit_section;
/// // A 12 µm offset along X seen over 180°, no motion error, no noise.
/// let th: Vec<f64> = (0..=180).map(|i| (i as f64 - 90.0).to_radians()).collect();
/// let d: Vec<f64> = th.iter().map(|t| 0.012 * t.sin()).collect();
/// let f = fit_section(&th, &d, 10).unwrap();
/// assert_eq!(f.order, 1);
/// assert!((f.centre[1] - 0.012).abs() < 1e-12 && f.bias[1].abs() < 1e-12);
/// ```
pub fn fit_section(
    theta: &[f64],
    dev: &[f64],
    max_order: usize,
) -> Result<SectionFit, SectionFitError> {
    let m = theta.len().min(dev.len());
    if m < 4 {
        return Err(SectionFitError::TooFew(m));
    }
    if let Some(i) = (0..m).find(|&i| !(theta[i].is_finite() && dev[i].is_finite())) {
        return Err(SectionFitError::NotFinite(i));
    }
    // Orders with at least one residual degree of freedom.
    let top = max_order.max(1).min((m - 2) / 2);
    let p = 2 * top + 1;
    let f = factor(&theta[..m], &dev[..m], p);
    let r00 = f.r[(0, 0)].abs();
    let resolved_cols = (0..p)
        .take_while(|&j| f.r[(j, j)].abs() > PIVOT_TOL * r00)
        .count();
    let resolved = (resolved_cols.saturating_sub(1)) / 2;
    if resolved == 0 {
        return Err(SectionFitError::NoCentre);
    }
    // Residual sum of squares of each nested model n = 0 … resolved.
    let rss = |n: usize| f.rss + f.qty.rows(2 * n + 1, p - 2 * n - 1).norm_squared();
    let factor_rho = correlation_factor(theta, dev, &f, resolved);
    let (mf, me) = (m as f64, m as f64 / factor_rho);
    let bic = |n: usize| {
        let ms = (rss(n) / mf).max(RMS_FLOOR_SQ);
        me * (ms).ln() + (2 * n + 1) as f64 * me.ln()
    };
    let order = (1..=resolved)
        .min_by(|&a, &b| bic(a).total_cmp(&bic(b)))
        .unwrap_or(1);
    let pn = 2 * order + 1;
    let (b, var) = leading(&f, pn).ok_or(SectionFitError::NoCentre)?;
    let (b01, _) = leading(&f, 3).ok_or(SectionFitError::NoCentre)?;
    let dof = (m - pn) as f64;
    let s2 = rss(order) / dof;
    let harmonics = (2..=order)
        .map(|k| {
            let (a, s) = (b[2 * k - 1], b[2 * k]);
            Harmonic {
                order: k as u32,
                amplitude: a.hypot(s),
                phase: a.atan2(s),
            }
        })
        .collect();
    Ok(SectionFit {
        order,
        resolved,
        harmonics,
        centre: [b01[1], b01[2]],
        bias: [b01[1] - b[1], b01[2] - b[2]],
        sigma: [
            (s2 * factor_rho * var[0]).sqrt(),
            (s2 * factor_rho * var[1]).sqrt(),
        ],
        noise: s2.sqrt(),
        correlation_factor: factor_rho,
    })
}

/// The centre terms (Z, X) of the least-squares fit of `values` on
/// {1, cos θ, sin θ} over the samples `theta` (rad): how a term of the
/// radial deviation moves the section's centre estimate. Zero when the span
/// cannot fit a centre.
pub fn centre_projection(theta: &[f64], values: &[f64]) -> [f64; 2] {
    if theta.len() < 3 || theta.len() != values.len() {
        return [0.0, 0.0];
    }
    let f = factor(theta, values, 3);
    match leading(&f, 3) {
        Some((b, _)) if b.iter().all(|v| v.is_finite()) => [b[1], b[2]],
        _ => [0.0, 0.0],
    }
}

/// f = (1 + ρ)/(1 − ρ) from the lag-1 autocorrelation ρ of the residuals
/// of the model up to order `n` (1 when ρ ≤ 0; ρ capped at 0.999).
fn correlation_factor(theta: &[f64], dev: &[f64], f: &Factor, n: usize) -> f64 {
    let p = 2 * n + 1;
    let Some((b, _)) = leading(f, p) else {
        return 1.0;
    };
    let mut buf = vec![0.0; f.r.nrows()];
    let (mut prev, mut num, mut den) = (None::<f64>, 0.0, 0.0);
    for (&t, &d) in theta.iter().zip(dev) {
        row(t, f.r.nrows(), &mut buf);
        let e = d - (0..p).map(|j| buf[j] * b[j]).sum::<f64>();
        if let Some(q) = prev {
            num += q * e;
        }
        den += e * e;
        prev = Some(e);
    }
    let rho = if den > 0.0 {
        (num / den).min(0.999)
    } else {
        0.0
    };
    if rho > 0.0 {
        (1.0 + rho) / (1.0 - rho)
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::numeric::gaussian as gauss;

    fn arc(from_deg: f64, span_deg: f64, n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| (from_deg + span_deg * i as f64 / (n - 1) as f64).to_radians())
            .collect()
    }

    #[test]
    fn noise_only_selects_no_harmonic_and_its_sigma_is_the_textbook_one() {
        // 180° from 31°, offset (7, −3) µm, 0.3 µm white noise.
        let th = arc(31.0, 180.0, 2000);
        let e = gauss(7, th.len());
        let d: Vec<f64> = th
            .iter()
            .zip(&e)
            .map(|(t, n)| 0.004 + 0.007 * t.cos() - 0.003 * t.sin() + 3e-4 * n)
            .collect();
        let f = fit_section(&th, &d, 10).unwrap();
        assert_eq!(f.order, 1, "{f:?}");
        assert_eq!(f.bias, [0.0, 0.0]);
        assert!((f.noise - 3e-4).abs() < 2e-5, "{}", f.noise);
        assert!(f.correlation_factor < 1.2, "{}", f.correlation_factor);
        // The centre is within 3σ, and σ is of the order σ_noise/√(m/2).
        for (k, want) in [0.007, -0.003].into_iter().enumerate() {
            assert!((f.centre[k] - want).abs() < 3.0 * f.sigma[k], "{f:?}");
            assert!(f.sigma[k] > 5e-6 && f.sigma[k] < 5e-5, "{f:?}");
        }
        assert!(f.resolved >= 8, "{f:?}");
    }

    #[test]
    fn noise_free_harmonics_are_selected_and_the_bias_is_the_actual_error() {
        // 150° from −20°: orders 2 and 4 of 5 and 2 µm, offset (10, 4) µm.
        let th = arc(-20.0, 150.0, 1501);
        let d: Vec<f64> = th
            .iter()
            .map(|t| {
                0.010 * t.cos()
                    + 0.004 * t.sin()
                    + 0.005 * (2.0 * t + 0.4).sin()
                    + 0.002 * (4.0 * t - 1.0).sin()
            })
            .collect();
        let f = fit_section(&th, &d, 8).unwrap();
        assert_eq!(f.order, 4, "{f:?}");
        // bias = LS centre − truth, exactly (the model holds).
        assert!((f.centre[0] - 0.010 - f.bias[0]).abs() < 1e-9, "{f:?}");
        assert!((f.centre[1] - 0.004 - f.bias[1]).abs() < 1e-9, "{f:?}");
        assert!(f.bias[0].abs() > 1e-3, "{f:?}");
        let h2 = f.harmonics.iter().find(|h| h.order == 2).unwrap();
        assert!((h2.amplitude - 0.005).abs() < 1e-9 && (h2.phase - 0.4).abs() < 1e-6);
    }

    #[test]
    fn correlated_noise_widens_sigma() {
        // AR(1) noise with φ = 0.9: f ≈ 19, so σ grows about √19-fold
        // against white noise of the same variance.
        let th = arc(10.0, 200.0, 4000);
        let w = gauss(3, th.len());
        let mut ar = vec![0.0; th.len()];
        for i in 1..th.len() {
            ar[i] = 0.9 * ar[i - 1] + (1.0f64 - 0.81).sqrt() * w[i];
        }
        let d_ar: Vec<f64> = th
            .iter()
            .zip(&ar)
            .map(|(t, n)| 0.01 * t.sin() + 3e-4 * n)
            .collect();
        let d_w: Vec<f64> = th
            .iter()
            .zip(&w)
            .map(|(t, n)| 0.01 * t.sin() + 3e-4 * n)
            .collect();
        let (a, b) = (
            fit_section(&th, &d_ar, 10).unwrap(),
            fit_section(&th, &d_w, 10).unwrap(),
        );
        // The effective count m/f keeps the BIC from reading the
        // correlated noise as harmonics.
        assert_eq!((a.order, b.order), (1, 1), "{a:?} {b:?}");
        assert!(a.sigma[0] > 3.0 * b.sigma[0], "{a:?} vs {b:?}");
        assert!(
            a.correlation_factor > 12.0 && a.correlation_factor < 30.0,
            "{a:?}"
        );
        assert!(a.sigma[1] > 3.0 * b.sigma[1], "{a:?} vs {b:?}");
    }

    #[test]
    fn streaming_equals_one_block_and_short_input_is_refused() {
        // More rows than a block: the same result as the dense QR of
        // fit_harmonics (a second method) for the selected model.
        let th = arc(5.0, 250.0, 3 * BLOCK + 17);
        let d: Vec<f64> = th
            .iter()
            .map(|t| 0.002 + 0.003 * (3.0 * t).cos() - 0.001 * t.cos())
            .collect();
        let f = fit_section(&th, &d, 6).unwrap();
        let dense = crate::ballbar::fit_harmonics(&th, &d, f.order).unwrap();
        let h3 = f.harmonics.iter().find(|h| h.order == 3).unwrap();
        assert!((h3.amplitude - dense[3].amplitude).abs() < 1e-12);
        assert_eq!(
            fit_section(&th[..3], &d[..3], 4),
            Err(SectionFitError::TooFew(3))
        );
        let mut bad = d.clone();
        bad[9] = f64::NAN;
        assert_eq!(
            fit_section(&th, &bad, 4),
            Err(SectionFitError::NotFinite(9))
        );
        let flat = vec![0.3; 10];
        assert_eq!(fit_section(&flat, &flat, 4), Err(SectionFitError::NoCentre));
    }

    #[test]
    fn sigma_and_noise_are_the_textbook_ones() {
        // A second computation: (XᵀX)⁻¹ of {1, cos, sin} formed directly,
        // the residual of fit_harmonics' dense QR, σ² = RSS/(m − 3).
        let th = arc(-40.0, 160.0, 1200);
        let e = gauss(21, th.len());
        let d: Vec<f64> = th
            .iter()
            .zip(&e)
            .map(|(t, n)| 0.002 - 0.006 * t.cos() + 0.009 * t.sin() + 5e-4 * n)
            .collect();
        let f = fit_section(&th, &d, 10).unwrap();
        assert_eq!(f.order, 1, "{f:?}");
        let mut xtx = nalgebra::Matrix3::<f64>::zeros();
        for t in &th {
            let r = nalgebra::Vector3::new(1.0, t.cos(), t.sin());
            xtx += r * r.transpose();
        }
        let inv = xtx.try_inverse().unwrap();
        let h = crate::ballbar::fit_harmonics(&th, &d, 1).unwrap();
        let rss: f64 = th
            .iter()
            .zip(&d)
            .map(|(t, v)| (v - h.iter().map(|c| c.eval(*t)).sum::<f64>()).powi(2))
            .sum();
        let s2 = rss / (th.len() - 3) as f64;
        assert!(
            (f.noise - s2.sqrt()).abs() < 1e-12 * s2.sqrt(),
            "{} vs {}",
            f.noise,
            s2.sqrt()
        );
        for k in 0..2 {
            let want = (s2 * f.correlation_factor * inv[(k + 1, k + 1)]).sqrt();
            assert!(
                (f.sigma[k] - want).abs() < 1e-9 * want,
                "{k}: {} vs {want}",
                f.sigma[k]
            );
        }
    }

    #[test]
    fn the_bic_keeps_a_harmonic_above_its_threshold_and_not_below() {
        // Full circle, white noise σ: adding order 3 lowers m·ln RSS by
        // about m·A²/(2σ²) and costs 2·ln m, so the threshold is
        // A* = σ·√(4 ln m / m). 0.6 A* is dropped, 1.6 A* is kept.
        let m = 3000;
        let th = arc(0.0, 360.0 * (m - 1) as f64 / m as f64, m);
        let e = gauss(5, m);
        let sigma = 3e-4;
        let a_star = sigma * (4.0 * (m as f64).ln() / m as f64).sqrt();
        for (scale, want) in [(0.6, 1), (1.6, 3)] {
            let d: Vec<f64> = th
                .iter()
                .zip(&e)
                .map(|(t, n)| 0.004 * t.cos() + scale * a_star * (3.0 * t + 0.5).sin() + sigma * n)
                .collect();
            let f = fit_section(&th, &d, 6).unwrap();
            assert_eq!(f.order, want, "{scale} A*: {f:?}");
        }
    }

    #[test]
    fn a_top_order_harmonic_leaves_white_residuals_and_every_order_is_resolved() {
        // Orders up to 10 over a full circle are all resolved, and the
        // residual model includes order 10's sine and cosine: ρ ≈ 0.
        let th = arc(3.0, 359.0, 3600);
        let e = gauss(9, th.len());
        let d: Vec<f64> = th
            .iter()
            .zip(&e)
            .map(|(t, n)| 0.005 * (10.0 * t + 0.2).sin() + 3e-4 * n)
            .collect();
        let f = fit_section(&th, &d, 10).unwrap();
        assert_eq!((f.resolved, f.order), (10, 10), "{f:?}");
        assert!(f.correlation_factor < 1.2, "{f:?}");
        // A 30° span resolves far fewer orders against the centre.
        let short = arc(100.0, 30.0, 600);
        let d: Vec<f64> = short.iter().map(|t| 0.001 * t.cos()).collect();
        let g = fit_section(&short, &d, 10).unwrap();
        assert!(g.resolved >= 1 && g.resolved <= 4, "{g:?}");
    }

    #[test]
    fn few_samples_fit_the_orders_they_can() {
        // 4 samples: orders 0–1 with one degree of freedom; 9 samples on a
        // full circle resolve up to order 3 ((9 − 2)/2), whatever is asked.
        let th4 = arc(0.0, 270.0, 4);
        let d4: Vec<f64> = th4.iter().map(|t| 0.01 * t.cos()).collect();
        let f = fit_section(&th4, &d4, 10).unwrap();
        assert_eq!(f.resolved, 1);
        assert!((f.centre[0] - 0.01).abs() < 1e-12, "{f:?}");
        let th9 = arc(0.0, 320.0, 9);
        let d9: Vec<f64> = th9.iter().map(|t| 0.01 * t.sin()).collect();
        assert_eq!(fit_section(&th9, &d9, 10).unwrap().resolved, 3);
    }

    #[test]
    fn centre_projection_moves_the_centre_by_the_terms_share() {
        // cos θ over any arc is a pure Z shift; a constant none.
        let th = arc(20.0, 130.0, 300);
        let c: Vec<f64> = th
            .iter()
            .map(|t| 0.003 * t.cos() - 0.001 * t.sin() + 0.7)
            .collect();
        let p = centre_projection(&th, &c);
        assert!(
            (p[0] - 0.003).abs() < 1e-12 && (p[1] + 0.001).abs() < 1e-12,
            "{p:?}"
        );
        assert_eq!(centre_projection(&th[..2], &c[..2]), [0.0, 0.0]);
        // Three points are enough for a centre.
        let p3 = centre_projection(&th[..3], &c[..3]);
        assert!(
            (p3[0] - 0.003).abs() < 1e-9 && (p3[1] + 0.001).abs() < 1e-9,
            "{p3:?}"
        );
        assert_eq!(centre_projection(&th, &c[..10]), [0.0, 0.0]);
        let mut bad = c.clone();
        bad[4] = f64::NAN;
        assert_eq!(centre_projection(&th, &bad), [0.0, 0.0]);
    }

    #[test]
    fn a_flawless_trace_has_no_correlation_to_widen() {
        // Residuals exactly zero: no autocorrelation (ρ undefined is 0),
        // f = 1, σ = 0.
        let th = arc(10.0, 200.0, 500);
        let f = fit_section(&th, &vec![0.0; th.len()], 6).unwrap();
        assert_eq!(
            (f.correlation_factor, f.sigma, f.order),
            (1.0, [0.0, 0.0], 1)
        );
    }

    #[test]
    fn a_sub_nanometre_harmonic_is_below_the_floor() {
        // 0.3 nm of order 3 on 0.05 nm of noise: the residual mean square
        // is floored at (1 nm)² (no instrument resolves less), so the BIC
        // keeps no harmonic; 30 nm of order 3 is kept.
        let th = arc(0.0, 359.0, 1000);
        let e = gauss(13, th.len());
        for (amp, want) in [(3e-7, 1), (3e-5, 3)] {
            let d: Vec<f64> = th
                .iter()
                .zip(&e)
                .map(|(t, n)| 0.002 * t.cos() + amp * (3.0 * t).sin() + 5e-8 * n)
                .collect();
            assert_eq!(fit_section(&th, &d, 6).unwrap().order, want, "{amp} mm");
        }
    }
}
