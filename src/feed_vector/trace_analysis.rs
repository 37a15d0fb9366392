//! Analysis of a measured constant-feed-speed-vector trace
//! (suzuki-best-kffp §4.1, Fig. 7: SERVO GUIDE samples X, Y in mm and C in
//! degrees every 1 ms).
//!
//! The trace is read by the core's tolerant reader
//! ([`crate::trace::read_table`]: any delimiter, decimal commas, quoted
//! numbers, text columns ignored, metadata above the header, headerless
//! with a sample period). Columns are found by name (aliases below, or the
//! names in [`ColumnMap`]) and scaled to core units: by the unit their
//! header states (`Time [ms]` is ms, `POS X(um)` µm, `TCMD C(%)` % of
//! `ratedTorque`), else by the mapping's factors; `headerUnits: false`
//! makes the mapping's factors apply to every column (the page, whose
//! menus the header's units fill). Before the analysis the trace must be
//! plausible ([`super::trace_plausibility`]): C turning at about ω and
//! X/Y on a circle. The commanded angle θ(t) that
//! Eqs. 8–9 need is rebuilt from the condition (ω, accel time), with t = 0
//! at `motionStart` (default: the first sample). Positions are machine
//! positions with the circle centre at the origin; with `relative: true`
//! they are displacements from the start point (R_W, 0, 0), as SERVO GUIDE
//! records them, and the start point is added back.
//!
//! # Units
//! After scaling: s, mm, rad, N·m.

use serde::{Deserialize, Serialize};

use super::analysis::{derive, summarize, Series};
use super::{command, Condition, FeedVectorError, FeedVectorResult};
use crate::numeric::compact;
use crate::trace::units::Quantity;
use crate::trace::{read_table, ReadOptions, TableRead};

/// Column names and units of a trace (the JS `mapping`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct ColumnMap {
    /// Time column (default aliases: time, t, zeit; generated from
    /// `samplePeriod` for a headerless file).
    pub time: Option<String>,
    /// X column (x, pos_x).
    pub x: Option<String>,
    /// Y column (y, pos_y).
    pub y: Option<String>,
    /// C column (c, pos_c).
    pub c: Option<String>,
    /// Torque column (torque, tcmd, torque_c, tcmd_c, tq); optional.
    pub torque: Option<String>,
    /// Seconds per time unit (1e-3 for ms) of a time column whose header
    /// states no unit. Default 1.
    pub time_scale: f64,
    /// mm per linear unit (1e-3 for µm). Default 1.
    pub linear_scale: f64,
    /// rad per angle unit. Default π/180 (degrees, as SERVO GUIDE).
    pub angle_scale: f64,
    /// N·m per torque unit. Default 1.
    pub torque_scale: f64,
    /// Time of the start of the commanded motion, s (default: first sample).
    pub motion_start: Option<f64>,
    /// Positions are displacements from the start point.
    pub relative: bool,
    /// The unit a header states scales its column (default true); false:
    /// the factors above scale every column.
    pub header_units: bool,
    /// Rated torque, N·m: reads a torque column in `%`.
    pub rated_torque: Option<f64>,
    /// Sample period, s, of a file without a time column.
    pub sample_period: Option<f64>,
    /// Start of the steady-state window after the motion start, s
    /// (default `accelTime + 0.4 s`).
    pub steady_from: Option<f64>,
}

impl Default for ColumnMap {
    fn default() -> Self {
        Self {
            time: None,
            x: None,
            y: None,
            c: None,
            torque: None,
            time_scale: 1.0,
            linear_scale: 1.0,
            angle_scale: std::f64::consts::PI / 180.0,
            torque_scale: 1.0,
            motion_start: None,
            relative: false,
            header_units: true,
            rated_torque: None,
            sample_period: None,
            steady_from: None,
        }
    }
}

/// The physical range of one column after scaling: |value| ≤ `max`.
struct Range {
    /// Largest magnitude, in `unit`.
    max: f64,
    /// Core unit after scaling.
    unit: &'static str,
    /// The mapping field whose unit factor scales the column.
    scale: &'static str,
    /// What the column measures.
    quantity: Quantity,
}

/// Times: |t| ≤ 1e7 s (116 days of recording).
const TIME: Range = Range {
    max: 1e7,
    unit: "s",
    scale: "mapping.timeScale",
    quantity: Quantity::Time,
};
/// X, Y: |x| ≤ 1e5 mm (100 m, beyond any machine's stroke).
const LINEAR: Range = Range {
    max: 1e5,
    unit: "mm",
    scale: "mapping.linearScale",
    quantity: Quantity::Length,
};
/// C: |c| ≤ 1e6 rad (160,000 turns).
const ANGLE: Range = Range {
    max: 1e6,
    unit: "rad",
    scale: "mapping.angleScale",
    quantity: Quantity::Angle,
};
/// Torque: |τ| ≤ 1e7 N·m.
const TORQUE: Range = Range {
    max: 1e7,
    unit: "N·m",
    scale: "mapping.torqueScale",
    quantity: Quantity::Torque,
};

