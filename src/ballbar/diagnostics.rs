//! Ball-bar diagnostics: the error sources that commercial ball-bar software
//! reports from a CCW + CW circular test — centre offset, backlash and
//! reversal spikes at the quadrant points, servo mismatch, scale mismatch,
//! squareness and cyclic (pitch) error.
//!
//! Source: ISO 230-4 Annex A (interpretation of circular-test traces) and
//! the signature model of [`super::synthetic`], which is its exact forward
//! model.
//!
//! Method (readings chosen): each run covering a full revolution is fitted by
//! linear least squares (QR) with
//! Δ(θ) = c₀ + c₁ cos θ + s₁ sin θ + c₂ cos 2θ + s₂ sin 2θ
//!        + βx·s·sign(sin θ)·cos θ/2 − βy·s·sign(cos θ)·sin θ/2
//!        + Σₙ₌₃⁸ (aₙ cos nθ + bₙ sin nθ),
//! s = +1 CCW, −1 CW (the dead-band backlash signature: a step of βx at the
//! X reversals θ = 0°, 180° and of βy at 90°, 270°; orders 3–8 take up
//! smooth motion errors so that they are not read as spikes).
//! Then,
//! averaging over
//! runs and with R₀ the nominal radius and v the feed:
//! - centre offset: the least-squares circle (LSC) of all full runs
//!   together, relative to the centre the deviations are about ([`Centre`]:
//!   the bar's pivot, a given centre, or the X/Y trace's own LSC, in which
//!   case it is 0 by construction and says so); the same centre as the
//!   ISO 230-4 H (the per-run c₁, s₁ are nuisance terms of the run model);
//! - backlash βx, βy;
//! - scale mismatch sx − sy = 2c₂/R₀ (X longer: positive);
//! - squareness α = (s₂,CCW + s₂,CW)/R₀ (positive: the axes enclose less
//!   than 90°); with one direction only it includes the servo mismatch;
//! - servo mismatch τ = (s₂,CCW − s₂,CW)/v (positive: X lags Y), needs both
//!   directions and the feed;
//! - the fit leaves out the 10° after each quadrant point in the direction
//!   of travel, where the reversal spikes are;
//! - reversal spikes: the residual of largest magnitude within 15° after
//!   each quadrant point in the direction of travel (one pass over the
//!   points, so multi-revolution files cost O(points)), reported only
//!   above the run's noise threshold: 1.5 × the largest |residual| away
//!   from the quadrant points (the trace's own noise and unmodelled error;
//!   at least 1 nm, the model's resolution). On noise alone the peak in a
//!   15° window cannot exceed the peak over the other 300°, so none is
//!   reported; a spike must stand 50 % above it;
//! - significance: backlash, scale mismatch, squareness and servo mismatch
//!   are reported only above 3 standard errors of their least-squares
//!   estimate (σ² of the kept residuals × the diagonal of (AᵀA)⁻¹, per run,
//!   then of the mean over runs); below it they read 0 and the report
//!   gives the 3-SE resolution it was compared with. σ² is inflated by
//!   (1 + ρ)/(1 − ρ), ρ the lag-1 autocorrelation of the residuals (AR(1)
//!   reading: a capture at 1 kHz has smooth, correlated residuals, whose
//!   plain σ²/n understates the error by that factor; at most n);
//! - every reversal spike is compared with one threshold, the largest of
//!   the runs' thresholds, which the report states (with each spike);
//! - cyclic error ([`super::cyclic`]): on the residuals of all runs, the
//!   pitch p (1 mm … R₀/4, a grid uniform in 2π/p fine enough to resolve
//!   the peak, then refined) whose model
//!   cos θ·(a sin 2πx/p + b cos 2πx/p) + sin θ·(c sin 2πy/p + d cos 2πy/p)
//!   explains most variance; then the pitch is refined (±2 %) and a, b, c, d
//!   are refitted jointly with the
//!   run model (whose orders 3–8 would otherwise absorb part of the cyclic
//!   signature) and averaged over runs; amplitudes √(a² + b²) for X,
//!   √(c² + d²) for Y; reported only when the best pitch passes the
//!   F-test of [`super::cyclic::CyclicTest`]; a reported cyclic error is
//!   subtracted before the run model is fitted again for the other
//!   estimates, spikes and standard errors.
//!
//! Units: trace in rad and mm; the report in µm, ms, ppm (µm/m), µrad and mm
//! as named.

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::cyclic::{cyclic_amplitudes, cyclic_pitch, signature, CyclicTest};
use super::trace_import::{BallbarTrace, Direction, Run};

