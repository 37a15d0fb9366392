//! Bindings for [`crate::toolpath`] and [`crate::compensate::reverse`]
//! (qiu §4-1 to §4-3): `parseNc`, `simulateToolPath`,
//! `simulateToolPathColumns`, `radiusReduction`,
//! `identifyAccDec`, `reverseCompensate`, `toolpathExample`.

use serde::Serialize;
use wasm_bindgen::prelude::*;

use super::args::JsArg;
use super::convert::{
    callback_arg, from_js, from_plain, name_arg, object, plain, plain_list, require_object,
    reserve, string_arg, to_js, Obj, NC_BYTES_PER_TEXT_BYTE, SIM_BYTES_PER_SEGMENT,
};
use crate::compensate::reverse::{reverse_compensate_with, ReverseConfig};
use crate::nc::files::{main_file, parse_files_noting_refusal, parse_files_owned, NcFile};
use crate::nc::program::{Keep, ParseOptions, Program, Segment, ToolRadii, Warning};
use crate::nc::summary::{summarize, Summary};
use crate::nc::{NcError, NcErrors};
use crate::toolpath::identify::{
    identify_acc_dec as identify, radius_reduction as eq3, CircleLoss,
};
use crate::toolpath::{example, SegmentColumns, SimConfig, Simulation};

#[wasm_bindgen(typescript_custom_section)]
const TS: &str = r#"
export interface Pose { /** [mm] */ x: number; /** [mm] */ y: number; /** [mm] */ z: number; /** [deg] */ a: number; /** [deg] */ b: number; /** [deg] */ c: number }
export type NcMotion =
  | { type: 'rapid' } | { type: 'linear' }
  | { type: 'arc'; /** [mm] */ center: [number, number, number]; /** [mm] */ radius: number; plane: 'XY' | 'ZX' | 'YZ'; /** [rad] signed */ sweep: number; rForm: boolean }
  | { type: 'dwell'; seconds: number };
