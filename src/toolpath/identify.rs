//! Radius loss of a circular motion (qiu Eq. 3) and the identification of
//! `tA` and `T` from measured radius losses (qiu §4-1).
//!
//! Eq. 3: `Δr = {1 − sin(tA·ω/2)/(tA·ω/2) · 1/√(T²ω² + 1)}·R`, `ω = F/R`,
//! the steady-state gain of the moving average (Eq. 1) times that of the
//! first-order lag (Eq. 2) at the circle's angular velocity. Reading: `F`
//! is given in mm/min as on the NC and converted to mm/s, so `ω` is in rad/s.
//!
//! Identification: least squares on `(tA, T)` of the Δr residuals,
//! Levenberg–Marquardt started from the best point of a logarithmic grid,
//! with `tA, T ≥ 0`. At small `ω`, Δr/R ≈ ω²(tA²/24 + T²/2) − ω⁴(…), so the
//! two values separate only through the ω⁴ term: the data must hold at
//! least two different `F/R`, and the Jacobian's conditioning is checked;
//! otherwise [`IdentifyError`] says what to measure.
//!
//! Units: mm, mm/min, s.

use nalgebra::{Matrix2, Vector2};
use serde::{Deserialize, Serialize};

use crate::numeric::{levenberg_marquardt, LmOptions, Normal};

/// Errors of Eq. 3 and of the identification.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IdentifyError {
    /// A value is out of range; names the field and, for data, the row.
    #[error("{field}: {message}")]
    Input {
        /// e.g. `radius` or `data[2].radiusLoss`.
        field: String,
        /// What was expected.
        message: String,
    },
    /// The data cannot determine both values.
    #[error("the data cannot determine both tA and T: {0}")]
    Underdetermined(String),
}

/// Δr of Eq. 3.
///
/// # Units
/// `feed` mm/min, `radius` mm, `t_a` and `t` s → mm.
///
/// # Errors
/// A non-positive radius or feed, or negative time constants.
///
/// # Examples
/// ```
/// use mtmotion::toolpath::identify::radius_reduction;
/// // F = 2000 mm/min on R = 10 mm: ω = 3.333 rad/s.
/// let dr = radius_reduction(2000.0, 10.0, 0.04, 0.015).unwrap();
/// let w: f64 = 2000.0 / 60.0 / 10.0;
/// let x = 0.04 * w / 2.0;
/// let expect = (1.0 - x.sin() / x / (0.015f64.powi(2) * w * w + 1.0).sqrt()) * 10.0;
/// assert!((dr - expect).abs() < 1e-15);
/// assert!((dr - 0.019873).abs() < 1e-6);
/// ```
pub fn radius_reduction(feed: f64, radius: f64, t_a: f64, t: f64) -> Result<f64, IdentifyError> {
    let bad = |f: &str, v: f64, m: &str| {
        Err(IdentifyError::Input {
            field: f.into(),
            message: format!("{m}, got {}", crate::numeric::compact(v)),
        })
    };
    if !(radius.is_finite() && (MIN_RADIUS..=MAX_RADIUS).contains(&radius)) {
        return bad("radius", radius, "expected a radius from 0.001 to 1e6 mm");
    }
    if !(feed.is_finite() && feed > 0.0 && feed <= MAX_FEED) {
        return bad(
            "feed",
            feed,
            "expected a feed above 0 and at most 1e6 mm/min",
        );
    }
    if !(t_a.is_finite() && (0.0..=MAX_TIME_CONSTANT).contains(&t_a)) {
        return bad("tA", t_a, "expected tA from 0 to 100 s");
    }
    if !(t.is_finite() && (0.0..=MAX_TIME_CONSTANT).contains(&t)) {
        return bad("T", t, "expected T from 0 to 100 s");
    }
    Ok(eq3(feed / 60.0 / radius, radius, t_a, t))
}

/// Smallest circle radius Eq. 3 accepts, mm: 1 µm, below any NC's
/// programming resolution (a subnormal radius would make ω infinite).
pub const MIN_RADIUS: f64 = 1e-3;
/// Largest circle radius, mm (1 km).
pub const MAX_RADIUS: f64 = 1e6;
/// Largest feed, mm/min (1 km/min, ten times the fastest linear drive).
pub const MAX_FEED: f64 = 1e6;
/// Largest acc/dec or servo time constant, s (real ones are ≤ 0.5 s).
pub const MAX_TIME_CONSTANT: f64 = 100.0;

fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

fn eq3(w: f64, r: f64, t_a: f64, t: f64) -> f64 {
    (1.0 - sinc(t_a * w / 2.0) / (t * t * w * w + 1.0).sqrt()) * r
}

/// One measured circle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct CircleLoss {
    /// Programmed feed, mm/min.
    pub feed: f64,
    /// Programmed radius, mm.
    pub radius: f64,
    /// Measured radius loss (programmed − measured), mm.
    pub radius_loss: f64,
}

