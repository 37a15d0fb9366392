//! Bindings for [`crate::toolpath`] and [`crate::compensate::reverse`]
//! (qiu §4-1 to §4-3): `parseNc`, `simulateToolPath`, `radiusReduction`,
//! `identifyAccDec`, `reverseCompensate`, `toolpathExample`.

use serde::Serialize;
use wasm_bindgen::prelude::*;

use super::convert::{from_js, object, string_arg, to_js, Obj};
use crate::compensate::reverse::{reverse_compensate, ReverseConfig};
use crate::nc::program::{parse, parse_all, ParseOptions, Segment, Warning};
use crate::nc::summary::{summarize, Summary};
use crate::nc::NcError;
use crate::toolpath::identify::{
    identify_acc_dec as identify, radius_reduction as eq3, CircleLoss,
};
use crate::toolpath::{example, SimConfig, Simulation};

#[wasm_bindgen(typescript_custom_section)]
const TS: &str = r#"
export interface Pose { x: number; y: number; z: number; a: number; b: number; c: number }
export type NcMotion =
  | { type: 'rapid' } | { type: 'linear' }
  | { type: 'arc'; center: [number, number, number]; radius: number; plane: 'XY' | 'ZX' | 'YZ'; sweep: number; rForm: boolean }
  | { type: 'dwell'; seconds: number };
/** One motion segment; mm, degrees for a/b/c, feed in mm/min. */
export interface NcSegment { block: number | null; line: number; motion: NcMotion; start: Pose; end: Pose; feed: number; fixed: boolean }
export interface NcWarning { line: number; column: number; message: string }
/** Reading options; an unknown key is an error naming it. dwellP: how G4 P is read ('auto': with a decimal point seconds, without milliseconds; 'milliseconds': Fanuc; 'seconds': LinuxCNC/Grbl). skipBlockDelete (default true): skip '/' blocks. cAxis (default false): C is a rotary axis; otherwise C on G01 is a Fanuc chamfer. */
export interface NcParseOptions { dwellP?: 'auto' | 'milliseconds' | 'seconds'; skipBlockDelete?: boolean; cAxis?: boolean; start?: Pose }
export interface NcWarningGroup { kind: string; count: number; lines: number[]; indices: number[] }
/** Lengths mm, motionTime s (Σ length/feed, rapids at rapidFeed mm/min, dwells; no acc/dec). */
export interface NcSummary {
  bboxMin: [number, number, number] | null; bboxMax: [number, number, number] | null;
  totalLength: number; cuttingLength: number; arcs: number; lines: number; rapids: number; dwells: number;
  units: string; planes: string[]; motionTime: number; rapidFeed: number; warnings: NcWarningGroup[];
}
export interface ParsedNc { segments: NcSegment[]; warnings: NcWarning[]; summary: NcSummary }
export interface NcCheck { errors: NcWarning[]; truncated: boolean; warnings: NcWarning[]; summary: NcSummary | null }
/** tA and T in s (T one value or [Tx, Ty, Tz]), dt in s, rapidFeed in mm/min, feedOverride as a fraction; dwellExactStop: every G4 first waits tA + 5·max T (exact stop, in-position check). */
export interface ToolPathConfig { tA?: number; T?: number | [number, number, number]; dt?: number; rapidFeed?: number; feedOverride?: number; dwellExactStop?: boolean }
export interface SegmentStats {
  segment: number; line: number; kind: 'line' | 'arc' | 'rapid'; length: number; radius: number;
  maxErrorUm: number; meanDeviation: number | null; halfDeviation: [number | null, number | null]; samples: number;
}
/** Time series (Float64Array, mm, mm/s, µm) and summary of one simulation. */
export interface ToolPathSimulation {
  t: Float64Array;
  cmdX: Float64Array; cmdY: Float64Array; cmdZ: Float64Array;
  simX: Float64Array; simY: Float64Array; simZ: Float64Array;
  nearX: Float64Array; nearY: Float64Array; nearZ: Float64Array;
  velCmdX: Float64Array; velCmdY: Float64Array; velCmdZ: Float64Array;
  velSimX: Float64Array; velSimY: Float64Array; velSimZ: Float64Array;
  errorUm: Float64Array;
  maxErrorUm: number; maxErrorTime: number; maxErrorLine: number;
  motionTime: number; nominalTime: number;
  segments: SegmentStats[]; warnings: NcWarning[];
}
export interface RadiusReductionInput { feed: number; radius: number; tA: number; T: number }
export interface CircleLoss { feed: number; radius: number; radiusLoss: number }
export interface AccDec { tA: number; T: number; residual: number }
export interface ReverseConfig extends ToolPathConfig { dwell?: number; iterations?: number }
export interface CompSummary { maxErrorUm: number; motionTime: number }
export interface SegmentChange { segment: number; line: number; kind: string; radiusBefore: number; radiusAfter: number; endShiftUm: number }
export interface ReverseCompensation {
  nc: string; before: CompSummary; after: CompSummary; segments: SegmentChange[];
  dwells: { afterLine: number; seconds: number }[]; historyUm: number[];
  beforeSim: ToolPathSimulation; afterSim: ToolPathSimulation;
}
"#;

