//! The simulated cone-frustum ball-bar test (kato §2–3): path → inverse
//! kinematics (continuous branch) → per-axis drives → forward kinematics
//! with the geometric errors → change of the bar length.
//!
//! Readings chosen: the feed is the speed of the spindle ball along its
//! circle; `points` samples cover one revolution (counter-clockwise about
//! the cone axis unless `clockwise`), after a lead-in arc of `leadInDeg`
//! that lets the drives leave their start transient (dropped from the
//! result). `radius`, if given, sets the spindle-ball circle radius and
//! the bar length follows from it (`L = radius / cos θ` perpendicular,
//! `L = radius` parallel). Axis commands must be continuous, as on a real
//! machine: every later point takes the branch nearest the previous one,
//! and the start branch is the one, in order of smallest rotary angles,
//! whose continuation stays inside the limits without any rotary axis
//! moving more than [`MAX_ROTARY_STEP`] in one sample (a branch change,
//! e.g. A → −A with C + 180°, which an ideal drive would pass unnoticed
//! but a servo cannot follow). If no start branch does, the test refuses
//! with [`ConeFrustumError::BranchJump`].
//!
//! Units: config in degrees, mm and mm/min; results in mm, rad, s (the JS
//! binding gives rotary axis positions in degrees).

use std::f64::consts::TAU;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::path::{Geometry, Method, PathPoint};
use super::{drive, sensitivity, ConeFrustumError};
use crate::kinematics::inverse::limits_from_degrees;
use crate::kinematics::{Chain, GeometricErrors, Model, Pose, AXES};
use crate::machine::{Machine, MachineRef};
use crate::servo::transmission::DriveErrors;
use crate::servo::{AxisKind, AxisParams};

fn perpendicular() -> Method {
    Method::Perpendicular
}
fn hundred() -> f64 {
    100.0
}
fn n3600() -> usize {
    3600
}
fn thirty() -> f64 {
    30.0
}
fn yes() -> bool {
    true
}

/// The test configuration (the JS `coneFrustumTest` argument).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct ConeFrustumConfig {
    /// Preset name or machine description.
    pub machine: MachineRef,
    /// Half-apex angle θ, degrees (ISO: 15 or 45).
    pub half_apex_deg: f64,
    /// Inclination β of the cone axis, degrees (kato: 10 or 30).
    pub inclination_deg: f64,
    /// Bar direction.
    #[serde(default = "perpendicular")]
    pub method: Method,
    /// Bar length, mm (kato: 100).
    #[serde(default = "hundred")]
    pub bar_length: f64,
    /// Feed of the spindle ball, mm/min.
    pub feed: f64,
    /// Spindle-ball circle radius, mm (sets the bar length).
    #[serde(default)]
    pub radius: Option<f64>,
    /// Table-ball centre in the workpiece frame, mm.
    #[serde(default)]
    pub centre: Option<[f64; 3]>,
    /// Geometric errors (mm, rad).
    #[serde(default)]
    pub errors: GeometricErrors,
    /// Drive errors: backlash and worm-gear pitch error per axis (mm, rad).
    #[serde(default)]
    pub drives: DriveErrors,
    /// The axes follow the command exactly (transmission errors remain).
    #[serde(default)]
    pub ideal_servo: bool,
    /// Spindle-ball offset from the gauge point along the tool axis, mm.
    #[serde(default)]
    pub tool_length: f64,
    /// Samples per revolution.
    #[serde(default = "n3600")]
    pub points: usize,
    /// Run clockwise about the cone axis.
    #[serde(default)]
    pub clockwise: bool,
    /// Lead-in arc before the measured revolution, degrees.
    #[serde(default = "thirty")]
    pub lead_in_deg: f64,
    /// Compute the sensitivity coefficients along the path (to each axis
    /// and each location error); `false` leaves both lists empty and saves
    /// about a quarter of the run (default `true`).
    #[serde(default = "yes")]
    pub sensitivities: bool,
}