/// Identified values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AccDec {
    /// Acc/dec time constant, s.
    #[serde(rename = "tA")]
    pub t_a: f64,
    /// Servo time constant, s.
    #[serde(rename = "T")]
    pub t: f64,
    /// RMS of the Δr residuals, mm.
    pub residual: f64,
}

fn residuals(d: &[CircleLoss], p: [f64; 2]) -> Vec<f64> {
    d.iter()
        .map(|c| eq3(c.feed / 60.0 / c.radius, c.radius, p[0], p[1]) - c.radius_loss)
        .collect()
}

fn cost(d: &[CircleLoss], p: [f64; 2]) -> f64 {
    residuals(d, p).iter().map(|r| r * r).sum()
}

/// Least-squares `tA`, `T` from measured radius losses (§4-1).
///
/// # Units
/// Feeds in mm/min, radii and losses in mm → s, s, mm.
///
/// # Errors
/// Fewer than two rows, a bad value (named by row), fewer than two
/// distinct `F/R`, or data whose Jacobian is too ill-conditioned to
/// separate `tA` from `T`.
///
/// # Examples
/// ```
/// use mtmotion::toolpath::identify::{identify_acc_dec, radius_reduction, CircleLoss};
/// let data: Vec<CircleLoss> = [(2000.0, 3.0), (4000.0, 5.0), (6000.0, 4.0), (1000.0, 10.0)]
///     .iter()
///     .map(|&(feed, radius)| CircleLoss { feed, radius, radius_loss: radius_reduction(feed, radius, 0.05, 0.02).unwrap() })
///     .collect();
/// let id = identify_acc_dec(&data).unwrap();
/// assert!((id.t_a - 0.05).abs() < 1e-6 && (id.t - 0.02).abs() < 1e-6);
/// ```
pub fn identify_acc_dec(data: &[CircleLoss]) -> Result<AccDec, IdentifyError> {
    check_data(data)?;
    // Levenberg–Marquardt ([`crate::numeric::levenberg_marquardt`]) with a
    // forward-difference Jacobian, tA and T kept ≥ 0, from the best point
    // of a grid.
    let normal = |v: &Vector2<f64>| -> Normal<2> {
        let p = [v[0], v[1]];
        let r = residuals(data, p);
        let (mut jtj, mut jtr) = (Matrix2::zeros(), Vector2::zeros());
        for (row, ri) in jacobian(data, p).iter().zip(&r) {
            let j = Vector2::new(row[0], row[1]);
            jtj += j * j.transpose();
            jtr += j * *ri;
        }
        Normal {
            jtj,
            jtr,
            cost: r.iter().map(|x| x * x).sum(),
        }
    };
    let opts = LmOptions {
        lambda: 1e-3,
        ..LmOptions::default()
    };
    let start = grid_start(data);
    let fit = levenberg_marquardt(
        Vector2::new(start[0], start[1]),
        normal,
        |v| v.map(|x| x.max(0.0)),
        &opts,
    );
    let (p, c) = ([fit.p[0], fit.p[1]], fit.normal.cost);
    check_conditioning(data, p)?;
    Ok(AccDec {
        t_a: p[0],
        t: p[1],
        residual: (c / data.len() as f64).sqrt(),
    })
}

/// At least two rows, each with a positive feed and radius and a loss
/// between 0 and the radius, and at least two distinct `F/R`.
fn check_data(data: &[CircleLoss]) -> Result<(), IdentifyError> {
    // every fit iteration evaluates every circle (1e6 rows took over 30 s)
    if data.len() > crate::budget::MAX_ACCDEC_CIRCLES {
        return Err(IdentifyError::Input {
            field: "data".into(),
            message: format!(
                "{} circles, more than the limit of {}; the fit needs a few circles at different F/R",
                data.len(),
                crate::budget::MAX_ACCDEC_CIRCLES
            ),
        });
    }
    if data.len() < 2 {
        return Err(IdentifyError::Underdetermined(format!(
            "{} circle(s) given; expected at least two with different F/R",
            data.len()
        )));
    }
    for (i, c) in data.iter().enumerate() {
        let bad = |f: &str, m: &str| {
            Err(IdentifyError::Input {
                field: format!("data[{i}].{f}"),
                message: m.into(),
            })
        };
        if !(c.feed.is_finite() && c.feed > 0.0) {
            return bad("feed", "expected a positive feed in mm/min");
        }
        if !(c.radius.is_finite() && c.radius > 0.0) {
            return bad("radius", "expected a positive radius in mm");
        }
        if !(c.radius_loss.is_finite() && c.radius_loss >= 0.0 && c.radius_loss < c.radius) {
            return bad(
                "radiusLoss",
                "expected a loss between 0 and the radius, in mm",
            );
        }
    }
    let ws: Vec<f64> = data.iter().map(|c| c.feed / 60.0 / c.radius).collect();
    let (wmin, wmax) = ws
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), &w| (a.min(w), b.max(w)));
    if wmax / wmin < 1.0 + 1e-6 {
        return Err(IdentifyError::Underdetermined(
            "all circles have the same angular velocity F/R; measure at least two different F/R"
                .into(),
        ));
    }
    Ok(())
}

