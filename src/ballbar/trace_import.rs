//! Ball-bar trace import: CSV/TSV (any delimiter [`crate::trace::Table`]
//! reads) holding either the axis angle and the radial deviation, or X/Y
//! positions; split into runs by direction of travel (CCW/CW).
//!
//! Source: the trace formats of ball-bar software (Renishaw QC20 exports
//! angle + deviation; controls export X/Y positions) as used for the
//! ISO 230-4 circular test and for takayama-alignment-travel-range §3.1.2.
//!
//! Readings chosen (no standard file format exists):
//! - columns, case-insensitive, unit suffix in brackets allowed:
//!   angle `angle`/`theta` (+ `_deg`/`_rad`; degrees unless the name
//!   says `rad`); deviation `deviation`/`dev`/`dr`/`radial`/`error`
//!   (+ `_um`/`_mm`; **µm unless the name says mm**, as ball-bar software
//!   reports µm); or `x`, `y` (mm unless the name says um); optional `time`
//!   /`t` (s, or ms if the name says ms) and `direction`/`dir` (+1 = CCW,
//!   −1 = CW);
//! - angle θ = 0 along +X, growing towards +Y (CCW seen from +Z);
//! - X/Y traces stay in machine coordinates: the deviation is taken about
//!   the centre the options give (the ball bar's pivot, or the programmed
//!   circle centre), never re-fitted, so a set-up or rotary-axis offset
//!   stays in the trace; without one, about the least-squares circle centre
//!   of all points (which removes any offset: the trace says which, in
//!   [`BallbarTrace::centre`]); the nominal radius is the given one, else
//!   the least-squares radius;
//! - angle/deviation traces: the nominal radius is 100 mm (the common bar
//!   length) unless given; it only enters at second order (Δ²/R);
//! - runs: without a direction column, the trace is split where the angle
//!   turns back by more than 1° from its running extreme (so noise at a
//!   standstill does not split it); angles are unwrapped across ±180°;
//! - trimming ([`super::trim`], on unless the options turn it off): each
//!   run keeps its constant-feed part; an X/Y trace without a given centre
//!   is then re-read about the least-squares centre of the kept samples;
//! - feed: from the options, else the median plateau speed × R from the
//!   time column (R: the least-squares radius of an X/Y trace, the nominal
//!   radius of an angle/deviation one), else unknown (no time column: the sample index is the
//!   time, and the trace warns);
//! - unit plausibility (warnings, not errors): a deviation above 1 % of
//!   the radius, or deviations spanning less than 0.1 µm (a ball bar's
//!   resolution), ask whether the column is in mm or µm.
//!
//! Units: the returned trace is in core units: angle rad, deviation and
//! radius mm, feed mm/min.

use serde::{Deserialize, Serialize};

use super::fit_circle;
use super::trim::{trim, Segment, TimeBase, Trimming};
use crate::trace::{read_table, ReadOptions, Table, TraceError};

/// Errors of ball-bar trace import.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BallbarTraceError {
    /// The table itself is malformed (names line and column).
    #[error(transparent)]
    Table(#[from] TraceError),
    /// The text is over a work budget ([`crate::budget`]).
    #[error(transparent)]
    Budget(#[from] crate::budget::BudgetError),
    /// The text is empty.
    #[error("the trace is empty: expected a header line such as 'angle_deg,deviation_um' (or 'x,y') and data rows")]
    Empty,
    /// The first line is already data.
    #[error("line {line}: expected a header line naming the columns (e.g. 'angle_deg,deviation_um' or 'x,y') before the data")]
    NoHeader {
        /// Line of the first data row.
        line: usize,
    },
    /// Neither angle+deviation nor X/Y columns.
    #[error("no ball-bar columns found: expected 'angle' and 'deviation' (or 'x' and 'y') in the header, found: {}", crate::budget::clip(.0, 200))]
    NoColumns(String),
    /// A column the mapping names is not in the file.
    #[error("columns.{field}: no column named '{name}' in the file (columns: {available})")]
    MappedColumn {
        /// The mapping's field (`x`, `y`, `angle`, `deviation`, `time`, `direction`).
        field: &'static str,
        /// The name it gives.
        name: String,
        /// The file's numeric columns.
        available: String,
    },
    /// A point lies at the nominal centre, so it has no angle.
    #[error("line {0}: the point lies at the nominal centre, so its angle is undefined")]
    AtCentre(usize),
    /// A direction value other than ±1.
    #[error("line {line}: direction must be +1 (CCW) or -1 (CW), got {value}")]
    BadDirection {
        /// 1-based line.
        line: usize,
        /// The value.
        value: f64,
    },
    /// No run long enough.
    #[error("line {line}: the trace has no run of at least {min} points in one direction")]
    TooShort {
        /// Line of the first data row.
        line: usize,
        /// Minimum points per run.
        min: usize,
    },
    /// The time column does not increase.
    #[error("line {line}, column {column} ('{}'): the time must increase from one row to the next; sort the rows by time or remove the repeated ones", crate::budget::clip(name, 40))]
    TimeNotIncreasing {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// Its header.
        name: String,
    },
    /// A bad option value.
    #[error("{field}: {message}")]
    BadOption {
        /// Option name.
        field: &'static str,
        /// What was expected.
        message: String,
    },
}

/// Direction of travel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// Counter-clockwise, angle increasing.
    Ccw,
    /// Clockwise, angle decreasing.
    Cw,
}