/// Shortest sample interval, s: 0.1 µs (SERVO GUIDE samples every 1 ms;
/// a shorter step is a wrong time unit, and differences of positions over
/// it would lose every digit).
pub const MIN_STEP: f64 = 1e-7;

/// The 0-based index (in the table) and scaled values of a column, each
/// finite and inside `range`: scaled by the unit its header states
/// (`map.header_units`), else by `scale`.
fn column(
    read: &TableRead,
    map: &ColumnMap,
    name: &Option<String>,
    aliases: &[&str],
    scale: f64,
    range: &Range,
) -> Result<(usize, Vec<f64>), FeedVectorError> {
    let table = &read.table;
    let names: Vec<&str> = match name {
        Some(n) => vec![n.as_str()],
        None => aliases.to_vec(),
    };
    table.column(&names, 1.0)?;
    let index = table.find(&names).unwrap_or(0);
    let scale = column_scale(read, map, index, scale, range)?;
    let values: Vec<f64> = table.columns[index].iter().map(|v| v * scale).collect();
    let at = |i: usize, why: String| value_error(read, index, i, why);
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(at(i, format!("'{}' is not a finite number", values[i])));
    }
    if let Some(i) = values.iter().position(|v| v.abs() > range.max) {
        return Err(at(
            i,
            format!(
                "{} {} (after scaling) is outside ±{:e} {}; check the column's unit and {}",
                compact(values[i]),
                range.unit,
                range.max,
                range.unit,
                range.scale
            ),
        ));
    }
    Ok((index, values))
}

/// The factor of table column `index` for a column of `range`'s quantity:
/// the header's unit (a `%` torque needs `mapping.ratedTorque`, whatever
/// `headerUnits`), else the mapping's `scale`.
fn column_scale(
    read: &TableRead,
    map: &ColumnMap,
    index: usize,
    scale: f64,
    range: &Range,
) -> Result<f64, FeedVectorError> {
    let Some(info) = read.info(index) else {
        return Ok(scale);
    };
    let line = read
        .layout
        .header_line
        .unwrap_or(read.layout.first_data_line);
    let refuse = |why: String| FeedVectorError::TraceValue {
        line,
        column: info.field,
        name: info.name.clone(),
        why,
    };
    if info.unit == Some("%") {
        return info.factor.ok_or_else(|| {
            refuse("the torque is in % of the rated torque; give mapping.ratedTorque (the motor's rated torque in N·m), or map a torque column in N·m".into())
        });
    }
    match (map.header_units, info.quantity, info.factor) {
        (true, Some(q), Some(f)) if q == range.quantity => Ok(f),
        (true, Some(q), Some(_)) => Err(refuse(format!(
            "the header states '{}', a unit of {}, but this column is read as the {} column (in {}); map the right column",
            info.unit.unwrap_or(""),
            q.core_unit(),
            match range.quantity {
                Quantity::Time => "time",
                Quantity::Length => "X or Y",
                Quantity::Angle => "C",
                _ => "torque",
            },
            range.unit
        ))),
        _ => Ok(scale),
    }
}

/// The error for the value of table column `col` (0-based) in data row
/// `row`, located at its line and named by its header (field in the file).
fn value_error(read: &TableRead, col: usize, row: usize, why: String) -> FeedVectorError {
    let table = &read.table;
    FeedVectorError::TraceValue {
        line: table.lines.get(row).copied().unwrap_or(0),
        column: read.info(col).map_or(col + 1, |c| c.field),
        name: table.names.get(col).cloned().unwrap_or_default(),
        why,
    }
}

/// The names the time column is found by when the mapping leaves it out
/// (case-insensitive; a unit suffix ignored).
pub const TIME_NAMES: [&str; 4] = ["time", "t", "time_s", "zeit"];
/// The names of the X column.
pub const X_NAMES: [&str; 3] = ["x", "pos_x", "x_pos"];
/// The names of the Y column.
pub const Y_NAMES: [&str; 3] = ["y", "pos_y", "y_pos"];
/// The names of the C column.
pub const C_NAMES: [&str; 3] = ["c", "pos_c", "c_pos"];
/// The names of the (optional) torque column.
pub const TORQUE_NAMES: [&str; 5] = ["torque", "tcmd", "torque_c", "tcmd_c", "tq"];

