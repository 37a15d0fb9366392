//! Bindings for [`crate::machine`]: the preset registry.

use wasm_bindgen::prelude::*;

use super::convert::{name_arg, to_js};
use crate::machine;

// GeometricErrors and DriveErrors are declared here rather than with the
// kinematics bindings: MachinePreset uses them, and the embed module (built
// without kinematics) must declare them too.
#[wasm_bindgen(typescript_custom_section)]
const TS: &str = r#"
export interface WormHarmonic {
  /** [-] Amplitude W of the ratio ripple (kato Eq. 1; rad with pitchReading 'additive'). */ w: number;
  /** [-] Order N, cycles per output revolution. */ n: number;
  /** [rad] Phase φ. */ phi: number;
}
export interface AxisParams {
  kind: 'linear' | 'rotary';
  /** [kg·m²] Equivalent inertia. */ j: number;
  /** [kg·m²] Load inertia. */ j1: number;
  /** [N·m·s/rad] Viscous damping. */ c: number;
  /** [1/s] Position gain. */ kpp: number;
  /** [N·m·s/rad] Velocity proportional gain. */ kvp: number;
  /** [N·m/rad] Velocity integral gain. */ kvi: number;
  /** [%] Pre-Control coefficient. */ kffp: number;
  /** [s] Smoothing time. */ ts: number;
  /** [s] Averaging time. */ ta: number;
  /** [s] Preceding time. */ tp: number;
  /** [N·m] Torque limit. */ torqueMax?: number;
  /** [m] Ball-screw lead. */ lead?: number;
  /** [-] Worm-gear ratio, motor rev per output rev. */ gearRatio?: number;
  /** [mm or rad] Backlash (full width): mm on a linear axis, rad on a rotary one. */ backlash?: number;
  pitchError?: WormHarmonic[];
  /** kato Eq. 1: 'gearRatio' (W·g/N at the table, default) or 'additive' (W in rad). */ pitchReading?: 'gearRatio' | 'additive';
  /** [N·m] kato Fig. 2: Coulomb friction F at the motor. */ friction?: number;
  /** [N·m] kato Fig. 2: load torque G at the motor. */ gravity?: number;
}
/** A machine's geometric errors (ISO 230 symbols; mm, rad). */
export interface GeometricErrors {
  /** [mm or rad] ISO 230 location errors, e.g. { EX0C: 0.01 (mm), EB0C: 2e-5 (rad), EC0Y: 1e-5 }. */
  location?: Record<string, number>;
  /** [mm or rad] ISO 230 component errors, constant or polynomial in position, e.g. { EXX: [0, 1e-5] }. */
  component?: Record<string, number | number[]>;
  /** [mm, rad] E_ST of thasana Eq. 8: [dx, dy, dz] in mm, [ex, ey, ez] in rad, in the tool frame. */
  tool?: number[];
}
/** A machine's drive errors per axis letter (servo::transmission; kato Eq. 1, Fig. 2). */
export interface DriveErrors {
  /** [mm or rad] Full backlash width per axis: mm on a linear axis, rad on a rotary one. */
  backlash?: Record<string, number>;
  /** Worm-gear pitch error per rotary axis (kato Eq. 1). */
  pitchError?: Record<string, WormHarmonic[]>;
}
/** A saturation point as a paper quotes it. */
export interface PaperSaturationPoint {
  /** [kg·m²] J + J1 */ jTotal: number; /** [rad/s²] dω/dt */ accelSat: number; /** [rad/s] */ omegaSat: number;
  /** [mm] smallest R_C at feedAtCuttingPoint */ rcMin: number;
}
/** The conditions a paper ran on a preset (suzuki §3 on nmv5000) and the saturation points it quotes. */
export interface PaperSweep {
  source: string; /** [mm] R_C */ rc: number; /** [mm] R_W */ rw: number;
  /** [rad/s] ω of the sweep */ omega: number[]; /** [kg·m²] loads J1 on C */ j1: number[];
  /** [s] acc/dec time */ accelTime: number; /** [mm/min] F_C */ feedAtCuttingPoint: number;
  saturation: PaperSaturationPoint[];
}
export interface MachinePreset {
  name: string; description: string; source: string;
  axes: Record<string, AxisParams>;
  /** [mm or deg] Travel limits: mm for linear axes, degrees for rotary axes. */
  limits?: Record<string, [number, number]>;
  /** Illustrative ISO 230-7 location errors for the page (not measured). */
  exampleErrors?: GeometricErrors;
  /** Illustrative worm-gear backlash for the page (not measured). */
  exampleDrives?: DriveErrors;
  /** The paper's test conditions on this machine, if a paper tests it so. */
  paperSweep?: PaperSweep;
  /** Readings `torqueSaturation` accepts (first = default). */
  saturationReadings?: string[];
  /** Readings of the paper's loop parameters `machinePreset(name, reading)` accepts (first = default); nmv5000: 'table' (Table 1: Kpp 60 1/s, J at the motor), 'kppText' (§3: Kpp 30 1/s on every axis), 'inertiaAtLoad' (J·(lead/2π)² at the motor: X's J read as kg behind its 16 mm lead). */
  loopReadings?: string[];
  [extra: string]: unknown;
}
"#;

/// The machine preset called `name`, under the loop reading `reading`
/// when given (one of its `loopReadings`; absent or null: the preset as
/// is, its default reading); throws an `Error` listing the
/// known names when there is none.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = machinePreset, unchecked_return_type = "MachinePreset")]
pub fn machine_preset(
    #[wasm_bindgen(unchecked_param_type = "string")] name: JsValue,
    #[wasm_bindgen(unchecked_optional_param_type = "string")] reading: JsValue,
) -> Result<JsValue, JsError> {
    let name: &str = &name_arg(&name, "name")?;
    if reading.is_undefined() || reading.is_null() {
        return to_js(&machine::preset(name)?);
    }
    let reading: &str = &name_arg(&reading, "reading")?;
    to_js(&machine::preset_with_reading(name, reading)?)
}

/// The names of all machine presets.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = machines, unchecked_return_type = "string[]")]
pub fn machines() -> Result<JsValue, JsError> {
    to_js(&machine::names())
}
