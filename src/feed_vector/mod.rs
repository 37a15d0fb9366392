//! The constant-feed-speed-vector test (suzuki-best-kffp §2.3, §3,
//! §4.1–4.2, Eqs. 1–11): X and Y on the circle of radius `R_W`, C turning at
//! the same ω, each axis through its own servo model
//! ([`crate::servo::simulate`]), then the analysis of Eqs. 4–11.
//!
//! - [`command`]: the commanded motion with its linear acc/dec;
//! - [`analysis`]: shape error, α, β, α − β, ΔR and the steady summary;
//! - [`trace_analysis`]: the same analysis of a measured (SERVO GUIDE-style)
//!   trace;
//! - [`trace_plausibility`]: the check that a trace is of this test (C at
//!   ω, X/Y on a circle) before its analysis.
//!
//! # Readings
//! - `condition.j1` is the load on C (Table 1's `*`), `condition.torqueMax`
//!   replaces C's limit and `condition.kffp` the set K_FFP of each axis.
//! - The steady state starts at `t_ss = accelTime + max(Ts) + max(Ta) +
//!   max(Tp) + 0.25 s` (the paper analyses the steady state, §5.1).
//!   The default duration is `t_ss` plus two periods `2·2π/ω`.
//!
//! # Units
//! `rc`, `rw` in mm; `omega` in rad/s; times in s; `j1` in kg·m²;
//! torque in N·m.

pub mod analysis;
pub mod command;
pub mod trace_analysis;
pub mod trace_plausibility;

use serde::{Deserialize, Serialize};

use crate::machine::Machine;
use crate::servo::simulate::{simulate_axis, AxisResponse};
use crate::servo::{AxisParams, ServoError};
use crate::trace::TraceError;

pub use analysis::{Series, Summary};

/// Errors of the feed-vector test and its trace analysis.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FeedVectorError {
    /// A servo parameter or command is unusable.
    #[error("axis {axis}: {source}")]
    Servo {
        /// The axis letter.
        axis: &'static str,
        /// The servo error.
        source: ServoError,
    },
    /// The machine lacks an axis the test needs.
    #[error("the machine has no '{0}' axis; the feed-vector test needs x, y and c")]
    MissingAxis(&'static str),
    /// A condition field is out of range.
    #[error("condition `{field}` = {}: {expected}", crate::numeric::compact(*.value))]
    BadCondition {
        /// camelCase field name.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What was expected.
        expected: String,
    },
    /// The trace could not be read.
    #[error(transparent)]
    Trace(#[from] TraceError),
    /// The input is over a work budget ([`crate::budget`]).
    #[error(transparent)]
    Budget(#[from] crate::budget::BudgetError),
    /// The trace is not of this test (C not turning at ω, X/Y off a circle).
    #[error("{0}")]
    Implausible(String),
    /// A trace value is unusable at a line and column.
    #[error(
        "line {line}, column {column} ('{}'): {why}",
        crate::budget::clip(name, 40)
    )]
    TraceValue {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// Column name.
        name: String,
        /// What is wrong.
        why: String,
    },
}

/// K_FFP per axis, %.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct KffpSet {
    /// X, %.
    pub x: f64,
    /// Y, %.
    pub y: f64,
    /// C, %.
    pub c: f64,
}

/// Test condition (the JS `condition`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Condition {
    /// Radius of curvature of the work piece R_C, mm.
    pub rc: f64,
    /// Offset of the tool centre R_W, mm.
    pub rw: f64,
    /// Angular velocity ω, rad/s.
    pub omega: f64,
    /// Acc/dec time of the command, s.
    pub accel_time: f64,
    /// Load inertia on C, kg·m².
    pub j1: f64,
    /// C torque limit, N·m (default: the machine's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque_max: Option<f64>,
    /// Duration, s (default: steady start + 2 periods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration: Option<f64>,
    /// Time step, s (default 1 ms, SERVO GUIDE's sampling).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dt: Option<f64>,
    /// K_FFP per axis, % (default: the machine's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kffp: Option<KffpSet>,
}