/// Marks in `read`'s layout the columns this analysis reads as time, X,
/// Y, C and torque when the mapping leaves them out (the page's default
/// column menus come from these roles).
///
/// # Examples
/// ```
/// use mtmotion::feed_vector::trace_analysis::roles;
/// use mtmotion::trace::{read_table, ReadOptions};
/// let mut r = read_table("Zeit [ms];POS X(um);Y;C [deg];Note\n0;1;2;3;a\n", &ReadOptions::default()).unwrap();
/// roles(&mut r);
/// let got: Vec<_> = r.layout.columns.iter().map(|c| c.role).collect();
/// assert_eq!(got, [Some("time"), Some("x"), Some("y"), Some("c"), None]);
/// ```
pub fn roles(read: &mut TableRead) {
    read.mark_roles(&[
        ("time", &TIME_NAMES),
        ("x", &X_NAMES),
        ("y", &Y_NAMES),
        ("c", &C_NAMES),
        ("torque", &TORQUE_NAMES),
    ]);
}

/// Smallest |unit factor| of a mapping (ns → s is 1e-9).
pub const MIN_SCALE: f64 = 1e-9;
/// Largest |unit factor| of a mapping (km → mm is 1e6); a larger one
/// makes times or positions overflow.
pub const MAX_SCALE: f64 = 1e6;

/// Analyses a measured trace (the JS `analyzeFeedVectorTrace`).
///
/// # Units
/// The condition as in [`Condition`]; trace units as set in `map`.
///
/// # Examples
/// ```
/// use mtmotion::feed_vector::{trace_analysis::{analyze_trace, ColumnMap}, Condition};
/// let cond = Condition::paper(1.0);
/// let text = "time,x,y,c\n0,8,0,0\n0.001,8,0.001,0.0573\n0.002,8,0.002,0.1146\n";
/// let whole = ColumnMap { steady_from: Some(0.0), ..ColumnMap::default() };
/// let r = analyze_trace(text, &cond, &whole).unwrap();
/// assert_eq!(r.series.t.len(), 3);
/// // 2 ms of trace hold no sample of the default steady window (0.464 s on)
/// let e = analyze_trace(text, &cond, &ColumnMap::default()).unwrap_err();
/// assert!(e.to_string().contains("at least 2 are needed"));
/// let e = analyze_trace("time,x,y,c\n0,8,0,0\n0.001,8,oops,0\n", &cond, &ColumnMap::default());
/// assert!(e.unwrap_err().to_string().starts_with("line 3, column 3"));
/// ```
pub fn analyze_trace(
    text: &str,
    cond: &Condition,
    map: &ColumnMap,
) -> Result<FeedVectorResult, FeedVectorError> {
    crate::budget::check_text("trace", text)?;
    analyze_with(cond, map, |o| read_table(text, o))
}

/// Analyses a measured trace given as bytes (the JS
/// `analyzeFeedVectorTrace` with a `Uint8Array`): a MATLAB v5 `.mat`
/// capture ([`crate::trace::mat`]), or text as in [`analyze_trace`].
///
/// # Units
/// As [`analyze_trace`].
pub fn analyze_trace_bytes(
    bytes: &[u8],
    cond: &Condition,
    map: &ColumnMap,
) -> Result<FeedVectorResult, FeedVectorError> {
    if !crate::trace::mat::is_mat(bytes) {
        return analyze_trace(&String::from_utf8_lossy(bytes), cond, map);
    }
    crate::budget::check_bytes("trace", bytes.len() as u64)?;
    analyze_with(cond, map, |o| crate::trace::read_bytes(bytes, o))
}

