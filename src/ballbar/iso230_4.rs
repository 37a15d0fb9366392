//! ISO 230-4 circular test: circular deviation G, circular hysteresis H and
//! radial deviation F (max, min), per direction; plus the diagnostics of
//! [`super::diagnostics`].
//!
//! Source: ISO 230-4:2005 §3 (definitions) and §5–6 (evaluation), the
//! least-squares reference circle (LSC) of §3.
//!
//! Readings chosen:
//! - the reference circle is the LSC (ISO 230-4 allows LSC or minimum
//!   zone); it is fitted to each run separately for G and F, and to all runs
//!   together for H;
//! - G = max ρᵢ − min ρᵢ, ρᵢ the distances from the run's LSC centre;
//! - F_max = max(ρᵢ − R₀), F_min = min(ρᵢ − R₀), R₀ the nominal radius, with
//!   the centre at the run's LSC centre (so a set-up offset does not enter);
//!   thus G = F_max − F_min;
//! - H = max over the common angles of |ρ_CCW(θ) − ρ_CW(θ)|, CW interpolated
//!   linearly at the CCW angles (only where CW samples lie within 2° on both
//!   sides), both about the common LSC centre;
//! - a trace point (θ, Δ) is the point (R₀ + Δ)·(cos θ, sin θ).
//!
//! Units: input in rad and mm (see [`BallbarTrace`]); the report is in µm
//! (fields named `…Um`), mm for centre and radius (`…Mm`), ms, ppm, µrad.

use serde::{Deserialize, Serialize};

use super::diagnostics::{diagnose, Diagnostics};
use super::trace_import::{BallbarTrace, Direction, Run};
use super::{fit_circle, FitError};

/// Errors of the circular test.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CircularTestError {
    /// The trace is over the work budget ([`crate::budget`]).
    #[error(transparent)]
    Budget(#[from] crate::budget::BudgetError),
    /// The trace has no runs.
    #[error("the trace has no runs: load or generate a trace first")]
    NoRuns,
    /// A run's arrays differ in length.
    #[error("runs[{run}]: angle has {angle} values but deviation has {deviation}")]
    LengthMismatch {
        /// Run index.
        run: usize,
        /// Angle length.
        angle: usize,
        /// Deviation length.
        deviation: usize,
    },
    /// Bad nominal radius.
    #[error("nominalRadius: expected a bar length from 0.001 to 1e6 mm, got {}", crate::numeric::compact(*.0))]
    BadRadius(f64),
    /// A sample outside its range ([`crate::ballbar::harmonics::MAX_ANGLE`], the bar
    /// length for the deviation).
    #[error("runs[{run}].{what}[{index}]: {} is outside {range}; check the trace's units", crate::numeric::compact(*.value))]
    BadSample {
        /// Run index.
        run: usize,
        /// "angleRad" or "deviation".
        what: &'static str,
        /// 0-based sample index.
        index: usize,
        /// The value.
        value: f64,
        /// The range, in words.
        range: String,
    },
    /// Bad feed.
    #[error("feed: expected a feed from 0.001 to 1e6 mm/min, got {}", crate::numeric::compact(*.0))]
    BadFeed(f64),
    /// The LSC of a run cannot be fitted.
    #[error("runs[{run}] ({direction:?}): {source}")]
    Fit {
        /// Run index.
        run: usize,
        /// Its direction.
        direction: Direction,
        /// The fit error.
        source: FitError,
    },
}

/// ISO 230-4 results of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct RunResult {
    /// Direction of travel.
    pub direction: Direction,
    /// Circular deviation G, µm.
    pub g_um: f64,
    /// Radial deviation F max, µm.
    pub f_max_um: f64,
    /// Radial deviation F min, µm.
    pub f_min_um: f64,
    /// LSC centre X relative to the nominal centre, mm.
    pub centre_x_mm: f64,
    /// LSC centre Y, mm.
    pub centre_y_mm: f64,
    /// LSC radius, mm.
    pub radius_mm: f64,
    /// Angular span of the run, degrees.
    pub span_deg: f64,
    /// Number of samples.
    pub points: usize,
}

/// The circular-test report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct CircularTest {
    /// Nominal radius, mm.
    pub nominal_radius_mm: f64,
    /// One result per run, in trace order.
    pub runs: Vec<RunResult>,
    /// Circular hysteresis H, µm (None without both directions).
    pub h_um: Option<f64>,
    /// Diagnostics (None unless a run covers a full revolution).
    pub diagnostics: Option<Diagnostics>,
}

