//! Bindings for [`crate::kinematics`], [`crate::cone_frustum`] and
//! [`crate::compensate::nc5`]. Rotary axis positions cross in degrees;
//! lengths in mm; error parameters in mm and rad.

use std::collections::BTreeMap;

use js_sys::Array;
use serde::Deserialize;
use wasm_bindgen::prelude::*;

use super::convert::{
    callback_arg, floats_arg, from_js, name_arg, object, opt_number_arg, string_arg, to_js, Obj,
};
use crate::compensate::nc5::{self, s_shape};
use crate::cone_frustum::{self, ConeFrustumConfig};
use crate::kinematics::{self, inverse::limits_from_degrees, GeometricErrors, Model, Pose, AXES};
use crate::machine::MachineRef;
use crate::servo::AxisKind;

#[wasm_bindgen(typescript_custom_section)]
const TS: &str = r#"
/** `[x, y, z, a, b, c]` (mm, degrees) or `{ x, y, z, a, b, c }`; missing axes are 0. */
export type AxisValues = number[] | Partial<Record<'x'|'y'|'z'|'a'|'b'|'c', number>>;
export type MachineArg = string | MachinePreset;
export interface ToolPose { /** [mm] tool tip */ position: [number, number, number]; /** [-] tool axis direction */ orientation: [number, number, number] }
export interface IkBranch { /** [mm or deg] axis positions */ q: Record<string, number>; withinLimits: boolean; singular: boolean }
/** forwardKinematicsBulk: n × 3 flat arrays. */
export interface ToolPoses { /** [mm] tool tips */ position: Float64Array; /** [-] tool axes */ orientation: Float64Array }
export interface ConeFrustumOptions {
  machine: MachineArg; halfApexDeg: number; inclinationDeg: number;
  method?: 'perpendicular' | 'parallel'; /** [mm] */ barLength?: number; /** [mm/min] of the spindle ball */ feed: number;
  /** [mm] spindle-ball circle */ radius?: number; /** [mm] table ball */ centre?: [number, number, number]; errors?: GeometricErrors;
  /** backlash and worm-gear pitch error per axis */ drives?: DriveErrors;
  idealServo?: boolean; /** [mm] */ toolLength?: number; /** [-] samples per revolution */ points?: number; clockwise?: boolean; leadInDeg?: number;
  /** false: no sensitivity coefficients (both lists empty; about a quarter faster) */ sensitivities?: boolean;
}
export interface ConeFrustumResult {
  /** [deg] path angle */ angle: Float64Array; /** [s] */ time: Float64Array; /** [mm] change of bar length */ deviation: Float64Array;
  /** [mm] nominal spindle-ball path */ path: { x: Float64Array; y: Float64Array; z: Float64Array };
  /** [mm or deg] per-axis command and actual position */ axes: Record<string, { command: Float64Array; actual: Float64Array }>;
  /** [mm/mm or mm/rad] sensitivity of the bar to each axis and each location error */ sensitivity: { axes: Record<string, Float64Array>; errors: Record<string, Float64Array>; /** [mm/mm or mm/rad] RMS of each error's series over the path */ errorsRms: Record<string, number> };
  /** [mm] */ barLength: number; /** [mm] */ radius: number; /** [s] */ duration: number; /** [mm] */ maxDeviation: number; /** [mm] */ minDeviation: number;
}
export interface Nc5Stats { meanMm: number[]; stdMm: number[]; meanRad: number[]; stdRad: number[] }
/** compensateNc5 options. */
export interface Nc5Options {
  machine: MachineArg; errors?: GeometricErrors; /** [mm] */ toolLength?: number;
  monteCarlo?: { /** [-] */ seed?: number; sigmaMm?: number; sigmaRad?: number; repeatabilityMm?: number };
  cutting?: Record<string, unknown>; compensateAxes?: string[];
  /** thasana Eq. 9 PID drives (units as in servo::pid). */
  feedDrive?: { /** [-] P */ p: number; /** [1/s] I */ i: number; /** [s] D */ d: number; /** [1/s] N */ n: number; /** [1/s² per unit of u] plant gain */ k: number; /** [1/s] plant damping */ a: number };
}
export interface Nc5Result {
  nc: string; before: Nc5Stats; after: Nc5Stats; /** [-] source lines of the evaluation points */ lines: number[];
  /** [mm, rad] x, y, z in mm; a, b in rad */ beforePoints: { x: Float64Array; y: Float64Array; z: Float64Array; a: Float64Array; b: Float64Array };
  /** [mm, rad] x, y, z in mm; a, b in rad */ afterPoints: { x: Float64Array; y: Float64Array; z: Float64Array; a: Float64Array; b: Float64Array };
  reductionPercent: number[]; totalReductionPercent: number; deflectionMm: number; machineErrors: GeometricErrors;
}
/** sShapeTestPiece options. */
export interface SShapeOptions {
  machine: MachineArg; /** [-] of the full-size part (paper: 0.15) */ scale?: number; /** [mm] */ toolLength?: number;
  /** [mm] part origin */ origin?: number[]; /** [mm/min] */ feed?: number;
}
export interface SShapeTestPiece { /** [mm] tool-tip targets */ points: number[][]; /** [-] tool axes */ axes: number[][]; nc: string }
"#;