#[derive(Serialize)]
struct Parsed<'a> {
    segments: &'a [Segment],
    warnings: &'a [Warning],
    summary: Summary,
}

/// Parses an NC program into motion segments and warnings; throws an
/// `Error` naming line and column.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = parseNc, unchecked_return_type = "ParsedNc")]
pub fn parse_nc(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "NcParseOptions | undefined")] options: JsValue,
) -> Result<JsValue, JsError> {
    let text: &str = &string_arg(&text, "text")?;
    let opts = parse_options(options)?;
    let p = parse_all(text, &opts).map_err(|e| JsError::new(&e.to_string()))?;
    let rapid_feed = SimConfig::default().rapid_feed;
    to_js(&Parsed {
        segments: &p.segments,
        warnings: &p.warnings,
        summary: summarize(&p, rapid_feed),
    })
}

fn parse_options(options: JsValue) -> Result<ParseOptions, JsError> {
    if options.is_undefined() || options.is_null() {
        return Ok(ParseOptions::default());
    }
    // serde-wasm-bindgen only reads the keys a struct names, so the core's
    // deny_unknown_fields never sees a misspelt key: check here.
    let keys: std::collections::BTreeMap<String, serde::de::IgnoredAny> =
        object(options.clone(), "options")?;
    if let Some(k) = keys
        .keys()
        .find(|k| !ParseOptions::KEYS.contains(&k.as_str()))
    {
        return Err(JsError::new(&format!(
            "options: unknown key '{k}'; expected one of {}",
            ParseOptions::KEYS.join(", ")
        )));
    }
    from_js(options, "options")
}

#[derive(Serialize)]
struct Checked<'a> {
    errors: &'a [NcError],
    truncated: bool,
    warnings: &'a [Warning],
    summary: Option<Summary>,
}

#[cfg(feature = "full")]
/// Checks an NC program without throwing on program errors: every error
/// (line, column, message; up to 100), or the warnings and the summary.
/// Throws only for a bad `text` or `options` argument.
#[wasm_bindgen(js_name = checkNc, unchecked_return_type = "NcCheck")]
pub fn check_nc(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "NcParseOptions | undefined")] options: JsValue,
) -> Result<JsValue, JsError> {
    let text: &str = &string_arg(&text, "text")?;
    let opts = parse_options(options)?;
    match parse_all(text, &opts) {
        Ok(p) => to_js(&Checked {
            errors: &[],
            truncated: false,
            warnings: &p.warnings,
            summary: Some(summarize(&p, SimConfig::default().rapid_feed)),
        }),
        Err(e) => to_js(&Checked {
            errors: &e.errors,
            truncated: e.truncated,
            warnings: &[],
            summary: None,
        }),
    }
}