/// A reversal spike after a quadrant point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Spike {
    /// Direction of the run.
    pub direction: Direction,
    /// The axis that reverses there ('x' at 0°/180°, 'y' at 90°/270°).
    pub axis: char,
    /// Quadrant point, degrees in [0, 360).
    pub angle_deg: f64,
    /// Signed spike height (outward positive), µm.
    pub height_um: f64,
    /// The threshold its magnitude was compared with, µm.
    pub threshold_um: f64,
}

/// The centre the deviations (and so the centre offset) are about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Centre {
    /// An angle/deviation trace: the ball bar's pivot; the offset is
    /// measured (the set-up error).
    BarPivot,
    /// An X/Y trace about a given centre (pivot or programmed): measured.
    Given,
    /// An X/Y trace about its own least-squares centre: the offset is 0 by
    /// construction, not a measurement.
    TraceLsc,
}

/// Cyclic (pitch) error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Cyclic {
    /// Pitch, mm.
    pub pitch_mm: f64,
    /// Amplitude on X, µm.
    pub amplitude_x_um: f64,
    /// Amplitude on Y, µm.
    pub amplitude_y_um: f64,
}

/// The diagnostics report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Diagnostics {
    /// Centre offset X (LSC of the full runs about [`Diagnostics::centre`]), µm.
    pub centre_offset_x_um: f64,
    /// Centre offset Y, µm.
    pub centre_offset_y_um: f64,
    /// What the centre offset is relative to.
    pub centre: Centre,
    /// Backlash X, µm.
    pub backlash_x_um: f64,
    /// Backlash Y, µm.
    pub backlash_y_um: f64,
    /// Smallest backlash X reported (3 standard errors), µm; below it
    /// `backlash_x_um` is 0.
    pub backlash_x_resolution_um: f64,
    /// Smallest backlash Y reported (3 standard errors), µm.
    pub backlash_y_resolution_um: f64,
    /// Reversal spikes per run and quadrant point, those above the noise
    /// threshold only.
    pub reversal_spikes: Vec<Spike>,
    /// Noise threshold of the reversal spikes (largest over the runs), µm.
    pub spike_threshold_um: f64,
    /// Servo mismatch, ms (None without both directions or feed; 0 below
    /// its resolution).
    pub servo_mismatch_ms: Option<f64>,
    /// Smallest servo mismatch reported (3 standard errors), ms.
    pub servo_mismatch_resolution_ms: Option<f64>,
    /// Scale mismatch sx − sy, ppm (0 below its resolution).
    pub scale_mismatch_ppm: f64,
    /// Smallest scale mismatch reported (3 standard errors), ppm.
    pub scale_mismatch_resolution_ppm: f64,
    /// Squareness, µrad (= µm/m; 0 below its resolution).
    pub squareness_urad: f64,
    /// Smallest squareness reported (3 standard errors), µrad.
    pub squareness_resolution_urad: f64,
    /// Cyclic error (None unless its F-test passes).
    pub cyclic: Option<Cyclic>,
    /// The cyclic error's significance test (None when not searched).
    pub cyclic_test: Option<CyclicTest>,
    /// RMS of the run model's residuals (fitted points, over the runs), µm:
    /// the fit quality every standard error above rests on.
    pub residual_rms_um: f64,
    /// Runs used (full revolutions).
    pub runs_used: usize,
}

