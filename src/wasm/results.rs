//! The results of the documentation calculators' functions as JS objects.
//!
//! The full module serialises them with serde-wasm-bindgen
//! ([`super::convert::to_js`]). The embed module (`--no-default-features`,
//! docs/performance.md) builds the same objects by hand with
//! [`super::convert::Obj`], so that serde's serialiser is not linked for
//! them: same keys in the same order, numbers as numbers, `None` as `null`,
//! enums by their serde names. `tests/node/optimised.test.mjs` checks the
//! two builds give the same objects, key for key.

use wasm_bindgen::prelude::*;

/// A result the embed calculators return, converted to its JS object.
pub trait JsResult {
    /// The plain JS object (arrays, objects, numbers, strings, null).
    fn js(&self) -> Result<JsValue, JsError>;
}

#[cfg(feature = "full")]
impl<T: serde::Serialize> JsResult for T {
    fn js(&self) -> Result<JsValue, JsError> {
        super::convert::to_js(self)
    }
}

#[cfg(not(feature = "full"))]
mod by_hand {
    use js_sys::Array;
    use wasm_bindgen::prelude::*;

    use super::JsResult;
    use crate::alignment::SweepPoint;
    use crate::ballbar::{CircularDeviation, Direction, RunResult};
    use crate::best_kffp::saturation::SaturationPoint;
    use crate::wasm::convert::Obj;

    fn list<T>(items: &[T], each: impl Fn(&T) -> JsValue) -> JsValue {
        items.iter().map(each).collect::<Array>().into()
    }

    fn opt(v: Option<f64>) -> JsValue {
        v.map_or(JsValue::NULL, JsValue::from_f64)
    }

    fn direction(d: Direction) -> JsValue {
        JsValue::from_str(match d {
            Direction::Ccw => "ccw",
            Direction::Cw => "cw",
        })
    }

    impl JsResult for Direction {
        fn js(&self) -> Result<JsValue, JsError> {
            Ok(direction(*self))
        }
    }

    impl JsResult for Vec<SaturationPoint> {
        fn js(&self) -> Result<JsValue, JsError> {
            Ok(list(self, |p| {
                Obj::new()
                    .num("jTotal", p.j_total)
                    .num("accelSat", p.accel_sat)
                    .num("omegaSat", p.omega_sat)
                    .num("rcMin", p.rc_min)
                    .num("torquePerOmega", p.torque_per_omega)
                    .build()
            }))
        }
    }

    impl JsResult for Vec<SweepPoint> {
        fn js(&self) -> Result<JsValue, JsError> {
            Ok(list(self, |p| {
                Obj::new()
                    .num("rangeDeg", p.range_deg)
                    .num("errorZ", p.error_z)
                    .num("errorX", p.error_x)
                    .build()
            }))
        }
    }

    fn run(r: &RunResult) -> JsValue {
        Obj::new()
            .val("direction", direction(r.direction))
            .num("gUm", r.g_um)
            .num("fMaxUm", r.f_max_um)
            .num("fMinUm", r.f_min_um)
            .num("centreXMm", r.centre_x_mm)
            .num("centreYMm", r.centre_y_mm)
            .num("radiusMm", r.radius_mm)
            .num("spanDeg", r.span_deg)
            .num("points", r.points as f64)
            .build()
    }

    impl JsResult for CircularDeviation {
        fn js(&self) -> Result<JsValue, JsError> {
            Ok(Obj::new()
                .num("nominalRadiusMm", self.nominal_radius_mm)
                .val("runs", list(&self.runs, run))
                .val("hUm", opt(self.h_um))
                .build())
        }
    }
}
