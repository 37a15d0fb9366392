//! Bindings for [`crate::servo`], [`crate::feed_vector`] and
//! [`crate::best_kffp`]: `frequencyResponse`, `simulateAxis`,
//! `feedVectorTest`, `analyzeFeedVectorTrace`, `bestKffp`,
//! `torqueSaturation`, `traceLayout`, `traceColumns`. Thin: convert, call the core, convert back.

use js_sys::Reflect;
use wasm_bindgen::prelude::*;

use super::args::JsArg;
use super::convert::{
    floats_arg, known_keys, name_arg, object, plain, plain_floats, require_object, string_arg,
    to_js, Obj,
};
#[cfg(feature = "full")]
use super::convert::{trace_arg, TraceArg};
use super::results::JsResult;
use crate::best_kffp::{self, saturation};
use crate::feed_vector::{self, trace_analysis, Condition, FeedVectorResult};
use crate::machine::{self, Machine};
use crate::servo::{response, simulate, AxisParams};

#[wasm_bindgen(typescript_custom_section)]
const TS: &str = r#"
export interface FrequencyResponse { /** [-] |G(jω)| */ magnitude: Float64Array; /** [rad] ∠G(jω) */ phase: Float64Array }
export interface SimulateInput { /** [s] Step. */ dt: number; /** [mm or rad] Command: mm on a linear axis, rad on a rotary one. */ position: Float64Array }
export interface AxisResponse {
  /** [mm or rad] Table position. */ position: Float64Array; /** [mm/s or rad/s] */ velocity: Float64Array;
  /** [N·m] Motor torque (clipped at torqueMax). */ torque: Float64Array; saturated: boolean;
}
export interface KffpSet { /** [%] */ x: number; /** [%] */ y: number; /** [%] */ c: number }
export interface FeedVectorCondition {
  /** [mm] */ rc: number; /** [mm] */ rw: number; /** [rad/s] */ omega: number;
  /** [s] */ accelTime: number; /** [kg·m²] load on C */ j1: number;
  /** [N·m] */ torqueMax?: number; /** [s] */ duration?: number; /** [s] default 0.001 */ dt?: number;
  /** % */ kffp?: KffpSet;
}
export interface FeedVectorSummary {
  /** [rad] */ meanAngleDiff: number; /** [mm] */ halfAmplitude: number; /** [mm] */ radiusDecrease: number;
  /** [N·m] */ peakTorque: number; saturated: boolean; /** [s] */ steadyFrom: number; /** [-] whole periods analysed */ periods: number;
}
export interface FeedVectorSeries {
  /** [s] */ t: Float64Array; /** [mm] */ xCmd: Float64Array; /** [mm] */ yCmd: Float64Array; /** [rad] */ cCmd: Float64Array;
  /** [mm] */ x: Float64Array; /** [mm] */ y: Float64Array; /** [rad] */ c: Float64Array; /** [N·m] */ torqueC: Float64Array;
  /** [mm] ΔR_C (Eq. 5) */ shapeError: Float64Array; /** [rad] α (Eq. 8) */ alpha: Float64Array; /** [rad] β (Eq. 9) */ beta: Float64Array;
  /** [rad] α − β (Eq. 10) */ angleDiff: Float64Array;
  /** [mm] ΔR (Eq. 11) */ radiusError: Float64Array; /** [rad/s] */ omegaC: Float64Array; /** [rad/s] */ omegaL: Float64Array;
}
export interface FeedVectorResult { series: FeedVectorSeries; summary: FeedVectorSummary }
export interface TraceMapping {
  time?: string; x?: string; y?: string; c?: string; torque?: string;
  /** [s/unit] default 1 */ timeScale?: number; /** [mm/unit] default 1 */ linearScale?: number;
  /** [rad/unit] default π/180 */ angleScale?: number; /** [N·m/unit] default 1 */ torqueScale?: number;
  /** [s] start of the commanded motion */ motionStart?: number; relative?: boolean; /** [s] after the motion start */ steadyFrom?: number;
  /** Default true: a unit stated in a column's header scales it; false: the factors above scale every column. */ headerUnits?: boolean;
  /** [N·m] rated torque: reads a torque column in % */ ratedTorque?: number; /** [s] sample period of a file without a time column */ samplePeriod?: number;
}
export interface BestKffpOptions { method?: 'auto' | 'analytic' | 'simulated'; /** [%] */ kMin?: number; /** [%] */ kMax?: number }
export interface BestKffpResult {
  kffp: KffpSet; before: FeedVectorSummary; after: FeedVectorSummary; method: 'analytic' | 'simulated';
  /** [rad] α_th of C (Eq. 17) */ alphaTh: number; /** [rad] α_th − β_th of X (Eq. 19) */ residualX: number; /** [rad] */ residualY: number;
}
export interface SaturationQuery { /** [kg·m²] */ j1: number[]; /** [N·m] C torque limit; absent: the machine's axes.c.torqueMax */ torqueMax?: number; /** [s] */ accelTime: number; /** [mm/min] */ feedAtCuttingPoint: number; /** [s] */ dt?: number;
  /** How the paper's saturation point is read; names in `machinePreset('nmv5000').saturationReadings` (default 'preControlOff'). */
  reading?: 'preControlOff' | 'presetKffp' | 'inertiaOnly' }