/// Command and actual position of one axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxisSeries {
    /// Axis letter.
    pub axis: String,
    /// Linear (positions in mm) or rotary (positions in rad).
    pub kind: AxisKind,
    /// Commanded position, mm or rad.
    pub command: Vec<f64>,
    /// Actual (table) position, mm or rad.
    pub actual: Vec<f64>,
}

/// A named series of sensitivity coefficients.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Series {
    /// Axis letter or ISO error symbol.
    pub name: String,
    /// Values along the path (mm/mm or mm/rad).
    pub values: Vec<f64>,
    /// Root mean square of `values` over the path (same unit): how much
    /// the bar sees of this axis or error on average.
    pub rms: f64,
}

impl Series {
    /// A series with its RMS.
    pub fn new(name: String, values: Vec<f64>) -> Self {
        let rms = if values.is_empty() {
            0.0
        } else {
            (values.iter().map(|v| v * v).sum::<f64>() / values.len() as f64).sqrt()
        };
        Self { name, values, rms }
    }
}

/// The result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct ConeFrustumResult {
    /// Path angle φ around the cone axis, degrees (0…360).
    pub angle_deg: Vec<f64>,
    /// Time, s (0 at the start of the measured revolution).
    pub time: Vec<f64>,
    /// Change of bar length, mm.
    pub deviation: Vec<f64>,
    /// Nominal spindle-ball path in the workpiece frame, mm.
    pub path: [Vec<f64>; 3],
    /// Per-axis command and actual position.
    pub axes: Vec<AxisSeries>,
    /// Sensitivity of the bar to each axis.
    pub axis_sensitivity: Vec<Series>,
    /// Sensitivity of the bar to each location error.
    pub error_sensitivity: Vec<Series>,
    /// Bar length used, mm.
    pub bar_length: f64,
    /// Spindle-ball circle radius, mm.
    pub radius: f64,
    /// Duration of one revolution, s.
    pub duration: f64,
    /// Largest bar-length change, mm.
    pub max_deviation: f64,
    /// Smallest (most negative) bar-length change, mm.
    pub min_deviation: f64,
}

fn bad(field: &'static str, value: f64, why: &'static str) -> ConeFrustumError {
    ConeFrustumError::BadConfig { field, value, why }
}

fn placeholder_axis(kind: AxisKind) -> AxisParams {
    AxisParams {
        kind,
        j: 1.0,
        j1: 0.0,
        c: 0.0,
        kpp: 1.0,
        kvp: 1.0,
        kvi: 0.0,
        kffp: 0.0,
        ts: 0.0,
        ta: 0.0,
        tp: 0.0,
        torque_max: None,
        lead: Some(0.01),
        gear_ratio: None,
        backlash: 0.0,
        pitch_error: Vec::new(),
        pitch_reading: Default::default(),
        friction: 0.0,
        gravity: 0.0,
    }
}

