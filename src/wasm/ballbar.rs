//! Bindings for [`crate::ballbar`] and [`crate::alignment`]: circle fit,
//! harmonics, travel-range and angle sweeps, alignment estimate, trace
//! import, ISO 230-4 circular test, synthetic traces and the paper's
//! examples. Thin: conversion only.

use js_sys::{Array, Reflect};
use wasm_bindgen::prelude::*;

use super::args::JsArg;
use super::convert::{
    count_arg, floats_arg, known_keys, name_arg, number_arg, object, opt_number, opt_number_arg,
    plain, plain_floats, require_object, string_arg, to_js, trace_arg, Obj, TraceArg,
};
use super::results::JsResult;
use crate::alignment::{self, examples, AngleSweepConfig, Section, SweepConfig};
use crate::ballbar::{
    self, BallbarTrace, Direction, ParseOptions, PlanePoint, Run, SyntheticConfig, TraceCentre,
};

#[wasm_bindgen(typescript_custom_section)]
const TS: &str = r#"
/** Centre, radius and RMS residual in the unit of the x, y given to fitCircle (mm in the page). */
export interface CircleFit { /** [as x, y] */ cx: number; /** [as x, y] */ cy: number; /** [as x, y] */ r: number; /** [as x, y] */ rmsResidual: number }
/** A sin(n·θ + φ); amplitude in the deviation's unit (mm), phase in rad. */
export interface HarmonicComponent { /** [-] n */ order: number; /** [mm] A */ amplitude: number; /** [rad] φ */ phase: number }
/** Lengths in mm, angles in degrees (ranges, centre), phases in rad. */
export interface TravelRangeSweepConfig {
  /** [mm] true centre offset */ offset?: { z: number; x: number };
  harmonics?: HarmonicComponent[];
  /** [deg] travel ranges */ ranges: number[];
  /** [mm] Ball-bar radius (default 100); 0 = DBB5 centre-ball reading. */
  radius?: number;
  /** [-] Samples per revolution (default 1000). */
  samples?: number;
  /** Centre of every range, degrees (default 0: 180° means −90°…90°). */
  centreDeg?: number;
}
/** errorZ, errorX: estimated − true centre, mm. */
export interface SweepPoint { rangeDeg: number; /** [mm] */ errorZ: number; /** [mm] */ errorX: number }
export interface AlignmentSection { /** [mm] height of the section */ y: number; angleDeg: Float64Array | number[]; /** [mm] */ deviation: Float64Array | number[] }
export interface AlignmentInput { sections: AlignmentSection[]; /** [mm] bar length (default 100) */ radius?: number }
export interface AlignmentEstimate {
  /** [mm] each section's height, estimated centre and fit RMS */ sections: { y: number; z: number; x: number; rmsResidual: number }[];
  /** [rad] (mm/mm); null with one section. */ deltaBz: number | null; /** [rad] */ deltaBx: number | null;
  /** [mm] offsets at height 0 of the fitted lines; null with one section. */ interceptZ: number | null; /** [mm] */ interceptX: number | null;
}
export interface AngleSweepConfig {
  /** [mm] heights and true centre offsets */ sections: { y: number; offset: { z: number; x: number } }[];
  /** [deg] */ ranges: number[]; harmonics?: HarmonicComponent[]; /** [mm] */ radius?: number; /** [-] */ samples?: number; centreDeg?: number;
}
/** Angle errors in rad. */
export interface AngleSweepPoint {
  rangeDeg: number; /** [rad] */ deltaBz: number; /** [rad] */ deltaBx: number; /** [rad] */ errorBz: number; /** [rad] */ errorBx: number;
}
export interface BallbarRun { direction: 'ccw' | 'cw'; /** [rad] unwrapped */ angleRad: Float64Array; /** [mm] */ deviation: Float64Array }
/** [mm] a point of the trace's X/Y plane */
export interface PlanePoint { /** [mm] */ x: number; /** [mm] */ y: number }
/** The centre an X/Y trace's deviations are about: given (pivot or programmed centre) or the trace's own least-squares centre (given: false), which removes any centre offset. */
export interface TraceCentre { point: PlanePoint; given: boolean }
/** A stretch of samples the trimming left out (source lines inclusive). */
export interface TrimmedStretch {
  reason: 'leadIn' | 'leadOut' | 'standstill' | 'transient' | 'overshoot' | 'short';
  /** [-] */ firstLine: number; /** [-] */ lastLine: number; /** [-] */ samples: number;
  /** [s, or the sample index when timeBase is 'sampleIndex'] */ startTime: number; /** [s, or the sample index] */ endTime: number;
  /** [rad] unwrapped */ startAngle: number; /** [rad] unwrapped */ endAngle: number;
}
/** What the trimming to the constant-feed part (speed plateau) did. */
export interface TraceTrimming {
  /** 'column': the file's time column; 'sampleIndex': no time column, uniform sampling assumed */ timeBase: 'column' | 'sampleIndex';
  /** false: found and listed only (options.trim false) */ applied: boolean;
  /** [-] plateau band, relative (0.05 = ±5 % of the median moving speed) */ band: number;
  /** [rad/s, or rad per sample when timeBase is 'sampleIndex'] median plateau speed */ plateauSpeed: number;
  /** [-] samples each side of the speed window */ halfWindow: number;
  trimmed: TrimmedStretch[];
}
export interface BallbarTrace {
  /** [mm] */ nominalRadius: number; /** [mm/min] the plateau's median speed, or as given */ feed: number | null; runs: BallbarRun[];
  /** null for angle/deviation traces */ centre: TraceCentre | null;
  /** null for traces not read from a file */ trimming?: TraceTrimming | null;
  /** about the file: units, time base; each names the column and what to do */ warnings?: string[];
}
export interface ParseTraceOptions {
  /** [mm] */ nominalRadius?: number; /** [mm/min] */ feed?: number;
  /** [mm] X/Y traces: the centre to take deviations about (pivot or programmed centre); default: the trace's own least-squares centre */ centre?: PlanePoint;
  /** Trim each run to its constant-feed part (default true); false keeps every sample and only lists the stretches. */ trim?: boolean;
  /** Which column is which, for a file that names them otherwise (EncoderX_Pos); a field left out is found by its usual names */ columns?: BallbarColumns;
}
/** Ball-bar column mapping: each names a column as the header writes it. Mapping x or y reads the file as X/Y positions. */
export interface BallbarColumns { x?: string | null; y?: string | null; angle?: string | null; deviation?: string | null; time?: string | null; direction?: string | null }
export interface CircularTestRun {
  direction: 'ccw' | 'cw'; gUm: number; fMaxUm: number; fMinUm: number;
  centreXMm: number; centreYMm: number; radiusMm: number; spanDeg: number; /** [-] samples in the run */ points: number;
}
export interface BallbarDiagnostics {
  /** LSC of the full runs about the centre named by `centre`; 0 by construction for 'traceLsc' */ centreOffsetXUm: number; centreOffsetYUm: number;
  /** 'barPivot': angle/deviation trace (measured set-up offset); 'given': X/Y about a given centre (measured); 'traceLsc': X/Y about its own least-squares centre (0 by construction) */ centre: 'barPivot' | 'given' | 'traceLsc';
  /** 0 below its resolution */ backlashXUm: number; backlashYUm: number;
  /** Smallest backlash reported (3 standard errors); below it the backlash reads 0. */ backlashXResolutionUm: number; backlashYResolutionUm: number;
  /** Only spikes above spikeThresholdUm (the largest of the runs' 1.5 × largest residual away from the quadrant points); each states the threshold it was compared with. */
  reversalSpikes: { direction: 'ccw' | 'cw'; axis: 'x' | 'y'; angleDeg: number; heightUm: number; thresholdUm: number }[]; spikeThresholdUm: number;
  /** null without both directions or feed; 0 below its resolution */ servoMismatchMs: number | null; /** 3 standard errors */ servoMismatchResolutionMs: number | null;
  /** 0 below its resolution */ scaleMismatchPpm: number; /** 3 standard errors */ scaleMismatchResolutionPpm: number;
  /** 0 below its resolution */ squarenessUrad: number; /** 3 standard errors */ squarenessResolutionUrad: number;
  /** null unless the F-test of cyclicTest passes */ cyclic: { pitchMm: number; amplitudeXUm: number; amplitudeYUm: number } | null;
  /** the cyclic error's significance test: F of the best pitch against the critical F (α = 0.1 % over every pitch position compared) */ cyclicTest: { /** [-] */ fRatio: number; /** [-] */ fCritical: number; /** [-] */ pitches: number } | null;
  /** RMS of the run model's residuals (the fit quality the standard errors rest on) */ residualRmsUm: number;
  /** [-] */ runsUsed: number;
}
/** circularTest without the diagnostics (the same runs and H). */
export interface CircularDeviationResult { nominalRadiusMm: number; runs: CircularTestRun[]; hUm: number | null }
export interface CircularTestResult { nominalRadiusMm: number; runs: CircularTestRun[]; hUm: number | null; diagnostics: BallbarDiagnostics | null }
/** mm, rad, s, mm/min; every field optional. */
export interface SyntheticTraceConfig {
  /** [mm] bar length */ radius?: number; /** [mm/min] */ feed?: number; /** [-] per revolution */ samples?: number;
  rangeDeg?: number; centreDeg?: number; bothDirections?: boolean;
  /** [mm] */ offsetX?: number; /** [mm] */ offsetY?: number; harmonics?: HarmonicComponent[];
  /** [-] scale error, 1e-6 = 1 ppm */ scaleX?: number; /** [-] */ scaleY?: number; /** [rad] */ squareness?: number;
  /** [s] X lags Y */ servoMismatch?: number;
  /** [mm] */ backlashX?: number; /** [mm] */ backlashY?: number; /** [mm] reversal-spike height */ spike?: number; spikeDecayDeg?: number;
  /** [mm] */ cyclicAmplitude?: number; /** [mm] */ cyclicPitch?: number; /** [mm] uniform noise half-width */ noise?: number;
}
export interface PaperExample {
  name: string; description: string;
  curves: { /** [mm] true centre */ offset: { z: number; x: number }; points: SweepPoint[] }[];
  angle: AngleSweepPoint[];
  paper: { label: string; rangeDeg: number; paper: string; /** [µm, or µm/700 mm for Fig. 12] ours, in the paper's unit */ ours: number }[];
}
"#;

