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
use crate::numeric::brent;
use crate::servo::response::{alpha_th, beta_th};
use crate::servo::AxisParams;

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