/// Runs the simulated test.
///
/// # Units
/// See [`ConeFrustumConfig`]; results in mm, rad, s.
///
/// # Examples
/// ```
/// use mtmotion::cone_frustum::{cone_frustum_test, ConeFrustumConfig, Method};
/// use mtmotion::kinematics::GeometricErrors;
/// use mtmotion::machine::MachineRef;
/// let cfg = ConeFrustumConfig {
///     machine: MachineRef::Name("trunnion-ac".into()), half_apex_deg: 45.0,
///     inclination_deg: 10.0, method: Method::Perpendicular, bar_length: 100.0,
///     feed: 1000.0, radius: None, centre: Some([0.0, 50.0, 0.0]), errors: GeometricErrors::default(),
///     drives: Default::default(),
///     ideal_servo: true, tool_length: 0.0, points: 360, clockwise: false, lead_in_deg: 0.0,
///     sensitivities: true };
/// let r = cone_frustum_test(&cfg).unwrap();
/// assert!(r.deviation.iter().all(|d| d.abs() < 1e-9)); // ideal machine, ideal servo
/// ```
pub fn cone_frustum_test(cfg: &ConeFrustumConfig) -> Result<ConeFrustumResult, ConeFrustumError> {
    let (machine, chain) = cfg.machine.resolve()?;
    cfg.drives
        .validate(&chain.axes())
        .map_err(ConeFrustumError::Drives)?;
    let geo = geometry(cfg)?;
    let radius = geo.circle_radius();
    let duration = TAU * radius / (cfg.feed / 60.0);
    let n = cfg.points;
    let s = Sampling {
        n,
        lead: (n as f64 * cfg.lead_in_deg / 360.0).ceil() as usize,
        dir: if cfg.clockwise { -1.0 } else { 1.0 },
        dt: duration / n as f64,
    };
    let present: Vec<usize> = (0..6)
        .filter(|i| chain.axes().contains(&AXES[*i]))
        .collect();
    if !cfg.ideal_servo {
        // every axis is simulated at SERVO_STEP or finer over the whole run
        let per_axis = ((s.n + s.lead) as u64)
            .saturating_mul((s.dt / super::drive::SERVO_STEP).ceil().max(1.0) as u64);
        crate::budget::check(
            "servo simulation",
            per_axis.saturating_mul(present.len() as u64),
            crate::budget::MAX_CONE_FRUSTUM_STEPS,
            "steps (1 ms steps of the whole revolution × axes)",
            "raise the feed (a revolution at 1 mm/min takes hours) or set idealServo: true",
        )?;
        // each worm-gear pitch-error harmonic is one `sin` per step, as in
        // `simulateAxis` (64 on A and C at 5 M steps took 5.2-7.9 s)
        let harmonics = |k: &usize| {
            machine.axes.get(AXES[*k]).map_or(0, |p| {
                cfg.drives.applied_to(AXES[*k], p.clone()).pitch_error.len() as u64
            })
        };
        crate::budget::check(
            "servo simulation",
            present
                .iter()
                .map(|k| per_axis.saturating_mul(1 + harmonics(k)))
                .fold(0u64, u64::saturating_add),
            crate::budget::MAX_AXIS_SIM_TERMS,
            "terms (1 ms steps × (1 + pitch-error harmonics), over the axes)",
            "raise the feed or give fewer pitch-error harmonics",
        )?;
    }
    let cmd = commands(cfg, &chain, &machine, &geo, &s)?;
    let (q_act, series) = drive_axes(cfg, &machine, &cmd.q, &present, &s)?;
    let r = bar_readings(cfg, &chain, &geo, &cmd, &q_act, &present, &s)?;
    let max_deviation = r
        .deviation
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    let min_deviation = r.deviation.iter().copied().fold(f64::INFINITY, f64::min);
    Ok(ConeFrustumResult {
        angle_deg: r.angle_deg,
        time: r.time,
        deviation: r.deviation,
        path: r.path,
        axes: series,
        axis_sensitivity: present
            .iter()
            .zip(r.axis_sens)
            .map(|(k, v)| Series::new(AXES[*k].to_string(), v))
            .collect(),
        error_sensitivity: r
            .symbols
            .into_iter()
            .zip(r.err_sens)
            .map(|(s, v)| Series::new(s, v))
            .collect(),
        bar_length: geo.bar_length,
        radius,
        duration,
        max_deviation,
        min_deviation,
    })
}

