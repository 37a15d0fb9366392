//! The configs of the documentation calculators' functions, read from JS.
//!
//! The full module deserialises them with serde-wasm-bindgen
//! ([`super::convert::object`]). The embed module (`--no-default-features`,
//! docs/performance.md) reads the few fields by hand from the same plain
//! snapshot ([`super::convert::plain`]), so that serde's deserialiser is
//! not linked at all: the same defaults, and serde's own messages for what
//! the calculators can pass (a missing field, a whole number out of range
//! or with a fraction), including the `Error: ` that serde-wasm-bindgen's
//! error puts before them. A value of the wrong JS type (a string for a
//! number) is refused naming the field rather than in serde's words.
//! `tests/node/optimised.test.mjs` checks both builds give the same values
//! and the same messages for the calculators' inputs.

use wasm_bindgen::prelude::*;

/// A config argument the embed calculators pass, read from JS.
pub trait JsArg: Sized {
    /// The config in `value`; `what` names the argument in errors.
    fn arg(value: JsValue, what: &str) -> Result<Self, JsError>;
}

#[cfg(feature = "full")]
impl<T: serde::de::DeserializeOwned> JsArg for T {
    fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
        super::convert::object(value, what)
    }
}

#[cfg(not(feature = "full"))]
mod by_hand {
    use js_sys::{Array, Reflect};
    use wasm_bindgen::prelude::*;

    use super::JsArg;
    use crate::alignment::travel_range::{default_radius, default_samples};
    use crate::alignment::{Locus, Offset, SweepConfig};
    use crate::ballbar::{Harmonic, ParseOptions, PlanePoint};
    use crate::best_kffp::saturation::{SaturationQuery, SaturationReading, READINGS};
    use crate::wasm::convert::{plain, require_object};
    use crate::wasm::toolpath::Eq3In;

    /// The snapshot of a config that must be a plain object.
    fn snapshot(value: &JsValue, what: &str) -> Result<JsValue, JsError> {
        require_object(value, what)?;
        plain(value, what)
    }

    /// The field `key`, or `None` when absent.
    fn get(obj: &JsValue, key: &str) -> Option<JsValue> {
        Reflect::get(obj, &JsValue::from_str(key))
            .ok()
            .filter(|v| !v.is_undefined())
    }

    /// A message in serde-wasm-bindgen's words (its error's text starts
    /// with the JS `Error: `).
    fn serde_says(what: &str, message: &str) -> JsError {
        JsError::new(&format!("{what}: Error: {message}"))
    }

    fn missing(what: &str, key: &str) -> JsError {
        serde_says(what, &format!("missing field `{key}`"))
    }

    fn not_a_number(what: &str, key: &str) -> JsError {
        JsError::new(&format!("{what}.{key}: expected a number"))
    }

    /// A required number (serde: "missing field").
    fn num(obj: &JsValue, key: &str, what: &str) -> Result<f64, JsError> {
        let v = get(obj, key).ok_or_else(|| missing(what, key))?;
        v.as_f64().ok_or_else(|| not_a_number(what, key))
    }

    /// A number with a default when absent.
    fn num_or(obj: &JsValue, key: &str, what: &str, default: f64) -> Result<f64, JsError> {
        match get(obj, key) {
            None => Ok(default),
            Some(v) => v.as_f64().ok_or_else(|| not_a_number(what, key)),
        }
    }

    /// An optional number: absent or null gives `None` (serde's `Option`).
    fn opt_num(obj: &JsValue, key: &str, what: &str) -> Result<Option<f64>, JsError> {
        match get(obj, key) {
            Some(v) if !v.is_null() => v.as_f64().map(Some).ok_or_else(|| not_a_number(what, key)),
            _ => Ok(None),
        }
    }

    /// The items of an array field; absent: serde's "missing field" when
    /// `required`, else none (serde's `#[serde(default)]`).
    fn items(
        obj: &JsValue,
        key: &str,
        what: &str,
        required: bool,
    ) -> Result<Vec<JsValue>, JsError> {
        match get(obj, key) {
            None if required => Err(missing(what, key)),
            None => Ok(Vec::new()),
            Some(v) if Array::is_array(&v) => Ok(Array::from(&v).iter().collect()),
            Some(_) => Err(JsError::new(&format!("{what}.{key}: expected an array"))),
        }
    }

    fn nums(obj: &JsValue, key: &str, what: &str) -> Result<Vec<f64>, JsError> {
        items(obj, key, what, true)?
            .iter()
            .map(|v| v.as_f64().ok_or_else(|| not_a_number(what, key)))
            .collect()
    }