/// The ISO 230-4 part of the circular-test report alone (no diagnostics):
/// what the documentation calculator shows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct CircularDeviation {
    /// Nominal radius, mm.
    pub nominal_radius_mm: f64,
    /// One result per run, in trace order.
    pub runs: Vec<RunResult>,
    /// Circular hysteresis H, µm (None without both directions).
    pub h_um: Option<f64>,
}

/// The points (x, y) of a run about the nominal centre, mm.
/// Equal lengths per run; every angle within ±[`super::harmonics::MAX_ANGLE`]
/// rad (2⁵³ rad overflowed a capacity: a trap) and every deviation smaller
/// in magnitude than the bar (a larger one puts the ball past the centre);
/// a feed, when given, from 0.001 to 1e6 mm/min (a subnormal one made the
/// servo-mismatch time infinite).
fn check_samples(trace: &BallbarTrace) -> Result<(), CircularTestError> {
    if let Some(f) = trace.feed {
        if !(super::synthetic::MIN_FEED..=super::synthetic::MAX_FEED).contains(&f) {
            return Err(CircularTestError::BadFeed(f));
        }
    }
    let r0 = trace.nominal_radius;
    for (k, run) in trace.runs.iter().enumerate() {
        if run.angle.len() != run.deviation.len() {
            return Err(CircularTestError::LengthMismatch {
                run: k,
                angle: run.angle.len(),
                deviation: run.deviation.len(),
            });
        }
        let max_angle = super::harmonics::MAX_ANGLE;
        let bad = |what, index, value, range: String| CircularTestError::BadSample {
            run: k,
            what,
            index,
            value,
            range,
        };
        if let Some(i) = run
            .angle
            .iter()
            .position(|a| a.is_nan() || a.abs() > max_angle)
        {
            return Err(bad("angleRad", i, run.angle[i], "±1e6 rad".into()));
        }
        if let Some(i) = run
            .deviation
            .iter()
            .position(|d| d.is_nan() || d.abs() >= r0)
        {
            let range = format!("±{} mm (the bar length)", crate::numeric::compact(r0));
            return Err(bad("deviation", i, run.deviation[i], range));
        }
    }
    Ok(())
}

pub(crate) fn run_points(run: &Run, r0: f64) -> (Vec<f64>, Vec<f64>) {
    run.angle
        .iter()
        .zip(&run.deviation)
        .map(|(t, d)| ((r0 + d) * t.cos(), (r0 + d) * t.sin()))
        .unzip()
}

/// Evaluates a ball-bar trace per ISO 230-4 ([`circular_deviation`]) and
/// runs the diagnostics.
///
/// # Units
/// Trace in rad and mm; report in µm, mm, ms, ppm and µrad as named.
///
/// # Errors
/// [`CircularTestError`] naming the run for empty traces, unequal lengths
/// or runs the LSC cannot fit.
///
/// # Examples
/// ```
/// use mtmotion::ballbar::{circular_test, synthetic_trace, Harmonic, SyntheticConfig};
/// // Ovality 5 µm (order 2): G = 10 µm, F = ±5 µm.
/// let h = vec![Harmonic { order: 2, amplitude: 0.005, phase: 0.0 }];
/// let t = synthetic_trace(&SyntheticConfig { harmonics: h, ..Default::default() }).unwrap();
/// let r = circular_test(&t).unwrap();
/// assert!((r.runs[0].g_um - 10.0).abs() < 1e-3 && (r.runs[0].f_max_um - 5.0).abs() < 1e-3);
/// assert!(r.h_um.unwrap() < 1e-6);
/// ```
pub fn circular_test(trace: &BallbarTrace) -> Result<CircularTest, CircularTestError> {
    let d = circular_deviation(trace)?;
    // the cyclic-error search of the diagnostics: its pitches grow with R₀
    let points = trace.runs.iter().map(|r| r.angle.len()).sum();
    crate::budget::check(
        "circular test, cyclic-error search",
        super::cyclic::search_work(points, trace.nominal_radius),
        crate::budget::MAX_CYCLIC_SEARCH_WORK,
        "units of work (pitches searched, about 6.3 per mm of radius, × points merged by angle, at most 18000)",
        "thin the trace (its points are merged into 0.02° bins) or use circularDeviation, which has no diagnostics",
    )?;
    Ok(CircularTest {
        nominal_radius_mm: d.nominal_radius_mm,
        runs: d.runs,
        h_um: d.h_um,
        diagnostics: diagnose(trace),
    })
}