/// The checked configuration as the path geometry: half apex, inclination,
/// bar direction, bar length (from `radius` when given) and centre.
fn geometry(cfg: &ConeFrustumConfig) -> Result<Geometry, ConeFrustumError> {
    if !(cfg.half_apex_deg.is_finite() && cfg.half_apex_deg > 0.0 && cfg.half_apex_deg < 90.0) {
        return Err(bad(
            "halfApexDeg",
            cfg.half_apex_deg,
            "must be between 0 and 90 degrees (ISO 10791-6: 15 or 45)",
        ));
    }
    if !(cfg.inclination_deg.is_finite() && cfg.inclination_deg.abs() < 90.0) {
        return Err(bad(
            "inclinationDeg",
            cfg.inclination_deg,
            "must be between −90 and 90 degrees",
        ));
    }
    // ISO 10791-6 runs at a few hundred to a few thousand mm/min; outside
    // 1…100,000 mm/min one revolution takes hours (time steps of seconds)
    // or microseconds.
    if !(cfg.feed.is_finite() && (1.0..=1e5).contains(&cfg.feed)) {
        return Err(bad(
            "feed",
            cfg.feed,
            "must be between 1 and 100,000 mm/min",
        ));
    }
    if !(cfg.points >= 8 && cfg.points <= 1_000_000) {
        return Err(bad(
            "points",
            cfg.points as f64,
            "must be between 8 and 1 000 000",
        ));
    }
    if !(cfg.lead_in_deg.is_finite() && (0.0..=360.0).contains(&cfg.lead_in_deg)) {
        return Err(bad(
            "leadInDeg",
            cfg.lead_in_deg,
            "must be between 0 and 360 degrees",
        ));
    }
    let theta = cfg.half_apex_deg.to_radians();
    let bar_length = match cfg.radius {
        Some(r) if !(r.is_finite() && r > 0.0) => return Err(bad("radius", r, "must be > 0 mm")),
        Some(r) => match cfg.method {
            Method::Perpendicular => r / theta.cos(),
            Method::Parallel => r,
        },
        None => cfg.bar_length,
    };
    if !(bar_length.is_finite() && bar_length > 0.0) {
        return Err(bad("barLength", bar_length, "must be > 0 mm"));
    }
    let centre = cfg.centre.unwrap_or([0.0; 3]);
    if !centre.iter().all(|v| v.is_finite()) {
        return Err(bad(
            "centre",
            f64::NAN,
            "must be three finite coordinates in mm",
        ));
    }
    Ok(Geometry {
        half_apex: theta,
        inclination: cfg.inclination_deg.to_radians(),
        method: cfg.method,
        bar_length,
        centre: Vector3::from(centre),
    })
}

/// How the revolution is sampled: `n` samples after `lead` lead-in ones,
/// direction `dir` (±1), step `dt` in s.
struct Sampling {
    n: usize,
    lead: usize,
    dir: f64,
    dt: f64,
}

impl Sampling {
    /// Path angle φ of sample `i`, rad (0 at the start of the measured revolution).
    fn phi(&self, i: usize) -> f64 {
        self.dir * TAU * (i as f64 - self.lead as f64) / self.n as f64
    }
}

/// The path points and the continuous axis commands of every sample.
struct Commands {
    points: Vec<PathPoint>,
    q: Vec<[f64; 6]>,
}

/// Inverse kinematics of every sample (the within-limit solutions), then
/// one continuous branch through them.
fn commands(
    cfg: &ConeFrustumConfig,
    chain: &Chain,
    machine: &Machine,
    geo: &Geometry,
    s: &Sampling,
) -> Result<Commands, ConeFrustumError> {
    let limits = limits_from_degrees(&machine.limits);
    let ik = crate::kinematics::inverse::Inverse::new(chain, cfg.tool_length)?;
    let total = s.lead + s.n;
    let mut points = Vec::with_capacity(total);
    let mut candidates: Vec<Vec<[f64; 6]>> = Vec::with_capacity(total);
    for i in 0..total {
        let phi = s.phi(i);
        let pt = geo.point(phi);
        let pose = Pose {
            position: pt.tip.into(),
            orientation: pt.axis.into(),
        };
        let sols = ik.solve(&pose, &limits)?;
        let inside: Vec<[f64; 6]> = sols
            .iter()
            .filter(|s| s.within_limits)
            .map(|s| s.q)
            .collect();
        if inside.is_empty() {
            return Err(out_of_limits(&sols, &limits, phi));
        }
        candidates.push(inside);
        points.push(pt);
    }
    let q = continuous_commands(&candidates, |i| s.phi(i).to_degrees())?;
    Ok(Commands { points, q })
}