/** One motion segment; mm, degrees for a/b/c, feed in mm/min. */
export interface NcSegment {
  /** [-] index of its block; null for an inserted segment */ block: number | null; /** [-] 1-based source line */ line: number; motion: NcMotion; start: Pose; end: Pose;
  /** [mm/min] */ feed: number; fixed: boolean;
}
/** file: set when the line is in one of the extra `files` (absent: the main program). */
export interface NcWarning { /** [-] 1-based */ line: number; /** [-] 1-based */ column: number; message: string; file?: string }
/** An extra program file holding subprograms (O… M99, G65 macros, o<name> sub … endsub) the main program calls. */
export interface NcFile { name: string; text: string }
/** Reading options; an unknown key is an error naming it. dwellP: how G4 P is read ('auto': with a decimal point seconds, without milliseconds; 'milliseconds': Fanuc; 'seconds': LinuxCNC/Grbl). skipBlockDelete (default true): skip '/' blocks. cAxis (default false): C is a rotary axis; otherwise C on G01 is a Fanuc chamfer. units (default 'mm'): the machine's unit for a program that states none (no G20/G21). */
export interface NcParseOptions { dwellP?: 'auto' | 'milliseconds' | 'seconds'; skipBlockDelete?: boolean; cAxis?: boolean; units?: 'mm' | 'inch'; start?: Pose; files?: NcFile[]; /** [mm or inch] tool radius per D number, in the program's units */ toolRadii?: NcToolRadii }
/** Tool radius per D number for cutter compensation G41/G42, in program units (inch under G20): a map { D1: 3, "8": 0.25 } or a text "D1=3, D8=0.25"; each finite and ≥ 0. Without an entry for a D the simulated path is the programmed path (warned). */
export type NcToolRadii = Record<string, number> | string;
/** One cutter-compensation stretch (G41/G42 … G40). radius: [mm] the tool radius its offset path used; null: the simulated path is the programmed path (warned). */
export interface NcCutterStretch { code: string; side: 'Left' | 'Right'; d: string | null; /** [mm] */ radius: number | null; plane: 'XY' | 'ZX' | 'YZ'; /** [-] */ line: number; /** [-] */ column: number; file?: string }
export interface NcWarningGroup { kind: string; /** [-] */ count: number; /** [-] source lines */ lines: number[]; /** [-] indices into warnings */ indices: number[] }
/** Lengths mm, motionTime s (Σ length/feed, rapids at rapidFeed mm/min, dwells; no acc/dec). */
export interface NcSummary {
  /** [mm] */ bboxMin: [number, number, number] | null; /** [mm] */ bboxMax: [number, number, number] | null;
  /** [mm] */ totalLength: number; /** [mm] */ cuttingLength: number;
  /** [-] */ arcs: number; /** [-] */ lines: number; /** [-] */ rapids: number; /** [-] */ dwells: number;
  units: string; planes: string[]; /** [s] */ motionTime: number; /** [mm/min] */ rapidFeed: number; warnings: NcWarningGroup[];
  cutterCompensation: NcCutterStretch[];
}
export interface ParsedNc { segments: NcSegment[]; warnings: NcWarning[]; summary: NcSummary }
/** notRead: the whole text was refused before any line was read (over the text budget, or not a text file: an image, a PDF, an archive). */
export interface NcCheck { notRead: boolean; errors: NcWarning[]; truncated: boolean; warnings: NcWarning[]; summary: NcSummary | null }
/** tA and T in s (T one value or [Tx, Ty, Tz]), dt in s, rapidFeed in mm/min, feedOverride as a fraction; dwellExactStop: every G4 first waits tA + 5·max T (exact stop, in-position check). */
export interface ToolPathConfig {
  files?: NcFile[]; /** [mm or inch] tool radius per D number, in the program's units */ toolRadii?: NcToolRadii; /** [s] */ tA?: number; /** [s] */ T?: number | [number, number, number]; /** [s] */ dt?: number; /** [mm/min] */ rapidFeed?: number;
  /** [-] fraction */ feedOverride?: number; dwellExactStop?: boolean;
}
export interface SegmentStats {
  /** [-] */ segment: number; /** [-] */ line: number; kind: 'line' | 'arc' | 'rapid'; /** [mm] */ length: number; /** [mm] */ radius: number;
  maxErrorUm: number; /** [mm] */ meanDeviation: number | null; /** [-] */ samples: number;
}
/** Time series (Float64Array, mm, mm/s, µm; sampleSegment a Uint32Array) and summary of one simulation. The series hold every sample when seriesStride is 1; a run of more than 1,000,000 samples keeps, of each seriesStride consecutive samples, the one with the largest contour error (t gives its time). The statistics always use every sample. */
export interface ToolPathSimulation {
  /** [-] samples simulated */ samples: number; /** [-] */ seriesStride: number;
  /** [s] */ t: Float64Array;
  /** [mm] */ cmdX: Float64Array; /** [mm] */ cmdY: Float64Array; /** [mm] */ cmdZ: Float64Array;
  /** [mm] */ simX: Float64Array; /** [mm] */ simY: Float64Array; /** [mm] */ simZ: Float64Array;
  /** [mm] */ nearX: Float64Array; /** [mm] */ nearY: Float64Array; /** [mm] */ nearZ: Float64Array;
  /** [mm/s] */ velCmdX: Float64Array; /** [mm/s] */ velCmdY: Float64Array; /** [mm/s] */ velCmdZ: Float64Array;
  /** [mm/s] */ velSimX: Float64Array; /** [mm/s] */ velSimY: Float64Array; /** [mm/s] */ velSimZ: Float64Array;
  errorUm: Float64Array;
  /** [-] per kept sample, the index of the reference segment its nearest point (nearX…) lies on: an index into parseNc's segments of the same program and options (SegmentStats.segment); for reverseCompensate's beforeSim and afterSim, into the original program's */ sampleSegment: Uint32Array;
  maxErrorUm: number; /** [s] */ maxErrorTime: number; /** [-] */ maxErrorLine: number;
  /** [s] */ motionTime: number; /** [s] */ nominalTime: number;
  segments: SegmentStats[]; warnings: NcWarning[];
}
/** simulateToolPath's per-segment statistics as columns, one typed array per SegmentStats field, index i for the i-th segment with a length; kind: 0 line, 1 arc, 2 rapid; meanDeviation NaN where SegmentStats has null. */
export interface SegmentColumns {
  /** [-] */ segment: Uint32Array; /** [-] */ line: Uint32Array; /** [-] 0 line, 1 arc, 2 rapid */ kind: Uint8Array; /** [mm] */ length: Float64Array; /** [mm] */ radius: Float64Array;
  maxErrorUm: Float64Array; /** [mm] */ meanDeviation: Float64Array; /** [-] */ samples: Uint32Array;
}
/** simulateToolPathColumns: a ToolPathSimulation whose segment statistics are columns (the same numbers; for programs of millions of segments). */
export interface ToolPathSimulationColumns extends Omit<ToolPathSimulation, 'segments'> { segmentColumns: SegmentColumns }
export interface RadiusReductionInput { /** [mm/min] */ feed: number; /** [mm] */ radius: number; /** [s] */ tA: number; /** [s] */ T: number }
export interface CircleLoss { /** [mm/min] */ feed: number; /** [mm] */ radius: number; /** [mm] */ radiusLoss: number }
export interface AccDec { /** [s] */ tA: number; /** [s] */ T: number; /** [mm] RMS of the Δr residuals */ residual: number }
/** dwell (unset: automatic 0.1 s, 0: none); timeBudget: largest motion-time growth as a fraction (default 0.05); dwellP: how G4 P is read, and so how an inserted dwell is written ('auto': P100 whole ms for Fanuc/Haas, G4 P0.1 seconds when the program shows LinuxCNC words; 'seconds': LinuxCNC/Grbl; 'milliseconds': Fanuc); fromLine, toLine: the program's own text lines to compensate, 1-based and inclusive (unset: first, last); every line outside stays byte for byte and its error is not made worse; step: the share of the measured deviation each round corrects; cornerSpikes: two new G1 lines out and back at each sharp corner (see docs/toolpath.md); expand: write the program flat and compensate that when its largest error sits on moves it computes (macros, canned cycles, subprogram bodies; default true; see ReverseCompensation.expanded). */
export interface ReverseConfig extends Omit<ToolPathConfig, 'files' | 'toolRadii'> { /** [s] */ dwell?: number; /** [-] */ iterations?: number; /** [-] fraction */ timeBudget?: number; dwellP?: 'auto' | 'milliseconds' | 'seconds'; /** [-] 1-based line */ fromLine?: number; /** [-] 1-based line */ toLine?: number; /** [-] share of the deviation a correction round corrects, (0, 1] (qiu: 1; default 0.5) */ step?: number; /** corner spikes at sharp corners (default true; false: qiu's radii, vertices and dwells only) */ cornerSpikes?: boolean; /** write flat when the largest error sits on computed moves (default true) */ expand?: boolean }
/** One region (cutting moves between rapids and fixed segments); reason says why it was left unchanged. */
export interface RegionNote {
  /** [-] */ firstLine: number; /** [-] */ lastLine: number; /** [-] */ arcs: number; /** [-] */ lines: number;
  beforeUm: number; afterUm: number; changed: boolean; reason: string;
}
export interface CompSummary { maxErrorUm: number; /** [s] */ motionTime: number }
export interface SegmentChange {
  /** [-] */ segment: number; /** [-] */ line: number; kind: string; /** [mm] */ radiusBefore: number; /** [mm] */ radiusAfter: number; endShiftUm: number;
}
export interface ReverseCompensation {
  nc: string; before: CompSummary; after: CompSummary; segments: SegmentChange[];
  dwells: { /** [-] */ afterLine: number; seconds: number }[];
  /** corner spikes: two new G1 lines after the block on afterLine, out from the corner by depthUm and back */ spikes: { /** [-] */ afterLine: number; depthUm: number }[];
  regions: RegionNote[]; historyUm: number[];
  beforeSim: ToolPathSimulation; afterSim: ToolPathSimulation;
  /** set when the written program is the original text byte for byte: why, in words (the download is then not offered) */ unchanged: string | null;
  /** set when the work budget cut the correction short: what was kept and what to change */ budgetNote: string | null;
  /** set when dwells were written as P in milliseconds without the program saying how its control reads P: what to set for a control that reads seconds */ dwellNote: string | null;
  /** the written program is the original written flat (one block per move, absolute mm) and compensated, because its largest error sat on moves it computes (macros, cycles, subprograms); the lines named in the result are the written program's */ expanded: boolean;
  /** why it was written flat, or why not although its largest error sits on such moves */ expandNote: string | null;
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
    #[wasm_bindgen(unchecked_optional_param_type = "NcParseOptions")] options: JsValue,
) -> Result<JsValue, JsError> {
    let p = parse_args(&text, options)?
        .0
        .map_err(|e| JsError::new(&e.to_string()))?;
    let rapid_feed = SimConfig::default().rapid_feed;
    to_js(&Parsed {
        segments: &p.segments,
        warnings: &p.warnings,
        summary: summarize(&p, rapid_feed),
    })
}