impl Direction {
    /// +1 for CCW, −1 for CW.
    pub fn sign(self) -> f64 {
        match self {
            Direction::Ccw => 1.0,
            Direction::Cw => -1.0,
        }
    }
}

/// One run in one direction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Run {
    /// Direction of travel.
    pub direction: Direction,
    /// Unwrapped angle, rad.
    pub angle: Vec<f64>,
    /// Radial deviation from the nominal radius, mm.
    pub deviation: Vec<f64>,
    /// Source line of each sample (empty for synthetic traces).
    #[serde(default)]
    pub lines: Vec<usize>,
}

/// A point of the trace's plane (X/Y positions), mm.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct PlanePoint {
    /// First plane axis (X), mm.
    pub x: f64,
    /// Second plane axis (Y), mm.
    pub y: f64,
}

/// The centre an X/Y trace's angles and deviations are taken about.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct TraceCentre {
    /// The centre, in the trace's X/Y coordinates, mm.
    pub point: PlanePoint,
    /// True when the options gave it (pivot or programmed centre); false
    /// when it is the least-squares centre of the trace itself, which
    /// removes any centre offset from the deviations.
    pub given: bool,
}

/// A ball-bar trace in core units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct BallbarTrace {
    /// Nominal radius (bar length), mm.
    pub nominal_radius: f64,
    /// Feed, mm/min, if known.
    pub feed: Option<f64>,
    /// Runs in file order.
    pub runs: Vec<Run>,
    /// For an X/Y trace, the centre its deviations are about; None for an
    /// angle/deviation trace (a ball bar measures about its own pivot).
    #[serde(default)]
    pub centre: Option<TraceCentre>,
    /// What was trimmed ([`super::trim`]); None for traces not read from
    /// a file.
    #[serde(default)]
    pub trimming: Option<Trimming>,
    /// Warnings about the file (units, time base), each naming the column
    /// and what to do.
    #[serde(default)]
    pub warnings: Vec<String>,
}

/// Options of [`parse_ballbar_trace`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct ParseOptions {
    /// Nominal radius, mm.
    pub nominal_radius: Option<f64>,
    /// Feed, mm/min.
    pub feed: Option<f64>,
    /// For X/Y traces: the centre to take the deviations about (the pivot
    /// or the programmed circle centre), mm in the trace's coordinates.
    pub centre: Option<PlanePoint>,
    /// Trim each run to its constant-feed part ([`super::trim`]); false
    /// keeps every sample (the stretches are still listed).
    pub trim: bool,
    /// Which column is which, for a file whose columns are named
    /// otherwise (`EncoderX_Pos`); default: found by their usual names.
    pub columns: BallbarColumns,
}

impl Default for ParseOptions {
    fn default() -> Self {
        Self {
            nominal_radius: None,
            feed: None,
            centre: None,
            trim: true,
            columns: BallbarColumns::default(),
        }
    }
}

