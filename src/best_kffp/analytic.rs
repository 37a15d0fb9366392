//! Best K_FFP, analytic (suzuki-best-kffp §4.6–4.7, Eqs. 17–20).
//!
//! Eq. 20 asks for the K_FFP at which the relative angle difference
//! `α_th − β_th` (Eq. 19) vanishes. Reading: the rotary axis keeps its set
//! K_FFP (α_th from Eq. 17, a closed form in [`crate::servo::response`]),
//! and each linear axis gets the K_FFP that makes its own phase lag equal
//! to it: `−∠G_X(jω) = α_th` and `−∠G_Y(jω) = α_th`. Both linear axes then
//! lag by the same angle, so α − β is zero for the circle as a whole and
//! no X/Y phase mismatch is left (the paper lowers the linear axes' K_FFP,
//! §5.3). Each equation is solved by bracketing and Brent's method on
//! `K_FFP ∈ [k_min, k_max]` to 1e-12 rad.
//!
//! # Units
//! ω in rad/s; K_FFP in %; angles in rad.

use super::BestKffpError;
use crate::servo::response::{alpha_th, beta_th};
use crate::servo::AxisParams;

/// Brent's method on `f` over `[a, b]` with `f(a)·f(b) ≤ 0`.
pub(crate) fn brent(
    mut f: impl FnMut(f64) -> f64,
    mut a: f64,
    mut b: f64,
    tol: f64,
) -> Option<f64> {
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

/// The K_FFP (%) of a linear axis whose phase lag at ω equals `target`
/// (rad), searched in `[k_min, k_max]`.
pub fn match_lag(
    axis: &AxisParams,
    omega: f64,
    target: f64,
    k_min: f64,
    k_max: f64,
    name: &'static str,
) -> Result<f64, BestKffpError> {
    let mut a = axis.clone();
    let mut err = None;
    let f = |k: f64| {
        a.kffp = k;
        match beta_th(&a, omega) {
            Ok(b) => b - target,
            Err(e) => {
                err = Some(e);
                f64::NAN
            }
        }
    };
    let root = brent(f, k_min, k_max, 1e-12);
    if let Some(e) = err {
        return Err(BestKffpError::Servo {
            axis: name,
            source: e,
        });
    }
    root.ok_or(BestKffpError::NoRoot {
        axis: name,
        k_min,
        k_max,
        target,
    })
}

/// K_FFP for X and Y (%), with the rotary axis `c` at its set K_FFP.
///
/// # Units
/// ω in rad/s; K_FFP in %.
///
/// # Examples
/// ```
/// use mtmotion::best_kffp::analytic::solve;
/// use mtmotion::servo::response::{alpha_th, beta_th};
/// let m = mtmotion::machine::preset("nmv5000").unwrap();
/// let (mut x, y, c) = (m.axes["x"].clone(), m.axes["y"].clone(), m.axes["c"].clone());
/// let (kx, _ky) = solve(&x, &y, &c, 3.0, -200.0, 400.0).unwrap();
/// x.kffp = kx;
/// let d = alpha_th(&c, 3.0).unwrap() - beta_th(&x, 3.0).unwrap();
/// assert!(d.abs() < 1e-9);
/// ```
pub fn solve(
    x: &AxisParams,
    y: &AxisParams,
    c: &AxisParams,
    omega: f64,
    k_min: f64,
    k_max: f64,
) -> Result<(f64, f64), BestKffpError> {
    let alpha = alpha_th(c, omega).map_err(|source| BestKffpError::Servo { axis: "c", source })?;
    let kx = match_lag(x, omega, alpha, k_min, k_max, "x")?;
    let ky = match_lag(y, omega, alpha, k_min, k_max, "y")?;
    Ok((kx, ky))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_finds_a_cubic_root() {
        let r = brent(|x| x * x * x - 2.0 * x - 5.0, 2.0, 3.0, 1e-14).unwrap();
        assert!((r - 2.094_551_481_542_327).abs() < 1e-12);
        assert!(brent(|x| x * x + 1.0, -1.0, 1.0, 1e-12).is_none());
    }
}