/// Axis values as `[x, y, z, a, b, c]` or `{ x, y, … }`; anything else is
/// refused in those words (not serde's "untagged enum").
enum AxisValues {
    Arr(Vec<f64>),
    Obj(BTreeMap<String, f64>),
}

impl<'de> Deserialize<'de> for AxisValues {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Either;
        impl<'de> serde::de::Visitor<'de> for Either {
            type Value = AxisValues;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("[x, y, z, a, b, c] or { x, y, z, a, b, c } (numbers)")
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                seq: A,
            ) -> Result<AxisValues, A::Error> {
                Vec::deserialize(serde::de::value::SeqAccessDeserializer::new(seq))
                    .map(AxisValues::Arr)
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<AxisValues, A::Error> {
                BTreeMap::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    .map(AxisValues::Obj)
            }
        }
        d.deserialize_any(Either)
    }
}

fn q_of(v: JsValue, what: &str) -> Result<[f64; 6], JsError> {
    let vals: AxisValues = from_js(v, what)?;
    let mut q = [0.0; 6];
    match vals {
        AxisValues::Arr(a) => {
            if a.len() > 6 {
                return Err(JsError::new(&format!(
                    "{what}: expected at most 6 values [x, y, z, a, b, c], got {}",
                    a.len()
                )));
            }
            q[..a.len()].copy_from_slice(&a);
        }
        AxisValues::Obj(m) => {
            for (k, v) in m {
                let i =
                    kinematics::Chain::axis_index(&k.to_ascii_lowercase()).ok_or_else(|| {
                        JsError::new(&format!(
                            "{what}: unknown key '{}'; expected one of x, y, z, a, b, c",
                            crate::budget::clip(&k, 40)
                        ))
                    })?;
                q[i] = v;
            }
        }
    }
    if let Some(i) = q.iter().position(|v| !v.is_finite()) {
        return Err(JsError::new(&format!(
            "{what}.{}: must be a finite number",
            AXES[i]
        )));
    }
    Ok(kinematics::q_from_degrees(&q))
}

fn machine_of(v: JsValue) -> Result<(crate::machine::Machine, kinematics::Chain), JsError> {
    if v.is_string() {
        return Ok(MachineRef::Name(name_arg(&v, "machine")?).resolve()?);
    }
    let m: MachineRef = from_js(v, "machine")?;
    Ok(m.resolve()?)
}

fn errors_of(v: JsValue) -> Result<GeometricErrors, JsError> {
    if v.is_undefined() || v.is_null() {
        Ok(GeometricErrors::default())
    } else {
        object(v, "errors")
    }
}

fn q_obj(q: &[f64; 6], axes: &[&str]) -> BTreeMap<String, f64> {
    let d = kinematics::q_to_degrees(q);
    AXES.iter()
        .enumerate()
        .filter(|(_, a)| axes.contains(a))
        .map(|(i, a)| (a.to_string(), d[i]))
        .collect()
}

