//! Angle wrapping: one definition for every model that compares angles
//! (phase lags in the feed-vector analysis, joint branches in the inverse
//! kinematics).
//!
//! Units: rad.

use std::f64::consts::{PI, TAU};

/// `a` wrapped into `(−π, π]`.
///
/// # Units
/// rad in, rad out.
///
/// # Examples
/// ```
/// use mtmotion::numeric::wrap_angle;
/// use std::f64::consts::PI;
/// assert!((wrap_angle(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-15);
/// assert_eq!(wrap_angle(-PI), PI);
/// assert_eq!(wrap_angle(PI), PI);
/// ```
pub fn wrap_angle(a: f64) -> f64 {
    let w = (a + PI).rem_euclid(TAU) - PI;
    if w <= -PI {
        w + TAU
    } else {
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stays_in_half_open_interval_and_keeps_the_angle() {
        for k in -2000..=2000 {
            let a = k as f64 * 0.0137 - 3.0;
            let w = wrap_angle(a);
            assert!(w > -PI && w <= PI, "{a} -> {w}");
            // Same direction: the difference is a whole number of turns.
            let turns = (a - w) / TAU;
            assert!((turns - turns.round()).abs() < 1e-12, "{a} -> {w}");
        }
    }
}