/// Each present axis' drive (servo model, or ideal) following its command,
/// with the configuration's drive errors (backlash, pitch error): the actual axis
/// positions of every sample and the per-axis series of the measured part.
fn drive_axes(
    cfg: &ConeFrustumConfig,
    machine: &Machine,
    q_cmd: &[[f64; 6]],
    present: &[usize],
    s: &Sampling,
) -> Result<(Vec<[f64; 6]>, Vec<AxisSeries>), ConeFrustumError> {
    let mut q_act = q_cmd.to_vec();
    let mut series = Vec::new();
    for &k in present {
        let letter = AXES[k];
        let kind = if k < 3 {
            AxisKind::Linear
        } else {
            AxisKind::Rotary
        };
        let params = match machine.axes.get(letter) {
            Some(p) => p.clone(),
            None if cfg.ideal_servo => placeholder_axis(kind),
            None => {
                return Err(ConeFrustumError::Servo {
                    axis: letter.to_uppercase(),
                    why: format!("machine '{}' has no feed-drive parameters for this axis; add axes.{letter} or set idealServo: true", machine.name),
                })
            }
        };
        let params = cfg.drives.applied_to(letter, params);
        let cmd: Vec<f64> = q_cmd.iter().map(|q| q[k]).collect();
        let act = if cfg.ideal_servo {
            drive::ideal(&params, &cmd)
        } else {
            drive::servo(&params, s.dt, &cmd)
        }
        .map_err(|e| ConeFrustumError::Servo {
            axis: letter.to_uppercase(),
            why: e.to_string(),
        })?;
        for (q, a) in q_act.iter_mut().zip(&act) {
            q[k] = *a;
        }
        series.push(AxisSeries {
            axis: letter.to_string(),
            kind,
            command: cmd[s.lead..].to_vec(),
            actual: act[s.lead..].to_vec(),
        });
    }
    Ok((q_act, series))
}

/// What the bar reads over the measured revolution, with the sensitivities.
struct BarReadings {
    angle_deg: Vec<f64>,
    time: Vec<f64>,
    deviation: Vec<f64>,
    path: [Vec<f64>; 3],
    axis_sens: Vec<Vec<f64>>,
    symbols: Vec<String>,
    err_sens: Vec<Vec<f64>>,
}

/// The bar-length change of each measured sample (forward kinematics with
/// the errors at the actual axis positions), the nominal path, and the
/// sensitivities to each axis and each location error at the command.
fn bar_readings(
    cfg: &ConeFrustumConfig,
    chain: &Chain,
    geo: &Geometry,
    cmd: &Commands,
    q_act: &[[f64; 6]],
    present: &[usize],
    s: &Sampling,
) -> Result<BarReadings, ConeFrustumError> {
    let n = s.n;
    let model = Model::new(chain, &cfg.errors, cfg.tool_length)?;
    let nominal = Model::new(chain, &GeometricErrors::default(), cfg.tool_length)?;
    let symbols = if cfg.sensitivities {
        crate::kinematics::errors::error_symbols(chain)
    } else {
        Vec::new()
    };
    let sens_axes: &[usize] = if cfg.sensitivities { present } else { &[] };
    let perturbed = symbols
        .iter()
        .map(|e| sensitivity::perturbed(chain, &GeometricErrors::default(), cfg.tool_length, e))
        .collect::<Result<Vec<_>, _>>()?;
    let mut r = BarReadings {
        angle_deg: Vec::with_capacity(n),
        time: Vec::with_capacity(n),
        deviation: Vec::with_capacity(n),
        path: [
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        ],
        axis_sens: vec![Vec::with_capacity(n); sens_axes.len()],
        err_sens: vec![Vec::with_capacity(n); symbols.len()],
        symbols,
    };
    let measured = q_act[s.lead..]
        .iter()
        .zip(&cmd.q[s.lead..])
        .zip(&cmd.points[s.lead..]);
    for (k, ((qa, qc), pt)) in measured.enumerate() {
        let (p, _) = model.eval(qa);
        r.deviation.push((p - geo.centre).norm() - geo.bar_length);
        for (c, v) in r.path.iter_mut().zip(pt.tip.iter()) {
            c.push(*v);
        }
        if cfg.sensitivities {
            for (a, v) in r
                .axis_sens
                .iter_mut()
                .zip(sensitivity::axes(&nominal, qc, &pt.bar, sens_axes))
            {
                a.push(v);
            }
        }
        for (e, m) in r.err_sens.iter_mut().zip(&perturbed) {
            e.push(sensitivity::error(m, qc, &pt.bar));
        }
        let j = k as f64;
        r.angle_deg.push(360.0 * j / n as f64);
        r.time.push(j * s.dt);
    }
    Ok(r)
}

