//! Least-squares circle fit: an algebraic (Kåsa) fit for the start value,
//! then geometric refinement by Levenberg–Marquardt.
//!
//! Source: the least-squares centre of takayama-alignment-travel-range §2.1
//! step (5) ("calculate a coordinate of the presumed rotation centre using
//! the method of least squares") and the LSC reference circle of ISO 230-4.
//!
//! Reading chosen: "least squares" is taken as the *geometric* fit, which
//! minimises Σ (|pᵢ − c| − r)² (the orthogonal distance to the circle, as in
//! ISO 230-4's LSC), not the algebraic residual Σ (|pᵢ − c|² − r²)², which is
//! biased on short arcs with noise. The algebraic fit only seeds the
//! iteration; on a noiseless arc both are exact, so the result is exact for
//! any span (tested down to 30°, and 10° in the unit tests).
//!
//! Numerics: the points are shifted to their centroid and scaled by their RMS
//! spread before fitting, so the fit is invariant to translation and rotation
//! and well conditioned for coordinates far from the origin.
//!
//! Units: whatever the inputs are in (mm in the core); the outputs are in the
//! same unit.

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

use crate::numeric::{levenberg_marquardt, LmOptions, Normal};

/// Errors of the circle fit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// Fewer than three points.
    #[error("a circle needs at least 3 points, got {0}")]
    TooFewPoints(usize),
    /// x and y arrays differ in length.
    #[error("x has {x} values but y has {y}: give one y per x")]
    LengthMismatch {
        /// Length of x.
        x: usize,
        /// Length of y.
        y: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("point {index} is not finite (x = {x}, y = {y})")]
    NotFinite {
        /// 0-based index of the point.
        index: usize,
        /// Its x.
        x: f64,
        /// Its y.
        y: f64,
    },
    /// All points lie on one straight line (or coincide).
    #[error("the points are collinear (or all equal): no circle passes through them; measure over a wider angle")]
    Collinear,
}

/// A fitted circle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Circle {
    /// Centre x.
    pub cx: f64,
    /// Centre y.
    pub cy: f64,
    /// Radius.
    pub r: f64,
    /// RMS of the orthogonal residuals |pᵢ − c| − r.
    pub rms_residual: f64,
}

/// Fits a circle to the points (`x[i]`, `y[i]`) in the geometric least-squares
/// sense.
///
/// # Units
/// Any length unit; the centre, radius and RMS residual come back in it.
///
/// # Errors
/// [`FitError`] for fewer than 3 points, unequal lengths, non-finite values
/// or collinear points.
///
/// # Examples
/// ```
/// use mtmotion::ballbar::fit_circle;
/// // A 30° arc of radius 50 about (3, −2).
/// let (x, y): (Vec<f64>, Vec<f64>) = (0..20)
///     .map(|i| {
///         let t = (i as f64 / 19.0 * 30.0).to_radians();
///         (3.0 + 50.0 * t.cos(), -2.0 + 50.0 * t.sin())
///     })
///     .unzip();
/// let c = fit_circle(&x, &y).unwrap();
/// assert!((c.cx - 3.0).abs() < 1e-9 && (c.cy + 2.0).abs() < 1e-9);
/// assert!((c.r - 50.0).abs() < 1e-9 && c.rms_residual < 1e-9);
/// assert!(fit_circle(&[0.0, 1.0, 2.0], &[0.0, 1.0, 2.0]).is_err());
/// ```
pub fn fit_circle(x: &[f64], y: &[f64]) -> Result<Circle, FitError> {
    if x.len() != y.len() {
        return Err(FitError::LengthMismatch {
            x: x.len(),
            y: y.len(),
        });
    }
    let n = x.len();
    if n < 3 {
        return Err(FitError::TooFewPoints(n));
    }
    let centroid = centroid(x, y)?;
    let (start, s) = kasa(x, y, centroid)?;
    // Levenberg–Marquardt on (a, b, r) in scaled coordinates
    // ([`crate::numeric::levenberg_marquardt`]). One pass over the points
    // per evaluation gives the cost and the normal equations together.
    let nf = n as f64;
    let pass = |p: &Vector3<f64>| geometric_pass(x, y, centroid, 1.0 / s, p);
    let opts = LmOptions {
        max_iterations: 60,
        // Converged: the gradient vanishes to rounding (scaled units) …
        gradient_tol: 1e-13 * nf,
        // … or the cost no longer drops.
        cost_drop_tol: 1e-28 * nf,
        ..LmOptions::default()
    };
    let fit = levenberg_marquardt(start, pass, |p| p, &opts);
    let (a, b, r, cost) = (fit.p[0], fit.p[1], fit.p[2], fit.normal.cost);
    if !(a.is_finite() && b.is_finite() && r.is_finite()) {
        return Err(FitError::Collinear);
    }
    let (mx, my) = centroid;
    Ok(Circle {
        cx: mx + a * s,
        cy: my + b * s,
        r: r.abs() * s,
        rms_residual: (cost / nf).sqrt() * s,
    })
}