export interface SaturationPoint {
  /** [kg·m²] J + J1 */ jTotal: number; /** [rad/s²] */ accelSat: number; /** [rad/s] */ omegaSat: number; /** [mm] */ rcMin: number;
  /** [N·m·s/rad] */ torquePerOmega: number;
}
/** kato Fig. 3: options of identifyPitchError. */
export interface PitchIdentifyOptions { /** [-] */ samples?: number; /** [-] */ maxOrder?: number; /** [rad] */ threshold?: number; /** [-] */ maxPeaks?: number }
/** a·sin(N θ + ψ): amplitude in rad at the table (the additive reading of Eq. 1). */
export interface PitchPeak { /** [-] */ order: number; /** [rad] */ amplitude: number; /** [rad] */ phase: number }
export interface PitchIdentification { /** [-] */ revolutions: number; /** [rad] amplitude per order 0…maxOrder */ spectrum: number[]; peaks: PitchPeak[] }
/** suzuki Table 1 identification: a measured response to a known command (one sample per dt). */
export interface MeasuredTrace {
  /** [s] */ dt: number; /** [mm or rad] */ command: number[]; /** [mm or rad] */ position: number[];
  /** [N·m] needed to identify J */ torque?: number[];
}
export interface IdentifiedAxis {
  axis: AxisParams; jIdentified: boolean; /** [mm or rad] */ rmsPosition: number; /** [N·m] */ rmsTorque: number; /** [-] */ iterations: number;
}
"#;

/// A machine given as a preset name or as a full machine object.
#[cfg(feature = "full")]
fn machine_arg(value: JsValue) -> Result<Machine, JsError> {
    if value.is_string() {
        return Ok(machine::preset(&name_arg(&value, "machine")?)?);
    }
    object(value, "machine")
}

/// The embed module's machine: a preset name only, among the presets with
/// a torque-saturation reading ([`machine::saturation_preset`]), so that
/// neither the other presets nor a machine's deserialiser are linked.
#[cfg(not(feature = "full"))]
fn machine_arg(value: JsValue) -> Result<Machine, JsError> {
    let name = name_arg(&value, "machine")?;
    Ok(machine::saturation_preset(&name)?)
}

/// `G(jω)` of `axis` at each ω (rad/s): magnitude and phase (rad).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = frequencyResponse, unchecked_return_type = "FrequencyResponse")]
pub fn frequency_response(
    #[wasm_bindgen(unchecked_param_type = "AxisParams")] axis: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array | number[]")] omegas: JsValue,
) -> Result<JsValue, JsError> {
    let axis: AxisParams = object(axis, "axis")?;
    let omegas = floats_arg(&omegas, "omegas")?;
    let r = response::frequency_response(&axis, &omegas)?;
    Ok(Obj::new()
        .arr("magnitude", &r.magnitude)
        .arr("phase", &r.phase)
        .build())
}