/// Tool tip and tool axis relative to the workpiece at axis positions `q`
/// (mm, degrees), through the error model.
#[wasm_bindgen(js_name = forwardKinematics, unchecked_return_type = "ToolPose")]
pub fn forward_kinematics(
    #[wasm_bindgen(unchecked_param_type = "MachineArg")] machine: JsValue,
    #[wasm_bindgen(unchecked_param_type = "AxisValues")] q: JsValue,
    #[wasm_bindgen(unchecked_param_type = "GeometricErrors | undefined")] errors: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number | undefined")] tool_length: JsValue,
) -> Result<JsValue, JsError> {
    let (_, chain) = machine_of(machine)?;
    let q = q_of(q, "q")?;
    let e = errors_of(errors)?;
    let tool_length = opt_number_arg(&tool_length, "toolLength")?.unwrap_or(0.0);
    to_js(&kinematics::forward(&chain, &q, &e, tool_length)?)
}

/// Bulk forward kinematics: `q` is a flat `Float64Array` of `n × 6` axis
/// values (mm, degrees); returns flat `position` and `orientation` arrays of
/// `n × 3`.
#[wasm_bindgen(js_name = forwardKinematicsBulk, unchecked_return_type = "ToolPoses")]
pub fn forward_kinematics_bulk(
    #[wasm_bindgen(unchecked_param_type = "MachineArg")] machine: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array | number[]")] q: JsValue,
    #[wasm_bindgen(unchecked_param_type = "GeometricErrors | undefined")] errors: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number | undefined")] tool_length: JsValue,
) -> Result<JsValue, JsError> {
    let (_, chain) = machine_of(machine)?;
    let q = floats_arg(&q, "q")?;
    let e = errors_of(errors)?;
    let tool_length = opt_number_arg(&tool_length, "toolLength")?.unwrap_or(0.0);
    let model = Model::new(&chain, &e, tool_length)?;
    let (pos, ori) = model.eval_bulk_degrees(&q)?;
    Ok(Obj::new()
        .arr("position", &pos)
        .arr("orientation", &ori)
        .build())
}

/// Every inverse-kinematics branch of the nominal machine for a pose.
#[wasm_bindgen(js_name = inverseKinematics, unchecked_return_type = "IkBranch[]")]
pub fn inverse_kinematics(
    #[wasm_bindgen(unchecked_param_type = "MachineArg")] machine: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolPose")] pose: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number | undefined")] tool_length: JsValue,
) -> Result<JsValue, JsError> {
    let tool_length = opt_number_arg(&tool_length, "toolLength")?;
    let (m, chain) = machine_of(machine)?;
    let pose: Pose = object(pose, "pose")?;
    let sols = kinematics::inverse(
        &chain,
        &pose,
        tool_length.unwrap_or(0.0),
        &limits_from_degrees(&m.limits),
    )?;
    let axes = chain.axes();
    let out = Array::new();
    for s in sols {
        out.push(
            &Obj::new()
                .ser("q", &q_obj(&s.q, &axes))?
                .flag("withinLimits", s.within_limits)
                .flag("singular", s.singular)
                .build(),
        );
    }
    Ok(out.into())
}

fn series_obj(items: impl Iterator<Item = (String, Vec<f64>)>) -> JsValue {
    let o = items.fold(Obj::new(), |o, (k, v)| o.arr(&k, &v));
    o.build()
}

/// The ISO 230 location-error symbols a cone-frustum test on this machine
/// can see (e.g. `EX0C`, `EC0Y`), for building an error table.
#[wasm_bindgen(js_name = errorSymbols, unchecked_return_type = "string[]")]
pub fn error_symbols(
    #[wasm_bindgen(unchecked_param_type = "MachinePreset | string")] machine: JsValue,
) -> Result<JsValue, JsError> {
    let (_, chain) = machine_of(machine)?;
    to_js(&crate::kinematics::errors::error_symbols(&chain))
}