/// Which column of the file is which (the JS `options.columns`): each
/// names a column as its header writes it (`EncoderX_Pos`), or as the
/// column finder matches it (case-insensitive, a unit suffix ignored).
/// A field left out is found by its usual names (see the module's
/// readings). Mapping `x` or `y` reads the file as X/Y positions.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct BallbarColumns {
    /// X position column (mm; µm if the name says `um`).
    pub x: Option<String>,
    /// Y position column.
    pub y: Option<String>,
    /// Angle column (degrees; rad if the name says `rad`).
    pub angle: Option<String>,
    /// Radial deviation column (µm; mm if the name says `mm`).
    pub deviation: Option<String>,
    /// Time column (s; ms if the name says `ms`).
    pub time: Option<String>,
    /// Direction column (+1 CCW, −1 CW).
    pub direction: Option<String>,
}

/// The names the angle column is found by when the mapping leaves it out
/// (case-insensitive; a unit suffix ignored).
pub const ANGLE_NAMES: [&str; 7] = [
    "angle",
    "theta",
    "angle_deg",
    "angle_rad",
    "theta_deg",
    "theta_rad",
    "ang",
];
/// The names of the radial deviation column.
pub const DEVIATION_NAMES: [&str; 10] = [
    "deviation",
    "dev",
    "dr",
    "radial",
    "error",
    "deviation_um",
    "dev_um",
    "deviation_mm",
    "dev_mm",
    "radial_deviation",
];
/// The names of the X column.
pub const X_NAMES: [&str; 4] = ["x", "pos_x", "x_mm", "x_um"];
/// The names of the Y column.
pub const Y_NAMES: [&str; 4] = ["y", "pos_y", "y_mm", "y_um"];
/// The names of the time column.
pub const TIME_NAMES: [&str; 4] = ["time", "t", "time_s", "time_ms"];
/// The names of the direction column.
pub const DIRECTION_NAMES: [&str; 2] = ["direction", "dir"];

/// Marks in `read`'s layout the columns the ball-bar import reads as
/// angle, deviation, X, Y, time and direction when the mapping leaves
/// them out (the page's default column menus come from these roles).
///
/// # Examples
/// ```
/// use mtmotion::ballbar::trace_import::roles;
/// use mtmotion::trace::{read_table, ReadOptions};
/// let mut r = read_table("Angle(deg)\tDeviation(um)\tEncoderX\n0\t1\t2\n", &ReadOptions::default()).unwrap();
/// roles(&mut r);
/// let got: Vec<_> = r.layout.columns.iter().map(|c| c.role).collect();
/// assert_eq!(got, [Some("angle"), Some("deviation"), None]);
/// ```
pub fn roles(read: &mut crate::trace::TableRead) {
    read.mark_roles(&[
        ("angle", &ANGLE_NAMES),
        ("deviation", &DEVIATION_NAMES),
        ("x", &X_NAMES),
        ("y", &Y_NAMES),
        ("time", &TIME_NAMES),
        ("direction", &DIRECTION_NAMES),
    ]);
}

/// The column the mapping gives for `field`, else the first alias found.
fn pick(
    t: &Table,
    mapped: &Option<String>,
    field: &'static str,
    aliases: &[&str],
) -> Result<Option<usize>, BallbarTraceError> {
    match mapped {
        Some(name) => {
            t.find(&[name.as_str()])
                .map(Some)
                .ok_or_else(|| BallbarTraceError::MappedColumn {
                    field,
                    name: name.clone(),
                    available: t.names.join(", "),
                })
        }
        None => Ok(t.find(aliases)),
    }
}

/// Minimum samples per run.
pub const MIN_RUN: usize = 8;

fn header_says(t: &Table, k: usize, what: &[&str]) -> bool {
    let n = t.names[k].to_ascii_lowercase().replace('µ', "u");
    what.iter().any(|w| n.contains(w))
}