/// ISO 230-4 G, F and H of a ball-bar trace, without the diagnostics
/// (the same values as [`circular_test`]).
///
/// # Units
/// Trace in rad and mm; G, F, H in µm, centre and radius in mm.
///
/// # Errors
/// As [`circular_test`].
///
/// # Examples
/// ```
/// use mtmotion::ballbar::{circular_deviation, circular_test, synthetic_trace, SyntheticConfig};
/// let t = synthetic_trace(&SyntheticConfig { both_directions: true, backlash_x: 0.002, ..Default::default() }).unwrap();
/// let (d, full) = (circular_deviation(&t).unwrap(), circular_test(&t).unwrap());
/// assert_eq!(d.runs, full.runs);
/// assert!((d.h_um.unwrap() - full.h_um.unwrap()).abs() < 1e-12);
/// ```
pub fn circular_deviation(trace: &BallbarTrace) -> Result<CircularDeviation, CircularTestError> {
    let r0 = trace.nominal_radius;
    if !(super::synthetic::MIN_RADIUS..=super::synthetic::MAX_RADIUS).contains(&r0) {
        return Err(CircularTestError::BadRadius(r0));
    }
    if trace.runs.is_empty() {
        return Err(CircularTestError::NoRuns);
    }
    crate::budget::check(
        "circular test",
        trace.runs.len() as u64,
        crate::budget::MAX_CIRCULAR_RUNS,
        "runs",
        "test one circle (a CCW and a CW run) at a time",
    )?;
    crate::budget::check(
        "circular test",
        trace.runs.iter().map(|r| r.angle.len() as u64).sum(),
        crate::budget::MAX_CIRCULAR_POINTS,
        "points",
        "thin the trace (a few thousand points per revolution are enough)",
    )?;
    check_samples(trace)?;
    let mut runs = Vec::with_capacity(trace.runs.len());
    let mut all = (Vec::new(), Vec::new());
    for (k, run) in trace.runs.iter().enumerate() {
        let (x, y) = run_points(run, r0);
        let c = fit_circle(&x, &y).map_err(|e| CircularTestError::Fit {
            run: k,
            direction: run.direction,
            source: e,
        })?;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (px, py) in x.iter().zip(&y) {
            let rho = (px - c.cx).hypot(py - c.cy);
            lo = lo.min(rho);
            hi = hi.max(rho);
        }
        let (amin, amax) = run
            .angle
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| {
                (a.min(t), b.max(t))
            });
        runs.push(RunResult {
            direction: run.direction,
            g_um: (hi - lo) * 1e3,
            f_max_um: (hi - r0) * 1e3,
            f_min_um: (lo - r0) * 1e3,
            centre_x_mm: c.cx,
            centre_y_mm: c.cy,
            radius_mm: c.r,
            span_deg: (amax - amin).to_degrees(),
            points: x.len(),
        });
        all.0.extend(x);
        all.1.extend(y);
    }
    let h_um = hysteresis(trace, r0, &all)?;
    Ok(CircularDeviation {
        nominal_radius_mm: r0,
        runs,
        h_um,
    })
}

/// H about the common LSC centre.
fn hysteresis(
    trace: &BallbarTrace,
    r0: f64,
    all: &(Vec<f64>, Vec<f64>),
) -> Result<Option<f64>, CircularTestError> {
    let has = |d| trace.runs.iter().any(|r| r.direction == d);
    if !(has(Direction::Ccw) && has(Direction::Cw)) {
        return Ok(None);
    }
    let c = fit_circle(&all.0, &all.1).map_err(|e| CircularTestError::Fit {
        run: 0,
        direction: Direction::Ccw,
        source: e,
    })?;
    let polar = |d: Direction| {
        let mut v: Vec<(f64, f64)> = trace
            .runs
            .iter()
            .filter(|r| r.direction == d)
            .flat_map(|r| {
                let (x, y) = run_points(r, r0);
                x.into_iter().zip(y).map(|(px, py)| {
                    let (u, w) = (px - c.cx, py - c.cy);
                    (w.atan2(u).rem_euclid(std::f64::consts::TAU), u.hypot(w))
                })
            })
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let (ccw, cw) = (polar(Direction::Ccw), polar(Direction::Cw));
    let gap = 2f64.to_radians();
    let mut h: Option<f64> = None;
    for &(t, rho) in &ccw {
        let j = cw.partition_point(|p| p.0 < t);
        let (Some(a), Some(b)) = (j.checked_sub(1).and_then(|i| cw.get(i)), cw.get(j)) else {
            continue;
        };
        if t - a.0 > gap || b.0 - t > gap {
            continue;
        }
        let f = if b.0 > a.0 {
            (t - a.0) / (b.0 - a.0)
        } else {
            0.0
        };
        let other = a.1 + f * (b.1 - a.1);
        let d = (rho - other).abs() * 1e3;
        h = Some(h.map_or(d, |m: f64| m.max(d)));
    }
    Ok(h)
}