/// The simulated ISO 10791-6 cone-frustum ball-bar test (kato).
#[wasm_bindgen(js_name = coneFrustumTest, unchecked_return_type = "ConeFrustumResult")]
pub fn cone_frustum_test(
    #[wasm_bindgen(unchecked_param_type = "ConeFrustumOptions")] options: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "Function | null")] on_progress: JsValue,
) -> Result<JsValue, JsError> {
    let cfg: ConeFrustumConfig = object(options, "options")?;
    let on_progress = callback_arg(on_progress, "onProgress")?;
    if let Some(f) = &on_progress {
        super::convert::progress(f, 0.0, "simulating");
    }
    let r = cone_frustum::cone_frustum_test(&cfg)?;
    if let Some(f) = &on_progress {
        super::convert::progress(f, 1.0, "done");
    }
    // Rotary positions go to JS in degrees, like every angle of the JS API.
    let axes = r.axes.iter().fold(Obj::new(), |o, s| {
        let scale = match s.kind {
            AxisKind::Rotary => 180.0 / std::f64::consts::PI,
            AxisKind::Linear => 1.0,
        };
        let c: Vec<f64> = s.command.iter().map(|v| v * scale).collect();
        let a: Vec<f64> = s.actual.iter().map(|v| v * scale).collect();
        o.val(
            &s.axis,
            Obj::new().arr("command", &c).arr("actual", &a).build(),
        )
    });
    let sens = Obj::new()
        .val(
            "axes",
            series_obj(
                r.axis_sensitivity
                    .iter()
                    .map(|s| (s.name.clone(), s.values.clone())),
            ),
        )
        .val(
            "errors",
            series_obj(
                r.error_sensitivity
                    .iter()
                    .map(|s| (s.name.clone(), s.values.clone())),
            ),
        )
        .val(
            "errorsRms",
            r.error_sensitivity
                .iter()
                .fold(Obj::new(), |o, s| o.num(&s.name, s.rms))
                .build(),
        )
        .build();
    Ok(Obj::new()
        .arr("angle", &r.angle_deg)
        .arr("time", &r.time)
        .arr("deviation", &r.deviation)
        .val(
            "path",
            Obj::new()
                .arr("x", &r.path[0])
                .arr("y", &r.path[1])
                .arr("z", &r.path[2])
                .build(),
        )
        .val("axes", axes.build())
        .val("sensitivity", sens)
        .num("barLength", r.bar_length)
        .num("radius", r.radius)
        .num("duration", r.duration)
        .num("maxDeviation", r.max_deviation)
        .num("minDeviation", r.min_deviation)
        .build())
}

fn points_obj(p: &nc5::PointErrors) -> JsValue {
    Obj::new()
        .arr("x", &p.x)
        .arr("y", &p.y)
        .arr("z", &p.z)
        .arr("a", &p.a)
        .arr("b", &p.b)
        .build()
}

/// Compensates a 5-axis NC program for the machine's geometric errors
/// (thasana §II-D).
#[wasm_bindgen(js_name = compensateNc5, unchecked_return_type = "Nc5Result")]
pub fn compensate_nc5(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Nc5Options")] options: JsValue,
) -> Result<JsValue, JsError> {
    let text: &str = &string_arg(&text, "text")?;
    let cfg: nc5::Nc5Config = object(options, "options")?;
    let r = nc5::compensate_nc5(text, &cfg)?;
    Ok(Obj::new()
        .val("nc", JsValue::from_str(&r.nc))
        .ser("before", &r.before)?
        .ser("after", &r.after)?
        .val("beforePoints", points_obj(&r.before_points))
        .val("afterPoints", points_obj(&r.after_points))
        .ser("lines", &r.lines)?
        .ser("reductionPercent", &r.reduction_percent)?
        .num("totalReductionPercent", r.total_reduction_percent)
        .num("deflectionMm", r.deflection_mm)
        .ser("machineErrors", &r.machine_errors)?
        .build())
}

/// The ISO 10791-7 S-shape test piece (scaled) and its 5-axis program with
/// 64 evaluation points.
#[wasm_bindgen(js_name = sShapeTestPiece, unchecked_return_type = "SShapeTestPiece")]
pub fn s_shape_test_piece(
    #[wasm_bindgen(unchecked_param_type = "SShapeOptions")] options: JsValue,
) -> Result<JsValue, JsError> {
    let o: s_shape::SShapeOptions = object(options, "options")?;
    to_js(&s_shape::s_shape(&o)?)
}