/// The best `[tA, T]` (s) of a 41 × 41 logarithmic grid over 0.1 ms…1 s
/// (and the origin).
fn grid_start(data: &[CircleLoss]) -> [f64; 2] {
    let mut best = ([0.0, 0.0], cost(data, [0.0, 0.0]));
    for i in 0..=40 {
        for j in 0..=40 {
            let p = [
                1e-4 * 1e4f64.powf(i as f64 / 40.0),
                1e-4 * 1e4f64.powf(j as f64 / 40.0),
            ];
            let c = cost(data, p);
            if c < best.1 {
                best = (p, c);
            }
        }
    }
    best.0
}

/// Forward-difference Jacobian of the residuals at `p` (relative step 1e-7,
/// at least 1e-11 s).
fn jacobian(data: &[CircleLoss], p: [f64; 2]) -> Vec<[f64; 2]> {
    let r0 = residuals(data, p);
    let mut j = vec![[0.0; 2]; data.len()];
    for k in 0..2 {
        let h = 1e-7 * p[k].abs().max(1e-4);
        let mut q = p;
        q[k] += h;
        let r1 = residuals(data, q);
        for (row, (a, b)) in j.iter_mut().zip(r1.iter().zip(&r0)) {
            row[k] = (a - b) / h;
        }
    }
    j
}

/// Refuses a fit whose Jacobian, columns scaled by the parameters, has a
/// condition number above 1e6 (eigenvalue ratio of JᵀJ below 1e-12): the
/// data cannot separate tA from T.
fn check_conditioning(data: &[CircleLoss], p: [f64; 2]) -> Result<(), IdentifyError> {
    let j = jacobian(data, p);
    let scale = [p[0].max(1e-4), p[1].max(1e-4)];
    let mut a = [[0.0; 2]; 2];
    for row in &j {
        for x in 0..2 {
            for y in 0..2 {
                a[x][y] += row[x] * scale[x] * row[y] * scale[y];
            }
        }
    }
    let tr = a[0][0] + a[1][1];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let disc = (tr * tr / 4.0 - det).max(0.0).sqrt();
    let (l1, l2) = (tr / 2.0 + disc, (tr / 2.0 - disc).max(0.0));
    if l1 <= 0.0 || l2 / l1 < 1e-12 {
        return Err(IdentifyError::Underdetermined(format!(
            "the radius losses vary too little with F/R (condition number {:.1e}); add circles with a larger F/R, where ω·tA and ω·T approach 1",
            (l1 / l2.max(1e-300)).sqrt()
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_omega_expansion() {
        // Δr/R ≈ ω²(tA²/24 + T²/2) for ω·tA, ω·T ≪ 1.
        let (r, f) = (100.0, 600.0);
        let w = f / 60.0 / r;
        let dr = radius_reduction(f, r, 0.05, 0.02).unwrap();
        let approx = r * w * w * (0.05f64.powi(2) / 24.0 + 0.02f64.powi(2) / 2.0);
        assert!((dr - approx).abs() / approx < 1e-3);
    }

    #[test]
    fn identification_recovers_and_refuses() {
        let mk = |pairs: &[(f64, f64)], ta, t| -> Vec<CircleLoss> {
            pairs
                .iter()
                .map(|&(feed, radius)| CircleLoss {
                    feed,
                    radius,
                    radius_loss: radius_reduction(feed, radius, ta, t).unwrap(),
                })
                .collect()
        };
        let d = mk(
            &[(2000.0, 2.0), (5000.0, 5.0), (8000.0, 4.0), (3000.0, 20.0)],
            0.064,
            0.033,
        );
        let id = identify_acc_dec(&d).unwrap();
        assert!(
            (id.t_a - 0.064).abs() < 1e-6 && (id.t - 0.033).abs() < 1e-6,
            "{id:?}"
        );
        assert!(id.residual < 1e-9);
        // Same F/R everywhere: refused.
        let d = mk(&[(2000.0, 10.0), (4000.0, 20.0)], 0.05, 0.02);
        assert!(matches!(
            identify_acc_dec(&d),
            Err(IdentifyError::Underdetermined(_))
        ));
        let e = identify_acc_dec(
            &[CircleLoss {
                feed: 1.0,
                radius: -1.0,
                radius_loss: 0.0,
            }; 2],
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "data[0].radius: expected a positive radius in mm"
        );
    }
}