/// Reads `parseNc`/`checkNc`'s arguments and parses: an `Err` for a bad
/// argument, `Ok((Err(_), _))` for the program's own errors, with
/// whether the text was refused as a whole (`checkNc`'s `notRead`).
fn parse_args(
    text: &JsValue,
    options: JsValue,
) -> Result<(Result<Program, NcErrors>, bool), JsError> {
    let text = string_arg(text, "text")?;
    let (files, options) = take_files(options)?;
    let opts = parse_options(options)?;
    reserve_for_nc(&text, &files);
    // the texts are freed once lexed, before the segments are made
    Ok(parse_files_noting_refusal(text, files, &opts, Keep::Motion))
}

/// Reserves the wasm memory reading `text` and `files` will take, in one
/// grow ([`reserve`]).
fn reserve_for_nc(text: &str, files: &[NcFile]) {
    let bytes = text.len() + files.iter().map(|f| f.text.len()).sum::<usize>();
    reserve(bytes.saturating_mul(NC_BYTES_PER_TEXT_BYTE));
}

/// Splits the optional `files` key off an options object: the extra files
/// and the options without it.
fn take_files(options: JsValue) -> Result<(Vec<NcFile>, JsValue), JsError> {
    let (files, rest) = take_key(options, "files")?;
    if files.is_undefined() {
        return Ok((Vec::new(), rest));
    }
    let files: Vec<NcFile> = from_js(files, "files (expected [{ name, text }])")?;
    Ok((files, rest))
}