/// Fixed-step simulation of one axis following `input.position`.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = simulateAxis, unchecked_return_type = "AxisResponse")]
pub fn simulate_axis(
    #[wasm_bindgen(unchecked_param_type = "AxisParams")] axis: JsValue,
    #[wasm_bindgen(unchecked_param_type = "SimulateInput")] input: JsValue,
) -> Result<JsValue, JsError> {
    let axis: AxisParams = object(axis, "axis")?;
    require_object(&input, "input")?;
    let input = plain(&input, "input")?;
    known_keys(&input, &["dt", "position"], "input")?;
    let dt = Reflect::get(&input, &JsValue::from_str("dt"))
        .ok()
        .and_then(|v| v.as_f64())
        .ok_or_else(|| JsError::new("input.dt: expected the time step in s (a number)"))?;
    let position = Reflect::get(&input, &JsValue::from_str("position")).unwrap_or_default();
    let command = plain_floats(&position, "input.position")?;
    let r = simulate::simulate_axis(&axis, dt, &command)?;
    Ok(Obj::new()
        .arr("position", &r.position)
        .arr("velocity", &r.velocity)
        .arr("torque", &r.torque)
        .flag("saturated", r.saturated)
        .build())
}

fn result_js(r: &FeedVectorResult) -> Result<JsValue, JsError> {
    let s = &r.series;
    let series = Obj::new()
        .arr("t", &s.t)
        .arr("xCmd", &s.x_cmd)
        .arr("yCmd", &s.y_cmd)
        .arr("cCmd", &s.c_cmd)
        .arr("x", &s.x)
        .arr("y", &s.y)
        .arr("c", &s.c)
        .arr("torqueC", &s.torque_c)
        .arr("shapeError", &s.shape_error)
        .arr("alpha", &s.alpha)
        .arr("beta", &s.beta)
        .arr("angleDiff", &s.angle_diff)
        .arr("radiusError", &s.radius_error)
        .arr("omegaC", &s.omega_c)
        .arr("omegaL", &s.omega_l)
        .build();
    Ok(Obj::new()
        .val("series", series)
        .ser("summary", &r.summary)?
        .build())
}

/// Simulates the constant-feed-speed-vector test (suzuki §2.3, §3).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = feedVectorTest, unchecked_return_type = "FeedVectorResult")]
pub fn feed_vector_test(
    #[wasm_bindgen(unchecked_param_type = "MachinePreset | string")] machine: JsValue,
    #[wasm_bindgen(unchecked_param_type = "FeedVectorCondition")] condition: JsValue,
) -> Result<JsValue, JsError> {
    let m = machine_arg(machine)?;
    let cond: Condition = object(condition, "condition")?;
    result_js(
        &feed_vector::feed_vector_test(&m, &cond).map_err(|e| JsError::new(&e.user_message()))?,
    )
}

/// Analyses a measured CSV/TSV trace of the test.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = analyzeFeedVectorTrace, unchecked_return_type = "FeedVectorResult")]
pub fn analyze_feed_vector_trace(
    #[wasm_bindgen(unchecked_param_type = "string | Uint8Array")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "FeedVectorCondition")] condition: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "TraceMapping")] mapping: JsValue,
) -> Result<JsValue, JsError> {
    let trace = trace_arg(&text, "text")?;
    let cond: Condition = object(condition, "condition")?;
    let map: trace_analysis::ColumnMap = if mapping.is_undefined() || mapping.is_null() {
        trace_analysis::ColumnMap::default()
    } else {
        object(mapping, "mapping")?
    };
    result_js(&analyze(&trace, &cond, &map)?)
}

/// The feed-vector analysis of a trace given as text or bytes.
#[cfg(feature = "full")]
fn analyze(
    trace: &TraceArg,
    cond: &Condition,
    map: &trace_analysis::ColumnMap,
) -> Result<FeedVectorResult, JsError> {
    match trace {
        TraceArg::Text(t) => trace_analysis::analyze_trace(t, cond, map),
        TraceArg::Bytes(b) => trace_analysis::analyze_trace_bytes(b, cond, map),
    }
    .map_err(|e| JsError::new(&e.user_message()))
}