/// Least-squares circle through the points (algebraic start, then
/// Levenberg–Marquardt); throws for < 3 or collinear points.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = fitCircle, unchecked_return_type = "CircleFit")]
pub fn fit_circle(
    #[wasm_bindgen(unchecked_param_type = "Float64Array | number[]")] x: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array | number[]")] y: JsValue,
) -> Result<JsValue, JsError> {
    let (x, y) = (floats_arg(&x, "x")?, floats_arg(&y, "y")?);
    to_js(&ballbar::fit_circle(&x, &y)?)
}

/// Least-squares harmonics of orders 0 … maxOrder (valid on partial ranges).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = harmonics, unchecked_return_type = "HarmonicComponent[]")]
pub fn harmonics(
    #[wasm_bindgen(unchecked_param_type = "Float64Array | number[]")] angle_rad: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array | number[]")] radial_deviation: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number")] max_order: JsValue,
) -> Result<JsValue, JsError> {
    let angle = floats_arg(&angle_rad, "angleRad")?;
    let dev = floats_arg(&radial_deviation, "radialDeviation")?;
    let max_order = count_arg(number_arg(&max_order, "maxOrder")?, "maxOrder", usize::MAX)?;
    to_js(&ballbar::fit_harmonics(&angle, &dev, max_order)?)
}