/// Splits key `name` off an options object (read as plain data): its value
/// (undefined when absent) and a copy of the options without it.
pub(super) fn take_key(options: JsValue, name: &str) -> Result<(JsValue, JsValue), JsError> {
    if !options.is_object() {
        return Ok((JsValue::UNDEFINED, options));
    }
    // Plain data first (no getter or Proxy runs while the key is read).
    let options = plain(&options, "options")?;
    let key = JsValue::from_str(name);
    let value = js_sys::Reflect::get(&options, &key).unwrap_or(JsValue::UNDEFINED);
    if value.is_undefined() {
        return Ok((value, options));
    }
    let rest = js_sys::Object::assign(&js_sys::Object::new(), options.unchecked_ref());
    let _ = js_sys::Reflect::delete_property(&rest, &key);
    Ok((value, rest.into()))
}

/// Index of the main program among several dropped program texts: the
/// first that ends with M2/M30, else the first that is no subprogram.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = ncMainFile)]
pub fn nc_main_file(
    #[wasm_bindgen(unchecked_param_type = "string[]")] texts: JsValue,
) -> Result<usize, JsError> {
    // counted before the texts are copied (1e6 texts took 19 s)
    let texts = plain_list(&texts, "texts", &crate::budget::MAIN_FILE_TEXTS)?;
    let texts: Vec<String> = from_plain(texts, "texts")?;
    let refs: Vec<&str> = texts.iter().map(String::as_str).collect();
    crate::budget::check_texts("texts", refs.iter().copied())?;
    Ok(main_file(&refs))
}

pub(super) fn parse_options(options: JsValue) -> Result<ParseOptions, JsError> {
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
            "options: unknown key '{k}'; expected one of {}, files",
            ParseOptions::KEYS.join(", ")
        )));
    }
    from_js(options, "options")
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct Checked<'a> {
    /// The whole text was refused before any line was read (over the text
    /// budget, or not a text file): the page keeps the program it had.
    not_read: bool,
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
    #[wasm_bindgen(unchecked_optional_param_type = "NcParseOptions")] options: JsValue,
) -> Result<JsValue, JsError> {
    let (read, not_read) = parse_args(&text, options)?;
    check_obj(read, not_read)
}

