//! Best K_FFP method (suzuki-best-kffp §4.7, §5.2–5.3, Eq. 20) and the
//! torque-saturation limits of the rotary axis (Figs. 17 and 21).
//!
//! - [`analytic`]: Eq. 20 for the linear model, by root finding;
//! - [`saturation`]: the ω, α and smallest R_C at which C saturates;
//! - [`best_kffp`] picks the method, and always checks its answer by
//!   simulating the feed-vector test with it (`before` / `after`).
//!
//! # Simulated mode (Fig. 18)
//! When the C torque saturates (or when asked), the linear model no longer
//! predicts the steady mean of α − β. Starting from the analytic K_FFP of X
//! and Y, both are shifted by a common δ (%) until the *simulated*
//! `meanAngleDiff` of the feed-vector test (with saturation) is zero:
//! secant steps inside a bracket, to 1e-7 rad. C keeps its set K_FFP and
//! is simulated once.
//!
//! # Units
//! K_FFP in %; ω in rad/s; angles in rad.

pub mod analytic;
pub mod from_trace;
pub mod saturation;

pub use from_trace::{best_kffp_from_trace, IdentifiedAxis, TraceKffp, TraceOptions};

use serde::{Deserialize, Serialize};

use crate::feed_vector::{self, Condition, FeedVectorError, KffpSet, Summary};
use crate::machine::Machine;
use crate::servo::ServoError;

/// Errors of the Best K_FFP method.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BestKffpError {
    /// A servo model failed.
    #[error("axis {axis}: {source}")]
    Servo {
        /// Axis letter.
        axis: &'static str,
        /// The servo error.
        source: ServoError,
    },
    /// The feed-vector test failed.
    #[error(transparent)]
    FeedVector(#[from] FeedVectorError),
    /// An axis could not be identified from the trace.
    #[error("identifying axis {axis} from the trace: {message}")]
    Identify {
        /// Axis letter.
        axis: &'static str,
        /// The identification's message.
        message: String,
    },
    /// The saturation query has no torque limit to saturate at.
    #[error("`torqueMax`: the machine's C axis has no torque limit (axes.c.torqueMax) and the query gives none; give the C axis' torque limit in N·m")]
    NoTorqueLimit,
    /// No K_FFP in the search range zeroes α − β.
    #[error("axis {axis}: no K_FFP in [{k_min} %, {k_max} %] gives the phase lag {target} rad of the rotary axis; widen options.kMin/kMax or change the C axis K_FFP")]
    NoRoot {
        /// Axis letter.
        axis: &'static str,
        /// Lower search bound, %.
        k_min: f64,
        /// Upper search bound, %.
        k_max: f64,
        /// The lag to match, rad.
        target: f64,
    },
    /// A query or option is out of range.
    #[error("`{field}` = {}: {expected}", crate::numeric::compact(*.value))]
    BadQuery {
        /// camelCase field name.
        field: &'static str,
        /// The value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
}

/// Which method to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Analytic unless the C axis saturates, then simulated.
    #[default]
    Auto,
    /// Eq. 20 on the linear model.
    Analytic,
    /// Search with the saturating simulation (Fig. 18).
    Simulated,
}

/// Options of [`best_kffp`] (the JS `options`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct Options {
    /// Method; default `auto`.
    pub method: Method,
    /// Lower bound of the K_FFP search, %.
    pub k_min: f64,
    /// Upper bound of the K_FFP search, %.
    pub k_max: f64,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            method: Method::Auto,
            k_min: -200.0,
            k_max: 400.0,
        }
    }
}

/// Result of the Best K_FFP method.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct BestKffp {
    /// The K_FFP per axis, %.
    pub kffp: KffpSet,
    /// Simulated summary with the condition's (or machine's) K_FFP.
    pub before: Summary,
    /// Simulated summary with the new K_FFP.
    pub after: Summary,
    /// `analytic` or `simulated`.
    pub method: Method,
    /// α_th of C (Eq. 17), rad.
    pub alpha_th: f64,
    /// α_th − β_th of X and Y with the new K_FFP (Eq. 19), rad.
    pub residual_x: f64,
    /// See `residual_x`.
    pub residual_y: f64,
}