/// takayama §2.1: centre-estimate error for each travel range.
#[wasm_bindgen(js_name = travelRangeSweep, unchecked_return_type = "SweepPoint[]")]
pub fn travel_range_sweep(
    #[wasm_bindgen(unchecked_param_type = "TravelRangeSweepConfig")] config: JsValue,
) -> Result<JsValue, JsError> {
    let cfg = SweepConfig::arg(config, "config")?;
    alignment::travel_range_sweep(&cfg)?.js()
}

/// takayama §2.2: angle-error estimate against travel range (Fig. 12).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = angleSweep, unchecked_return_type = "AngleSweepPoint[]")]
pub fn angle_sweep(
    #[wasm_bindgen(unchecked_param_type = "AngleSweepConfig")] config: JsValue,
) -> Result<JsValue, JsError> {
    let cfg: AngleSweepConfig = object(config, "config")?;
    to_js(&alignment::angle_sweep(&cfg)?)
}

fn get(obj: &JsValue, key: &str) -> JsValue {
    Reflect::get(obj, &JsValue::from_str(key)).unwrap_or(JsValue::UNDEFINED)
}

fn number(obj: &JsValue, key: &str, what: &str) -> Result<f64, JsError> {
    get(obj, key)
        .as_f64()
        .ok_or_else(|| JsError::new(&format!("{what}.{key}: expected a number")))
}