/// Largest number of samples a test may have (the work budget
/// [`crate::budget::MAX_FEED_VECTOR_SAMPLES`]).
pub const MAX_SAMPLES: usize = crate::budget::MAX_FEED_VECTOR_SAMPLES;

fn bad(field: &'static str, value: f64, expected: &str) -> FeedVectorError {
    FeedVectorError::BadCondition {
        field,
        value,
        expected: expected.to_string(),
    }
}

impl FeedVectorError {
    /// The message in the user's words: a condition field is named by the
    /// label and unit the page shows (`R_C [mm] = -5: …`), not by its code
    /// name ("condition `rc`"); other errors as [`std::fmt::Display`].
    ///
    /// # Examples
    /// ```
    /// use mtmotion::feed_vector::Condition;
    /// let mut c = Condition::paper(1.0);
    /// c.rc = -5.0;
    /// let e = c.validate().unwrap_err();
    /// assert_eq!(e.user_message(), "R_C [mm] = -5: must be between 0 and 10,000 mm");
    /// ```
    pub fn user_message(&self) -> String {
        match self {
            Self::BadCondition {
                field,
                value,
                expected,
            } => match Condition::field_label(field) {
                Some((label, unit)) => format!(
                    "{label} [{unit}] = {}: {expected}",
                    crate::numeric::compact(*value)
                ),
                None => self.to_string(),
            },
            _ => self.to_string(),
        }
    }
}

impl Condition {
    /// Label and unit of a condition field (camelCase) as the suzuki paper
    /// and the page name it.
    pub fn field_label(field: &str) -> Option<(&'static str, &'static str)> {
        Some(match field {
            "rc" => ("R_C", "mm"),
            "rw" => ("R_W", "mm"),
            "omega" => ("ω", "rad/s"),
            "accelTime" => ("accel time", "s"),
            "j1" => ("J1 (load on C)", "kg·m²"),
            "torqueMax" => ("torque max", "N·m"),
            "duration" => ("duration", "s"),
            "dt" => ("time step", "s"),
            "kffp" => ("K_FFP", "%"),
            _ => return None,
        })
    }

    /// The paper's test (§3): R_C = 5 mm, R_W = 8 mm, T_acc = 0.064 s,
    /// J1 = 1.70 kg·m², at angular velocity `omega`.
    pub fn paper(omega: f64) -> Self {
        Self {
            rc: 5.0,
            rw: 8.0,
            omega,
            accel_time: 0.064,
            j1: 1.70,
            torque_max: None,
            duration: None,
            dt: None,
            kffp: None,
        }
    }

    /// Checks the geometric and timing fields.
    pub fn validate(&self) -> Result<(), FeedVectorError> {
        // Positive, not subnormal, and at most `hi`.
        let within = |f: &'static str, v: f64, hi: f64, expected: &'static str| {
            if v.is_normal() && v > 0.0 && v <= hi {
                Ok(())
            } else {
                Err(bad(f, v, expected))
            }
        };
        let pos = |f: &'static str, v: f64| within(f, v, 1e12, "must be a finite number > 0");
        within("rc", self.rc, 1e4, "must be between 0 and 10,000 mm")?;
        within("rw", self.rw, 1e4, "must be between 0 and 10,000 mm")?;
        // 1000 rad/s is 9,549 rpm, faster than any rotary table; and the
        // test needs at least 8 samples per revolution.
        within(
            "omega",
            self.omega,
            1000.0,
            "must be between 0 and 1000 rad/s (9,549 rpm)",
        )?;
        if !(self.accel_time.is_finite() && (0.0..=100.0).contains(&self.accel_time)) {
            return Err(bad(
                "accelTime",
                self.accel_time,
                "must be between 0 and 100 s",
            ));
        }
        if !(self.j1.is_finite() && (0.0..=1e4).contains(&self.j1)) {
            return Err(bad("j1", self.j1, "must be between 0 and 1e4 kg·m²"));
        }
        if let Some(t) = self.torque_max {
            pos("torqueMax", t)?;
        }
        if let Some(dt) = self.dt {
            if !(dt.is_finite() && (1e-7..=0.01).contains(&dt)) {
                return Err(bad("dt", dt, "must be between 1e-7 and 0.01 s"));
            }
        }
        if self.omega * self.step() > std::f64::consts::FRAC_PI_4 {
            return Err(bad(
                "omega",
                self.omega,
                "turns more than π/4 per time step: lower ω or dt (at least 8 samples per revolution)",
            ));
        }
        if let Some(d) = self.duration {
            pos("duration", d)?;
        }
        if let Some(k) = self.kffp {
            for (f, v) in [("kffp.x", k.x), ("kffp.y", k.y), ("kffp.c", k.c)] {
                if !(v.is_finite() && (-1000.0..=1000.0).contains(&v)) {
                    return Err(bad(f, v, "must be between −1000 and 1000 %"));
                }
            }
        }
        Ok(())
    }