/// Reads a ball-bar trace.
///
/// The file is read by the core's tolerant reader
/// ([`crate::trace::read_table`]): any delimiter, decimal commas, quoted
/// numbers, text columns (ignored), metadata above the header, and the
/// controls' layouts it recognises (TwinCAT Scope, SINUMERIK trace XML,
/// halscope). [`ParseOptions::columns`] names the columns of a file that
/// names them otherwise (`EncoderX_Pos, EncoderY_Pos`).
///
/// # Units
/// See the module header; the result is in rad, mm and mm/min.
///
/// # Errors
/// [`BallbarTraceError`], naming the line wherever a line is at fault.
///
/// # Examples
/// ```
/// use mtmotion::ballbar::{parse_ballbar_trace, Direction, ParseOptions};
/// let mut text = String::from("angle [deg],deviation [um]\n");
/// for i in 0..=36 { text += &format!("{},{}\n", i * 10, 2.0); }
/// for i in (0..36).rev() { text += &format!("{},{}\n", i * 10, -1.0); }
/// let t = parse_ballbar_trace(&text, ParseOptions::default()).unwrap();
/// assert_eq!(t.runs.len(), 2);
/// assert_eq!(t.runs[1].direction, Direction::Cw);
/// assert!((t.runs[0].deviation[0] - 0.002).abs() < 1e-15);
/// let e = parse_ballbar_trace("angle,deviation\n0,1\n10,x\n", ParseOptions::default());
/// assert!(e.unwrap_err().to_string().starts_with("line 3"));
///
/// // columns named otherwise, `;` with decimal commas and a text column
/// use mtmotion::ballbar::BallbarColumns;
/// let mut text = String::from("Sample;EncoderX_Pos;EncoderY_Pos;State\n");
/// for i in 0..40 {
///     let a = (i as f64 * 9.0).to_radians();
///     text += &format!("{i};{};{};run\n", 50.0 * a.cos(), 50.0 * a.sin()).replace('.', ",");
/// }
/// let columns = BallbarColumns {
///     x: Some("EncoderX_Pos".into()),
///     y: Some("EncoderY_Pos".into()),
///     ..BallbarColumns::default()
/// };
/// let opts = ParseOptions { columns, ..ParseOptions::default() };
/// let t = parse_ballbar_trace(&text, opts.clone()).unwrap();
/// assert!((t.nominal_radius - 50.0).abs() < 1e-9);
/// let e = parse_ballbar_trace("a,b\n1,2\n", opts).unwrap_err();
/// assert_eq!(e.to_string(), "columns.x: no column named 'EncoderX_Pos' in the file (columns: a, b)");
/// ```
pub fn parse_ballbar_trace(
    text: &str,
    opts: ParseOptions,
) -> Result<BallbarTrace, BallbarTraceError> {
    crate::budget::check_text("trace", text)?;
    parse_with(opts, |o| read_table(text, o))
}

/// [`parse_ballbar_trace`] of a file's bytes: a MATLAB v5 `.mat` capture
/// ([`crate::trace::mat`]: its signals are the columns, named as the
/// capture names them, so [`ParseOptions::columns`] usually maps them), or
/// text (UTF-8) read as [`parse_ballbar_trace`] reads it.
///
/// # Units
/// As [`parse_ballbar_trace`].
///
/// # Errors
/// As [`parse_ballbar_trace`]; for a `.mat` capture, its byte and cause
/// where it breaks the format, and the trace budget for its size.
///
/// # Examples
/// ```
/// use mtmotion::ballbar::{parse_ballbar_trace_bytes, ParseOptions};
/// let e = parse_ballbar_trace_bytes(b"MATLAB 5.0 MAT-file", ParseOptions::default()).unwrap_err();
/// assert_eq!(e.to_string(), "byte 19: MATLAB .mat: the 128-byte header is cut short at 19 bytes");
/// let t = parse_ballbar_trace_bytes(b"angle,deviation\n0,1\n", ParseOptions::default());
/// assert!(t.unwrap_err().to_string().contains("no run of at least 8 points"));
/// ```
pub fn parse_ballbar_trace_bytes(
    bytes: &[u8],
    opts: ParseOptions,
) -> Result<BallbarTrace, BallbarTraceError> {
    if !crate::trace::mat::is_mat(bytes) {
        return parse_ballbar_trace(&String::from_utf8_lossy(bytes), opts);
    }
    crate::budget::check_bytes("trace", bytes.len() as u64)?;
    parse_with(opts, |o| crate::trace::read_bytes(bytes, o))
}