/// `checkNc`'s result (`NcCheck`) for a program read: `not_read` says
/// whether its errors refused the text as a whole.
pub(super) fn check_obj(
    read: Result<Program, NcErrors>,
    not_read: bool,
) -> Result<JsValue, JsError> {
    match read {
        Ok(p) => to_js(&Checked {
            not_read: false,
            errors: &[],
            truncated: false,
            warnings: &p.warnings,
            summary: Some(summarize(&p, SimConfig::default().rapid_feed)),
        }),
        Err(e) => to_js(&Checked {
            not_read,
            errors: &e.errors,
            truncated: e.truncated,
            warnings: &[],
            summary: None,
        }),
    }
}

fn sim_obj(s: &Simulation, warnings: &[Warning]) -> Result<JsValue, JsError> {
    Ok(series_obj(s)
        .ser("segments", &s.segments)?
        .ser("warnings", warnings)?
        .build())
}

/// Every field of a `ToolPathSimulation` but its `segments` and
/// `warnings`.
fn series_obj(s: &Simulation) -> Obj {
    let err_um: Vec<f64> = s.error.iter().map(|e| e * 1e3).collect();
    Obj::new()
        .num("samples", s.samples as f64)
        .num("seriesStride", s.series_stride as f64)
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
        .indices("sampleSegment", &s.segment)
        .num("maxErrorUm", s.max_error * 1e3)
        .num("maxErrorTime", s.max_error_time)
        .num("maxErrorLine", s.max_error_line as f64)
        .num("motionTime", s.motion_time)
        .num("nominalTime", s.nominal_time)
}

/// The `SegmentColumns` object: one typed array per field.
fn columns_obj(c: &SegmentColumns) -> JsValue {
    Obj::new()
        .indices("segment", &c.segment)
        .indices("line", &c.line)
        .val("kind", js_sys::Uint8Array::from(c.kind.as_slice()).into())
        .arr("length", &c.length)
        .arr("radius", &c.radius)
        .arr("maxErrorUm", &c.max_error_um)
        .arr("meanDeviation", &c.mean_deviation)
        .indices("samples", &c.samples)
        .build()
}

/// `onProgress(fraction, stage)` as a Rust callback: `false` from it
/// cancels; no callback never cancels.
#[cfg(feature = "full")]
fn js_progress(cb: &Option<js_sys::Function>) -> impl FnMut(f64, &str) -> bool + '_ {
    move |f: f64, stage: &str| match cb {
        Some(cb) => {
            super::convert::progress(cb, f, stage).is_none_or(|v| v.as_bool() != Some(false))
        }
        None => true,
    }
}

/// Simulates the program (Eqs. 1–2) and its contour error (§4-2).
/// `onProgress(fraction, 'simulating')` is called every 262,144 samples;
/// returning `false` cancels.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = simulateToolPath, unchecked_return_type = "ToolPathSimulation")]
pub fn simulate_tool_path(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolPathConfig")] config: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "Function | null")] on_progress: JsValue,
) -> Result<JsValue, JsError> {
    let (p, cfg, on_progress) = sim_args(text, config, on_progress, SIM_BYTES_PER_SEGMENT)?;
    let mut progress = js_progress(&on_progress);
    let s = crate::toolpath::simulate_with_progress(&p.segments, &p.segments, &cfg, &mut |f| {
        progress(f, "simulating")
    })?;
    sim_obj(&s, &p.warnings)
}

/// As `simulateToolPath`, with the per-segment statistics as columns
/// (`segmentColumns`, typed arrays) instead of one object each: the same
/// numbers, for programs of millions of segments.
#[cfg(feature = "full")]
#[wasm_bindgen(
    js_name = simulateToolPathColumns,
    unchecked_return_type = "ToolPathSimulationColumns"
)]
pub fn simulate_tool_path_columns(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolPathConfig")] config: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "Function | null")] on_progress: JsValue,
) -> Result<JsValue, JsError> {
    let (p, cfg, on_progress) = sim_args(text, config, on_progress, 0)?;
    columns_sim(p, &cfg, &on_progress)
}