/// The Best K_FFP per axis (Eq. 20), checked by simulation.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = bestKffp, unchecked_return_type = "BestKffpResult")]
pub fn best_kffp(
    #[wasm_bindgen(unchecked_param_type = "MachinePreset | string")] machine: JsValue,
    #[wasm_bindgen(unchecked_param_type = "FeedVectorCondition")] condition: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "BestKffpOptions")] options: JsValue,
) -> Result<JsValue, JsError> {
    let m = machine_arg(machine)?;
    let cond: Condition = object(condition, "condition")?;
    let opts: best_kffp::Options = if options.is_undefined() || options.is_null() {
        best_kffp::Options::default()
    } else {
        object(options, "options")?
    };
    to_js(
        &best_kffp::best_kffp(&m, &cond, &opts).map_err(|e| match e {
            best_kffp::BestKffpError::FeedVector(f) => JsError::new(&f.user_message()),
            other => JsError::from(other),
        })?,
    )
}

/// Torque-saturation limits of the C axis per load (Figs. 17, 21).
#[wasm_bindgen(js_name = torqueSaturation, unchecked_return_type = "SaturationPoint[]")]
pub fn torque_saturation(
    #[wasm_bindgen(unchecked_param_type = "MachinePreset | string")] machine: JsValue,
    #[wasm_bindgen(unchecked_param_type = "SaturationQuery")] query: JsValue,
) -> Result<JsValue, JsError> {
    let m = machine_arg(machine)?;
    let q = saturation::SaturationQuery::arg(query, "query")?;
    saturation::torque_saturation(&m, &q)?.js()
}

/// The inertia J of one axis of a machine (kg·m²; a preset name or a
/// machine object, as `torqueSaturation` takes it): what a caller subtracts
/// from a total J + J1 to get the load J1 the query takes.
#[wasm_bindgen(js_name = axisInertia)]
pub fn axis_inertia(
    #[wasm_bindgen(unchecked_param_type = "MachinePreset | string")] machine: JsValue,
    #[wasm_bindgen(unchecked_param_type = "string")] axis: JsValue,
) -> Result<f64, JsError> {
    let m = machine_arg(machine)?;
    let axis = name_arg(&axis, "axis")?;
    match m.axes.get(axis.as_str()) {
        Some(a) => Ok(a.j),
        None => Err(JsError::new(&format!(
            "axis: machine '{}' has no axis '{}'; its axes: {}",
            m.name,
            crate::budget::clip(&axis, 20),
            m.axes
                .keys()
                .map(String::as_str)
                .collect::<Vec<_>>()
                .join(", ")
        ))),
    }
}

#[cfg(feature = "full")]
/// kato Fig. 3: the pitch-error harmonics of a rotary axis from its error
/// trace (commanded table angle and error, rad), by Fourier analysis.
#[wasm_bindgen(js_name = identifyPitchError, unchecked_return_type = "PitchIdentification")]
pub fn identify_pitch_error(
    #[wasm_bindgen(unchecked_param_type = "Float64Array | number[]")] angle: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array | number[]")] error: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "PitchIdentifyOptions")] options: JsValue,
) -> Result<JsValue, JsError> {
    let o: crate::servo::pitch_identify::PitchIdentifyOptions =
        if options.is_undefined() || options.is_null() {
            Default::default()
        } else {
            object(options, "options")?
        };
    let (angle, error) = (floats_arg(&angle, "angle")?, floats_arg(&error, "error")?);
    to_js(&crate::servo::pitch_identify::identify_pitch_error(
        &angle, &error, &o,
    )?)
}

#[cfg(feature = "full")]
/// suzuki Table 1: J, C, Kvp and Kpp of `initial` fitted to a measured
/// trace by least squares against the simulation.
#[wasm_bindgen(js_name = identifyAxis, unchecked_return_type = "IdentifiedAxis")]
pub fn identify_axis(
    #[wasm_bindgen(unchecked_param_type = "AxisParams")] initial: JsValue,
    #[wasm_bindgen(unchecked_param_type = "MeasuredTrace")] trace: JsValue,
) -> Result<JsValue, JsError> {
    let a: AxisParams = object(initial, "initial")?;
    let t: crate::servo::identify::MeasuredTrace = object(trace, "trace")?;
    to_js(&crate::servo::identify::identify_axis(&a, &t)?)
}

#[wasm_bindgen(typescript_custom_section)]
const TS_COLUMNS: &str = r#"
/** A trace's columns: the name as written, the name without its unit, and the unit it states (s, ms, us, mm, um, m, deg, rad, n·m) or null. */
export interface TraceColumn { name: string; bare: string; unit: string | null }
"#;