/// The ball-bar trace of the table `read` gives.
fn parse_with(
    opts: ParseOptions,
    read: impl FnOnce(&ReadOptions) -> Result<crate::trace::TableRead, TraceError>,
) -> Result<BallbarTrace, BallbarTraceError> {
    check_options(&opts)?;
    let cols = &opts.columns;
    // The table's own hints name the servo columns; a ball-bar trace names its own.
    let t = read(&ReadOptions::default())
        .map_err(|e| match e {
            TraceError::Empty => BallbarTraceError::Empty,
            TraceError::NoHeader { line } => BallbarTraceError::NoHeader { line },
            // numbers only: the ball-bar columns must be named
            TraceError::BadOption {
                line,
                field: "samplePeriod",
                ..
            } => BallbarTraceError::NoHeader { line },
            e => e.into(),
        })?
        .table;
    let (time, time_base) = time_of(&t, cols)?;
    let mut polar = angle_and_deviation(&t, &opts, cols)?;
    let mut angle = unwrap_angles(&polar.angle);
    let segments = match pick(&t, &cols.direction, "direction", &DIRECTION_NAMES)? {
        Some(k) => runs_from_direction_column(&t, k)?,
        None => runs_from_turning_points(&angle),
    };
    let (kept, trimming) = trim(&angle, &time, &t.lines, &segments, time_base, opts.trim);
    // An X/Y trace about its own LSC: the centre of the kept samples only,
    // so that a standstill's or a lead-in's weight does not move it.
    if let (Some((x, y)), Some(c)) = (&polar.xy, polar.centre) {
        if !c.given && trimming.applied {
            let mut idx: Vec<usize> = kept.iter().flat_map(|(_, k)| k.iter().copied()).collect();
            idx.sort_unstable();
            idx.dedup();
            let (kx, ky): (Vec<f64>, Vec<f64>) = idx.iter().map(|&i| (x[i], y[i])).unzip();
            if let Ok(f) = fit_circle(&kx, &ky) {
                let centre = TraceCentre {
                    point: PlanePoint { x: f.cx, y: f.cy },
                    given: false,
                };
                let r0 = opts.nominal_radius.unwrap_or(f.r);
                polar = polar_about(&t, x.clone(), y.clone(), centre, r0, f.r)?;
                angle = unwrap_angles(&polar.angle);
            }
        }
    }
    let runs: Vec<Run> = kept
        .into_iter()
        .map(|(direction, idx)| Run {
            direction,
            angle: idx.iter().map(|&i| angle[i]).collect(),
            deviation: idx.iter().map(|&i| polar.deviation[i]).collect(),
            lines: idx.iter().map(|&i| t.lines[i]).collect(),
        })
        .collect();
    if runs.is_empty() {
        return Err(BallbarTraceError::TooShort {
            line: t.lines[0],
            min: MIN_RUN,
        });
    }
    let radius = polar.radius;
    let measured = (time_base == TimeBase::Column && trimming.plateau_speed > 0.0)
        .then_some(trimming.plateau_speed * polar.path_radius * 60.0);
    let feed = opts.feed.or(measured);
    let mut warnings = unit_warnings(&polar.source, &runs, radius);
    if time_base == TimeBase::SampleIndex {
        warnings.push(format!(
            "no time column: the sample index is used as time (uniform sampling assumed) to find the constant-feed part{}; add a 'time' column (s, or 'time_ms') to measure the feed",
            if opts.feed.is_some() { "" } else { ", and the feed is unknown" }
        ));
    }
    Ok(BallbarTrace {
        nominal_radius: radius,
        feed,
        runs,
        centre: polar.centre,
        trimming: Some(trimming),
        warnings,
    })
}

/// Largest deviation read as plausible, relative to the radius (1 %: a
/// ball bar's travel is ±1 mm on a 100 mm bar).
pub const MAX_PLAUSIBLE_DEVIATION: f64 = 0.01;
/// Smallest peak-to-peak deviation read as plausible, mm (0.1 µm, a ball
/// bar's resolution: Renishaw QC20 0.1 µm).
pub const MIN_PLAUSIBLE_SPAN: f64 = 1e-4;

/// Unit warnings (module header): a deviation over 1 % of the radius, or
/// a trace whose deviations span less than a ball bar resolves.
fn unit_warnings(source: &str, runs: &[Run], radius: f64) -> Vec<String> {
    let all = || runs.iter().flat_map(|r| r.deviation.iter().copied());
    let big = all().fold(0.0f64, |m, d| m.max(d.abs()));
    let (lo, hi) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), d| {
        (a.min(d), b.max(d))
    });
    let compact = crate::numeric::compact;
    let mut w = Vec::new();
    if big > MAX_PLAUSIBLE_DEVIATION * radius {
        w.push(format!(
            "{source}: the deviation reaches {} mm, more than 1 % of the radius {} mm: are these mm or µm? A deviation column without a unit is read as µm, one named e.g. 'deviation_mm' as mm; X/Y columns are mm unless named e.g. 'x_um'",
            compact(big),
            compact(radius)
        ));
    }
    if hi - lo < MIN_PLAUSIBLE_SPAN {
        w.push(format!(
            "{source}: the deviations span only {} µm, less than a ball bar resolves (0.1 µm): are these mm or µm? A deviation column without a unit is read as µm; name it e.g. 'deviation_mm' if its values are mm",
            compact((hi - lo) * 1e3)
        ));
    }
    w
}