fn sgn(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Least squares through the normal equations (the basis is bounded and a
/// run covers a full revolution, so they are well conditioned; memory stays
/// O(cols²) for traces of any length), also returning the diagonal of
/// (AᵀA)⁻¹ (the coefficient variances per unit residual variance). None
/// when rank deficient.
pub(super) fn lsq_full<const N: usize>(
    rows: impl Iterator<Item = ([f64; N], f64)>,
    cols: usize,
) -> Option<(DVector<f64>, DVector<f64>)> {
    let mut m = DMatrix::<f64>::zeros(cols, cols);
    let mut g = DVector::<f64>::zeros(cols);
    for (b, y) in rows {
        for i in 0..cols {
            g[i] += b[i] * y;
            for j in i..cols {
                m[(i, j)] += b[i] * b[j];
            }
        }
    }
    for i in 0..cols {
        for j in 0..i {
            m[(i, j)] = m[(j, i)];
        }
    }
    let chol = cholesky(m)?;
    let x = chol.solve(&g);
    let inv = chol.inverse().diagonal();
    Some((x, inv))
}

/// Cholesky factor of normal equations; None when rank deficient (a pivot
/// below 1e-10 of the largest column norm).
fn cholesky(m: DMatrix<f64>) -> Option<nalgebra::Cholesky<f64, nalgebra::Dyn>> {
    let cols = m.nrows();
    let big = (0..cols).map(|k| m[(k, k)]).fold(0.0, f64::max);
    let chol = m.cholesky()?;
    let l = chol.l();
    if (0..cols).any(|k| l[(k, k)] * l[(k, k)] <= 1e-20 * big) {
        return None;
    }
    Some(chol)
}

/// The solution of normal equations (full symmetric `m`); None when rank
/// deficient.
pub(super) fn cholesky_solve(m: DMatrix<f64>, g: &DVector<f64>) -> Option<DVector<f64>> {
    Some(cholesky(m)?.solve(g))
}

/// Columns of the per-run model: 7 signature terms, then orders 3 … 8.
pub(super) const COLS: usize = 7 + 2 * 6;

pub(super) fn basis(t: f64, s: f64) -> [f64; COLS] {
    let (c, sn) = (t.cos(), t.sin());
    let mut b = [0.0; COLS];
    b[..7].copy_from_slice(&[
        1.0,
        c,
        sn,
        (2.0 * t).cos(),
        (2.0 * t).sin(),
        s * sgn(sn) * c / 2.0,
        -s * sgn(c) * sn / 2.0,
    ]);
    for k in 3..=8 {
        let (sk, ck) = (k as f64 * t).sin_cos();
        b[7 + 2 * (k - 3)] = ck;
        b[8 + 2 * (k - 3)] = sk;
    }
    b
}

/// Runs the diagnostics on the runs that cover a full revolution (≥ 355°);
/// None when there are none.
///
/// # Units
/// See [`Diagnostics`].
///
/// # Examples
/// ```
/// use mtmotion::ballbar::{diagnostics::diagnose, synthetic_trace, SyntheticConfig};
/// let t = synthetic_trace(&SyntheticConfig { squareness: 20e-6, ..Default::default() }).unwrap();
/// let d = diagnose(&t).unwrap();
/// assert!((d.squareness_urad - 20.0).abs() < 0.1);
/// ```
pub fn diagnose(trace: &BallbarTrace) -> Option<Diagnostics> {
    let r0 = trace.nominal_radius;
    let full = full_runs(trace);
    let mut resid: Vec<(f64, f64)> = Vec::new();
    for run in &full {
        let (_, _, res, _) = fit_run(run)?;
        resid.extend(run.angle.iter().copied().zip(res));
    }
    let searched = cyclic_pitch(&resid, r0, COLS * full.len());
    let cyclic = searched
        .filter(|(_, t)| t.significant())
        .and_then(|(p, _)| cyclic_amplitudes(&full, p, r0));
    // A significant cyclic error is taken out before the other estimates,
    // so that it is neither read as their noise nor as a spike.
    let corrected: Vec<Run> = match cyclic {
        Some((c, coef)) => full
            .iter()
            .map(|r| Run {
                deviation: r
                    .angle
                    .iter()
                    .zip(&r.deviation)
                    .map(|(&t, &d)| d - signature(t, c.pitch_mm, &coef, r0))
                    .collect(),
                ..(*r).clone()
            })
            .collect(),
        None => full.iter().map(|r| (*r).clone()).collect(),
    };
    let mut fits: Vec<RunStat> = Vec::new();
    let mut peaks = Vec::new();
    let mut spike_threshold = 0.0f64;
    let mut rms = 0.0;
    for run in &corrected {
        let (coef, inv, res, var) = fit_run(run)?;
        let (found, threshold) = find_spikes(run, &res);
        peaks.extend(found);
        spike_threshold = spike_threshold.max(threshold);
        rms += fit_points_rms(run, &res);
        fits.push((run.direction, coef, inv * var));
    }
    let (all_mean, all_se) = stat(&fits, None)?;
    let n = fits.len() as f64;
    // One threshold for every spike: the largest of the runs'.
    let spikes: Vec<Spike> = peaks
        .into_iter()
        .filter(|s| s.height_um.abs() > spike_threshold * 1e3)
        .map(|s| Spike {
            threshold_um: spike_threshold * 1e3,
            ..s
        })
        .collect();
    let s2 = |d| stat(&fits, Some(d)).map(|(m, e)| (m[4], e[4]));
    let (ccw, cw) = (s2(Direction::Ccw), s2(Direction::Cw));
    let (squareness, squareness_se) = match (ccw, cw) {
        (Some(a), Some(b)) => ((a.0 + b.0) / r0, a.1.hypot(b.1) / r0),
        _ => (2.0 * all_mean[4] / r0, 2.0 * all_se[4] / r0),
    };
    let servo = match (ccw, cw, trace.feed) {
        (Some(a), Some(b), Some(f)) if f > 0.0 => {
            let v = f / 60.0;
            Some(((a.0 - b.0) / v * 1e3, a.1.hypot(b.1) / v * 1e3))
        }
        _ => None,
    };
    let k = SIGNIFICANCE;
    let significant = |v: f64, r: f64| if v.abs() > r { v } else { 0.0 };
    let resolution = [k * all_se[5] * 1e3, k * all_se[6] * 1e3];
    let scale_res = k * 2.0 * all_se[3] / r0 * 1e6;
    let square_res = k * squareness_se * 1e6;
    let (offset_x, offset_y) = common_centre(&full).unwrap_or((all_mean[1], all_mean[2]));
    let centre = match trace.centre {
        None => Centre::BarPivot,
        Some(c) if c.given => Centre::Given,
        Some(_) => Centre::TraceLsc,
    };
    Some(Diagnostics {
        centre_offset_x_um: offset_x * 1e3,
        centre_offset_y_um: offset_y * 1e3,
        centre,
        backlash_x_um: significant(all_mean[5] * 1e3, resolution[0]),
        backlash_y_um: significant(all_mean[6] * 1e3, resolution[1]),
        backlash_x_resolution_um: resolution[0],
        backlash_y_resolution_um: resolution[1],
        reversal_spikes: spikes,
        spike_threshold_um: spike_threshold * 1e3,
        servo_mismatch_ms: servo.map(|(v, se)| significant(v, k * se)),
        servo_mismatch_resolution_ms: servo.map(|(_, se)| k * se),
        scale_mismatch_ppm: significant(2.0 * all_mean[3] / r0 * 1e6, scale_res),
        scale_mismatch_resolution_ppm: scale_res,
        squareness_urad: significant(squareness * 1e6, square_res),
        squareness_resolution_urad: square_res,
        cyclic: cyclic.map(|(c, _)| c),
        cyclic_test: searched.map(|(_, t)| t),
        residual_rms_um: rms / n * 1e3,
        runs_used: fits.len(),
    })
}

/// Standard errors a diagnostic must exceed to be reported (3).
pub const SIGNIFICANCE: f64 = 3.0;

/// A run's direction, coefficients and their variances (mm²).
type RunStat = (Direction, DVector<f64>, DVector<f64>);

/// The mean coefficients over the runs of direction `d` (all: None) and
/// their standard errors (of the mean); None when there are none.
fn stat(fits: &[RunStat], d: Option<Direction>) -> Option<(DVector<f64>, DVector<f64>)> {
    let sel: Vec<&RunStat> = fits.iter().filter(|f| d.is_none_or(|d| f.0 == d)).collect();
    let first = sel.first()?;
    let n = sel.len() as f64;
    let mut mean = DVector::<f64>::zeros(first.1.len());
    let mut var = DVector::<f64>::zeros(first.1.len());
    for (_, c, v) in &sel {
        mean += c;
        var += v;
    }
    Some((mean / n, var.map(f64::sqrt) / n))
}

/// The LSC centre of all full runs together, mm, relative to the centre
/// the deviations are about: the linearised LSC, Δ ≈ r + cx cos θ + cy sin θ
/// fitted to the deviations (second order Δ²/R₀ left out: 1e-8 µm for µm
/// deviations on a 100 mm bar), which keeps the digits a fit on the
/// R₀-sized coordinates would cancel.
fn common_centre(full: &[&Run]) -> Option<(f64, f64)> {
    let rows = full.iter().flat_map(|r| {
        r.angle.iter().zip(&r.deviation).map(|(&t, &d)| {
            let (sn, cs) = t.sin_cos();
            ([1.0, cs, sn], d)
        })
    });
    let (c, _) = lsq_full(rows, 3)?;
    Some((c[1], c[2]))
}

/// RMS of a run's residuals over its fitted points, mm.
fn fit_points_rms(run: &Run, res: &[f64]) -> f64 {
    let s = run.direction.sign();
    let (sum, count) = run
        .angle
        .iter()
        .zip(res)
        .filter(|(t, _)| !after_quadrant(**t, s, FIT_SKIP))
        .fold((0.0, 0usize), |(a, c), (_, r)| (a + r * r, c + 1));
    if count == 0 {
        0.0
    } else {
        (sum / count as f64).sqrt()
    }
}

/// The runs that cover a full revolution (≥ 355°).
pub(super) fn full_runs(trace: &BallbarTrace) -> Vec<&Run> {
    trace
        .runs
        .iter()
        .filter(|r| {
            let (lo, hi) = r
                .angle
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| {
                    (a.min(t), b.max(t))
                });
            r.angle.len() == r.deviation.len() && hi - lo >= 355f64.to_radians()
        })
        .collect()
}

/// Coefficients, diagonal of the inverse normal matrix, residuals (mm),
/// residual variance (mm²).
pub(super) type RunFit = (DVector<f64>, DVector<f64>, Vec<f64>, f64);

/// The error model fitted to one run: coefficients, the diagonal of the
/// inverse normal matrix, the residual of every sample (mm) and the
/// residual variance of the fitted samples (mm²). The 10° after each
/// quadrant point in the direction of travel, where reversal spikes live,
/// are left out of the fit (the steps stay visible); orders 3–8 are in
/// the model, so that smooth motion errors are read neither as spikes nor
/// as cyclic error.
pub(super) fn fit_run(run: &Run) -> Option<RunFit> {
    let s = run.direction.sign();
    let keep: Vec<usize> = (0..run.angle.len())
        .filter(|&i| !after_quadrant(run.angle[i], s, FIT_SKIP))
        .collect();
    // Each point's basis once (ten sin/cos), for the fit and the residuals.
    let bases: Vec<[f64; COLS]> = run.angle.iter().map(|&t| basis(t, s)).collect();
    let (coef, inv) = lsq_full(keep.iter().map(|&i| (bases[i], run.deviation[i])), COLS)?;
    let res: Vec<f64> = bases
        .iter()
        .zip(&run.deviation)
        .map(|(b, d)| d - b.iter().zip(coef.iter()).map(|(b, c)| b * c).sum::<f64>())
        .collect();
    // Residual variance of the fitted points → standard errors, inflated
    // for correlated residuals (module header).
    let dof = keep.len().saturating_sub(COLS).max(1) as f64;
    let var = keep.iter().map(|&i| res[i] * res[i]).sum::<f64>() / dof;
    let kept: Vec<f64> = keep.iter().map(|&i| res[i]).collect();
    Some((coef, inv, res, var * ar1_inflation(&kept)))
}

/// The variance inflation (1 + ρ)/(1 − ρ) of correlated residuals, ρ their
/// lag-1 autocorrelation (0 when negative), at most the number of samples.
pub(super) fn ar1_inflation(res: &[f64]) -> f64 {
    let n = res.len();
    let ss: f64 = res.iter().map(|r| r * r).sum();
    if n < 3 || ss <= 0.0 {
        return 1.0;
    }
    let lag: f64 = res.windows(2).map(|w| w[0] * w[1]).sum();
    let rho = (lag / ss).clamp(0.0, 1.0);
    if rho >= 1.0 {
        return n as f64;
    }
    ((1.0 + rho) / (1.0 - rho)).min(n as f64)
}

/// The part after each quadrant point, in the direction of travel, that the
/// run model leaves out, rad (10°: where the reversal spikes live).
pub(super) const FIT_SKIP: f64 = 10.0 * (std::f64::consts::PI / 180.0);

/// The (θ, deviation) pairs of a run the run model is fitted to: all but
/// the [`FIT_SKIP`] after each quadrant point.
pub(super) fn fit_points(run: &Run) -> impl Iterator<Item = (f64, f64)> + '_ {
    let s = run.direction.sign();
    run.angle
        .iter()
        .zip(&run.deviation)
        .filter(move |(t, _)| !after_quadrant(**t, s, FIT_SKIP))
        .map(|(&t, &d)| (t, d))
}