#[wasm_bindgen(typescript_custom_section)]
const TS_LAYOUT: &str = r#"
/** Options of traceLayout (the core's tolerant reader). */
export interface TraceReadOptions { /** [s] sample period of a file without a time column: a time column is generated */ samplePeriod?: number; /** [N·m] rated torque: converts a torque column in % */ ratedTorque?: number }
export type TraceQuantity = 'time' | 'length' | 'angle' | 'torque' | 'percent';
/** A unit a header may state. */
export interface TraceUnit { code: string; quantity: TraceQuantity; /** [s, mm, rad or N·m per unit; 0.01 for %] factor to the core unit */ factor: number }
/** What one column was read as. */
export interface TraceColumnLayout {
  name: string; bare: string; /** [-] 1-based field in the file, 0 for a generated column */ field: number; kind: 'numeric' | 'text' | 'generated';
  unit: string | null; quantity: TraceQuantity | null; /** [s, mm, rad or N·m per unit] null without a stated unit */ factor: number | null; coreUnit: string | null; note: string | null;
  /** what the import named by traceLayout's purpose reads this column as when its mapping leaves it out; null otherwise */
  role: 'time' | 'x' | 'y' | 'c' | 'torque' | 'angle' | 'deviation' | 'direction' | null;
}
/** Which import a layout preview is for: its roles mark the columns it reads by default. */
export type TracePurpose = 'feedVector' | 'ballbar';
/** One line above the header, as a key/value pair. */
export interface TraceMeta { /** [-] 1-based line (0: a .mat file's variable) */ line: number; key: string; value: string }
/** How the core read a trace: the page's layout preview and unit menus. */
export interface TraceLayout {
  /** which layout was read: a delimited table, or a control's or instrument's own export */
  format: 'delimited' | 'halsampler' | 'halscope' | 'twincatScope' | 'sinumerikTrace' | 'matV5';
  delimiter: 'tab' | ';' | ',' | 'spaces' | 'none'; decimalComma: boolean; /** [-] 1-based line, null: headerless */ headerLine: number | null;
  /** [-] 1-based line */ firstDataLine: number; /** [-] data rows */ rows: number; columns: TraceColumnLayout[]; metadata: TraceMeta[]; notes: string[]; units: TraceUnit[];
}
"#;

#[cfg(feature = "full")]
/// How the core's tolerant reader reads a trace (text, or a `.mat`
/// capture's bytes as a `Uint8Array`): the layout recognised, delimiter, decimal
/// separator, header line, metadata, each column's kind, unit and factor
/// to core units, and notes in words; throws with the cause and the first
/// offending line.
#[wasm_bindgen(js_name = traceLayout, unchecked_return_type = "TraceLayout")]
pub fn trace_layout(
    #[wasm_bindgen(unchecked_param_type = "string | Uint8Array")] text: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "TraceReadOptions")] options: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "TracePurpose")] purpose: JsValue,
) -> Result<JsValue, JsError> {
    let trace = trace_arg(&text, "text")?;
    let purpose = if purpose.is_undefined() || purpose.is_null() {
        None
    } else {
        Some(name_arg(&purpose, "purpose")?)
    };
    let opts: crate::trace::ReadOptions = if options.is_undefined() || options.is_null() {
        Default::default()
    } else {
        object(options, "options")?
    };
    let read = match &trace {
        TraceArg::Text(text) => {
            crate::budget::check_text("trace", text)?;
            crate::trace::read_table(text, &opts)?
        }
        TraceArg::Bytes(bytes) if crate::trace::mat::is_mat(bytes) => {
            crate::trace::read_bytes(bytes, &opts)?
        }
        TraceArg::Bytes(bytes) => {
            let text = String::from_utf8_lossy(bytes);
            crate::budget::check_text("trace", &text)?;
            crate::trace::read_table(&text, &opts)?
        }
    };
    let mut read = read;
    match purpose.as_deref() {
        None => {}
        Some("feedVector") => trace_analysis::roles(&mut read),
        Some("ballbar") => crate::ballbar::trace_import::roles(&mut read),
        Some(other) => {
            return Err(JsError::new(&format!(
                "purpose: '{}' is not one of 'feedVector', 'ballbar'",
                other
            )))
        }
    }
    to_js(&read.layout)
}