/// The options' radius (a bar length from 0.001 to 1e6 mm) and feed, when
/// given, are finite and positive.
fn check_options(opts: &ParseOptions) -> Result<(), BallbarTraceError> {
    if let Some(r) = opts.nominal_radius {
        if !(super::synthetic::MIN_RADIUS..=super::synthetic::MAX_RADIUS).contains(&r) {
            return Err(BallbarTraceError::BadOption {
                field: "nominalRadius",
                message: format!(
                    "expected a bar length from 0.001 to 1e6 mm, got {}",
                    crate::numeric::compact(r)
                ),
            });
        }
    }
    if let Some(f) = opts.feed {
        if !(f.is_finite() && f > 0.0) {
            return Err(BallbarTraceError::BadOption {
                field: "feed",
                message: format!("expected a feed > 0 mm/min, got {f}"),
            });
        }
    }
    if let Some(c) = opts.centre {
        if !(c.x.is_finite() && c.y.is_finite()) {
            return Err(BallbarTraceError::BadOption {
                field: "centre",
                message: "expected finite x and y in mm".into(),
            });
        }
    }
    Ok(())
}

/// Angles (rad, wrapped as read), radial deviations (mm), the nominal
/// radius (mm), for X/Y traces the positions (mm) and the centre used, and
/// the columns read (for messages).
struct Polar {
    angle: Vec<f64>,
    deviation: Vec<f64>,
    radius: f64,
    /// The radius the tool path runs on (X/Y: the LSC radius, whatever
    /// nominal radius the options give), for the feed, mm.
    path_radius: f64,
    xy: Option<(Vec<f64>, Vec<f64>)>,
    centre: Option<TraceCentre>,
    source: String,
}

/// The time of each sample (s) from a time column (`time`/`t`, s, or ms
/// if the name says ms), strictly increasing; else the sample index.
fn time_of(t: &Table, cols: &BallbarColumns) -> Result<(Vec<f64>, TimeBase), BallbarTraceError> {
    let Some(k) = pick(t, &cols.time, "time", &TIME_NAMES)? else {
        return Ok((
            (0..t.rows()).map(|i| i as f64).collect(),
            TimeBase::SampleIndex,
        ));
    };
    let scale = if header_says(t, k, &["ms"]) {
        1e-3
    } else {
        1.0
    };
    let time = t.column_at(k + 1, scale)?;
    if let Some(i) = (1..time.len()).find(|&i| time[i] <= time[i - 1]) {
        return Err(BallbarTraceError::TimeNotIncreasing {
            line: t.lines[i],
            column: k + 1,
            name: t.names[k].clone(),
        });
    }
    Ok((time, TimeBase::Column))
}

/// The angle, radial deviation and nominal radius from angle/deviation
/// columns, or from X/Y columns.
fn angle_and_deviation(
    t: &Table,
    opts: &ParseOptions,
    cols: &BallbarColumns,
) -> Result<Polar, BallbarTraceError> {
    let ang = pick(t, &cols.angle, "angle", &ANGLE_NAMES)?;
    let dev = pick(t, &cols.deviation, "deviation", &DEVIATION_NAMES)?;
    let (xk, yk) = (
        pick(t, &cols.x, "x", &X_NAMES)?,
        pick(t, &cols.y, "y", &Y_NAMES)?,
    );
    let want_xy = cols.x.is_some() || cols.y.is_some();
    match (ang, dev, xk, yk) {
        (Some(a), Some(d), _, _) if !want_xy => {
            let sa = if header_says(t, a, &["rad"]) {
                1.0
            } else {
                std::f64::consts::PI / 180.0
            };
            let sd = if header_says(t, d, &["mm"]) {
                1.0
            } else {
                1e-3
            };
            Ok(Polar {
                angle: t.column_at(a + 1, sa)?,
                deviation: t.column_at(d + 1, sd)?,
                radius: opts.nominal_radius.unwrap_or(100.0),
                path_radius: opts.nominal_radius.unwrap_or(100.0),
                xy: None,
                centre: None,
                source: format!(
                    "column {} ('{}')",
                    d + 1,
                    crate::budget::clip(&t.names[d], 40)
                ),
            })
        }
        (_, _, Some(xi), Some(yi)) => polar_from_xy(t, xi, yi, opts),
        _ => Err(BallbarTraceError::NoColumns(
            t.names
                .iter()
                .map(|n| crate::budget::clip(n, 40))
                .collect::<Vec<_>>()
                .join(", "),
        )),
    }
}