/// `obj.key` as numbers; `obj` is a [`plain`] snapshot.
fn floats(obj: &JsValue, key: &str, what: &str) -> Result<Vec<f64>, JsError> {
    plain_floats(&get(obj, key), &format!("{what}.{key}"))
}

/// An `Error` unless section `s` (of a plain snapshot) is an object with
/// only the keys `allowed`.
fn section_object(s: &JsValue, what: &str, allowed: &[&str]) -> Result<(), JsError> {
    if !s.is_object() || Array::is_array(s) {
        return Err(JsError::new(&format!(
            "{what}: expected an object {{ {} }}",
            allowed.join(", ")
        )));
    }
    known_keys(s, allowed, what)
}

/// The sections of an alignment input (a plain snapshot).
fn sections_of(input: &JsValue) -> Result<Vec<Section>, JsError> {
    let list = get(input, "sections");
    if !Array::is_array(&list) {
        return Err(JsError::new(
            "sections: expected an array of { y, angleDeg, deviation }",
        ));
    }
    let mut sections = Vec::new();
    for (k, s) in Array::from(&list).iter().enumerate() {
        let what = format!("sections[{k}]");
        section_object(&s, &what, &["y", "angleDeg", "deviation"])?;
        sections.push(Section {
            y: number(&s, "y", &what)?,
            angle_deg: floats(&s, "angleDeg", &what)?,
            deviation: floats(&s, "deviation", &what)?,
        });
    }
    Ok(sections)
}

/// takayama §2.2: offset per section and ΔBz, ΔBx from two sections.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = estimateAlignment, unchecked_return_type = "AlignmentEstimate")]
pub fn estimate_alignment(
    #[wasm_bindgen(unchecked_param_type = "AlignmentInput")] input: JsValue,
) -> Result<JsValue, JsError> {
    require_object(&input, "input")?;
    let input = plain(&input, "input")?;
    known_keys(&input, &["sections", "radius"], "input")?;
    let sections = sections_of(&input)?;
    let radius = opt_number(&input, "radius", "input")?.unwrap_or(100.0);
    to_js(&alignment::estimate_alignment(&sections, radius)?)
}

fn trace_to_js(t: &BallbarTrace) -> Result<JsValue, JsError> {
    let runs = Array::new();
    for r in &t.runs {
        runs.push(
            &Obj::new()
                .val("direction", r.direction.js()?)
                .arr("angleRad", &r.angle)
                .arr("deviation", &r.deviation)
                .build(),
        );
    }
    let feed = t.feed.map_or(JsValue::NULL, JsValue::from_f64);
    let centre = match t.centre {
        None => JsValue::NULL,
        Some(c) => to_js(&c)?,
    };
    Ok(Obj::new()
        .num("nominalRadius", t.nominal_radius)
        .val("feed", feed)
        .val("runs", runs.into())
        .val("centre", centre)
        .val("trimming", to_js(&t.trimming)?)
        .val("warnings", to_js(&t.warnings)?)
        .build())
}

fn trace_from_js(v: &JsValue) -> Result<BallbarTrace, JsError> {
    let list = get(v, "runs");
    if !Array::is_array(&list) {
        return Err(JsError::new(
            "trace.runs: expected an array of { direction, angleRad, deviation }",
        ));
    }
    let mut runs = Vec::new();
    // `trimming` and `warnings` are what parseBallbarTrace reported about
    // the file: accepted so its result can be passed on as it is, not read.
    known_keys(
        v,
        &[
            "nominalRadius",
            "feed",
            "runs",
            "centre",
            "trimming",
            "warnings",
        ],
        "trace",
    )?;
    for (k, r) in Array::from(&list).iter().enumerate() {
        let what = format!("trace.runs[{k}]");
        section_object(&r, &what, &["direction", "angleRad", "deviation"])?;
        let direction = match get(&r, "direction").as_string().as_deref() {
            Some("ccw") => Direction::Ccw,
            Some("cw") => Direction::Cw,
            _ => {
                return Err(JsError::new(&format!(
                    "{what}.direction: expected 'ccw' or 'cw'"
                )))
            }
        };
        runs.push(Run {
            direction,
            angle: floats(&r, "angleRad", &what)?,
            deviation: floats(&r, "deviation", &what)?,
            lines: Vec::new(),
        });
    }
    Ok(BallbarTrace {
        nominal_radius: number(v, "nominalRadius", "trace")?,
        feed: opt_number(v, "feed", "trace")?,
        runs,
        centre: centre_from_js(&get(v, "centre"))?,
        trimming: None,
        warnings: Vec::new(),
    })
}