/// The centroid of the points; a non-finite point is an error naming its index.
fn centroid(x: &[f64], y: &[f64]) -> Result<(f64, f64), FitError> {
    let (mut mx, mut my) = (0.0, 0.0);
    for (i, (&a, &b)) in x.iter().zip(y).enumerate() {
        if !a.is_finite() || !b.is_finite() {
            return Err(FitError::NotFinite {
                index: i,
                x: a,
                y: b,
            });
        }
        mx += a;
        my += b;
    }
    let nf = x.len() as f64;
    Ok((mx / nf, my / nf))
}

/// The algebraic (Kåsa) circle `x² + y² + D x + E y + F = 0` of the points
/// centred on `centroid` and scaled to unit spread: the start `(a, b, r)` in
/// those coordinates, and the spread `s` (the input's unit).
fn kasa(x: &[f64], y: &[f64], centroid: (f64, f64)) -> Result<(Vector3<f64>, f64), FitError> {
    let (mx, my) = centroid;
    let nf = x.len() as f64;
    // Second and third moments of the centred points, for the Kåsa fit.
    let (mut suu, mut suv, mut svv, mut suz, mut svz, mut sz) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (&a, &b) in x.iter().zip(y) {
        let (u, v) = (a - mx, b - my);
        let z = u * u + v * v;
        suu += u * u;
        suv += u * v;
        svv += v * v;
        suz += u * z;
        svz += v * z;
        sz += z;
    }
    let spread2 = (suu + svv) / nf;
    if spread2 <= 0.0 || !spread2.is_finite() {
        return Err(FitError::Collinear);
    }
    let s = spread2.sqrt();
    // Scale to unit spread: moments of order k scale by s^-k.
    let (suu, suv, svv) = (suu / spread2, suv / spread2, svv / spread2);
    let (suz, svz, sz) = (suz / (spread2 * s), svz / (spread2 * s), sz / spread2);
    let det = suu * svv - suv * suv;
    // The scatter matrix is singular for collinear points; relative to its
    // trace (= n after scaling) a determinant below 1e-20·n² means the
    // points deviate from a line by less than ~1e-10 of their spread.
    if det <= 1e-20 * nf * nf {
        return Err(FitError::Collinear);
    }
    let d = -(svv * suz - suv * svz) / det;
    let e = -(suu * svz - suv * suz) / det;
    let f = -sz / nf;
    let (a, b) = (-d / 2.0, -e / 2.0);
    let r = (a * a + b * b - f).max(0.0).sqrt();
    Ok((Vector3::new(a, b, r), s))
}