/// The analysis of the table `read` gives with the map's read options.
fn analyze_with(
    cond: &Condition,
    map: &ColumnMap,
    read: impl FnOnce(&ReadOptions) -> Result<TableRead, crate::trace::TraceError>,
) -> Result<FeedVectorResult, FeedVectorError> {
    cond.validate()?;
    validate_map(map)?;
    let opts = ReadOptions {
        sample_period: map.sample_period,
        rated_torque: map.rated_torque,
    };
    let read = read(&opts)?;
    let t = time_column(&read, map)?;
    let (_, mut x) = column(&read, map, &map.x, &X_NAMES, map.linear_scale, &LINEAR)?;
    let (_, y) = column(&read, map, &map.y, &Y_NAMES, map.linear_scale, &LINEAR)?;
    let (ci, c) = column(&read, map, &map.c, &C_NAMES, map.angle_scale, &ANGLE)?;
    let torque = if map.torque.is_some() || read.table.find(&TORQUE_NAMES).is_some() {
        column(
            &read,
            map,
            &map.torque,
            &TORQUE_NAMES,
            map.torque_scale,
            &TORQUE,
        )?
        .1
    } else {
        Vec::new()
    };
    if map.relative {
        x.iter_mut().for_each(|v| *v += cond.rw);
    }
    let t0 = map.motion_start.unwrap_or(t[0]);
    let tt: Vec<f64> = t.iter().map(|v| v - t0).collect();
    let theta: Vec<f64> = tt
        .iter()
        .map(|&t| command::angle(t, cond.omega, cond.accel_time))
        .collect();
    let saturated = match (cond.torque_max, torque.is_empty()) {
        (Some(limit), false) => torque.iter().any(|v| v.abs() >= limit),
        _ => false,
    };
    let mut series = Series {
        x_cmd: theta.iter().map(|th| cond.rw * th.cos()).collect(),
        y_cmd: theta.iter().map(|th| cond.rw * th.sin()).collect(),
        c_cmd: theta,
        t: tt,
        x,
        y,
        c,
        torque_c: torque,
        ..Series::default()
    };
    derive(&mut series, cond.rw, cond.rc);
    // the trace's own steady window: same rule as the simulation, from the
    // machine-independent part (accel time + 0.4 s)
    let t_ss = map.steady_from.unwrap_or(cond.accel_time + 0.4);
    steady_window_holds_samples(&series.t, t_ss, map.steady_from.is_some())?;
    let c_name = read.table.names.get(ci).cloned().unwrap_or_default();
    super::trace_plausibility::check(&series, cond, t_ss, &read.table.lines, &c_name)?;
    let summary = summarize(&series, cond.omega, t_ss, saturated);
    Ok(FeedVectorResult { series, summary })
}

/// Checks the mapping's unit factors and times.
fn validate_map(map: &ColumnMap) -> Result<(), FeedVectorError> {
    for (field, v) in [
        ("mapping.timeScale", map.time_scale),
        ("mapping.linearScale", map.linear_scale),
        ("mapping.angleScale", map.angle_scale),
        ("mapping.torqueScale", map.torque_scale),
    ] {
        if !(v.is_finite() && (MIN_SCALE..=MAX_SCALE).contains(&v.abs())) {
            return Err(super::bad(
                field,
                v,
                "must be a unit factor of magnitude 1e-9 to 1e6 (e.g. 0.001 for ms, 25.4 for inch)",
            ));
        }
    }
    for (field, v) in [
        ("mapping.motionStart", map.motion_start),
        ("mapping.steadyFrom", map.steady_from),
    ] {
        if let Some(v) = v.filter(|v| !(v.is_finite() && v.abs() <= TIME.max)) {
            return Err(super::bad(field, v, "must be a time in s within ±1e7 s"));
        }
    }
    Ok(())
}

/// The steady window (times from `t_ss` after the motion start on) must
/// hold two samples or more: an empty one would give a summary of zeros.
fn steady_window_holds_samples(tt: &[f64], t_ss: f64, given: bool) -> Result<(), FeedVectorError> {
    let inside = tt.len() - tt.partition_point(|&t| t < t_ss);
    if inside >= 2 {
        return Ok(());
    }
    let end = tt.last().copied().unwrap_or(0.0);
    let rule = if given {
        "mapping.steadyFrom"
    } else {
        "accel time + 0.4 s, the default of mapping.steadyFrom"
    };
    Err(super::bad(
        "mapping.steadyFrom",
        t_ss,
        &format!(
            "the steady window starts {} s after the motion start ({rule}), but the trace ends {} s after it and the window holds {inside} sample(s), at least 2 are needed: record a longer trace, or set mapping.steadyFrom or mapping.motionStart",
            compact(t_ss),
            compact(end)
        ),
    ))
}

/// The time column in s, which must increase strictly from row to row.
fn time_column(read: &TableRead, map: &ColumnMap) -> Result<Vec<f64>, FeedVectorError> {
    let (tcol, t) = column(read, map, &map.time, &TIME_NAMES, map.time_scale, &TIME)?;
    for i in 1..t.len() {
        let (now, before) = (t[i], t[i - 1]);
        if now - before >= MIN_STEP {
            continue;
        }
        let (now_s, before_s) = (compact(now), compact(before));
        let why = if now > before {
            format!(
                "time {now_s} s is {} s after the line before, less than the shortest sample interval of {MIN_STEP:e} s; check the time unit (mapping.timeScale)",
                compact(now - before)
            )
        } else {
            format!("time {now_s} does not increase after {before_s} on the line before; sort the trace or pick the right time column")
        };
        return Err(value_error(read, tcol, i, why));
    }
    Ok(t)
}