/// `trace.centre` (null or absent: an angle/deviation trace).
fn centre_from_js(c: &JsValue) -> Result<Option<TraceCentre>, JsError> {
    if c.is_null() || c.is_undefined() {
        return Ok(None);
    }
    let point = get(c, "point");
    Ok(Some(TraceCentre {
        point: PlanePoint {
            x: number(&point, "x", "trace.centre.point")?,
            y: number(&point, "y", "trace.centre.point")?,
        },
        given: get(c, "given")
            .as_bool()
            .ok_or_else(|| JsError::new("trace.centre.given: expected true or false"))?,
    }))
}

/// Reads a ball-bar trace (angle + deviation, or X/Y): a text file, or a
/// file's bytes as a `Uint8Array` (a MATLAB `.mat` capture, or text);
/// errors name the line (a `.mat` file's: the byte).
#[wasm_bindgen(js_name = parseBallbarTrace, unchecked_return_type = "BallbarTrace")]
pub fn parse_ballbar_trace(
    #[wasm_bindgen(unchecked_param_type = "string | Uint8Array")] text: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "ParseTraceOptions")] options: JsValue,
) -> Result<JsValue, JsError> {
    let trace = trace_arg(&text, "text")?;
    let opts: ParseOptions = if options.is_undefined() || options.is_null() {
        ParseOptions::default()
    } else {
        ParseOptions::arg(options, "options")?
    };
    trace_to_js(&match trace {
        TraceArg::Text(text) => ballbar::parse_ballbar_trace(&text, opts)?,
        TraceArg::Bytes(bytes) => ballbar::parse_ballbar_trace_bytes(&bytes, opts)?,
    })
}

#[cfg(feature = "full")]
#[wasm_bindgen(typescript_custom_section)]
const TS_B5R: &str = r#"
/** A feature of a Renishaw .b5r report: NAME, DT (unit code) and the value as written, in `unit` (null: a unit code the reader does not know). */
export interface B5rFeature { name: string; dt: string; unit: string | null; /** [as unit] */ value: number; /** [-] 1-based line */ line: number }
export interface B5rRun { /** RUN_DIRECTION as written ('CW', 'CCW', '' when missing) */ direction: string; features: B5rFeature[]; /** [-] */ line: number }
export interface B5rAnalysis { /** e.g. 'RENISHAW_DIAGNOSTICS' */ name: string; features: B5rFeature[]; /** [-] */ line: number }
/** What a .b5r holds that the core reads: settings, metadata, runs' and analyses' features. The raw samples are not read. */
export interface B5rReport {
  testName: string | null; instrument: string | null; /** [mm] bar length */ radius: number | null; /** [mm/min] programmed */ feed: number | null;
  /** e.g. 'XY' */ plane: string | null; /** the axes A and B stand for */ axes: [string, string] | null;
  /** [element, text] */ metadata: [string, string][]; runs: B5rRun[]; analyses: B5rAnalysis[];
  /** elements not read, as 'NAME (line N)' */ unread: string[]; notes: string[];
}
/** A .b5r feature beside ours: `ours` and `theirsInOurs` in `oursUnit`; null where we compute none or the units are of another quantity. */
export interface B5rBeside {
  /** the analysis's name, or 'run CW' */ source: string; feature: string; /** [as theirsUnit] */ theirs: number; theirsUnit: string | null;
  /** [as oursUnit] */ ours: number | null; /** '' where we compute none */ oursUnit: string; /** [as oursUnit] */ theirsInOurs: number | null; /** [-] 1-based line in the file */ line: number;
}
"#;