/// One pass over the points at `p = (a, b, r)` (scaled coordinates, `inv`
/// = 1/spread): the cost and the normal equations of the orthogonal
/// residuals |pᵢ − c| − r, with J = [−u/d, −v/d, −1] per point.
fn geometric_pass(
    x: &[f64],
    y: &[f64],
    centroid: (f64, f64),
    inv: f64,
    p: &Vector3<f64>,
) -> Normal<3> {
    let (mx, my) = centroid;
    let (a, b, r) = (p[0], p[1], p[2]);
    let (mut m, mut g, mut cost) = ([0.0f64; 5], [0.0f64; 3], 0.0);
    for (&px, &py) in x.iter().zip(y) {
        let (u, v) = ((px - mx) * inv - a, (py - my) * inv - b);
        let dist = (u * u + v * v).sqrt();
        let (ju, jv) = if dist > 0.0 {
            (-u / dist, -v / dist)
        } else {
            (0.0, 0.0)
        };
        let res = dist - r;
        m[0] += ju * ju;
        m[1] += ju * jv;
        m[2] -= ju;
        m[3] += jv * jv;
        m[4] -= jv;
        g[0] += ju * res;
        g[1] += jv * res;
        g[2] -= res;
        cost += res * res;
    }
    let nf = x.len() as f64;
    Normal {
        jtj: Matrix3::new(m[0], m[1], m[2], m[1], m[3], m[4], m[2], m[4], nf),
        jtr: Vector3::new(g[0], g[1], g[2]),
        cost,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arc(cx: f64, cy: f64, r: f64, from: f64, span: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
        (0..n)
            .map(|i| {
                let t = (from + span * i as f64 / (n - 1) as f64).to_radians();
                (cx + r * t.cos(), cy + r * t.sin())
            })
            .unzip()
    }

    #[test]
    fn exact_on_short_noiseless_arcs() {
        for span in [10.0, 30.0, 90.0, 180.0, 360.0] {
            let (x, y) = arc(1000.0, -250.0, 100.0, 17.0, span, 50);
            let c = fit_circle(&x, &y).unwrap();
            let tol = 1e-8;
            assert!((c.cx - 1000.0).abs() < tol, "{span}: {c:?}");
            assert!((c.cy + 250.0).abs() < tol, "{span}: {c:?}");
            assert!((c.r - 100.0).abs() < tol, "{span}: {c:?}");
        }
    }

    #[test]
    fn three_points_define_the_circle() {
        // Circle through (0,0), (2,0), (0,2): centre (1,1), r = √2.
        let c = fit_circle(&[0.0, 2.0, 0.0], &[0.0, 0.0, 2.0]).unwrap();
        assert!((c.cx - 1.0).abs() < 1e-12 && (c.cy - 1.0).abs() < 1e-12);
        assert!((c.r - 2f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn geometric_not_algebraic() {
        // Radial noise ±e alternating on a half circle: the geometric fit
        // keeps the radius (mean distance) at r, to first order.
        let n = 181;
        let (x, y): (Vec<f64>, Vec<f64>) = (0..n)
            .map(|i| {
                let t = (i as f64).to_radians();
                let rr = 10.0 + if i % 2 == 0 { 0.5 } else { -0.5 };
                (rr * t.cos(), rr * t.sin())
            })
            .unzip();
        let c = fit_circle(&x, &y).unwrap();
        // The mean of the residuals of a geometric LS fit is zero.
        let mean: f64 = x
            .iter()
            .zip(&y)
            .map(|(a, b)| (a - c.cx).hypot(b - c.cy) - c.r)
            .sum::<f64>()
            / n as f64;
        assert!(mean.abs() < 1e-12, "{mean}");
        assert!((c.rms_residual - 0.5).abs() < 0.01, "{c:?}");
    }

    #[test]
    fn rejects_bad_input() {
        assert_eq!(
            fit_circle(&[1.0, 2.0], &[1.0, 2.0]),
            Err(FitError::TooFewPoints(2))
        );
        assert_eq!(
            fit_circle(&[1.0, 2.0, 3.0], &[1.0, 2.0]),
            Err(FitError::LengthMismatch { x: 3, y: 2 })
        );
        assert_eq!(
            fit_circle(&[0.0, 1.0, 2.0, 3.0], &[1.0, 3.0, 5.0, 7.0]),
            Err(FitError::Collinear)
        );
        assert_eq!(fit_circle(&[1.0; 4], &[2.0; 4]), Err(FitError::Collinear));
        assert!(matches!(
            fit_circle(&[0.0, 1.0, f64::NAN], &[0.0, 1.0, 0.0]),
            Err(FitError::NotFinite { index: 2, .. })
        ));
    }
}