    /// The time step, s.
    pub fn step(&self) -> f64 {
        self.dt.unwrap_or(1e-3)
    }
}

/// The X, Y and C axes of `machine` with the condition applied.
pub fn axes_for(machine: &Machine, cond: &Condition) -> Result<[AxisParams; 3], FeedVectorError> {
    let get = |k: &'static str| {
        machine
            .axes
            .get(k)
            .cloned()
            .ok_or(FeedVectorError::MissingAxis(k))
    };
    let (mut x, mut y, mut c) = (get("x")?, get("y")?, get("c")?);
    c.j1 = cond.j1;
    if cond.torque_max.is_some() {
        c.torque_max = cond.torque_max;
    }
    if let Some(k) = cond.kffp {
        x.kffp = k.x;
        y.kffp = k.y;
        c.kffp = k.c;
    }
    for (name, a) in [("x", &x), ("y", &y), ("c", &c)] {
        a.validate()
            .map_err(|source| FeedVectorError::Servo { axis: name, source })?;
    }
    Ok([x, y, c])
}

/// Start of the steady-state window, s (module header).
pub fn steady_from(axes: &[AxisParams; 3], cond: &Condition) -> f64 {
    let max = |f: fn(&AxisParams) -> f64| axes.iter().map(f).fold(0.0, f64::max);
    cond.accel_time + max(|a| a.ts) + max(|a| a.ta) + max(|a| a.tp) + 0.25
}

/// Number of samples of the test.
pub fn samples(axes: &[AxisParams; 3], cond: &Condition) -> Result<usize, FeedVectorError> {
    let dt = cond.step();
    let t_ss = steady_from(axes, cond);
    let duration = cond
        .duration
        .unwrap_or(t_ss + 2.0 * std::f64::consts::TAU / cond.omega + 2.0 * dt);
    let n = (duration / dt).round() + 1.0;
    if n > MAX_SAMPLES as f64 {
        return Err(bad(
            "duration",
            duration,
            &format!("gives {n} samples at dt = {dt} s; at most {MAX_SAMPLES} are allowed — shorten it or raise dt"),
        ));
    }
    // the whole test: each pitch-error harmonic is one `sin` per sample
    crate::budget::check(
        "feed-vector test",
        (n as u64).saturating_mul(axes.iter().map(|a| 1 + a.pitch_error.len() as u64).sum()),
        crate::budget::MAX_AXIS_SIM_TERMS,
        "terms (samples × (1 + pitch-error harmonics), over X, Y and C)",
        "shorten it, raise dt or give fewer pitch-error harmonics",
    )?;
    Ok(n as usize)
}

/// Result of one simulated test.
#[derive(Debug, Clone, PartialEq)]
pub struct FeedVectorResult {
    /// The time series.
    pub series: Series,
    /// The steady-state summary.
    pub summary: Summary,
}

/// Samples beyond the end of the test that the Pre-Control read-ahead may
/// see: the command is simulated that much longer and the response cut, so
/// the end of the test is not a stop of the NC.
pub(crate) fn read_ahead_pad(axes: &[AxisParams; 3], dt: f64) -> usize {
    let ahead = axes.iter().map(|a| a.tp + a.ta).fold(0.0, f64::max);
    (ahead / dt).ceil() as usize + 2
}