/// Reads a Renishaw ball-bar results file (`.b5r`, XML): the test's
/// settings and the features it reports; errors name the line.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = readB5r, unchecked_return_type = "B5rReport")]
pub fn read_b5r(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
) -> Result<JsValue, JsError> {
    let text = string_arg(&text, "text")?;
    crate::budget::check_text("trace", &text)?;
    crate::trace::b5r::read(&text)?.js()
}

/// A `.b5r` report's features beside our circular test of `trace`.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = b5rBeside, unchecked_return_type = "B5rBeside[]")]
pub fn b5r_beside(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "BallbarTrace")] trace: JsValue,
) -> Result<JsValue, JsError> {
    let text = string_arg(&text, "text")?;
    require_object(&trace, "trace")?;
    let trace = plain(&trace, "trace")?;
    crate::budget::check_text("trace", &text)?;
    let report = crate::trace::b5r::read(&text)?;
    let ours = ballbar::circular_test(&trace_from_js(&trace)?)?;
    ballbar::b5r_beside::beside(&report, &ours).js()
}

/// ISO 230-4 G, H, F per direction, plus the ball-bar diagnostics.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = circularTest, unchecked_return_type = "CircularTestResult")]
pub fn circular_test(
    #[wasm_bindgen(unchecked_param_type = "BallbarTrace")] trace: JsValue,
) -> Result<JsValue, JsError> {
    require_object(&trace, "trace")?;
    let trace = plain(&trace, "trace")?;
    ballbar::circular_test(&trace_from_js(&trace)?)?.js()
}

/// ISO 230-4 G, H, F per direction without the diagnostics: what the
/// circularity calculator shows (the embed module has no `circularTest`).
#[wasm_bindgen(js_name = circularDeviation, unchecked_return_type = "CircularDeviationResult")]
pub fn circular_deviation(
    #[wasm_bindgen(unchecked_param_type = "BallbarTrace")] trace: JsValue,
) -> Result<JsValue, JsError> {
    require_object(&trace, "trace")?;
    let trace = plain(&trace, "trace")?;
    ballbar::circular_deviation(&trace_from_js(&trace)?)?.js()
}

/// A synthetic ball-bar trace with known machine errors.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = syntheticBallbarTrace, unchecked_return_type = "BallbarTrace")]
pub fn synthetic_ballbar_trace(
    #[wasm_bindgen(unchecked_param_type = "SyntheticTraceConfig")] config: JsValue,
) -> Result<JsValue, JsError> {
    let cfg: SyntheticConfig = if config.is_undefined() {
        SyntheticConfig::default()
    } else {
        object(config, "config")?
    };
    trace_to_js(&ballbar::synthetic_trace(&cfg)?)
}

/// The paper's Figs. 6, 7, 8, 12 ("fig6" …) with its quoted numbers;
/// `radius` 100 mm (default, ball bar) or 0 (DBB5 centre ball).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = ballbarExample, unchecked_return_type = "PaperExample")]
pub fn ballbar_example(
    #[wasm_bindgen(unchecked_param_type = "string")] name: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number | undefined")] radius: JsValue,
) -> Result<JsValue, JsError> {
    let name: &str = &name_arg(&name, "name")?;
    let radius = opt_number_arg(&radius, "radius")?.unwrap_or(100.0);
    to_js(&examples::example(name, radius)?)
}