/// Simulates a program read (its blocks dropped) and gives
/// `simulateToolPathColumns`'s result.
#[cfg(feature = "full")]
pub(super) fn columns_sim(
    mut p: Program,
    cfg: &SimConfig,
    on_progress: &Option<js_sys::Function>,
) -> Result<JsValue, JsError> {
    let mut progress = js_progress(on_progress);
    // The segments are dropped once the timed command and the path are built.
    let segments = std::mem::take(&mut p.segments);
    let (s, columns) =
        crate::toolpath::simulate_columns_owned(segments, cfg, &mut |f| progress(f, "simulating"))?;
    Ok(series_obj(&s)
        .val("segmentColumns", columns_obj(&columns))
        .ser("warnings", &p.warnings)?
        .build())
}

/// Reads a tool-path simulation's arguments and parses the program: the
/// program (its blocks and text dropped: the simulation needs only the
/// segments), the config and the progress callback. The wasm memory the
/// simulation will take, `bytes_per_segment` per segment, is reserved
/// (none for `simulateToolPathColumns`: its large blocks, the timed
/// command, the path and the columns, each grow the memory in one step,
/// and a reservation only left the 2 M-line program's memory at 2,094
/// instead of 1,708 MiB, at 6.3 instead of 5.9 s CPU).
fn sim_args(
    text: JsValue,
    config: JsValue,
    on_progress: JsValue,
    bytes_per_segment: usize,
) -> Result<(Program, SimConfig, Option<js_sys::Function>), JsError> {
    let text = string_arg(&text, "text")?;
    let (files, config) = take_files(config)?;
    let (opts, cfg) = sim_config(config)?;
    let on_progress = callback_arg(on_progress, "onProgress")?;
    reserve_for_nc(&text, &files);
    // The texts are freed once lexed, the blocks once run: neither is
    // simulated, and their memory goes to the simulation.
    let p = parse_files_owned(text, files, &opts, Keep::Motion);
    Ok((sim_program(p, bytes_per_segment)?, cfg, on_progress))
}

/// A tool-path config without its `files`: how the program is read (its
/// `toolRadii`) and the simulation's config.
pub(super) fn sim_config(config: JsValue) -> Result<(ParseOptions, SimConfig), JsError> {
    let (radii, config) = take_key(config, "toolRadii")?;
    let cfg: SimConfig = if config.is_undefined() || config.is_null() {
        SimConfig::default()
    } else {
        object(config, "config")?
    };
    let opts = ParseOptions {
        tool_radii: if radii.is_undefined() {
            ToolRadii::default()
        } else {
            from_js(radii, "config.toolRadii")?
        },
        ..ParseOptions::default()
    };
    Ok((opts, cfg))
}

/// The program to simulate, read: its first error thrown, its blocks
/// dropped, and `bytes_per_segment` reserved per segment.
pub(super) fn sim_program(
    read: Result<Program, NcErrors>,
    bytes_per_segment: usize,
) -> Result<Program, JsError> {
    let mut p = read.map_err(|e| JsError::new(&e.first().to_string()))?;
    drop(std::mem::take(&mut p.blocks));
    if p.segments.len() <= crate::budget::MAX_TOOLPATH_SEGMENTS {
        reserve(p.segments.len() * bytes_per_segment);
    }
    Ok(p)
}

/// The input of `radiusReduction` (read in [`super::args`]).
#[derive(serde::Deserialize)]
pub(crate) struct Eq3In {
    pub(crate) feed: f64,
    pub(crate) radius: f64,
    #[serde(rename = "tA")]
    pub(crate) t_a: f64,
    #[serde(rename = "T")]
    pub(crate) t: f64,
}

/// Δr of Eq. 3, mm (feed in mm/min, radius in mm, tA and T in s).
#[wasm_bindgen(js_name = radiusReduction)]
pub fn radius_reduction(
    #[wasm_bindgen(unchecked_param_type = "RadiusReductionInput")] input: JsValue,
) -> Result<f64, JsError> {
    let i = Eq3In::arg(input, "radiusReduction")?;
    Ok(eq3(i.feed, i.radius, i.t_a, i.t)?)
}

