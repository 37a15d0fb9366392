//! Plausibility of a measured constant-feed-speed-vector trace before its
//! analysis (suzuki-best-kffp §2.3: C turns at ω while X and Y run on a
//! circle of radius R_W about C's centre).
//!
//! A trace whose C channel is a constant voltage, or whose C is in rad
//! but read as degrees, would otherwise give a summary ("16 periods") that
//! means nothing. Readings chosen:
//! - the check is made when the steady window commands at least
//!   [`MIN_TRAVEL`] of C; a shorter window cannot tell a constant channel
//!   from a slow one;
//! - C is constant when its span over the whole trace is under 0.01 % of the
//!   commanded travel in the steady window;
//! - C's rate (least-squares slope over the steady window) must be within
//!   a factor [`RATE_FACTOR`] of ω: a servo's steady lag changes the rate
//!   by far less, a wrong unit (rad/deg: 57×, ms/s: 1000×) by far more;
//! - X/Y are on a circle about the origin when the 10th to 90th percentile
//!   of their radius spans at most [`RADIUS_SPREAD`] of the median (single
//!   outliers are the range checks' business).
//!
//! # Units
//! s, mm, rad (the trace after scaling).

use super::analysis::Series;
use super::{Condition, FeedVectorError};
use crate::numeric::compact;

/// Least commanded C travel in the steady window for the check, rad.
pub const MIN_TRAVEL: f64 = 0.1;
/// Largest factor between C's rate and ω.
pub const RATE_FACTOR: f64 = 2.0;
/// Largest 10–90 % spread of the X/Y radius, relative to its median.
pub const RADIUS_SPREAD: f64 = 0.2;

/// Least-squares slope of `v` against `t`.
fn slope(t: &[f64], v: &[f64]) -> f64 {
    let n = t.len() as f64;
    let (mt, mv) = (t.iter().sum::<f64>() / n, v.iter().sum::<f64>() / n);
    let sxy: f64 = t.iter().zip(v).map(|(a, b)| (a - mt) * (b - mv)).sum();
    let sxx: f64 = t.iter().map(|a| (a - mt) * (a - mt)).sum();
    sxy / sxx
}