/// Whether θ lies within `w` after a quadrant point in the direction `s`.
pub(super) fn after_quadrant(t: f64, s: f64, w: f64) -> bool {
    (s * t).rem_euclid(std::f64::consts::FRAC_PI_2) < w
}

/// The reversal spikes of one run above its own noise threshold (the
/// caller compares them with one threshold for all runs), and that
/// threshold (mm). One pass over the points: each point belongs to at most
/// one window, the 15° after quadrant point k·90° in the direction of
/// travel.
fn find_spikes(run: &Run, res: &[f64]) -> (Vec<Spike>, f64) {
    let s = run.direction.sign();
    let w = 15f64.to_radians();
    let (lo, hi) = run
        .angle
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| {
            (a.min(t), b.max(t))
        });
    let q = std::f64::consts::FRAC_PI_2;
    if !(lo.is_finite() && hi.is_finite()) {
        return (Vec::new(), 0.0);
    }
    let k0 = (lo / q).ceil() as i64;
    let k1 = (hi / q).floor() as i64;
    let count = (k1 - k0 + 1).max(0) as usize;
    let mut peak = vec![0.0f64; count];
    let mut outside = 0.0f64;
    for (&t, &r) in run.angle.iter().zip(res) {
        // The quadrant point whose window may hold t.
        let k = if s > 0.0 {
            (t / q).floor()
        } else {
            (t / q).ceil()
        } as i64;
        let qa = k as f64 * q;
        let inside = if s > 0.0 { t - qa <= w } else { qa - t <= w };
        match (inside, usize::try_from(k - k0)) {
            (true, Ok(j)) if j < count => {
                if r.abs() > peak[j].abs() {
                    peak[j] = r;
                }
            }
            _ => outside = outside.max(r.abs()),
        }
    }
    let threshold = (1.5 * outside).max(1e-6);
    let mut out = Vec::new();
    for (j, &p) in peak.iter().enumerate() {
        let qa = (k0 + j as i64) as f64 * q;
        // A reversal inside the run, with its window inside the run.
        let (w0, w1) = if s > 0.0 { (qa, qa + w) } else { (qa - w, qa) };
        if qa <= lo + 1e-9 || qa >= hi - 1e-9 || w0 < lo || w1 > hi || p.abs() <= threshold {
            continue;
        }
        let deg = qa.to_degrees().rem_euclid(360.0);
        let axis = if ((deg / 90.0).round() as i64) % 2 == 0 {
            'x'
        } else {
            'y'
        };
        out.push(Spike {
            direction: run.direction,
            axis,
            angle_deg: deg.round(),
            height_um: p * 1e3,
            threshold_um: threshold * 1e3,
        });
    }
    (out, threshold)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ballbar::{synthetic_trace, SyntheticConfig};

    #[test]
    fn pure_noise_reports_no_spike_and_no_backlash() {
        // Uniform noise ±2 µm, nothing else: no feature may be reported,
        // and the stated resolutions are of the noise's order.
        let t = synthetic_trace(&SyntheticConfig {
            noise: 0.002,
            ..Default::default()
        })
        .unwrap();
        let d = diagnose(&t).unwrap();
        assert!(d.reversal_spikes.is_empty(), "{:?}", d.reversal_spikes);
        assert_eq!((d.backlash_x_um, d.backlash_y_um), (0.0, 0.0), "{d:?}");
        assert!(d.cyclic.is_none(), "{d:?}");
        // σ of uniform ±2 µm is 1.15 µm; the backlash column's standard
        // error over ~3000 points is a few hundredths of that.
        assert!(
            d.backlash_x_resolution_um > 0.01 && d.backlash_x_resolution_um < 1.0,
            "{d:?}"
        );
        // Threshold 1.5 × the largest residual: about 3 µm.
        assert!(
            d.spike_threshold_um > 2.5 && d.spike_threshold_um < 3.5,
            "{d:?}"
        );
    }

    #[test]
    fn correlated_residuals_widen_the_standard_errors() {
        assert_eq!(ar1_inflation(&[1.0, -1.0, 1.0, -1.0]), 1.0);
        assert_eq!(ar1_inflation(&[0.0; 5]), 1.0);
        assert_eq!(ar1_inflation(&[1.0, 1.0]), 1.0);
        // ρ = 3/4 for four equal values: (1 + ρ)/(1 − ρ) = 7, capped at n = 4.
        assert_eq!(ar1_inflation(&[1.0; 4]), 4.0);
        // A slow sine: ρ = cos(0.1) nearly; inflation about 400 (≤ n).
        let s: Vec<f64> = (0..2000).map(|i| (i as f64 * 0.1).sin()).collect();
        let f = ar1_inflation(&s);
        assert!(f > 300.0 && f < 500.0, "{f}");
    }

    #[test]
    fn features_above_the_noise_are_still_reported() {
        let t = synthetic_trace(&SyntheticConfig {
            noise: 0.0005,
            backlash_x: 0.004,
            spike: 0.006,
            spike_decay_deg: 2.0,
            ..Default::default()
        })
        .unwrap();
        let d = diagnose(&t).unwrap();
        assert!((d.backlash_x_um - 4.0).abs() < 0.2, "{d:?}");
        assert_eq!(d.backlash_y_um, 0.0, "{d:?}");
        // CCW −180…180 and CW 180…−180: three inner quadrant points each.
        assert_eq!(d.reversal_spikes.len(), 6, "{:?}", d.reversal_spikes);
        for s in &d.reversal_spikes {
            assert!((s.height_um - 6.0).abs() < 0.8, "{s:?}");
        }
    }

    #[test]
    fn a_multi_revolution_file_reads_as_its_single_revolution() {
        // Eleven revolutions of the same CCW signature (39,600 points, over
        // the binning limit) against the single revolution (a second
        // computation, unbinned).
        let one = synthetic_trace(&SyntheticConfig {
            both_directions: false,
            cyclic_amplitude: 0.002,
            cyclic_pitch: 5.0,
            backlash_x: 0.003,
            ..Default::default()
        })
        .unwrap();
        let r = &one.runs[0];
        let mut many = one.clone();
        let m = &mut many.runs[0];
        m.angle.clear();
        m.deviation.clear();
        for k in 0..11 {
            let shift = std::f64::consts::TAU * k as f64;
            m.angle.extend(r.angle.iter().map(|a| a + shift));
            m.deviation.extend(&r.deviation);
        }
        let (a, b) = (diagnose(&one).unwrap(), diagnose(&many).unwrap());
        let (ca, cb) = (a.cyclic.unwrap(), b.cyclic.unwrap());
        assert!(
            (ca.pitch_mm - cb.pitch_mm).abs() < 0.01 * ca.pitch_mm,
            "{ca:?} {cb:?}"
        );
        assert!(
            (ca.amplitude_x_um - cb.amplitude_x_um).abs() < 0.05,
            "{ca:?} {cb:?}"
        );
        assert!((cb.amplitude_x_um - 2.0).abs() < 0.2, "{cb:?}");
        assert!(
            (a.backlash_x_um - b.backlash_x_um).abs() < 0.05,
            "{a:?} {b:?}"
        );
    }
}