/// Least-squares tA and T from measured circle radius losses (§4-1).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = identifyAccDec, unchecked_return_type = "AccDec")]
pub fn identify_acc_dec(
    #[wasm_bindgen(unchecked_param_type = "CircleLoss[]")] data: JsValue,
) -> Result<JsValue, JsError> {
    // counted before the rows are copied (1e6 rows took 12 s to refuse)
    let data = plain_list(&data, "data", &crate::budget::ACCDEC_CIRCLES)?;
    let d: Vec<CircleLoss> = from_plain(data, "data")?;
    to_js(&identify(&d)?)
}

/// Reverse compensation of the program (§4-3(2)). `onProgress(fraction,
/// stage)` is called between simulations; returning `false` cancels.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = reverseCompensate, unchecked_return_type = "ReverseCompensation")]
pub fn reverse_compensate_js(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ReverseConfig")] config: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "Function | null")] on_progress: JsValue,
) -> Result<JsValue, JsError> {
    let text: &str = &string_arg(&text, "text")?;
    let (files, config) = take_files(config)?;
    if !files.is_empty() {
        return Err(JsError::new(
            "reverseCompensate rewrites one program text: paste the subprograms it calls after M30 in the same text (config.files is not read here)",
        ));
    }
    let cfg: ReverseConfig = if config.is_undefined() || config.is_null() {
        ReverseConfig::default()
    } else {
        require_object(&config, "config")?;
        let config = plain(&config, "config")?;
        if !js_sys::Reflect::get(&config, &JsValue::from_str("toolRadii"))
            .unwrap_or(JsValue::UNDEFINED)
            .is_undefined()
        {
            return Err(JsError::new(
                "config.toolRadii: reverseCompensate corrects the programmed path and does not offset it for cutter compensation; leave toolRadii out (the G41/G42 offset is applied by the control to the corrected program)",
            ));
        }
        from_plain(config, "config")?
    };
    let on_progress = callback_arg(on_progress, "onProgress")?;
    let mut progress = js_progress(&on_progress);
    reserve_for_nc(text, &[]);
    let c = reverse_compensate_with(text, &cfg, &mut progress)?;
    Ok(Obj::new()
        .val("nc", JsValue::from_str(&c.nc))
        .ser("before", &c.before)?
        .ser("after", &c.after)?
        .ser("segments", &c.segments)?
        .ser("dwells", &c.dwells)?
        .ser("spikes", &c.spikes)?
        .ser("regions", &c.regions)?
        .ser("historyUm", &c.history_um)?
        .val("beforeSim", sim_obj(&c.sim_before, &[])?)
        .val("afterSim", sim_obj(&c.sim_after, &[])?)
        .val(
            "unchanged",
            c.unchanged
                .as_deref()
                .map_or(JsValue::NULL, JsValue::from_str),
        )
        .val(
            "budgetNote",
            c.budget_note
                .as_deref()
                .map_or(JsValue::NULL, JsValue::from_str),
        )
        .val(
            "dwellNote",
            c.dwell_note
                .as_deref()
                .map_or(JsValue::NULL, JsValue::from_str),
        )
        .val("expanded", JsValue::from_bool(c.expanded))
        .val(
            "expandNote",
            c.expand_note
                .as_deref()
                .map_or(JsValue::NULL, JsValue::from_str),
        )
        .build())
}

/// The built-in test path resembling qiu Fig. 2: `"arcs"` (43 arcs) or
/// `"lines"` (83 lines).
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = toolpathExample)]
pub fn toolpath_example(
    #[wasm_bindgen(unchecked_param_type = "string")] kind: JsValue,
) -> Result<String, JsError> {
    let kind: &str = &name_arg(&kind, "kind")?;
    match kind {
        "arcs" => Ok(example::arc_example()),
        "lines" => Ok(example::line_example()),
        other => Err(JsError::new(&format!(
            "toolpathExample: unknown example '{}'; expected 'arcs' or 'lines'",
            crate::budget::clip(other, 40)
        ))),
    }
}