#[wasm_bindgen(typescript_custom_section)]
const TS_BAND: &str = r#"
/** A section as a trace file: its text is read in the core (units, layout, trimming) about the input's centre. */
export interface AlignmentTraceSection { /** [mm] height of the section */ y: number; /** the ball-bar trace file (CSV/TSV) */ text: string; /** [-] 0-based run of the file (default 0) */ run?: number }
export interface AlignmentBandInput {
  sections: (AlignmentSection | AlignmentTraceSection)[];
  /** [mm] bar length (default 100) */ radius?: number;
  /** [mm] X/Y traces: the common centre (pivot or programmed circle centre) every section is read about; required for X/Y traces */ centre?: PlanePoint;
  /** [-] Highest harmonic order considered, 1 … 50 (default 10); the orders kept are those the data supports (BIC). */ maxOrder?: number;
}
/** [rad] Half-widths of an angle error's band. */
export interface AngleBand { /** [rad] */ systematic: number; /** [rad] */ statistical: number; /** [rad] */ band: number; determined: boolean }
export interface AlignmentSectionBand {
  /** [mm] */ y: number; /** [deg] the section's measured span */ rangeDeg: number; /** [deg] */ centreDeg: number;
  /** [mm] systematic error of the centre (selected harmonics) */ biasZ: number; /** [mm] */ biasX: number;
  /** [mm] standard error from the noise */ sigmaZ: number; /** [mm] */ sigmaX: number; /** [mm] max|Δ|²/R */ secondOrder: number;
  /** [mm] band half-width: |bias| + secondOrder + coverage·sigma */ bandZ: number; /** [mm] */ bandX: number;
  determinedZ: boolean; determinedX: boolean; /** why an offset is not determined, in words */ note: string | null;
  /** [mm] */ peakToValley: number; /** [mm] residual standard deviation */ noise: number;
  /** [-] highest harmonic order kept (1: none) */ order: number; /** [-] highest order the span resolves */ resolvedOrder: number;
  harmonics: HarmonicComponent[];
}
export interface AlignmentBand {
  estimate: AlignmentEstimate;
  sections: AlignmentSectionBand[];
  bandBz: AngleBand | null; bandBx: AngleBand | null;
  /** [-] coverage factor of the statistical parts (3) */ coverage: number;
}
"#;

/// takayama §2.1–2.2 on measured sections (arrays, or trace files read
/// about one common centre): offsets, angle errors and their bands.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = estimateAlignmentBand, unchecked_return_type = "AlignmentBand")]
pub fn estimate_alignment_band(
    #[wasm_bindgen(unchecked_param_type = "AlignmentBandInput")] input: JsValue,
) -> Result<JsValue, JsError> {
    require_object(&input, "input")?;
    let input = plain(&input, "input")?;
    if !get(&input, "travelRangeDeg").is_undefined() {
        return Err(JsError::new(
            "input.travelRangeDeg: not an input: the travel range is each section's measured span",
        ));
    }
    known_keys(
        &input,
        &["sections", "radius", "centre", "maxOrder"],
        "input",
    )?;
    let radius = opt_number(&input, "radius", "input")?.unwrap_or(100.0);
    let max_order = match opt_number(&input, "maxOrder", "input")? {
        Some(v) => count_arg(v, "input.maxOrder", usize::MAX)?,
        None => 10,
    };
    let sections = band_sections(&input, radius)?;
    let cfg = alignment::BandConfig { radius, max_order };
    to_js(&alignment::estimate_alignment_band(&sections, &cfg)?)
}

/// The sections of a band input: arrays as given, or trace texts read by
/// the core about `input.centre`.
#[cfg(feature = "full")]
fn band_sections(input: &JsValue, radius: f64) -> Result<Vec<Section>, JsError> {
    let list = get(input, "sections");
    let first = Array::is_array(&list).then(|| Array::from(&list).get(0));
    if !first.is_some_and(|s| s.is_object() && !get(&s, "text").is_undefined()) {
        return sections_of(input);
    }
    let centre = match get(input, "centre") {
        c if c.is_undefined() || c.is_null() => None,
        c => Some({
            section_object(&c, "input.centre", &["x", "y"])?;
            ballbar::PlanePoint {
                x: number(&c, "x", "input.centre")?,
                y: number(&c, "y", "input.centre")?,
            }
        }),
    };
    let mut traces = Vec::new();
    for (k, s) in Array::from(&list).iter().enumerate() {
        let what = format!("sections[{k}]");
        section_object(&s, &what, &["y", "text", "run"])?;
        let run = match opt_number(&s, "run", &what)? {
            Some(v) => count_arg(v, &format!("{what}.run"), usize::MAX)?,
            None => 0,
        };
        traces.push(alignment::from_trace::TraceSection {
            y: number(&s, "y", &what)?,
            text: get(&s, "text").as_string().ok_or_else(|| {
                JsError::new(&format!("{what}.text: expected the trace file's text"))
            })?,
            run,
        });
    }
    Ok(alignment::from_trace::sections_from_traces(
        &traces, radius, centre,
    )?)
}