/// Refuses a trace whose C does not turn at about ω or whose X/Y are not
/// on a circle (see the module's readings). `lines` are the rows' source
/// lines, `c_name` the C column's header.
///
/// # Errors
/// [`FeedVectorError::Implausible`], saying what was found and what to do.
pub fn check(
    s: &Series,
    cond: &Condition,
    t_ss: f64,
    lines: &[usize],
    c_name: &str,
) -> Result<(), FeedVectorError> {
    let from = s.t.partition_point(|&t| t < t_ss);
    let (t, last) = (&s.t[from..], s.t.len() - 1);
    let span = t[t.len() - 1] - t[0];
    let travel = cond.omega * span;
    if travel < MIN_TRAVEL {
        return Ok(());
    }
    let where_ = format!("lines {}–{}", lines[from], lines[last]);
    let (lo, hi) =
        s.c.iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    if hi - lo < 1e-4 * travel {
        return Err(FeedVectorError::Implausible(format!(
            "C is constant: {} deg over {} s (column '{c_name}', lines {}–{}); is this the C channel? The condition's ω = {} rad/s turns C by {} deg in the steady window: map the C column (mapping.c) and check its unit",
            compact(s.c[0].to_degrees()),
            compact(s.t[last] - s.t[0]),
            lines[0],
            lines[last],
            compact(cond.omega),
            compact(travel.to_degrees()),
        )));
    }
    let rate = slope(t, &s.c[from..]);
    if !(rate / cond.omega <= RATE_FACTOR && rate / cond.omega >= 1.0 / RATE_FACTOR) {
        return Err(FeedVectorError::Implausible(format!(
            "C turns at {} rad/s in the steady window (column '{c_name}', {where_}), but the condition's ω is {} rad/s: check the C column, its unit (deg or rad: mapping.angleScale), the time unit (mapping.timeScale) and ω",
            compact(rate),
            compact(cond.omega),
        )));
    }
    let mut r: Vec<f64> = (from..=last).map(|i| s.x[i].hypot(s.y[i])).collect();
    r.sort_by(f64::total_cmp);
    let pct = |p: f64| r[((r.len() - 1) as f64 * p).round() as usize];
    let (p10, med, p90) = (pct(0.1), pct(0.5), pct(0.9));
    let on_circle = (p90 - p10).partial_cmp(&(RADIUS_SPREAD * med));
    if !matches!(
        on_circle,
        Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)
    ) {
        return Err(FeedVectorError::Implausible(format!(
            "X/Y are not on a circle about (0, 0): their radius runs from {} to {} mm (10th to 90th percentile, {where_}); map the X and Y columns, or set mapping.relative if they are displacements from the start point",
            compact(p10),
            compact(p90),
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 s trace at 1 ms on the paper's condition: X/Y on R_W, C at ω.
    fn trace(c_rate: f64, radius: impl Fn(usize) -> f64) -> (Series, Condition) {
        let cond = Condition::paper(1.0);
        let t: Vec<f64> = (0..3000).map(|i| i as f64 * 1e-3).collect();
        let s = Series {
            x: t.iter()
                .enumerate()
                .map(|(i, t)| radius(i) * t.cos())
                .collect(),
            y: t.iter()
                .enumerate()
                .map(|(i, t)| radius(i) * t.sin())
                .collect(),
            c: t.iter().map(|t| c_rate * t).collect(),
            t,
            ..Series::default()
        };
        (s, cond)
    }

    fn msg(s: &Series, cond: &Condition) -> String {
        let lines: Vec<usize> = (2..s.t.len() + 2).collect();
        match check(s, cond, 0.464, &lines, "C [deg]") {
            Ok(()) => String::new(),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn a_plausible_trace_passes_and_each_fault_is_named() {
        let (s, cond) = trace(1.0, |_| 8.0);
        assert_eq!(msg(&s, &cond), "");
        let (s, _) = trace(0.0, |_| 8.0);
        assert_eq!(
            msg(&s, &cond),
            "C is constant: 0 deg over 2.999 s (column 'C [deg]', lines 2–3001); is this the C channel? The condition's ω = 1 rad/s turns C by 145.245 deg in the steady window: map the C column (mapping.c) and check its unit"
        );
        // rad read as degrees: 57× too slow
        let (s, _) = trace(1.0f64.to_radians(), |_| 8.0);
        assert!(msg(&s, &cond).starts_with("C turns at 0.0174533 rad/s in the steady window (column 'C [deg]', lines 466–3001)"), "{}", msg(&s, &cond));
        for rate in [0.49, 2.01, -1.0] {
            assert!(
                msg(&trace(rate, |_| 8.0).0, &cond).starts_with("C turns at"),
                "{rate}"
            );
        }
        for rate in [0.51, 1.99] {
            assert_eq!(msg(&trace(rate, |_| 8.0).0, &cond), "", "{rate}");
        }
        // Y in µm read as mm: an ellipse
        let (mut s, _) = trace(1.0, |_| 8.0);
        s.y.iter_mut().for_each(|v| *v *= 1e3);
        assert!(msg(&s, &cond)
            .starts_with("X/Y are not on a circle about (0, 0): their radius runs from"));
        // one wild sample in 20 is not a spread
        assert_eq!(
            msg(
                &trace(1.0, |i| if i % 20 == 0 { 80.0 } else { 8.0 }).0,
                &cond
            ),
            ""
        );
        assert_ne!(
            msg(
                &trace(1.0, |i| if i % 5 == 0 { 80.0 } else { 8.0 }).0,
                &cond
            ),
            ""
        );
        // a radius swinging ±0.7 mm about 8 mm is a circle, ±1 mm is not (20 %)
        let wobble = |a: f64| {
            msg(
                &trace(1.0, move |i| 8.0 + a * (i as f64 * 0.01).sin()).0,
                &cond,
            )
        };
        assert_eq!(wobble(0.7), "");
        assert!(wobble(1.0).starts_with("X/Y are not on a circle"));
        // a window under 0.1 rad of travel is not judged
        let (s, _) = trace(0.0, |_| 8.0);
        let short = Series {
            t: s.t[..560].to_vec(),
            c: s.c[..560].to_vec(),
            x: s.x[..560].to_vec(),
            y: s.y[..560].to_vec(),
            ..Series::default()
        };
        assert_eq!(msg(&short, &cond), "");
        let longer = Series {
            t: s.t[..570].to_vec(),
            c: s.c[..570].to_vec(),
            x: s.x[..570].to_vec(),
            y: s.y[..570].to_vec(),
            ..Series::default()
        };
        assert_ne!(msg(&longer, &cond), "");
    }

    #[test]
    fn the_slope_is_the_least_squares_one() {
        let t = [0.0, 1.0, 2.0, 3.0];
        assert!((slope(&t, &[1.0, 3.0, 5.0, 7.0]) - 2.0).abs() < 1e-15);
        assert!((slope(&t, &[0.0, 1.0, 1.0, 2.0]) - 0.6).abs() < 1e-15);
    }
}