/// Angle and deviation of X/Y positions about the given centre, else about
/// their least-squares centre (the nominal radius is the fitted one unless
/// the options give it).
fn polar_from_xy(
    t: &Table,
    xi: usize,
    yi: usize,
    opts: &ParseOptions,
) -> Result<Polar, BallbarTraceError> {
    let s = |k| {
        if header_says(t, k, &["um"]) {
            1e-3
        } else {
            1.0
        }
    };
    let (x, y) = (t.column_at(xi + 1, s(xi))?, t.column_at(yi + 1, s(yi))?);
    // Nominal centre: the LSC of all points (collinear data is caught
    // here and reported at the first line).
    let c = fit_circle(&x, &y).map_err(|_| BallbarTraceError::TooShort {
        line: t.lines[0],
        min: MIN_RUN,
    })?;
    let r0 = opts.nominal_radius.unwrap_or(c.r);
    let centre = TraceCentre {
        point: opts.centre.unwrap_or(PlanePoint { x: c.cx, y: c.cy }),
        given: opts.centre.is_some(),
    };
    polar_about(t, x, y, centre, r0, c.r)
}

/// The polar form of X/Y positions about `centre`, nominal radius `r0`.
fn polar_about(
    t: &Table,
    x: Vec<f64>,
    y: Vec<f64>,
    centre: TraceCentre,
    r0: f64,
    path_radius: f64,
) -> Result<Polar, BallbarTraceError> {
    let mut a = Vec::with_capacity(x.len());
    let mut d = Vec::with_capacity(x.len());
    for (i, (px, py)) in x.iter().zip(&y).enumerate() {
        let (u, v) = (px - centre.point.x, py - centre.point.y);
        if u.hypot(v) <= 1e-12 * r0 {
            return Err(BallbarTraceError::AtCentre(t.lines[i]));
        }
        a.push(v.atan2(u));
        d.push(u.hypot(v) - r0);
    }
    Ok(Polar {
        angle: a,
        deviation: d,
        radius: r0,
        path_radius,
        xy: Some((x, y)),
        centre: Some(centre),
        source: "the X/Y columns".into(),
    })
}

/// The angle unwrapped across ±180°: each step is taken as the shorter way round.
fn unwrap_angles(raw_angle: &[f64]) -> Vec<f64> {
    let mut angle: Vec<f64> = Vec::with_capacity(raw_angle.len());
    for &a in raw_angle {
        let v = match angle.last() {
            None => a,
            Some(&prev) => {
                let tau = std::f64::consts::TAU;
                let step = (a - prev).rem_euclid(tau);
                prev + if step > std::f64::consts::PI {
                    step - tau
                } else {
                    step
                }
            }
        };
        angle.push(v);
    }
    angle
}

/// A run: first sample, end (exclusive) and direction.
type RunBounds = Segment;

/// Runs where the direction column (+1 CCW, −1 CW) keeps its value.
fn runs_from_direction_column(t: &Table, k: usize) -> Result<Vec<RunBounds>, BallbarTraceError> {
    let mut bounds = Vec::new();
    let mut start = 0;
    for i in 0..t.rows() {
        let v = t.columns[k][i];
        if v != 1.0 && v != -1.0 {
            return Err(BallbarTraceError::BadDirection {
                line: t.lines[i],
                value: v,
            });
        }
        if i + 1 == t.rows() || t.columns[k][i + 1] != v {
            let direction = if v > 0.0 {
                Direction::Ccw
            } else {
                Direction::Cw
            };
            bounds.push((start, i + 1, direction));
            start = i + 1;
        }
    }
    Ok(bounds)
}