/// Finds the K_FFP per axis that zeroes α − β (the JS `bestKffp`).
///
/// # Units
/// See [`Condition`]; K_FFP in %.
///
/// # Examples
/// ```
/// use mtmotion::best_kffp::{best_kffp, Method, Options};
/// use mtmotion::feed_vector::Condition;
/// let m = mtmotion::machine::preset("nmv5000").unwrap();
/// let r = best_kffp(&m, &Condition::paper(std::f64::consts::PI), &Options::default()).unwrap();
/// assert_eq!(r.method, Method::Analytic);
/// assert!(r.residual_x.abs() < 1e-9 && r.residual_y.abs() < 1e-9);
/// assert!(r.after.mean_angle_diff.abs() < 0.05 * r.before.mean_angle_diff.abs());
/// ```
pub fn best_kffp(
    machine: &Machine,
    cond: &Condition,
    opts: &Options,
) -> Result<BestKffp, BestKffpError> {
    check_options(opts)?;
    cond.validate()?;
    let axes = feed_vector::axes_for(machine, cond)?;
    let base = Baseline::simulate(&axes, cond)?;
    let before = base.summary;
    let [x, y, c] = &axes;
    let alpha = crate::servo::response::alpha_th(c, cond.omega)
        .map_err(|source| BestKffpError::Servo { axis: "c", source })?;
    let method = match opts.method {
        Method::Auto if before.saturated => Method::Simulated,
        Method::Auto => Method::Analytic,
        m => m,
    };
    let (kffp, after) = matched_set(&base, cond, &axes, alpha, 0.0, method, opts)?;
    let (kx, ky) = (kffp.x, kffp.y);
    let residual = |a: &crate::servo::AxisParams, k: f64, name: &'static str| {
        let mut a = a.clone();
        a.kffp = k;
        crate::servo::response::beta_th(&a, cond.omega)
            .map(|b| alpha - b)
            .map_err(|source| BestKffpError::Servo { axis: name, source })
    };
    Ok(BestKffp {
        kffp,
        before,
        after,
        method,
        alpha_th: alpha,
        residual_x: residual(x, kx, "x")?,
        residual_y: residual(y, ky, "y")?,
    })
}

/// The search bounds are finite with kMin < kMax.
fn check_options(opts: &Options) -> Result<(), BestKffpError> {
    if opts.k_min.is_finite() && opts.k_max.is_finite() && opts.k_min < opts.k_max {
        return Ok(());
    }
    Err(BestKffpError::BadQuery {
        field: "options.kMin",
        value: opts.k_min,
        expected: "kMin and kMax must be finite with kMin < kMax (in %)",
    })
}

/// One simulation of the feed-vector test with the set K_FFP: its summary
/// (`before`), and the padded command and C response that the simulated
/// search and the `after` check reuse. C keeps its set K_FFP, so its
/// response is the same in every run (bit for bit): it is simulated once,
/// not three times (with 64 pitch-error harmonics on C each C run was
/// about 2.3 s of a 9 s call).
pub(crate) struct Baseline {
    n: usize,
    t_ss: f64,
    dt: f64,
    /// The command padded for the Pre-Control read-ahead.
    full: feed_vector::command::Command,
    /// The command cut to `n` samples.
    cmd: feed_vector::command::Command,
    c: crate::servo::simulate::AxisResponse,
    /// The test's summary with the axes' own K_FFP.
    pub summary: Summary,
}

impl Baseline {
    /// Simulates the test on `axes` (as [`feed_vector::feed_vector_test`]).
    pub(crate) fn simulate(
        axes: &[crate::servo::AxisParams; 3],
        cond: &Condition,
    ) -> Result<Self, FeedVectorError> {
        let n = feed_vector::samples(axes, cond)?;
        let dt = cond.step();
        let full = feed_vector::padded_command(axes, cond, n);
        let (cmd, [x, y, c]) = feed_vector::simulate_test(axes, cond, n)?;
        let t_ss = feed_vector::steady_from(axes, cond);
        let summary = feed_vector::assemble(cmd.clone(), x, y, c.clone(), cond, t_ss).summary;
        Ok(Self {
            n,
            t_ss,
            dt,
            full,
            cmd,
            c,
            summary,
        })
    }