    /// A whole number of type `ty` up to `max`, with serde's messages for a
    /// field under `#[serde(flatten)]` (read from serde's buffered copy,
    /// where a safe integer is an `i64`): a safe integer below 0 or above
    /// `max` is an invalid value, anything else that is not a safe integer
    /// an invalid type.
    fn whole(x: f64, ty: &str, max: u64, what: &str) -> Result<u64, JsError> {
        const SAFE: f64 = 9_007_199_254_740_991.0;
        let message = if x.fract() == 0.0 && x.abs() <= SAFE {
            if x >= 0.0 && x as u64 <= max {
                return Ok(x as u64);
            }
            format!("invalid value: integer `{}`, expected {ty}", x as i64)
        } else {
            let mut s = format!("{x}");
            if x.is_finite() && !s.contains('.') {
                s.push_str(".0");
            }
            format!("invalid type: floating point `{s}`, expected {ty}")
        };
        Err(serde_says(what, &message))
    }

    impl JsArg for Eq3In {
        fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
            let o = snapshot(&value, what)?;
            Ok(Eq3In {
                feed: num(&o, "feed", what)?,
                radius: num(&o, "radius", what)?,
                t_a: num(&o, "tA", what)?,
                t: num(&o, "T", what)?,
            })
        }
    }

    fn reading(o: &JsValue, what: &str) -> Result<SaturationReading, JsError> {
        let Some(v) = get(o, "reading") else {
            return Ok(SaturationReading::default());
        };
        let name = v
            .as_string()
            .ok_or_else(|| JsError::new(&format!("{what}.reading: expected a string")))?;
        let all = [
            SaturationReading::PreControlOff,
            SaturationReading::PresetKffp,
            SaturationReading::InertiaOnly,
        ];
        match READINGS.iter().position(|r| *r == name) {
            Some(k) => Ok(all[k]),
            None => Err(serde_says(
                what,
                &format!(
                    "unknown variant `{}`, expected one of `{}`",
                    crate::budget::clip(&name, 60),
                    READINGS.join("`, `")
                ),
            )),
        }
    }

    impl JsArg for SaturationQuery {
        fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
            let o = snapshot(&value, what)?;
            Ok(SaturationQuery {
                j1: nums(&o, "j1", what)?,
                torque_max: opt_num(&o, "torqueMax", what)?,
                accel_time: num(&o, "accelTime", what)?,
                feed_at_cutting_point: num(&o, "feedAtCuttingPoint", what)?,
                dt: opt_num(&o, "dt", what)?,
                reading: reading(&o, what)?,
            })
        }
    }

    fn harmonic(h: &JsValue, what: &str) -> Result<Harmonic, JsError> {
        if !h.is_object() || Array::is_array(h) {
            return Err(JsError::new(&format!(
                "{what}.harmonics: expected objects {{ order, amplitude, phase }}"
            )));
        }
        Ok(Harmonic {
            order: whole(num(h, "order", what)?, "u32", u32::MAX.into(), what)? as u32,
            amplitude: num(h, "amplitude", what)?,
            phase: num_or(h, "phase", what, 0.0)?,
        })
    }

    impl JsArg for SweepConfig {
        fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
            let o = snapshot(&value, what)?;
            let offset = match get(&o, "offset") {
                None => Offset::default(),
                Some(v) => Offset {
                    z: num(&v, "z", what)?,
                    x: num(&v, "x", what)?,
                },
            };
            let harmonics = items(&o, "harmonics", what, false)?
                .iter()
                .map(|h| harmonic(h, what))
                .collect::<Result<_, _>>()?;
            let samples = match get(&o, "samples") {
                None => default_samples(),
                Some(v) => {
                    let x = v.as_f64().ok_or_else(|| not_a_number(what, "samples"))?;
                    whole(x, "usize", u32::MAX.into(), what)? as usize
                }
            };
            Ok(SweepConfig {
                offset,
                ranges: nums(&o, "ranges", what)?,
                locus: Locus {
                    harmonics,
                    radius: num_or(&o, "radius", what, default_radius())?,
                    samples,
                    centre_deg: num_or(&o, "centreDeg", what, 0.0)?,
                },
            })
        }
    }

    impl JsArg for ParseOptions {
        fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
            let o = snapshot(&value, what)?;
            let centre = match get(&o, "centre") {
                None => None,
                Some(v) => Some(PlanePoint {
                    x: num(&v, "x", &format!("{what}.centre"))?,
                    y: num(&v, "y", &format!("{what}.centre"))?,
                }),
            };
            Ok(ParseOptions {
                nominal_radius: opt_num(&o, "nominalRadius", what)?,
                feed: opt_num(&o, "feed", what)?,
                centre,
                trim: match get(&o, "trim") {
                    None => true,
                    Some(v) => v.as_bool().ok_or_else(|| {
                        JsError::new(&format!("{what}.trim: expected true or false"))
                    })?,
                },
            })
        }
    }
}