/// The chain of a machine reference (for callers that need it).
pub fn chain_of(m: &MachineRef) -> Result<Chain, ConeFrustumError> {
    Ok(m.resolve()?.1)
}

/// Largest change of a rotary axis between two samples that still counts
/// as continuous motion, rad (10°; the test's own steps are ~0.1°).
pub const MAX_ROTARY_STEP: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// Follows the nearest branch from each possible start (smallest rotary
/// angles first) and returns the first continuous command sequence.
fn continuous_commands(
    candidates: &[Vec<[f64; 6]>],
    angle_deg: impl Fn(usize) -> f64,
) -> Result<Vec<[f64; 6]>, ConeFrustumError> {
    let nearest = |prev: &[f64; 6], options: &[[f64; 6]]| -> [f64; 6] {
        let d = |q: &[f64; 6]| {
            (0..6)
                .map(|k| ((q[k] - prev[k]) * if k >= 3 { 1000.0 } else { 1.0 }).powi(2))
                .sum::<f64>()
        };
        *options
            .iter()
            .min_by(|a, b| d(a).total_cmp(&d(b)))
            .unwrap_or(prev)
    };
    let mut starts = candidates.first().cloned().unwrap_or_default();
    let rot = |q: &[f64; 6]| q[3..].iter().map(|v| v.abs()).sum::<f64>();
    starts.sort_by(|a, b| rot(a).total_cmp(&rot(b)));
    let mut first_jump: Option<(usize, usize, f64)> = None;
    'start: for start in starts {
        let mut q = Vec::with_capacity(candidates.len());
        q.push(start);
        for (i, options) in candidates.iter().enumerate().skip(1) {
            let prev = q[i - 1];
            let next = nearest(&prev, options);
            if let Some((k, jump)) = (3..6)
                .map(|k| (k, (next[k] - prev[k]).abs()))
                .filter(|(_, j)| *j > MAX_ROTARY_STEP)
                .max_by(|a, b| a.1.total_cmp(&b.1))
            {
                if first_jump.is_none() {
                    first_jump = Some((i, k, jump));
                }
                continue 'start;
            }
            q.push(next);
        }
        return Ok(q);
    }
    let (i, k, jump) = first_jump.unwrap_or((0, 3, 0.0));
    Err(ConeFrustumError::BranchJump {
        axis: AXES[k].to_uppercase(),
        jump_deg: jump.to_degrees(),
        angle_deg: angle_deg(i),
    })
}

/// The error for a point no solution reaches: names the worst axis of the
/// branch that misses the limits least.
fn out_of_limits(
    sols: &[crate::kinematics::Solution],
    limits: &[[f64; 2]; 6],
    phi: f64,
) -> ConeFrustumError {
    let excess = |q: &[f64; 6]| {
        (0..6)
            .map(|k| (k, (limits[k][0] - q[k]).max(q[k] - limits[k][1])))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0, 0.0))
    };
    let s = sols
        .iter()
        .map(|s| s.q)
        .min_by(|a, b| excess(a).1.total_cmp(&excess(b).1))
        .unwrap_or([0.0; 6]);
    let (k, _) = excess(&s);
    let scale = if k >= 3 {
        180.0 / std::f64::consts::PI
    } else {
        1.0
    };
    ConeFrustumError::OutOfLimits {
        axis: AXES[k].to_uppercase(),
        value: s[k] * scale,
        angle_deg: phi.to_degrees(),
        min: limits[k][0] * scale,
        max: limits[k][1] * scale,
    }
}