fn sim_obj(s: &Simulation, warnings: &[Warning]) -> Result<JsValue, JsError> {
    let err_um: Vec<f64> = s.error.iter().map(|e| e * 1e3).collect();
    Ok(Obj::new()
        .arr("t", &s.t)
        .arr("cmdX", &s.cmd[0])
        .arr("cmdY", &s.cmd[1])
        .arr("cmdZ", &s.cmd[2])
        .arr("simX", &s.sim[0])
        .arr("simY", &s.sim[1])
        .arr("simZ", &s.sim[2])
        .arr("nearX", &s.near[0])
        .arr("nearY", &s.near[1])
        .arr("nearZ", &s.near[2])
        .arr("velCmdX", &s.vel_cmd[0])
        .arr("velCmdY", &s.vel_cmd[1])
        .arr("velCmdZ", &s.vel_cmd[2])
        .arr("velSimX", &s.vel_sim[0])
        .arr("velSimY", &s.vel_sim[1])
        .arr("velSimZ", &s.vel_sim[2])
        .arr("errorUm", &err_um)
        .num("maxErrorUm", s.max_error * 1e3)
        .num("maxErrorTime", s.max_error_time)
        .num("maxErrorLine", s.max_error_line as f64)
        .num("motionTime", s.motion_time)
        .num("nominalTime", s.nominal_time)
        .ser("segments", &s.segments)?
        .ser("warnings", warnings)?
        .build())
}

/// Simulates the program (Eqs. 1–2) and its contour error (§4-2).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = simulateToolPath, unchecked_return_type = "ToolPathSimulation")]
pub fn simulate_tool_path(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolPathConfig")] config: JsValue,
) -> Result<JsValue, JsError> {
    let text: &str = &string_arg(&text, "text")?;
    let cfg: SimConfig = if config.is_undefined() || config.is_null() {
        SimConfig::default()
    } else {
        object(config, "config")?
    };
    let p = parse(text)?;
    let s = crate::toolpath::simulate_program(&p, &cfg)?;
    sim_obj(&s, &p.warnings)
}

#[derive(serde::Deserialize)]
struct Eq3In {
    feed: f64,
    radius: f64,
    #[serde(rename = "tA")]
    t_a: f64,
    #[serde(rename = "T")]
    t: f64,
}

/// Δr of Eq. 3, mm (feed in mm/min, radius in mm, tA and T in s).
#[wasm_bindgen(js_name = radiusReduction)]
pub fn radius_reduction(
    #[wasm_bindgen(unchecked_param_type = "RadiusReductionInput")] input: JsValue,
) -> Result<f64, JsError> {
    let i: Eq3In = object(input, "radiusReduction")?;
    Ok(eq3(i.feed, i.radius, i.t_a, i.t)?)
}

/// Least-squares tA and T from measured circle radius losses (§4-1).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = identifyAccDec, unchecked_return_type = "AccDec")]
pub fn identify_acc_dec(
    #[wasm_bindgen(unchecked_param_type = "CircleLoss[]")] data: JsValue,
) -> Result<JsValue, JsError> {
    let d: Vec<CircleLoss> = from_js(data, "data")?;
    to_js(&identify(&d)?)
}

/// Reverse compensation of the program (§4-3(2)).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = reverseCompensate, unchecked_return_type = "ReverseCompensation")]
pub fn reverse_compensate_js(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ReverseConfig")] config: JsValue,
) -> Result<JsValue, JsError> {
    let text: &str = &string_arg(&text, "text")?;
    let cfg: ReverseConfig = if config.is_undefined() || config.is_null() {
        ReverseConfig::default()
    } else {
        object(config, "config")?
    };
    let c = reverse_compensate(text, &cfg)?;
    Ok(Obj::new()
        .val("nc", JsValue::from_str(&c.nc))
        .ser("before", &c.before)?
        .ser("after", &c.after)?
        .ser("segments", &c.segments)?
        .ser("dwells", &c.dwells)?
        .ser("historyUm", &c.history_um)?
        .val("beforeSim", sim_obj(&c.sim_before, &[])?)
        .val("afterSim", sim_obj(&c.sim_after, &[])?)
        .build())
}

/// The built-in test path resembling qiu Fig. 2: `"arcs"` (43 arcs) or
/// `"lines"` (83 lines).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = toolpathExample)]
pub fn toolpath_example(
    #[wasm_bindgen(unchecked_param_type = "string")] kind: JsValue,
) -> Result<String, JsError> {
    let kind: &str = &string_arg(&kind, "kind")?;
    match kind {
        "arcs" => Ok(example::arc_example()),
        "lines" => Ok(example::line_example()),
        other => Err(JsError::new(&format!(
            "toolpathExample: unknown example '{other}'; expected 'arcs' or 'lines'"
        ))),
    }
}