/// One axis simulated on its (padded) command and cut to `n` samples,
/// errors tagged with the axis.
pub(crate) fn run_axis(
    name: &'static str,
    axis: &AxisParams,
    dt: f64,
    cmd: &[f64],
    n: usize,
) -> Result<AxisResponse, FeedVectorError> {
    let mut r = simulate_axis(axis, dt, cmd)
        .map_err(|source| FeedVectorError::Servo { axis: name, source })?;
    r.position.truncate(n);
    r.velocity.truncate(n);
    r.torque.truncate(n);
    if let Some(limit) = axis.torque_max {
        // saturation beyond the cut does not count
        r.saturated = r.saturated && r.torque.iter().any(|t| t.abs() >= limit);
    }
    Ok(r)
}

/// The command of a test with `n` samples, padded for the Pre-Control
/// read-ahead ([`read_ahead_pad`]).
pub(crate) fn padded_command(
    axes: &[AxisParams; 3],
    cond: &Condition,
    n: usize,
) -> command::Command {
    let dt = cond.step();
    command::sample(
        n + read_ahead_pad(axes, dt),
        dt,
        cond.rw,
        cond.omega,
        cond.accel_time,
    )
}

/// The padded command of a test with `n` samples, and the three responses.
pub(crate) fn simulate_test(
    axes: &[AxisParams; 3],
    cond: &Condition,
    n: usize,
) -> Result<(command::Command, [AxisResponse; 3]), FeedVectorError> {
    let dt = cond.step();
    let mut cmd = padded_command(axes, cond, n);
    let x = run_axis("x", &axes[0], dt, &cmd.x, n)?;
    let y = run_axis("y", &axes[1], dt, &cmd.y, n)?;
    let c = run_axis("c", &axes[2], dt, &cmd.theta, n)?;
    cmd.t.truncate(n);
    cmd.theta.truncate(n);
    cmd.x.truncate(n);
    cmd.y.truncate(n);
    Ok((cmd, [x, y, c]))
}

/// Builds series and summary from the command and the three responses.
pub(crate) fn assemble(
    cmd: command::Command,
    x: AxisResponse,
    y: AxisResponse,
    c: AxisResponse,
    cond: &Condition,
    t_ss: f64,
) -> FeedVectorResult {
    let saturated = c.saturated;
    let mut series = Series {
        t: cmd.t,
        x_cmd: cmd.x,
        y_cmd: cmd.y,
        c_cmd: cmd.theta,
        x: x.position,
        y: y.position,
        c: c.position,
        torque_c: c.torque,
        ..Series::default()
    };
    analysis::derive(&mut series, cond.rw, cond.rc);
    let summary = analysis::summarize(&series, cond.omega, t_ss, saturated);
    FeedVectorResult { series, summary }
}

/// Simulates the constant-feed-speed-vector test (the JS `feedVectorTest`).
///
/// # Units
/// See [`Condition`]; series in mm, rad, s, N·m.
///
/// # Examples
/// ```
/// use mtmotion::feed_vector::{feed_vector_test, Condition};
/// let m = mtmotion::machine::preset("nmv5000").unwrap();
/// let r = feed_vector_test(&m, &Condition::paper(std::f64::consts::PI)).unwrap();
/// // the rotary axis lags the linear axes: α − β > 0 with K_FFP = 100 %
/// assert!(r.summary.mean_angle_diff > 0.0 && r.summary.mean_angle_diff < 0.05);
/// assert!(!r.summary.saturated);
/// ```
pub fn feed_vector_test(
    machine: &Machine,
    cond: &Condition,
) -> Result<FeedVectorResult, FeedVectorError> {
    cond.validate()?;
    let axes = axes_for(machine, cond)?;
    let n = samples(&axes, cond)?;
    let (cmd, [x, y, c]) = simulate_test(&axes, cond, n)?;
    let t_ss = steady_from(&axes, cond);
    Ok(assemble(cmd, x, y, c, cond, t_ss))
}