    /// The test's summary with X and Y replaced by `x` and `y`.
    fn with_xy(
        &self,
        x: &crate::servo::AxisParams,
        y: &crate::servo::AxisParams,
        cond: &Condition,
    ) -> Result<Summary, FeedVectorError> {
        let xr = feed_vector::run_axis("x", x, self.dt, &self.full.x, self.n)?;
        let yr = feed_vector::run_axis("y", y, self.dt, &self.full.y, self.n)?;
        Ok(
            feed_vector::assemble(self.cmd.clone(), xr, yr, self.c.clone(), cond, self.t_ss)
                .summary,
        )
    }
}

/// The K_FFP set whose X and Y lags on the model equal `lag` (rad; C
/// keeps its K_FFP), and, with the simulated method, shifted in common
/// until the saturating simulation's mean α − β is `sim_target` (rad);
/// with the model's simulated summary for that set.
#[allow(clippy::too_many_arguments)]
pub(crate) fn matched_set(
    base: &Baseline,
    cond: &Condition,
    axes: &[crate::servo::AxisParams; 3],
    lag: f64,
    sim_target: f64,
    method: Method,
    opts: &Options,
) -> Result<(KffpSet, Summary), BestKffpError> {
    let [x, y, c] = axes;
    let mut kx = analytic::match_lag(x, cond.omega, lag, opts.k_min, opts.k_max, "x")?;
    let mut ky = analytic::match_lag(y, cond.omega, lag, opts.k_min, opts.k_max, "y")?;
    if method == Method::Simulated {
        let shift = simulated_shift_to(base, axes, cond, kx, ky, sim_target, opts)?;
        kx += shift;
        ky += shift;
    }
    let kffp = KffpSet {
        x: kx,
        y: ky,
        c: c.kffp,
    };
    let (mut xa, mut ya) = (x.clone(), y.clone());
    xa.kffp = kx;
    ya.kffp = ky;
    let after = base.with_xy(&xa, &ya, cond)?;
    Ok((kffp, after))
}

/// The common K_FFP shift of X and Y that brings the simulated mean α − β
/// to `target` rad.
fn simulated_shift_to(
    base: &Baseline,
    axes: &[crate::servo::AxisParams; 3],
    cond: &Condition,
    kx: f64,
    ky: f64,
    target: f64,
    opts: &Options,
) -> Result<f64, BestKffpError> {
    let failure: std::cell::RefCell<Option<FeedVectorError>> = std::cell::RefCell::new(None);
    let mut eval = |delta: f64| -> f64 {
        let mut x = axes[0].clone();
        let mut y = axes[1].clone();
        x.kffp = kx + delta;
        y.kffp = ky + delta;
        match base.with_xy(&x, &y, cond) {
            Ok(s) => s.mean_angle_diff - target,
            Err(e) => {
                *failure.borrow_mut() = Some(e);
                f64::NAN
            }
        }
    };
    // secant from δ = 0 and δ = −10 %, then Brent inside a bracket
    let (mut d0, mut f0) = (0.0, eval(0.0));
    let (mut d1, mut f1) = (-10.0, eval(-10.0));
    for _ in 0..6 {
        if let Some(e) = failure.borrow_mut().take() {
            return Err(e.into());
        }
        if f1.abs() < 1e-7 {
            return Ok(d1);
        }
        if f1 == f0 {
            break;
        }
        let d2 = d1 - f1 * (d1 - d0) / (f1 - f0);
        if !d2.is_finite() {
            break;
        }
        let d2 = d2.clamp(opts.k_min - kx.min(ky), opts.k_max - kx.max(ky));
        d0 = d1;
        f0 = f1;
        d1 = d2;
        f1 = eval(d1);
    }
    if let Some(e) = failure.borrow_mut().take() {
        return Err(e.into());
    }
    if f1.abs() < 1e-6 {
        return Ok(d1);
    }
    let (lo, hi) = (opts.k_min - kx.min(ky), opts.k_max - kx.max(ky));
    crate::numeric::brent(&mut eval, lo, hi, 1e-6).ok_or(BestKffpError::NoRoot {
        axis: "x",
        k_min: opts.k_min,
        k_max: opts.k_max,
        target: 0.0,
    })
}