#[cfg(feature = "full")]
/// The numeric columns of a trace in any layout `traceLayout` reads, and
/// the unit each header states (text columns left out); throws
/// for a file that is not a text trace ("this is not a text trace (it
/// looks like a PNG image)") or a malformed table (line and column).
#[wasm_bindgen(js_name = traceColumns, unchecked_return_type = "TraceColumn[]")]
pub fn trace_columns(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
) -> Result<JsValue, JsError> {
    let text: &str = &string_arg(&text, "text")?;
    crate::budget::check_text("trace", text)?;
    // The tolerant reader every import uses (delimiters, decimal commas,
    // text columns, the controls' layouts), not the strict CSV table.
    let table = crate::trace::read_table(text, &crate::trace::ReadOptions::default())?.table;
    let out = js_sys::Array::new();
    for n in &table.names {
        let (bare, unit) = crate::trace::name_unit(n);
        let unit = unit.map_or(JsValue::NULL, JsValue::from_str);
        out.push(
            &Obj::new()
                .val("name", JsValue::from_str(n))
                .val("bare", JsValue::from_str(&bare))
                .val("unit", unit)
                .build(),
        );
    }
    Ok(out.into())
}

#[cfg(feature = "full")]
#[wasm_bindgen(typescript_custom_section)]
const TS_KFFP_TRACE: &str = r#"
/** bestKffpFromTrace options: the search of bestKffp, and whether to identify X and Y from the trace first. */
export interface TraceKffpOptions extends BestKffpOptions { identify?: boolean }
export interface TraceIdentifiedAxis { axis: 'x' | 'y'; params: AxisParams; /** [mm] */ rmsPosition: number }
/** The recommendation from a measured constant-feed-speed-vector trace (suzuki §4.7, anchored on the measurement). */
export interface TraceKffpResult {
  /** [%] the set the trace was measured with */ measuredWith: KffpSet; /** [%] recommended */ kffp: KffpSet;
  measured: FeedVectorSummary; modelBefore: FeedVectorSummary; modelAfter: FeedVectorSummary;
  /** [rad] measured − model mean α − β at the measured set */ mismatch: number;
  /** [rad] predicted mean α − β after */ predictedMeanAngleDiff: number; /** [mm] predicted shape-error half amplitude after */ predictedHalfAmplitude: number;
  method: 'analytic' | 'simulated'; identified: TraceIdentifiedAxis[];
}
"#;

/// Best K_FFP from a measured constant-feed-speed-vector trace: the trace
/// is analysed (`analyzeFeedVectorTrace`), then the recommendation is
/// anchored on it (`condition.kffp` = the set it was measured with).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = bestKffpFromTrace, unchecked_return_type = "TraceKffpResult")]
pub fn best_kffp_from_trace(
    #[wasm_bindgen(unchecked_param_type = "MachinePreset | string")] machine: JsValue,
    #[wasm_bindgen(unchecked_param_type = "FeedVectorCondition")] condition: JsValue,
    #[wasm_bindgen(unchecked_param_type = "string | Uint8Array")] text: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "TraceMapping")] mapping: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "TraceKffpOptions")] options: JsValue,
) -> Result<JsValue, JsError> {
    let m = machine_arg(machine)?;
    let trace = trace_arg(&text, "text")?;
    let cond: Condition = object(condition, "condition")?;
    let map: trace_analysis::ColumnMap = if mapping.is_undefined() || mapping.is_null() {
        trace_analysis::ColumnMap::default()
    } else {
        object(mapping, "mapping")?
    };
    let opts: best_kffp::TraceOptions = if options.is_undefined() || options.is_null() {
        best_kffp::TraceOptions::default()
    } else {
        object(options, "options")?
    };
    let trace = analyze(&trace, &cond, &map)?;
    to_js(
        &best_kffp::best_kffp_from_trace(&m, &cond, &trace, &opts).map_err(|e| match e {
            best_kffp::BestKffpError::FeedVector(f) => JsError::new(&f.user_message()),
            other => JsError::from(other),
        })?,
    )
}