/// Runs split where the angle turns back by more than 1° from its running
/// extreme (noise at a standstill does not split a run).
fn runs_from_turning_points(angle: &[f64]) -> Vec<RunBounds> {
    let tol = 1f64.to_radians();
    let mut bounds = Vec::new();
    let (mut start, mut ext, mut dir) = (0usize, 0usize, None::<Direction>);
    for i in 1..angle.len() {
        match dir {
            None => {
                if (angle[i] - angle[start]).abs() > tol {
                    dir = Some(if angle[i] > angle[start] {
                        Direction::Ccw
                    } else {
                        Direction::Cw
                    });
                    ext = i;
                }
            }
            Some(d) => {
                let s = d.sign();
                if (angle[i] - angle[ext]) * s >= 0.0 {
                    ext = i;
                } else if (angle[ext] - angle[i]) * s > tol {
                    bounds.push((start, ext + 1, d));
                    start = ext;
                    ext = i;
                    dir = Some(if d == Direction::Ccw {
                        Direction::Cw
                    } else {
                        Direction::Ccw
                    });
                }
            }
        }
    }
    if let Some(d) = dir {
        bounds.push((start, angle.len(), d));
    }
    bounds
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xy_trace_with_time_gives_runs_radius_and_feed() {
        // CCW full circle of R = 50 about (10, 20) at 1 rev per 6 s, then CW.
        let mut s = String::from("t [s]\tX\tY\n");
        for i in 0..=360 {
            let a = (i as f64).to_radians();
            s += &format!(
                "{}\t{}\t{}\n",
                i as f64 / 60.0,
                10.0 + 50.0 * a.cos(),
                20.0 + 50.0 * a.sin()
            );
        }
        for i in 1..=360 {
            let a = (360.0 - i as f64).to_radians();
            s += &format!(
                "{}\t{}\t{}\n",
                6.0 + i as f64 / 60.0,
                10.0 + 50.0 * a.cos(),
                20.0 + 50.0 * a.sin()
            );
        }
        let t = parse_ballbar_trace(&s, ParseOptions::default()).unwrap();
        assert_eq!(t.runs.len(), 2);
        assert!((t.nominal_radius - 50.0).abs() < 1e-9);
        // v = 2π·50 mm / 6 s = 52.36 mm/s = 3141.6 mm/min.
        assert!((t.feed.unwrap() - 100.0 * std::f64::consts::PI / 6.0 * 60.0).abs() < 1e-6);
        assert!(t.runs[0].deviation.iter().all(|d| d.abs() < 1e-9));
        // The angle is unwrapped: the CCW run ends at +2π, not 0.
        assert!((t.runs[0].angle.last().unwrap() - std::f64::consts::TAU).abs() < 1e-9);
    }

    #[test]
    fn malformed_traces_name_the_line() {
        let o = ParseOptions::default();
        let e = parse_ballbar_trace("foo,bar\n1,2\n", o.clone())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("'angle' and 'deviation'") && e.contains("foo, bar"),
            "{e}"
        );
        let e = parse_ballbar_trace("angle,dev\n0,1\n1,2\n2\n3,4\n", o.clone())
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("line 4:"), "{e}");
        let e = parse_ballbar_trace("angle,dev\n0,1\n1,2\n", o.clone())
            .unwrap_err()
            .to_string();
        assert!(e.contains("at least 8 points"), "{e}");
        let e = parse_ballbar_trace("angle,dev,dir\n0,1,1\n1,2,0\n2,3,1\n", o.clone())
            .unwrap_err()
            .to_string();
        assert_eq!(e, "line 3: direction must be +1 (CCW) or -1 (CW), got 0");
        let bad = ParseOptions {
            nominal_radius: Some(-1.0),
            ..ParseOptions::default()
        };
        assert!(parse_ballbar_trace("angle,dev\n0,1\n", bad)
            .unwrap_err()
            .to_string()
            .starts_with("nominalRadius"));
    }

    #[test]
    fn empty_and_headerless_files_name_the_ball_bar_columns() {
        let e = parse_ballbar_trace("", ParseOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("angle_deg,deviation_um") && !e.contains("time,x,y,c"),
            "{e}"
        );
        let e = parse_ballbar_trace("0,1\n1,2\n", ParseOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("line 1:") && e.contains("angle_deg,deviation_um"),
            "{e}"
        );
    }
}
