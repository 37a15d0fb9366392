//! Brent's root finder (R. P. Brent, *Algorithms for Minimization without
//! Derivatives*, 1973, ch. 4): bracketing, secant / inverse quadratic
//! interpolation, bisection when those stall. Used by the Best K_FFP
//! solvers (suzuki-best-kffp Eq. 20) and the torque-saturation search.
//!
//! Units: whatever `f` takes and returns.

/// A root of `f` in `[a, b]` by Brent's method, to within `tol` in x.
///
/// `None` when `f(a)·f(b) > 0` (no bracket) or an end value is not finite.
/// At most 200 iterations; inverse quadratic interpolation with bisection
/// as the fallback, so it never does worse than bisection.
///
/// # Examples
/// ```
/// let r = mtmotion::numeric::brent(|x| x * x - 2.0, 0.0, 2.0, 1e-14).unwrap();
/// assert!((r - 2f64.sqrt()).abs() < 1e-13);
/// assert!(mtmotion::numeric::brent(|x| x * x + 1.0, -1.0, 1.0, 1e-12).is_none());
/// ```
pub fn brent(mut f: impl FnMut(f64) -> f64, mut a: f64, mut b: f64, tol: f64) -> Option<f64> {
    let (mut fa, mut fb) = (f(a), f(b));
    if !(fa.is_finite() && fb.is_finite()) || fa * fb > 0.0 {
        return None;
    }
    if fa == 0.0 {
        return Some(a);
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if fb * fc > 0.0 {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let m = 0.5 * (c - b);
        if m.abs() <= tol1 || fb == 0.0 {
            return Some(b);
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol1 * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = d;
            }
        } else {
            d = m;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(m) };
        fb = f(b);
    }
    Some(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_wallis_cubic_root() {
        // Wallis' cubic x³ − 2x − 5 = 0; root from its closed form.
        let r = brent(|x| x * x * x - 2.0 * x - 5.0, 2.0, 3.0, 1e-14).unwrap();
        assert!((r - 2.094_551_481_542_327).abs() < 1e-12);
    }

    #[test]
    fn no_bracket_or_non_finite_end_is_none() {
        assert!(brent(|x| x * x + 1.0, -1.0, 1.0, 1e-12).is_none());
        assert!(brent(|x| 1.0 / x - 1.0, 0.0, 2.0, 1e-12).is_none());
    }

    #[test]
    fn a_root_at_an_end_is_returned() {
        assert_eq!(brent(|x| x - 1.0, 1.0, 3.0, 1e-12), Some(1.0));
    }
}
