//! Bindings for [`crate::machine`]: the preset registry.

use wasm_bindgen::prelude::*;

use super::convert::{string_arg, to_js};
use crate::machine;

// GeometricErrors is declared here rather than with the kinematics bindings:
// MachinePreset uses it, and the embed module (built without kinematics)
// must declare it too.
#[wasm_bindgen(typescript_custom_section)]
const TS: &str = r#"
export interface WormHarmonic { w: number; n: number; phi: number }
export interface AxisParams {
  kind: 'linear' | 'rotary';
  /** Equivalent inertia, kg·m². */ j: number;
  /** Load inertia, kg·m². */ j1: number;
  /** Viscous damping, N·m·s/rad. */ c: number;
  /** Position gain, 1/s. */ kpp: number;
  kvp: number; kvi: number;
  /** Pre-Control coefficient, %. */ kffp: number;
  /** Smoothing, averaging and preceding times, s. */ ts: number; ta: number; tp: number;
  /** Torque limit, N·m. */ torqueMax?: number;
  /** Ball-screw lead, m. */ lead?: number;
  gearRatio?: number; backlash?: number; pitchError?: WormHarmonic[];
  /** kato Eq. 1: 'gearRatio' (W·g/N at the table, default) or 'additive' (W in rad). */ pitchReading?: 'gearRatio' | 'additive';
  /** kato Fig. 2: Coulomb friction F and load torque G at the motor, N·m. */ friction?: number; gravity?: number;
}
/** A machine's geometric and drive errors (ISO 230 symbols; mm, rad). */
export interface GeometricErrors {
  /** ISO 230 location errors, e.g. { EX0C: 0.01 (mm), EB0C: 2e-5 (rad), EC0Y: 1e-5 }. */
  location?: Record<string, number>;
  /** ISO 230 component errors, constant or polynomial in position (mm or rad), e.g. { EXX: [0, 1e-5] }. */
  component?: Record<string, number | number[]>;
  /** E_ST of thasana Eq. 8: [dx, dy, dz, ex, ey, ez] in the tool frame. */
  tool?: number[];
  /** Full backlash width per axis, mm or rad. */
  backlash?: Record<string, number>;
  /** Worm-gear pitch error per rotary axis (kato Eq. 1). */
  pitchError?: Record<string, WormHarmonic[]>;
}
export interface MachinePreset {
  name: string; description: string; source: string;
  axes: Record<string, AxisParams>;
  /** mm for linear axes, degrees for rotary axes. */
  limits?: Record<string, [number, number]>;
  /** Illustrative ISO 230-7 location errors and backlash for the page (not measured). */
  exampleErrors?: GeometricErrors;
  /** Readings `torqueSaturation` accepts (first = default). */
  saturationReadings?: string[];
  [extra: string]: unknown;
}
"#;

/// The machine preset called `name`; throws an `Error` listing the known
/// names when there is none.
#[wasm_bindgen(js_name = machinePreset, unchecked_return_type = "MachinePreset")]
pub fn machine_preset(
    #[wasm_bindgen(unchecked_param_type = "string")] name: JsValue,
) -> Result<JsValue, JsError> {
    let name: &str = &string_arg(&name, "name")?;
    to_js(&machine::preset(name)?)
}

/// The names of all machine presets.
#[wasm_bindgen(js_name = machines, unchecked_return_type = "string[]")]
pub fn machines() -> Result<JsValue, JsError> {
    to_js(&machine::names())
}
